# SPDX-License-Identifier: MIT
"""Check a scadprofile module against the exact geometry of its DXF:

    python3 tests/dxf/check.py IN.dxf OUT.scad MODULE TOL [FIT] [options]
    python3 tests/dxf/check.py --batch JOBS    (a check per line: LABEL, tab, ARGS)

FIT is inside (default), outside or middle. Options:
    --unit-mm F      millimetres per output unit (default 1)
    --layers A,B     only entities on these layers
    --contours N     the module must have exactly N contours
    --hatch          the exact geometry is the HATCH boundaries
    --touch          contours meet at points: the fit's side may be off by
                     tol/100 there (scadprofile separates them so)

The exact geometry is evaluated here, independently of Conica: lines and
the arcs of bulges by their formulas, ARC / CIRCLE / ELLIPSE by ezdxf's
own vertices() (which apply the entity's OCS), SPLINEs by a de Boor
evaluation of the rational B-spline written below, INSERTs expanded by
ezdxf's virtual_entities(). Densely sampled (the samples' own chord error
is below 1e-6 of the tolerance), then

  - deviation, both ways: every exact sample within TOL of the module's
    polygons and every point of the polygons (edges sampled) within TOL of
    the exact geometry;
  - fit sign, of the region the contours bound (outlines and holes alike,
    by parity): inside: no exact point (the curves' samples, straight
    edges sampled too) lies in the polygons' region; outside: every one
    does; both up to the written digits and the samples (2.5 TOL/1000);
  - every contour kept: each contour of the module lies along the exact
    geometry and each exact entity is near some contour (the two-sided
    deviation), and --contours N when given.
Prints the figures; exit 1 on a failed check."""
import math
import re
import shlex
import sys

import ezdxf
import numpy as np
from ezdxf.math import bulge_to_arc

UNITS_MM = {0: 1, 1: 25.4, 2: 304.8, 4: 1, 5: 10, 6: 1000}


def de_boor(p, knots, ctrl, w, t):
    """Point of the rational B-spline at t (homogeneous de Boor)."""
    n = len(ctrl)
    k = p
    while k + 1 < n and knots[k + 1] <= t:
        k += 1
    d = [np.array([ctrl[j][0] * w[j], ctrl[j][1] * w[j], w[j]], float) for j in range(k - p, k + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            i = j + k - p
            den = knots[i + p - r + 1] - knots[i]
            a = 0.0 if den == 0 else (t - knots[i]) / den
            d[j] = (1 - a) * d[j - 1] + a * d[j]
    return d[p][:2] / d[p][2]


def spline_samples(p, knots, ctrl, w, m):
    a, b = knots[p], knots[len(ctrl)]
    ts = np.linspace(a, b, m)
    return [de_boor(p, knots, ctrl, w, t) for t in ts]


TOL = [1.0]  # the tolerance checked (main sets it)


def count(r, sweep, m):
    """Samples of an arc of radius r and sweep (radians) whose chords stay
    within 1e-3 of the tolerance of it, at most m per turn."""
    n = math.pi * math.sqrt(abs(r) / (2e-3 * TOL[0])) * abs(sweep) / (2 * math.pi)
    return int(min(m * abs(sweep) / (2 * math.pi) + 2, max(16, n + 2)))


def arc_samples(c, r, a0, a1, m):
    while a1 <= a0:
        a1 += 2 * math.pi
    t = np.linspace(a0, a1, count(r, a1 - a0, m))
    return np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)])


def poly_samples(pts, closed, ocs, m):
    """LWPOLYLINE / POLYLINE vertices (x, y, bulge) as polylines of samples."""
    out = []
    n = len(pts)
    for i in range(n if closed else n - 1):
        x0, y0, b = pts[i]
        x1, y1, _ = pts[(i + 1) % n]
        if b == 0:
            seg = [(x0, y0), (x1, y1)]
        else:
            c, s, e, r = bulge_to_arc((x0, y0), (x1, y1), b)
            seg = arc_samples(c, r, s, e, m)
        seg = np.array(seg, float)
        z = ocs.uz
        if abs(z.x) < 1e-12 and abs(z.y) < 1e-12:  # +-z: identity or x mirrored
            seg[:, 0] *= 1 if z.z > 0 else -1
            out.append(seg)
        else:
            out.append([tuple(ocs.to_wcs((x, y, 0)))[:2] for x, y in seg])
    return out


