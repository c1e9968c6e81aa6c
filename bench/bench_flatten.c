/* SPDX-License-Identifier: MIT */
/* Flattening against an independent greedy reference and against cairo
 * (issue 20). Prints tables, asserts nothing.
 *
 * usage: build/bench/bench_flatten [--verbose] [--table greedy|cairo]
 *            [SPLINES_DIR]
 * (SPLINES_DIR defaults to $CONICA_SHARED_DATA/splines, else
 * ../shared/data/splines; run from the repository root so that examples/
 * is found.)
 *
 * Table G: on the curve set of tests/support/flatten_check.h (thesis
 *   curves, examples, 50 random B-splines of degrees 2-7, rational ones,
 *   near-cusps) at 1e-2, 1e-3, 1e-4 of the control points' diagonal: the
 *   guaranteed plotter's points over the greedy reference's (longest chord
 *   from each point whose true deviation is within tolerance), and the
 *   largest true deviation of its output in both directions, measured by
 *   the checker (never by the plotter's certificate).
 * Table C (built with cairo only): random cubic and quadratic Bézier
 *   pieces flattened by cairo_copy_path_flat at cairo_set_tolerance(T), by
 *   conica_plot_bezier (the lean entry for one piece, the same points) and
 *   by conica_plot at abs_tolerance T: CPU time (CLOCK_PROCESS_CPUTIME_ID,
 *   best of alternating rounds), points, and violations of T measured by
 *   the checker (cairo's points carry no parameters: the curve -> polyline
 *   distance is measured against the whole polyline). */
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

#define NRANDOM 50
#define BEZ_COUNT 2000    /* Bézier pieces per kind in Table C */
#define ROUNDS 5          /* alternating rounds of Table C */
#define CHECK_SAMPLES 200 /* curve samples per piece for cairo's violations */

static const double rel_tols[3] = {1e-2, 1e-3, 1e-4};

static void table_greedy(const char *splines_dir, int verbose)
{
    fc_set *set = malloc(sizeof *set);
    if (!set)
        return;
    fc_set_make(set, splines_dir, "examples", NRANDOM);
    printf("Table G: guaranteed plotter vs the independent greedy reference, %zu curves "
           "(%zu thesis curves from %s)\n\n",
           set->n, set->thesis, splines_dir);
    if (set->thesis == 0)
        fprintf(stderr, "bench_flatten: notice: no thesis curves in %s: skipped\n", splines_dir);
    printf("| tolerance / diagonal | guaranteed pts | greedy pts | mean ratio | worst ratio "
           "(curve) | largest deviation / tol (curve->poly, poly->curve) | violations |\n"
           "|---|---|---|---|---|---|---|\n");
    double all = 0;
    size_t nall = 0;
    for (int ti = 0; ti < 3; ti++) {
        size_t pg = 0, pr = 0, viol = 0;
        double sum = 0, worst = 0, wdev = 0, wback = 0;
        const char *wname = "";
        for (size_t i = 0; i < set->n; i++) {
            const conica_bspline *s = &set->s[i];
            double tol = rel_tols[ti] * conica_plot_extent(s);
            conica_polyline pl;
            conica_polyline_init(&pl);
            if (fc_plot(s, tol, &pl) != CONICA_OK) {
                printf("| %s: plot failed |\n", set->name[i]);
                continue;
            }
            size_t g = fc_greedy(s, tol);
            double back = 0, dev = fc_plot_dev(s, &pl, &back);
            double ratio = (double)pl.n / (double)g;
            if (verbose)
                printf("| %s | %g | %zu | %zu | %.3f | %.3f | %.3f |\n", set->name[i],
                       rel_tols[ti], pl.n, g, ratio, dev / tol, back / tol);
            pg += pl.n;
            pr += g;
            sum += ratio;
            all += ratio;
            nall++;
            if (ratio > worst) {
                worst = ratio;
                wname = set->name[i];
            }
            wdev = dev / tol > wdev ? dev / tol : wdev;
            wback = back / tol > wback ? back / tol : wback;
            viol += dev > tol || back > tol;
            conica_polyline_free(&pl);
        }
        printf("| %g | %zu | %zu | %.3fx | %.3fx (%s) | %.4f, %.4f | %zu |\n", rel_tols[ti], pg,
               pr, sum / (double)set->n, worst, wname, wdev, wback, viol);
    }
    printf("\nMean ratio over all %zu plots: %.4fx\n\n", nall, all / (double)(nall ? nall : 1));
    fc_set_free(set);
    free(set);
}

#ifdef CONICA_HAVE_CAIRO
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static unsigned long long rng = 0x853C49E6748FEA9Bull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* cairo's flattening of one cubic (c[8]) into xy (cap points); returns
 * the point count. */
static size_t cairo_flat(cairo_t *cr, const double *c, double *xy, size_t cap)
{
    cairo_new_path(cr);
    cairo_move_to(cr, c[0], c[1]);
    cairo_curve_to(cr, c[2], c[3], c[4], c[5], c[6], c[7]);
    return bench_cairo_points(cr, xy, cap);
}

