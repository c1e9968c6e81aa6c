/* SPDX-License-Identifier: MIT */
/* Type-generic core of conica_subdivide() (CONIS §1.1 with the
 * numerics of Section 2.3). subdiv.c includes this file twice: once with
 * REAL = double and once with REAL = long double, so that default and
 * precise mode run ONE implementation of the scheme.
 *
 * Required macros (undefined again at the end of this file):
 *   REAL          the floating type
 *   SFX(name)     name with a type suffix (name##_d / name##_l)
 *   M(fn)         the math function for REAL (fn / fn##l)
 *   FMA(a, b, c)  a*b + c, fused where the hardware fuses (double)
 *   RC(x)         a constant of type REAL
 *   R_EPSILON     machine epsilon of REAL
 *   REAL_IS_DOUBLE  1 for double (general fit through LAPACK), 0 otherwise
 *
 * Notation (CONIS): an edge p_i p_{i+1}, its midpoint m (4), its normal
 * n_edge = perp(p_{i+1} - p_i) (5); the new point lies on l(t) = m + t*n_edge
 * (7) and on the fitted conic (3).
 *
 * Local frame (issue 3, "exact anywhere"): every patch is mapped by the
 * similarity that sends the edge end points to (-1,0) and (1,0); the
 * bisector l(t) becomes the y axis, so the new point is (0, y) and maps back
 * to m + y*perp(h) with h the half edge. The scale factor 2^-e is a power of
 * two, so scaling itself is exact; results do not depend on position, size
 * or rotation beyond the rounding of the input coordinates. The levels'
 * points are stored relative to the working origin of subdiv_origin.c, so
 * that their own rounding is that of the curve's size, not of where it
 * sits.
 */

/* ------------------------------------------------------------------ types */

/* One point-normal pair of a patch, in the coordinates the fit uses. */
typedef struct SFX(pair) {
    REAL x, y, nx, ny; /* point and normal */
    REAL wv, wn;       /* point and normal weights (matrix W) */
} SFX(pair);

/* Read-only description of one level, shared by all workers. */
typedef struct SFX(job) {
    REAL wev, wen, wov, won; /* w_e^v, w_e^n, w_o^v = tau*w_o^n, w_o^n */
    int ref;                 /* reference-compatible: absolute coordinates + SVD */
    int fast;                /* closed-form pencil fit allowed */
    int plain;               /* ablation: textbook quadratic, no FMA */
    int normalize;           /* ablation: normalise sampled normals every level */
    int closed;
    int noisy;     /* settings.noise > 0: the input is rounded (SFX(make_frame)) */
    int maxgrow;   /* outer neighbours per side when growing a patch */
    size_t n;      /* points of the level being refined */
    const REAL *xy, *nxy;
    /* Inflection flags per point of this level (eq. (9) points and the
     * midpoints of S-shaped edges), or NULL; dinfl receives the next
     * level's (each worker writes its own edges' entries). */
    const unsigned char *infl;
    unsigned char *dinfl;
} SFX(job);

/* Per-thread state: fit workspace and counters. */
typedef struct SFX(worker) {
    const SFX(job) *job;
#if REAL_IS_DOUBLE
    conica__svdws *ws;
#endif
    size_t grown, fallbacks;
} SFX(worker);

/* Local frame of one edge (see the header comment). */
typedef struct SFX(frame) {
    REAL mx, my;   /* midpoint (4) */
    REAL hx, hy;   /* half edge (p1 - p0)/2 */
    REAL hsx, hsy; /* half edge times sc (a power of two): |hs| in [1, 2*sqrt2) */
    REAL sc, hh;   /* the power of two, |hs|^2 */
    REAL ihh;      /* 1 / hh */
    REAL straight; /* an end normal's sine along the chord at most this: none */
} SFX(frame);

/* ------------------------------------------------------------ arithmetic */

/* max(|a|, |b|) inline (libm's fmax is a call at -O2, for NaN rules we do
 * not need: callers check finiteness). */
static REAL SFX(maxabs)(REAL a, REAL b)
{
    a = M(fabs)(a);
    b = M(fabs)(b);
    return a > b ? a : b;
}

#if REAL_IS_DOUBLE
/* a*b - c*d with Kahan's FMA trick (CONIS, Code 4): error <= 1.5 ulp. */
static REAL SFX(diffprod)(REAL a, REAL b, REAL c, REAL d)
{
    REAL w = d * c;
    REAL e = FMA(-d, c, w);
    REAL f = FMA(a, b, -w);
    return f + e;
}
#else
/* a*b - c*d in long double: conica__diffprodl (subdiv.c). */
static REAL SFX(diffprod)(REAL a, REAL b, REAL c, REAL d)
{
    return conica__diffprodl(a, b, c, d);
}
#endif

/* a*b - c*d where the result only needs the working precision (frame
 * rotations, residuals): Kahan's form in double, where the FMAs are
 * hardware and nearly free; the plain form in long double, whose 11 extra
 * bits already cover it and where the exact form costs 2 x 17 flops. */
#if REAL_IS_DOUBLE
#define DIFFPROD_WP(a, b, c, d) SFX(diffprod)(a, b, c, d)
#else
#define DIFFPROD_WP(a, b, c, d) ((a) * (b) - (c) * (d))
#endif

/*
 * Root nearest 0 of a t^2 + 2 b t + c = 0 (eq. (8) written as in Section
 * 2.3). kind 0: stable form t = c / (-b - sign(b) sqrt(b^2 - ac)) with the
 * discriminant from diffprod; this is the root the reference's code picks
 * (eq. (12) prints the two branches swapped; the code and eq. (6) choose the
 * root nearest the midpoint) and it tends to -c/(2b) by itself as a -> 0,
 * without the cancellation of (-b + sqrt(...))/a. kind 1: the reference's
 * own evaluation, t = -c/(2b) when |a| <= CONICA__REF_A_EPS. kind 2
 * (ablation): textbook formula, no FMA.
 * Returns 1 and *t, or 0 when there is no real root.
 */
static CONICA__HOT_INLINE int SFX(nearest_root)(REAL a, REAL b, REAL c, int kind, REAL *t)
{
    REAL disc, r, den, t1, t2;

    if (kind == 1) {
        if (M(fabs)(a) <= RC(CONICA__REF_A_EPS)) {
            *t = -c / (2 * b);
            return isfinite(*t);
        }
        disc = SFX(diffprod)(b, b, a, c);
        if (!(disc >= 0))
            return 0;
        r = M(sqrt)(disc);
        *t = b < 0 ? (-b - r) / a : (-b + r) / a;
        return isfinite(*t);
    }
    if (kind == 2) {
        if (M(fabs)(a) <= RC(CONICA__REF_A_EPS) * M(fabs)(b)) {
            *t = -c / (2 * b);
            return isfinite(*t);
        }
        disc = b * b - a * c;
        if (!(disc >= 0))
            return 0;
        r = M(sqrt)(disc);
        t1 = (-b + r) / a;
        t2 = (-b - r) / a;
        *t = M(fabs)(t1) < M(fabs)(t2) ? t1 : t2;
        return isfinite(*t);
    }
    disc = SFX(diffprod)(b, b, a, c);
    if (!(disc >= 0))
        return 0;
    r = M(sqrt)(disc);
    den = b >= 0 ? -(b + r) : (r - b);
    if (den == 0) {
        /* a = b = 0: either every t solves it (c = 0, take the midpoint)
         * or none does. */
        if (c != 0)
            return 0;
        *t = 0;
        return 1;
    }
    *t = c / den;
    return isfinite(*t);
}

/* The root of a t^2 + 2 b t + c = 0 on the side `want` (+1: t > 0, -1:
 * t < 0) of t = 0, or the nearest root for want = 0 (SFX(nearest_root),
 * kind 0). The far root follows from the near one t1 by Vieta (t1 t2 =
 * c / a; t1 + t2 = -2b / a when t1 = 0), without the cancellation of
 * (-b +- sqrt(...)) / a. Used for the long arcs of SFX(long_arc), whose
 * point is not the nearest. Returns 1 and *t, or 0 when there is none. */
static int SFX(side_root)(REAL a, REAL b, REAL c, int want, REAL *t)
{
    REAL t1;
    if (!SFX(nearest_root)(a, b, c, 0, &t1))
        return 0;
    if (want == 0 || (want > 0 ? t1 > 0 : t1 < 0)) {
        *t = t1;
        return 1;
    }
    if (a == 0)
        return 0; /* one root only */
    *t = t1 != 0 ? (c / a) / t1 : -2 * b / a;
    return isfinite(*t) && (want > 0 ? *t > 0 : *t < 0);
}

/* ------------------------------------------------------- patch selection */

static size_t SFX(next)(const SFX(job) *j, size_t i)
{
    return i + 1 == j->n ? 0 : i + 1;
}

/* Point q in the rotated frame of SFX(frame) (edge from (-1,0) to (1,0)). */
static CONICA__HOT_INLINE void SFX(to_frame)(const SFX(job) *j, const SFX(frame) *f, size_t q,
                                             REAL *x, REAL *y)
{
    REAL wx = (j->xy[2 * q] - f->mx) * f->sc, wy = (j->xy[2 * q + 1] - f->my) * f->sc;
    *x = FMA(wx, f->hsx, wy * f->hsy) * f->ihh;
    *y = DIFFPROD_WP(f->hsx, wy, f->hsy, wx) * f->ihh;
}

/* Tolerance of SFX(line_class) for the edge of frame f: CONICA__ON_LINE_ULPS
 * rounding units of the patch's coordinates (eps * |p|) against the half
 * edge |h|, in the frame's units. */
static REAL SFX(on_line_tol)(const SFX(frame) *f)
{
    return RC(CONICA__ON_LINE_ULPS) * RC(CONICA__ON_LINE_EPS) *
           (1 + (M(fabs)(f->mx) + M(fabs)(f->my)) * f->sc);
}

/* Side of the edge line of the frame point (x, y): -1 above (y > 0), +1
 * below, 0 on the line to within tol (scaled by the distance along the
 * edge, where the frame's rotation errors grow). Points collinear by
 * construction (an inflection point (9), an S-shaped edge's midpoint and
 * the points next to them) are off the line only by rounding: their side
 * is the sign of a rounding error, which differs between default and
 * precise mode, so every branch that asks for a side asks here. */
static int SFX(line_class)(REAL tol, REAL x, REAL y)
{
    REAL lim = tol * (1 + M(fabs)(x));
    return y > lim ? -1 : (y < -lim ? 1 : 0);
}

/*
 * "Same half plane" rule for growing patches (REFERENCE.md section 1): a
 * further outer neighbour `cand` joins only if it lies on the same side as
 * the first outer neighbour `first` on that side. Default mode uses the edge
 * line p_i p_{i+1} as REFERENCE.md describes it (points on the line, to
 * within SFX(line_class)'s tolerance, count as the same side). Reference
 * mode reproduces the reference's areInSameHalfPlane(p_i, p_{i+1}, first,
 * cand) exactly, which measures against the line through p_{i+1} and
 * `first`.
 */
