/* Benchmarks of the spline plotters (issue 5, seed 004). Prints tables,
 * asserts nothing. Run `build/bench/bench_plot [DATA_DIR]` from the
 * repository root (DATA_DIR defaults to ../shared/data/splines).
 *
 * Table 1: points to reach 0.5 px on a 1000x1000 viewport (tolerance
 *   5e-4 x the control points' box diagonal, as REFERENCE.md section 5)
 *   per method, beside the greedy minimum (longest chords on dense samples,
 *   vertices on the curve) and Wang's formula per Bézier piece.
 * Table 2: time and flops to reach that deviation: guaranteed plotter vs
 *   uniform de Boor sampling at the smallest uniform N that passes, over a
 *   degree sweep, with eq. (3.27)'s operation model for the thesis loop.
 * Table 3: the seven criteria of the adaptive loop (thesis defaults,
 *   delta = 3 px): points, deviation, time, flops. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "conica/plot.h"

#define REL_TOL 5e-4       /* 0.5 px of a 1000 px view */
#define GREEDY_SAMPLES 2000 /* per knot interval, thesis curves */
#define CHECK_SAMPLES 40    /* per chord when measuring a plot */
#define UNIFORM_CHECK_SAMPLES 10 /* per chord of uniform sampling (short chords) */
#define SCAN_MAX 600        /* uniform N scanned on the thesis curves */
#define MIN_TIME 0.02       /* seconds of repetitions per timing */
#define RANDOM_COUNT 20

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double diag_of(const conica_bspline *s)
{
    return conica_plot_extent(s);
}

static void point(const conica_bspline *s, double t, double *out)
{
    if (s->dim == 1) {
        out[0] = t;
        conica_bspline_eval(s, t, out + 1, NULL);
    } else {
        conica_bspline_eval(s, t, out, NULL);
    }
}

static double seg_dist(const double *q, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
    double u = l2 > 0 ? ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2 : 0;
    u = u < 0 ? 0 : (u > 1 ? 1 : u);
    double ex = q[0] - a[0] - u * dx, ey = q[1] - a[1] - u * dy;
    return sqrt(ex * ex + ey * ey);
}

/* Greedy longest chords on dense samples: a chord whose samples are all
 * within tol is within tol both ways (its ends are on the curve). */
static size_t greedy_min(const conica_bspline *s, double tol, size_t per_interval)
{
    size_t p = (size_t)s->degree, m = 0;
    size_t cap = conica_bspline_bezier_count(s) * per_interval + 1;
    double *P = malloc(cap * 2 * sizeof *P);
    for (size_t mu = p; mu < s->n; mu++) {
        double a = s->knots[mu], b = s->knots[mu + 1];
        if (!(a < b))
            continue;
        for (size_t i = 0; i < per_interval; i++)
            point(s, a + (b - a) * (double)i / (double)per_interval, P + 2 * m++);
    }
    point(s, s->knots[s->n], P + 2 * m++);
    size_t count = 1, i = 0;
    while (i + 1 < m) {
        size_t j = i + 1;
        while (j + 1 < m) {
            size_t k = i + 1;
            for (; k <= j; k++)
                if (seg_dist(P + 2 * k, P + 2 * i, P + 2 * (j + 1)) > tol)
                    break;
            if (k <= j)
                break;
            j++;
        }
        count++;
        i = j;
    }
    free(P);
    return count;
}

/* Wang's formula per Bézier piece: n = ceil(sqrt(p(p-1) max|D2 b| / (8 tol))). */
static size_t wang(const conica_bspline *s, double tol)
{
    size_t pieces = conica_bspline_bezier_count(s), total = 1;
    int p = s->degree, d = s->dim;
    double *b = malloc((size_t)(p + 1) * (size_t)d * sizeof *b);
    for (size_t k = 0; k < pieces; k++) {
        double a0, a1, M = 0;
        conica_bspline_bezier_piece(s, k, b, NULL, &a0, &a1, NULL);
        for (int i = 0; i + 2 <= p; i++) {
            double n2 = 0;
            for (int c = 0; c < d; c++) {
                double e = b[(i + 2) * d + c] - 2 * b[(i + 1) * d + c] + b[i * d + c];
                n2 += e * e;
            }
            /* the graph of a function: x is linear, its D2 vanishes */
            M = sqrt(n2) > M ? sqrt(n2) : M;
        }
        double n = ceil(sqrt((double)(p * (p - 1)) * M / (8 * tol)));
        total += n < 1 ? 1 : (size_t)n;
    }
    free(b);
    return total;
}

