/* SPDX-License-Identifier: MIT */
/* Internal B-spline helpers shared by bspline*.c, plot*.c and surface.c. */
#ifndef CONICA_BSPLINE_INTERNAL_H
#define CONICA_BSPLINE_INTERNAL_H

#include <stddef.h>

#include "conica/bspline.h"

/* Largest homogeneous dimension: 3 coordinates + weight. */
#define CONICA__HDIM_MAX 4

/* Where a validation failure sits (for the parser's line numbers). */
enum { CONICA__AT_NONE = 0, CONICA__AT_KNOT, CONICA__AT_CTRL, CONICA__AT_WEIGHT };

/* Validate raw arrays as conica_bspline_set does; on failure fill st,
 * *where and *index (the offending knot / control point / weight). When
 * allow_high_mult is set, multiplicities > p+1 are accepted (make_regular
 * trims them). */
conica_code conica__bspline_check(int degree, int dim, const double *knots, size_t nknots,
                                  const double *ctrl, size_t n, const double *w,
                                  int allow_high_mult, int *where, size_t *index,
                                  conica_status *st);

/* Span mu of x in knots[0..nk) for degree p with p <= mu <= n-1 (n = nk-p-1):
 * knots[mu] <= x < knots[mu+1]; x >= knots[n] gives the last non-empty span.
 * left != 0 selects knots[mu] < x <= knots[mu+1] instead (x > knots[p]). */
size_t conica__find_span(const double *knots, size_t nk, int p, double x, int left);

/* Triangular algorithm (eq. (1.11)) on hd-dimensional homogeneous points:
 * d holds the p+1 local coefficients c_{mu-p..mu} (hd values each) and is
 * overwritten column by column; knots points at the full knot vector and
 * mu is the span. If left_edge / right_edge are not NULL they receive the
 * p+1 points of the left / right diagonals of the triangle, i.e. the
 * control points of the two halves after inserting x p times (left_edge
 * ends and right_edge starts with the value at x). Returns the number of
 * flops spent. */
double conica__deboor(const double *knots, size_t mu, int p, double x, int hd,
                      double *d, double *left_edge, double *right_edge);

/* Homogeneous copy of control points [i0, i0+cnt): hd = dim (+1 if rational). */
void conica__homog(const conica_bspline *s, size_t i0, size_t cnt, double *out);
/* Homogeneous dimension of s. */
int conica__hdim(const conica_bspline *s);

/* Copy of s clamped to its domain (end knots of multiplicity p+1). */
conica_code conica__bspline_clamp(const conica_bspline *s, conica_bspline *out,
                                  conica_status *st);
/* Insert z into s (in place) count times without atomic copy (s may be
 * partially updated on NOMEM/LIMIT: callers work on scratch copies). */
conica_code conica__insert_raw(conica_bspline *s, double z, size_t count, conica_status *st);

/* Deep copy. */
conica_code conica__bspline_copy(const conica_bspline *s, conica_bspline *out,
                                 conica_status *st);

#endif