static int SFX(same_side)(const SFX(job) *j, const SFX(frame) *f, size_t i, size_t i1,
                          size_t first, size_t cand)
{
    const REAL *p = j->xy;
    if (j->ref) {
        REAL v0x = p[2 * i], v0y = p[2 * i + 1], v1x = p[2 * i1], v1y = p[2 * i1 + 1];
        REAL v2x = p[2 * first], v2y = p[2 * first + 1], v3x = p[2 * cand], v3y = p[2 * cand + 1];
        REAL ax = v3x - v1x, ay = v3y - v1y, bx = v0x - v1x, by = v0y - v1y;
        REAL nx = v2y - v1y, ny = v1x - v2x, d1, d2;
        if (bx * bx + by * by < RC(CONICA__REF_EPS) || ax * ax + ay * ay < RC(CONICA__REF_EPS))
            return 1;
        d1 = nx * ax + ny * ay;
        d2 = nx * bx + ny * by;
        if (M(fabs)(d1) < RC(CONICA__REF_EPS) || M(fabs)(d2) < RC(CONICA__REF_EPS))
            return 1;
        return d2 * (d1 > 0 ? 1 : -1) >= 0;
    } else {
        REAL tol = SFX(on_line_tol)(f), x, y;
        int s1, s2;
        SFX(to_frame)(j, f, first, &x, &y);
        s1 = SFX(line_class)(tol, x, y);
        SFX(to_frame)(j, f, cand, &x, &y);
        s2 = SFX(line_class)(tol, x, y);
        return s1 == 0 || s2 == 0 || s1 == s2;
    }
}

/*
 * Indices of the patch of edge (i, i+1): the two end points first, then up
 * to maxl outer neighbours to the left and maxr to the right. A side whose
 * edge end point is an inserted inflection point takes no neighbour beyond
 * it (CONIS, modified neighbourhoods after (10)). Open curves take the
 * neighbours that exist. In default mode a closed curve never wraps round
 * onto the patch's own points. f is the edge's frame (default mode; NULL in
 * reference mode). Returns the number of pairs.
 */
static int SFX(collect)(const SFX(job) *j, const SFX(frame) *f, size_t i, int maxl, int maxr,
                        size_t *idx)
{
    size_t n = j->n, i1 = SFX(next)(j, i), jj;
    int cnt = 2, k, nl = 0;

    idx[0] = i;
    idx[1] = i1;
    if (!(j->infl && j->infl[i])) {
        for (k = 1; k <= maxl; k++) {
            if (j->closed) {
                if (!j->ref && (size_t)k + 2 > n)
                    break;
                jj = i >= (size_t)k % n ? i - (size_t)k % n : i + n - (size_t)k % n;
            } else {
                if ((size_t)k > i)
                    break;
                jj = i - (size_t)k;
            }
            if (k > 1 && !SFX(same_side)(j, f, i, i1, idx[2], jj))
                break;
            idx[cnt++] = jj;
            nl++;
        }
    }
    if (!(j->infl && j->infl[i1])) {
        int first = cnt;
        for (k = 1; k <= maxr; k++) {
            if (j->closed) {
                if (!j->ref && (size_t)(nl + k) + 2 > n)
                    break;
                jj = i1 + (size_t)k % n;
                if (jj >= n)
                    jj -= n;
            } else {
                if (i1 + (size_t)k >= n)
                    break;
                jj = i1 + (size_t)k;
            }
            if (k > 1 && !SFX(same_side)(j, f, i, i1, idx[first], jj))
                break;
            idx[cnt++] = jj;
        }
    }
    return cnt;
}

/* Build the local frame of edge (i, i1); returns 0 for a zero-length edge.
 * f->straight: CONICA__FAST_MIN_SINE; for rounded input (settings.noise >
 * 0) at least CONICA__STRAIGHT_ULPS rounding units of the patch's
 * coordinates against the half edge (SFX(on_line_tol)'s measure): the
 * chord's own direction is that uncertain, so a smaller tilt of an end
 * normal is the rounding of a straight run's points (float32 grids, and
 * their in-plane rotation by Blender's add-on), whose sign says nothing. */
static int SFX(make_frame)(const SFX(job) *j, size_t i, size_t i1, SFX(frame) *f)
{
    const REAL *p = j->xy;
    REAL x0 = p[2 * i], y0 = p[2 * i + 1], x1 = p[2 * i1], y1 = p[2 * i1 + 1], mag;
    /* Halves first: exact (short of underflow) and free of overflow. */
    f->hx = RC(0.5) * x1 - RC(0.5) * x0;
    f->hy = RC(0.5) * y1 - RC(0.5) * y0;
    f->mx = RC(0.5) * x0 + RC(0.5) * x1;
    f->my = RC(0.5) * y0 + RC(0.5) * y1;
    mag = SFX(maxabs)(f->hx, f->hy);
    if (!(mag > 0) || !isfinite(mag))
        return 0;
#if REAL_IS_DOUBLE
    f->sc = conica__inv_pow2(mag);
#else
    f->sc = M(ldexp)(RC(1.0), -M(ilogb)(mag));
#endif
    f->hsx = f->hx * f->sc;
    f->hsy = f->hy * f->sc;
    f->hh = FMA(f->hsx, f->hsx, f->hsy * f->hsy);
    f->ihh = 1 / f->hh;
    f->straight = RC(CONICA__FAST_MIN_SINE);
    if (j->noisy) {
        REAL r = RC(CONICA__STRAIGHT_ULPS) * RC(CONICA__ON_LINE_EPS) *
                 (1 + (M(fabs)(f->mx) + M(fabs)(f->my)) * f->sc);
        f->straight = r > f->straight ? r : f->straight;
    }
    return 1;
}

/* Map the patch into the local frame: end points exactly (-1,0), (1,0),
 * unit normals, weights from W (CONIS, step 2). */
static void SFX(local_pairs)(const SFX(job) *j, const SFX(frame) *f, const size_t *idx, int cnt,
                             SFX(pair) *P)
{
    int k;
    for (k = 0; k < cnt; k++) {
        size_t q = idx[k];
        REAL nx = j->nxy[2 * q], ny = j->nxy[2 * q + 1], lx, ly, len;
        if (k < 2) {
            P[k].x = k == 0 ? RC(-1.0) : RC(1.0);
            P[k].y = 0;
            P[k].wv = j->wev;
            P[k].wn = j->wen;
        } else {
            SFX(to_frame)(j, f, q, &P[k].x, &P[k].y);
            P[k].wv = j->wov;
            P[k].wn = j->won;
        }
        /* Rotate the normal by the frame (scale irrelevant), then make it
         * unit so that the fit's weights mean the same at every level. */
        lx = FMA(nx, f->hsx, ny * f->hsy);
        ly = DIFFPROD_WP(f->hsx, ny, f->hsy, nx);
        len = 1 / M(sqrt)(FMA(lx, lx, ly * ly));
        P[k].nx = lx * len;
        P[k].ny = ly * len;
    }
}

/* ----------------------------------------------------------- fast path */

/*
 * Closed-form fit for the local frame (issue 3's hint). As w_e -> infinity
 * the weighted fit of step 2 is forced through both end points with their
 * normals; those conics form the pencil
 *     C = mu * L0 * L1 + lam * y^2,
 * L0 = a0 (x+1) + b0 y and L1 = a1 (x-1) + b1 y the tangent lines at
 * (-1,0) and (1,0) (normals (a0,b0), (a1,b1)), y = 0 the chord. The ratio
 * mu : lam is fitted to the outer pairs by weighted least squares (point
 * residual C(p) with weight w_o^v, normal residual cross(grad C(p), n) with
 * weight w_o^n, both linear in (mu, lam)) as the smallest eigenvector of
 * the 2x2 normal matrix. With no outer pair (an open 2-point curve) the
 * parabola of the pencil is taken.
 * Then x = 0 meets C where (mu b0 b1 + lam) y^2 + mu (a0 b1 - a1 b0) y
 * - mu a0 a1 = 0 (eq. (8) in the frame), and the normal there is grad C
 * (eq. (3), Code 5), not normalised.
 * Returns 1 with (*py, *gx, *gy), 0 when the line misses the conic, -1 when
 * the pencil is degenerate (caller uses the general fit).
 */
static int SFX(fast_fit)(const SFX(job) *j, const SFX(frame) *f, const SFX(pair) *P, int cnt,
                         REAL *py, REAL *gx, REAL *gy)
{
    REAL a0 = P[0].nx, b0 = P[0].ny, a1 = P[1].nx, b1 = P[1].ny;
    REAL mu, lam, A2, B1, C0, y, L0, L1, s;
    int k;

    /* A tangent through the other end point makes the pencil singular. */
    if (M(fabs)(a0) <= f->straight || M(fabs)(a1) <= f->straight)
        return -1;
    if (cnt == 2) {
        mu = 1;
        s = SFX(diffprod)(a0, b1, a1, b0);
        lam = s * s / (4 * a0 * a1);
    } else {
        REAL n11 = 0, n12 = 0, n22 = 0, h, r;
        for (k = 2; k < cnt; k++) {
            REAL u = P[k].x, v = P[k].y, nu = P[k].nx, nv = P[k].ny;
            REAL l0 = FMA(a0, u + 1, b0 * v), l1 = FMA(a1, u - 1, b1 * v);
            REAL r1 = P[k].wv * (l0 * l1), r2 = P[k].wv * (v * v);
            REAL ggx = FMA(l1, a0, l0 * a1), ggy = FMA(l1, b0, l0 * b1);
            REAL s1 = P[k].wn * DIFFPROD_WP(ggx, nv, ggy, nu), s2 = P[k].wn * (-2 * v * nu);
            n11 = FMA(r1, r1, FMA(s1, s1, n11));
            n12 = FMA(r1, r2, FMA(s1, s2, n12));
            n22 = FMA(r2, r2, FMA(s2, s2, n22));
        }
        /* Smallest eigenvector of [[n11 n12][n12 n22]], from the larger of
         * the two cancellation-free forms of the null vector of N - l_min I. */
        h = (n11 - n22) / 2;
        r = M(sqrt)(FMA(h, h, n12 * n12));
        if (!isfinite(r) || !(r > 0))
            return -1; /* N = c I: the outer pairs do not decide the ratio */
        if (h >= 0) {
            mu = n12;
            lam = -(h + r);
        } else {
            mu = r - h;
            lam = -n12;
        }
        s = 1 / SFX(maxabs)(mu, lam);
        mu *= s;
        lam *= s;
    }
    if (!isfinite(mu) || !isfinite(lam))
        return -1;
    if (j->plain) {
        A2 = mu * b0 * b1 + lam;
        B1 = mu * (a0 * b1 - a1 * b0);
    } else {
        A2 = FMA(mu, b0 * b1, lam);
        B1 = mu * SFX(diffprod)(a0, b1, a1, b0);
    }
    C0 = -mu * (a0 * a1);
    if (!SFX(nearest_root)(A2, B1 / 2, C0, j->plain ? 2 : 0, &y))
        return 0;
    if (j->plain) {
        L0 = a0 + b0 * y;
        L1 = b1 * y - a1;
        *gx = mu * (L1 * a0 + L0 * a1);
        *gy = mu * (L1 * b0 + L0 * b1) + 2 * lam * y;
    } else {
        L0 = FMA(b0, y, a0);
        L1 = FMA(b1, y, -a1);
        *gx = mu * FMA(L1, a0, L0 * a1);
        *gy = FMA(mu, FMA(L1, b0, L0 * b1), 2 * lam * y);
    }
    *py = y;
    if (!isfinite(*gx) || !isfinite(*gy) || (*gx == 0 && *gy == 0))
        return 0;
    return 1;
}

