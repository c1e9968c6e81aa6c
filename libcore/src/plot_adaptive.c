/* The thesis's adaptive knot-insertion loop (seed 004, Sections 3.2-3.5):
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
 * as the complexity count of Section 3.5.4 assumes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "plot_internal.h"

#define PI_ 3.14159265358979323846
#define THR_SIMPLIFIED_ANGLE 0.00188
#define THR_ANGLE (2.0 * PI_ / 180.0)

typedef struct work {
    int p, d, h;
    size_t n, cap;
    double *k;  /* n + p + 1 knots */
    double *H;  /* homogeneous control points */
    double *P;  /* projected control points (d each) */
    double *f;  /* feature per index */
    conica_plot_criterion crit;
    double flops;
} work;

static double *pt(const work *w, size_t i)
{
    return w->P + i * (size_t)w->d;
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

static size_t mult_at(const work *w, double z)
{
    /* knots are sorted: binary search the run */
    size_t nk = w->n + (size_t)w->p + 1, lo = 0, hi = nk;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (w->k[mid] < z)
            lo = mid + 1;
        else
            hi = mid;
    }
    size_t m = 0;
    while (lo + m < nk && w->k[lo + m] == z)
        m++;
    return m;
}

/* Rule R for feature index i; returns 0 when no admissible knot exists. */
static int place(const work *w, const conica_plot_settings *set, size_t i, int segment,
                 double *z)
{
    size_t p = (size_t)w->p;
    const double *k = w->k;
    double a = k[p], b = k[w->n];
    double zz;
    if (segment) {
        switch (set->rule) {
        case CONICA_RULE_KNOT_AVERAGE: {
            double s0 = 0, s1 = 0;
            for (size_t q = 1; q <= p; q++) {
                s0 += k[i + q];
                s1 += k[i + 1 + q];
            }
            zz = 0.5 * (s0 + s1) / (double)p;
            break;
        }
        case CONICA_RULE_CHAIKIN:
            zz = 0.5 * (k[i + 1] + k[i + p + 1]);
            break;
        default:
            zz = k[i + 1] + set->rule_ratio * (k[i + p + 1] - k[i + 1]);
            break;
        }
    } else {
        switch (set->rule) {
        case CONICA_RULE_KNOT_AVERAGE: {
            double s0 = 0;
            for (size_t q = 1; q <= p; q++)
                s0 += k[i + q];
            zz = s0 / (double)p;
            break;
        }
        case CONICA_RULE_CHAIKIN:
            /* the new knot average lands midway between t*_i and t*_{i+1} */
            zz = 0.5 * (k[i + 1] + k[i + p + 1]);
            break;
        default:
            /* thesis code: z = t_mu + R (t_{mu+p} - t_mu) */
            zz = k[i] + set->rule_ratio * (k[i + p] - k[i]);
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
            double l0 = k[q] > a ? k[q] : a, l1 = k[q + 1] < b ? k[q + 1] : b;
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

static int grow(work *w)
{
    size_t nc = w->cap * 2;
    size_t p = (size_t)w->p;
    double *k = realloc(w->k, (nc + p + 1) * sizeof *k);
    if (!k)
        return 0;
    w->k = k;
    double *H = realloc(w->H, nc * (size_t)w->h * sizeof *H);
    if (!H)
        return 0;
    w->H = H;
    double *P = realloc(w->P, nc * (size_t)w->d * sizeof *P);
    if (!P)
        return 0;
    w->P = P;
    double *f = realloc(w->f, nc * sizeof *f);
    if (!f)
        return 0;
    w->f = f;
    w->cap = nc;
    return 1;
}

static void project(const work *w, const double *hp, double *out)
{
    double wt = w->h > w->d ? hp[w->d] : 1.0;
    for (int c = 0; c < w->d; c++)
        out[c] = hp[c] / wt;
}

/* Böhm insertion (Lemma 1.18) of z; returns the largest control point move.
 * *mu_out gets the span. */
static double insert(work *w, double z, size_t *mu_out)
{
    size_t p = (size_t)w->p, h = (size_t)w->h, d = (size_t)w->d, n = w->n;
    size_t nk = n + p + 1;
    size_t mu = conica__find_span(w->k, nk, w->p, z, 0);
    double nh[CONICA_BSPLINE_MAX_DEGREE * CONICA__HDIM_MAX];
    for (size_t j = mu - p + 1; j <= mu; j++) {
        double a = (z - w->k[j]) / (w->k[j + p] - w->k[j]);
        size_t l = j - (mu - p + 1);
        for (size_t c = 0; c < h; c++)
            nh[l * h + c] = w->H[(j - 1) * h + c] + a * (w->H[j * h + c] - w->H[(j - 1) * h + c]);
    }
    w->flops += (double)p * (3.0 + 3.0 * (double)h);
    memmove(w->H + (mu + 1) * h, w->H + mu * h, (n - mu) * h * sizeof *w->H);
    memmove(w->P + (mu + 1) * d, w->P + mu * d, (n - mu) * d * sizeof *w->P);
    memmove(w->f + mu + 1, w->f + mu, (n - mu) * sizeof *w->f);
    memmove(w->k + mu + 2, w->k + mu + 1, (nk - mu - 1) * sizeof *w->k);
    w->k[mu + 1] = z;
    double move = 0.0;
    for (size_t l = 0; l < p; l++) {
        size_t j = mu - p + 1 + l;
        double np_[3];
        memcpy(w->H + j * h, nh + l * h, h * sizeof *nh);
        project(w, nh + l * h, np_);
        double mv = sqrt(dist2(np_, w->P + j * d, (int)d));
        move = mv > move ? mv : move;
        memcpy(w->P + j * d, np_, d * sizeof *np_);
    }
    w->flops += 4.0 * (double)p;
    w->n = n + 1;
    *mu_out = mu;
    return move;
}

/* Böhm insertion under the max_knots cap; *move gets the largest control
 * point move, *mu the span. */
static conica_code insert_capped(work *w, double z, size_t *knots_left,
                                 const conica_plot_settings *set, conica_plot_stats *stats,
                                 double *move, size_t *mu, conica_status *st)
{
    if (*knots_left == 0)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "more than %zu knots inserted (max_knots)", set->max_knots);
    if (w->n == w->cap && !grow(w))
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    *move = insert(w, z, mu);
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
    w.n = g->n;
    w.cap = g->n + 16;
    w.crit = set->criterion;
    size_t p = (size_t)w.p;
    w.k = malloc((w.cap + p + 1) * sizeof *w.k);
    w.H = malloc(w.cap * (size_t)w.h * sizeof *w.H);
    w.P = malloc(w.cap * (size_t)w.d * sizeof *w.P);
    w.f = malloc(w.cap * sizeof *w.f);
    conica_code rc = CONICA_OK;
    if (!w.k || !w.H || !w.P || !w.f) {
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto done;
    }
    memcpy(w.k, g->knots, (g->n + p + 1) * sizeof *w.k);
    conica__homog(g, 0, g->n, w.H);
    for (size_t i = 0; i < w.n; i++)
        project(&w, w.H + i * (size_t)w.h, w.P + i * (size_t)w.d);
    /* optional uniform pre-phase (Section 3.5.3) */
    double a = w.k[p], b = w.k[w.n];
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
        w.f[i] = feature(&w, i);
    int segment = is_segment_crit(w.crit);
    size_t small = 0, iter = 0;
    for (;;) {
        /* criterion C: the largest feature */
        size_t best = 0;
        double fb = -1;
        for (size_t i = 0; i < w.n; i++)
            if (w.f[i] > fb) {
                fb = w.f[i];
                best = i;
            }
        if (fb < 0)
            break; /* no admissible place left */
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
            w.f[best] = -1; /* nothing to insert here any more */
            continue;
        }
        size_t mu;
        double move;
        rc = insert_capped(&w, z, knots_left, set, stats, &move, &mu, st);
        if (rc != CONICA_OK)
            goto done;
        (*budget_left)--;
        /* features whose local polygon touched the changed points */
        size_t lo = mu >= p + 2 ? mu - p - 2 : 0, hi = mu + 3 < w.n ? mu + 3 : w.n;
        for (size_t i = lo; i < hi; i++)
            w.f[i] = feature(&w, i);
        /* stopping test S: control point movement (Section 3.4) */
        if (set->stop == CONICA_STOP_MOVEMENT && iter % set->skip == 0) {
            small = move < eps ? small + 1 : 0;
            if (small >= set->consec)
                break;
        }
    }
    /* output */
    {
        size_t d = (size_t)w.d;
        double buf[3];
        for (size_t i = first_is_join ? 1 : 0; i < w.n && rc == CONICA_OK; i++) {
            if (set->output == CONICA_OUTPUT_CONTROL_POLYGON || i == 0 || i + 1 == w.n) {
                double ti = set->output == CONICA_OUTPUT_CONTROL_POLYGON ? NAN
                            : (i == 0 ? w.k[p] : w.k[w.n]);
                rc = conica__out_push(o, w.P + i * d, ti, st);
            } else {
                double s = 0;
                for (size_t q = 1; q <= p; q++)
                    s += w.k[i + q];
                conica_bspline_eval(g, s / (double)p, buf, NULL);
                stats->flops += (double)(p * (p + 1) / 2) * (3.0 + 3.0 * (double)w.h);
                rc = conica__out_push(o, buf, s / (double)p, st);
            }
        }
    }
done:
    stats->flops += w.flops;
    free(w.k);
    free(w.H);
    free(w.P);
    free(w.f);
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
