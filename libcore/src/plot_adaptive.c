/* SPDX-License-Identifier: MIT */
/* The thesis's adaptive knot-insertion loop (Dahl 2019, §3.2-3.5):
 * each iteration a geometric criterion C picks the part of the control
 * polygon with the largest value, a rule R places one knot there, Böhm's
 * method (Lemma 1.18) inserts it, and a stopping test S ends the loop.
 *
 * Choices the thesis leaves open, fixed here (REFERENCE.md section 4 gives
 * the thesis code's defaults, which we follow):
 * - control points are the coefficients (functions: (t*_j, c_j));
 * - eps = delta / rho * Delta c (eq. (3.26)) or the absolute tolerance;
 * - default thresholds: length eps, length ratio 1 + 0.1 delta/rho
 *   (= 1 + 0.1 eps/Delta c), simplified angle 0.00188, angle 2 pi/180,
 *   base line eps^2 (squared distances, Appendix A.3);
 * - the movement test runs every `skip` iterations and stops after
 *   `consec` moves below eps in a row (thesis defaults 1 and 5); the move
 *   of an insertion is the largest distance between an old control point
 *   and the one replacing it (the new points lie on the old segments);
 * - local control polygons are triples P_{i-1} P_i P_{i+1} for the
 *   point criteria (angles, base line, length ratio), segments for the
 *   length criteria; the extended base line uses quadruples P_{i-1}..P_{i+2}
 *   and halves the value when both inner points are on the same side of
 *   the base line (Lemma 3.15: "more flat" than an inflection);
 * - a knot that would reach multiplicity p (the thesis assumes <= p-1,
 *   Section 3.5.2) or leave the open domain is moved to the middle of the
 *   longest knot interval under the chosen control point (Section 3.3.3:
 *   "we can simply perturb the value").
 * Features are cached and only the p+4 around an insertion are recomputed,
 * as the complexity count of Section 3.5.4 assumes.
 *
 * Storage (issue 17): the control points, their features and the knots
 * live in chunks of at most ADP_CHUNK records, found by index through a
 * Fenwick tree of the chunk sizes, and the largest feature through a
 * tournament tree over the chunks' maxima. An insertion then moves at most
 * one chunk and an iteration costs O(ADP_CHUNK + log n) instead of the
 * O(n) of plain arrays (a memmove of every later point and a scan of every
 * feature): 120 000 knots took 9 s and a million would have taken ten
 * minutes. Same operations in the same order, so the same points. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define PI_ 3.14159265358979323846
#define THR_SIMPLIFIED_ANGLE 0.00188
#define THR_ANGLE (2.0 * PI_ / 180.0)

/* Records per chunk at most (a chunk that fills up is split in two). */
#define ADP_CHUNK 256

/* A run of consecutive records. Record j holds, in this order, the
 * homogeneous control point H_j (h values), its projection P_j (d), the
 * feature f_j and the knot t_{j+1}: inserting a control point at j and a
 * knot at j+1 (Boehm) is then one record inserted at j. t_0 and the p
 * knots after t_n are kept apart: they never change. */
typedef struct chunk {
    size_t count;
    double fmax;   /* largest feature of the chunk (-1: none above -1) */
    size_t farg;   /* its first offset */
    double *rec;   /* ADP_CHUNK records */
} chunk;

typedef struct work {
    int p, d, h;
    size_t n;      /* control points (records) */
    size_t rs;     /* doubles per record: h + d + 2 */
    double k0;     /* t_0 */
    double tail[CONICA_BSPLINE_MAX_DEGREE + 1]; /* t_{n+1} .. t_{n+p} */
    chunk **ch;
    size_t nch, chcap;
    size_t *fen;   /* Fenwick tree of the chunk counts (1-based, nch) */
    size_t *tour;  /* tournament tree over chunk maxima: winner chunk per node */
    size_t tsize;  /* its leaves (a power of two >= nch) */
    size_t cache_c, cache_start; /* the chunk last found, and its first index */
    int cache_ok;
    int nomem;
    conica_plot_criterion crit;
    double flops;
} work;

static void fen_rebuild(work *w)
{
    for (size_t c = 1; c <= w->nch; c++)
        w->fen[c] = w->ch[c - 1]->count;
    for (size_t c = 1; c <= w->nch; c++) {
        size_t parent = c + (c & (~c + 1));
        if (parent <= w->nch)
            w->fen[parent] += w->fen[c];
    }
}