/* ----------------------------------------------------------- SVD fit */

/*
 * One-sided Jacobi SVD (Hestenes) of the m x n column-major matrix a
 * (lda = rows, rows >= n: callers pad with zero rows): right singular vector
 * of the smallest singular value into v. Used for long double, where LAPACK
 * has nothing, and as the double path's fallback. Accurate in the relative
 * sense one-sided Jacobi is known for, which matters with weights 1e5 : 1.
 */
static int SFX(jacobi_min_right)(REAL *a, int rows, int n, REAL *v)
{
    REAL V[CONICA__FIT_MAX_COLS * CONICA__FIT_MAX_COLS];
    int p, q, k, sweep, rotated = 1, best = 0;
    REAL bestn = 0;
    /* Columns count as orthogonal when |a_p . a_q| <= tol |a_p| |a_q|: the
     * rounding of a dot product of `rows` terms is about sqrt(rows) eps of
     * that, so asking for eps alone can stall (long double, weights
     * 1e5 : 1); sqrt(rows) eps is LAPACK's dgesvj threshold. */
    REAL tol = M(sqrt)((REAL)rows) * R_EPSILON;

    for (p = 0; p < n; p++)
        for (q = 0; q < n; q++)
            V[p + q * n] = p == q ? 1 : 0;
    for (sweep = 0; sweep < CONICA__JACOBI_MAX_SWEEPS && rotated; sweep++) {
        rotated = 0;
        for (p = 0; p < n - 1; p++) {
            for (q = p + 1; q < n; q++) {
                REAL al = 0, be = 0, ga = 0, zeta, t, c, s;
                REAL *ap = a + (size_t)p * (size_t)rows, *aq = a + (size_t)q * (size_t)rows;
                for (k = 0; k < rows; k++) {
                    al = FMA(ap[k], ap[k], al);
                    be = FMA(aq[k], aq[k], be);
                    ga = FMA(ap[k], aq[k], ga);
                }
                if (ga == 0 || M(fabs)(ga) <= tol * M(sqrt)(al) * M(sqrt)(be))
                    continue;
                rotated = 1;
                zeta = (be - al) / (2 * ga);
                t = (zeta >= 0 ? 1 : -1) / (M(fabs)(zeta) + M(sqrt)(1 + zeta * zeta));
                c = 1 / M(sqrt)(1 + t * t);
                s = c * t;
                for (k = 0; k < rows; k++) {
                    REAL x = ap[k], y = aq[k];
                    ap[k] = c * x - s * y;
                    aq[k] = s * x + c * y;
                }
                for (k = 0; k < n; k++) {
                    REAL x = V[k + p * n], y = V[k + q * n];
                    V[k + p * n] = c * x - s * y;
                    V[k + q * n] = s * x + c * y;
                }
            }
        }
    }
    if (rotated)
        return -1;
    for (p = 0; p < n; p++) {
        REAL nn = 0;
        for (k = 0; k < rows; k++)
            nn = FMA(a[k + p * rows], a[k + p * rows], nn);
        if (p == 0 || nn < bestn) {
            bestn = nn;
            best = p;
        }
    }
    for (k = 0; k < n; k++)
        v[k] = V[k + best * n];
    return 0;
}

/*
 * General weighted fit (CONIS, step 2): rows of matrix (2) generalised
 * to cnt pairs (one point row, two normal rows and one alpha column per
 * pair), scaled by W; q = right singular vector of the smallest singular
 * value. Writes the six conic coefficients q20, q02, q11, q10, q01, q00.
 * Returns 0 on success.
 */
static int SFX(svd_fit)(SFX(worker) *w, const SFX(pair) *P, int cnt, REAL *q)
{
    REAL a[CONICA__FIT_MAX_ROWS * CONICA__FIT_MAX_COLS];
    REAL v[CONICA__FIT_MAX_COLS];
    int m = 3 * cnt, n = 6 + cnt, rows = m > n ? m : n, k, c;

    for (k = 0; k < rows * n; k++)
        a[k] = 0;
    for (k = 0; k < cnt; k++) {
        REAL x = P[k].x, y = P[k].y, wv = P[k].wv, wn = P[k].wn;
        int r0 = 3 * k, r1 = r0 + 1, r2 = r0 + 2;
        a[r0 + 0 * rows] = wv * (x * x);
        a[r0 + 1 * rows] = wv * (y * y);
        a[r0 + 2 * rows] = wv * (2 * x * y);
        a[r0 + 3 * rows] = wv * (2 * x);
        a[r0 + 4 * rows] = wv * (2 * y);
        a[r0 + 5 * rows] = wv;
        a[r1 + 0 * rows] = wn * (2 * x);
        a[r1 + 2 * rows] = wn * (2 * y);
        a[r1 + 3 * rows] = wn * 2;
        a[r1 + (6 + k) * rows] = wn * -P[k].nx;
        a[r2 + 1 * rows] = wn * (2 * y);
        a[r2 + 2 * rows] = wn * (2 * x);
        a[r2 + 4 * rows] = wn * 2;
        a[r2 + (6 + k) * rows] = wn * -P[k].ny;
    }
    /* LAPACK's bidiagonal QR can loop for ever on Inf/NaN (found by the
     * fuzzer with a point at 1e300, whose square overflows): such a patch
     * has no fit. */
    for (k = 0; k < rows * n; k++)
        if (!isfinite(a[k]))
            return -1;
#if REAL_IS_DOUBLE
    {
        double copy[CONICA__FIT_MAX_ROWS * CONICA__FIT_MAX_COLS];
        for (c = 0; c < n; c++)
            for (k = 0; k < m; k++)
                copy[k + c * m] = a[k + c * rows];
        if (conica__svd_min_right(w->ws, copy, m, n, v) != 0 &&
            SFX(jacobi_min_right)(a, rows, n, v) != 0)
            return -1;
    }
#else
    (void)w;
    (void)c;
    if (SFX(jacobi_min_right)(a, rows, n, v) != 0)
        return -1;
#endif
    for (k = 0; k < 6; k++) {
        q[k] = v[k];
        if (!isfinite(q[k]))
            return -1;
    }
    return 0;
}

/*
 * General fit in the translate-and-scale frame: p -> (p - m) / |p1 - p0|,
 * the frame of REFERENCE.md's measured local-frame variant of the reference
 * (no rotation, so that on data that lie on no conic the fit's ||q|| = 1
 * normalisation stays close to the reference's and its shapes follow the
 * reference's). l(t) of eq. (7) becomes t * e with e the unit edge normal;
 * a, b, c of Section 2.3 with m~ = (0,0,1), n~ = (e, 0); normal from
 * Code 5. Writes the new point and its (unnormalised) normal in global
 * coordinates. With `bounded` (an irregular patch, see SFX(edge)) an
 * intersection farther than CONICA__IRREGULAR_MAX_T edge lengths from the
 * midpoint counts as none. want = +1 or -1 takes the intersection on that
 * side of the edge (the frame's y > 0 or y < 0; SFX(long_arc)), 0 the one
 * nearest the midpoint (eq. (6)). *py receives the new point's height over the
 * edge in the units of the rotated frame of SFX(frame) (half edge = 1),
 * i.e. 2t. Returns 1 on success, 0 when the fit or the intersection fails.
 */
static int SFX(svd_tframe)(SFX(worker) *w, const SFX(frame) *f, const size_t *idx, int cnt,
                           int bounded, int want, REAL *py, REAL *ox, REAL *oy, REAL *nx,
                           REAL *ny)
{
    const SFX(job) *j = w->job;
    SFX(pair) P[CONICA__FIT_MAX_PAIRS];
    REAL q[6], dx = 2 * f->hx, dy = 2 * f->hy, len, inv, ex, ey, a, b, t, x, y;
    int k;

    if (cnt < 3)
        return 0;
    len = M(sqrt)(FMA(f->hsx, f->hsx, f->hsy * f->hsy)) * 2 / f->sc;
    inv = 1 / len;
    if (!isfinite(inv) || !(inv > 0))
        return 0;
    for (k = 0; k < cnt; k++) {
        size_t qi = idx[k];
        REAL mx = j->nxy[2 * qi], my = j->nxy[2 * qi + 1];
        REAL mag = SFX(maxabs)(mx, my), nl;
        mx /= mag;
        my /= mag;
        nl = M(sqrt)(FMA(mx, mx, my * my));
        P[k].x = (j->xy[2 * qi] - f->mx) * inv;
        P[k].y = (j->xy[2 * qi + 1] - f->my) * inv;
        P[k].nx = mx / nl;
        P[k].ny = my / nl;
        P[k].wv = k < 2 ? j->wev : j->wov;
        P[k].wn = k < 2 ? j->wen : j->won;
    }
    if (SFX(svd_fit)(w, P, cnt, q) != 0)
        return 0;
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0 && q[4] == 0 && q[5] == 0)
        return 0;
    ex = -dy * inv;
    ey = dx * inv;
    if (j->plain) {
        a = q[0] * ex * ex + 2 * q[2] * ex * ey + q[1] * ey * ey;
        b = q[3] * ex + q[4] * ey;
    } else {
        a = FMA(q[0] * ex, ex, FMA(2 * q[2] * ex, ey, q[1] * ey * ey));
        b = FMA(q[3], ex, q[4] * ey);
    }
    if (want != 0 ? !SFX(side_root)(a, b, q[5], want, &t)
                  : !SFX(nearest_root)(a, b, q[5], j->plain ? 2 : 0, &t))
        return 0;
    if (want != 0) {
        /* A long arc's point is the far intersection, and only an
         * ellipse's is bounded: a hyperbola's lies on its other branch.
         * No bound in edge lengths, which a long arc on a conic exceeds
         * (three points on a circle: 1.87 edge lengths). */
        if (!(DIFFPROD_WP(q[0], q[1], q[2], q[2]) > 0))
            return 0;
    } else if (bounded && !(M(fabs)(t) <= RC(CONICA__IRREGULAR_MAX_T))) {
        return 0;
    }
    x = t * ex;
    y = t * ey;
    if (j->plain) {
        *nx = q[0] * x + q[2] * y + q[3];
        *ny = q[2] * x + q[1] * y + q[4];
    } else {
        *nx = FMA(q[0], x, FMA(q[2], y, q[3]));
        *ny = FMA(q[2], x, FMA(q[1], y, q[4]));
    }
    /* m + t * len * e = m + t * perp(p1 - p0) */
    *py = 2 * t;
    *ox = FMA(-t, dy, f->mx);
    *oy = FMA(t, dx, f->my);
    return isfinite(*nx) && isfinite(*ny) && !(*nx == 0 && *ny == 0) && isfinite(*ox) &&
           isfinite(*oy);
}

/* ------------------------------------------------------- edge points */

static void SFX(store)(const SFX(job) *j, REAL x, REAL y, REAL nx, REAL ny, REAL *oxy, REAL *on)
{
    oxy[0] = x;
    oxy[1] = y;
    if (j->normalize) {
        REAL len = M(sqrt)(FMA(nx, nx, ny * ny));
        if (len > 0 && isfinite(len)) {
            nx /= len;
            ny /= len;
        }
    }
    on[0] = nx;
    on[1] = ny;
}

