/* SPDX-License-Identifier: MIT */
/* Profile storage, status helpers and the exact orientation predicate. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void conica_scad_profile_init(conica_scad_profile *p)
{
    if (p)
        memset(p, 0, sizeof *p);
}

void conica_scad_profile_free(conica_scad_profile *p)
{
    if (!p)
        return;
    for (size_t i = 0; i < p->ncontours; i++)
        free(p->contours[i].xy);
    free(p->contours);
    free(p->groups);
    memset(p, 0, sizeof *p);
}

conica_code conica_scad_add_group(conica_scad_profile *p, const char *name, conica_scad_fill fill,
                                  size_t line, size_t *index, conica_status *st)
{
    if (!p || (fill != CONICA_SCAD_FILL_NONZERO && fill != CONICA_SCAD_FILL_EVENODD))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid argument");
    if (p->ngroups >= CONICA_SCAD_MAX_CONTOURS)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "more than %zu groups",
                                 (size_t)CONICA_SCAD_MAX_CONTOURS);
    if (p->ngroups == p->gcap) {
        size_t ncap = p->gcap ? 2 * p->gcap : 8;
        conica_scad_group *g = realloc(p->groups, ncap * sizeof *g);
        if (!g)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        p->groups = g;
        p->gcap = ncap;
    }
    conica_scad_group *g = &p->groups[p->ngroups];
    memset(g, 0, sizeof *g);
    if (name) {
        size_t len = strlen(name);
        if (len >= sizeof g->name)
            len = sizeof g->name - 1;
        memcpy(g->name, name, len);
        g->name[len] = '\0';
    }
    g->fill = fill;
    g->line = line;
    if (index)
        *index = p->ngroups;
    p->ngroups++;
    conica__ok(st);
    return CONICA_OK;
}

conica_code conica_scad_add_contour(conica_scad_profile *p, size_t group, const double *xy,
                                    size_t n, conica_status *st)
{
    size_t total;
    if (!p || !xy || n == 0 || group >= p->ngroups)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "invalid argument");
    for (size_t i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i]))
            return conica__fail(st, CONICA_ERR_NONFINITE, 0, i / 2,
                                     "point %zu is not finite", i / 2 + 1);
    /* a running count: summing the contours here made n additions
     * quadratic (160 000 small paths: seconds in this loop alone) */
    total = p->npoints;
    if (p->ncontours >= CONICA_SCAD_MAX_CONTOURS || n > CONICA_SCAD_MAX_POINTS - total)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                 "profile larger than %zu contours or %zu points",
                                 (size_t)CONICA_SCAD_MAX_CONTOURS, (size_t)CONICA_SCAD_MAX_POINTS);
    if (p->ncontours == p->ccap) {
        size_t ncap = p->ccap ? 2 * p->ccap : 8;
        conica_scad_contour *c = realloc(p->contours, ncap * sizeof *c);
        if (!c)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        p->contours = c;
        p->ccap = ncap;
    }
    double *copy = malloc(2 * n * sizeof *copy);
    if (!copy)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    memcpy(copy, xy, 2 * n * sizeof *copy);
    p->contours[p->ncontours].group = group;
    p->contours[p->ncontours].subpath =
        p->ncontours > 0 && p->contours[p->ncontours - 1].group == group
            ? p->contours[p->ncontours - 1].subpath + 1
            : 1;
    p->contours[p->ncontours].n = n;
    p->contours[p->ncontours].xy = copy;
    p->ncontours++;
    p->npoints += n;
    conica__ok(st);
    return CONICA_OK;
}

double conica__scad_area2(const double *xy, size_t n)
{
    /* Shoelace relative to the first point (no cancellation from where the
     * contour sits), summed with Neumaier compensation. */
    double s = 0.0, comp = 0.0;
    if (n < 3)
        return 0.0;
    double x0 = xy[0], y0 = xy[1];
    for (size_t i = 1; i + 1 < n; i++) {
        double ax = xy[2 * i] - x0, ay = xy[2 * i + 1] - y0;
        double bx = xy[2 * i + 2] - x0, by = xy[2 * i + 3] - y0;
        double t = ax * by - ay * bx;
        double u = s + t;
        comp += fabs(s) >= fabs(t) ? (s - u) + t : (t - u) + s;
        s = u;
    }
    return s + comp;
}
