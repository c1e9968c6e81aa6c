/* SPDX-License-Identifier: MIT */
/* Benchmarks of the spline plotters (issue 5, Dahl 2019). Prints tables,
 * asserts nothing. Run `build/bench/bench_plot [--rounds R] [--table T]
 * [DATA_DIR]` from the repository root (DATA_DIR defaults to
 * ../shared/data/splines; T is 1, 2, 2b, 2c or 3 to print one table, all by
 * default; R is the number of rounds of Table 2c, 7 by default).
 *
 * Table 1: points to reach 0.5 px on a 1000x1000 viewport (tolerance
 *   5e-4 x the control points' box diagonal, as REFERENCE.md section 5)
 *   per method, beside the greedy minimum (longest chords on dense samples,
 *   vertices on the curve) and Wang's formula per Bézier piece.
 * Table 2: time and flops to reach that deviation: guaranteed plotter vs
 *   uniform de Boor sampling at the smallest uniform N that passes, over a
 *   degree sweep, with eq. (3.27)'s operation model for the thesis loop.
 * Table 2c: the comparison of Tables 2 and 2b in CPU time
 *   (CLOCK_PROCESS_CPUTIME_ID, which a loaded host disturbs less than wall
 *   time), the two methods alternating within each round, best of R
 *   rounds: the figures the README's time goals are judged on.
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
#define MIN_CPU_TIME 0.01   /* CPU seconds of repetitions per Table 2c timing */
#define ROUNDS_DEFAULT 7    /* alternating rounds of Table 2c */
#define RANDOM_COUNT 20
#define DEGREE_COUNT 9      /* degrees of Tables 2 and 2c */
#define PER_DEGREE 5        /* random curves per degree */
#define SEED 0x9E3779B97F4A7C15ull

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
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
static unsigned long long rng_state = SEED;
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

static const int degrees[DEGREE_COUNT] = {2, 3, 5, 8, 12, 16, 20, 25, 30};
static const char *const names[4] = {"sptest1", "sptest2", "sptest3", "sptest4"};

/* The thesis curves and their uniform scans (done once for Tables 1, 2b
 * and 2c). */
typedef struct thesis {
    int have;
    conica_bspline s[4];
    size_t first[4], always[4];
} thesis;

/* Table 2's random set: PER_DEGREE planar curves per degree, n = p + 6,
 * drawn from SEED after Table 1's RANDOM_COUNT curves (so every table sees
 * the same curves whichever tables run), with the first uniform N that
 * passes (uniform_pass). */
typedef struct rset {
    conica_bspline s[DEGREE_COUNT][PER_DEGREE];
    size_t N[DEGREE_COUNT][PER_DEGREE];
} rset;

static void rset_make(rset *rs)
{
    conica_bspline skip;
    conica_bspline_init(&skip);
    rng_state = SEED;
    for (int r = 0; r < RANDOM_COUNT; r++) {
        random_spline(60, 0, 0, 1 + r % 2, &skip);
        conica_bspline_free(&skip);
    }
    for (int di = 0; di < DEGREE_COUNT; di++)
        for (int r = 0; r < PER_DEGREE; r++) {
            conica_bspline *s = &rs->s[di][r];
            random_spline(0, degrees[di], (size_t)degrees[di] + 6, 2, s);
            rs->N[di][r] = uniform_pass(s, REL_TOL * diag_of(s));
        }
}

static void table1_row(const char *name, const conica_bspline *s, size_t per_interval,
                       size_t uni, size_t uni_always)
{
    double tol = REL_TOL * diag_of(s);
    size_t gmin = greedy_min(s, tol, per_interval);
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
}

