/* SPDX-License-Identifier: MIT */
/* The reference implementation's own example curves (../shared/data/conis/
 * input) against what it produced at 5 levels (reference-k5): proof that
 * conica_subdivide() is the same scheme (CONIS §1.1).
 *
 * - reference-compatible + precise: same point counts, inflection points
 *   inserted at the same places, every point within 1e-6 of the input's
 *   bounding-box diagonal (ExStar_sub0's positions excepted: the reference
 *   itself is unstable there, REFERENCE.md section 1);
 * - default settings (local frames, double): same counts and inflection
 *   places, points within 5e-2 of the diagonal (the local frame changes the
 *   fitted conic for data that lie on no conic; REFERENCE.md measured up to
 *   3e-2 for such a variant), except on a level-0 edge where the
 *   reference's edge point turns against its convex sub-polygon and ours
 *   does not (against_subpolygon: lG2's long arc);
 * Every figure is printed, so a failure says which file and by how much.
 * The fairness test at the end checks the curvature of the same runs. */
#include "conica_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/curve.h"
#include "conica/subdiv.h"
#include "ts_fairness.h"

#define LEVELS 5
#define STRIDE (1u << LEVELS) /* level-0 vertices sit every 2^5 output points */
#define TOL_COMPAT 1e-6       /* x diagonal, reference-compatible + precise */
#define TOL_DEFAULT 5e-2      /* x diagonal, default settings */
/* An output vertex is "an input vertex" when it is this close (x diagonal):
 * the reference printed 19 digits of a long double, we read them as double. */
#define TOL_SAME_VERTEX 1e-12

static const char *const names[] = {
    "5pointOpenCircle", "ExLetG_sub0", "ExStar_sub0", "ExStep_sub0", "ex6_sub0E", "ex6_sub0F",
    "example1",         "example10",   "example11",   "example12",   "example13", "example2",
    "example3",         "example4",    "example5",    "example6",    "example7",  "example8",
    "example9",         "lG2",         "tau_example2", "tau_sub0",   "tst"};
#define NNAMES (sizeof names / sizeof names[0])

static int load(const char *rel, conica_curve *c)
{
    char path[1024];
    char *buf;
    long size;
    size_t got;
    FILE *f;
    conica_status st;
    conica_code rc;
    if (!ct_data_path(path, sizeof path, rel))
        return 0;
    f = fopen(path, "rb");
    if (!f)
        return 0;
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)size + 1);
    if (!buf) {
        fclose(f);
        return 0;
    }
    got = fread(buf, 1, (size_t)size, f);
    fclose(f);
    rc = conica_curve_parse(buf, got, c, &st);
    free(buf);
    if (rc != CONICA_OK)
        printf("reference-data: %s:%zu: %s\n", rel, st.line, st.message);
    return rc == CONICA_OK;
}

static double bbox_diagonal(const conica_curve *c)
{
    double x0 = c->xy[0], x1 = x0, y0 = c->xy[1], y1 = y0;
    size_t i;
    for (i = 1; i < c->n; i++) {
        double x = c->xy[2 * i], y = c->xy[2 * i + 1];
        x0 = x < x0 ? x : x0;
        x1 = x > x1 ? x : x1;
        y0 = y < y0 ? y : y0;
        y1 = y > y1 ? y : y1;
    }
    return hypot(x1 - x0, y1 - y0);
}

/* Which level-0 slots (every STRIDE-th output point) are inserted
 * inflection points rather than input vertices: input vertices appear in
 * order; anything between them is an inserted point. Writes a '0'/'1'
 * string into pattern (one char per slot) and returns the number of
 * inserted points, or -1 when the input vertices are not all found. */
static long inflection_pattern(const double *xy, size_t n_out, int closed,
                               const conica_curve *in, double diag, char *pattern, size_t cap)
{
    size_t slots = closed ? n_out / STRIDE : (n_out - 1) / STRIDE + 1, j, k = 0;
    long inserted = 0;
    if (slots + 1 > cap)
        return -1;
    for (j = 0; j < slots; j++) {
        const double *p = xy + 2 * (j * STRIDE);
        if (k < in->n && hypot(p[0] - in->xy[2 * k], p[1] - in->xy[2 * k + 1]) <=
                             TOL_SAME_VERTEX * diag) {
            pattern[j] = '0';
            k++;
        } else {
            pattern[j] = '1';
            inserted++;
        }
    }
    pattern[slots] = '\0';
    return k == in->n ? inserted : -1;
}