/*
 * Reference-compatible edge point: absolute coordinates, the general fit,
 * sampling exactly as the reference's Conic::sample (origin m, direction
 * n_edge unnormalised, normal oriented along n_edge), patch growth up to 3
 * outer neighbours a side, midpoint with the edge normal as the last resort.
 */
static void SFX(edge_ref)(SFX(worker) *w, size_t i, REAL *oxy, REAL *on)
{
    const SFX(job) *j = w->job;
    size_t idx[CONICA__FIT_MAX_PAIRS], i1 = SFX(next)(j, i);
    SFX(pair) P[CONICA__FIT_MAX_PAIRS];
    REAL x0 = j->xy[2 * i], y0 = j->xy[2 * i + 1], x1 = j->xy[2 * i1], y1 = j->xy[2 * i1 + 1];
    REAL ox = (x0 + x1) / 2, oy = (y0 + y1) / 2, dx = y0 - y1, dy = x1 - x0;
    int cnt, prev = -1, g, k;

    for (g = 1; g <= j->maxgrow; g++) {
        REAL q[6], qux, quy, qpx, qpy, qpz, a, b, c, t, px, py, nx, ny;
        cnt = SFX(collect)(j, NULL, i, g, g, idx);
        if (cnt == prev)
            break;
        prev = cnt;
        for (k = 0; k < cnt; k++) {
            P[k].x = j->xy[2 * idx[k]];
            P[k].y = j->xy[2 * idx[k] + 1];
            P[k].nx = j->nxy[2 * idx[k]];
            P[k].ny = j->nxy[2 * idx[k] + 1];
            P[k].wv = k < 2 ? j->wev : j->wov;
            P[k].wn = k < 2 ? j->wen : j->won;
        }
        if (cnt < 3 || SFX(svd_fit)(w, P, cnt, q) != 0)
            continue;
        /* Eigen's isZero(): every coefficient within 1e-15 of zero. */
        for (k = 0; k < 6; k++)
            if (M(fabs)(q[k]) > RC(CONICA__REF_ZERO))
                break;
        if (k == 6)
            continue;
        /* Q u with u = (dx, dy, 0), Q p with p = (ox, oy, 1). */
        qux = q[0] * dx + q[2] * dy;
        quy = q[2] * dx + q[1] * dy;
        qpx = q[0] * ox + q[2] * oy + q[3];
        qpy = q[2] * ox + q[1] * oy + q[4];
        qpz = q[3] * ox + q[4] * oy + q[5];
        a = dx * qux + dy * quy;
        b = dx * qpx + dy * qpy;
        c = ox * qpx + oy * qpy + qpz;
        if (!SFX(nearest_root)(a, b, c, 1, &t))
            continue;
        px = ox + t * dx;
        py = oy + t * dy;
        nx = FMA(q[0], px, FMA(q[2], py, q[3]));
        ny = FMA(q[2], px, FMA(q[1], py, q[4]));
        if (nx * dx + ny * dy < 0) {
            nx = -nx;
            ny = -ny;
        }
        if ((nx == 0 && ny == 0) || !isfinite(px) || !isfinite(py) || !isfinite(nx) ||
            !isfinite(ny))
            continue;
        if (g > 1)
            w->grown++;
        SFX(store)(j, px, py, nx, ny, oxy, on);
        return;
    }
    w->fallbacks++;
    SFX(store)(j, ox, oy, dx, dy, oxy, on);
}

/*
 * Convexity region of an edge (README.md, "Convexity region"). In the
 * rotated frame the edge runs from (-1,0) to (1,0) and its end tangents are
 * the lines L0 = a0 (x+1) + b0 y = 0 and L1 = a1 (x-1) + b1 y = 0. A
 * convex arc that joins the end points, touching L0 and L1 there, lies in
 * the triangle bounded by the chord and the two tangent lines; CONIS's
 * promise that every piece between inflection points turns one way needs
 * exactly this of every edge point (the refined polygon then stays convex,
 * and the conic's normal there lies between the end normals).
 *
 * The side of the chord the arc bulges to is the side away from the
 * patch's outer neighbours (a convex polygon lies on one side of each edge
 * line, its curve on the other); `side` is +1 or -1 for y > 0 or y < 0, or
 * 0 when the neighbours do not decide it (none, on the line, or on both
 * sides). The tangent rays into side s meet iff s * cr > 0 with
 * cr = sign(a0 a1) (a0 b1 - a1 b0); none of this depends on the normals'
 * orientation (the engine accepts either, see SFX(edge)).
 */
static REAL SFX(region_cross)(const SFX(pair) *P)
{
    REAL c = DIFFPROD_WP(P[0].nx, P[1].ny, P[1].nx, P[0].ny);
    return (P[0].nx > 0) == (P[1].nx > 0) ? c : -c;
}

/* Edges with no convex region. 1: a tangent along the chord (to within
 * f->straight, SFX(make_frame)): the region is the chord itself. 2: the tangent
 * rays meet on the side of the chord the polygon says the arc cannot bulge
 * to (an end normal that does not lie between its vertex's edge normals,
 * as p_11's given normal in example8): no convex arc joins the end pairs,
 * the curve must cross the chord (an S-shaped edge). 0: a proper
 * triangle. */
static int SFX(no_region)(const SFX(frame) *f, const SFX(pair) *P, int side)
{
    REAL cr;
    if (M(fabs)(P[0].nx) <= f->straight || M(fabs)(P[1].nx) <= f->straight)
        return 1;
    cr = SFX(region_cross)(P);
    return side != 0 && cr != 0 && (side > 0) != (cr > 0) ? 2 : 0;
}

/* Does (0, y) lie in the region (boundary included; the chord's midpoint
 * always does)? Only called when SFX(no_region) returned 0. */
static int SFX(in_region)(const SFX(pair) *P, int side, REAL y)
{
    REAL a0 = P[0].nx, b0 = P[0].ny, a1 = P[1].nx, b1 = P[1].ny, cr;
    if (y == 0)
        return 1;
    if (side == 0) {
        cr = SFX(region_cross)(P);
        side = cr > 0 ? 1 : (cr < 0 ? -1 : 0); /* 0: parallel tangents, either side */
    }
    if (side != 0 && (y > 0) != (side > 0))
        return 0;
    /* Not beyond either tangent line: on the side of L0 that holds (1,0),
     * on the side of L1 that holds (-1,0). */
    return a0 * FMA(b0, y, a0) >= 0 && a1 * FMA(-b1, y, a1) >= 0;
}

/* The side of the chord away from the patch's outer neighbours (see
 * SFX(in_region)): +1, -1, 0 when they do not decide it (none, or all on
 * the edge line), or 2 when they lie on both sides (the polygon itself
 * turns both ways here). Neighbours on the edge line to within rounding
 * (SFX(line_class)) count as on it. */
static int SFX(bulge_side)(const SFX(frame) *f, const SFX(pair) *P, int cnt)
{
    int k, s = 0;
    REAL tol = SFX(on_line_tol)(f);
    for (k = 2; k < cnt; k++) {
        int t = SFX(line_class)(tol, P[k].x, P[k].y);
        if (t == 0)
            continue;
        if (s != 0 && t != s)
            return 2;
        s = t;
    }
    return s;
}

/* The travel direction of the polygon at its vertex q in the frame of f,
 * (ux, uy) = unit(q - a) + unit(c - q) for the vertex's neighbours a and
 * c; a missing one (an open end) adds nothing. */
static void SFX(travel)(const SFX(job) *j, const SFX(frame) *f, size_t q, REAL qx, REAL *ux,
                        REAL *uy)
{
    size_t n = j->n, nb[2];
    int k;
    nb[0] = q > 0 ? q - 1 : (j->closed ? n - 1 : (size_t)-1);
    nb[1] = q + 1 < n ? q + 1 : (j->closed ? 0 : (size_t)-1);
    *ux = 0;
    *uy = 0;
    for (k = 0; k < 2; k++) {
        REAL x, y, len;
        if (nb[k] == (size_t)-1)
            continue;
        SFX(to_frame)(j, f, nb[k], &x, &y);
        x -= qx;
        len = M(sqrt)(FMA(x, x, y * y));
        if (!(len > 0) || !isfinite(len))
            continue;
        *ux += (k == 0 ? -x : x) / len;
        *uy += (k == 0 ? -y : y) / len;
    }
}

/*
 * Does edge (i, i+1) carry a long arc: a convex arc from p_i to p_{i+1}
 * that bulges to `side` (+1, -1: the frame's y > 0, y < 0) and turns by
 * more than a half turn? Then both end tangents, each oriented along the
 * polygon's travel at its vertex (SFX(travel)), point into `side`, leaving
 * p_i and reaching p_{i+1} from there, but the tangent rays into that side
 * do not meet (SFX(no_region) == 2): the arc passes beyond them and comes
 * back. A folded polygon such as the reference's lG2 (points on a circle
 * taken out of order, vertices turning by up to 174 degrees) has such
 * edges: its sub-polygons between the inflection points of CONIS,
 * eqs. (9)-(10), are convex, and the convex arc through such an edge's end
 * pairs is the long arc of an ellipse. The intersection eq. (6) picks, the
 * one nearest the midpoint, lies on the short arc on the other side of the
 * chord, where the refined polygon turns the other way: two curvature sign
 * changes more at every such edge, and more at every level below it.
 * On return o[k] is +1 when end k's normal lies to the right of the
 * travel, -1 when to the left (the engine accepts either orientation at
 * every vertex). The arc crosses the bisector x = 0 moving in +x (with the
 * chord it closes a convex loop), so the new point's normal, oriented as
 * p_i's, has a frame y component of sign -o[0].
 */
static int SFX(long_arc)(const SFX(job) *j, const SFX(frame) *f, size_t i, size_t i1,
                         const SFX(pair) *P, int side, int o[2])
{
    REAL ux, uy;
    if ((side != 1 && side != -1) || j->n < 3 || SFX(no_region)(f, P, side) != 2)
        return 0;
    /* The tangent (-b, a) of the frame normal (a, b) against the travel:
     * o = +1 when it runs along it (the normal to the right), -1 against. */
    SFX(travel)(j, f, i, RC(-1.0), &ux, &uy);
    o[0] = FMA(-P[0].ny, ux, P[0].nx * uy) > 0 ? 1 : -1;
    SFX(travel)(j, f, i1, RC(1.0), &ux, &uy);
    o[1] = FMA(-P[1].ny, ux, P[1].nx * uy) > 0 ? 1 : -1;
    /* the oriented tangents' y, o * a: into `side` at p_i, out of it at
     * p_{i+1} */
    return o[0] * side * P[0].nx > 0 && o[1] * side * P[1].nx < 0;
}

/*
 * The point of a long arc (SFX(long_arc)) when the fit gives none on its
 * side (on data that lie on no conic the patch's fit is often a
 * hyperbola): the ellipse of the pencil mu L0 L1 + lam y^2 (SFX(fast_fit))
 * whose weight is that of a circular arc of the same turn. As a rational
 * quadratic with control points p_i, T (the tangents' intersection),
 * p_{i+1} a conic of the pencil has lam = s^2 / (4 a0 a1 w^2), s = a0 b1 -
 * a1 b0 (w = 1: the parabola, the short arcs' fallback); a circular arc
 * turning by phi has w = cos(phi / 2), so w^2 = (1 + n0.n1) / 2 for the
 * unit end normals n0, n1 oriented alike (o of SFX(long_arc)), and with
 * s^2 = 1 - (n0.n1)^2 (Lagrange's identity) lam = (1 - n0.n1) / (2 a0 a1),
 * finite also for antiparallel normals (a half turn). The result is the circle when a
 * circle fits both end pairs, and an ellipse whenever the arc turns by
 * less than a full turn; x = 0 meets it once on each side of the chord,
 * and the long arc's point is the one on `want`. Returns 1 with (*py,
 * *gx, *gy) as SFX(fast_fit), 0 when there is none.
 */