static void table1(const thesis *th)
{
    printf("Table 1: points for a max deviation of 0.5 px on 1000x1000 (tol = %g x diagonal)\n\n",
           REL_TOL);
    printf("| curve     |  p | greedy | guaranteed (x min) | uniform N: first / all from | "
           "fnplt N=101 dev/tol | "
           "Wang | thesis loop (3 px): pts, dev/tol | mathematica: pts, dev/tol |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    if (th->have)
        for (int i = 0; i < 4; i++)
            table1_row(names[i], &th->s[i], GREEDY_SAMPLES, th->first[i], th->always[i]);
    size_t sum[4] = {0, 0, 0, 0};
    conica_bspline s;
    conica_bspline_init(&s);
    rng_state = SEED;
    for (int r = 0; r < RANDOM_COUNT; r++) {
        random_spline(60, 0, 0, 1 + r % 2, &s);
        double tol = REL_TOL * diag_of(&s);
        conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
        run rg = measure(&s, &g, 0);
        sum[0] += greedy_min(&s, tol, 64);
        sum[1] += rg.points;
        sum[2] += uniform_pass(&s, tol);
        sum[3] += wang(&s, tol);
        conica_bspline_free(&s);
    }
    printf("| random x%d (sums) | 2-30 | %zu | %zu (%.2fx) | %zu (first pass) | - | %zu | - | "
           "- |\n\n",
           RANDOM_COUNT, sum[0], sum[1], (double)sum[1] / (double)sum[0], sum[2], sum[3]);
}

static void table2(const rset *rs)
{
    printf("Table 2: time to reach 0.5 px: guaranteed vs uniform de Boor at the smallest\n"
           "passing N (random planar curves, n = p + 6, %d per degree; flops per point;\n"
           "eq. (1.14) R(p) = 3/2 p(p+1) per dimension for evaluation, eq. (3.27)\n"
           "R = 53pK/(N0+K) for the thesis loop with the base line criterion)\n\n",
           PER_DEGREE);
    printf("| p | uniform N | uniform us | guaranteed pts | guaranteed us | speed-up | "
           "uniform flops/pt | guaranteed flops/pt | thesis loop flops/pt (eq. 3.27 model) |\n");
    printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int di = 0; di < DEGREE_COUNT; di++) {
        int p = degrees[di];
        double tu = 0, tg = 0, fu = 0, fg = 0, fa = 0, fmodel = 0;
        size_t nu = 0, ng = 0, na = 0;
        for (int r = 0; r < PER_DEGREE; r++) {
            const conica_bspline *s = &rs->s[di][r];
            double tol = REL_TOL * diag_of(s);
            conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
            u.points = rs->N[di][r];
            run ru = measure(s, &u, 1);
            conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
            run rg = measure(s, &g, 1);
            conica_plot_settings a = settings(CONICA_PLOT_ADAPTIVE, tol);
            a.criterion = CONICA_CRIT_BASE_LINE;
            run ra = measure(s, &a, 0);
            tu += ru.seconds;
            tg += rg.seconds;
            fu += ru.flops;
            fg += rg.flops;
            fa += ra.flops;
            nu += ru.points;
            ng += rg.points;
            na += ra.points;
            fmodel += 53.0 * p * (double)ra.knots / (double)(s->n + ra.knots) * (double)ra.points;
        }
        printf("| %2d | %5.0f | %8.1f | %5.0f | %8.1f | %5.2fx | %7.0f | %7.0f | %7.0f (%.0f) |\n",
               p,
               (double)nu / PER_DEGREE, tu / PER_DEGREE * 1e6, (double)ng / PER_DEGREE,
               tg / PER_DEGREE * 1e6, tu / tg, fu / (double)nu, fg / (double)ng,
               fa / (double)na, fmodel / (double)na);
    }
}

static void table2b(const thesis *th)
{
    printf("\nTable 2b: the same on the thesis curves, uniform at its first passing N and at\n"
           "the N from which every larger N passes\n\n");
    printf("| curve | p | guaranteed pts, us, flops | uniform first N: us, flops | "
           "uniform all-from N: us, flops | speed-up (first / all-from) |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int i = 0; i < 4; i++) {
        const conica_bspline *s = &th->s[i];
        double tol = REL_TOL * diag_of(s);
        conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
        run rg = measure(s, &g, 1);
        conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
        u.points = th->first[i];
        run r1 = measure(s, &u, 1);
        u.points = th->always[i];
        run r2 = measure(s, &u, 1);
        printf("| %s | %d | %zu, %.1f, %.0f | %zu: %.1f, %.0f | %zu: %.1f, %.0f | "
               "%.2fx / %.2fx |\n",
               names[i], s->degree, rg.points, rg.seconds * 1e6, rg.flops, th->first[i],
               r1.seconds * 1e6, r1.flops, th->always[i], r2.seconds * 1e6, r2.flops,
               r1.seconds / rg.seconds, r2.seconds / rg.seconds);
    }
}

/* CPU seconds per plot, repeating the plot for at least MIN_CPU_TIME. */
static double cpu_per_plot(const conica_bspline *s, const conica_plot_settings *set,
                           conica_polyline *pl)
{
    size_t reps = 0;
    double t0 = cpu_now(), t;
    do {
        conica_plot(s, set, pl, NULL, NULL);
        reps++;
        t = cpu_now() - t0;
    } while (t < MIN_CPU_TIME);
    return t / (double)reps;
}

/* One Table 2c entry: a curve with the uniform N it is compared at, and
 * the best CPU time per plot of each method over the rounds. */
typedef struct cpu_entry {
    const conica_bspline *s;
    size_t N;
    double tg, tu;
} cpu_entry;

/* Counts of one guaranteed and one uniform plot of an entry. */
typedef struct cpu_counts {
    size_t points;
    double trials, flops_g, flops_u;
} cpu_counts;

