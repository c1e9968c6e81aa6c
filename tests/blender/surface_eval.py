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
import numpy as np
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


def _span_many(knots, p, n, t):
    """_span() for an array of parameters."""
    knots = np.asarray(knots, dtype=float)
    k = np.clip(np.searchsorted(knots, t, side="right") - 1, p, n - 1)
    return np.where(t >= knots[n], _span(knots, p, n, knots[n]), k)


def _basis_many(knots, p, k, t):
    """_basis() for arrays of spans and parameters: an n x (p + 1) array."""
    knots = np.asarray(knots, dtype=float)
    m = len(t)
    N = np.zeros((m, p + 1))
    N[:, 0] = 1.0
    left = np.zeros((m, p + 1))
    right = np.zeros((m, p + 1))
    for j in range(1, p + 1):
        left[:, j] = t - knots[k + 1 - j]
        right[:, j] = knots[k + j] - t
        saved = np.zeros(m)
        for r in range(j):
            den = right[:, r + 1] + left[:, j - r]
            with np.errstate(divide="ignore", invalid="ignore"):
                tmp = np.where(den != 0.0, N[:, r] / den, 0.0)
            N[:, r] = saved + right[:, r + 1] * tmp
            saved = left[:, j - r] * tmp
        N[:, j] = saved
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

    def at_many(self, u, v):
        """at() for arrays of parameters: an n x 3 array of points."""
        u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
        ku = _span_many(self.ku, self.p, self.nu, u)
        kv = _span_many(self.kv, self.q, self.nv, v)
        Nu = _basis_many(self.ku, self.p, ku, u)
        Nv = _basis_many(self.kv, self.q, kv, v)
        H = self._homogeneous()
        acc = np.zeros((len(u), 4))
        for a in range(self.p + 1):
            for b in range(self.q + 1):
                acc += (Nu[:, a] * Nv[:, b])[:, None] * H[ku - self.p + a, kv - self.q + b]
        return acc[:, :3] / acc[:, 3:]

    def _homogeneous(self):
        if not hasattr(self, "_H"):
            net = np.asarray(self.net, dtype=float)  # nu x nv x (x, y, z, w)
            self._H = np.concatenate((net[..., :3] * net[..., 3:], net[..., 3:]), axis=2)
        return self._H

    def clamp_many(self, u, v):
        """_clamp() for arrays: cyclic directions wrap, others clamp."""
        if self.cu:
            u = self.u0 + np.mod(u - self.u0, self.u1 - self.u0)
        else:
            u = np.clip(u, self.u0, self.u1)
        if self.cv:
            v = self.v0 + np.mod(v - self.v0, self.v1 - self.v0)
        else:
            v = np.clip(v, self.v0, self.v1)
        return u, v

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
    distance larger (the check stays on the safe side). many() runs the
    same iteration for a whole array of points at once (numpy), which is
    what keeps the Blender suite's surface cases at seconds."""

    def __init__(self, surf, dense=96):
        self.s = surf
        # cell centres: no sample on a boundary row, where a pole collapses
        # a whole row to one point and Newton could not leave it
        n = dense
        c = (np.arange(n) + 0.5) / n
        u = np.repeat(surf.u0 + (surf.u1 - surf.u0) * c, n)
        v = np.tile(surf.v0 + (surf.v1 - surf.v0) * c, n)
        self.params = np.stack((u, v), axis=1)
        pts = surf.at_many(u, v)
        self.tree = kdtree.KDTree(n * n)
        for k, p in enumerate(pts.tolist()):
            self.tree.insert(p, k)
        self.tree.balance()
        self.h = 1e-6 * max(surf.u1 - surf.u0, surf.v1 - surf.v0)

    def __call__(self, q):
        return float(self.many(np.asarray([q], dtype=float))[0])

    def many(self, q):
        """The distances of the points q (an n x 3 array) from the surface."""
        s, h = self.s, self.h
        q = np.asarray(q, dtype=float).reshape(-1, 3)
        if len(q) == 0:
            return np.zeros(0)
        start = self.params[[self.tree.find(p)[1] for p in q.tolist()]]
        u, v = start[:, 0].copy(), start[:, 1].copy()
        best = np.linalg.norm(s.at_many(u, v) - q, axis=1)
        live = np.ones(len(q), dtype=bool)
        span = s.u1 - s.u0 + s.v1 - s.v0
        for _ in range(12):
            if not live.any():
                break
            idx = np.nonzero(live)[0]
            uu, vv, qq = u[idx], v[idx], q[idx]
            p = s.at_many(uu, vv)
            Su = (s.at_many(*s.clamp_many(uu + h, vv)) -
                  s.at_many(*s.clamp_many(uu - h, vv))) / (2 * h)
            Sv = (s.at_many(*s.clamp_many(uu, vv + h)) -
                  s.at_many(*s.clamp_many(uu, vv - h))) / (2 * h)
            r = p - qq
            a11 = np.einsum("ij,ij->i", Su, Su)
            a12 = np.einsum("ij,ij->i", Su, Sv)
            a22 = np.einsum("ij,ij->i", Sv, Sv)
            b1 = -np.einsum("ij,ij->i", Su, r)
            b2 = -np.einsum("ij,ij->i", Sv, r)
            det = a11 * a22 - a12 * a12
            full = (det > 1e-12 * (a11 * a22)) & (det > 0.0)
            # a pole (S_v = 0 on the sphere's axis): a step along the
            # direction that still moves the point
            pole = ~full & (np.maximum(a11, a22) > 0.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                du = np.where(full, (b1 * a22 - b2 * a12) / det,
                              np.where(pole & (a11 >= a22), b1 / a11, 0.0))
                dv = np.where(full, (a11 * b2 - a12 * b1) / det,
                              np.where(pole & (a11 < a22), b2 / a22, 0.0))
            stuck = ~full & ~pole  # no direction moves the point: stop there
            du[stuck] = 0.0
            dv[stuck] = 0.0
            un, vn = s.clamp_many(uu + du, vv + dv)
            d = np.linalg.norm(s.at_many(un, vn) - qq, axis=1)
            best[idx] = np.minimum(best[idx], d)
            u[idx], v[idx] = un, vn
            done = stuck | (np.abs(du) + np.abs(dv) < 1e-13 * span)
            live[idx[done]] = False
        return best


def mesh_arrays(me):
    """(vertices n x 3, loop vertex indices, loop starts, loop totals) of a
    mesh, read with foreach_get."""
    co = np.zeros(3 * len(me.vertices))
    me.vertices.foreach_get("co", co)
    lv = np.zeros(len(me.loops), dtype=np.int32)
    me.loops.foreach_get("vertex_index", lv)
    ls = np.zeros(len(me.polygons), dtype=np.int32)
    lt = np.zeros(len(me.polygons), dtype=np.int32)
    me.polygons.foreach_get("loop_start", ls)
    me.polygons.foreach_get("loop_total", lt)
    return co.reshape(-1, 3), lv, ls, lt


def mesh_deviation(me, dist, world=None):
    """Largest distance of a mesh from the surface: every vertex, and on
    every face its centre and the midpoints of its edges (a quad's
    bilinear interior strays most there; an edge two faces share is
    measured once)."""
    co, lv, ls, lt = mesh_arrays(me)
    worst_vertex = float(dist.many(co).max()) if len(co) else 0.0
    if len(ls) == 0:
        return worst_vertex, 0.0
    face = np.repeat(np.arange(len(ls)), lt)
    cen = np.zeros((len(ls), 3))
    np.add.at(cen, face, co[lv])
    cen /= lt[:, None]
    # each loop's edge: its vertex and the next one around its face
    pos = np.arange(len(lv)) - np.repeat(ls, lt)
    nxt = lv[np.repeat(ls, lt) + (pos + 1) % np.repeat(lt, lt)]
    edges = np.unique(np.sort(np.stack((lv, nxt), axis=1), axis=1), axis=0)
    mid = (co[edges[:, 0]] + co[edges[:, 1]]) / 2
    worst_face = float(max(dist.many(cen).max(), dist.many(mid).max()))
    return worst_vertex, worst_face