typedef struct result {
    int ok_count, ok_inflections;
    double max_dev; /* x diagonal */
    size_t worst_index;
    size_t turned; /* level-0 edges left out of max_dev (against_subpolygon) */
} result;

/* Side of point p of the line a -> b: +1 left, -1 right, 0 on it. */
static int side_of(const double *a, const double *b, const double *p)
{
    double c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    return c > 0 ? 1 : (c < 0 ? -1 : 0);
}

/* Turn of the polygon a -> b -> c at b, in degrees (0..180). */
static double turn_deg(const double *a, const double *b, const double *c)
{
    double ux = b[0] - a[0], uy = b[1] - a[1], vx = c[0] - b[0], vy = c[1] - b[1];
    return fabs(atan2(ux * vy - uy * vx, ux * vx + uy * vy)) * 180.0 / 3.14159265358979;
}

/* Level-0 edge e (slots e and e+1, every STRIDE-th point) of a closed
 * output whose neighbours e-1 and e+2 lie strictly on one side of it (no
 * inflection in the edge: the CONIS paper's convex sub-polygons), whose
 * end vertices turn by more than a half turn together (the polygon folds
 * back over the edge, so the convex arc through it may turn by more than
 * a half turn, a long arc), and where the reference's level-1 edge point
 * lies on the neighbours' side, so that its refined polygon turns against
 * the sub-polygon there, while ours lies on the other side. There the
 * default mode takes the long arc on purpose (lG2's p7 p8:
 * libcore/src/subdiv_impl.h, SFX(long_arc)) and the reference's points are
 * no measure of it; the fairness test below judges those edges. */
static int against_subpolygon(const double *ours, const double *theirs, size_t n_out, size_t e)
{
    size_t slots = n_out / STRIDE;
    const double *a = ours + 2 * (((e + slots - 1) % slots) * STRIDE);
    const double *p0 = ours + 2 * (e * STRIDE), *p1 = ours + 2 * (((e + 1) % slots) * STRIDE);
    const double *b = ours + 2 * (((e + 2) % slots) * STRIDE);
    size_t mid = e * STRIDE + STRIDE / 2;
    int sa = side_of(p0, p1, a), sb = side_of(p0, p1, b);
    if (slots < 4 || sa == 0 || sa != sb || turn_deg(a, p0, p1) + turn_deg(p0, p1, b) <= 180)
        return 0;
    return side_of(p0, p1, theirs + 2 * mid) == sa && side_of(p0, p1, ours + 2 * mid) == -sa;
}

