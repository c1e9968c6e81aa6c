/* SPDX-License-Identifier: MIT */
/* Fidelity on real outlines: the glyphs of a Debian font (FreeType), each
 * contour through conica/path.h, measured by the independent checker of
 * tests/support. Prints, per mode: worst distance / tolerance (both
 * directions), worst area error / (tolerance x perimeter), contours and
 * corners kept, points written, CPU seconds. Prints figures, asserts
 * nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conica/path.h"
#include "fidelity.h"
#include "glyphs.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double perimeter(const double *xy, size_t n)
{
    double l = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        l += hypot(xy[2 * j] - xy[2 * i], xy[2 * j + 1] - xy[2 * i + 1]);
    }
    return l;
}

static void run(const char *font, const char *text, int smooth, double rel)
{
    ts_text t;
    size_t contours = 0, kept = 0, corners = 0, ckept = 0, points = 0;
    double worst = 0, limit = 0, area = 0, secs = 0;
    ts_text_init(&t);
    if (ts_text_outlines(font, text, &t) != TS_OK) {
        printf("%s: not available (install fonts-dejavu-core libfreetype-dev)\n", font);
        return;
    }
    for (size_t g = 0; g < t.n; g++) {
        const ts_outline *o = &t.glyph[g];
        conica_path p;
        conica_path_result r;
        conica_path_settings s = conica_path_defaults();
        double t0;
        if (!o->n)
            continue;
        conica_path_init(&p);
        conica_path_result_init(&r);
        for (size_t i = 0; i < o->n; i++) {
            const ts_contour *c = &o->c[i];
            conica_path_move_to(&p, c->seg[0].p[0][0], c->seg[0].p[0][1], 0, NULL);
            for (size_t k = 0; k < c->n; k++) {
                double q[6];
                for (int j = 1; j <= c->seg[k].degree; j++) {
                    q[2 * j - 2] = c->seg[k].p[j][0];
                    q[2 * j - 1] = c->seg[k].p[j][1];
                }
                conica_path_bezier_to(&p, c->seg[k].degree, q, NULL, k, NULL);
            }
            conica_path_close(&p, NULL);
        }
        s.rel_tolerance = rel;
        t0 = cpu();
        if ((smooth ? conica_path_smooth(&p, &s, &r, NULL) : conica_path_flatten(&p, &s, &r, NULL)) !=
            CONICA_OK) {
            printf("U+%04lX failed\n", t.cp[g]);
            conica_path_free(&p);
            continue;
        }
        secs += cpu() - t0;
        contours += o->n;
        kept += r.n;
        for (size_t i = 0; i < r.n && i < o->n; i++) {
            ts_poly poly = {r.lines[i].xy, r.lines[i].n, 1};
            ts_hausdorff h;
            ts_corner *k = NULL;
            size_t nk = 0;
            ts_corner_check kc;
            double tol = r.lines[i].tolerance;
            points += r.lines[i].n;
            if (ts_hausdorff_measure(&o->c[i], 1, &poly, 1, NULL, &h) == TS_OK && h.max / tol > worst)
                worst = h.max / tol;
            {
                double a = fabs(ts_poly_area(poly.xy, poly.n) - ts_contour_area(&o->c[i])) /
                           (tol * perimeter(poly.xy, poly.n));
                area = a > area ? a : area;
            }
            if (ts_contour_corners(&o->c[i], 40.0 * M_PI / 180.0 + 1e-6, &k, &nk) == TS_OK &&
                ts_corners_kept(k, nk, &poly, 1, 1e-9, (smooth ? 5.0 : 25.0) * M_PI / 180.0, &kc) ==
                    TS_OK) {
                corners += nk;
                ckept += kc.kept;
            }
            free(k);
        }
        if (smooth) {
            /* the limit curve: the same samples at level 8 (chords 1/16 of
             * level 4's), whose points all lie on it */
            conica_path_result_free(&r);
            s.levels = 8;
            if (conica_path_smooth(&p, &s, &r, NULL) == CONICA_OK)
                for (size_t i = 0; i < r.n && i < o->n; i++) {
                    ts_poly poly = {r.lines[i].xy, r.lines[i].n, 1};
                    ts_hausdorff h;
                    if (ts_hausdorff_measure(&o->c[i], 1, &poly, 1, NULL, &h) == TS_OK &&
                        h.max / r.lines[i].tolerance > limit)
                        limit = h.max / r.lines[i].tolerance;
                }
        }
        conica_path_result_free(&r);
        conica_path_free(&p);
    }
    {
        const char *base = strrchr(font, '/');
        char lim[16] = "-";
        if (smooth)
            snprintf(lim, sizeof lim, "%5.3f", limit);
        printf("| %-7s | %s | %.0e | %s | %5.3f | %5.3f | %zu/%zu | %zu/%zu | %zu | %.3f |\n",
               smooth ? "smooth" : "flatten", base ? base + 1 : font, rel, lim, worst, area, kept,
               contours, ckept, corners, points, secs);
    }
    ts_text_free(&t);
}

