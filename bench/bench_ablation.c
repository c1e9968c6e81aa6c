/* SPDX-License-Identifier: MIT */
/* The numerics ablation of CONIS §3.2 (Table 1, Figures 3-6), as
 * run-time settings of the one implementation (plotsvg_variant):
 *   BASE      double, normals normalised every level, plain quadratic formula
 *   NORM_SKIP no normalisation, plain quadratic formula
 *   FINAL     our defaults (no normalisation, Kahan/FMA root, local frames)
 *   PRECISE   FINAL in long double
 * each in our local frames and in the reference's (absolute coordinates and
 * weighted SVD, reference_compatible), where the CONIS paper measured it.
 * Prints E, E_max (eqs. (13)-(14)) at k = 4, 8, 12 on the four conics of
 * Table 1 (samples as REFERENCE.md section 1), then the normal angle error
 * and the comb roughness at k = 10 on a non-convex example of the reference
 * (conis/input/example9.txt of the shared data, found as the tests find it:
 * $CONICA_SHARED_DATA, else ../shared/data from the working directory, else
 * ../shared/data next to the repository holding this executable; skipped
 * with a notice naming every place tried when absent), and with --svg FILE
 * draws the four combs at k = 10 side by side (Figure 6).
 * A benchmark: prints figures, asserts nothing.
 *
 * usage: bench_ablation [--svg OUT.svg] [--example FILE] */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "conica/curve.h"
#include "conica/subdiv.h"
#include "plotsvg.h"

#define NVAR 4
/* Every variant runs twice: in our local frames (the default) and with
 * reference_compatible (absolute coordinates + weighted SVD, as the CONIS paper's
 * implementation, where its ablation was measured). */
#define NFRAME 2
#define NRUN (NVAR * NFRAME)
#define COMB_LEVEL 10
/* The example inside the shared data directory. */
#define EXAMPLE_REL "conis/input/example9.txt"
/* From the executable (BUILD/bench/bench_ablation with BUILD = REPO/build)
 * to the shared data next to the repository. */
#define EXE_TO_DATA "/../../../shared/data"

static const char *const var_name[NVAR] = {"base", "norm-skip", "final", "precise"};
static const char *const var_label[NVAR] = {"BASE", "NORM_SKIP", "FINAL", "PRECISE"};
static const char *const frame_label[NFRAME] = {"local", "reference"};
static const int levels[3] = {4, 8, 12};

static void run_settings(int r, conica_subdiv_settings *s)
{
    *s = conica_subdiv_defaults();
    plotsvg_variant(var_name[r % NVAR], s);
    s->reference_compatible = r / NVAR;
}

struct conic_case {
    const char *name;
    plotsvg_conic q;
    int closed;
    double xy[12], nxy[12];
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Exact point-normal samples of REFERENCE.md section 1: 6 per conic;
 * normals = normalised gradient of f (eq. (3)). */
static void make_cases(struct conic_case c[4])
{
    const double pi = 3.14159265358979323846;
    c[0] = (struct conic_case){"x^2+y^2=25", {1, 1, 0, 0, 0, -25}, 1, {0}, {0}};
    c[1] = (struct conic_case){"4x^2+9y^2=36", {4, 9, 0, 0, 0, -36}, 1, {0}, {0}};
    c[2] = (struct conic_case){"y^2-4x^2=4", {-4, 1, 0, 0, 0, -4}, 0, {0}, {0}};
    c[3] = (struct conic_case){"y=x^2", {1, 0, 0, 0, -0.5, 0}, 0, {0}, {0}};
    for (int i = 0; i < 6; i++) {
        double t = 2.0 * pi * i / 6.0, x;
        /* circle */
        c[0].xy[2 * i] = 5.0 * cos(t);
        c[0].xy[2 * i + 1] = 5.0 * sin(t);
        /* ellipse x = 3 cos t, y = 2 sin t */
        c[1].xy[2 * i] = 3.0 * cos(t);
        c[1].xy[2 * i + 1] = 2.0 * sin(t);
        /* hyperbola, upper branch, x = -4 + 8i/5 */
        x = -4.0 + 8.0 * i / 5.0;
        c[2].xy[2 * i] = x;
        c[2].xy[2 * i + 1] = sqrt(4.0 + 4.0 * x * x);
        /* parabola, x = -4 + 8i/6 */
        x = -4.0 + 8.0 * i / 6.0;
        c[3].xy[2 * i] = x;
        c[3].xy[2 * i + 1] = x * x;
    }
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 6; i++) {
            const plotsvg_conic *q = &c[k].q;
            double x = c[k].xy[2 * i], y = c[k].xy[2 * i + 1];
            double gx = q->q20 * x + q->q11 * y + q->q10, gy = q->q11 * x + q->q02 * y + q->q01;
            double g = hypot(gx, gy);
            c[k].nxy[2 * i] = gx / g;
            c[k].nxy[2 * i + 1] = gy / g;
        }
}