/* Subdivide one example in the given mode and compare it with reference-k5. */
static int compare_one(const char *name, int compat, result *res)
{
    char rel[256], pat_ours[4096], pat_ref[4096];
    conica_curve in, ref, out;
    conica_curvel outl;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_status st;
    conica_code rc;
    double diag, *xy;
    size_t i, n_out;
    long inf_ours, inf_ref;

    conica_curve_init(&in);
    conica_curve_init(&ref);
    conica_curve_init(&out);
    conica_curvel_init(&outl);
    snprintf(rel, sizeof rel, "conis/input/%s.txt", name);
    REQUIRE(load(rel, &in));
    snprintf(rel, sizeof rel, "conis/reference-k5/%s.k5.txt", name);
    REQUIRE(load(rel, &ref));
    in.closed = strcmp(name, "5pointOpenCircle") != 0;
    if (!in.nxy) /* as the reference: area-weighted normals of the closed curve */
        REQUIRE_EQ(conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    diag = bbox_diagonal(&in);

    s.levels = LEVELS;
    s.reference_compatible = compat;
    s.precise = compat;
    memset(&st, 0, sizeof st);
    if (compat) {
        rc = conica_subdividel(&in, &s, &outl, NULL, &st);
        n_out = outl.n;
    } else {
        rc = conica_subdivide(&in, &s, &out, NULL, &st);
        n_out = out.n;
    }
    INFO("%s (%s): status %d %s", name, compat ? "reference-compatible, precise" : "default",
         (int)rc, st.message);
    REQUIRE_EQ(rc, CONICA_OK);

    xy = malloc(2 * (n_out ? n_out : 1) * sizeof *xy);
    REQUIRE(xy != NULL);
    for (i = 0; i < 2 * n_out; i++)
        xy[i] = compat ? (double)outl.xy[i] : out.xy[i];

    res->ok_count = n_out == ref.n;
    res->max_dev = 0;
    res->worst_index = 0;
    res->ok_inflections = 0;
    res->turned = 0;
    if (res->ok_count) {
        size_t e, turned_edge = (size_t)-1;
        for (i = 0; i < n_out; i++) {
            double d;
            if (!compat && in.closed && i % STRIDE == 1) {
                e = i / STRIDE;
                turned_edge = against_subpolygon(xy, ref.xy, n_out, e) ? e : (size_t)-1;
                if (turned_edge != (size_t)-1) {
                    printf("reference-data: %-16s default: level-0 edge %zu left out (the "
                           "reference's edge point turns against its convex sub-polygon)\n",
                           name, e);
                    res->turned++;
                }
            }
            if (turned_edge != (size_t)-1 && i % STRIDE != 0)
                continue;
            d = hypot(xy[2 * i] - ref.xy[2 * i], xy[2 * i + 1] - ref.xy[2 * i + 1]) / diag;
            if (!(d <= res->max_dev)) { /* NaN counts as worst */
                res->max_dev = isnan(d) ? INFINITY : d;
                res->worst_index = i;
            }
        }
    }
    inf_ours = inflection_pattern(xy, n_out, in.closed, &in, diag, pat_ours, sizeof pat_ours);
    inf_ref = inflection_pattern(ref.xy, ref.n, in.closed, &in, diag, pat_ref, sizeof pat_ref);
    res->ok_inflections = inf_ours >= 0 && inf_ref >= 0 && strcmp(pat_ours, pat_ref) == 0;
    printf("reference-data: %-16s %-30s points %6zu (reference %6zu)  inflections %ld (reference %ld)%s"
           "  max deviation %.3g x diagonal at point %zu\n",
           name, compat ? "reference-compatible+precise" : "default", n_out, ref.n, inf_ours,
           inf_ref, res->ok_inflections ? "" : " MISPLACED", res->max_dev, res->worst_index);
    if (!res->ok_inflections)
        printf("reference-data:   slots ours %s\nreference-data:   slots ref  %s\n",
               inf_ours >= 0 ? pat_ours : "?", inf_ref >= 0 ? pat_ref : "?");

    free(xy);
    conica_curve_free(&in);
    conica_curve_free(&ref);
    conica_curve_free(&out);
    conica_curvel_free(&outl);
    return 1;
}

static void compare_all(int compat, double tol)
{
    size_t k;
    ct_data_dir_or_skip();
    for (k = 0; k < NNAMES; k++) {
        result r;
        int unstable = strcmp(names[k], "ExStar_sub0") == 0;
        compare_one(names[k], compat, &r);
        INFO("%s: max deviation %.3g x diagonal at point %zu (tolerance %g)", names[k],
             r.max_dev, r.worst_index, tol);
        CHECK(r.ok_count);
        CHECK(r.ok_inflections);
        if (compat && unstable) {
            /* REFERENCE.md section 1: the reference's own output here moves
             * by up to 7 diagonals with the last bits of its input. */
            if (!(r.max_dev <= tol))
                WARN("%s: positions differ by %.3g x diagonal (not checked: unstable in the "
                     "reference itself)",
                     names[k], r.max_dev);
        } else {
            CHECK(r.max_dev <= tol);
        }
    }
}

TEST_CASE("reference examples: reference-compatible + precise match reference-k5 within 1e-6",
          "[subdiv][reference][data]")
{
    compare_all(1, TOL_COMPAT);
}

TEST_CASE("reference examples: default settings match reference-k5 within 5e-2",
          "[subdiv][reference][data]")
{
    compare_all(0, TOL_DEFAULT);
}

/* ------------------------------------------------ fairness (issue 20) */

/* The largest turn of a polygon vertex, in degrees (printed: the
 * reference's lG2 folds back on itself, turning by up to 174 degrees). */
static double max_turn_deg(const conica_curve *c)
{
    double worst = 0;
    size_t i;
    for (i = c->closed ? 0 : 1; i < (c->closed ? c->n : c->n - 1); i++) {
        size_t a = i == 0 ? c->n - 1 : i - 1, b = i + 1 == c->n ? 0 : i + 1;
        double t = turn_deg(c->xy + 2 * a, c->xy + 2 * i, c->xy + 2 * b);
        worst = t > worst ? t : worst;
    }
    return worst;
}

/* Curvature fairness of the default mode on the examples (discrete
 * curvature of the circle through three consecutive points,
 * tests/support/ts_fairness.h), at k = 5 and k = 8:
 * - an example whose polygon turns one way and whose every normal lies in
 *   the cone of its vertex's edge normals (a convex point-normal polygon)
 *   gives curvature of one sign;
 * - a non-convex one (inflection points inserted) has a total variation no
 *   greater than the reference's own output (reference-k5) at k = 5 and the
 *   reference-compatible mode at k = 8, and as many curvature sign changes
 *   as inflections, also where the polygon folds back on itself (lG2). */
/* Returns 1 when the example was checked as a convex one. */
static int fairness_one(const char *name)
{
    char rel[256];
    conica_curve in, ref, out;
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    ts_fairness poly, mref, m[2], mc;
    size_t outside;
    int k, convex;
    double turn;

    conica_curve_init(&in);
    conica_curve_init(&ref);
    conica_curve_init(&out);
    snprintf(rel, sizeof rel, "conis/input/%s.txt", name);
    REQUIRE(load(rel, &in));
    snprintf(rel, sizeof rel, "conis/reference-k5/%s.k5.txt", name);
    REQUIRE(load(rel, &ref));
    in.closed = ref.closed = strcmp(name, "5pointOpenCircle") != 0;
    if (!in.nxy)
        REQUIRE_EQ(conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    REQUIRE_EQ(ts_fairness_measure(in.xy, in.n, in.closed, &poly), 0);
    REQUIRE_EQ(ts_fairness_measure(ref.xy, ref.n, ref.closed, &mref), 0);
    outside = ts_normals_outside_cone(in.xy, in.nxy, in.n, in.closed, NULL);
    convex = poly.sign_changes == 0 && outside == 0;
    turn = max_turn_deg(&in);
    for (k = 0; k < 2; k++) {
        conica_subdiv_info_init(&info);
        s.levels = k ? 8 : 5;
        s.reference_compatible = 0;
        s.precise = 0;
        REQUIRE_EQ(conica_subdivide(&in, &s, &out, &info, NULL), CONICA_OK);
        REQUIRE_EQ(ts_fairness_measure(out.xy, out.n, out.closed, &m[k]), 0);
        INFO("%s at k = %d: %zu curvature sign changes, total variation %.4g", name, s.levels,
             m[k].sign_changes, m[k].tv);
        if (convex)
            CHECK_EQ_U(m[k].sign_changes, 0);
        if (poly.sign_changes > 0 && info.inflections > 0) {
            double bound = mref.tv;
            if (k == 1) {
                conica_subdiv_settings sc = s;
                sc.reference_compatible = 1;
                sc.precise = 1;
                REQUIRE_EQ(conica_subdivide(&in, &sc, &out, NULL, NULL), CONICA_OK);
                REQUIRE_EQ(ts_fairness_measure(out.xy, out.n, out.closed, &mc), 0);
                bound = mc.tv;
            }
            printf("fairness: %-12s k=%d TV %9.4g (reference%s %9.4g)  sign changes %3zu "
                   "(inflections %zu, reference-k5 %zu)  normals outside their cone %zu  "
                   "largest turn %.0f deg\n",
                   name, s.levels, m[k].tv, k ? "-compatible" : "-k5", bound,
                   m[k].sign_changes, info.inflections, mref.sign_changes, outside, turn);
            CHECK_LE(m[k].tv, bound);
            CHECK_EQ_U(m[k].sign_changes, info.inflections);
        }
        conica_subdiv_info_free(&info);
    }
    conica_curve_free(&in);
    conica_curve_free(&ref);
    conica_curve_free(&out);
    return convex;
}

TEST_CASE("reference examples: curvature fairness (one sign when convex, TV <= reference)",
          "[subdiv][reference][data][fairness]")
{
    size_t k;
    int convex = 0;
    ct_data_dir_or_skip();
    for (k = 0; k < NNAMES; k++)
        convex += fairness_one(names[k]);
    printf("fairness: %d convex examples checked at k = 5 and 8\n", convex);
    CHECK(convex > 0);
}
