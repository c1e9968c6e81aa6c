/* SPDX-License-Identifier: MIT */
/*
 * fidelity.h - an independent checker of polylines against exact curves.
 *
 * Shares no code with libcore: tools' output (polylines, interleaved x,y)
 * is measured against ts_contour curves (glyphs.h, or built by the test).
 *
 *     ts_poly p = {xy, n, 1};
 *     ts_hausdorff h;
 *     ts_sampling s = ts_sampling_defaults();
 *     if (ts_hausdorff_measure(&contour, 1, &p, 1, &s, &h) == TS_OK)
 *         CHECK_LE(h.max, tol);
 *
 * Distances are Euclidean in the curves' units. Curve-side extrema are found
 * by dense sampling (ts_sampling.per_seg per segment) and then a
 * golden-section search in the bracket around the best sample, so they are
 * accurate to ~1e-12 of the size unless the sampling misses a whole basin
 * (use more samples for segments that wiggle within 1/per_seg of their
 * parameter range). The crossing and corner tests use plain double
 * arithmetic: not robust for nearly collinear edges.
 */
#ifndef TS_FIDELITY_H
#define TS_FIDELITY_H

#include "ts_outline.h"

/** A polyline: xy[2*i], xy[2*i+1] is vertex i; closed adds the edge
 *  n-1 -> 0. Edge i runs from vertex i to vertex (i + 1) % n. */
typedef struct ts_poly {
    const double *xy;
    size_t n;
    int closed;
} ts_poly;

/** A place on curves: contour index, segment index, parameter in [0, 1]. */
typedef struct ts_curve_place {
    size_t contour, seg;
    double t;
} ts_curve_place;

/** A place on polylines: polyline index, edge index, fraction in [0, 1]. */
typedef struct ts_poly_place {
    size_t poly, edge;
    double u;
} ts_poly_place;

/** Sampling density. */
typedef struct ts_sampling {
    size_t per_seg;  /**< curve samples per segment (>= 2) */
    size_t per_edge; /**< interior points per polyline edge (>= 1) */
} ts_sampling;

/** per_seg 64, per_edge 8. */
ts_sampling ts_sampling_defaults(void);

/* Largest per_seg / per_edge the functions accept (caps the work). */
#define TS_MAX_SAMPLES ((size_t)1 << 16)

/** Point of segment `s` at t (rational quadratics included). */
void ts_seg_eval(const ts_seg *s, double t, double out[2]);
/** Derivative d/dt of ts_seg_eval at t. */
void ts_seg_deriv(const ts_seg *s, double t, double out[2]);

/** Dense samples of a contour: per_seg points per segment at t = k/per_seg,
 *  k < per_seg, plus the last end point when the contour is open. Every
 *  segment end is a sample, so corners are vertices of the result.
 *  @param[out] xy  interleaved, caller frees; untouched on failure
 *  @param[out] n   number of points
 *  @return TS_OK, TS_ERR_ARG (no segments, bad degree, per_seg 0 or above
 *          TS_MAX_SAMPLES), TS_ERR_NOMEM */
ts_code ts_contour_sample(const ts_contour *c, size_t per_seg, double **xy, size_t *n);

/** Distance from q to the union of contours c[0..nc), with the nearest place
 *  in *where (NULL to ignore). +inf when there is no segment. */
double ts_dist_to_curve(const ts_contour *c, size_t nc, const double q[2], size_t per_seg,
                        ts_curve_place *where);
/** Exact distance from q to the union of polylines p[0..np) (+inf if empty). */
double ts_dist_to_poly(const ts_poly *p, size_t np, const double q[2], ts_poly_place *where);

/** Both directed Hausdorff distances and where they are attained. */
typedef struct ts_hausdorff {
    double poly_to_curve;        /**< max over polyline points of the distance to the curves */
    ts_poly_place poly_worst;    /**< where on the polylines */
    ts_curve_place poly_nearest; /**< the nearest curve place to it */
    double curve_to_poly;        /**< max over curve points of the distance to the polylines */
    ts_curve_place curve_worst;
    ts_poly_place curve_nearest;
    double max; /**< the Hausdorff distance: max of the two */
} ts_hausdorff;

