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
 * their edges' normals (where the tangles are). A benchmark: prints figures, asserts nothing (the fairness
 * test, tests/test_fairness.c, asserts the bounds).
 *
 * usage: bench_fairness [DATA_DIR] */
#include <dirent.h>
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
            printf("notice: %s absent (set CONICA_SHARED_DATA or pass DATA_DIR): skipped\n", path);
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
    return 0;
}