static void conic_table(void)
{
    struct conic_case c[4];
    make_cases(c);
    printf("Conic reproduction (CONIS, Table 1 setting: 6 exact point-normal samples),\n"
           "E / E_max of eqs. (13)-(14) per variant:\n\n");
    printf("| conic | variant | frame | E k=4 | E_max k=4 | E k=8 | E_max k=8 | E k=12 "
           "| E_max k=12 | s (k=12) |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < 4; k++) {
        conica_curve in;
        conica_curve_init(&in);
        if (conica_curve_set(c[k].xy, c[k].nxy, 6, c[k].closed, &in, NULL) != CONICA_OK) {
            printf("| %s | (cannot build input) |\n", c[k].name);
            continue;
        }
        for (int r = 0; r < NRUN; r++) {
            conica_subdiv_settings s;
            double t = 0.0;
            printf("| %s | %s | %s |", c[k].name, var_label[r % NVAR], frame_label[r / NVAR]);
            run_settings(r, &s);
            for (int l = 0; l < 3; l++) {
                plotsvg_errors e;
                conica_status st;
                double t0 = now();
                s.levels = levels[l];
                if (plotsvg_measure(&in, &s, &c[k].q, &e, &st) != CONICA_OK)
                    printf(" failed: %s | |", st.message);
                else
                    printf(" %.2e | %.2e |", e.e_mean, e.e_max);
                t = now() - t0;
            }
            printf(" %.4f |\n", t);
        }
        conica_curve_free(&in);
    }
    printf("\n");
}

/* Normal errors, comb roughness and the k = 10 combs on a non-convex shape. */
static void example(const char *path, const char *svg)
{
    conica_curve in, out[NRUN];
    double *kappa[NRUN] = {0}, *tips[NRUN] = {0};
    double scale = 0.0, maxlen = 0.0;
    FILE *probe = fopen(path, "rb");
    if (!probe) {
        printf("non-convex example: notice: %s absent, skipped\n", path);
        fprintf(stderr, "bench_ablation: notice: %s absent: non-convex example skipped\n", path);
        return;
    }
    fclose(probe);
    conica_curve_init(&in);
    for (int v = 0; v < NRUN; v++)
        conica_curve_init(&out[v]);
    if (plotsvg_load_curve("bench_ablation", path, 1, &in))
        return;
    printf("Non-convex example %s (%zu points, %s normals): normal angle error (degrees)\n"
           "and comb noise (median |second difference of curvature| / median curvature)\n"
           "at k = %d:\n\n",
           path, in.n, in.nxy ? "given" : "estimated", COMB_LEVEL);
    printf("| variant | frame | normal mean k=4 | max k=4 | mean k=8 | max k=8 | mean k=12 "
           "| max k=12 | comb noise k=%d |\n|---|---|---|---|---|---|---|---|---|\n", COMB_LEVEL);
    for (int v = 0; v < NRUN; v++) {
        conica_subdiv_settings s;
        conica_status st;
        run_settings(v, &s);
        printf("| %s | %s |", var_label[v % NVAR], frame_label[v / NVAR]);
        for (int l = 0; l < 3; l++) {
            plotsvg_errors e;
            s.levels = levels[l];
            if (plotsvg_measure(&in, &s, NULL, &e, &st) != CONICA_OK)
                printf(" failed: %s | |", st.message);
            else
                printf(" %.2e | %.2e |", e.n_mean, e.n_max);
        }
        s.levels = COMB_LEVEL;
        /* the comb from the double points (long double results rounded) */
        if (conica_subdivide(&in, &s, &out[v], NULL, &st) != CONICA_OK || !out[v].nxy) {
            printf(" failed |\n");
            continue;
        }
        kappa[v] = malloc(out[v].n * sizeof(double));
        tips[v] = malloc(2 * out[v].n * sizeof(double));
        if (!kappa[v] || !tips[v]) {
            printf(" out of memory |\n");
            continue;
        }
        plotsvg_curvatures(out[v].xy, out[v].nxy, out[v].n, 1, 0, kappa[v]);
        printf(" %.3g |\n", plotsvg_comb_roughness(kappa[v], out[v].n, 1, tips[v]));
    }
    printf("\n");
    /* how far each variant's curve is from FINAL's, at the comb level */
    if (out[2].n) {
        double size = plotsvg_size(out[2].xy, out[2].n);
        printf("max distance of each variant's k = %d points from FINAL's, / curve size:", COMB_LEVEL);
        for (int v = 0; v < NRUN; v++) {
            double d = 0.0;
            if (out[v].n != out[2].n) {
                printf(" %s/%s n/a;", var_label[v % NVAR], frame_label[v / NVAR]);
                continue;
            }
            for (size_t i = 0; i < out[v].n; i++)
                d = fmax(d, hypot(out[v].xy[2 * i] - out[2].xy[2 * i],
                                  out[v].xy[2 * i + 1] - out[2].xy[2 * i + 1]));
            printf(" %s/%s %.2e;", var_label[v % NVAR], frame_label[v / NVAR], d / size);
        }
        printf("\n\n");
    }
    /* one scale for all panels, FINAL's auto scale, so the combs compare */
    if (kappa[2] && tips[2])
        scale = plotsvg_comb_scale(kappa[2], out[2].n, plotsvg_size(out[2].xy, out[2].n), tips[2],
                                   &maxlen);
    if (svg && kappa[2]) {
        cli_output o;
        const double w = 450.0, h = 450.0;
        if (cli_output_open("bench_ablation", svg, &o) == 0) {
            plotsvg_begin(o.f, NVAR * w, NFRAME * h, "curvature combs at k = 10 per variant");
            for (int v = 0; v < NRUN; v++) {
                char title[96];
                if (!kappa[v] || !tips[v])
                    continue;
                plotsvg_comb_tips(out[v].xy, out[v].nxy, kappa[v], out[v].n, scale, maxlen,
                                  tips[v]);
                snprintf(title, sizeof title, "%s, %s frame, k = %d", var_label[v % NVAR],
                         frame_label[v / NVAR], COMB_LEVEL);
                plotsvg_comb_panel(o.f, w * (v % NVAR), h * (v / NVAR), w, h, &in, &out[v],
                                   tips[v], PLOTSVG_DEFAULT_MAX_TEETH, title);
            }
            plotsvg_end(o.f);
            if (cli_output_commit("bench_ablation", &o) == 0)
                printf("combs at k = %d written to %s\n\n", COMB_LEVEL, svg);
            else
                cli_output_abort(&o);
        }
    }
    for (int v = 0; v < NRUN; v++) {
        free(kappa[v]);
        free(tips[v]);
        conica_curve_free(&out[v]);
    }
    conica_curve_free(&in);
}

