# SPDX-License-Identifier: GPL-3.0-or-later
# Conic Subdivide vs Blender's own Subdivide, inside one Blender run:
#   CONICA_ZIP=build/conica-blender.zip BLENDER_USER_SCRIPTS=$tmp \
#   blender -b --factory-startup --python bench/bench_blender.py
# (scripts/bench-blender.sh does exactly that). A 1000-point cyclic POLY
# spline (a convex closed curve, so both produce 8000 points) refined by
# curve.conic_subdivide(levels=3) and by curve.subdivide(number_cuts=7);
# median of REPEATS runs each, on a fresh copy of the curve every time.
# Prints figures only, asserts nothing.
import math
import os
import statistics
import sys
import time

import addon_utils
import bpy

N = 1000
REPEATS = int(os.environ.get("CONICA_BENCH_REPEATS", "5"))


def setup():
    z = os.environ["CONICA_ZIP"]
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(z), overwrite=True)
    if addon_utils.enable("conica", default_set=True) is None:
        print("bench-blender: error: the add-on did not load", file=sys.stderr)
        sys.exit(1)
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    bpy.context.view_layer.update()


def link_selected(ob):
    """Link ob to the scene as the only selected, active object."""
    bpy.context.scene.collection.objects.link(ob)
    for o in bpy.context.view_layer.objects:
        if o is not None:
            o.select_set(False)
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob


def make_curve(name):
    cu = bpy.data.curves.new(name, "CURVE")
    cu.dimensions = "3D"
    sp = cu.splines.new("POLY")
    sp.points.add(N - 1)
    co = []
    for i in range(N):
        t = 2 * math.pi * i / N
        # a convex closed curve (superellipse-like, no inflections)
        co += [3.0 * math.cos(t), 2.0 * math.sin(t) + 0.2 * math.sin(t) ** 3, 0.0, 1.0]
    sp.points.foreach_set("co", co)
    sp.use_cyclic_u = True
    ob = bpy.data.objects.new(name, cu)
    link_selected(ob)
    return ob


def drop(ob):
    cu = ob.data
    bpy.data.objects.remove(ob, do_unlink=True)
    bpy.data.curves.remove(cu)


def points(ob):
    return sum(len(s.points) for s in ob.data.splines)


def run_conic(edit):
    ops = sys.modules["conica"].operators
    ob = make_curve("conic")
    if edit:
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
    # bpy.ops evaluates the view layer before an operator: do it here so the
    # timing holds the operator and the evaluation of its result only, as
    # for Blender's own operator below.
    bpy.context.view_layer.update()
    c0 = time.process_time()
    t0 = time.perf_counter()
    bpy.ops.curve.conic_subdivide(levels=3)
    t = time.perf_counter() - t0
    cpu = time.process_time() - c0
    if edit:
        bpy.ops.object.mode_set(mode="OBJECT")
    n = points(ob)
    timing = dict(ops.last_timing)
    drop(ob)
    return t, n, timing, cpu


def run_blender(with_switch):
    ob = make_curve("blender")
    bpy.context.view_layer.update()
    if with_switch:
        c0 = time.process_time()
        t0 = time.perf_counter()
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
        bpy.ops.curve.subdivide(number_cuts=7)
        bpy.ops.object.mode_set(mode="OBJECT")
        t = time.perf_counter() - t0
        cpu = time.process_time() - c0
    else:
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
        bpy.context.view_layer.update()
        c0 = time.process_time()
        t0 = time.perf_counter()
        bpy.ops.curve.subdivide(number_cuts=7)
        t = time.perf_counter() - t0
        cpu = time.process_time() - c0
        bpy.ops.object.mode_set(mode="OBJECT")
    n = points(ob)
    drop(ob)
    return t, n, None, cpu


def evaluation_cost():
    """CPU ms Blender spends evaluating the refined 8000-point curve after
    an operator (bpy.ops updates the view layer): in edit mode after its own
    Subdivide, in object mode after Conic Subdivide's kind of change."""
    ed, obj = [], []
    for _ in range(REPEATS):
        ob = make_curve("eval")
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
        bpy.ops.curve.subdivide(number_cuts=7)
        ob.update_tag(refresh={"DATA"})
        c0 = time.process_time()
        bpy.context.view_layer.update()
        ed.append(time.process_time() - c0)
        bpy.ops.object.mode_set(mode="OBJECT")
        ob.update_tag(refresh={"DATA"})
        c0 = time.process_time()
        bpy.context.view_layer.update()
        obj.append(time.process_time() - c0)
        drop(ob)
    return median_ms(ed), median_ms(obj)