static int SFX(long_arc_point)(const SFX(pair) *P, const int o[2], int want, REAL *py, REAL *gx,
                               REAL *gy)
{
    REAL a0 = P[0].nx, b0 = P[0].ny, a1 = o[0] * o[1] * P[1].nx, b1 = o[0] * o[1] * P[1].ny;
    REAL d = FMA(a0, a1, b0 * b1), lam = (1 - d) / (2 * (a0 * a1)), y, L0, L1;
    if (!isfinite(lam) || !SFX(side_root)(FMA(b0, b1, lam), SFX(diffprod)(a0, b1, a1, b0) / 2,
                                          -(a0 * a1), want, &y))
        return 0;
    L0 = FMA(b0, y, a0);
    L1 = FMA(b1, y, -a1);
    *gx = FMA(L1, a0, L0 * a1);
    *gy = FMA(L1, b0, FMA(L0, b1, 2 * lam * y));
    *py = y;
    return isfinite(*gx) && isfinite(*gy) && !(*gx == 0 && *gy == 0);
}

/*
 * Edge point of edge (i, i+1) in default mode (local frame), in three
 * steps so that SFX(level) can run the closed-form fits of several edges
 * back to back (their long chains of dependent divisions and square roots
 * then overlap in the processor; each edge's arithmetic is unchanged):
 * SFX(edge_prep) classifies the patch, the pencil fit of SFX(fast_fit) runs
 * where it says so (EDGE_FAST), SFX(edge_finish) does the rest. The state
 * between them: */
enum { SFX(EDGE_DONE), SFX(EDGE_MIDPOINT), SFX(EDGE_FAST), SFX(EDGE_REST) };
typedef struct SFX(estate) {
    size_t idx[CONICA__FIT_MAX_PAIRS];
    SFX(pair) P[CONICA__FIT_MAX_PAIRS];
    SFX(frame) f;
    REAL y, gx, gy; /* the fast fit's result */
    int stage, cnt, ok, regular, side, conflict, want, orient[2];
} SFX(estate);

/* Up to the fit: the patch, its frame and pairs, and its class. Stage
 * EDGE_DONE when the point is already stored (coincident end points). */
static void SFX(edge_prep)(SFX(worker) *w, size_t i, SFX(estate) *st, REAL *oxy, REAL *on)
{
    const SFX(job) *j = w->job;
    size_t *idx = st->idx, i1;
    SFX(pair) *P = st->P;
    int cnt, ok = 0, maxl = 1, maxr = 1, regular = 1, side, conflict;
    int want = 0;

    st->orient[0] = st->orient[1] = 0;
    st->y = st->gx = st->gy = 0;
    st->cnt = 0;
    st->ok = 0;
    st->regular = 1;
    st->side = 0;
    st->conflict = 0;
    st->want = 0;
    i1 = SFX(next)(j, i);
    if (!SFX(make_frame)(j, i, i1, &st->f)) {
        /* Coincident end points (rounding at extreme levels): repeat the
         * point; its normal is as good as any. */
        w->fallbacks++;
        SFX(store)(j, j->xy[2 * i], j->xy[2 * i + 1], j->nxy[2 * i], j->nxy[2 * i + 1], oxy, on);
        st->stage = SFX(EDGE_DONE);
        return;
    }
    /* CONIS after (10): next to an inflection point the patch is the
     * inflection point, the edge's other end and two neighbours beyond it.
     * The same holds next to an S-shaped edge's midpoint (below): beyond
     * it the curve turns the other way, so a neighbour there says nothing
     * about the side this edge's arc bulges to. */
    if (j->infl) {
        if (j->infl[i])
            maxr = 2;
        if (j->infl[i1])
            maxl = 2;
    }
    cnt = SFX(collect)(j, &st->f, i, maxl, maxr, idx);
    SFX(local_pairs)(j, &st->f, idx, cnt, P);
    /* The pencil describes a convex arc between the end points; it is used
     * when the patch looks like one: the end normals do not tilt the same
     * way (a0*b0 and a1*b1 not of one strict sign, whatever the normals'
     * orientation) and the first outer neighbours lie on one side of the
     * edge. Elsewhere (inconsistent patches, which only data on no conic
     * produce) the general fit decides, as in the reference; no conic is
     * consistent with such a patch, so its fit is ill-conditioned and an
     * intersection far off the edge is an artefact: it must lie within
     * CONICA__IRREGULAR_MAX_T edge lengths of the midpoint.
     * Every result must moreover lie in the edge's convexity region
     * (SFX(in_region), README.md): else the patch grows, then the
     * parabola of the pencil (a conic through both end pairs that stays in
     * the region) is taken. An edge whose region is the chord alone gets
     * the midpoint at once. Where the tangent rays into the side the
     * polygon says the arc bulges to do not meet (SFX(no_region) == 2),
     * either the arc turns by more than a half turn (SFX(long_arc): the
     * fit's intersection on that side, else an ellipse of the pencil) or
     * no convex arc fits (an S-shaped edge), and there is no region to hold
     * the fit to: it is taken as the reference takes it; without a fit the
     * edge gets an inflection at its midpoint (below). Where the outer
     * neighbours lie on both sides of the edge (conflict 3: the polygon
     * itself turns both ways, which no piece between inflection points
     * does) the fit is taken as the reference takes it, too. */
    side = SFX(bulge_side)(&st->f, P, cnt);
    conflict = side == 2 ? 3 : SFX(no_region)(&st->f, P, side);
    if (conflict == 1) {
        st->stage = SFX(EDGE_MIDPOINT); /* want 0: oriented by the end normals */
        return;
    }
    if (conflict == 2 && SFX(long_arc)(j, &st->f, i, i1, P, side, st->orient)) {
        /* A long arc (SFX(long_arc)): its region is the wedge of the chord
         * and the two tangent rays, unbounded on `side`, which
         * SFX(in_region) tests as it tests a triangle; the point is the
         * fit's intersection on that side, not the nearest (eq. (6) assumes
         * a polygon that turns less than a half turn over an edge). The
         * pencil's closed form only knows the nearest root: general fit. */
        want = side;
        conflict = 0;
        regular = 0;
    }
    st->stage = SFX(EDGE_REST);
    if (j->fast && want == 0) {
        /* Outer neighbours on both sides (side 2, with points on the edge
         * line to within rounding counting as neither) make it irregular. */
        regular = (P[0].nx * P[0].ny) * (P[1].nx * P[1].ny) <= 0 && side != 2;
        if (regular)
            st->stage = SFX(EDGE_FAST); /* ok = SFX(fast_fit)(...) */
        else
            ok = -1;
    }
    st->cnt = cnt;
    st->ok = ok;
    st->regular = regular;
    st->side = side;
    st->conflict = conflict;
    st->want = want;
}

/* The rest, from the fit's result on (stage EDGE_FAST: st->ok, y, gx, gy
 * from SFX(fast_fit)). Returns 1 when the point is an inflection point (an
 * S-shaped edge's midpoint), which the next levels treat as CONIS
 * treats those of eq. (9). */
static int SFX(edge_finish)(SFX(worker) *w, size_t i, SFX(estate) *st, REAL *oxy, REAL *on)
{
    const SFX(job) *j = w->job;
    size_t *idx = st->idx;
    const SFX(pair) *P = st->P;
    SFX(frame) f = st->f;
    REAL y = st->y, gx = st->gx, gy = st->gy, ox = 0, oy = 0, nx = 0, ny = 0;
    int cnt = st->cnt, ok = st->ok, g, regular = st->regular, local = 0, side = st->side;
    int conflict = st->conflict, infl = 0, want = st->want, *orient = st->orient;

    if (st->stage == SFX(EDGE_MIDPOINT))
        goto midpoint;
    if (st->stage == SFX(EDGE_FAST) && ok > 0)
        local = 1;
    if (!j->fast || ok < 0 || want != 0)
        ok = SFX(svd_tframe)(w, &f, idx, cnt, !regular, want, &y, &ox, &oy, &nx, &ny);
    if (ok > 0 && conflict == 0 && !SFX(in_region)(P, side, y))
        ok = 0;
    /* No real intersection, or none in the region: grow the patch one
     * neighbour a side at a time (REFERENCE.md section 1) and refit with
     * the general fit. */
    for (g = 2; !ok && g <= j->maxgrow; g++) {
        int c2 = SFX(collect)(j, &f, i, g, g, idx);
        if (c2 <= cnt)
            continue;
        cnt = c2;
        local = 0;
        ok = SFX(svd_tframe)(w, &f, idx, cnt, !regular, want, &y, &ox, &oy, &nx, &ny) &&
             (conflict != 0 || SFX(in_region)(P, side, y));
        if (ok)
            w->grown++;
    }
    if (!ok && want != 0) {
        /* A long arc without a fit on its side: the pencil's ellipse of
         * SFX(long_arc_point), within CONICA__IRREGULAR_MAX_T edge lengths
         * of the midpoint as every irregular patch's point. */
        ok = SFX(long_arc_point)(P, orient, want, &y, &gx, &gy) && SFX(in_region)(P, side, y) &&
             M(fabs)(y) <= 2 * RC(CONICA__IRREGULAR_MAX_T);
        local = ok;
        if (ok)
            w->fallbacks++;
    }
    if (!ok && conflict >= 2 && j->infl && (j->infl[i] || j->infl[SFX(next)(j, i)])) {
        /* An S-shaped edge next to an inflection point: the inflection is
         * already there, and a second one at the midpoint would start a
         * cascade (every level's edge next to the new inflection point is
         * S-shaped again), the zigzag combs of folded polygons such as the
         * reference's lG2. The convex arc instead: the parabola of the
         * pencil, within CONICA__IRREGULAR_MAX_T edge lengths of the
         * midpoint, else the midpoint with the edge normal (below). */
        ok = SFX(fast_fit)(j, &f, P, 2, &y, &gx, &gy) > 0 &&
             M(fabs)(y) <= 2 * RC(CONICA__IRREGULAR_MAX_T);
        local = ok;
        if (ok)
            w->fallbacks++;
    } else if (!ok && conflict >= 2) {
        /* An S-shaped edge holds an inflection of the curve: put it at the
         * midpoint, as eq. (9) does for the polygon's inflection edges,
         * with the tangent there of the cubic through both end pairs
         * (slope -(s0 + s1)/4 for the end slopes s0 = -a0/b0, s1 = -a1/b1
         * over the half edge), which turns against both end tangents, so
         * that each half of the edge gets a proper convex region. (The
         * edge normal of the plain midpoint fallback would put the chord
         * in as both halves' tangent: straight pieces, whose rounded
         * midpoints then wiggle at the rounding level.) The point is
         * flagged as an inflection point for the next levels. */
        w->fallbacks++;
        ox = f.mx;
        oy = f.my;
        gx = -FMA(P[0].nx, P[1].ny, P[1].nx * P[0].ny);
        gy = 4 * P[0].ny * P[1].ny;
        nx = FMA(gx, f.hsx, -gy * f.hsy);
        ny = FMA(gx, f.hsy, gy * f.hsx);
        if (isfinite(nx) && isfinite(ny) && !(nx == 0 && ny == 0)) {
            infl = 1;
            goto oriented;
        }
    }
    if (!ok && conflict == 0 && want == 0) {
        /* The parabola of the pencil (the quadratic Bezier through the
         * tangent lines' intersection) lies in the region whenever the
         * region is a proper triangle. */
        ok = SFX(fast_fit)(j, &f, P, 2, &y, &gx, &gy) > 0 && SFX(in_region)(P, side, y);
        local = ok;
        if (ok)
            w->fallbacks++;
    }
    if (local) {
        /* Back to global coordinates: (gx, gy) in the frame is
         * gx*hs + gy*perp(hs) (a rotation times |hs| in [1, 2*sqrt2),
         * so magnitudes stay O(|g|)). */
        ox = FMA(-y, f.hy, f.mx);
        oy = FMA(y, f.hx, f.my);
        nx = FMA(gx, f.hsx, -gy * f.hsy);
        ny = FMA(gx, f.hsy, gy * f.hsx);
    }
midpoint:
    if (!ok || !isfinite(ox) || !isfinite(oy) || !isfinite(nx) || !isfinite(ny) ||
        (nx == 0 && ny == 0)) {
        /* Last resort: the midpoint with the edge normal (as the reference). */
        w->fallbacks++;
        ox = f.mx;
        oy = f.my;
        nx = -f.hsy;
        ny = f.hsx;
    }
oriented : {
        /* Orient the normal like the edge's end normals (their sum; n_edge
         * if they cancel), so the output keeps the input's orientation. */
        REAL sx = FMA(P[0].nx, f.hsx, -P[0].ny * f.hsy) + FMA(P[1].nx, f.hsx, -P[1].ny * f.hsy);
        REAL sy = FMA(P[0].nx, f.hsy, P[0].ny * f.hsx) + FMA(P[1].nx, f.hsy, P[1].ny * f.hsx);
        if (want != 0) {
            /* A long arc turns by more than a half turn, so the end
             * normals' sum points the wrong way: oriented as p_i's normal,
             * the new one has a frame y of sign -o[0] (SFX(long_arc)). */
            sx = orient[0] * f.hsy;
            sy = -orient[0] * f.hsx;
        }
        if (sx == 0 && sy == 0) {
            sx = -f.hsy;
            sy = f.hsx;
        }
        if (nx * sx + ny * sy < 0) {
            nx = -nx;
            ny = -ny;
        }
    }
    SFX(store)(j, ox, oy, nx, ny, oxy, on);
    return infl;
}

