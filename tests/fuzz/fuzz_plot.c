/* SPDX-License-Identifier: MIT */
/* libFuzzer target: conica_bspline_set + conica_plot (Dahl 2019) on
 * arbitrary splines and settings, every method, small budgets.
 *
 * Input layout (missing bytes read as 0):
 *   byte 0 degree 1..6, byte 1 dim 1..3, byte 2 extra control points 0..15,
 *   byte 3 rational / method, bytes 4.. criterion, rule, stop, output,
 *   tolerance exponent, then knot steps, control values and weights.
 * Knots are built from steps (a zero step repeats a knot) or taken raw
 * (NaN, Inf, decreasing...) so that validation sees both. */
#include "fuzz_common.h"

#include "conica/bspline.h"
#include "conica/plot.h"

#define FZ_MAXN (6 + 1 + 15)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    double knots[FZ_MAXN + 7], ctrl[3 * FZ_MAXN], w[FZ_MAXN], prev = 0;
    conica_bspline s;
    conica_status st;
    conica_code rc;
    fz_init(&r, data, size);
    int degree = (int)fz_range(&r, 1, 6);
    int dim = (int)fz_range(&r, 1, 3);
    size_t n = (size_t)degree + 1 + fz_range(&r, 0, 15);
    unsigned b3 = fz_u8(&r);
    int rational = (int)(b3 & 1);
    conica_plot_settings set = conica_plot_defaults();
    set.method = (conica_plot_method)((b3 >> 1) % (unsigned)CONICA_PLOT_METHOD_COUNT_);
    set.criterion = (conica_plot_criterion)(fz_u8(&r) % (unsigned)CONICA_CRIT_COUNT_);
    set.rule = (conica_plot_rule)(fz_u8(&r) % (unsigned)CONICA_RULE_COUNT_);
    set.stop = (conica_plot_stop)(fz_u8(&r) % (unsigned)CONICA_STOP_COUNT_);
    unsigned b = fz_u8(&r);
    set.output = b & 1 ? CONICA_OUTPUT_CURVE_POINTS : CONICA_OUTPUT_CONTROL_POLYGON;
    set.local_weight = (conica_plot_local_weight)((b >> 1) % 3u);
    set.prephase_knots = (b >> 3) & 7u;
    unsigned te = fz_u8(&r);
    if (te & 1)
        set.abs_tolerance = ldexp(1.0, -(int)(te >> 2) % 40);
    else if (te & 2)
        set.pixel_tolerance = (double)(te >> 2) / 8.0; /* 0 is a bad setting */
    set.rule_ratio = (double)fz_range(&r, 1, 255) / 256.0;
    set.threshold = (double)fz_u8(&r) / 64.0 - 0.5;
    set.skip = fz_range(&r, 0, 4);
    set.consec = fz_range(&r, 0, 4);
    set.knot_budget = fz_u8(&r);
    set.points = fz_range(&r, 0, 255);
    set.local_min_points = fz_range(&r, 0, 8);
    set.local_omega = (double)fz_u8(&r) / 255.0;
    set.math_initial_points = fz_range(&r, 0, 64);
    set.math_angle = (double)fz_u8(&r) / 64.0;
    set.math_max_recursion = fz_range(&r, 0, 8);
    set.max_points = (size_t)1 << 13;
    set.max_knots = (size_t)1 << 12;
    set.max_iterations = (size_t)1 << 16;

    size_t nk = n + (size_t)degree + 1;
    double t = 0;
    for (size_t i = 0; i < nk; i++) {
        unsigned k = fz_u8(&r);
        if (k < 200) {
            t += k < 100 ? 0.0 : (double)(k - 99) / 16.0; /* repeated or increasing */
            knots[i] = t;
        } else {
            knots[i] = t = fz_double(&r, t);
        }
    }
    for (size_t i = 0; i < n * (size_t)dim; i++)
        ctrl[i] = prev = fz_double(&r, i >= (size_t)dim ? ctrl[i - (size_t)dim] : prev);
    for (size_t i = 0; i < n; i++) {
        unsigned k = fz_u8(&r);
        w[i] = k < 240 ? (double)(k + 1) / 64.0 : fz_double(&r, 1.0);
    }

    memset(&st, 0, sizeof st);
    conica_bspline_init(&s);
    rc = conica_bspline_set(degree, dim, knots, nk, ctrl, n, rational ? w : NULL, &s, &st);
    fz_check_status(rc, &st);
    if (rc != CONICA_OK) {
        /* the repair path of Section 1.1.2 on the same arrays */
        rc = conica_bspline_make_regular(degree, dim, knots, nk, ctrl, n, rational ? w : NULL,
                                         &s, &st);
        fz_check_status(rc, &st);
        if (rc != CONICA_OK)
            return 0;
    }
    conica_polyline pl;
    conica_plot_stats stats;
    conica_polyline_init(&pl);
    rc = conica_plot(&s, &set, &pl, &stats, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        FZ_ASSERT(pl.n >= 1 && pl.n <= set.max_points);
        FZ_ASSERT(pl.dim == conica_bspline_point_dim(&s));
        FZ_ASSERT(pl.npieces >= 1 && pl.piece_start[0] == 0);
        for (size_t k = 1; k < pl.npieces; k++)
            FZ_ASSERT(pl.piece_start[k] > pl.piece_start[k - 1] && pl.piece_start[k] < pl.n);
        for (size_t i = 0; i < pl.n * (size_t)pl.dim; i++)
            FZ_ASSERT(!isnan(pl.xy[i]));
        if (pl.n <= 512 && s.n <= 16) {
            double d1 = 0, d2 = 0;
            rc = conica_plot_deviation(&s, &pl, 4, &d1, &d2, &st);
            fz_check_status(rc, &st);
        }
    }
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
    return 0;
}