static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

#define NPLACES 3
#define PLACE_MAX (PATH_MAX + 64)

/* The places the shared data's example may be (see the header comment)
 * into tried[]; returns the index of the first that exists, or -1 after a
 * notice on stderr naming them all. */
static int find_example(char tried[NPLACES][PLACE_MAX])
{
    char exe[PATH_MAX];
    const char *env = getenv("CONICA_SHARED_DATA");
    int nt = 0;
    if (env && env[0])
        snprintf(tried[nt++], PLACE_MAX, "%s/%s", env, EXAMPLE_REL);
    snprintf(tried[nt++], PLACE_MAX, "../shared/data/%s", EXAMPLE_REL);
    {
        ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
        char *slash;
        if (len > 0) {
            exe[len] = '\0';
            if ((slash = strrchr(exe, '/')) != NULL) {
                *slash = '\0';
                snprintf(tried[nt++], PLACE_MAX, "%s%s/%s", exe, EXE_TO_DATA, EXAMPLE_REL);
            }
        }
    }
    for (int i = 0; i < nt; i++)
        if (is_file(tried[i]))
            return i;
    fprintf(stderr, "bench_ablation: notice: the shared data's %s was not found (tried:",
            EXAMPLE_REL);
    for (int i = 0; i < nt; i++)
        fprintf(stderr, " %s", tried[i]);
    fprintf(stderr, "); set CONICA_SHARED_DATA or pass --example FILE\n");
    return -1;
}

int main(int argc, char **argv)
{
    const char *svg = NULL;
    const char *ex = NULL;
    char places[NPLACES][PLACE_MAX];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--svg") && i + 1 < argc)
            svg = argv[++i];
        else if (!strcmp(argv[i], "--example") && i + 1 < argc)
            ex = argv[++i];
        else {
            fprintf(stderr, "usage: bench_ablation [--svg OUT.svg] [--example FILE]\n");
            return 2;
        }
    }
    if (!ex) {
        int k = find_example(places);
        ex = places[k < 0 ? 0 : k];
    }
    conic_table();
    example(ex, svg);
    return 0;
}
