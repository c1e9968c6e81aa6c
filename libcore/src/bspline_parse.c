/* SPDX-License-Identifier: MIT */
/* Parser of the .spl spline text format (docs/file-formats.md):
 *     degree P
 *     knots t1 t2 ...        (may be split over several `knots` lines)
 *     c x [y [z]]            (one control point a line)
 *     w w1 w2 ...            (optional weights, may be split too)
 * `#` starts a comment. Numbers are read by conica__parse_double (no C
 * locale). Every count is capped before it grows an array. */
#include <stdlib.h>
#include <string.h>

#include "bspline_internal.h"
#include "internal.h"
#include "numparse.h"

typedef struct dvec {
    double *v;
    size_t n, cap;
    size_t *line; /* source line of each value */
} dvec;

static int dvec_push(dvec *a, double x, size_t line)
{
    if (a->n == a->cap) {
        size_t nc = a->cap ? 2 * a->cap : 64;
        double *v = realloc(a->v, nc * sizeof *v);
        if (!v)
            return 0;
        a->v = v;
        size_t *l = realloc(a->line, nc * sizeof *l);
        if (!l)
            return 0;
        a->line = l;
        a->cap = nc;
    }
    a->v[a->n] = x;
    a->line[a->n] = line;
    a->n++;
    return 1;
}