def median_ms(xs):
    return 1e3 * statistics.median(xs)


def main():
    setup()
    run_conic(False)  # warm up (first call loads and caches)
    run_blender(False)
    # Interleaved, so a busy machine slows both sides alike.
    conic, conic_edit, bl, bl_sw = [], [], [], []
    for _ in range(REPEATS):
        conic.append(run_conic(False))
        bl.append(run_blender(False))
        conic_edit.append(run_conic(True))
        bl_sw.append(run_blender(True))
    def med(rows, k):
        return median_ms([r[k] for r in rows])
    c_ms, ce_ms, b_ms, bs_ms = (med(r, 0) for r in (conic, conic_edit, bl, bl_sw))
    c_cpu, ce_cpu, b_cpu, bs_cpu = (med(r, 3) for r in (conic, conic_edit, bl, bl_sw))
    split = {k: median_ms([c[2][k] for c in conic]) for k in
             ("read", "extension", "libcore", "write", "total")}
    split_edit = {k: median_ms([c[2][k] for c in conic_edit]) for k in
                  ("read", "extension", "libcore", "write", "total")}
    print("Blender %s, %d-point cyclic POLY spline, median of %d interleaved runs "
          "(wall clock and process CPU time)" % (bpy.app.version_string, N, REPEATS))
    print("| operation | output points | median ms (wall) | median ms (CPU) |")
    print("|---|---|---|---|")
    print("| curve.conic_subdivide(levels=3), object mode | %d | %.2f | %.2f |" %
          (conic[0][1], c_ms, c_cpu))
    print("| curve.conic_subdivide(levels=3), edit mode | %d | %.2f | %.2f |" %
          (conic_edit[0][1], ce_ms, ce_cpu))
    print("| curve.subdivide(number_cuts=7), edit mode, operator only | %d | %.2f | %.2f |" %
          (bl[0][1], b_ms, b_cpu))
    print("| curve.subdivide(number_cuts=7) + edit-mode switches | %d | %.2f | %.2f |" %
          (bl_sw[0][1], bs_ms, bs_cpu))
    print()
    print("Conic Subdivide, object mode, split (median wall ms): read (foreach_get) %.3f, "
          "_conica call %.3f of which libcore %.3f, write (new spline + foreach_set) %.3f, "
          "execute() total %.3f; the rest of the bpy.ops call is Blender evaluating "
          "the new 8000-point curve" % (split["read"], split["extension"], split["libcore"],
                                        split["write"], split["total"]))
    print("Conic Subdivide, edit mode, split (median wall ms): read %.3f, _conica call %.3f "
          "of which libcore %.3f, write %.3f, execute() total %.3f" %
          (split_edit["read"], split_edit["extension"], split_edit["libcore"],
           split_edit["write"], split_edit["total"]))
    ev_edit, ev_obj = evaluation_cost()
    print("Blender's evaluation of the 8000-point result (median CPU ms), inside both "
          "operators' times: edit mode %.2f, object mode %.2f" % (ev_edit, ev_obj))
    print("ratio conic (object mode) / Blender operator only: %.2fx wall, %.2fx CPU "
          "(goal <= 2x)" % (c_ms / b_ms, c_cpu / b_cpu))
    print("ratio conic (edit mode) / Blender operator only (edit mode): %.2fx wall, "
          "%.2fx CPU (goal <= 1.5x; both edit-mode operators)" % (ce_ms / b_ms, ce_cpu / b_cpu))
    print("ratio conic (object mode) / Blender operator with mode switches: %.2fx wall, "
          "%.2fx CPU" % (c_ms / bs_ms, c_cpu / bs_cpu))

# CONICA_BENCH_SUBDIVIDE=0 leaves out the Subdivide comparison and the
# adaptive table (for the surface tables alone).
if os.environ.get("CONICA_BENCH_SUBDIVIDE", "1") != "0":
    main()
else:
    setup()


