/* SPDX-License-Identifier: MIT */
/* Exact chord deviation of a planar rational quadratic (a conic arc: the
 * circles, ellipses and NURBS conics of Dahl 2019, §1.3, rational
 * B-splines) for the guaranteed plotter (plot_guaranteed.c): the largest
 * value of a rational quadratic scalar form, the deviation of the chord
 * [f(0), f(lam)] of a Bézier remainder, and the longest chord within a
 * tolerance. Pure arithmetic on caller arrays; calls only libm.
 *
 * Why closed forms. The certificate of plot_guaranteed.c (step 2) bounds
 * the distance of the arc to its chord by the signed-distance form
 * s(u) = sum B_i(u) w_i s_i / sum B_i(u) w_i of the sub-arc's control
 * points (Dahl 2019, §1.3, the convex hull property for rational splines,
 * Lemma 1.13). For degree 2 that form is the quotient of two quadratics,
 * whose derivative's numerator N' W - N W' is again a quadratic (the
 * cubic terms cancel), so its largest |value| is attained at u = 0, 1 or
 * one of at most two closed-form roots: the exact deviation, where the
 * control-point coefficients alone over-estimate a shallow arc by up to
 * 2x (for the chord of the sub-arc itself, s_0 = s_2 = 0, the maximum is
 * |s_1| w_1 / (w_1 + sqrt(w_0 w_2)), at the standard-form midpoint). With
 * the exact deviation as a function of the chord's end, the longest chord
 * within T (the greedy optimum's chord) is its root, found in a few
 * steps of D ~ K lam^2 (Dahl 2019, Theorem 1.16: the control polygon
 * converges quadratically). */
#include <math.h>

#include "plot_internal.h"

/* r2_step: stop when D is within this fraction of T; at most R2_ITER
 * evaluations of the deviation; one step changes lam by a factor within
 * [R2_FMIN, R2_FMAX]. */
#define R2_STOP 2e-3
#define R2_ITER 6
#define R2_FMIN 0.25
#define R2_FMAX 4.0

/* |N / W| at u (power-basis coefficients n0..n2, d0..d2). */
static double r2_val(double n0, double n1, double n2, double d0, double d1, double d2, double u)
{
    double N = n0 + u * (n1 + u * n2), W = d0 + u * (d1 + u * d2);
    return fabs(N / W);
}

double conica__r2_absmax(const double *s, const double *w)
{
    double best = fabs(s[0]) > fabs(s[2]) ? fabs(s[0]) : fabs(s[2]);
    if (s[0] == 0.0 && s[2] == 0.0) /* the sub-arc's own chord: the standard form's midpoint */
        return fabs(s[1]) * w[1] / (w[1] + sqrt(w[0] * w[2]));
    double a0 = w[0] * s[0], a1 = w[1] * s[1], a2 = w[2] * s[2];
    double n0 = a0, n1 = 2.0 * (a1 - a0), n2 = a0 - 2.0 * a1 + a2;
    double d0 = w[0], d1 = 2.0 * (w[1] - w[0]), d2 = w[0] - 2.0 * w[1] + w[2];
    /* N' W - N W' = c0 + c1 u + c2 u^2 */
    double c0 = n1 * d0 - n0 * d1, c1 = 2.0 * (n2 * d0 - n0 * d2), c2 = n2 * d1 - n1 * d2;
    double u[2];
    int nu = 0;
    if (c2 != 0.0) {
        double disc = c1 * c1 - 4.0 * c2 * c0;
        if (disc >= 0.0) {
            double q = -0.5 * (c1 + copysign(sqrt(disc), c1));
            if (q != 0.0) {
                u[nu++] = q / c2;
                u[nu++] = c0 / q;
            } else {
                u[nu++] = 0.0;
            }
        }
    } else if (c1 != 0.0) {
        u[nu++] = -c0 / c1;
    }
    for (int i = 0; i < nu; i++)
        if (u[i] > 0.0 && u[i] < 1.0) {
            double v = r2_val(n0, n1, n2, d0, d1, d2, u[i]);
            best = v > best ? v : best;
        }
    return best;
}

double conica__r2_chord_dev(const double *R, double lam)
{
    double q1[3], r1[3], q2[3];
    for (int c = 0; c < 3; c++) {
        q1[c] = R[c] + lam * (R[3 + c] - R[c]);
        r1[c] = R[3 + c] + lam * (R[6 + c] - R[3 + c]);
        q2[c] = q1[c] + lam * (r1[c] - q1[c]);
    }
    double ax = R[0] / R[2], ay = R[1] / R[2];
    double mx = q1[0] / q1[2] - ax, my = q1[1] / q1[2] - ay;
    double cx = q2[0] / q2[2] - ax, cy = q2[1] / q2[2] - ay;
    double c2 = cx * cx + cy * cy;
    if (!(c2 > 0.0) || !(R[2] * q2[2] > 0.0))
        return 0.0;
    double s = fabs(mx * cy - my * cx) / sqrt(c2);
    return s * q1[2] / (q1[2] + sqrt(R[2] * q2[2]));
}

double conica__r2_step(const double *R, double T, double lam, size_t *evals)
{
    lam = lam > 0.0 && lam < 1.0 ? lam : 1.0;
    for (int it = 0; it < R2_ITER; it++) {
        double D = conica__r2_chord_dev(R, lam);
        ++*evals;
        if (lam >= 1.0 && D <= T)
            return 2.0; /* the whole remainder */
        double f = D > 0.0 ? sqrt(T / D) : R2_FMAX; /* D ~ K lam^2 */
        f = f < R2_FMIN ? R2_FMIN : (f > R2_FMAX ? R2_FMAX : f);
        double nl = lam * f;
        if (fabs(D - T) <= R2_STOP * T)
            break;
        lam = nl < 1.0 ? nl : 1.0;
    }
    return lam;
}