static conica_plot_settings settings(conica_plot_method m, double tol)
{
    conica_plot_settings set = conica_plot_defaults();
    set.method = m;
    set.abs_tolerance = tol;
    return set;
}

/* Hausdorff deviation (both directions, measured) of a plot. */
static size_t check_samples = CHECK_SAMPLES;
static double deviation(const conica_bspline *s, const conica_polyline *pl)
{
    double c2p = 0, p2c = 0;
    size_t samples = pl->t ? check_samples : 400;
    conica_plot_deviation(s, pl, samples, &c2p, &p2c, NULL);
    return c2p > p2c ? c2p : p2c;
}

static double dev_uniform(const conica_bspline *s, size_t n)
{
    conica_plot_settings set = settings(CONICA_PLOT_UNIFORM, 1);
    set.points = n;
    if (set.max_points < n)
        set.max_points = n;
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_plot(s, &set, &pl, NULL, NULL);
    /* vertices on the curve: the curve-to-chord distance decides (the chord
     * is then within it of the curve too, as in plot_guaranteed.c) */
    double d = 0;
    conica_plot_deviation(s, &pl, UNIFORM_CHECK_SAMPLES, &d, NULL, NULL);
    conica_polyline_free(&pl);
    return d;
}

/* First uniform N that passes, scanning upwards in steps of 2% (uniform
 * sampling is not monotone in N, so no bisection). */
static size_t uniform_pass(const conica_bspline *s, double tol)
{
    size_t n = 2;
    while (n < ((size_t)1 << 22)) {
        if (dev_uniform(s, n) <= tol)
            return n;
        n += n / 50 > 1 ? n / 50 : 1;
    }
    return n;
}

/* Scan N = 2..nmax: the first N that passes and the N from which every
 * larger N up to nmax passes. */
static void uniform_scan(const conica_bspline *s, double tol, size_t nmax, size_t *first,
                         size_t *always)
{
    *first = 0;
    *always = 2;
    for (size_t n = 2; n <= nmax; n++) {
        int pass = dev_uniform(s, n) <= tol;
        if (pass && !*first)
            *first = n;
        if (!pass)
            *always = n + 1;
    }
}

typedef struct run {
    size_t points, knots;
    double dev, seconds, flops;
} run;

static run measure(const conica_bspline *s, const conica_plot_settings *set, int timed)
{
    run r = {0, 0, 0, 0, 0};
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_plot_stats st;
    if (conica_plot(s, set, &pl, &st, NULL) != CONICA_OK)
        return r;
    r.points = pl.n;
    r.knots = st.knots_inserted;
    r.flops = st.flops;
    r.dev = deviation(s, &pl);
    if (timed) { /* best of 3 rounds of at least MIN_TIME (a loaded machine) */
        r.seconds = INFINITY;
        for (int round = 0; round < 3; round++) {
            size_t reps = 0;
            double t0 = now(), t;
            do {
                conica_plot(s, set, &pl, NULL, NULL);
                reps++;
                t = now() - t0;
            } while (t < MIN_TIME);
            r.seconds = t / (double)reps < r.seconds ? t / (double)reps : r.seconds;
        }
    }
    conica_polyline_free(&pl);
    return r;
}

static int load(const char *dir, const char *name, conica_bspline *s)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s.spl", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    static char buf[1 << 16];
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    return conica_bspline_parse(buf, len, s, NULL) == CONICA_OK;
}

/* xorshift for the random set (fixed seed) */
static unsigned long long rng_state = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