/* One subdivision level: src (j->n points) -> dst. Old vertices copied
 * bit-for-bit (step 1), one edge point per edge (steps 2-4); inflection
 * flags follow their points (i -> 2i), edge points get their own. */
static void SFX(level)(SFX(worker) *w, REAL *dxy, REAL *dn, size_t e_begin, size_t e_end)
{
    const SFX(job) *j = w->job;
    SFX(estate) st[CONICA__EDGE_BATCH];
    size_t e, b, e1;
    for (b = e_begin; b < e_end; b = e1) {
        e1 = e_end - b > CONICA__EDGE_BATCH ? b + CONICA__EDGE_BATCH : e_end;
        for (e = b; e < e1; e++) {
            dxy[4 * e] = j->xy[2 * e];
            dxy[4 * e + 1] = j->xy[2 * e + 1];
            dn[4 * e] = j->nxy[2 * e];
            dn[4 * e + 1] = j->nxy[2 * e + 1];
            if (j->dinfl)
                j->dinfl[2 * e] = j->infl[e];
            st[e - b].stage = SFX(EDGE_DONE);
            if (e + 1 < j->n || j->closed) {
                if (j->ref)
                    SFX(edge_ref)(w, e, dxy + 4 * e + 2, dn + 4 * e + 2);
                else
                    SFX(edge_prep)(w, e, &st[e - b], dxy + 4 * e + 2, dn + 4 * e + 2);
                if (j->dinfl)
                    j->dinfl[2 * e + 1] = 0;
            }
        }
        for (e = b; e < e1; e++) {
            SFX(estate) *t = &st[e - b];
            if (t->stage == SFX(EDGE_FAST))
                t->ok = SFX(fast_fit)(j, &t->f, t->P, t->cnt, &t->y, &t->gx, &t->gy);
        }
        for (e = b; e < e1; e++) {
            if (st[e - b].stage != SFX(EDGE_DONE)) {
                int fl = SFX(edge_finish)(w, e, &st[e - b], dxy + 4 * e + 2, dn + 4 * e + 2);
                if (j->dinfl)
                    j->dinfl[2 * e + 1] = (unsigned char)fl;
            }
        }
    }
}

/* Optional threads (settings.threads): the edges of one level split into
 * contiguous chunks, one worker each. Every edge point depends only on the
 * previous level, so results are bit-identical for any thread count. */
typedef struct SFX(task) {
    SFX(worker) *w;
    REAL *dxy, *dn;
    size_t begin, end;
} SFX(task);

static void *SFX(task_main)(void *arg)
{
    SFX(task) *t = arg;
    SFX(level)(t->w, t->dxy, t->dn, t->begin, t->end);
    return NULL;
}

static void SFX(level_threads)(SFX(worker) *wk, int nth, REAL *dxy, REAL *dn, size_t lo,
                               size_t hi)
{
    SFX(task) task[CONICA__MAX_THREADS];
    pthread_t tid[CONICA__MAX_THREADS];
    int started[CONICA__MAX_THREADS], t;
    size_t chunk, n = hi - lo;

    if (nth > 1 && n / (size_t)nth < CONICA__THREAD_MIN_EDGES)
        nth = (int)(n / CONICA__THREAD_MIN_EDGES) > 1 ? (int)(n / CONICA__THREAD_MIN_EDGES) : 1;
    if (nth <= 1) {
        SFX(level)(wk, dxy, dn, lo, hi);
        return;
    }
    chunk = (n + (size_t)nth - 1) / (size_t)nth;
    for (t = 0; t < nth; t++) {
        task[t].w = &wk[t];
        task[t].dxy = dxy;
        task[t].dn = dn;
        task[t].begin = lo + ((size_t)t * chunk < n ? (size_t)t * chunk : n);
        task[t].end = lo + ((size_t)(t + 1) * chunk < n ? (size_t)(t + 1) * chunk : n);
    }
    for (t = 1; t < nth; t++)
        started[t] = pthread_create(&tid[t], NULL, SFX(task_main), &task[t]) == 0;
    SFX(task_main)(&task[0]);
    for (t = 1; t < nth; t++) {
        if (started[t])
            pthread_join(tid[t], NULL);
        else
            SFX(task_main)(&task[t]); /* no thread: do it here */
    }
}

/* ----------------------------------------------------- inflection points */

/* Input accessor: the caller's double or long double arrays. */
typedef struct SFX(input) {
    const double *xyd, *nd;
    const long double *xyl, *nl;
    size_t n;
    int closed;
    double noise; /* settings.noise: rounding of the input coordinates */
} SFX(input);

static void SFX(in_pt)(const SFX(input) *in, size_t k, REAL *x, REAL *y)
{
    if (in->xyd) {
        *x = (REAL)in->xyd[2 * k];
        *y = (REAL)in->xyd[2 * k + 1];
    } else {
        *x = (REAL)in->xyl[2 * k];
        *y = (REAL)in->xyl[2 * k + 1];
    }
}

static void SFX(in_nrm)(const SFX(input) *in, size_t k, REAL *x, REAL *y)
{
    if (in->nd) {
        *x = (REAL)in->nd[2 * k];
        *y = (REAL)in->nd[2 * k + 1];
    } else {
        *x = (REAL)in->nl[2 * k];
        *y = (REAL)in->nl[2 * k + 1];
    }
}

/*
 * Does edge (i, i+1) need an inflection point (CONIS, before (9)):
 * p_{i-1} and p_{i+2} strictly on different sides of the edge line. Edges
 * without both neighbours (open ends) and edges whose neighbourhood has
 * coincident points never do, as in the reference. In default mode the
 * sides are the exact ones of the input's coordinates (conica__diffprodl in
 * long double, whatever REAL is): the input of both modes is the same, so
 * both insert the same points, also where a neighbour lies on the edge line
 * to within rounding (a midpoint rounded to the input's decimals, as on
 * ExStar_sub0's collinear runs), where a rounded evaluation decides by the
 * sign of its own error.
 */
static int SFX(needs_infl)(const SFX(input) *in, int ref, size_t i)
{
    size_t n = in->n, a, c, d;
    REAL x0, y0, x1, y1, x2, y2, x3, y3, d1, d2, eps = ref ? RC(CONICA__REF_EPS) : 0;

    if (in->closed) {
        a = (i + n - 1) % n;
        c = (i + 1) % n;
        d = (i + 2) % n;
    } else {
        if (i == 0 || i + 2 >= n)
            return 0;
        a = i - 1;
        c = i + 1;
        d = i + 2;
    }
    SFX(in_pt)(in, a, &x0, &y0);
    SFX(in_pt)(in, i, &x1, &y1);
    SFX(in_pt)(in, c, &x2, &y2);
    SFX(in_pt)(in, d, &x3, &y3);
    if ((x0 == x1 && y0 == y1) || (x2 == x3 && y2 == y3) || (x1 == x2 && y1 == y2) ||
        (x0 == x3 && y0 == y3))
        return 0;
    if (ref) {
        REAL nx = y2 - y1, ny = x1 - x2;
        d1 = nx * (x3 - x1) + ny * (y3 - y1);
        d2 = nx * (x0 - x1) + ny * (y0 - y1);
    } else {
        if (in->xyd) {
            /* Double input: the filter decides nearly every edge, the long
             * double test below only those it cannot. */
            const double *p = in->xyd;
            double ex = p[2 * c] - p[2 * i], ey = p[2 * c + 1] - p[2 * i + 1], lim = 0;
            int s1, s2;
            if (in->noise > 0)
                lim = CONICA__NOISE_SIDE * in->noise * sqrt(ex * ex + ey * ey);
            s1 = conica__side_filter(p + 2 * i, p + 2 * c, p + 2 * d, lim);
            s2 = s1 == 0 ? 0 : conica__side_filter(p + 2 * i, p + 2 * c, p + 2 * a, lim);
            if (s1 == 0 || s2 == 0)
                return 0;
            if (s1 != 2 && s2 != 2)
                return s1 != s2;
        }
        /* Differences of two doubles are exact in long double (short of an
         * exponent gap over 11 bits), the products exact by Dekker. */
        long double ex = (long double)x2 - (long double)x1, ey = (long double)y2 - (long double)y1;
        long double e1 = conica__diffprodl(ex, (long double)y3 - (long double)y1, ey,
                                           (long double)x3 - (long double)x1);
        long double e2 = conica__diffprodl(ex, (long double)y0 - (long double)y1, ey,
                                           (long double)x0 - (long double)x1);
        if (e1 == 0 || e2 == 0)
            return 0;
        if (in->noise > 0) {
            /* e1, e2 are |edge| times the distances of the neighbours from
             * the edge line; a distance the input's rounding can make (each
             * of the three points moved by up to noise) is no side. */
            long double lim = (long double)CONICA__NOISE_SIDE * (long double)in->noise *
                              sqrtl(ex * ex + ey * ey);
            if (fabsl(e1) <= lim || fabsl(e2) <= lim)
                return 0;
        }
        return (e1 > 0) != (e2 > 0);
    }
    if (M(fabs)(d1) <= eps || M(fabs)(d2) <= eps)
        return 0;
    return (d1 > 0) != (d2 > 0);
}