/* Records in the chunks before chunk c. */
static size_t fen_prefix(const work *w, size_t c)
{
    size_t acc = 0;
    for (size_t i = c; i > 0; i -= i & (~i + 1))
        acc += w->fen[i];
    return acc;
}

static void fen_add(work *w, size_t c)
{
    for (size_t i = c + 1; i <= w->nch; i += i & (~i + 1))
        w->fen[i]++;
}

/* Chunk holding record i (< n) and the index of its first record. */
static void locate(work *w, size_t i, size_t *c, size_t *start)
{
    size_t pos = 0, acc = 0, step = 1;
    if (w->cache_ok && i >= w->cache_start &&
        i - w->cache_start < w->ch[w->cache_c]->count) {
        *c = w->cache_c;
        *start = w->cache_start;
        return;
    }
    while (step * 2 <= w->nch)
        step *= 2;
    for (; step; step /= 2)
        if (pos + step <= w->nch && acc + w->fen[pos + step] <= i) {
            pos += step;
            acc += w->fen[pos];
        }
    *c = pos; /* 0-based: the chunk after the `pos` whole ones */
    *start = acc;
    w->cache_c = pos;
    w->cache_start = acc;
    w->cache_ok = 1;
}

static double *rec(work *w, size_t i)
{
    size_t c, start;
    locate(w, i, &c, &start);
    return w->ch[c]->rec + (i - start) * w->rs;
}

static double *Hp(work *w, size_t i) { return rec(w, i); }
static double *pt(work *w, size_t i) { return rec(w, i) + w->h; }
static double *fp(work *w, size_t i) { return rec(w, i) + w->h + w->d; }

/* Knot t_i, 0 <= i <= n + p. */
static double kn(work *w, size_t i)
{
    if (i == 0)
        return w->k0;
    if (i > w->n)
        return w->tail[i - w->n - 1];
    return rec(w, i - 1)[w->h + w->d + 1];
}

static int tour_better(const work *w, size_t a, size_t b)
{
    if (b == SIZE_MAX)
        return a != SIZE_MAX;
    if (a == SIZE_MAX)
        return 0;
    if (w->ch[a]->fmax != w->ch[b]->fmax)
        return w->ch[a]->fmax > w->ch[b]->fmax;
    return a < b;
}

static void tour_fix(work *w, size_t c)
{
    size_t node = w->tsize + c;
    w->tour[node] = c < w->nch ? c : SIZE_MAX;
    for (node /= 2; node >= 1; node /= 2) {
        size_t a = w->tour[2 * node], b = w->tour[2 * node + 1];
        w->tour[node] = tour_better(w, a, b) || b == SIZE_MAX ? a : b;
    }
}

/* The chunk's largest feature by the same rule as a scan of the whole
 * array: strictly greater than the best so far, starting from -1. */
static void chunk_max(work *w, size_t c)
{
    chunk *k = w->ch[c];
    size_t off = (size_t)(w->h + w->d);
    k->fmax = -1;
    k->farg = 0;
    for (size_t j = 0; j < k->count; j++)
        if (k->rec[j * w->rs + off] > k->fmax) {
            k->fmax = k->rec[j * w->rs + off];
            k->farg = j;
        }
}

static void refresh(work *w, size_t i)
{
    size_t c, start;
    locate(w, i, &c, &start);
    chunk_max(w, c);
    tour_fix(w, c);
}

/* Rebuild the index structures after the chunk list changed. */
static int rebuild(work *w)
{
    size_t ts = 1;
    while (ts < w->nch)
        ts *= 2;
    size_t *fen = realloc(w->fen, (w->nch + 1) * sizeof *fen);
    if (!fen)
        return 0;
    w->fen = fen;
    if (ts != w->tsize || !w->tour) {
        size_t *t = realloc(w->tour, 2 * ts * sizeof *t);
        if (!t)
            return 0;
        w->tour = t;
        w->tsize = ts;
    }
    fen_rebuild(w);
    for (size_t c = 0; c < ts; c++)
        w->tour[ts + c] = c < w->nch ? c : SIZE_MAX;
    for (size_t node = ts - 1; node >= 1; node--) {
        size_t a = w->tour[2 * node], b = w->tour[2 * node + 1];
        w->tour[node] = tour_better(w, a, b) || b == SIZE_MAX ? a : b;
    }
    w->cache_ok = 0;
    return 1;
}