/* The thesis's random regime; n_max bounds the size, p_fixed > 0 fixes p. */
static void random_spline(size_t n_max, int p_fixed, size_t n_fixed, int dim, conica_bspline *s)
{
    size_t n = n_fixed ? n_fixed : 3 + (size_t)(urand() * (double)(n_max - 2));
    int p = p_fixed ? p_fixed : 2 + (int)(urand() * 29);
    if ((size_t)p > n - 1)
        p = (int)n - 1;
    size_t nk = n + (size_t)p + 1;
    double *k = malloc(nk * sizeof *k), *c = malloc(n * (size_t)dim * sizeof *c);
    for (size_t i = 0; i <= (size_t)p; i++) {
        k[i] = 0;
        k[nk - 1 - i] = 10;
    }
    for (size_t i = (size_t)p + 1; i < n; i++)
        k[i] = 10 * urand();
    for (size_t a = (size_t)p + 1; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
            if (k[b] < k[a]) {
                double t = k[a];
                k[a] = k[b];
                k[b] = t;
            }
    for (size_t i = 0; i < n * (size_t)dim; i++)
        c[i] = 10 * urand();
    conica_bspline_init(s);
    conica_bspline_set(p, dim, k, nk, c, n, NULL, s, NULL);
    free(k);
    free(c);
}

static void table1_row(const char *name, const conica_bspline *s, size_t per_interval,
                       size_t *sum)
{
    double tol = REL_TOL * diag_of(s);
    size_t gmin = greedy_min(s, tol, per_interval);
    size_t uni, uni_always;
    uniform_scan(s, tol, SCAN_MAX, &uni, &uni_always);
    double fn = dev_uniform(s, 101) / tol;
    size_t w = wang(s, tol);
    conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
    run rg = measure(s, &g, 0);
    conica_plot_settings a = conica_plot_defaults(); /* thesis loop, 3 px */
    a.method = CONICA_PLOT_ADAPTIVE;
    run ra = measure(s, &a, 0);
    conica_plot_settings mm = settings(CONICA_PLOT_MATHEMATICA, tol);
    run rm = measure(s, &mm, 0);
    printf("| %-9s | %2d | %6zu | %6zu (%.2fx) | %4zu / %4zu | %6.2f | %6zu | %5zu, %6.1f | "
           "%5zu, %5.2f |\n",
           name, s->degree, gmin, rg.points, (double)rg.points / (double)gmin, uni, uni_always,
           fn, w, ra.points, ra.dev / tol, rm.points, rm.dev / tol);
    if (sum) {
        sum[0] += gmin;
        sum[1] += rg.points;
        sum[2] += uni;
        sum[3] += w;
        sum[4] += ra.points;
        sum[5] += rm.points;
    }
    (void)rg;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "../shared/data/splines";
    setvbuf(stdout, NULL, _IOLBF, 0);
    const char *names[] = {"sptest1", "sptest2", "sptest3", "sptest4"};
    conica_bspline s;
    conica_bspline_init(&s);
    int have = 1;
    for (int i = 0; i < 4; i++)
        if (!load(dir, names[i], &s))
            have = 0;
    if (!have)
        printf("(thesis curves not found in %s: their rows are skipped)\n\n", dir);

    printf("Table 1: points for a max deviation of 0.5 px on 1000x1000 (tol = %g x diagonal)\n\n",
           REL_TOL);
    printf("| curve     |  p | greedy | guaranteed (x min) | uniform N: first / all from | "
           "fnplt N=101 dev/tol | "
           "Wang | thesis loop (3 px): pts, dev/tol | mathematica: pts, dev/tol |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    if (have)
        for (int i = 0; i < 4; i++) {
            load(dir, names[i], &s);
            table1_row(names[i], &s, GREEDY_SAMPLES, NULL);
        }
    size_t sum[6] = {0, 0, 0, 0, 0, 0};
    rng_state = 0x9E3779B97F4A7C15ull;
    for (int r = 0; r < RANDOM_COUNT; r++) {
        conica_bspline_free(&s);
        random_spline(60, 0, 0, 1 + r % 2, &s);
        double tol = REL_TOL * diag_of(&s);
        size_t gmin = greedy_min(&s, tol, 64);
        conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
        run rg = measure(&s, &g, 0);
        size_t uni = uniform_pass(&s, tol);
        size_t w = wang(&s, tol);
        sum[0] += gmin;
        sum[1] += rg.points;
        sum[2] += uni;
        sum[3] += w;
    }
    printf("| random x%d (sums) | 2-30 | %zu | %zu (%.2fx) | %zu (first pass) | - | %zu | - | - |\n\n",
           RANDOM_COUNT, sum[0], sum[1], (double)sum[1] / (double)sum[0], sum[2], sum[3]);

    printf("Table 2: time to reach 0.5 px: guaranteed vs uniform de Boor at the smallest\n"
           "passing N (random planar curves, n = p + 6, 5 per degree; flops per point;\n"
           "eq. (1.14) R(p) = 3/2 p(p+1) per dimension for evaluation, eq. (3.27)\n"
           "R = 53pK/(N0+K) for the thesis loop with the base line criterion)\n\n");
    printf("| p | uniform N | uniform us | guaranteed pts | guaranteed us | speed-up | "
           "uniform flops/pt | guaranteed flops/pt | thesis loop flops/pt (eq. 3.27 model) |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    const int degrees[] = {2, 3, 5, 8, 12, 16, 20, 25, 30};
    for (int di = 0; di < 9; di++) {
        int p = degrees[di];
        double tu = 0, tg = 0, fu = 0, fg = 0, fa = 0, fmodel = 0;
        size_t nu = 0, ng = 0, na = 0;
        for (int r = 0; r < 5; r++) {
            conica_bspline_free(&s);
            random_spline(0, p, (size_t)p + 6, 2, &s);
            double tol = REL_TOL * diag_of(&s);
            size_t N = uniform_pass(&s, tol);
            conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
            u.points = N;
            run ru = measure(&s, &u, 1);
            conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
            run rg = measure(&s, &g, 1);
            conica_plot_settings a = settings(CONICA_PLOT_ADAPTIVE, tol);
            a.criterion = CONICA_CRIT_BASE_LINE;
            run ra = measure(&s, &a, 0);
            tu += ru.seconds;
            tg += rg.seconds;
            fu += ru.flops;
            fg += rg.flops;
            fa += ra.flops;
            nu += ru.points;
            ng += rg.points;
            na += ra.points;
            fmodel += 53.0 * p * (double)ra.knots / (double)(s.n + ra.knots) * (double)ra.points;
        }
        printf("| %2d | %5.0f | %8.1f | %5.0f | %8.1f | %5.2fx | %7.0f | %7.0f | %7.0f (%.0f) |\n", p,
               (double)nu / 5.0, tu / 5 * 1e6, (double)ng / 5.0, tg / 5 * 1e6, tu / tg, fu / (double)nu,
               fg / (double)ng, fa / (double)na, fmodel / (double)na);
    }

    if (have) {
        printf("\nTable 2b: the same on the thesis curves, uniform at its first passing N and at\n"
               "the N from which every larger N passes\n\n");
        printf("| curve | p | guaranteed pts, us, flops | uniform first N: us, flops | "
               "uniform all-from N: us, flops | speed-up (first / all-from) |\n");
        printf("|---|---|---|---|---|---|\n");
        for (int i = 0; i < 4; i++) {
            load(dir, names[i], &s);
            double tol = REL_TOL * diag_of(&s);
            size_t first, always;
            uniform_scan(&s, tol, SCAN_MAX, &first, &always);
            conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
            run rg = measure(&s, &g, 1);
            conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
            u.points = first;
            run r1 = measure(&s, &u, 1);
            u.points = always;
            run r2 = measure(&s, &u, 1);
            printf("| %s | %d | %zu, %.1f, %.0f | %zu: %.1f, %.0f | %zu: %.1f, %.0f | %.2fx / %.2fx |\n",
                   names[i], s.degree, rg.points, rg.seconds * 1e6, rg.flops, first,
                   r1.seconds * 1e6, r1.flops, always, r2.seconds * 1e6, r2.flops,
                   r1.seconds / rg.seconds, r2.seconds / rg.seconds);
        }
    }

    printf("\nTable 3: the seven criteria of the adaptive loop (thesis defaults: delta = 3 px\n"
           "on 1000x1000, R = 0.5, movement stop skip 1 consec 5, budget 500); points, measured\n"
           "deviation of the control polygon in units of 0.5 px, time, flops\n\n");
    printf("| criterion | sptest1 | sptest2 | sptest3 | sptest4 | random x%d: pts, us |\n",
           RANDOM_COUNT / 4);
    printf("|---|---|---|---|---|---|\n");
    for (int c = 0; c < CONICA_CRIT_COUNT_; c++) {
        printf("| %-18s |", conica_plot_criterion_name((conica_plot_criterion)c));
        for (int i = 0; i < 4; i++) {
            if (!have) {
                printf(" - |");
                continue;
            }
            load(dir, names[i], &s);
            conica_plot_settings a = conica_plot_defaults();
            a.method = CONICA_PLOT_ADAPTIVE;
            a.criterion = (conica_plot_criterion)c;
            run ra = measure(&s, &a, 1);
            printf(" %zu pts, %.1f, %.0f us |", ra.points, ra.dev / (REL_TOL * diag_of(&s)),
                   ra.seconds * 1e6);
        }
        rng_state = 12345;
        size_t pts = 0;
        double us = 0;
        for (int r = 0; r < RANDOM_COUNT / 4; r++) {
            conica_bspline_free(&s);
            random_spline(60, 0, 0, 2, &s);
            conica_plot_settings a = conica_plot_defaults();
            a.method = CONICA_PLOT_ADAPTIVE;
            a.criterion = (conica_plot_criterion)c;
            run ra = measure(&s, &a, 1);
            pts += ra.points;
            us += ra.seconds * 1e6;
        }
        printf(" %zu, %.0f |\n", pts, us);
    }
    conica_bspline_free(&s);
    return 0;
}
