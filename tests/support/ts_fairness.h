/* SPDX-License-Identifier: MIT */
/*
 * ts_fairness.h - fairness of a polyline's discrete curvature, for the
 * fairness tests and bench_fairness (issue 20). Shares no code with libcore.
 *
 * The discrete curvature at vertex i is the signed curvature of the circle
 * through vertices i-1, i, i+1 (positive for a counter-clockwise turn). Its
 * total variation is sum |kappa_{i+1} - kappa_i| over consecutive vertices
 * (cyclically for a closed polyline; open ones have no curvature at their
 * two ends). A sign change is a pair of consecutive curvatures of opposite
 * signs, skipping curvatures whose magnitude is at most
 * TS_FAIR_ZERO_REL times the largest (straight runs, where rounding alone
 * decides the sign).
 */
#ifndef TS_FAIRNESS_H
#define TS_FAIRNESS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TS_FAIR_ZERO_REL 1e-9
/* A normal counts as inside its vertex's cone to within this sine. */
#define TS_FAIR_CONE_TOL 1e-9

typedef struct ts_fairness {
    double tv;           /* total variation of the discrete curvature */
    double kmax;         /* largest |kappa| */
    size_t sign_changes; /* sign changes of kappa (see above) */
} ts_fairness;

/** Signed curvature of the circle through a, b, c (0 if two coincide). */
double ts_circle_curvature(const double a[2], const double b[2], const double c[2]);

/** Measure the polyline xy (n vertices, interleaved x,y). Returns 0, or -1
 *  when n < 3 (no curvature) or memory runs out. */
int ts_fairness_measure(const double *xy, size_t n, int closed, ts_fairness *out);

/** Does the normal nrm of vertex b (edges a -> b -> c) lie outside the
 *  cone of the two edges' normals (either orientation), i.e. its tangent
 *  not between the edge directions? 1 or 0 (0 for a zero edge or normal
 *  and for collinear edges, which have no cone). */
int ts_normal_outside_cone(const double a[2], const double b[2], const double c[2],
                           const double nrm[2]);

/** Vertices of the point-normal polygon (xy, nxy: n vertices) whose normal
 *  lies outside the cone of its two edges' normals (either orientation):
 *  its tangent does not lie between the incoming and outgoing edge
 *  directions, so no arc that turns the polygon's way leaves the vertex
 *  along both edges. Open polygons' end vertices are not counted. Returns
 *  the count; *first (if not NULL) gets the first such vertex. nxy NULL:
 *  0. */
size_t ts_normals_outside_cone(const double *xy, const double *nxy, size_t n, int closed,
                               size_t *first);

#ifdef __cplusplus
}
#endif

#endif