static chunk *chunk_new(const work *w)
{
    chunk *k = malloc(sizeof *k);
    if (!k)
        return NULL;
    k->rec = malloc(ADP_CHUNK * w->rs * sizeof *k->rec);
    if (!k->rec) {
        free(k);
        return NULL;
    }
    k->count = 0;
    k->fmax = -1;
    k->farg = 0;
    return k;
}

/* Insert record r at index pos (0 <= pos <= n-1: never at the end, Boehm
 * inserts before an existing point). Returns 0 when out of memory. */
static int insert_rec(work *w, size_t pos, const double *r)
{
    size_t c, start;
    locate(w, pos, &c, &start);
    chunk *k = w->ch[c];
    size_t off = pos - start, rs = w->rs;
    memmove(k->rec + (off + 1) * rs, k->rec + off * rs, (k->count - off) * rs * sizeof *k->rec);
    memcpy(k->rec + off * rs, r, rs * sizeof *r);
    k->count++;
    w->n++;
    fen_add(w, c);
    w->cache_ok = 0;
    if (k->count < ADP_CHUNK)
        return 1;
    /* full: the upper half moves to a new chunk after it */
    if (w->nch == w->chcap) {
        size_t nc = 2 * w->chcap;
        chunk **t = realloc(w->ch, nc * sizeof *t);
        if (!t)
            return 0;
        w->ch = t;
        w->chcap = nc;
    }
    chunk *up = chunk_new(w);
    if (!up)
        return 0;
    size_t half = k->count / 2;
    up->count = k->count - half;
    memcpy(up->rec, k->rec + half * rs, up->count * rs * sizeof *k->rec);
    k->count = half;
    memmove(w->ch + c + 2, w->ch + c + 1, (w->nch - c - 1) * sizeof *w->ch);
    w->ch[c + 1] = up;
    w->nch++;
    chunk_max(w, c);
    chunk_max(w, c + 1);
    return rebuild(w);
}

static void work_free(work *w)
{
    for (size_t c = 0; c < w->nch; c++) {
        free(w->ch[c]->rec);
        free(w->ch[c]);
    }
    free(w->ch);
    free(w->fen);
    free(w->tour);
}

/* The records of g, chunks half full. Returns 0 when out of memory. */
static int work_init(work *w, const conica_bspline *g)
{
    size_t p = (size_t)w->p, n = g->n, per = ADP_CHUNK / 2;
    double hp[CONICA__HDIM_MAX];
    w->rs = (size_t)(w->h + w->d + 2);
    w->k0 = g->knots[0];
    for (size_t q = 0; q < p; q++)
        w->tail[q] = g->knots[n + 1 + q];
    w->chcap = n / per + 2;
    w->ch = malloc(w->chcap * sizeof *w->ch);
    if (!w->ch)
        return 0;
    for (size_t i = 0; i < n; i++) {
        if (i % per == 0) {
            chunk *k = chunk_new(w);
            if (!k)
                return 0;
            w->ch[w->nch++] = k;
        }
        chunk *k = w->ch[w->nch - 1];
        double *r = k->rec + k->count * w->rs;
        conica__homog(g, i, 1, hp);
        memcpy(r, hp, (size_t)w->h * sizeof *hp);
        r[w->h + w->d] = -1;
        r[w->h + w->d + 1] = g->knots[i + 1];
        k->count++;
    }
    w->n = n;
    return rebuild(w);
}

static double dist2(const double *a, const double *b, int d)
{
    double r = 0;
    for (int c = 0; c < d; c++)
        r += (a[c] - b[c]) * (a[c] - b[c]);
    return r;
}

/* Def. 3.14 / Appendix A.3: squared distance of q to the base line [a, b];
 * the nearest end point when the projection falls outside. */
static double baseline_d2(const double *q, const double *a, const double *b, int d)
{
    double ab2 = 0, t = 0;
    for (int c = 0; c < d; c++) {
        ab2 += (b[c] - a[c]) * (b[c] - a[c]);
        t += (q[c] - a[c]) * (b[c] - a[c]);
    }
    if (t <= 0 || ab2 <= 0)
        return dist2(q, a, d);
    if (t >= ab2)
        return dist2(q, b, d);
    double r = dist2(q, a, d) - t * t / ab2;
    return r > 0 ? r : 0;
}