static cpu_counts counts_of(const cpu_entry *e)
{
    cpu_counts c = {0, 0, 0, 0};
    double tol = REL_TOL * diag_of(e->s);
    conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
    conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
    u.points = e->N;
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_plot_stats st;
    if (conica_plot(e->s, &g, &pl, &st, NULL) == CONICA_OK) {
        c.points = pl.n;
        c.trials = (double)st.iterations;
        c.flops_g = st.flops;
    }
    if (conica_plot(e->s, &u, &pl, &st, NULL) == CONICA_OK)
        c.flops_u = st.flops;
    conica_polyline_free(&pl);
    return c;
}

static void table2c(const thesis *th, const rset *rs, int rounds)
{
    enum { MAX_ENTRIES = 4 + DEGREE_COUNT * PER_DEGREE };
    cpu_entry e[MAX_ENTRIES];
    size_t ne = 0;
    if (th->have)
        for (int i = 0; i < 4; i++)
            e[ne++] = (cpu_entry){&th->s[i], th->always[i], INFINITY, INFINITY};
    size_t first_random = ne;
    for (int di = 0; di < DEGREE_COUNT; di++)
        for (int r = 0; r < PER_DEGREE; r++)
            e[ne++] = (cpu_entry){&rs->s[di][r], rs->N[di][r], INFINITY, INFINITY};
    /* Rounds over all curves; within a round each curve is timed with both
     * methods back to back (the order swapped every round), so a change
     * of the host's load hits both; the best round of each is kept. */
    conica_polyline pl;
    conica_polyline_init(&pl);
    for (int round = 0; round < rounds; round++)
        for (size_t i = 0; i < ne; i++) {
            double tol = REL_TOL * diag_of(e[i].s);
            conica_plot_settings g = settings(CONICA_PLOT_GUARANTEED, tol);
            conica_plot_settings u = settings(CONICA_PLOT_UNIFORM, tol);
            u.points = e[i].N;
            double t1, t2;
            if (round % 2 == 0) {
                t1 = cpu_per_plot(e[i].s, &g, &pl);
                t2 = cpu_per_plot(e[i].s, &u, &pl);
            } else {
                t2 = cpu_per_plot(e[i].s, &u, &pl);
                t1 = cpu_per_plot(e[i].s, &g, &pl);
            }
            e[i].tg = t1 < e[i].tg ? t1 : e[i].tg;
            e[i].tu = t2 < e[i].tu ? t2 : e[i].tu;
        }
    conica_polyline_free(&pl);

    printf("\nTable 2c: CPU time per plot (CLOCK_PROCESS_CPUTIME_ID), best of %d alternating\n"
           "rounds (each timing repeats the plot for >= %g ms): guaranteed vs uniform de Boor\n"
           "at the N uniform needs reliably -- on the thesis curves the N from which every\n"
           "larger N up to %d passes, on the random set of Table 2 its first passing N\n"
           "(2%% steps; %d curves per degree: means per curve, speed-up = total uniform\n"
           "time / total guaranteed time, per-curve range in brackets)\n\n",
           rounds, MIN_CPU_TIME * 1e3, SCAN_MAX, PER_DEGREE);
    printf("| curve | p | guaranteed pts | trials/pt | uniform N | guaranteed us | uniform us | "
           "speed-up | guaranteed flops/pt | uniform flops/pt |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t i = 0; i < first_random; i++) {
        cpu_counts c = counts_of(&e[i]);
        printf("| %s | %d | %zu | %.2f | %zu (all from) | %.2f | %.2f | **%.2fx** | %.0f | "
               "%.0f |\n",
               names[i], e[i].s->degree, c.points, c.trials / (double)c.points, e[i].N,
               e[i].tg * 1e6, e[i].tu * 1e6, e[i].tu / e[i].tg, c.flops_g / (double)c.points,
               c.flops_u / (double)e[i].N);
    }
    for (int di = 0; di < DEGREE_COUNT; di++) {
        double tg = 0, tu = 0, trials = 0, fg = 0, fu = 0, lo = INFINITY, hi = 0;
        size_t pts = 0, nu = 0;
        for (int r = 0; r < PER_DEGREE; r++) {
            const cpu_entry *x = &e[first_random + (size_t)(di * PER_DEGREE + r)];
            cpu_counts c = counts_of(x);
            double ratio = x->tu / x->tg;
            tg += x->tg;
            tu += x->tu;
            pts += c.points;
            nu += x->N;
            trials += c.trials;
            fg += c.flops_g;
            fu += c.flops_u;
            lo = ratio < lo ? ratio : lo;
            hi = ratio > hi ? ratio : hi;
        }
        printf("| random p=%d x%d | %d | %.0f | %.2f | %.0f (first) | %.2f | %.2f | "
               "**%.2fx** (%.2f-%.2f) | %.0f | %.0f |\n",
               degrees[di], PER_DEGREE, degrees[di], (double)pts / PER_DEGREE,
               trials / (double)pts, (double)nu / PER_DEGREE, tg / PER_DEGREE * 1e6,
               tu / PER_DEGREE * 1e6, tu / tg, lo, hi, fg / (double)pts, fu / (double)nu);
    }
}

