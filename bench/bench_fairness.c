/* SPDX-License-Identifier: MIT */
/* bench_fairness (issue 20): fairness of the curvature at inflections on the
 * reference implementation's own examples (conis/input of the shared data,
 * from $CONICA_SHARED_DATA, else ../shared/data from the working directory;
 * skipped with a notice when absent). For every example whose polygon turns
 * both ways (the CONIS paper's inserted inflection points, eq. (9)), prints
 * the total variation of the discrete curvature (circle through three
 * consecutive points, tests/support/ts_fairness.h) and its sign changes:
 * the reference's own output (reference-k5), the reference-compatible mode
 * (absolute coordinates + weighted SVD, long double) and the default mode
 * (local frames), at k = 5 and k = 8; and the number of inflections the
 * input has, and how many of its vertices carry a normal outside the cone of
 * their edges' normals (where the tangles are). A second table needs no
 * data: random folded polygons (points on a circle in random order, points
 * in a square) and star-shaped blobs, normals estimated, at k = 5: how many
 * have as many curvature sign changes as inflections. A benchmark: prints
 * figures, asserts nothing (tests/test_reference_data.c asserts the bounds
 * on the reference's examples).
 *
 * usage: bench_fairness [DATA_DIR] */
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/curve.h"
#include "conica/subdiv.h"
#include "plotsvg.h"
#include "ts_fairness.h"

#define PATH_CAP 1024

/* At most this many examples (the shared data has 23). */
#define MAX_EXAMPLES 256
#define NAME_CAP 128

static int by_name(const void *a, const void *b)
{
    return strcmp((const char *)a, (const char *)b);
}

/* The examples' names: every NAME.txt in DIR/conis/input, sorted. */
static size_t list_examples(const char *dir, char names[][NAME_CAP])
{
    char path[PATH_CAP];
    DIR *d;
    struct dirent *e;
    size_t n = 0;
    snprintf(path, sizeof path, "%s/conis/input", dir);
    if (!(d = opendir(path)))
        return 0;
    while ((e = readdir(d)) != NULL && n < MAX_EXAMPLES) {
        size_t len = strlen(e->d_name);
        if (len > 4 && len < NAME_CAP && !strcmp(e->d_name + len - 4, ".txt")) {
            memcpy(names[n], e->d_name, len - 4);
            names[n][len - 4] = '\0';
            n++;
        }
    }
    closedir(d);
    qsort(names, n, sizeof names[0], by_name);
    return n;
}

static int load(const char *path, int closed, conica_curve *c)
{
    return plotsvg_load_curve("bench_fairness", path, closed, c) == 0;
}

/* Subdivide in = (reference-compatible + precise, or default) at k levels
 * and measure; returns the number of inflection points inserted, -1 on
 * failure. */
static long run(const conica_curve *in, int compat, int k, ts_fairness *m)
{
    conica_subdiv_settings s = conica_subdiv_defaults();
    conica_subdiv_info info;
    conica_curve out;
    conica_status st;
    long ninfl = -1;
    conica_curve_init(&out);
    conica_subdiv_info_init(&info);
    s.levels = k;
    s.reference_compatible = compat;
    s.precise = compat;
    if (conica_subdivide(in, &s, &out, &info, &st) != CONICA_OK)
        fprintf(stderr, "bench_fairness: %s\n", st.message);
    else if (ts_fairness_measure(out.xy, out.n, out.closed, m) == 0)
        ninfl = (long)info.inflections;
    conica_subdiv_info_free(&info);
    conica_curve_free(&out);
    return ninfl;
}

/* Random folded polygons (seeded, so the table is the same every run). */
#define FOLD_SEED 20u
#define FOLD_POLYGONS 300
#define FOLD_MIN_POINTS 5
#define FOLD_MAX_POINTS 16
#define FOLD_LEVELS 5

/* xorshift64*: a uniform double in [0, 1). */
static double fold_uniform(uint64_t *st)
{
    *st ^= *st >> 12;
    *st ^= *st << 25;
    *st ^= *st >> 27;
    return (double)((*st * 2685821657736338717ull) >> 11) * 0x1.0p-53;
}

/* One polygon of family fam (0: points on the unit circle in random order,
 * 1: points in the square [-1, 1]^2, 2: a star-shaped blob, radius 0.5 to
 * 1.5 at evenly spaced angles) into xy; returns its size. */
static size_t fold_polygon(int fam, uint64_t *st, double *xy)
{
    size_t n = FOLD_MIN_POINTS +
               (size_t)(fold_uniform(st) * (FOLD_MAX_POINTS - FOLD_MIN_POINTS + 1)), i;
    const double two_pi = 6.283185307179586;
    for (i = 0; i < n; i++) {
        double a = two_pi * fold_uniform(st), r = 1;
        if (fam == 1) {
            xy[2 * i] = 2 * fold_uniform(st) - 1;
            xy[2 * i + 1] = 2 * fold_uniform(st) - 1;
            continue;
        }
        if (fam == 2) {
            a = two_pi * (double)i / (double)n;
            r = 0.5 + fold_uniform(st);
        }
        xy[2 * i] = r * cos(a);
        xy[2 * i + 1] = r * sin(a);
    }
    return n;
}

