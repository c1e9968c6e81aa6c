/* SPDX-License-Identifier: MIT */
/* The working origin of subdivision (default mode): the point the levels'
 * coordinates are measured from, so that where a curve sits does not
 * change what they compute or what it costs. Called by subdiv_impl.h's
 * SFX(run); reads the input points only, calls nothing.
 *
 * Why. Every level stores its new points, and each stored coordinate is
 * rounded to the unit in the last place of its magnitude. Deep levels
 * bring the sagitta of an edge (e^2 / 8r) down towards that unit: the
 * blob of radius 5 with 10^6 points at (5000, 3000) has edges of 2e-6 at
 * level 4, a sagitta of 1e-13 and a rounding of 4.5e-13 (2^-41) there,
 * against 4.4e-16 at the origin. Its chords' directions then carry
 * errors as large as the end normals' tilt against them (2e-7 rad), the
 * patches look S-shaped, and 7 % of the edges went to the general fit
 * (SVD) and grew: 4.3x the origin's CPU. Measured from a point inside the
 * curve's box, the levels' points keep the rounding of the curve's own
 * size, as at the origin; the caller adds the origin back once, at the end.
 *
 * The origin, per coordinate: the centre c of the points' range [lo, hi]
 * when |c| >= hi - lo, else 0 (a curve around the origin computes as it
 * always did, bit for bit). Then every point p lies in [c/2, 3c/2], so
 * p - c is exact (Sterbenz's lemma) and (p - c) + c gives p back: the
 * input points stay the output's old vertices bit for bit. */
#include <math.h>
#include <stddef.h>

#include "internal.h"

void conica__subdiv_origin(const double *xyd, const long double *xyl, size_t n, long double c[2])
{
    for (size_t d = 0; d < 2; d++) {
        long double lo = 0, hi = 0, m;
        for (size_t k = 0; k < n; k++) {
            long double x = xyd ? (long double)xyd[2 * k + d] : xyl[2 * k + d];
            lo = k == 0 || x < lo ? x : lo;
            hi = k == 0 || x > hi ? x : hi;
        }
        m = 0.5L * lo + 0.5L * hi;
        if (xyd)
            m = (double)m; /* the double levels subtract a double */
        c[d] = isfinite(m) && fabsl(m) >= hi - lo ? m : 0.0L;
    }
}
