/* SPDX-License-Identifier: MIT */
/* Table A (issue 38): in one run, for random cubic and quadratic Bézier
 * pieces, elliptic arcs (rational quadratic pieces), full ellipses as
 * 9-point quadratic NURBS and general rational quadratics (random
 * weights) in a 100 x 100 box, at T = 0.1, 0.01, 0.001: the guaranteed
 * plotter's points over the independent greedy optimum (median, p90 of the
 * per-curve ratios; the greedy reference and the checker are
 * tests/support/flatten_check.c's), its CPU time over cairo's
 * (cairo_copy_path_flat at cairo_set_tolerance(T); arcs and ellipses drawn
 * with cairo_arc under the ellipse's affine map, the way a cairo user
 * draws them; cairo has no general rational quadratic), and violations of
 * T by the checker (conica: both directions, from its parameters; cairo:
 * CHECK_SAMPLES curve points against its polyline). Prints, asserts
 * nothing.
 *
 * usage: build/bench/bench_arcs [--quick]
 *        build/bench/bench_arcs --time SET T REPS  (conica alone, see time_set) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conica/plot.h"
#include "flatten_check.h"

#ifdef CONICA_HAVE_CAIRO
#include <cairo.h>

#include "cairo_points.h"
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define N_TIME 1000       /* curves per set timed */
#define N_GREEDY 40       /* of them compared with the greedy optimum */
#define ROUNDS 3          /* alternating timing rounds, best taken */
#define CHECK_SAMPLES 400 /* curve samples per curve for cairo's violations */
#define XY_CAP (1 << 16)  /* points of one flattened curve */

enum { SET_CUBIC, SET_QUAD, SET_ARC, SET_CIRCLE, SET_RATIONAL, SET_COUNT };
static const char *set_name[SET_COUNT] = {"cubic", "quadratic", "conic arc (ellipse)",
                                          "NURBS ellipse (full)", "rational quadratic"};
static const double tols[3] = {0.1, 0.01, 0.001};

typedef struct curve {
    conica_bspline s;
    int degree;         /* Bézier degree of a single piece, 0 for the NURBS ellipse */
    double ctrl[8], w[3];
    double cx, cy, rot, ax, ay, th0, th1; /* the ellipse arc, for cairo */
} curve;

static unsigned long long rng = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The point (cos t, sin t) of the unit circle scaled by r under the
 * ellipse map of c. */
static void ell_map(const curve *c, double x, double y, double *out)
{
    double ex = c->ax * x, ey = c->ay * y, cs = cos(c->rot), sn = sin(c->rot);
    out[0] = c->cx + cs * ex - sn * ey;
    out[1] = c->cy + sn * ex + cs * ey;
}

static void random_ellipse(curve *c)
{
    c->ax = 5 + 45 * urand();
    c->ay = 5 + 45 * urand();
    c->cx = 50 + (urand() - 0.5) * 20;
    c->cy = 50 + (urand() - 0.5) * 20;
    c->rot = 2 * M_PI * urand();
}