/* Side of q relative to the line a->b (2-D cross product; 3-D: the sign
 * of the component along the normal of the local plane is meaningless, so
 * we compare the cross products' directions, Lemma 3.15 in vector form). */
static void cross_ab(const double *q, const double *a, const double *b, int d, double *out)
{
    double u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    for (int c = 0; c < d; c++) {
        u[c] = q[c] - a[c];
        v[c] = b[c] - a[c];
    }
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
}

/* Feature of index i (segment i..i+1 for the length criteria, point i
 * otherwise); -1 where undefined. Returns the value, counts flops. */
static double feature(work *w, size_t i)
{
    int d = w->d;
    size_t n = w->n;
    switch (w->crit) {
    case CONICA_CRIT_SIMPLIFIED_LENGTH: {
        if (i + 1 >= n)
            return -1;
        /* eq. (3.11): max + 1/2 min of the coordinate differences (3-D:
         * max + 1/2 sum of the others) */
        double mx = 0, sum = 0;
        for (int c = 0; c < d; c++) {
            double e = fabs(pt(w, i + 1)[c] - pt(w, i)[c]);
            sum += e;
            mx = e > mx ? e : mx;
        }
        w->flops += 2.0 * d;
        return mx + 0.5 * (sum - mx);
    }
    case CONICA_CRIT_LENGTH:
        if (i + 1 >= n)
            return -1;
        w->flops += 3.0 * d;
        return sqrt(dist2(pt(w, i), pt(w, i + 1), d));
    default:
        break;
    }
    if (i == 0 || i + 1 >= n)
        return -1;
    const double *a = pt(w, i - 1), *q = pt(w, i), *b = pt(w, i + 1);
    switch (w->crit) {
    case CONICA_CRIT_LENGTH_RATIO: {
        /* eq. (3.21) on the triple: (l_{i-1} + l_i) / d(P_{i-1}, P_{i+1}) */
        double l = sqrt(dist2(a, q, d)) + sqrt(dist2(q, b, d));
        double base = sqrt(dist2(a, b, d));
        w->flops += 19;
        if (l <= 0)
            return 1.0;
        return base > 0 ? l / base : 1e300;
    }
    case CONICA_CRIT_ANGLE:
        w->flops += 40;
        return conica__turn_angle(a, q, b, d);
    case CONICA_CRIT_SIMPLIFIED_ANGLE: {
        double dot = 0, la = 0, lb = 0;
        for (int c = 0; c < d; c++) {
            double u = q[c] - a[c], v = b[c] - q[c];
            dot += u * v;
            la += u * u;
            lb += v * v;
        }
        if (la <= 0 || lb <= 0)
            return 0.0;
        /* Fig. 16: T(x) = -pi/2 x|x| + pi/2 from the squared cosine */
        double x2 = dot * fabs(dot) / (la * lb);
        w->flops += 23;
        return -0.5 * PI_ * x2 + 0.5 * PI_;
    }
    case CONICA_CRIT_BASE_LINE:
        w->flops += 30;
        return baseline_d2(q, a, b, d);
    case CONICA_CRIT_EXTENDED_BASE_LINE: {
        if (i + 2 >= n) {
            w->flops += 30;
            return baseline_d2(q, a, b, d);
        }
        const double *q2 = b, *e = pt(w, i + 2);
        double d1 = baseline_d2(q, a, e, d), d2 = baseline_d2(q2, a, e, d);
        double c1[3], c2[3];
        cross_ab(q, a, e, d, c1);
        cross_ab(q2, a, e, d, c2);
        double same = c1[0] * c2[0] + c1[1] * c2[1] + c1[2] * c2[2];
        double v = d1 > d2 ? d1 : d2;
        w->flops += 56;
        return same > 0 ? 0.5 * v : v;
    }
    default:
        return -1;
    }
}