/* Points of a flattened r = 50 circle (two SVG-style arcs) per fit mode,
 * beside the fewest any polygon needs: inscribed R (1 - cos(pi/n)) <= T,
 * circumscribed R (1/cos(pi/n) - 1) <= T, straddling (R - T)/cos(pi/n)
 * = R + T at best, i.e. cos(pi/n) >= (R - T)/(R + T). */
static void circle_table(void)
{
    const double R = 50, T[3] = {0.1, 0.01, 0.001};
    const char *names[3] = {"inside", "outside", "middle"};
    printf("\nFlattened circle r = 50 (conica_path_flatten, two arcs), points vs the minimum\n\n");
    printf("| fit | T | points | minimum | ratio | worst deviation / T |\n|---|---|---|---|---|---|\n");
    for (int f = 0; f < 3; f++)
        for (int k = 0; k < 3; k++) {
            conica_path p;
            conica_path_result r;
            conica_path_settings s = conica_path_defaults();
            double c = f == 0 ? 1 - T[k] / R : f == 1 ? R / (R + T[k]) : (R - T[k]) / (R + T[k]);
            double nmin = ceil(M_PI / acos(c)), worst = 0;
            conica_path_init(&p);
            conica_path_result_init(&r);
            conica_path_move_to(&p, R, 0, 0, NULL);
            conica_path_arc_to(&p, 0, 0, R, R, 0, 0, M_PI, -R, 0, 0, NULL);
            conica_path_arc_to(&p, 0, 0, R, R, 0, M_PI, M_PI, R, 0, 0, NULL);
            conica_path_close(&p, NULL);
            s.tolerance = T[k];
            s.fit = (conica_path_fit)f;
            if (conica_path_flatten(&p, &s, &r, NULL) != CONICA_OK) {
                printf("| %s | %g | failed |\n", names[f], T[k]);
                conica_path_free(&p);
                continue;
            }
            {
                /* measured: vertices and chord middles against the circle */
                const conica_path_polyline *l = &r.lines[0];
                for (size_t i = 0; i < l->n; i++) {
                    size_t j = (i + 1) % l->n;
                    double mx = 0.5 * (l->xy[2 * i] + l->xy[2 * j]);
                    double my = 0.5 * (l->xy[2 * i + 1] + l->xy[2 * j + 1]);
                    worst = fmax(worst, fabs(hypot(l->xy[2 * i], l->xy[2 * i + 1]) - R));
                    worst = fmax(worst, fabs(hypot(mx, my) - R));
                }
            }
            printf("| %s | %g | %zu | %.0f | %.3f | %.6f |\n", names[f], T[k], r.lines[0].n, nmin,
                   (double)r.lines[0].n / nmin, worst / T[k]);
            conica_path_result_free(&r);
            conica_path_free(&p);
        }
}

int main(void)
{
    const char *text = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789&@%$?";
    printf("Fidelity on real outlines (DejaVu glyphs, %zu characters; lib: conica/path.h,\n"
           "checker: tests/support, dense sampling both directions)\n\n",
           strlen(text));
    printf("| mode | font | rel. tol | limit curve: worst dist / tol | written polyline: worst dist / tol | "
           "area err / (tol x perim) | contours kept | corners kept | points | CPU s |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++) {
            run(TS_FONT_SANS, text, m == 0, k ? 1e-4 : 1e-3);
            run(TS_FONT_SERIF, text, m == 0, k ? 1e-4 : 1e-3);
        }
    circle_table();
    return 0;
}