static void make_curve(int set, curve *c)
{
    conica_bspline_init(&c->s);
    c->degree = set == SET_CUBIC ? 3 : (set == SET_CIRCLE ? 0 : 2);
    if (set == SET_CUBIC || set == SET_QUAD) {
        for (int k = 0; k < 2 * (c->degree + 1); k++)
            c->ctrl[k] = 100 * urand();
        conica_bspline_from_bezier(c->degree, 2, c->ctrl, NULL, &c->s, NULL);
    } else if (set == SET_RATIONAL) {
        for (int k = 0; k < 6; k++)
            c->ctrl[k] = 100 * urand();
        c->w[0] = c->w[2] = 1.0;
        c->w[1] = exp(log(0.2) + (log(5.0) - log(0.2)) * urand()); /* 0.2..5 */
        conica_bspline_from_bezier(2, 2, c->ctrl, c->w, &c->s, NULL);
    } else if (set == SET_ARC) { /* sweep 0.1..pi: one rational quadratic piece */
        random_ellipse(c);
        double sweep = 0.1 + (M_PI - 0.1) * urand();
        c->th0 = 2 * M_PI * urand();
        c->th1 = c->th0 + sweep;
        double h = 0.5 * sweep, m = c->th0 + h;
        ell_map(c, cos(c->th0), sin(c->th0), c->ctrl);
        ell_map(c, cos(m) / cos(h), sin(m) / cos(h), c->ctrl + 2);
        ell_map(c, cos(c->th1), sin(c->th1), c->ctrl + 4);
        c->w[0] = c->w[2] = 1.0;
        c->w[1] = cos(h);
        conica_bspline_from_bezier(2, 2, c->ctrl, c->w, &c->s, NULL);
    } else { /* the 9-point quadratic NURBS ellipse, knots 0 0 0 1 1 2 2 3 3 4 4 4 */
        random_ellipse(c);
        c->th0 = 0;
        c->th1 = 2 * M_PI;
        static const double ux[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
        static const double uy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
        static const double kn[12] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
        double P[18], W[9];
        for (int i = 0; i < 9; i++) {
            ell_map(c, ux[i], uy[i], P + 2 * i);
            W[i] = i % 2 ? sqrt(0.5) : 1.0;
        }
        conica_bspline_set(2, 2, kn, 12, P, 9, W, &c->s, NULL);
    }
}

/* Guaranteed flattening of c at T: the lean entry for one Bézier piece,
 * conica_plot for the NURBS ellipse. Returns the point count (0 on
 * failure). */
static size_t conica_flat(const curve *c, double T, double *xy, conica_polyline *pl)
{
    if (c->degree > 0) {
        size_t n = 0;
        int rational = c->s.w != NULL;
        if (conica_plot_bezier(c->degree, c->ctrl, rational ? c->w : NULL, T, 0, xy, NULL, XY_CAP,
                               &n, NULL) != CONICA_OK)
            return 0;
        return n;
    }
    conica_plot_settings ps = conica_plot_defaults();
    ps.abs_tolerance = T;
    return conica_plot(&c->s, &ps, pl, NULL, NULL) == CONICA_OK ? pl->n : 0;
}

#ifdef CONICA_HAVE_CAIRO
static size_t cairo_flat(cairo_t *cr, const curve *c, double *xy)
{
    cairo_new_path(cr);
    if (c->degree == 3) {
        cairo_move_to(cr, c->ctrl[0], c->ctrl[1]);
        cairo_curve_to(cr, c->ctrl[2], c->ctrl[3], c->ctrl[4], c->ctrl[5], c->ctrl[6], c->ctrl[7]);
    } else if (c->degree == 2 && !c->s.w) { /* the quadratic as its exact cubic */
        const double *q = c->ctrl;
        cairo_move_to(cr, q[0], q[1]);
        cairo_curve_to(cr, q[0] + 2.0 / 3.0 * (q[2] - q[0]), q[1] + 2.0 / 3.0 * (q[3] - q[1]),
                       q[4] + 2.0 / 3.0 * (q[2] - q[4]), q[5] + 2.0 / 3.0 * (q[3] - q[5]), q[4],
                       q[5]);
    } else {
        cairo_save(cr);
        cairo_translate(cr, c->cx, c->cy);
        cairo_rotate(cr, c->rot);
        cairo_scale(cr, c->ax, c->ay);
        cairo_arc(cr, 0, 0, 1, c->th0, c->th1);
        cairo_restore(cr);
    }
    return bench_cairo_points(cr, xy, XY_CAP);
}

#endif

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* --time SET T REPS: conica alone on the 1000 curves of set SET (0 cubic
 * .. 4 rational quadratic) at T, REPS times: CPU per curve and points (for
 * callgrind, or to compare builds without cairo's noise). */
static int time_set(int set, double T, int reps)
{
    curve *cv = malloc(N_TIME * sizeof *cv);
    double *xy = malloc(2 * XY_CAP * sizeof *xy);
    if (!cv || !xy || set < 0 || set >= SET_COUNT || reps < 1)
        return 1;
    conica_polyline pl;
    conica_polyline_init(&pl);
    rng = 0x9E3779B97F4A7C15ull + (unsigned long long)set;
    for (size_t i = 0; i < N_TIME; i++)
        make_curve(set, &cv[i]);
    size_t pts = 0;
    double t0 = cpu_now();
    for (int r = 0; r < reps; r++)
        for (size_t i = 0; i < N_TIME; i++)
            pts += conica_flat(&cv[i], T, xy, &pl);
    double t = (cpu_now() - t0) / reps / N_TIME;
    printf("%s, T = %g: %.3f us per curve, %.1f points\n", set_name[set], T, 1e6 * t,
           (double)pts / reps / N_TIME);
    for (size_t i = 0; i < N_TIME; i++)
        conica_bspline_free(&cv[i].s);
    conica_polyline_free(&pl);
    free(cv);
    free(xy);
    return 0;
}

int main(int argc, char **argv)
{
    size_t ntime = N_TIME, ngreedy = N_GREEDY;
    if (argc == 5 && strcmp(argv[1], "--time") == 0)
        return time_set(atoi(argv[2]), atof(argv[3]), atoi(argv[4]));
    if (argc > 1 && strcmp(argv[1], "--quick") == 0) {
        ntime = 200;
        ngreedy = 10;
    } else if (argc > 1) {
        fprintf(stderr, "usage: bench_arcs [--quick | --time SET T REPS]\n");
        return 2;
    }
    curve *cv = malloc(ntime * sizeof *cv);
    double *xy = malloc(2 * XY_CAP * sizeof *xy), *ratio = malloc(ngreedy * sizeof *ratio);
    if (!cv || !xy || !ratio)
        return 1;
#ifdef CONICA_HAVE_CAIRO
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(sf);
#endif
    printf("Table A: guaranteed plotter vs the greedy optimum and cairo, %zu curves per set "
           "(%zu against the greedy optimum), 100 x 100 box, fixed seed\n\n",
           ntime, ngreedy);
    printf("| set | T | pts / greedy median | p90 | conica pts | cairo pts | conica us | cairo us "
           "| CPU conica / cairo | conica worst dev / T (violations) | cairo worst dev / T "
           "(violations) |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    conica_polyline pl;
    conica_polyline_init(&pl);
    for (int set = 0; set < SET_COUNT; set++) {
        rng = 0x9E3779B97F4A7C15ull + (unsigned long long)set;
        for (size_t i = 0; i < ntime; i++)
            make_curve(set, &cv[i]);
        int has_cairo = set != SET_RATIONAL;
        for (int ti = 0; ti < 3; ti++) {
            double T = tols[ti], best_g = INFINITY, best_c = INFINITY;
#ifdef CONICA_HAVE_CAIRO
            cairo_set_tolerance(cr, T);
#endif
            for (int r = 0; r < ROUNDS; r++)
                for (int k = 0; k < 2; k++) {
                    int which = (k + r) % 2; /* 0 conica, 1 cairo */
                    if (which == 1 && !has_cairo)
                        continue;
                    double t0 = cpu_now();
                    for (size_t i = 0; i < ntime; i++) {
                        if (which == 0)
                            conica_flat(&cv[i], T, xy, &pl);
#ifdef CONICA_HAVE_CAIRO
                        else
                            cairo_flat(cr, &cv[i], xy);
#endif
                    }
                    double t = (cpu_now() - t0) / (double)ntime;
                    double *best = which == 0 ? &best_g : &best_c;
                    *best = t < *best ? t : *best;
                }
            size_t pg = 0, pc = 0, vg = 0, vc = 0;
            double wg = 0, wc = 0;
            for (size_t i = 0; i < ntime; i++) {
                conica_plot_settings ps = conica_plot_defaults();
                ps.abs_tolerance = T;
                if (conica_plot(&cv[i].s, &ps, &pl, NULL, NULL) != CONICA_OK) {
                    vg++;
                    continue;
                }
                double back = 0, dg = fc_plot_dev(&cv[i].s, &pl, &back);
                dg = back > dg ? back : dg;
                wg = dg / T > wg ? dg / T : wg;
                vg += dg > T;
                pg += pl.n;
                if (i < ngreedy)
                    ratio[i] = (double)pl.n / (double)fc_greedy(&cv[i].s, T);
#ifdef CONICA_HAVE_CAIRO
                if (has_cairo) {
                    size_t n = cairo_flat(cr, &cv[i], xy);
                    double dc = fc_curve_to_polyline(&cv[i].s, xy, n, CHECK_SAMPLES);
                    pc += n;
                    wc = dc / T > wc ? dc / T : wc;
                    vc += dc > T;
                }
#endif
            }
            qsort(ratio, ngreedy, sizeof *ratio, cmp_d);
            size_t p90 = (size_t)ceil(0.9 * (double)ngreedy) - 1;
            printf("| %s | %g | %.3fx | %.3fx | %.1f |", set_name[set], T,
                   ratio[ngreedy / 2], ratio[p90], (double)pg / (double)ntime);
            if (has_cairo && isfinite(best_c))
                printf(" %.1f | %.3f | %.3f | **%.2f** | %.3f (%zu) | %.3f (%zu) |\n",
                       (double)pc / (double)ntime, best_g * 1e6, best_c * 1e6, best_g / best_c, wg,
                       vg, wc, vc);
            else
                printf(" - | %.3f | - | - | %.3f (%zu) | - |\n", best_g * 1e6, wg, vg);
        }
        for (size_t i = 0; i < ntime; i++)
            conica_bspline_free(&cv[i].s);
    }
    printf("\n");
    conica_polyline_free(&pl);
#ifdef CONICA_HAVE_CAIRO
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
#else
    printf("Table A: notice: built without cairo (Debian libcairo2-dev): no cairo columns\n");
#endif
    free(cv);
    free(xy);
    free(ratio);
    return 0;
}
