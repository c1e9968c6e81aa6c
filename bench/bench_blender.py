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
    bpy.context.scene.collection.objects.link(ob)
    for o in bpy.context.view_layer.objects:
        if o is not None:
            o.select_set(False)
    ob.select_set(True)
    bpy.context.view_layer.objects.active = ob
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
    t0 = time.perf_counter()
    bpy.ops.curve.conic_subdivide(levels=3)
    t = time.perf_counter() - t0
    if edit:
        bpy.ops.object.mode_set(mode="OBJECT")
    n = points(ob)
    timing = dict(ops.last_timing)
    drop(ob)
    return t, n, timing


def run_blender(with_switch):
    ob = make_curve("blender")
    bpy.context.view_layer.update()
    if with_switch:
        t0 = time.perf_counter()
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
        bpy.ops.curve.subdivide(number_cuts=7)
        bpy.ops.object.mode_set(mode="OBJECT")
        t = time.perf_counter() - t0
    else:
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.curve.select_all(action="SELECT")
        bpy.context.view_layer.update()
        t0 = time.perf_counter()
        bpy.ops.curve.subdivide(number_cuts=7)
        t = time.perf_counter() - t0
        bpy.ops.object.mode_set(mode="OBJECT")
    n = points(ob)
    drop(ob)
    return t, n


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
    c_ms = median_ms([c[0] for c in conic])
    ce_ms = median_ms([c[0] for c in conic_edit])
    b_ms = median_ms([b[0] for b in bl])
    bs_ms = median_ms([b[0] for b in bl_sw])
    split = {k: median_ms([c[2][k] for c in conic]) for k in
             ("read", "extension", "libcore", "write", "total")}
    print("Blender %s, %d-point cyclic POLY spline, median of %d runs" %
          (bpy.app.version_string, N, REPEATS))
    print("| operation | output points | median ms |")
    print("|---|---|---|")
    print("| curve.conic_subdivide(levels=3), object mode | %d | %.2f |" % (conic[0][1], c_ms))
    print("| curve.conic_subdivide(levels=3), edit mode | %d | %.2f |" %
          (conic_edit[0][1], ce_ms))
    print("| curve.subdivide(number_cuts=7), edit mode, operator only | %d | %.2f |" %
          (bl[0][1], b_ms))
    print("| curve.subdivide(number_cuts=7) + edit-mode switches | %d | %.2f |" %
          (bl_sw[0][1], bs_ms))
    print()
    print("Conic Subdivide, object mode, split (median ms): read (foreach_get) %.3f, "
          "_conica call %.3f of which libcore %.3f, write (new spline + foreach_set) %.3f, "
          "operator total %.3f" % (split["read"], split["extension"], split["libcore"],
                                   split["write"], split["total"]))
    print("ratio conic (object mode) / Blender operator only: %.2fx (goal <= 2x)" %
          (c_ms / b_ms))
    print("ratio conic (edit mode) / Blender operator with mode switches: %.2fx" %
          (ce_ms / bs_ms))


main()