def adaptive_table():
    """Curve to Polyline (Adaptive) on a Bezier circle of radius 1 (4
    anchors) and on a NURBS circle (9 points, order 3, weights): points and
    measured deviation per tolerance, next to Blender's fixed resolution."""
    print()
    print("| input | method | points | max distance to the curve |")
    print("|---|---|---|---|")
    k = 4.0 / 3.0 * (math.sqrt(2.0) - 1.0)
    for tol in (1e-2, 1e-3, 1e-4, 1e-5):
        cu = bpy.data.curves.new("bez", "CURVE")
        cu.dimensions = "3D"
        sp = cu.splines.new("BEZIER")
        sp.bezier_points.add(3)
        for i, bp in enumerate(sp.bezier_points):
            c, s = round(math.cos(i * math.pi / 2)), round(math.sin(i * math.pi / 2))
            bp.handle_left_type = bp.handle_right_type = "FREE"
            bp.co = (c, s, 0)
            bp.handle_left = (c + s * k, s - c * k, 0)
            bp.handle_right = (c - s * k, s + c * k, 0)
        sp.use_cyclic_u = True
        ob = bpy.data.objects.new("bez", cu)
        link_selected(ob)
        # reference: the cubic itself, densely sampled
        ref = []
        for i in range(4):
            p0 = sp.bezier_points[i]
            p1 = sp.bezier_points[(i + 1) % 4]
            P = [p0.co, p0.handle_right, p1.handle_left, p1.co]
            for j in range(2000):
                t = j / 2000
                b = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3]
                ref.append(sum((P[m] * b[m] for m in range(1, 4)), P[0] * b[0]))
        bpy.ops.curve.adaptive_to_poly(tolerance=tol)
        pts = [p.co.xyz for p in cu.splines[0].points]
        worst = 0.0
        m = len(pts)
        for q in ref:  # distance from the true curve to the polyline
            best = float("inf")
            for i in range(m):
                a, b2 = pts[i], pts[(i + 1) % m]
                ab = b2 - a
                L = ab.dot(ab)
                t = 0.0 if L == 0 else max(0.0, min(1.0, (q - a).dot(ab) / L))
                best = min(best, (a + ab * t - q).length)
            worst = max(worst, best)
        print("| Bezier circle (4 anchors) | adaptive, tolerance %g | %d | %.3g |" %
              (tol, m, worst))
        drop(ob)
    print("| Bezier circle (4 anchors) | Blender's fixed resolution_u=12 | 48 | "
          "(not adaptive: 12 per segment whatever the curvature) |")


if os.environ.get("CONICA_BENCH_SUBDIVIDE", "1") != "0":
    adaptive_table()


def large_curve():
    """A 20 000-point cyclic POLY circle, Conic Subdivide at level 7
    (2 560 000 points), median of BIG_REPEATS runs, object mode: the
    operator's time against the subdivision itself (libcore's time in the
    same call) plus Blender's own data writes of that many points (a plain
    script's points.add + foreach_set of co, radius, tilt)."""
    n, levels = 20000, 7
    reps = int(os.environ.get("CONICA_BENCH_BIG_REPEATS", "3"))
    ops = sys.modules["conica"].operators
    import array

    def make():
        cu = bpy.data.curves.new("big", "CURVE")
        cu.dimensions = "3D"
        sp = cu.splines.new("POLY")
        sp.points.add(n - 1)
        co = array.array("f")
        for i in range(n):
            t = 2 * math.pi * i / n
            co.extend((math.cos(t), math.sin(t), 0.0, 1.0))
        sp.points.foreach_set("co", co)
        sp.use_cyclic_u = True
        ob = bpy.data.objects.new("big", cu)
        link_selected(ob)
        bpy.context.view_layer.update()
        return ob

    rows = []
    for _ in range(reps):
        ob = make()
        t0 = time.perf_counter()
        bpy.ops.curve.conic_subdivide(levels=levels)
        total = time.perf_counter() - t0
        out = len(ob.data.splines[0].points)
        rows.append((total, dict(ops.last_timing)))
        drop(ob)
        # Blender's own writes of as many points, into a fresh spline
        ob = make()
        m = out
        co = array.array("f", bytes(16 * m))
        one = array.array("f", [1.0]) * m
        ob.data.splines.clear()
        bpy.context.view_layer.update()
        t0 = time.perf_counter()
        sp = ob.data.splines.new("POLY")
        sp.points.add(m - 1)
        sp.points.foreach_set("co", co)
        sp.points.foreach_set("radius", one)
        sp.points.foreach_set("tilt", one)
        sp.use_cyclic_u = True
        rows[-1][1]["blender_writes"] = time.perf_counter() - t0
        # what Blender then does with any new curve of that size (the
        # operator's time holds the same evaluation: bpy.ops updates the
        # view layer after it)
        ob.data.update_tag()
        t0 = time.perf_counter()
        bpy.context.view_layer.update()
        rows[-1][1]["blender_eval"] = time.perf_counter() - t0
        drop(ob)

    def med(key):
        return statistics.median(r[1][key] for r in rows)
    total = statistics.median(r[0] for r in rows)
    base = med("libcore") + med("blender_writes")
    print()
    print("Large curve: %d-point cyclic POLY circle, curve.conic_subdivide(levels=%d) -> "
          "%d points, object mode, median of %d runs (wall s)" % (n, levels, out, reps))
    print("| part | median s |")
    print("|---|---|")
    print("| whole operator (bpy.ops call, with Blender's evaluation of the result) | %.2f |"
          % total)
    print("| execute(): read (foreach_get) | %.3f |" % med("read"))
    print("| execute(): _conica call | %.2f |" % med("extension"))
    print("| of which libcore (the subdivision itself) | %.2f |" % med("libcore"))
    print("| execute(): write (points.add + foreach_set) | %.2f |" % med("write"))
    print("| Blender's own writes of %d points (points.add + foreach_set co, radius, tilt) "
          "| %.2f |" % (out, med("blender_writes")))
    print("| Blender's evaluation of that new %d-point curve (view_layer.update()) | %.2f |"
          % (out, med("blender_eval")))
    print("ratio whole operator / (subdivision + Blender's own writes and their evaluation): "
          "%.2fx (goal <= 2x)" % (total / (base + med("blender_eval"))))
    print("ratio whole operator / (subdivision + Blender's own writes, not evaluated): %.2fx"
          % (total / base))