static void SFX(unit)(REAL *x, REAL *y)
{
    REAL len = M(sqrt)(FMA(*x, *x, *y * *y));
    *x /= len;
    *y /= len;
}

static REAL SFX(clamped_acos)(REAL c)
{
    return M(acos)(c > 1 ? 1 : (c < -1 ? -1 : c));
}

/* Angle between the unit vectors u and v, in [0, pi]. Reference mode:
 * acos of the dot product, as the reference. Default mode: atan2 of cross
 * and dot, accurate to a rounding unit at every angle; acos loses half the
 * digits near 0 and pi (acos(1 - d) ~ sqrt(2d)), i.e. at the nearly
 * collinear edges where eq. (10) meets inflections, and there its error
 * differs between the modes. */
static REAL SFX(angle)(int ref, REAL ux, REAL uy, REAL vx, REAL vy)
{
    if (ref)
        return SFX(clamped_acos)(ux * vx + uy * vy);
    return M(atan2)(M(fabs)(DIFFPROD_WP(ux, vy, uy, vx)), FMA(ux, vx, uy * vy));
}

/*
 * Candidate inflection normal of eq. (10): (1 - gamma) * orth + gamma * d
 * with gamma = 1/2 - |phi/pi - 1/2|, phi the angle between the edges AB and
 * BC; d = +-BC is the edge direction with the sign that tilts the normal
 * away from the neighbour (as the reference resolves the sign eq. (10)
 * leaves open). Returns the angle between the candidate and the edge normal
 * (the reference's "area weighted" blend uses the lengths of two unit
 * vectors, so it is a no-op there and is left out).
 */
static REAL SFX(infl_candidate)(int ref, REAL abx, REAL aby, REAL bcx, REAL bcy, REAL ox, REAL oy,
                                REAL *nx, REAL *ny)
{
    REAL ang = SFX(angle)(ref, abx, aby, bcx, bcy);
    REAL gam = RC(0.5) - M(fabs)(ang / RC(CONICA__PI) - RC(0.5));
    REAL rx = bcx, ry = bcy, cx, cy;
    if (abx * ox + aby * oy >= 0) {
        rx = -rx;
        ry = -ry;
    }
    *nx = (1 - gam) * ox + gam * rx;
    *ny = (1 - gam) * oy + gam * ry;
    SFX(unit)(nx, ny);
    cx = ox;
    cy = oy;
    if (*nx * ox + *ny * oy < 0) {
        cx = -cx;
        cy = -cy;
    }
    return M(fabs)(SFX(angle)(ref, *nx, *ny, cx, cy));
}

/* Position (9) and normal (10) of the inflection point on edge (i, i+1). */
static void SFX(infl_point)(const SFX(input) *in, int ref, size_t i, REAL *pxy, REAL *pn)
{
    size_t n = in->n, a = (i + n - 1) % n, c = (i + 1) % n, d = (i + 2) % n;
    REAL x0, y0, x1, y1, x2, y2, x3, y3, ax, ay, ex, ey, bx, by, ox, oy, lx, ly, rx, ry, la, ra;

    SFX(in_pt)(in, a, &x0, &y0);
    SFX(in_pt)(in, i, &x1, &y1);
    SFX(in_pt)(in, c, &x2, &y2);
    SFX(in_pt)(in, d, &x3, &y3);
    ax = x0 - x1; /* v0v1 */
    ay = y0 - y1;
    ex = x1 - x2; /* v1v2 */
    ey = y1 - y2;
    bx = x3 - x2; /* v3v2 */
    by = y3 - y2;
    SFX(unit)(&ax, &ay);
    SFX(unit)(&ex, &ey);
    SFX(unit)(&bx, &by);
    ox = -ey;
    oy = ex;
    la = SFX(infl_candidate)(ref, ax, ay, -ex, -ey, ox, oy, &lx, &ly);
    ra = SFX(infl_candidate)(ref, bx, by, ex, ey, ox, oy, &rx, &ry);
    pxy[0] = RC(0.5) * x1 + RC(0.5) * x2;
    pxy[1] = RC(0.5) * y1 + RC(0.5) * y2;
    if (la < ra) {
        pn[0] = lx;
        pn[1] = ly;
    } else {
        pn[0] = rx;
        pn[1] = ry;
    }
    if (!ref) {
        /* Orient like the edge's end normals, so the output's normals keep
         * the input's orientation. */
        REAL n1x, n1y, n2x, n2y;
        SFX(in_nrm)(in, i, &n1x, &n1y);
        SFX(in_nrm)(in, c, &n2x, &n2y);
        SFX(unit)(&n1x, &n1y);
        SFX(unit)(&n2x, &n2y);
        if (pn[0] * (n1x + n2x) + pn[1] * (n1y + n2y) < 0) {
            pn[0] = -pn[0];
            pn[1] = -pn[1];
        }
    }
}

/* The edges that need an inflection point: need[i] for edge (i, i+1),
 * their number returned (SFX(load) reads the flags). Default mode then
 * reads the sign changes at the coordinates' own rounding
 * (conica__infl_at_rounding), so a curve gets the same inflection points
 * wherever it sits; reference mode keeps the reference's test. */
static size_t SFX(count_infl)(const SFX(input) *in, int ref, unsigned char *need)
{
    size_t i, c = 0, ne = in->closed ? in->n : in->n - 1;
    for (i = 0; i < ne; i++) {
        need[i] = (unsigned char)SFX(needs_infl)(in, ref, i);
        c += need[i];
    }
    if (!ref && c >= 2)
        c = conica__infl_at_rounding(in->xyd, in->xyl, in->n, in->closed, in->noise, need);
    return c;
}

/* Is the normal of input vertex v outside the cone of its two edges'
 * normals (u -> v -> w; either orientation)? Then its tangent does not lie
 * between the incoming and outgoing edge directions, and no arc that turns
 * the polygon's way at v leaves v along both edges: the curve's turn
 * changes sign at v itself. */
static int SFX(outside_cone)(const SFX(input) *in, size_t u, size_t v, size_t w)
{
    REAL x0, y0, x1, y1, x2, y2, nx, ny, ux, uy, vx, vy, tx, ty, turn, c1, c2;
    SFX(in_pt)(in, u, &x0, &y0);
    SFX(in_pt)(in, v, &x1, &y1);
    SFX(in_pt)(in, w, &x2, &y2);
    SFX(in_nrm)(in, v, &nx, &ny);
    ux = x1 - x0;
    uy = y1 - y0;
    vx = x2 - x1;
    vy = y2 - y1;
    if ((ux == 0 && uy == 0) || (vx == 0 && vy == 0) || (nx == 0 && ny == 0))
        return 0;
    SFX(unit)(&ux, &uy);
    SFX(unit)(&vx, &vy);
    tx = -ny;
    ty = nx;
    SFX(unit)(&tx, &ty);
    if (tx * (ux + vx) + ty * (uy + vy) < 0) {
        tx = -tx;
        ty = -ty;
    }
    turn = DIFFPROD_WP(ux, vy, uy, vx);
    c1 = DIFFPROD_WP(ux, ty, uy, tx);
    c2 = DIFFPROD_WP(tx, vy, ty, vx);
    if (M(fabs)(turn) <= RC(CONICA__CONE_SINE))
        return 0;
    return turn > 0 ? (c1 < -RC(CONICA__CONE_SINE) || c2 < -RC(CONICA__CONE_SINE))
                    : (c1 > RC(CONICA__CONE_SINE) || c2 > RC(CONICA__CONE_SINE));
}

/*
 * Default mode, an inflection edge (i, i+1) of the polygon whose end
 * normals say there is no inflection inside it: one end normal lies outside
 * its vertex's cone (SFX(outside_cone)) and the two end normals tilt apart
 * as a convex arc's do (the fast path's regular test). A convex arc joins
 * the end pairs, and no convex arc passes through the chord's midpoint of
 * eq. (9): the midpoint would force two more inflections into the edge,
 * which the subdivision draws as a tangle in the comb. The curve's
 * inflection is that vertex (its turn changes sign there), so the point
 * inserted on the edge is the convex arc's: the midpoint of the parabola of
 * the pencil (the quadratic Bezier with the tangent lines' intersection as
 * control point, (p_i + 2 T + p_i+1) / 4, normal perpendicular to the
 * chord), and the vertex is flagged as the inflection point for the
 * patches (none reaches across it). Returns the vertex (i or i+1) and
 * writes the point, or returns (size_t)-1 when eq. (9) stands.
 */
static size_t SFX(infl_at_vertex)(const SFX(input) *in, size_t i, REAL *pxy, REAL *pn)
{
    size_t n = in->n, a = (i + n - 1) % n, c = (i + 1) % n, d = (i + 2) % n, v;
    int o0 = SFX(outside_cone)(in, a, i, c), o1 = SFX(outside_cone)(in, i, c, d);
    REAL x1, y1, x2, y2, n1x, n1y, n2x, n2y, hx, hy, a0, b0, a1, b1, det, r1, r2, txx, tyy;
    REAL px, py, ex, ey;
    if (o0 == o1)
        return (size_t)-1;
    v = o0 ? i : c;
    SFX(in_pt)(in, i, &x1, &y1);
    SFX(in_pt)(in, c, &x2, &y2);
    SFX(in_nrm)(in, i, &n1x, &n1y);
    SFX(in_nrm)(in, c, &n2x, &n2y);
    SFX(unit)(&n1x, &n1y);
    SFX(unit)(&n2x, &n2y);
    hx = x2 - x1;
    hy = y2 - y1;
    a0 = FMA(n1x, hx, n1y * hy);
    b0 = DIFFPROD_WP(hx, n1y, hy, n1x);
    a1 = FMA(n2x, hx, n2y * hy);
    b1 = DIFFPROD_WP(hx, n2y, hy, n2x);
    if (!((a0 * b0) * (a1 * b1) < 0))
        return (size_t)-1; /* the end normals describe an S: eq. (9) */
    /* T: n1 . (T - p_i) = 0 and n2 . (T - p_i+1) = 0 */
    det = DIFFPROD_WP(n1x, n2y, n1y, n2x);
    r1 = FMA(n1x, x1, n1y * y1);
    r2 = FMA(n2x, x2, n2y * y2);
    if (det == 0)
        return (size_t)-1;
    txx = DIFFPROD_WP(r1, n2y, n1y, r2) / det;
    tyy = DIFFPROD_WP(n1x, r2, r1, n2x) / det;
    px = RC(0.25) * x1 + RC(0.5) * txx + RC(0.25) * x2;
    py = RC(0.25) * y1 + RC(0.5) * tyy + RC(0.25) * y2;
    ex = px - (RC(0.5) * x1 + RC(0.5) * x2);
    ey = py - (RC(0.5) * y1 + RC(0.5) * y2);
    /* the parabola stays in the triangle of chord and tangent lines; one
     * that bulges more than an edge length is no fair answer either */
    if (!isfinite(px) || !isfinite(py) ||
        !(FMA(ex, ex, ey * ey) <= RC(CONICA__IRREGULAR_MAX_T) * FMA(hx, hx, hy * hy)))
        return (size_t)-1;
    pxy[0] = px;
    pxy[1] = py;
    pn[0] = -hy;
    pn[1] = hx;
    SFX(unit)(&pn[0], &pn[1]);
    if (pn[0] * (n1x + n2x) + pn[1] * (n1y + n2y) < 0) {
        pn[0] = -pn[0];
        pn[1] = -pn[1];
    }
    return v;
}