static void dvec_free(dvec *a)
{
    free(a->v);
    free(a->line);
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

conica_bspline_parse_limits conica_bspline_parse_limits_defaults(void)
{
    conica_bspline_parse_limits lim;
    lim.max_ctrl = CONICA_BSPLINE_MAX_CTRL;
    lim.max_degree = CONICA_BSPLINE_MAX_DEGREE;
    return lim;
}

conica_code conica_bspline_parse(const char *buf, size_t len, conica_bspline *out,
                                 conica_status *st)
{
    return conica_bspline_parse_ex(buf, len, NULL, out, st);
}

conica_code conica_bspline_parse_ex(const char *buf, size_t len,
                                    const conica_bspline_parse_limits *lim, conica_bspline *out,
                                    conica_status *st)
{
    if ((!buf && len) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "NULL input or output");
    const conica_bspline_parse_limits def = conica_bspline_parse_limits_defaults();
    if (!lim)
        lim = &def;
    if (lim->max_ctrl < 1 || lim->max_ctrl > CONICA_BSPLINE_MAX_CTRL || lim->max_degree < 1 ||
        lim->max_degree > CONICA_BSPLINE_MAX_DEGREE)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "reader caps out of range: max_ctrl %zu (1..%zu), max_degree %d "
                            "(1..%d)",
                            lim->max_ctrl, (size_t)CONICA_BSPLINE_MAX_CTRL, lim->max_degree,
                            CONICA_BSPLINE_MAX_DEGREE);
    /* knots and weights: n + p + 1 values at most for a spline within the caps */
    const size_t max_values = lim->max_ctrl + (size_t)lim->max_degree + 1;
    dvec knots = {0}, ctrl = {0}, wts = {0};
    int degree = -1, dim = 0;
    size_t degree_line = 0, ncpts = 0;
    conica_code rc = CONICA_OK;
    size_t pos = 0, line = 1;
    while (pos < len && rc == CONICA_OK) {
        size_t eol = pos;
        while (eol < len && buf[eol] != '\n')
            eol++;
        size_t end = pos;
        while (end < eol && buf[end] != '#')
            end++;
        size_t i = pos;
        while (i < end && is_space(buf[i]))
            i++;
        if (i < end) {
            size_t ks = i;
            while (i < end && !is_space(buf[i]))
                i++;
            size_t kl = i - ks;
            const char *kw = buf + ks;
            enum { K_DEG, K_KNOTS, K_C, K_W } kind;
            if (kl == 6 && memcmp(kw, "degree", 6) == 0)
                kind = K_DEG;
            else if (kl == 5 && memcmp(kw, "knots", 5) == 0)
                kind = K_KNOTS;
            else if (kl == 1 && kw[0] == 'c')
                kind = K_C;
            else if (kl == 1 && kw[0] == 'w')
                kind = K_W;
            else {
                rc = conica__fail(st, CONICA_ERR_PARSE, line, ks, "unknown keyword '%.*s'",
                                  (int)(kl > 40 ? 40 : kl), kw);
                break;
            }
            int count = 0;
            double vals[4];
            for (;;) {
                while (i < end && is_space(buf[i]))
                    i++;
                if (i >= end)
                    break;
                double x;
                size_t used = 0;
                int r = conica__parse_double(buf + i, end - i, &x, &used);
                if (r == CONICA__NUM_OK && i + used < end && !is_space(buf[i + used]))
                    r = CONICA__NUM_SYNTAX;
                if (r != CONICA__NUM_OK) {
                    size_t te = i;
                    while (te < end && !is_space(buf[te]))
                        te++;
                    rc = conica__fail(st, r == CONICA__NUM_NONFINITE ? CONICA_ERR_NONFINITE
                                                                     : CONICA_ERR_PARSE,
                                      line, i, "%s '%.*s'",
                                      r == CONICA__NUM_NONFINITE ? "non-finite number"
                                                                 : "bad number",
                                      (int)(te - i > 40 ? 40 : te - i), buf + i);
                    break;
                }
                i += used;
                if (kind == K_KNOTS || kind == K_W) {
                    dvec *a = kind == K_KNOTS ? &knots : &wts;
                    if (a->n >= max_values) {
                        rc = conica__fail(st, CONICA_ERR_LIMIT, line, i,
                                          "more than %zu values (max_ctrl + max_degree + 1)",
                                          max_values);
                        break;
                    }
                    if (!dvec_push(a, x, line)) {
                        rc = conica__fail(st, CONICA_ERR_NOMEM, line, i, "out of memory");
                        break;
                    }
                } else {
                    if (count >= (kind == K_DEG ? 1 : 3)) {
                        rc = conica__fail(st, CONICA_ERR_PARSE, line, i, "too many numbers for '%s'",
                                          kind == K_DEG ? "degree" : "c");
                        break;
                    }
                    vals[count] = x;
                }
                count++;
            }
            if (rc != CONICA_OK)
                break;
            if (kind == K_DEG) {
                if (degree >= 0) {
                    rc = conica__fail(st, CONICA_ERR_PARSE, line, ks,
                                      "degree given twice (first on line %zu)", degree_line);
                    break;
                }
                /* range before the integer test: (long)1e30 is undefined */
                if (count != 1 || !(vals[0] >= 1) ||
                    (vals[0] <= CONICA_BSPLINE_MAX_DEGREE && vals[0] != (double)(long)vals[0])) {
                    rc = conica__fail(st, CONICA_ERR_PARSE, line, ks,
                                      "degree needs one positive integer");
                    break;
                }
                if (vals[0] > lim->max_degree) {
                    rc = conica__fail(st, CONICA_ERR_LIMIT, line, ks, "degree %.0f exceeds %d%s",
                                      vals[0], lim->max_degree,
                                      lim->max_degree < CONICA_BSPLINE_MAX_DEGREE
                                          ? " (max_degree)" : "");
                    break;
                }
                degree = (int)vals[0];
                degree_line = line;
            } else if (kind == K_C) {
                if (count == 0) {
                    rc = conica__fail(st, CONICA_ERR_PARSE, line, ks,
                                      "control point needs 1 to 3 numbers");
                    break;
                }
                if (dim == 0)
                    dim = count;
                else if (count != dim) {
                    rc = conica__fail(st, CONICA_ERR_PARSE, line, ks,
                                      "control point has %d numbers, earlier ones have %d", count,
                                      dim);
                    break;
                }
                if (ncpts >= lim->max_ctrl) {
                    rc = conica__fail(st, CONICA_ERR_LIMIT, line, ks,
                                      "more than %zu control points (max_ctrl)", lim->max_ctrl);
                    break;
                }
                for (int q = 0; q < count && rc == CONICA_OK; q++)
                    if (!dvec_push(&ctrl, vals[q], line))
                        rc = conica__fail(st, CONICA_ERR_NOMEM, line, ks, "out of memory");
                ncpts++;
            } else if (count == 0) {
                rc = conica__fail(st, CONICA_ERR_PARSE, line, ks, "'%s' without numbers",
                                  kind == K_KNOTS ? "knots" : "w");
            }
        }
        pos = eol + 1;
        line++;
    }
    if (rc == CONICA_OK) {
        size_t last = line > 1 ? line - 1 : 1;
        if (degree < 0)
            rc = conica__fail(st, CONICA_ERR_PARSE, last, len, "missing 'degree' line");
        else if (knots.n == 0)
            rc = conica__fail(st, CONICA_ERR_PARSE, last, len, "missing 'knots' line");
        else if (ncpts == 0)
            rc = conica__fail(st, CONICA_ERR_PARSE, last, len, "missing 'c' lines");
        else if (wts.n && wts.n != ncpts)
            rc = conica__fail(st, CONICA_ERR_PARSE, wts.line[wts.n - 1], len,
                              "%zu weights for %zu control points", wts.n, ncpts);
        else if (knots.n != ncpts + (size_t)degree + 1)
            rc = conica__fail(st, CONICA_ERR_PARSE, knots.line[knots.n - 1], len,
                              "%zu knots, but %zu control points of degree %d need %zu",
                              knots.n, ncpts, degree, ncpts + (size_t)degree + 1);
    }
    if (rc == CONICA_OK) {
        int where;
        size_t idx;
        conica_status tmp;
        rc = conica__bspline_check(degree, dim, knots.v, knots.n, ctrl.v, ncpts,
                                   wts.n ? wts.v : NULL, 0, &where, &idx, &tmp);
        if (rc != CONICA_OK) {
            size_t l = degree_line;
            if (where == CONICA__AT_KNOT)
                l = knots.line[idx];
            else if (where == CONICA__AT_CTRL)
                l = ctrl.line[idx * (size_t)dim];
            else if (where == CONICA__AT_WEIGHT)
                l = wts.line[idx];
            rc = conica__fail(st, rc, l, 0, "%s", tmp.message);
        }
    }
    if (rc == CONICA_OK)
        rc = conica_bspline_set(degree, dim, knots.v, knots.n, ctrl.v, ncpts,
                                wts.n ? wts.v : NULL, out, st);
    dvec_free(&knots);
    dvec_free(&ctrl);
    dvec_free(&wts);
    return rc;
}
