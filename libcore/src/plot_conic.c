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

/* conica__r2_step: stop when a step changes lam by at most this fraction
 * of it (D ~ lam^2: within twice that of T); at most R2_ITER steps. */
#define R2_STOP 1e-3
#define R2_ITER 8

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

/* Longest chord in closed form. For the remainder R (homogeneous points
 * R_i = (x_i w_i, y_i w_i, w_i)) and its sub-arc [0, lam] (de Casteljau:
 * Q_0 = R_0, Q_1 = (1 - lam) R_0 + lam R_1, Q_2 = R(lam)), the middle
 * point's distance to the chord's line is det[Q_0, Q_1, Q_2] /
 * (w(Q_0) w(Q_1) w(Q_2) |b - a|), with det[Q_0, Q_1, Q_2] =
 * lam^3 det[R_0, R_1, R_2] = lam^3 w_0 (u x v), u = R_1 - a w_1,
 * v = R_2 - a w_2 (spatial parts, a = R_0 / w_0), and
 * b - a = lam e / W(lam), e = 2 (1 - lam) u + lam v. Times the standard
 * form's w / (1 + w), w = w(Q_1) / sqrt(w_0 W(lam)) (conica__r2_absmax),
 *   D(lam) = lam^2 |u x v| / (|e| (w(Q_1) + sqrt(w_0 W(lam)))),
 * whose root D = T is the fixed point of
 *   lam = sqrt(T |e| (w(Q_1) + sqrt(w_0 W)) / |u x v|),
 * a function of lam that varies by O(lam) only: a few steps from the
 * guess (or from lam = 0). */
double conica__r2_step(const double *R, double T, double lam, size_t *evals)
{
    double w0 = R[2], w1 = R[5], w2 = R[8], ax = R[0] / w0, ay = R[1] / w0;
    double ux = R[3] - ax * w1, uy = R[4] - ay * w1, vx = R[6] - ax * w2, vy = R[7] - ay * w2;
    double cr = fabs(ux * vy - uy * vx);
    if (!(cr > 0.0))
        return 2.0; /* straight */
    double k = T / cr;
    lam = lam > 0.0 && lam < 1.0 ? lam : 0.0;
    for (int it = 0; it < R2_ITER; it++) {
        double v = 1.0 - lam, ex = 2.0 * v * ux + lam * vx, ey = 2.0 * v * uy + lam * vy;
        double W = v * (v * w0 + 2.0 * lam * w1) + lam * lam * w2, wq = w0 + lam * (w1 - w0);
        ++*evals;
        if (!(W > 0.0))
            break;
        double e2 = ex * ex + ey * ey, sw = sqrt(w0 * W), S = wq + sw;
        double nl = sqrt(k * sqrt(e2) * S);
        if (nl >= 1.0 && lam >= 1.0)
            return 2.0; /* the whole remainder is within T */
        /* The map's slope c = g'(lam) = g/2 (|e|'/|e| + S'/S), S = w(Q_1) +
         * sqrt(w_0 W), from the values at hand (off the chain of square
         * roots): Newton's step lam + (g - lam) / (1 - c) on g(lam) = lam,
         * done when what a plain step would leave (c times its change) is
         * within R2_STOP. Near a chord of a few hundredths of the
         * remainder c is about lam / 4: one evaluation where the plain
         * iteration needed two. */
        double dex = vx - 2.0 * ux, dey = vy - 2.0 * uy;
        double dW = 2.0 * (lam * w2 - v * w0 + (v - lam) * w1);
        double c = 0.5 * nl * ((ex * dex + ey * dey) / e2 + ((w1 - w0) + w0 * dW / (2.0 * sw)) / S);
        double dl = nl - lam;
        int newton = isfinite(c) && fabs(c) < 0.5;
        int done = newton ? fabs(c * dl) <= R2_STOP * nl : fabs(dl) <= R2_STOP * nl;
        double nx = newton ? lam + dl / (1.0 - c) : nl;
        lam = nx < 1.0 ? (nx > 0.0 ? nx : nl) : 1.0;
        if (done)
            break;
    }
    return lam;
}