static void fold_table(void)
{
    static const char *const fam_name[3] = {"points on a circle, random order",
                                            "points in a square", "star-shaped blobs"};
    int fam;
    printf("\nRandom polygons (%d per family, %d-%d points, seed %u), normals estimated\n"
           "(area), k = %d: polygons whose curvature sign changes equal their inflections,\n"
           "the excess sign changes in total, and the median TV:\n\n",
           FOLD_POLYGONS, FOLD_MIN_POINTS, FOLD_MAX_POINTS, FOLD_SEED, FOLD_LEVELS);
    printf("| family | sc = inflections | excess sc | median TV |\n|---|---|---|---|\n");
    for (fam = 0; fam < 3; fam++) {
        static double tv[FOLD_POLYGONS];
        uint64_t st = 0x9E3779B97F4A7C15ull * (FOLD_SEED + (uint64_t)fam);
        size_t equal = 0, excess = 0, ntv = 0, a, b;
        int t;
        for (t = 0; t < FOLD_POLYGONS; t++) {
            double xy[2 * FOLD_MAX_POINTS];
            size_t n = fold_polygon(fam, &st, xy);
            conica_curve in;
            ts_fairness m;
            long ni;
            conica_curve_init(&in);
            if (conica_curve_set(xy, NULL, n, 1, &in, NULL) != CONICA_OK ||
                conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL) != CONICA_OK) {
                conica_curve_free(&in);
                continue;
            }
            ni = run(&in, 0, FOLD_LEVELS, &m);
            conica_curve_free(&in);
            if (ni < 0)
                continue;
            equal += m.sign_changes == (size_t)ni;
            excess += m.sign_changes > (size_t)ni ? m.sign_changes - (size_t)ni : 0;
            tv[ntv++] = m.tv;
        }
        for (a = 1; a < ntv; a++) /* insertion sort: 300 values */
            for (b = a; b > 0 && tv[b - 1] > tv[b]; b--) {
                double x = tv[b];
                tv[b] = tv[b - 1];
                tv[b - 1] = x;
            }
        printf("| %s | %zu of %zu | %zu | %.4g |\n", fam_name[fam], equal, ntv, excess,
               ntv ? tv[ntv / 2] : 0.0);
    }
}

int main(int argc, char **argv)
{
    const char *env = getenv("CONICA_SHARED_DATA");
    const char *dir = argc > 1 ? argv[1] : (env && *env ? env : "../shared/data");
    static char names[MAX_EXAMPLES][NAME_CAP];
    char path[PATH_CAP];
    size_t i, nnames;
    int any = 0;
    snprintf(path, sizeof path, "%s/conis/input/example9.txt", dir);
    {
        FILE *probe = fopen(path, "rb");
        if (!probe) {
            printf("notice: %s absent (set CONICA_SHARED_DATA or pass DATA_DIR): reference "
                   "examples skipped\n",
                   path);
            fold_table();
            return 0;
        }
        fclose(probe);
    }
    printf("Curvature total variation (TV) and sign changes (sc) on the reference's\n"
           "non-convex examples; ref = reference-k5 output, compat = reference-compatible\n"
           "+ precise, local = default mode; infl = inflections of the input; outside =\n"
           "vertices whose normal lies outside the cone of its two edges' normals (no\n"
           "convex arc leaves them along the polygon), the first one named.\n\n");
    printf("| example | infl | outside | k=5 ref TV (sc) | k=5 compat TV (sc) | k=5 local TV (sc) "
           "| k=8 compat TV (sc) | k=8 local TV (sc) |\n|---|---|---|---|---|---|---|---|\n");
    nnames = list_examples(dir, names);
    for (i = 0; i < nnames; i++) {
        conica_curve in, ref;
        ts_fairness mr, m[4];
        long ni[4];
        int k, ok = 1, closed = strcmp(names[i], "5pointOpenCircle") != 0;
        size_t bad = 0, first = 0;
        conica_curve_init(&in);
        conica_curve_init(&ref);
        if (snprintf(path, sizeof path, "%s/conis/input/%s.txt", dir, names[i]) >=
                (int)sizeof path ||
            !load(path, closed, &in))
            ok = 0;
        if (ok && (snprintf(path, sizeof path, "%s/conis/reference-k5/%s.k5.txt", dir,
                            names[i]) >= (int)sizeof path ||
                   !load(path, closed, &ref)))
            ok = 0;
        if (ok) {
            if (!in.nxy && conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL) != CONICA_OK)
                ok = 0;
        }
        for (k = 0; ok && k < 4; k++)
            ni[k] = run(&in, !(k & 1), k < 2 ? 5 : 8, &m[k]);
        if (ok)
            bad = ts_normals_outside_cone(in.xy, in.nxy, in.n, in.closed, &first);
        if (ok && ni[0] > 0) {
            char outside[64] = "none";
            any = 1;
            if (bad)
                snprintf(outside, sizeof outside, "%zu (p%zu)", bad, first);
            if (ts_fairness_measure(ref.xy, ref.n, ref.closed, &mr) != 0)
                printf("| %s | %ld | %s | (no curvature) |", names[i], ni[0], outside);
            else
                printf("| %s | %ld | %s | %.4g (%zu) |", names[i], ni[0], outside, mr.tv,
                       mr.sign_changes);
            for (k = 0; k < 4; k++)
                if (ni[k] < 0)
                    printf(" failed |");
                else
                    printf(" %.4g (%zu) |", m[k].tv, m[k].sign_changes);
            printf("\n");
        } else if (!ok) {
            printf("| %s | (cannot load) |\n", names[i]);
        }
        conica_curve_free(&in);
        conica_curve_free(&ref);
    }
    if (!any)
        printf("(no non-convex example)\n");
    fold_table();
    return 0;
}