static double default_threshold(conica_plot_criterion c, double eps, double diag)
{
    switch (c) {
    case CONICA_CRIT_SIMPLIFIED_LENGTH:
    case CONICA_CRIT_LENGTH:
        return eps;
    case CONICA_CRIT_LENGTH_RATIO:
        return 1.0 + 0.1 * (diag > 0 ? eps / diag : 0.0);
    case CONICA_CRIT_SIMPLIFIED_ANGLE:
        return THR_SIMPLIFIED_ANGLE;
    case CONICA_CRIT_ANGLE:
        return THR_ANGLE;
    default:
        return eps * eps;
    }
}

static int is_segment_crit(conica_plot_criterion c)
{
    return c == CONICA_CRIT_SIMPLIFIED_LENGTH || c == CONICA_CRIT_LENGTH;
}

/* First knot index in [0, n+p] whose knot is >= z (knots do not decrease). */
static size_t knot_lower_bound(work *w, double z)
{
    size_t lo = 0, hi = w->n + (size_t)w->p + 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (kn(w, mid) < z)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static size_t mult_at(work *w, double z)
{
    /* knots are sorted: binary search the run */
    size_t nk = w->n + (size_t)w->p + 1, lo = knot_lower_bound(w, z);
    size_t m = 0;
    while (lo + m < nk && kn(w, lo + m) == z)
        m++;
    return m;
}

/* conica__find_span(knots, n + p + 1, p, x, 0) on the chunked knots. */
static size_t find_span(work *w, double x)
{
    size_t p = (size_t)w->p, n = w->n;
    size_t lo = p, hi = n;
    if (!(x > kn(w, p)) || x == kn(w, p)) {
        while (lo + 1 < n && !(kn(w, lo) < kn(w, lo + 1)))
            lo++;
        return lo;
    }
    if (x >= kn(w, n)) {
        size_t mu = n - 1;
        while (mu > p && !(kn(w, mu) < kn(w, mu + 1)))
            mu--;
        return mu;
    }
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (kn(w, mid) <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Rule R for feature index i; returns 0 when no admissible knot exists. */
static int place(work *w, const conica_plot_settings *set, size_t i, int segment, double *z)
{
    size_t p = (size_t)w->p;
    double a = kn(w, p), b = kn(w, w->n);
    double zz;
    if (segment) {
        switch (set->rule) {
        case CONICA_RULE_KNOT_AVERAGE: {
            double s0 = 0, s1 = 0;
            for (size_t q = 1; q <= p; q++) {
                s0 += kn(w, i + q);
                s1 += kn(w, i + 1 + q);
            }
            zz = 0.5 * (s0 + s1) / (double)p;
            break;
        }
        case CONICA_RULE_CHAIKIN:
            zz = 0.5 * (kn(w, i + 1) + kn(w, i + p + 1));
            break;
        default:
            zz = kn(w, i + 1) + set->rule_ratio * (kn(w, i + p + 1) - kn(w, i + 1));
            break;
        }
    } else {
        switch (set->rule) {
        case CONICA_RULE_KNOT_AVERAGE: {
            double s0 = 0;
            for (size_t q = 1; q <= p; q++)
                s0 += kn(w, i + q);
            zz = s0 / (double)p;
            break;
        }
        case CONICA_RULE_CHAIKIN:
            /* the new knot average lands midway between t*_i and t*_{i+1} */
            zz = 0.5 * (kn(w, i + 1) + kn(w, i + p + 1));
            break;
        default:
            /* thesis code: z = t_mu + R (t_{mu+p} - t_mu) */
            zz = kn(w, i) + set->rule_ratio * (kn(w, i + p) - kn(w, i));
            break;
        }
    }
    if (zz > a && zz < b && mult_at(w, zz) + 1 <= p - 1 + (p == 1))
        goto ok;
    {
        /* perturb: middle of the longest knot interval under P_i */
        size_t lo = i, hi = i + p + 1;
        if (segment)
            hi++;
        double best = 0;
        zz = NAN;
        for (size_t q = lo; q < hi && q + 1 < w->n + p + 1; q++) {
            double kq = kn(w, q), kq1 = kn(w, q + 1);
            double l0 = kq > a ? kq : a, l1 = kq1 < b ? kq1 : b;
            if (l1 - l0 > best) {
                double mid = 0.5 * (l0 + l1);
                if (mid > l0 && mid < l1) {
                    best = l1 - l0;
                    zz = mid;
                }
            }
        }
        if (!(best > 0))
            return 0;
    }
ok:
    *z = zz;
    return 1;
}

static void project(const work *w, const double *hp, double *out)
{
    double wt = w->h > w->d ? hp[w->d] : 1.0;
    for (int c = 0; c < w->d; c++)
        out[c] = hp[c] / wt;
}

/* Boehm insertion (Lemma 1.18) of z; returns the largest control point move
 * (-1 when out of memory). *mu_out gets the span. */
static double insert(work *w, double z, size_t *mu_out)
{
    size_t p = (size_t)w->p, h = (size_t)w->h, d = (size_t)w->d;
    size_t mu = find_span(w, z);
    double nh[CONICA_BSPLINE_MAX_DEGREE * CONICA__HDIM_MAX];
    double r[CONICA__HDIM_MAX + 3 + 2];
    for (size_t j = mu - p + 1; j <= mu; j++) {
        double a = (z - kn(w, j)) / (kn(w, j + p) - kn(w, j));
        size_t l = j - (mu - p + 1);
        const double *h0 = Hp(w, j - 1), *h1 = Hp(w, j);
        for (size_t c = 0; c < h; c++)
            nh[l * h + c] = h0[c] + a * (h1[c] - h0[c]);
    }
    w->flops += (double)p * (3.0 + 3.0 * (double)h);
    /* the new record at mu: the last new point, the knot z; the old point
     * mu moves to mu + 1 (its feature is recomputed by the caller) */
    memcpy(r, rec(w, mu), w->rs * sizeof *r);
    memcpy(r, nh + (p - 1) * h, h * sizeof *nh);
    r[h + d + 1] = z;
    if (!insert_rec(w, mu, r)) {
        w->nomem = 1;
        return -1;
    }
    double move = 0.0;
    for (size_t l = 0; l < p; l++) {
        size_t j = mu - p + 1 + l;
        double np_[3];
        double *hj = Hp(w, j), *pj = hj + h;
        /* the point it replaces: the old P_j, for j = mu now at mu + 1 */
        const double *old = l + 1 == p ? pt(w, mu + 1) : pj;
        project(w, nh + l * h, np_);
        double mv = sqrt(dist2(np_, old, (int)d));
        move = mv > move ? mv : move;
        hj = Hp(w, j); /* pt() may have moved the cache, not the records */
        memcpy(hj, nh + l * h, h * sizeof *nh);
        memcpy(hj + h, np_, d * sizeof *np_);
    }
    w->flops += 4.0 * (double)p;
    *mu_out = mu;
    return move;
}

/* Boehm insertion under the max_knots cap; *move gets the largest control
 * point move, *mu the span. */
static conica_code insert_capped(work *w, double z, size_t *knots_left,
                                 const conica_plot_settings *set, conica_plot_stats *stats,
                                 double *move, size_t *mu, conica_status *st)
{
    if (*knots_left == 0)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "more than %zu knots inserted (max_knots)", set->max_knots);
    *move = insert(w, z, mu);
    if (w->nomem)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    (*knots_left)--;
    stats->knots_inserted++;
    return CONICA_OK;
}

static conica_code adaptive_piece(const conica_bspline *g, const conica_plot_settings *set,
                                  double eps, double thr, int first_is_join, size_t *knots_left,
                                  size_t *budget_left,
                                  conica__out *o, conica_plot_stats *stats, conica_status *st)
{
    work w;
    memset(&w, 0, sizeof w);
    w.p = g->degree;
    w.d = g->dim;
    w.h = conica__hdim(g);
    w.crit = set->criterion;
    size_t p = (size_t)w.p;
    conica_code rc = CONICA_OK;
    if (!work_init(&w, g)) {
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < w.n; i++)
        project(&w, Hp(&w, i), pt(&w, i));
    /* optional uniform pre-phase (Section 3.5.3) */
    double a = kn(&w, p), b = kn(&w, w.n);
    for (size_t q = 1; q <= set->prephase_knots; q++) {
        double z = a + (b - a) * (double)q / (double)(set->prephase_knots + 1);
        if (!(z > a && z < b) || mult_at(&w, z) + 1 > p - 1 + (p == 1))
            continue;
        size_t mu;
        double move;
        rc = insert_capped(&w, z, knots_left, set, stats, &move, &mu, st);
        if (rc != CONICA_OK)
            goto done;
    }
    for (size_t i = 0; i < w.n; i++)
        *fp(&w, i) = feature(&w, i);
    for (size_t c = 0; c < w.nch; c++) {
        chunk_max(&w, c);
        tour_fix(&w, c);
    }
    int segment = is_segment_crit(w.crit);
    size_t small = 0, iter = 0;
    for (;;) {
        /* criterion C: the largest feature (the first of equal ones) */
        size_t win = w.tour[1], best = 0;
        double fb = win == SIZE_MAX ? -1 : w.ch[win]->fmax;
        if (fb < 0)
            break; /* no admissible place left */
        best = fen_prefix(&w, win) + w.ch[win]->farg;
        if (set->stop == CONICA_STOP_THRESHOLD && fb <= thr)
            break;
        if (*budget_left == 0)
            break; /* knot budget (Section 3.4), per continuous piece as the
                    * thesis plots each piece by its own call */
        if (stats->iterations >= set->max_iterations) {
            rc = conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                              "adaptive loop exceeds %zu iterations (max_iterations)",
                              set->max_iterations);
            goto done;
        }
        stats->iterations++;
        iter++;
        double z;
        if (!place(&w, set, best, segment, &z)) {
            *fp(&w, best) = -1; /* nothing to insert here any more */
            refresh(&w, best);
            continue;
        }
        size_t mu;
        double move = 0.0; /* set by insert_capped on success (-O3 cannot see it) */
        rc = insert_capped(&w, z, knots_left, set, stats, &move, &mu, st);
        if (rc != CONICA_OK)
            goto done;
        (*budget_left)--;
        /* features whose local polygon touched the changed points */
        size_t lo = mu >= p + 2 ? mu - p - 2 : 0, hi = mu + 3 < w.n ? mu + 3 : w.n;
        for (size_t i = lo; i < hi; i++)
            *fp(&w, i) = feature(&w, i);
        for (size_t i = lo; i < hi; i++) { /* each chunk of the window once */
            size_t c, start;
            locate(&w, i, &c, &start);
            chunk_max(&w, c);
            tour_fix(&w, c);
            i = start + w.ch[c]->count - 1;
        }
        /* stopping test S: control point movement (Section 3.4) */
        if (set->stop == CONICA_STOP_MOVEMENT && iter % set->skip == 0) {
            small = move < eps ? small + 1 : 0;
            if (small >= set->consec)
                break;
        }
    }
    /* output */
    {
        double buf[3];
        for (size_t i = first_is_join ? 1 : 0; i < w.n && rc == CONICA_OK; i++) {
            if (set->output == CONICA_OUTPUT_CONTROL_POLYGON || i == 0 || i + 1 == w.n) {
                double ti = set->output == CONICA_OUTPUT_CONTROL_POLYGON ? NAN
                            : (i == 0 ? kn(&w, p) : kn(&w, w.n));
                rc = conica__out_push(o, pt(&w, i), ti, st);
            } else {
                double sum = 0;
                for (size_t q = 1; q <= p; q++)
                    sum += kn(&w, i + q);
                conica_bspline_eval(g, sum / (double)p, buf, NULL);
                stats->flops += (double)(p * (p + 1) / 2) * (3.0 + 3.0 * (double)w.h);
                rc = conica__out_push(o, buf, sum / (double)p, st);
            }
        }
    }
done:
    stats->flops += w.flops;
    work_free(&w);
    return rc;
}

conica_code conica__plot_adaptive(const conica__pieces *pc, const conica_plot_settings *set,
                                  double tol, conica__out *o, conica_plot_stats *stats,
                                  conica_status *st)
{
    size_t knots_left = set->max_knots;
    for (size_t k = 0; k < pc->count; k++) {
        size_t budget_left = set->knot_budget;
        double diag = conica__ctrl_diagonal(&pc->sp[k]);
        double thr = set->threshold > 0 ? set->threshold
                                        : default_threshold(set->criterion, tol, diag);
        conica_code rc = CONICA_OK;
        if (!pc->joined[k])
            rc = conica__out_piece(o, st);
        if (rc == CONICA_OK)
            rc = adaptive_piece(&pc->sp[k], set, tol, thr, pc->joined[k], &knots_left,
                                &budget_left, o, stats, st);
        if (rc != CONICA_OK)
            return rc;
    }
    return CONICA_OK;
}