/* Level 0: the input with unit normals, plus inflection points on the
 * edges need (SFX(count_infl)) marks, NULL for none. Writes the flags (if
 * flags) and the level-0 indices of inserted points. */
static size_t SFX(load)(const SFX(input) *in, int ref, const unsigned char *need, REAL *xy,
                        REAL *nn, unsigned char *flags, size_t *infl_idx)
{
    size_t i, k = 0, ni = 0;
    int flag_next = 0, flag_first = 0;
    for (i = 0; i < in->n; i++) {
        SFX(in_pt)(in, i, &xy[2 * k], &xy[2 * k + 1]);
        SFX(in_nrm)(in, i, &nn[2 * k], &nn[2 * k + 1]);
        SFX(unit)(&nn[2 * k], &nn[2 * k + 1]);
        if (flags)
            flags[k] = (unsigned char)flag_next;
        flag_next = 0;
        k++;
        if (need && (in->closed || i + 1 < in->n) && need[i]) {
            size_t v = ref ? (size_t)-1 : SFX(infl_at_vertex)(in, i, &xy[2 * k], &nn[2 * k]);
            if (v == (size_t)-1) {
                SFX(infl_point)(in, ref, i, &xy[2 * k], &nn[2 * k]);
                if (flags)
                    flags[k] = 1;
            } else {
                if (flags)
                    flags[k] = 0;
                if (v == i && flags)
                    flags[k - 1] = 1;
                else if (v != i && i + 1 < in->n)
                    flag_next = 1;
                else if (v != i)
                    flag_first = 1; /* closed: the edge back to vertex 0 */
            }
            if (infl_idx)
                infl_idx[ni] = k;
            ni++;
            k++;
        }
    }
    if (flags && flag_first)
        flags[0] = 1;
    return k;
}

/* ---------------------------------------------------------------- driver */

/*
 * Run the whole subdivision. On success *res_xy / *res_n (malloc'ed, N
 * points) hold the result with unit normals and *res_infl the output
 * indices of the inflection points (NULL if none). Nothing is allocated on
 * failure.
 */
static conica_code SFX(run)(const SFX(input) *in, const conica_subdiv_settings *s, REAL **res_xy,
                            REAL **res_n, size_t *res_count, size_t **res_infl, size_t *res_ninfl,
                            conica_subdiv_info *stats, conica_status *st)
{
    int L = s->levels, lev;
    int ref = s->reference_compatible != 0;
    int insert = s->insert_inflections && L > 0;
    unsigned char *need = insert ? malloc(in->n) : NULL; /* SFX(count_infl) */
    size_t ninfl = need ? SFX(count_infl)(in, ref, need) : 0;
    size_t n0 = in->n + ninfl, N, NB = 0, i;
    REAL *A = NULL, *An = NULL, *B = NULL, *Bn = NULL;
    unsigned char *F[2] = {NULL, NULL}; /* inflection flags, double-buffered like A/B */
    size_t *infl = NULL;
    REAL org[2] = {0, 0}; /* the working origin (subdiv_origin.c) */
    SFX(job) job;
    SFX(worker) wk[CONICA__MAX_THREADS];
#if REAL_IS_DOUBLE
    conica__svdws ws[CONICA__MAX_THREADS];
#endif
    int nth = s->threads > 1 ? (s->threads < CONICA__MAX_THREADS ? s->threads : CONICA__MAX_THREADS)
                             : 1, t;
    conica_code code = CONICA_OK;

    if (insert && !need)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory for %zu input points",
                            in->n);
    N = conica_subdiv_count(n0, in->closed, L);
    if (N == 0 || N > s->max_points || N > ((size_t)-1) / (2 * sizeof(REAL))) {
        free(need);
        if (N > 0 && N <= s->max_points)
            return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "output of %zu points is too large",
                                N);
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "%d levels on %zu points (%zu inflection points added) would make "
                            "more than the %zu points allowed (max_points)",
                            L, in->n, ninfl, s->max_points);
    }
    if (L > 0)
        NB = conica_subdiv_count(n0, in->closed, L - 1);
    A = malloc(2 * N * sizeof *A);
    An = malloc(2 * N * sizeof *An);
    if (NB) {
        B = malloc(2 * NB * sizeof *B);
        Bn = malloc(2 * NB * sizeof *Bn);
    }
    /* Flags of levels 0..L-1 (the last level's are not needed): level l
     * in F[(L - l) % 2], at most NB points. */
    if (L > 0) {
        F[0] = malloc(NB);
        F[1] = malloc(NB);
    }
    if (ninfl)
        infl = malloc(ninfl * sizeof *infl);
#if REAL_IS_DOUBLE
    for (t = 0; t < nth; t++)
        conica__svdws_init(&ws[t]);
#endif
    if (!A || !An || (NB && (!B || !Bn)) || (L > 0 && (!F[0] || !F[1])) || (ninfl && !infl))
        code = CONICA_ERR_NOMEM;
    if (code != CONICA_OK) {
        free(A);
        free(An);
        free(B);
        free(Bn);
        free(F[0]);
        free(F[1]);
        free(infl);
        free(need);
#if REAL_IS_DOUBLE
        for (t = 0; t < nth; t++)
            conica__svdws_free(&ws[t]);
#endif
        return conica__fail(st, code, 0, 0, "out of memory for %zu output points", N);
    }

    /* The levels alternate between the two buffers so that the last one
     * lands in A (double buffering, no allocation per level or point). */
    {
        REAL *sx = (L % 2) ? B : A, *sn = (L % 2) ? Bn : An;
        size_t cur = SFX(load)(in, ref, need, sx, sn, L > 0 ? F[L % 2] : NULL, infl);

        free(need);
        /* The levels measure from the working origin (subdiv_origin.c),
         * added back below: exact for the input points (Sterbenz). The
         * reference's mode keeps its absolute coordinates. */
        if (!ref && L > 0) {
            long double c[2];
            conica__subdiv_origin(in->xyd, in->xyl, in->n, c);
            org[0] = (REAL)c[0];
            org[1] = (REAL)c[1];
            for (i = 0; i < cur; i++) {
                sx[2 * i] -= org[0];
                sx[2 * i + 1] -= org[1];
            }
        }

        job.wev = (REAL)s->w_edge_point;
        job.wen = (REAL)s->w_edge_normal;
        job.won = (REAL)s->w_outer_normal;
        job.wov = (REAL)s->tau * (REAL)s->w_outer_normal;
        job.ref = ref;
        job.fast = !ref && !s->force_svd;
        job.plain = s->plain_quadratic != 0;
        job.normalize = s->normalize_normals != 0;
        job.closed = in->closed;
        job.noisy = s->noise > 0;
        job.maxgrow = ref ? (s->patch_grow < 3 ? s->patch_grow : 3) : s->patch_grow;
        for (t = 0; t < nth; t++) {
            wk[t].job = &job;
#if REAL_IS_DOUBLE
            wk[t].ws = &ws[t];
#endif
            wk[t].grown = 0;
            wk[t].fallbacks = 0;
        }
        size_t all_edges = 0, step = 0;
        if (s->progress) { /* the edge points of all levels, reported in ~256 steps */
            size_t c = cur;
            for (lev = 1; lev <= L; lev++) {
                size_t ne = in->closed ? c : c - 1;
                all_edges += ne;
                c += ne;
            }
            step = all_edges / 256 > CONICA__THREAD_MIN_EDGES ? all_edges / 256
                                                               : CONICA__THREAD_MIN_EDGES;
            s->progress(s->progress_ctx, 0, all_edges);
        }
        stats->edge_points = 0;
        for (lev = 1; lev <= L; lev++) {
            REAL *dx = ((L - lev) % 2) ? B : A, *dn = ((L - lev) % 2) ? Bn : An;
            size_t ne = in->closed ? cur : cur - 1;
            job.n = cur;
            job.xy = sx;
            job.nxy = sn;
            job.infl = F[(L - lev + 1) % 2];
            job.dinfl = lev < L ? F[(L - lev) % 2] : NULL;
            if (!s->progress) {
                SFX(level_threads)(wk, nth, dx, dn, 0, cur);
            } else { /* the same points, in slices with a report after each */
                size_t lo, hi;
                for (lo = 0; lo < cur; lo = hi) {
                    hi = cur - lo > step ? lo + step : cur;
                    SFX(level_threads)(wk, nth, dx, dn, lo, hi);
                    s->progress(s->progress_ctx,
                                stats->edge_points + (hi < ne ? hi : ne), all_edges);
                }
            }
            stats->edge_points += ne;
            cur += ne;
            sx = dx;
            sn = dn;
        }
        stats->patch_grown = 0;
        stats->midpoint_fallbacks = 0;
        for (t = 0; t < nth; t++) {
            stats->patch_grown += wk[t].grown;
            stats->midpoint_fallbacks += wk[t].fallbacks;
        }
        (void)cur;
    }
    free(B);
    free(Bn);
    free(F[0]);
    free(F[1]);
#if REAL_IS_DOUBLE
    for (t = 0; t < nth; t++)
        conica__svdws_free(&ws[t]);
#endif
    /* Unit normals out (kept unnormalised between levels, Section 2.3),
     * and never a NaN. */
    for (i = 0; i < N; i++) {
        REAL nx = An[2 * i], ny = An[2 * i + 1], len;
        REAL mag = SFX(maxabs)(nx, ny);
        if (org[0] != 0 || org[1] != 0) {
            A[2 * i] += org[0];
            A[2 * i + 1] += org[1];
        }
        if (!isfinite(A[2 * i]) || !isfinite(A[2 * i + 1]) || !(mag > 0) || !isfinite(mag)) {
            code = conica__fail(st, CONICA_ERR_NUMERIC, 0, i,
                                "point %zu of the output is not finite or has no normal", i);
            break;
        }
        nx /= mag;
        ny /= mag;
        len = M(sqrt)(FMA(nx, nx, ny * ny));
        An[2 * i] = nx / len;
        An[2 * i + 1] = ny / len;
    }
    if (code != CONICA_OK) {
        free(A);
        free(An);
        free(infl);
        return code;
    }
    for (i = 0; i < ninfl; i++)
        infl[i] <<= L;
    *res_xy = A;
    *res_n = An;
    *res_count = N;
    *res_infl = infl;
    *res_ninfl = ninfl;
    stats->inflections = ninfl;
    return CONICA_OK;
}

#undef REAL
#undef SFX
#undef M
#undef FMA
#undef DIFFPROD_WP
#undef RC
#undef R_EPSILON
#undef REAL_IS_DOUBLE