if os.environ.get("CONICA_BENCH_BIG", "1") != "0":
    large_curve()


def _blender_mesh(ob, ru, rv, dist):
    """(vertices, deviation, CPU s) of Blender's own conversion of ob at
    resolution_u = ru, resolution_v = rv, as a user runs it: Object >
    Convert > Mesh keeping the original (an operator that makes a mesh
    object, like Surface to Mesh); the median of REPEATS runs' process time."""
    import surface_eval as se
    for sp in ob.data.splines:
        sp.resolution_u, sp.resolution_v = ru, rv
    ob.data.update_tag()
    cpu = []
    for _ in range(max(1, REPEATS)):
        for o in bpy.context.view_layer.objects:
            if o is not None:
                o.select_set(o is ob)
        bpy.context.view_layer.objects.active = ob
        bpy.context.view_layer.update()
        c0 = time.process_time()
        bpy.ops.object.convert(target="MESH", keep_original=True)
        cpu.append(time.process_time() - c0)
        new = bpy.context.active_object
        n, d = len(new.data.vertices), max(se.mesh_deviation(new.data, dist))
        bpy.data.objects.remove(new, do_unlink=True)
    return n, d, statistics.median(cpu)


def _best_blender(ob, dev, dist, rmax=64):
    """Blender's best Resolution U and V, chosen independently, for a
    measured deviation no larger than dev: (ru, rv, vertices). From the
    smallest uniform resolution r that meets dev, one direction is lowered
    as far as it goes (bisection: the deviation falls as either resolution
    grows), then the other, in both orders; the fewest vertices of those
    points and the uniform one. None when r = rmax does not meet dev."""
    import surface_eval as se
    seen = {}

    def meets(ru, rv):
        if (ru, rv) not in seen:
            for sp in ob.data.splines:
                sp.resolution_u, sp.resolution_v = ru, rv
            ob.data.update_tag()
            ev = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
            me = ev.to_mesh()
            seen[(ru, rv)] = (max(se.mesh_deviation(me, dist)) <= dev, len(me.vertices))
            ev.to_mesh_clear()
        return seen[(ru, rv)]

    def lowest(fixed, first, hi):
        """The smallest resolution up to hi (which meets dev) of one
        direction while the other is `fixed` (first: lower U, else V)."""
        lo = 1
        while lo < hi:
            mid = (lo + hi) // 2
            if meets(*((mid, fixed) if first else (fixed, mid)))[0]:
                hi = mid
            else:
                lo = mid + 1
        return lo
    r = next((r for r in range(1, rmax + 1) if meets(r, r)[0]), None)
    if r is None:
        return None
    cands = [(r, r)]
    ru = lowest(r, True, r)
    cands.append((ru, lowest(ru, False, r)))
    rv = lowest(r, False, r)
    cands.append((lowest(rv, True, r), rv))
    ok = [(meets(a, b)[1], a, b) for a, b in cands if meets(a, b)[0]]
    n, a, b = min(ok)
    return a, b, n