static void table3(const thesis *th)
{
    printf("\nTable 3: the seven criteria of the adaptive loop (thesis defaults: delta = 3 px\n"
           "on 1000x1000, R = 0.5, movement stop skip 1 consec 5, budget 500); points, measured\n"
           "deviation of the control polygon in units of 0.5 px, time, flops\n\n");
    printf("| criterion | sptest1 | sptest2 | sptest3 | sptest4 | random x%d: pts, us |\n",
           RANDOM_COUNT / 4);
    printf("|---|---|---|---|---|---|\n");
    conica_bspline s;
    conica_bspline_init(&s);
    for (int c = 0; c < CONICA_CRIT_COUNT_; c++) {
        printf("| %-18s |", conica_plot_criterion_name((conica_plot_criterion)c));
        for (int i = 0; i < 4; i++) {
            if (!th->have) {
                printf(" - |");
                continue;
            }
            conica_plot_settings a = conica_plot_defaults();
            a.method = CONICA_PLOT_ADAPTIVE;
            a.criterion = (conica_plot_criterion)c;
            run ra = measure(&th->s[i], &a, 1);
            printf(" %zu pts, %.1f, %.0f us |", ra.points,
                   ra.dev / (REL_TOL * diag_of(&th->s[i])), ra.seconds * 1e6);
        }
        rng_state = 12345;
        size_t pts = 0;
        double us = 0;
        for (int r = 0; r < RANDOM_COUNT / 4; r++) {
            random_spline(60, 0, 0, 2, &s);
            conica_plot_settings a = conica_plot_defaults();
            a.method = CONICA_PLOT_ADAPTIVE;
            a.criterion = (conica_plot_criterion)c;
            run ra = measure(&s, &a, 1);
            pts += ra.points;
            us += ra.seconds * 1e6;
            conica_bspline_free(&s);
        }
        printf(" %zu, %.0f |\n", pts, us);
    }
}

static int usage(const char *why)
{
    fprintf(stderr,
            "bench_plot: %s\n"
            "usage: bench_plot [--rounds R] [--table 1|2|2b|2c|3] [DATA_DIR]\n",
            why);
    return 2;
}

/* Table t is printed: all of them, or the one --table names. */
static int want(const char *only, const char *t)
{
    return !only || !strcmp(only, t);
}

int main(int argc, char **argv)
{
    const char *dir = "../shared/data/splines", *only = NULL;
    int rounds = ROUNDS_DEFAULT;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--rounds") && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (*end || v < 1 || v > 1000)
                return usage("--rounds wants an integer 1..1000");
            rounds = (int)v;
        } else if (!strcmp(argv[i], "--table") && i + 1 < argc) {
            only = argv[++i];
            if (strcmp(only, "1") && strcmp(only, "2") && strcmp(only, "2b") &&
                strcmp(only, "2c") && strcmp(only, "3"))
                return usage("--table wants 1, 2, 2b, 2c or 3");
        } else if (argv[i][0] == '-') {
            return usage("unknown option");
        } else {
            dir = argv[i];
        }
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    thesis th;
    th.have = 1;
    for (int i = 0; i < 4; i++) {
        conica_bspline_init(&th.s[i]);
        if (!load(dir, names[i], &th.s[i]))
            th.have = 0;
    }
    if (!th.have)
        printf("(thesis curves not found in %s: their rows are skipped)\n\n", dir);
    else if (want(only, "1") || want(only, "2b") || want(only, "2c"))
        for (int i = 0; i < 4; i++)
            uniform_scan(&th.s[i], REL_TOL * diag_of(&th.s[i]), SCAN_MAX, &th.first[i],
                         &th.always[i]);
    rset *rs = NULL;
    if (want(only, "2") || want(only, "2c")) {
        rs = malloc(sizeof *rs);
        if (!rs) {
            fprintf(stderr, "bench_plot: out of memory\n");
            return 1;
        }
        rset_make(rs);
    }

    if (want(only, "1"))
        table1(&th);
    if (want(only, "2"))
        table2(rs);
    if (want(only, "2b") && th.have)
        table2b(&th);
    if (want(only, "2c"))
        table2c(&th, rs, rounds);
    if (want(only, "3"))
        table3(&th);

    if (rs)
        for (int di = 0; di < DEGREE_COUNT; di++)
            for (int r = 0; r < PER_DEGREE; r++)
                conica_bspline_free(&rs->s[di][r]);
    free(rs);
    for (int i = 0; i < 4; i++)
        conica_bspline_free(&th.s[i]);
    return 0;
}