/** Hausdorff distance between contours c[0..nc) and polylines p[0..np).
 *  Polyline side: every vertex and s->per_edge points inside every edge,
 *  the worst edge point refined by golden section. Curve side: per_seg
 *  samples per segment, refined likewise.
 *  @param[in] s  NULL for ts_sampling_defaults()
 *  @return TS_OK, TS_ERR_ARG (nothing to measure, a polyline without
 *          vertices, bad degree or sampling); *out untouched on failure */
ts_code ts_hausdorff_measure(const ts_contour *c, size_t nc, const ts_poly *p, size_t np,
                             const ts_sampling *s, ts_hausdorff *out);

/** Signed area enclosed by a contour (counter-clockwise positive, y up),
 *  closed by a straight line if its ends differ. Green's theorem per
 *  segment by Gauss-Legendre quadrature: exact (to rounding) for lines and
 *  polynomial Beziers, ~1e-15 relative for rational arcs. */
double ts_contour_area(const ts_contour *c);
/** Sum of ts_contour_area over an outline (its nonzero-rule area when the
 *  contours do not cross and are oriented as TrueType's, negated). */
double ts_outline_area(const ts_outline *o);
/** Shoelace area of the closed polygon xy[0..n) (interleaved). */
double ts_poly_area(const double *xy, size_t n);

/** One proper crossing: two edges meeting at a single point inside both
 *  (touching at a vertex, or collinear overlap, is not a crossing). */
typedef struct ts_crossing {
    ts_poly_place a, b; /**< a.poly <= b.poly; u is the crossing's fraction */
    double p[2];
} ts_crossing;

/** Count proper crossings between edges of different polylines and, when
 *  `within` is set, between edges of the same polyline (self-intersection).
 *  Sort-and-sweep on x with a y-overlap prefilter.
 *  @param[out] count  number of crossing pairs of edges
 *  @param[out] first  the first crossing found, or NULL
 *  @return TS_OK, TS_ERR_NOMEM */
ts_code ts_poly_crossings(const ts_poly *p, size_t np, int within, size_t *count,
                          ts_crossing *first);

/** A corner of a contour: the join at the end of segment `seg` (and start
 *  of the next), where the tangent turns by `turn` radians (signed,
 *  positive = left, in (-pi, pi]). */
typedef struct ts_corner {
    size_t seg;
    double p[2];
    double turn;
} ts_corner;

/** Joins of `c` whose tangent turn exceeds min_turn radians in magnitude
 *  (the last-to-first join counts when c->closed). Tangents at segment ends
 *  come from the nearest distinct control point, so a degenerate handle
 *  does not fake a corner.
 *  @param[out] out  caller frees (NULL when *n == 0); untouched on failure
 *  @return TS_OK, TS_ERR_ARG (bad degree), TS_ERR_NOMEM */
ts_code ts_contour_corners(const ts_contour *c, double min_turn, ts_corner **out, size_t *n);

/** Result of ts_corners_kept. */
typedef struct ts_corner_check {
    size_t kept, missing;
    size_t first_missing;      /**< index into the corners, when missing > 0 */
    double first_missing_turn; /**< the polyline's turn there; NaN when no
                                    vertex was within pos_tol */
} ts_corner_check;

/** Did each corner stay a corner? A corner is kept when some polyline
 *  vertex lies within pos_tol of it and the polyline turns there (between
 *  its neighbours farther than pos_tol away) by at least |turn| - slack
 *  radians. Orientation is not compared (a reversed polyline is fine).
 *  @return TS_OK, TS_ERR_ARG (pos_tol < 0) */
ts_code ts_corners_kept(const ts_corner *k, size_t nk, const ts_poly *p, size_t np,
                        double pos_tol, double slack, ts_corner_check *out);

/** Max relative radial error of points against an ellipse with centre
 *  `center`, semi-axes rx, ry, rotated by rot radians: max over points of
 *  |rho - 1| with rho = |(x'/rx, y'/ry)| in the ellipse's frame (for a
 *  circle exactly |distance to centre - r| / r). Index of the worst point in
 *  *worst (NULL to ignore); 0 for n == 0. */
double ts_ellipse_radial_error(const double *xy, size_t n, const double center[2], double rx,
                               double ry, double rot, size_t *worst);

#endif /* TS_FIDELITY_H */