def surface_table():
    """Surface to Mesh (Adaptive) on Blender's Add > Surface primitives at
    three tolerances: vertices, measured deviation (vertices, face centres
    and edge midpoints projected onto the surface by
    tests/blender/surface_eval.py) and CPU time, against Blender's own
    conversion (the evaluated mesh) at its best independent Resolution U
    and V (_best_blender): the fewest vertices found whose measured
    deviation is no larger."""
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "tests", "blender"))
    import surface_eval as se
    ops = sys.modules["conica"].operators
    print()
    print("Surfaces: Surface to Mesh (Adaptive) vs Blender's conversion at its best "
          "Resolution U, V for the same measured deviation")
    print("| primitive | tolerance | adaptive vertices | adaptive deviation | adaptive CPU ms | "
          "Blender U x V | Blender vertices | Blender deviation | Blender CPU ms | "
          "vertices ratio | CPU ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for prim in ("surface", "cylinder", "sphere", "torus"):
        for tol in (1e-2, 5e-3, 2e-3):
            for ob in list(bpy.data.objects):
                bpy.data.objects.remove(ob, do_unlink=True)
            getattr(bpy.ops.surface, "primitive_nurbs_surface_%s_add" % prim)()
            ob = bpy.context.active_object
            dist = se.Distance(se.Surface(ob.data.splines[0], ops.nurbs_knots))
            cpu = []
            for _ in range(max(1, REPEATS)):
                bpy.context.view_layer.objects.active = ob
                ob.select_set(True)
                bpy.context.view_layer.update()
                c0 = time.process_time()
                bpy.ops.object.conic_surface_to_mesh(tolerance=tol)
                cpu.append(time.process_time() - c0)
                new = bpy.context.active_object
                if len(cpu) < max(1, REPEATS):
                    bpy.data.objects.remove(new, do_unlink=True)
            dev = max(se.mesh_deviation(new.data, dist))
            nv = len(new.data.vertices)
            bpy.data.objects.remove(new, do_unlink=True)
            best = _best_blender(ob, dev, dist)
            if best is None:
                print("| %s | %g | %d | %.3g | %.2f | > 64 x 64 | - | - | - | - | - |"
                      % (prim, tol, nv, dev, 1e3 * statistics.median(cpu)))
                continue
            n, d, bcpu = _blender_mesh(ob, best[0], best[1], dist)
            acpu = statistics.median(cpu)
            print("| %s | %g | %d | %.3g | %.2f | %d x %d | %d | %.3g | %.2f | %.2f | %.1f |"
                  % (prim, tol, nv, dev, 1e3 * acpu, best[0], best[1], n, d, 1e3 * bcpu,
                     nv / n, acpu / bcpu if bcpu > 0 else float("inf")))


def surface_times():
    """CPU time of Surface to Mesh (Adaptive) at fine tolerances, where the
    certified grid has tens of thousands of cells: the operator alone
    (bpy.ops call, process time), one run each."""
    print()
    print("Surfaces: Surface to Mesh (Adaptive) CPU time (process time of the operator)")
    print("| primitive | tolerance | vertices | CPU s |")
    print("|---|---|---|---|")
    for prim in ("sphere", "torus"):
        for tol in (1e-3, 1e-4):
            for ob in list(bpy.data.objects):
                bpy.data.objects.remove(ob, do_unlink=True)
            getattr(bpy.ops.surface, "primitive_nurbs_surface_%s_add" % prim)()
            c0 = time.process_time()
            bpy.ops.object.conic_surface_to_mesh(tolerance=tol)
            cpu = time.process_time() - c0
            nv = len(bpy.context.active_object.data.vertices)
            print("| %s | %g | %d | %.2f |" % (prim, tol, nv, cpu))


if os.environ.get("CONICA_BENCH_SURFACES", "1") != "0":
    surface_table()
    surface_times()
