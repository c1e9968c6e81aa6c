# SPDX-License-Identifier: GPL-3.0-or-later
"""A NURBS surface evaluator of its own and mesh-to-surface distances, for
the Blender suite (tests/blender/test_addon.py) and the surface table of
bench/bench_blender.py. Independent of the add-on's plotter: it reads the
control net, weights, orders and settings a Blender SURFACE spline exposes
and evaluates the rational tensor product directly (Cox-de Boor basis,
"The NURBS Book" A2.2). The knot vectors are Blender's (the caller passes
them: the add-on's nurbs_knots, itself checked against Blender's own
evaluation, and here again by check_against_blender()).
"""
import math

from mathutils import kdtree


def _span(knots, p, n, t):
    """Index k with knots[k] <= t < knots[k+1], p <= k < n (n control points)."""
    if t >= knots[n]:  # the end: the last span of non-zero length
        k = n - 1
        while k > p and knots[k] == knots[k + 1]:
            k -= 1
        return k
    lo, hi = p, n
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if knots[mid] <= t:
            lo = mid
        else:
            hi = mid
    return lo


def _basis(knots, p, k, t):
    """The p + 1 non-zero basis functions N_{k-p..k}(t)."""
    N = [1.0] + [0.0] * p
    left = [0.0] * (p + 1)
    right = [0.0] * (p + 1)
    for j in range(1, p + 1):
        left[j] = t - knots[k + 1 - j]
        right[j] = knots[k + j] - t
        saved = 0.0
        for r in range(j):
            den = right[r + 1] + left[j - r]
            tmp = N[r] / den if den != 0.0 else 0.0
            N[r] = saved + right[r + 1] * tmp
            saved = left[j - r] * tmp
        N[j] = saved
    return N


class Surface:
    """A NURBS surface from a Blender SURFACE spline: net[i][j] = (x, y, z, w)
    with i along u, wrapped by order - 1 in a cyclic direction."""

    def __init__(self, sp, knots_fn):
        pu, pv = sp.point_count_u, sp.point_count_v
        self.p = max(2, min(sp.order_u, pu)) - 1
        self.q = max(2, min(sp.order_v, pv)) - 1
        self.cu, self.cv = sp.use_cyclic_u, sp.use_cyclic_v
        self.ku = knots_fn(pu, self.p + 1, self.cu, sp.use_endpoint_u, sp.use_bezier_u)
        self.kv = knots_fn(pv, self.q + 1, self.cv, sp.use_endpoint_v, sp.use_bezier_v)
        self.nu = pu + (self.p if self.cu else 0)
        self.nv = pv + (self.q if self.cv else 0)
        pts = [tuple(p.co) for p in sp.points]  # points[v * pu + u]
        self.net = [[pts[(j % pv) * pu + (i % pu)] for j in range(self.nv)]
                    for i in range(self.nu)]
        self.u0, self.u1 = self.ku[self.p], self.ku[self.nu]
        self.v0, self.v1 = self.kv[self.q], self.kv[self.nv]

    def at(self, u, v):
        ku, kv = _span(self.ku, self.p, self.nu, u), _span(self.kv, self.q, self.nv, v)
        Nu, Nv = _basis(self.ku, self.p, ku, u), _basis(self.kv, self.q, kv, v)
        x = y = z = den = 0.0
        for a in range(self.p + 1):
            row = self.net[ku - self.p + a]
            for b in range(self.q + 1):
                px, py, pz, pw = row[kv - self.q + b]
                c = Nu[a] * Nv[b] * pw
                x += c * px
                y += c * py
                z += c * pz
                den += c
        return (x / den, y / den, z / den)

    def _clamp(self, u, v):
        if self.cu:
            u = self.u0 + (u - self.u0) % (self.u1 - self.u0)
        else:
            u = min(self.u1, max(self.u0, u))
        if self.cv:
            v = self.v0 + (v - self.v0) % (self.v1 - self.v0)
        else:
            v = min(self.v1, max(self.v0, v))
        return u, v


class Distance:
    """Distance from points to the surface: a dense parameter grid's nearest
    sample (mathutils KD tree) as the start, then Gauss-Newton on
    |S(u, v) - q|^2 with central-difference derivatives. Starting from the
    nearest of a dense sampling finds the global foot point on the smooth
    primitives measured here; a local minimum elsewhere could only make a
    distance larger (the check stays on the safe side)."""

    def __init__(self, surf, dense=96):
        self.s = surf
        self.params = []
        # cell centres: no sample on a boundary row, where a pole collapses
        # a whole row to one point and Newton could not leave it
        n = dense
        self.tree = kdtree.KDTree(n * n)
        k = 0
        for a in range(n):
            u = surf.u0 + (surf.u1 - surf.u0) * (a + 0.5) / n
            for b in range(n):
                v = surf.v0 + (surf.v1 - surf.v0) * (b + 0.5) / n
                self.tree.insert(surf.at(u, v), k)
                self.params.append((u, v))
                k += 1
        self.tree.balance()
        self.h = 1e-6 * max(surf.u1 - surf.u0, surf.v1 - surf.v0)

    def __call__(self, q):
        s, h = self.s, self.h
        u, v = self.params[self.tree.find(q)[1]]
        best = math.dist(s.at(u, v), q)
        for _ in range(12):
            p = s.at(u, v)
            pu1, pu0 = s.at(*s._clamp(u + h, v)), s.at(*s._clamp(u - h, v))
            pv1, pv0 = s.at(*s._clamp(u, v + h)), s.at(*s._clamp(u, v - h))
            Su = [(pu1[c] - pu0[c]) / (2 * h) for c in range(3)]
            Sv = [(pv1[c] - pv0[c]) / (2 * h) for c in range(3)]
            r = [p[c] - q[c] for c in range(3)]
            a11 = sum(x * x for x in Su)
            a12 = sum(Su[c] * Sv[c] for c in range(3))
            a22 = sum(x * x for x in Sv)
            b1 = -sum(Su[c] * r[c] for c in range(3))
            b2 = -sum(Sv[c] * r[c] for c in range(3))
            det = a11 * a22 - a12 * a12
            if det > 1e-12 * (a11 * a22) and det > 0.0:
                du = (b1 * a22 - b2 * a12) / det
                dv = (a11 * b2 - a12 * b1) / det
            elif max(a11, a22) > 0.0:
                # a pole (S_v = 0 on the sphere's axis): a step along the
                # direction that still moves the point
                du, dv = (b1 / a11, 0.0) if a11 >= a22 else (0.0, b2 / a22)
            else:
                break
            u, v = s._clamp(u + du, v + dv)
            d = math.dist(s.at(u, v), q)
            best = min(best, d)
            if abs(du) + abs(dv) < 1e-13 * (s.u1 - s.u0 + s.v1 - s.v0):
                break
        return best


def mesh_deviation(me, dist, world=None):
    """Largest distance of a mesh from the surface: every vertex, and on
    every face its centre and the midpoints of its edges (a quad's
    bilinear interior strays most there)."""
    co = [tuple(v.co) for v in me.vertices]
    worst_vertex = max((dist(p) for p in co), default=0.0)
    worst_face = 0.0
    for poly in me.polygons:
        idx = list(poly.vertices)
        pts = [co[i] for i in idx]
        n = len(pts)
        cen = tuple(sum(p[c] for p in pts) / n for c in range(3))
        worst_face = max(worst_face, dist(cen))
        for a in range(n):
            p, q = pts[a], pts[(a + 1) % n]
            worst_face = max(worst_face, dist(tuple((p[c] + q[c]) / 2 for c in range(3))))
    return worst_vertex, worst_face