def entity_samples(e, m, pieces):
    t = e.dxftype()
    if t == "LINE":
        pieces.append([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
    elif t == "CIRCLE":
        k = count(e.dxf.radius, 2 * math.pi, m)
        pieces.append([tuple(v)[:2] for v in e.vertices(np.linspace(0, 360, k))])
    elif t == "ARC":
        s, en = e.dxf.start_angle, e.dxf.end_angle
        while en <= s:
            en += 360
        k = count(e.dxf.radius, math.radians(en - s), m)
        pieces.append([tuple(v)[:2] for v in e.vertices(np.linspace(s, en, k))])
    elif t == "ELLIPSE":
        s, en = e.dxf.start_param, e.dxf.end_param
        while en <= s:
            en += 2 * math.pi
        pieces.append([tuple(v)[:2] for v in e.vertices(np.linspace(s, en, m))])
    elif t == "LWPOLYLINE":
        pts = [(x, y, b) for x, y, _, _, b in e.get_points("xyseb")]
        pieces.extend(poly_samples(pts, e.closed, e.ocs(), m))
    elif t == "POLYLINE":
        pts = [(v.dxf.location.x, v.dxf.location.y, v.dxf.bulge) for v in e.vertices]
        pieces.extend(poly_samples(pts, e.is_closed, e.ocs(), m))
    elif t == "SPLINE":
        ctrl = [tuple(v)[:2] for v in e.control_points]
        w = list(e.weights) or [1.0] * len(ctrl)
        pieces.append(spline_samples(e.dxf.degree, list(e.knots), ctrl, w, 4 * m))
    elif t == "INSERT":
        for one in e.multi_insert():  # a column/row array, copy by copy
            for v in one.virtual_entities():
                entity_samples(v, m, pieces)


def hatch_samples(h, m, pieces):
    for path in h.paths:
        if hasattr(path, "vertices"):
            pts = [(x, y, b) for x, y, b in path.vertices]
            pieces.extend(poly_samples(pts, True, h.ocs(), m))
            continue
        for edge in path.edges:
            k = type(edge).__name__
            if k == "LineEdge":
                pieces.append([tuple(edge.start)[:2], tuple(edge.end)[:2]])
            elif k == "ArcEdge":
                pieces.append(arc_samples(edge.center, edge.radius, math.radians(edge.start_angle),
                                          math.radians(edge.end_angle), m))
            elif k == "EllipseEdge":
                ce = edge.construction_tool()
                s, en = ce.start_param, ce.end_param
                while en <= s:
                    en += 2 * math.pi
                pieces.append([tuple(v)[:2] for v in ce.vertices(np.linspace(s, en, m))])
            elif k == "SplineEdge":
                ctrl = [tuple(v)[:2] for v in edge.control_points]
                w = list(edge.weights) or [1.0] * len(ctrl)
                pieces.append(spline_samples(edge.degree, list(edge.knot_values), ctrl, w, 4 * m))


def split(A, B, step):
    """The segments A[i]B[i] cut into pieces of at most step."""
    k = np.maximum(1, np.ceil(np.hypot(*(B - A).T) / step)).astype(int)
    if k.max() == 1:
        return A, B
    i = np.repeat(np.arange(len(A)), k)
    j = np.arange(len(i)) - np.repeat(np.cumsum(k) - k, k)
    f0, f1 = (j / k[i])[:, None], ((j + 1) / k[i])[:, None]
    return A[i] + f0 * (B[i] - A[i]), A[i] + f1 * (B[i] - A[i])


def seg_dist(P, A, B, w=None):
    """Distance of each point of P (k x 2) to the nearest segment A[i]B[i];
    with w, inf beyond w (only the segments near a point are looked at)."""
    P = np.asarray(P, float).reshape(-1, 2)
    best = np.full(len(P), np.inf)
    if len(P) == 0 or len(A) == 0:
        return best
    if w is None or not np.isfinite(w):
        for k in range(0, len(P), 64):
            best[k:k + 64] = pair_dist(P[k:k + 64, None, :], A, B).min(1)
        return best
    # segments cut into pieces of at most 2 w; a point within w of a piece
    # is within 2 w of its middle: the grid cell of 2 w of the point or
    # one of its 8 neighbours
    A, B = split(A, B, 2 * w)
    c = 2 * w
    lo = np.minimum(A.min(0), P.min(0)) - 2 * c
    Mc = np.floor((0.5 * (A + B) - lo) / c).astype(np.int64)
    Qc = np.floor((P - lo) / c).astype(np.int64)
    ny = max(Mc[:, 1].max(), Qc[:, 1].max()) + 3
    key = Mc[:, 0] * ny + Mc[:, 1]
    order = np.argsort(key, kind="stable")
    A, B, key = A[order], B[order], key[order]
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            q = (Qc[:, 0] + dx) * ny + Qc[:, 1] + dy
            a = np.searchsorted(key, q, "left")
            n = np.searchsorted(key, q, "right") - a
            k = 0
            while k < len(P):
                # a run of points with at most 4e6 pairs
                e = k + max(1, int(np.searchsorted(np.cumsum(n[k:]), 4000000)))
                cnt = n[k:e]
                tot = int(cnt.sum())
                if tot:
                    qi = np.repeat(np.arange(k, e), cnt)
                    si = np.repeat(a[k:e], cnt) + np.arange(tot) - np.repeat(np.cumsum(cnt) - cnt, cnt)
                    d = pair_dist(P[qi], A[si], B[si])
                    starts = np.cumsum(cnt) - cnt
                    has = cnt > 0
                    m = np.minimum.reduceat(d, starts[has])
                    rows = np.arange(k, e)[has]
                    best[rows] = np.minimum(best[rows], m)
                k = e
    best[best > w] = np.inf
    return best


def pair_dist(Q, A, B):
    """Distance of Q to the segment AB, elementwise (broadcast)."""
    AB = B - A
    L = np.maximum((AB ** 2).sum(-1), 1e-300)
    t = np.clip(((Q - A) * AB).sum(-1) / L, 0, 1)
    return np.sqrt(((A + t[..., None] * AB - Q) ** 2).sum(-1))


def inside(poly, P):
    """Winding test (non-zero) of points P against a closed polygon."""
    x, y = P[:, 0], P[:, 1]
    res = np.zeros(len(P), bool)
    n = len(poly)
    for i in range(n):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % n]
        c = ((y0 > y) != (y1 > y)) & (x < (x1 - x0) * (y - y0) / ((y1 - y0) or 1e-300) + x0)
        res ^= c
    return res


def exact_geometry(dxf, tol, unit_mm, layers, hatch):
    """The drawing's exact geometry as dense polylines in output units, and
    its size."""
    doc = ezdxf.readfile(dxf)
    scale = UNITS_MM.get(doc.header.get("$INSUNITS", 0), 1) / unit_mm
    TOL[0] = tol / scale  # in drawing units, as the radii

    def sample(m):
        pieces = []
        for e in doc.modelspace():
            if layers is not None and e.dxf.layer not in layers:
                continue
            if hatch and e.dxftype() == "HATCH":
                hatch_samples(e, m, pieces)
            elif not hatch:
                entity_samples(e, m, pieces)
        return pieces
    # samples per entity: their chords within 1e-4 of the tolerance of the
    # curves (radius at most the drawing's size)
    rough = np.concatenate([np.array(p, float) for p in sample(200)]) * scale
    size = max(np.ptp(rough[:, 0]), np.ptp(rough[:, 1]), 1e-9)
    m = int(min(100000, max(1000, math.pi * math.sqrt(size / (4e-3 * tol)))))
    pieces = [np.array(p, float) * scale for p in sample(m) if len(p) >= 2]
    return pieces, size


def check(args, cache):
    """One check (the command line's arguments); True when it passes. The
    exact geometry of a drawing is kept in cache for its next check."""
    dxf, scad, module, tol = args[0], args[1], args[2], float(args[3])
    fit = args[4] if len(args) > 4 and not args[4].startswith("--") else "inside"
    unit_mm, layers, want, hatch, touch = 1.0, None, None, False, False
    for i, a in enumerate(args):
        if a == "--unit-mm":
            unit_mm = float(args[i + 1])
        elif a == "--layers":
            layers = set(args[i + 1].split(","))
        elif a == "--contours":
            want = int(args[i + 1])
        elif a == "--hatch":
            hatch = True
        elif a == "--touch":
            touch = True
    key = (dxf, tol, unit_mm, tuple(sorted(layers)) if layers is not None else None, hatch)
    if key not in cache:
        cache[key] = exact_geometry(dxf, tol, unit_mm, layers, hatch)
    pieces, size = cache[key]
    A0 = np.concatenate([p[:-1] for p in pieces])
    A1 = np.concatenate([p[1:] for p in pieces])
    exact = np.concatenate(pieces)

    text = open(scad).read()
    pts = re.search(r"function %s_points\(\) = \[(.*?)\];" % module, text, re.S).group(1)
    P = np.array([[float(a), float(b)] for a, b in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", pts)])
    paths = re.search(r"function %s_paths\(\) = \[(.*?)\];\s*\n" % module, text, re.S).group(1)
    polys = [P[[int(i) for i in re.findall(r"\d+", p)]] for p in re.findall(r"\[([0-9, \n]+)\]", paths)]
    E0 = np.concatenate([q for q in polys])
    E1 = np.concatenate([np.roll(q, -1, 0) for q in polys])
    # polygon points: vertices and 16 points along every edge
    f = np.linspace(0, 1, 17)[:-1]
    dense = np.concatenate([E0 + t * (E1 - E0) for t in f])
    d_out = seg_dist(dense, A0, A1, 2 * tol).max()          # polygon -> exact
    d_in = seg_dist(exact, E0, E1, 2 * tol).max()           # exact -> polygon
    ok = True
    print("contours %d, points %d, exact samples %d" % (len(polys), len(P), len(exact)))
    print("deviation polygon->exact %.3g, exact->polygon %.3g, tolerance %g" % (d_out, d_in, tol))
    # the samples' chords are within 1e-3 of the tolerance of the curves
    if not (d_out <= 1.001 * tol and d_in <= 1.001 * tol):
        print("FAIL: deviation beyond the tolerance")
        ok = False
    if want is not None and len(polys) != want:
        print("FAIL: %d contours, expected %d" % (len(polys), want))
        ok = False
    if fit in ("inside", "outside"):
        # the fit's side, of the region: each exact point (edges sampled
        # every step, lines too) is in the polygons' region (parity over
        # every contour: outlines and holes) or on their edge (the written
        # digits and the samples, 2.5 TOL/1000); inside: never in it
        step = max(size / 4000, tol / 4)
        bnd = np.concatenate([split(A0, A1, step)[0], A1])
        par = np.zeros(len(bnd), bool)
        for q in polys:
            lo, hi = q.min(0), q.max(0)
            sel = np.nonzero((bnd >= lo).all(1) & (bnd <= hi).all(1))[0]
            par[sel] ^= inside(q, bnd[sel])
        wrong = bnd[par] if fit == "inside" else bnd[~par]
        worst = seg_dist(wrong, E0, E1, 2 * tol).max() if len(wrong) else 0.0
        print("%s: exact points on the wrong side of the polygon by at most %.3g (%d points)"
              % (fit, worst, len(bnd)))
        # --touch: where two contours meet at a point, scadprofile moves
        # each copy of it tol/100 into its own material (docs/scadprofile.md)
        if worst > (1.01e-2 if touch else 2.5e-3) * tol:
            print("FAIL: the polygon %s the drawn region"
                  % ("adds material beyond" if fit == "inside" else "cuts into"))
            ok = False
    return ok


def main():
    """One check, or with --batch FILE one per line of FILE (LABEL, a tab,
    the arguments), each printed between '=== LABEL' and 'RESULT LABEL
    ok|FAIL' (exit 1 when one failed): a drawing's exact geometry is
    computed once for all its checks."""
    args = sys.argv[1:]
    if args[:1] != ["--batch"]:
        sys.exit(0 if check(args, {}) else 1)
    cache, bad = {}, 0
    for line in open(args[1]):
        if not line.strip():
            continue
        label, rest = line.rstrip("\n").split("\t", 1)
        print("=== " + label)
        try:
            ok = check(shlex.split(rest), cache)
        except Exception as e:  # a module that does not parse, a file missing
            print("FAIL: %s: %s" % (type(e).__name__, e))
            ok = False
        bad += not ok
        print("RESULT %s %s" % (label, "ok" if ok else "FAIL"), flush=True)
    sys.exit(1 if bad else 0)


main()