static void table_cairo(void)
{
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
    cairo_t *cr = cairo_create(sf);
    double *cub = malloc(BEZ_COUNT * 8 * sizeof *cub);
    conica_bspline *sp = malloc(BEZ_COUNT * sizeof *sp);
    size_t cap = 1 << 16;
    double *xy = malloc(2 * cap * sizeof *xy);
    if (!cub || !sp || !xy)
        return;
    printf("Table C: cubic and quadratic Bézier pieces in a 100 x 100 box (%d each, fixed seed):\n"
           "cairo_copy_path_flat at cairo_set_tolerance(T) vs conica_plot_bezier and conica_plot\n"
           "(guaranteed) at abs_tolerance T; CPU us per piece, best of %d alternating rounds; deviation\n"
           "measured by the checker (tests/support/flatten_check.c)\n\n",
           BEZ_COUNT, ROUNDS);
    printf("| pieces | T | cairo us | conica_plot_bezier us | conica_plot us | conica / cairo "
           "CPU (conica_plot) | cairo pts | conica pts | cairo worst dev / T (violations) | "
           "conica worst dev / T (violations) |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int kind = 0; kind < 2; kind++) {
        int p = kind == 0 ? 3 : 2;
        rng = 0x853C49E6748FEA9Bull + (unsigned long long)kind;
        for (size_t i = 0; i < BEZ_COUNT; i++) {
            double q[8];
            for (int k = 0; k < 8; k++)
                q[k] = 100 * urand();
            double *c = cub + 8 * i;
            if (p == 2) { /* the quadratic q0 q1 q2 as its exact cubic for cairo */
                c[0] = q[0];
                c[1] = q[1];
                c[2] = q[0] + 2.0 / 3.0 * (q[2] - q[0]);
                c[3] = q[1] + 2.0 / 3.0 * (q[3] - q[1]);
                c[4] = q[4] + 2.0 / 3.0 * (q[2] - q[4]);
                c[5] = q[5] + 2.0 / 3.0 * (q[3] - q[5]);
                c[6] = q[4];
                c[7] = q[5];
            } else {
                memcpy(c, q, sizeof q);
            }
            conica_bspline_init(&sp[i]);
            conica_bspline_from_bezier(p, 2, p == 2 ? q : c, NULL, &sp[i], NULL);
        }
        for (int ti = 0; ti < 2; ti++) {
            double T = ti == 0 ? 0.1 : 0.01;
            conica_plot_settings ps = conica_plot_defaults();
            ps.abs_tolerance = T;
            cairo_set_tolerance(cr, T);
            conica_polyline pl;
            conica_polyline_init(&pl);
            double best_c = INFINITY, best_g = INFINITY, best_b = INFINITY;
            for (int r = 0; r < ROUNDS; r++)
                for (int which = 0; which < 3; which++) {
                    int w = (which + r) % 3;
                    size_t nb = 0;
                    double t0 = cpu_now();
                    for (size_t i = 0; i < BEZ_COUNT; i++) {
                        if (w == 0)
                            cairo_flat(cr, cub + 8 * i, xy, cap);
                        else if (w == 1)
                            conica_plot(&sp[i], &ps, &pl, NULL, NULL);
                        else
                            conica_plot_bezier(p, sp[i].ctrl, NULL, T, 0, xy, NULL, cap, &nb,
                                               NULL);
                    }
                    double t = (cpu_now() - t0) / BEZ_COUNT;
                    double *best = w == 0 ? &best_c : (w == 1 ? &best_g : &best_b);
                    *best = t < *best ? t : *best;
                }
            size_t pc = 0, pg = 0, vc = 0, vg = 0;
            double wc = 0, wg = 0;
            for (size_t i = 0; i < BEZ_COUNT; i++) {
                size_t n = cairo_flat(cr, cub + 8 * i, xy, cap);
                pc += n;
                double dc = fc_curve_to_polyline(&sp[i], xy, n, CHECK_SAMPLES);
                wc = dc / T > wc ? dc / T : wc;
                vc += dc > T;
                if (conica_plot(&sp[i], &ps, &pl, NULL, NULL) == CONICA_OK) {
                    double back = 0, dg = fc_plot_dev(&sp[i], &pl, &back);
                    dg = back > dg ? back : dg;
                    pg += pl.n;
                    wg = dg / T > wg ? dg / T : wg;
                    vg += dg > T;
                }
            }
            conica_polyline_free(&pl);
            printf("| %s | %g | %.3f | %.3f | %.3f | **%.2f** (%.2f) | %.2f | %.2f | %.3f (%zu) | "
                   "%.3f (%zu) |\n",
                   p == 3 ? "cubic" : "quadratic", T, best_c * 1e6, best_b * 1e6, best_g * 1e6,
                   best_b / best_c, best_g / best_c, (double)pc / BEZ_COUNT,
                   (double)pg / BEZ_COUNT, wc, vc, wg, vg);
        }
        for (size_t i = 0; i < BEZ_COUNT; i++)
            conica_bspline_free(&sp[i]);
    }
    printf("\n");
    free(cub);
    free(sp);
    free(xy);
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
}
#endif

int main(int argc, char **argv)
{
    const char *dir = "../shared/data/splines", *only = NULL, *env = getenv("CONICA_SHARED_DATA");
    char envdir[2048];
    int verbose = 0;
    if (env && *env) {
        snprintf(envdir, sizeof envdir, "%s/splines", env);
        dir = envdir;
    }
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--verbose") == 0)
            verbose = 1;
        else if (strcmp(argv[i], "--table") == 0 && i + 1 < argc)
            only = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_flatten [--verbose] [--table greedy|cairo] [DIR]\n");
            return 2;
        } else
            dir = argv[i];
    }
    if (!only || strcmp(only, "greedy") == 0)
        table_greedy(dir, verbose);
    if (!only || strcmp(only, "cairo") == 0) {
#ifdef CONICA_HAVE_CAIRO
        table_cairo();
#else
        printf("Table C: notice: built without cairo (Debian libcairo2-dev), skipped\n");
#endif
    }
    return 0;
}
