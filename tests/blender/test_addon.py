# SPDX-License-Identifier: GPL-3.0-or-later
# Conica add-on tests, run inside real Blender (headless):
#   CONICA_ZIP=build/conica-blender.zip BLENDER_USER_SCRIPTS=$tmp \
#   blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py
# Prints one `PASS name` or `FAIL name: why` line per check (tests/cli/blender.sh
# turns them into the suite summary). Every check runs even if others fail.
# CONICA_CASES=name,name runs only those test functions (and the install),
# for development: `CONICA_CASES=mesh_circle_converted sh tests/cli/blender.sh build`.
#
# Precision: Blender stores curve coordinates as float32, so "within 1e-9 of
# the radius" is checked on the values _conica returns in double for the
# spline's stored (float32) input; the points written back into Blender are
# checked within float32 rounding of their coordinates.
import array
import importlib
import math
import os
import shutil
import sys
import tempfile
import time
import traceback

import addon_utils
import bpy
from mathutils import Vector, geometry

RESULTS = []
TMP = tempfile.mkdtemp(prefix="conica-blender-")
F32 = 2.0 ** -24


def report(name, ok, why=""):
    RESULTS.append((name, ok))
    if ok:
        print("PASS %s%s" % (name, ": " + why if why else ""), flush=True)
    else:
        print("FAIL %s: %s" % (name, why), flush=True)


# CONICA_TIMES=1 prints `TIME name seconds` (process CPU time) per test function.
TIMES = os.environ.get("CONICA_TIMES", "") == "1"
SELECTED = [c for c in os.environ.get("CONICA_CASES", "").split(",") if c]


def case(fn):
    """Run one test function; an exception is a failure of that test."""
    if SELECTED and fn.__name__ not in SELECTED and fn.__name__ != "install_from_zip":
        return fn
    c0 = time.process_time()
    try:
        fn()
    except Exception as exc:  # noqa: BLE001 - report and go on
        report(fn.__name__, False, "%s: %s\n%s" % (type(exc).__name__, exc,
                                                   traceback.format_exc()))
    if TIMES:
        print("TIME %s %.2f s" % (fn.__name__, time.process_time() - c0), flush=True)
    return fn


# ---------------------------------------------------------------- helpers

def fresh_scene():
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for cu in list(bpy.data.curves):
        bpy.data.curves.remove(cu)
    bpy.context.view_layer.update()


def new_curve(name):
    cu = bpy.data.curves.new(name, "CURVE")
    cu.dimensions = "3D"
    ob = bpy.data.objects.new(name, cu)
    bpy.context.scene.collection.objects.link(ob)
    return ob


def select_only(*objs):
    for o in bpy.context.view_layer.objects:
        if o is not None:
            o.select_set(False)
    for o in objs:
        o.select_set(True)
    bpy.context.view_layer.objects.active = objs[0] if objs else None


def add_bezier(cu, pts, tangents, cyclic, hlen=None):
    """Bezier spline through pts; handles along tangents (length hlen[i] or
    the tangent's own length)."""
    sp = cu.splines.new("BEZIER")
    sp.bezier_points.add(len(pts) - 1)
    for i, bp in enumerate(sp.bezier_points):
        p, t = pts[i], tangents[i]
        s = 1.0 if hlen is None else hlen[i]
        bp.handle_left_type = bp.handle_right_type = "FREE"
        bp.co = p
        bp.handle_left = [p[k] - s * t[k] for k in range(3)]
        bp.handle_right = [p[k] + s * t[k] for k in range(3)]
    sp.use_cyclic_u = cyclic
    return sp


def add_poly(cu, pts, cyclic, radius=None, tilt=None):
    sp = cu.splines.new("POLY")
    sp.points.add(len(pts) - 1)
    for i, p in enumerate(sp.points):
        p.co = (pts[i][0], pts[i][1], pts[i][2], 1.0)
        if radius:
            p.radius = radius[i]
        if tilt:
            p.tilt = tilt[i]
    sp.use_cyclic_u = cyclic
    return sp


def add_nurbs(cu, pts, weights, order, cyclic=False, endpoint=False, bezier=False):
    sp = cu.splines.new("NURBS")
    sp.points.add(len(pts) - 1)
    for i, p in enumerate(sp.points):
        p.co = (pts[i][0], pts[i][1], pts[i][2], weights[i])
    sp.use_cyclic_u = cyclic
    sp.order_u = order
    sp.use_endpoint_u = endpoint
    sp.use_bezier_u = bezier
    return sp


def poly_co(sp):
    n = len(sp.points)
    co = array.array("f", bytes(16 * n))
    sp.points.foreach_get("co", co)
    return [(co[4 * i], co[4 * i + 1], co[4 * i + 2]) for i in range(n)]


def spline_snapshot(sp):
    if sp.type == "BEZIER":
        return ("BEZIER", sp.use_cyclic_u,
                [(tuple(b.co), tuple(b.handle_left), tuple(b.handle_right), b.radius, b.tilt)
                 for b in sp.bezier_points])
    return (sp.type, sp.use_cyclic_u,
            [(tuple(p.co), p.radius, p.tilt) for p in sp.points])


def curve_snapshot(cu):
    return [spline_snapshot(s) for s in cu.splines]


def full_snapshot(sp):
    """Everything a curve spline holds that RNA shows (for "left exactly as
    it was" checks): settings, and every point's coordinates, weights,
    handles and handle types, radius, tilt, soft-body weight, selection and
    hidden flags."""
    head = tuple(getattr(sp, k) for k in (
        "type", "use_cyclic_u", "order_u", "use_endpoint_u", "use_bezier_u", "resolution_u",
        "use_smooth", "material_index", "tilt_interpolation", "radius_interpolation", "hide"))
    if sp.type == "BEZIER":
        pts = [(tuple(b.co), tuple(b.handle_left), tuple(b.handle_right), b.handle_left_type,
                b.handle_right_type, b.radius, b.tilt, b.weight_softbody,
                b.select_control_point, b.select_left_handle, b.select_right_handle, b.hide)
               for b in sp.bezier_points]
    else:
        pts = [(tuple(p.co), p.radius, p.tilt, p.weight_softbody, p.select, p.hide)
               for p in sp.points]
    return repr((head, pts))  # repr: NaN-aware equality


def last_reports():
    return list(conica_pkg().operators.last_reports)


def conica_pkg():
    return sys.modules["conica"]


def dist(a, b):
    return math.sqrt(sum((a[k] - b[k]) ** 2 for k in range(3)))


def eval_points(ob):
    """Blender's own evaluation of a curve object (its evaluated mesh)."""
    dg = bpy.context.evaluated_depsgraph_get()
    ev = ob.evaluated_get(dg)
    me = ev.to_mesh()
    pts = [tuple(v.co) for v in me.vertices]
    ev.to_mesh_clear()
    return pts


def point_polyline_distance(p, poly, closed):
    best = float("inf")
    m = len(poly)
    for i in range(m if closed else m - 1):
        a, b = poly[i], poly[(i + 1) % m]
        ab = [b[k] - a[k] for k in range(3)]
        ap = [p[k] - a[k] for k in range(3)]
        L = sum(x * x for x in ab)
        t = 0.0 if L == 0 else max(0.0, min(1.0, sum(ab[k] * ap[k] for k in range(3)) / L))
        q = [a[k] + t * ab[k] for k in range(3)]
        best = min(best, dist(p, q))
    return best


def direct_curve(sp, levels, **kw):
    """What Conic Subdivide passes to _conica.curve (its defaults), returned
    in double: (points, normals, attrs, info)."""
    ops = conica_pkg().operators
    return ops.spline_curve(sp, ops.SplineData(sp), mode="smooth", levels=levels,
                            typecode="d", **kw)


def as_points(flat):
    return [(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]) for i in range(len(flat) // 3)]


def bezier_at(p0, p1, p2, p3, t):
    """de Casteljau, independent of the add-on."""
    u = 1.0 - t
    return tuple(u ** 3 * p0[k] + 3 * u * u * t * p1[k] + 3 * u * t * t * p2[k] +
                 t ** 3 * p3[k] for k in range(3))


def mid_errors(sp, fn):
    """|fn| at the middle (t = 1/2) of every drawn segment of a Bezier
    spline: how far its stored (float32) control points put the drawn curve
    off the conic fn, where the path front end samples it."""
    bp = sp.bezier_points
    n = len(bp)
    segs = n if sp.use_cyclic_u else n - 1
    return [abs(fn(bezier_at(bp[i].co, bp[i].handle_right, bp[(i + 1) % n].handle_left,
                             bp[(i + 1) % n].co, 0.5))) for i in range(segs)]


KAPPA = 4.0 / 3.0 * (math.sqrt(2.0) - 1.0)  # circular cubic handle factor


# ---------------------------------------------------------------- drawn curves
# Independent of the add-on: the drawn curve of a Bezier spline evaluated
# densely by Blender's own mathutils.geometry.interpolate_bezier, exact
# point-polyline distances, turning angles and crossings.


def drawn_spline(sp, per_seg=256):
    """Dense points of a BEZIER spline's drawn curve, per segment, from
    mathutils.geometry.interpolate_bezier (independent of the add-on)."""
    bp = sp.bezier_points
    n = len(bp)
    segs = n if sp.use_cyclic_u else n - 1
    out = []
    for i in range(segs):
        a, b = bp[i], bp[(i + 1) % n]
        pts = geometry.interpolate_bezier(a.co, a.handle_right, b.handle_left, b.co, per_seg + 1)
        out.extend(pts if i == 0 else pts[1:])
    return out

def shape_size(sp):
    bp = sp.bezier_points
    n = len(bp)
    pts = [b.co for b in bp]
    for i, b in enumerate(bp):
        if sp.use_cyclic_u or i + 1 < n:
            pts.append(b.handle_right)
        if sp.use_cyclic_u or i > 0:
            pts.append(b.handle_left)
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    diag = math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
    return diag, max(abs(c) for p in pts for c in p)

def seg_dist(p, a, b):
    ab = b - a
    L = ab.length_squared
    t = 0.0 if L == 0 else max(0.0, min(1.0, (p - a).dot(ab) / L))
    return (p - (a + t * ab)).length

class PolyDist:
    """Exact distance of points to a polyline: its edges in a uniform grid,
    searched ring by ring until no nearer edge can be left."""
    def __init__(self, pts, closed, cells=64):
        p = [Vector(q) for q in pts]
        m = len(p)
        self.edges = [(p[k], p[(k + 1) % m]) for k in range(m if closed else m - 1)]
        lo = [min(q[c] for q in p) for c in range(3)]
        hi = [max(q[c] for q in p) for c in range(3)]
        self.lo = lo
        self.h = max(hi[c] - lo[c] for c in range(3)) / cells or 1.0
        self.grid = {}
        for e, (a, b) in enumerate(self.edges):
            r = [range(self._c(min(a[c], b[c]), c), self._c(max(a[c], b[c]), c) + 1)
                 for c in range(3)]
            for i in r[0]:
                for j in r[1]:
                    for k in r[2]:
                        self.grid.setdefault((i, j, k), []).append(e)
        self.span = max(self._c(hi[c], c) for c in range(3)) + 1

    def _c(self, v, c):
        return int(math.floor((v - self.lo[c]) / self.h))

    def __call__(self, q):
        q = Vector(q)
        ci = [self._c(q[c], c) for c in range(3)]
        best = float("inf")
        r = 0
        while True:
            seen = set()
            for i in range(ci[0] - r, ci[0] + r + 1):
                for j in range(ci[1] - r, ci[1] + r + 1):
                    for k in range(ci[2] - r, ci[2] + r + 1):
                        if max(abs(i - ci[0]), abs(j - ci[1]), abs(k - ci[2])) != r:
                            continue
                        for e in self.grid.get((i, j, k), ()):
                            if e not in seen:
                                seen.add(e)
                                best = min(best, seg_dist(q, *self.edges[e]))
            if best <= r * self.h or r > self.span + max(abs(x) for x in ci):
                return best
            r += 1


def anchor_turns(sp):
    """Turning angle of the drawn curve's tangent at each anchor (handles;
    a handle on its anchor borrows the next control point)."""
    bp = sp.bezier_points
    n = len(bp)
    out = []
    for i in range(n):
        if not sp.use_cyclic_u and (i == 0 or i == n - 1):
            out.append(0.0)
            continue
        c = bp[i].co
        prev = [bp[i].handle_left, bp[i - 1].handle_right, bp[i - 1].co]
        nxt = [bp[i].handle_right, bp[(i + 1) % n].handle_left, bp[(i + 1) % n].co]
        a = next((c - q for q in prev if (c - q).length > 0), None)
        b = next((q - c for q in nxt if (q - c).length > 0), None)
        out.append(a.angle(b) if a is not None and b is not None else 0.0)
    return out

def poly_turn(pts, k, closed):
    m = len(pts)
    a = Vector(pts[k]) - Vector(pts[(k - 1) % m])
    b = Vector(pts[(k + 1) % m]) - Vector(pts[k])
    return a.angle(b)

def _cross(a, b, c, d):
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
    # proper crossings only (touching is not crossing)
    return ((o1 > 0) != (o2 > 0) and (o3 > 0) != (o4 > 0) and
            0.0 not in (o1, o2, o3, o4))

def crossing_pairs(polys, cells=128):
    """Pairs (i, j) of closed 2D (xy) polylines whose edges cross."""
    segs = []
    for i, (pts, closed) in enumerate(polys):
        m = len(pts)
        for k in range(m if closed else m - 1):
            segs.append((i, pts[k], pts[(k + 1) % m]))
    xs = [p[0] for _i, a, b in segs for p in (a, b)]
    ys = [p[1] for _i, a, b in segs for p in (a, b)]
    x0, y0 = min(xs), min(ys)
    h = max(max(xs) - x0, max(ys) - y0) / cells or 1.0
    grid = {}
    for s, (i, a, b) in enumerate(segs):
        for gx in range(int((min(a[0], b[0]) - x0) / h), int((max(a[0], b[0]) - x0) / h) + 1):
            for gy in range(int((min(a[1], b[1]) - y0) / h), int((max(a[1], b[1]) - y0) / h) + 1):
                grid.setdefault((gx, gy), []).append(s)
    found = set()
    for cell in grid.values():
        for u in range(len(cell)):
            i, a, b = segs[cell[u]]
            for v in range(u + 1, len(cell)):
                j, c, d = segs[cell[v]]
                if i != j and (min(i, j), max(i, j)) not in found and _cross(a, b, c, d):
                    found.add((min(i, j), max(i, j)))
    return found


def fidelity_check(name, sp_in, out_pts, closed, fid, drawn=None, both=False):
    """Every output point within fid * size (+ float32 storage) of the drawn
    spline sp_in (size: bounding-box diagonal of its anchors and the
    handles that shape it); both: and the drawn curve within it of the
    output polyline. Returns the worst ratio to the tolerance."""
    size, mx = shape_size(sp_in)
    tol = fid * size
    slack = 4 * F32 * mx
    drawn = drawn if drawn is not None else drawn_spline(sp_in)
    pd = PolyDist(drawn, sp_in.use_cyclic_u)
    worst = max(pd(q) for q in out_pts) if out_pts else float("inf")
    back = 0.0
    if both:
        od = PolyDist(out_pts, closed)
        back = max(od(q) for q in drawn[::4])
    ok = worst <= tol + slack and back <= tol + slack
    report(name, ok, "output points up to %.3g from the drawn curve%s; tolerance %.3g" %
           (worst, ", drawn curve up to %.3g from the output" % back if both else "", tol))
    return max(worst, back) / tol


def circle_bezier(cu, R=1.0):
    pts, tans = [], []
    for i in range(4):
        a = i * math.pi / 2
        c, s = round(math.cos(a)), round(math.sin(a))
        pts.append((R * c, R * s, 0.0))
        tans.append((-s * KAPPA * R, c * KAPPA * R, 0.0))
    return add_bezier(cu, pts, tans, True)


def run_op(op, **kw):
    return op(**kw)


# ---------------------------------------------------------------- install

@case
def install_from_zip():
    z = os.environ["CONICA_ZIP"]
    r = bpy.ops.preferences.addon_install(filepath=os.path.abspath(z), overwrite=True)
    report("install_from_zip", r == {"FINISHED"}, str(r))
    mod = addon_utils.enable("conica", default_set=True, handle_error=None)
    report("addon_enable", mod is not None and hasattr(bpy.types, "CURVE_OT_conic_subdivide"),
           "enable returned %r" % mod)
    pkg = conica_pkg()
    report("bl_info_blender_3_4", tuple(pkg.bl_info["blender"]) <= (3, 4, 0),
           str(pkg.bl_info["blender"]))
    report("import_check_ok", pkg.IMPORT_ERROR is None, str(pkg.IMPORT_ERROR))
    ext = pkg._conica
    report("abi_tag", ext.ABI == "abi3" and tuple(ext.PY_MIN_VERSION) == (3, 11) and
           os.path.basename(ext.__file__) == "_conica.abi3.so",
           "%r %r %s" % (ext.ABI, ext.PY_MIN_VERSION, ext.__file__))
    here = os.path.dirname(pkg.__file__)
    mpath = os.path.join(here, "blender_manifest.toml")
    report("manifest_in_package", os.path.isfile(mpath))
    import tomllib
    with open(mpath, "rb") as f:
        man = tomllib.load(f)
    need = ("schema_version", "id", "version", "name", "tagline", "maintainer", "type",
            "blender_version_min", "license")
    report("manifest_fields", all(k in man for k in need) and man["type"] == "add-on" and
           man["platforms"] == [pkg.running_platform()] and len(man["tagline"]) <= 64 and
           man["tagline"][-1].isalnum() and
           tuple(int(x) for x in man["blender_version_min"].split(".")) >= (4, 2, 0) and
           tuple(int(x) for x in man["version"].split(".")) == tuple(pkg.bl_info["version"]),
           repr(man))


@case
def menus_and_search():
    ops = conica_pkg().operators
    for name, fn in ops.MENUS:
        menu = getattr(bpy.types, name, None)
        ok = menu is not None and fn in menu._dyn_ui_initialize()
        report("menu_" + name, ok, "menu missing or entry not appended")
    report("labels", bpy.types.CURVE_OT_conic_subdivide.bl_label == "Conic Subdivide" and
           bpy.types.CURVE_OT_adaptive_to_poly.bl_label == "Curve to Polyline (Adaptive)")
    props = bpy.ops.curve.conic_subdivide.get_rna_type().properties
    lv = props["levels"]
    report("levels_prop", (lv.default, lv.hard_min, lv.hard_max, lv.is_skip_save) ==
           (3, 1, 8, True), "%r" % ((lv.default, lv.hard_min, lv.hard_max, lv.is_skip_save),))
    report("operator_props", all(k in props for k in
                                 ("keep_corners", "corner_angle", "fidelity", "output")) and
           not any(k in props for k in ("normals", "precise", "tolerance")),
           repr(sorted(props.keys())))
    kc, ca, fi = props["keep_corners"], props["corner_angle"], props["fidelity"]
    report("keep_corners_default_on_40deg", kc.default is True and
           abs(ca.default - math.radians(40.0)) < 1e-6, "%r %r" % (kc.default, ca.default))
    report("fidelity_prop", fi.name == "Fidelity" and abs(fi.default - 1e-3) < 1e-9 and
           "drawn curve" in fi.description and "fraction of the spline's size" in
           fi.description, "%r %r %r" % (fi.name, fi.default, fi.description))
    tp = bpy.ops.curve.adaptive_to_poly.get_rna_type().properties["tolerance"]
    report("adaptive_tolerance_prop", abs(tp.default - 1e-3) < 1e-9 and tp.subtype == "DISTANCE",
           "%r %r" % (tp.default, tp.subtype))
    # the redo panel shows 0.001 as 0.001000, not 0.00
    report("redo_panel_digits", tp.precision >= 5 and fi.precision >= 5,
           "tolerance %d, fidelity %d digits" % (tp.precision, fi.precision))


def _package_copy(name, edit):
    """A copy of the installed package as `name`, changed by edit(dir),
    imported; returns its IMPORT_ERROR after checking that register()
    and unregister() do not raise (only a preferences panel is made)."""
    here = os.path.dirname(conica_pkg().__file__)
    dst = os.path.join(TMP, "fakepath", name)
    shutil.copytree(here, dst, ignore=shutil.ignore_patterns("__pycache__"))
    edit(dst)
    sys.path.insert(0, os.path.dirname(dst))
    try:
        m = importlib.import_module(name)
        m.register()
        m.unregister()
        return m.IMPORT_ERROR or ""
    finally:
        sys.path.pop(0)


@case
def import_check_mismatch():
    """A package whose binary is not the stable-ABI module says so in one
    sentence, naming what it has and what to rebuild."""
    def other_binary(dst):
        for f in os.listdir(dst):
            if f.startswith("_conica"):
                os.rename(os.path.join(dst, f),
                          os.path.join(dst, "_conica.cpython-39-aarch64-linux-gnu.so"))
    msg = _package_copy("conica_mismatch", other_binary)
    report("import_check_mismatch_message",
           "cpython-39" in msg and "_conica.abi3.so" in msg and "rebuild" in msg and
           msg.count(". ") == 0, msg)

    def other_platform(dst):
        mpath = os.path.join(dst, "blender_manifest.toml")
        with open(mpath) as f:
            text = f.read()
        with open(mpath, "w") as f:
            f.write(text.replace('platforms = ["linux-x64"]', 'platforms = ["windows-x64"]'))
    msg = _package_copy("conica_otherplatform", other_platform)
    report("import_check_platform_message",
           "built for windows-x64" in msg and "linux-x64" in msg and "rebuild" in msg, msg)
    report("import_check_platform_name", conica_pkg().running_platform() == "linux-x64",
           conica_pkg().running_platform())


@case
def extension_rejects_bad_input():
    ext = conica_pkg()._conica
    bad = [
        ("wrong_length", dict(points=[0, 0, 1], dim=2), ext.ArgumentError),
        ("nan", dict(points=[0, 0, float("nan"), 1, 2, 2], dim=2), ext.NonFiniteError),
        ("empty", dict(points=[]), ext.DegenerateError),
        ("huge_levels", dict(points=[0, 0, 1, 1], levels=1000), ext.LimitError),
        ("too_many_points", dict(points=[0, 0, 1, 1], levels=29), ext.LimitError),
        ("non_numeric", dict(points=[0, "a", 1, 1]), TypeError),
        ("string", dict(points="0011"), TypeError),
        ("int_buffer", dict(points=array.array("i", [0, 0, 1, 1])), TypeError),
        ("dim", dict(points=[0, 0, 1, 1], dim=5), ext.ArgumentError),
        ("nonplanar", dict(points=[0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], dim=3, closed=True),
         ext.NonPlanarError),
        ("normals_length", dict(points=[0, 0, 1, 1], normals=[1, 0]), ext.ArgumentError),
        ("huge_coordinate", dict(points=[0, 0, 1, 1e308, 2, 0], closed=True), ext.LimitError),
        ("bad_typecode", dict(points=[0, 0, 1, 1], typecode="q"), ValueError),
        ("bad_normal_method", dict(points=[0, 0, 1, 1], normal_method="x"),
         ext.ArgumentError),
    ]
    for name, kw, exc in bad:
        try:
            ext.subdivide(**kw)
            report("ext_rejects_" + name, False, "no exception")
        except exc as e:
            report("ext_rejects_" + name, isinstance(e, (ext.ConicaError, TypeError)), str(e))
        except Exception as e:  # noqa: BLE001
            report("ext_rejects_" + name, False, "%s: %s" % (type(e).__name__, e))
    # a triangle whose size underflows is degenerate, not "non-planar";
    # a tiny one above DBL_MIN is processed like any other
    for e, exc in ((1e-310, ext.DegenerateError), (1e-200, None), (1e-160, None)):
        tri = [0, 0, 0, e, 0, 0, 0, e, 0]
        try:
            res = ext.subdivide(tri, dim=3, closed=True, levels=1)
            ok = exc is None and len(res[0]) == 18 and all(math.isfinite(v) for v in res[0]) \
                and max(abs(v) for v in res[0]) <= 2 * e and res[0][:3].tolist() == [0, 0, 0]
            why = "processed"
        except ext.ConicaError as err:
            ok = exc is not None and type(err) is exc and "too small" in str(err)
            why = "%s: %s" % (type(err).__name__, err)
        report("ext_tiny_triangle_%g" % e, ok, why)
    report("ext_error_hierarchy", issubclass(ext.DegenerateError, ValueError) and
           issubclass(ext.NumericError, RuntimeError) and
           issubclass(ext.OutOfMemoryError, MemoryError) and
           issubclass(ext.LimitError, ext.ConicaError))
    for name, kw in [("plot_knots", dict(ctrl=[0, 0, 0, 1, 1, 1, 2, 0, 0], degree=2,
                                         knots=[0, 0, 1], tolerance=1e-3)),
                     ("plot_tol", dict(ctrl=[0, 0, 0, 1, 1, 1, 2, 0, 0], degree=2,
                                       knots=[0, 0, 0, 1, 1, 1], tolerance=-1.0)),
                     ("plot_weights", dict(ctrl=[0, 0, 0, 1, 1, 1, 2, 0, 0], degree=2,
                                           knots=[0, 0, 0, 1, 1, 1], tolerance=1e-3,
                                           weights=[1, -1, 1]))]:
        try:
            ext.plot(**kw)
            report("ext_rejects_" + name, False, "no exception")
        except ext.ConicaError as e:
            report("ext_rejects_" + name, True, str(e))
    # accepted inputs: lists, array('f'), array('d'), memoryviews
    ok = True
    for src in ([1, 0, 0, 1, -1, 0, 0, -1], array.array("f", [1, 0, 0, 1, -1, 0, 0, -1]),
                memoryview(array.array("d", [1, 0, 0, 1, -1, 0, 0, -1]))):
        r = ext.subdivide(src, closed=True, levels=1)
        ok = ok and len(r[0]) == 16 and r[0].typecode == "d"
    report("ext_accepts_sequences_and_buffers", ok)


@case
def curve_rejects_bad_input():
    """_conica.curve (the path front end): bad input of every kind raises
    the matching ConicaError, never crashes."""
    ext = conica_pkg()._conica
    sq = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    hl = [0, -0.1, 0, 0.9, 0, 0, 1, 0.9, 0, 0.1, 1, 0]
    hr = [0, 0.1, 0, 1.1, 0, 0, 1, 1.1, 0, -0.1, 1, 0]
    bad = [
        ("kind", ("SPLINE", sq), {}, ext.ArgumentError),
        ("mode", ("POLY", sq), dict(mode="round"), ext.ArgumentError),
        ("no_handles", ("BEZIER", sq), {}, ext.ArgumentError),
        ("handles_on_poly", ("POLY", sq, hl, hr), {}, ext.ArgumentError),
        ("handle_length", ("BEZIER", sq, hl[:9], hr), {}, ext.ArgumentError),
        ("nan", ("POLY", sq[:3] + [float("nan")] + sq[4:]), {}, ext.NonFiniteError),
        ("nan_handle", ("BEZIER", sq, hl[:4] + [float("inf")] + hl[5:], hr), {},
         ext.NonFiniteError),
        ("huge", ("POLY", sq[:3] + [1e300] + sq[4:]), {}, ext.LimitError),
        ("one_point", ("BEZIER", [0, 0, 0], [0, 0, 0], [0, 0, 0]), {}, ext.DegenerateError),
        ("coincident", ("POLY", [1, 1, 0] * 3), dict(closed=True), ext.DegenerateError),
        ("nonplanar", ("POLY", [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1]), dict(closed=True),
         ext.NonPlanarError),
        ("dim", ("POLY", sq), dict(dim=4), ext.ArgumentError),
        ("levels", ("POLY", sq), dict(levels=17), ext.LimitError),
        ("levels_handles", ("POLY", sq), dict(levels=16, handles=True), ext.LimitError),
        ("fidelity", ("POLY", sq), dict(fidelity=0.0), ext.ArgumentError),
        ("tolerance", ("POLY", sq), dict(tolerance=-1.0), ext.ArgumentError),
        ("precision", ("POLY", sq), dict(precision=-1.0), ext.ArgumentError),
        ("corner_angle", ("POLY", sq), dict(corner_angle=float("nan")), ext.ArgumentError),
        ("nurbs_no_knots", ("NURBS", sq), dict(degree=2), ext.ArgumentError),
        ("nurbs_knot_count", ("NURBS", sq), dict(degree=2, knots=[0, 0, 0, 1, 1, 1]),
         ext.ArgumentError),
        ("nurbs_weight", ("NURBS", sq), dict(degree=2, knots=[0, 0, 0, 1, 2, 2, 2],
                                             weights=[1, -1, 1, 1]), ext.ArgumentError),
        ("nurbs_degree", ("NURBS", sq), dict(degree=9, knots=[0] * 14), ext.ArgumentError),
        ("weights_on_poly", ("POLY", sq), dict(weights=[1, 1, 1, 1]), ext.ArgumentError),
        ("attrs_length", ("POLY", sq), dict(attrs=[1, 2, 3], nattrs=2), ext.ArgumentError),
        ("max_points", ("POLY", sq), dict(levels=16, max_points=100, corner_angle=math.pi),
         ext.LimitError),
        ("string", ("POLY", "0011"), {}, TypeError),
        ("int_buffer", ("POLY", array.array("i", sq)), {}, TypeError),
    ]
    for name, args, kw, exc in bad:
        try:
            ext.curve(*args, **kw)
            report("curve_rejects_" + name, False, "no exception")
        except exc as e:
            report("curve_rejects_" + name, isinstance(e, (ext.ConicaError, TypeError)), str(e))
        except Exception as e:  # noqa: BLE001
            report("curve_rejects_" + name, False, "%s: %s" % (type(e).__name__, e))
    # the three kinds, 2D and 3D, lists and buffers: points in, arrays out
    ok = True
    for kind, args, kw in (("POLY", (sq,), {}), ("BEZIER", (sq, hl, hr), {}),
                           ("NURBS", (sq,), dict(degree=2, knots=[0, 0, 0, 1, 2, 2, 2]))):
        for handles in (False, True):
            r = ext.curve(kind, *args, closed=kind != "NURBS", handles=handles, attrs=[1, 0] * 4,
                          nattrs=2, want_normals=True, **kw)
            n = r[3]["points"]
            ok = ok and len(r) == (6 if handles else 4) and len(r[0]) == 3 * n and \
                len(r[1]) == 3 * n and len(r[2]) == 2 * n and n >= 4 and r[0].typecode == "d"
            if handles:
                ok = ok and len(r[4]) == len(r[5]) == 3 * n
    r = ext.curve("POLY", array.array("f", [1, 0, 0, 1, -1, 0, 0, -1]), dim=2, closed=True,
                  levels=1, stride=4, typecode="f", corner_angle=math.pi)
    ok = ok and len(r[0]) == 4 * 8 and r[0].typecode == "f" and r[0][3] == 1.0
    report("curve_kinds_and_buffers", ok)


# ---------------------------------------------------------------- exactness

def check_on_conic(name, pts, fn, tol):
    worst = max(abs(fn(p)) for p in pts) if pts else float("inf")
    report(name, worst <= tol, "worst %.3g > %.3g" % (worst, tol))


@case
def circle_bezier_exact():
    """Four circular cubics (handles 4/3 tan(pi/8) r): the path front end
    samples each at its ends and middle, where the drawn cubic is on the
    circle, so the conic subdivision reproduces the circle; what is left is
    the float32 rounding of the stored handles (the middles are off by it)."""
    fresh_scene()
    ob = new_curve("circle")
    sp = circle_bezier(ob.data)
    rad = lambda p: math.hypot(p[0], p[1]) - 1.0  # noqa: E731
    drawn = max(mid_errors(sp, rad))
    res = direct_curve(sp, 3)
    pts = as_points(res[0])
    report("circle_double_count", len(pts) == 32, str(len(pts)))
    check_on_conic("circle_double_drawn_rounding", pts, rad, 2 * drawn + 1e-12)
    check_on_conic("circle_double_1e-7", pts, rad, 1e-7)
    check_on_conic("circle_double_planar", pts, lambda p: p[2], 1e-12)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=3)
    report("circle_op_finished", r == {"FINISHED"}, str(r))
    out = ob.data.splines[0]
    stored = poly_co(out)
    report("circle_op_poly_cyclic", out.type == "POLY" and out.use_cyclic_u and
           len(stored) == 32, "%s %s %d" % (out.type, out.use_cyclic_u, len(stored)))
    check_on_conic("circle_stored_float32", stored, rad, 4 * F32)
    # the stored points are the double results rounded to float32
    worst = max(abs(stored[i][k] - pts[i][k]) for i in range(32) for k in range(3))
    report("circle_stored_is_rounded_double", worst <= F32, "worst %.3g" % worst)


@case
def ellipse_bezier_exact():
    fresh_scene()
    ob = new_curve("ellipse")
    a, b = 2.0, 1.0
    pts = [(a, 0, 0), (0, b, 0), (-a, 0, 0), (0, -b, 0)]
    tans = [(0, KAPPA * b, 0), (-KAPPA * a, 0, 0), (0, -KAPPA * b, 0), (KAPPA * a, 0, 0)]
    sp = add_bezier(ob.data, pts, tans, True)

    def ell(p):  # geometric distance to the ellipse ~ residual / gradient norm
        return (((p[0] / a) ** 2 + (p[1] / b) ** 2 - 1.0) /
                (2 * math.hypot(p[0] / a ** 2, p[1] / b ** 2)))
    drawn = max(mid_errors(sp, ell))
    out = as_points(direct_curve(sp, 4)[0])
    check_on_conic("ellipse_double_drawn_rounding", out, ell, 2 * drawn + 1e-12)
    check_on_conic("ellipse_double_1e-7", out, ell, 1e-7 * a)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=4)
    st = poly_co(ob.data.splines[0])
    report("ellipse_stored_count", len(st) == 64, str(len(st)))
    check_on_conic("ellipse_stored_float32", st, ell, 8 * F32 * a)


def arc_handles(pts, centre, r):
    """Handles of exact circular cubics through pts (on the circle):
    4/3 tan(theta/4) r along the tangents, theta the angle of each arc."""
    n = len(pts)
    ang = [math.atan2(p[1] - centre[1], p[0] - centre[0]) for p in pts]
    hl, hr = [None] * n, [None] * n
    for i in range(n):
        tx, ty = -math.sin(ang[i]), math.cos(ang[i])
        d_out = (ang[(i + 1) % n] - ang[i]) % (2 * math.pi) if i + 1 < n else 0.0
        d_in = (ang[i] - ang[i - 1]) % (2 * math.pi) if i > 0 else 0.0
        h_out = 4.0 / 3.0 * math.tan(d_out / 4) * r
        h_in = 4.0 / 3.0 * math.tan(d_in / 4) * r
        p = pts[i]
        hr[i] = (p[0] + h_out * tx, p[1] + h_out * ty, p[2])
        hl[i] = (p[0] - h_in * tx, p[1] - h_in * ty, p[2])
    return hl, hr


@case
def open_arc_exact():
    fresh_scene()
    ob = new_curve("arc")
    # Pythagorean points: exactly representable, exactly on the circle r=5;
    # the handles make each cubic a circular arc (up to float32 storage)
    pts = [(5, 0, 0), (4, 3, 0), (3, 4, 0), (0, 5, 0), (-3, 4, 0), (-4, 3, 0)]
    hl, hr = arc_handles(pts, (0, 0), 5.0)
    sp = ob.data.splines.new("BEZIER")
    sp.bezier_points.add(len(pts) - 1)
    for i, bp in enumerate(sp.bezier_points):
        bp.handle_left_type = bp.handle_right_type = "FREE"
        bp.co, bp.handle_left, bp.handle_right = pts[i], hl[i], hr[i]
    rad = lambda p: math.hypot(p[0], p[1]) - 5.0  # noqa: E731
    drawn = max(mid_errors(sp, rad))
    out = as_points(direct_curve(sp, 3)[0])
    report("arc_double_count", len(out) == 5 * 8 + 1, str(len(out)))
    check_on_conic("arc_double_drawn_rounding", out, rad, 2 * drawn + 1e-12)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=3)
    s = ob.data.splines[0]
    st = poly_co(s)
    report("arc_open_kept", not s.use_cyclic_u and len(st) == 41 and
           st[0] == (5.0, 0.0, 0.0) and st[-1] == (-4.0, 3.0, 0.0), "%d %r %r" %
           (len(st), st[0], st[-1]))
    check_on_conic("arc_stored_float32", st, rad, 4 * F32 * 5)


@case
def moved_rotated_circle_exact():
    """Circle r=5 at (1000,-500,20) in the plane spanned by (1,0,0) and
    (0,0.6,0.8): every coordinate and handle exact in float32 (handle factor
    9049/16384, the dyadic nearest 4/3 tan(pi/8) that float32 holds there,
    so the drawn cubics' middles are 6e-5 off the circle). The plane fit,
    the projection and the way back must add nothing to that."""
    fresh_scene()
    ob = new_curve("moved")
    c = (1000.0, -500.0, 20.0)
    nrm = (0.0, -0.8, 0.6)
    m = 9049.0 / 16384.0
    pts = [(1005.0, -500.0, 20.0), (1000.0, -497.0, 24.0), (995.0, -500.0, 20.0),
           (1000.0, -503.0, 16.0)]
    tans = [(0, 3 * m, 4 * m), (-5 * m, 0, 0), (0, -3 * m, -4 * m), (5 * m, 0, 0)]
    sp = add_bezier(ob.data, pts, tans, True)
    ob.rotation_euler = (0.3, 0.2, 0.1)  # object transform: must stay untouched
    rad = lambda p: dist(p, c) - 5.0  # noqa: E731
    drawn = max(mid_errors(sp, rad))
    out = as_points(direct_curve(sp, 3)[0])
    report("moved_double_count", len(out) == 32, str(len(out)))
    check_on_conic("moved_double_radius_drawn", out, rad, 2 * drawn + 1e-9)
    check_on_conic("moved_double_plane_1e-9", out,
                   lambda p: sum((p[k] - c[k]) * nrm[k] for k in range(3)), 1e-9)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=3)
    st = poly_co(ob.data.splines[0])
    report("moved_op_finished", r == {"FINISHED"} and len(st) == 32, "%r %d" % (r, len(st)))
    check_on_conic("moved_stored_float32", st, rad, 2 * drawn + 4 * F32 * 1000)
    report("moved_transform_untouched",
           tuple(round(x, 6) for x in ob.rotation_euler) == (0.3, 0.2, 0.1) and
           tuple(ob.location) == (0, 0, 0))


@case
def poly_star_inflections():
    """A star polygon smoothed (Keep Corners off): inflection points are
    inserted, every old vertex stays bit for bit."""
    fresh_scene()
    ob = new_curve("star")
    pts = []
    for i in range(10):
        r = 1.0 if i % 2 == 0 else 0.5
        a = i * math.pi / 5
        pts.append((r * math.cos(a), r * math.sin(a), 0.0))
    sp = add_poly(ob.data, pts, True)
    before = poly_co(sp)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=3, keep_corners=False)
    st = poly_co(ob.data.splines[0])
    ninfl = len(st) // 8 - 10
    report("star_op_count", r == {"FINISHED"} and len(st) % 8 == 0 and ninfl > 0,
           "%r %d points: %d inflections" % (r, len(st), ninfl))
    # interpolatory: every old vertex is still there, bit for bit
    sset = set(st)
    report("star_old_vertices_kept", all(p in sset for p in before))
    # with the default Keep Corners (40 degrees) every tip is a corner and
    # the star's straight edges stay as they are
    fresh_scene()
    ob = new_curve("star_corners")
    add_poly(ob.data, pts, True)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=3)
    st = poly_co(ob.data.splines[0])
    report("star_corners_kept", st == before, "%d points" % len(st))


@case
def nurbs_knots_match_blender():
    """The knot vector we compute gives the curve Blender draws: Blender's
    evaluated points lie on our adaptive plot (within the tolerance)."""
    ops = conica_pkg().operators
    configs = [("endpoint3", 3, False, True, False), ("uniform3", 3, False, False, False),
               ("uniform4", 4, False, False, False), ("bezier3", 3, False, True, True),
               ("cyclic3", 3, True, False, False), ("cyclic4", 4, True, False, False),
               ("endpoint4", 4, False, True, False)]
    base = [(0, 0, 0), (1, 2, 0), (3, 2.5, 0), (4, 0, 0), (5, -1, 0), (7, 1, 0), (8, 3, 0)]
    w = [1, 0.5, 2, 1, 1.5, 1, 0.8]
    tol = 1e-4
    for name, order, cyc, endp, bez in configs:
        fresh_scene()
        ob = new_curve("nurbs_" + name)
        sp = add_nurbs(ob.data, base, w, order, cyc, endp, bez)
        sp.resolution_u = 16
        data = ops.SplineData(sp)
        res = ops.spline_curve(sp, data, mode="flatten", tolerance=tol, typecode="d")
        poly = as_points(res[0])
        bl = eval_points(ob)
        worst = max(point_polyline_distance(p, poly, cyc) for p in bl)
        report("nurbs_knots_" + name, worst <= tol + 1e-5 and len(bl) > 10,
               "Blender's curve is %.3g from our plot (%d pts, %d ours)" %
               (worst, len(bl), len(poly)))


@case
def nurbs_circle():
    fresh_scene()
    ob = new_curve("nurbs_circle")
    h = math.sqrt(0.5)
    pts = [(1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0), (-1, 0, 0), (-1, -1, 0), (0, -1, 0),
           (1, -1, 0), (1, 0, 0)]
    w = [1, h, 1, h, 1, h, 1, h, 1]
    add_nurbs(ob.data, pts, w, 3, False, True, True)
    select_only(ob)
    r = bpy.ops.curve.adaptive_to_poly(tolerance=1e-4)
    sp = ob.data.splines[0]
    st = poly_co(sp)
    report("nurbs_to_poly", r == {"FINISHED"} and sp.type == "POLY" and 10 < len(st) < 2000,
           "%r %s %d" % (r, sp.type, len(st)))
    check_on_conic("nurbs_to_poly_vertices_on_circle", st,
                   lambda p: math.hypot(p[0], p[1]) - 1.0, 4 * F32)
    mids = [tuple((st[i][k] + st[i + 1][k]) / 2 for k in range(3)) for i in range(len(st) - 1)]
    check_on_conic("nurbs_to_poly_within_tolerance", mids,
                   lambda p: math.hypot(p[0], p[1]) - 1.0, 1e-4 + 4 * F32)
    # Conic Subdivide on a NURBS circle: plotted, then refined on the circle
    fresh_scene()
    ob = new_curve("nurbs_circle2")
    add_nurbs(ob.data, pts, w, 3, False, True, True)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    st = poly_co(ob.data.splines[0])
    report("nurbs_conic_subdivide", r == {"FINISHED"} and len(st) > 8, "%r %d" % (r, len(st)))
    # the NURBS is drawn as its four rational quadratic pieces, exact arcs:
    # sampled with exact points and normals, the conic subdivision stays on
    # the circle up to float32 storage (of the weights too)
    check_on_conic("nurbs_conic_subdivide_on_circle", st,
                   lambda p: math.hypot(p[0], p[1]) - 1.0, 4 * F32)
    ext = conica_pkg()._conica
    ctrl = [c for p in pts for c in p]
    r = ext.plot(ctrl, degree=2, knots=[0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4], weights=w,
                 tolerance=1e-4, tangents=True)
    P, T = r[0], r[3]
    worst = max(abs(P[3 * i] * T[3 * i] + P[3 * i + 1] * T[3 * i + 1]) /
                math.hypot(T[3 * i], T[3 * i + 1]) for i in range(len(P) // 3))
    report("nurbs_exact_tangents", worst < 1e-12, "%.3g" % worst)


@case
def bezier_to_poly_adaptive():
    fresh_scene()
    ob = new_curve("bez_adapt")
    sp = circle_bezier(ob.data)
    for bp in sp.bezier_points:
        bp.radius = 2.0
    select_only(ob)
    r = bpy.ops.curve.adaptive_to_poly(tolerance=1e-5)
    s = ob.data.splines[0]
    st = poly_co(s)
    anchors = {(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0)}
    report("bezier_to_poly", r == {"FINISHED"} and s.type == "POLY" and s.use_cyclic_u and
           anchors <= set(st), "%r %s %d" % (r, s.type, len(st)))
    # a cubic circle approximation is within 2.8e-4 of the circle
    mids = [tuple((st[i][k] + st[(i + 1) % len(st)][k]) / 2 for k in range(3))
            for i in range(len(st))]
    check_on_conic("bezier_to_poly_tolerance", mids, lambda p: math.hypot(p[0], p[1]) - 1.0,
                   2.8e-4 + 1e-5 + 4 * F32)
    report("bezier_to_poly_radius", all(abs(p.radius - 2.0) < 1e-6 for p in s.points))


@case
def adaptive_outputs_and_edit_mode():
    fresh_scene()
    ob = new_curve("ad_orig")
    circle_bezier(ob.data)
    base = [(0, 0, 0), (1, 2, 0), (3, 2.5, 0), (4, 0, 0), (5, -1, 0)]
    add_nurbs(ob.data, base, [1, 0.5, 2, 1, 1], 3, cyclic=True)
    add_poly(ob.data, [(0, 0, 0), (1, 0, 0)], False)
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.adaptive_to_poly(tolerance=1e-3, output="NEW_OBJECT")
    new = bpy.data.objects.get("ad_orig.conic")
    types = sorted(s.type for s in new.data.splines) if new else []
    cyc = sorted(s.use_cyclic_u for s in new.data.splines) if new else []
    report("adaptive_new_object", r == {"FINISHED"} and types == ["POLY"] * 3 and
           cyc == [False, True, True] and curve_snapshot(ob.data) == before,
           "%r %r %r" % (r, types, cyc))
    # the cyclic NURBS's polyline does not repeat its first point at the end
    if new:
        nz = [s for s in new.data.splines if s.use_cyclic_u and len(s.points) > 4]
        ok = all(poly_co(s)[0] != poly_co(s)[-1] for s in nz) and len(nz) == 2
        report("adaptive_cyclic_no_duplicate_end", ok)
    # edit mode: only the spline with selected points is converted
    fresh_scene()
    ob = new_curve("ad_edit")
    circle_bezier(ob.data)
    sp2 = circle_bezier(ob.data, 2.0)
    for i, s in enumerate(ob.data.splines):
        for bp in s.bezier_points:
            bp.select_control_point = i == 1
            bp.select_left_handle = bp.select_right_handle = False
    del sp2
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    r = bpy.ops.curve.adaptive_to_poly(tolerance=1e-3)
    bpy.ops.object.mode_set(mode="OBJECT")
    types = [(s.type, round(max(abs(c) for p in poly_co(s) for c in p), 3)
              if s.type == "POLY" else None) for s in ob.data.splines]
    report("adaptive_edit_mode_selected_only", r == {"FINISHED"} and
           sorted(t[0] for t in types) == ["BEZIER", "POLY"] and
           [t for t in types if t[0] == "POLY"][0][1] == 2.0, "%r %r" % (r, types))


# ---------------------------------------------------------------- drawn curves
# Faithful to the curves users bring: Bezier and NURBS splines are drawn
# curves, the result stays within the Fidelity of them (path.h).

def _active_copy():
    """The active object and a copy of its curve as it is now."""
    ob = bpy.context.active_object
    return ob, ob.data.copy()


@case
def bezier_primitive_follows_drawn_curve():
    """Add > Curve > Bezier: two anchors whose handles draw an S-shaped
    cubic. The only conic through the anchors with their tangents is the
    chord, which the add-on used to return; now every output point lies on
    the drawn cubic within the Fidelity."""
    for fid in (None, 1e-5):
        fresh_scene()
        bpy.ops.curve.primitive_bezier_curve_add()
        ob, src = _active_copy()
        select_only(ob)
        kw = {} if fid is None else dict(fidelity=fid)
        r = bpy.ops.curve.conic_subdivide(**kw)
        sp = ob.data.splines[0]
        st = poly_co(sp)
        tag = "default" if fid is None else "%g" % fid
        a0, a1 = (tuple(b.co) for b in src.splines[0].bezier_points)
        report("bezier_primitive_%s_finished" % tag, r == {"FINISHED"} and sp.type == "POLY" and
               not sp.use_cyclic_u and len(st) > 9 and st[0] == a0 and st[-1] == a1,
               "%r %s %d %r %r" % (r, sp.type, len(st), st[:1], st[-1:]))
        fidelity_check("bezier_primitive_%s_on_drawn_curve" % tag, src.splines[0], st, False,
                       fid or 1e-3)
        off = max(abs(p[1]) for p in st)  # the chord is y = 0
        report("bezier_primitive_%s_not_the_chord" % tag, off > 0.1, "%.3g" % off)
        if fid is None:
            n_default = len(st)
        else:
            report("bezier_primitive_fidelity_more_points", len(st) > n_default,
                   "%d vs %d" % (len(st), n_default))
        bpy.data.curves.remove(src)


@case
def bezier_primitive_radius_tilt_linear():
    """Radius and tilt of new points: linear between the anchors' values in
    the segment's parameter t (found here on the drawn cubic)."""
    fresh_scene()
    bpy.ops.curve.primitive_bezier_curve_add()
    ob = bpy.context.active_object
    bp = ob.data.splines[0].bezier_points
    bp[0].radius, bp[1].radius = 1.0, 3.0
    bp[0].tilt, bp[1].tilt = 0.0, 1.0
    src = ob.data.copy()
    select_only(ob)
    bpy.ops.curve.conic_subdivide()
    pts = ob.data.splines[0].points
    dense = drawn_spline(src.splines[0], 2048)
    worst = 0.0
    for p in pts:
        q = Vector(p.co[:3])
        i = min(range(len(dense)), key=lambda j: (dense[j] - q).length_squared)
        t = i / 2048.0
        worst = max(worst, abs(p.radius - (1.0 + 2.0 * t)), abs(p.tilt - t))
    report("bezier_radius_tilt_linear_in_t", worst < 2e-3 and pts[0].radius == 1.0 and
           pts[-1].radius == 3.0 and pts[-1].tilt == 1.0, "worst %.3g" % worst)
    bpy.data.curves.remove(src)


@case
def bezier_circle_primitive_on_circle():
    """Add > Curve > Circle: four anchors on the unit circle (acceptance:
    the output on the circle to float32 rounding). Blender gives the
    primitive AUTO handles of length 0.552125, not 4/3 tan(pi/8) =
    0.552285: its drawn cubics are 8.5e-5 inside the circle at their
    middles, where the path front end samples them; so this measures how
    far the drawn curve, not the add-on, is from the circle."""
    fresh_scene()
    bpy.ops.curve.primitive_bezier_circle_add()
    ob, src = _active_copy()
    sp_in = src.splines[0]
    k = (sp_in.bezier_points[0].handle_right - sp_in.bezier_points[0].co).length
    rad = lambda p: math.hypot(p[0], p[1]) - 1.0  # noqa: E731
    drawn = max(mid_errors(sp_in, rad))
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide()
    st = poly_co(ob.data.splines[0])
    worst = max(abs(rad(p)) for p in st)
    report("bezier_circle_primitive_radial_1e-6", r == {"FINISHED"} and worst < 1e-6,
           "relative radial error %.3g: the primitive's handles are %.7f long (a circle "
           "needs %.7f), so its drawn cubics are %.3g off the circle at their middles"
           % (worst, k, KAPPA, drawn))
    fidelity_check("bezier_circle_primitive_on_drawn_curve", sp_in, st, True, 1e-3)
    bpy.data.curves.remove(src)


def text_curve(body):
    """A text object with Blender's built-in font, converted to curves."""
    bpy.ops.object.text_add()
    ob = bpy.context.active_object
    ob.data.body = body
    font = ob.data.font.filepath
    bpy.ops.object.convert(target="CURVE")
    return bpy.context.active_object, font


@case
def text_glyphs_faithful():
    """'Sphinx gR&8' in Bfont, converted to curves (cyclic Bezier splines
    with corners, straight and tangent joins), Conic Subdivide with its
    defaults: within the Fidelity of each drawn spline, the same splines,
    every corner still a corner, no new crossings."""
    fresh_scene()
    ob, font = text_curve("Sphinx gR&8")
    src = ob.data.copy()
    sins = list(src.splines)
    report("text_builtin_font", font == "<builtin>" and ob.type == "CURVE" and
           len(sins) > 10 and all(sp.type == "BEZIER" and sp.use_cyclic_u for sp in sins),
           "%r %s %d" % (font, ob.type, len(sins)))
    drawn = [drawn_spline(sp) for sp in sins]
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide()
    outs = [sp for sp in ob.data.splines]
    report("text_spline_count_unchanged", r == {"FINISHED"} and len(outs) == len(sins) and
           all(sp.type == "POLY" and sp.use_cyclic_u for sp in outs),
           "%r %d -> %d" % (r, len(sins), len(outs)))
    out = [poly_co(sp) for sp in outs]
    worst, where = 0.0, None
    for i, (sp, d, o) in enumerate(zip(sins, drawn, out)):
        size, mx = shape_size(sp)
        pd = PolyDist(d, True)
        w = max(pd(q) for q in o) / (1e-3 * size + 4 * F32 * mx)
        if w > worst:
            worst, where = w, i
    report("text_on_drawn_curves", worst <= 1.0,
           "worst %.3g of the tolerance (spline %r)" % (worst, where))
    # corners: anchors whose handles turn by more than 40 degrees
    ncorner, worst_turn, missing = 0, 0.0, []
    for i, (sp, o) in enumerate(zip(sins, out)):
        index = {p: k for k, p in enumerate(o)}
        for b, turn in zip(sp.bezier_points, anchor_turns(sp)):
            if turn <= math.radians(40.0):
                continue
            ncorner += 1
            k = index.get(tuple(b.co))
            if k is None:
                missing.append((i, tuple(b.co)))
                continue
            worst_turn = max(worst_turn, abs(poly_turn(o, k, True) - turn))
    report("text_corners_kept", ncorner > 20 and not missing and
           worst_turn < math.radians(6.0),
           "%d corners, %d missing, polyline turn off by up to %.2f degrees" %
           (ncorner, len(missing), math.degrees(worst_turn)))
    before = crossing_pairs([([q[:2] for q in d], True) for d in drawn])
    after = crossing_pairs([([q[:2] for q in o], True) for o in out])
    report("text_no_new_crossings", not (after - before),
           "new crossings between splines %r" % sorted(after - before))
    bpy.data.curves.remove(src)


@case
def text_glyphs_bezier_and_polyline_outputs():
    """The same glyphs as Bezier output (handles along the conic tangents;
    measured 0.82 of the tolerance, not a guarantee: 1.5 allowed) and
    through Curve to Polyline (Adaptive) (the guaranteed plotter: within
    its tolerance in both directions)."""
    fresh_scene()
    ob, _font = text_curve("gR&8")
    src = ob.data.copy()
    sins = list(src.splines)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(output="BEZIER")
    worst = 0.0
    for sp_in, sp in zip(sins, ob.data.splines):
        size, mx = shape_size(sp_in)
        ev = drawn_spline(sp, 32)
        pd = PolyDist(drawn_spline(sp_in), True)
        od = PolyDist(ev, True)
        w = max(max(pd(q) for q in ev[::2]), max(od(q) for q in drawn_spline(sp_in, 32)))
        worst = max(worst, w / (1e-3 * size + 4 * F32 * mx))
    report("text_bezier_output_near_drawn", len(ob.data.splines) == len(sins) and worst < 1.5,
           "worst %.3g of the tolerance" % worst)
    fresh_scene()
    ob, _font = text_curve("gR&8")
    src = ob.data.copy()
    sins = list(src.splines)
    select_only(ob)
    tol = 1e-4
    r = bpy.ops.curve.adaptive_to_poly(tolerance=tol)
    worst = 0.0
    for sp_in, sp in zip(sins, ob.data.splines):
        o = poly_co(sp)
        d = drawn_spline(sp_in)
        mx = shape_size(sp_in)[1]
        pd, od = PolyDist(d, True), PolyDist(o, True)
        w = max(max(pd(q) for q in o), max(od(q) for q in d[::8]))
        worst = max(worst, w / (tol + 4 * F32 * mx))
    report("text_to_polyline_within_tolerance", r == {"FINISHED"} and worst <= 1.0,
           "worst %.3g of the tolerance" % worst)
    bpy.data.curves.remove(src)


@case
def poly_circle_20000_no_inflections():
    """20 000 points on a circle, stored in float32: the rounding of the
    coordinates must make no inflection points (each would be an extra
    point): exactly 20000 * 2^3 points at level 3."""
    fresh_scene()
    ob = new_curve("circle20k")
    sp = ob.data.splines.new("POLY")
    n = 20000
    sp.points.add(n - 1)
    co = array.array("f", bytes(16 * n))
    for i in range(n):
        a = 2 * math.pi * i / n
        co[4 * i], co[4 * i + 1], co[4 * i + 3] = math.cos(a), math.sin(a), 1.0
    sp.points.foreach_set("co", co)
    sp.use_cyclic_u = True
    before = set(poly_co(sp))
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=3)
    st = poly_co(ob.data.splines[0])
    report("poly_circle_20000_count", r == {"FINISHED"} and len(st) == n * 8,
           "%r %d points (%+d)" % (r, len(st), len(st) - n * 8))
    report("poly_circle_20000_vertices_kept", before <= set(st))


# ---------------------------------------------------------------- attributes

@case
def cyclic_radius_tilt_material():
    fresh_scene()
    ob = new_curve("hexagon")
    cu = ob.data
    cu.materials.append(bpy.data.materials.new("m0"))
    cu.materials.append(bpy.data.materials.new("m1"))
    pts = [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0.0) for i in range(6)]
    radius = [1, 2, 3, 4, 5, 6]
    tilt = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]
    sp = add_poly(cu, pts, True, radius, tilt)
    sp.material_index = 1
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=1, keep_corners=False)
    s = cu.splines[0]
    rr = [p.radius for p in s.points]
    tt = [p.tilt for p in s.points]
    report("cyclic_kept", s.use_cyclic_u and len(s.points) == 12, str(len(s.points)))
    report("material_index_kept", s.material_index == 1, str(s.material_index))
    report("radius_at_old_vertices", all(abs(rr[2 * i] - radius[i]) < 1e-6 for i in range(6)),
           str(rr))
    report("tilt_at_old_vertices", all(abs(tt[2 * i] - tilt[i]) < 1e-6 for i in range(6)),
           str(tt))
    ok = all(min(radius[i], radius[(i + 1) % 6]) < rr[2 * i + 1] <
             max(radius[i], radius[(i + 1) % 6]) for i in range(6))
    report("radius_interpolated", ok, str(rr))
    ok = abs(tt[11] - 0.25) < 1e-6 and abs(tt[1] - 0.05) < 1e-6
    report("tilt_interpolated", ok, str(tt))


# ---------------------------------------------------------------- outputs

@case
def output_bezier():
    fresh_scene()
    ob = new_curve("out_bez")
    circle_bezier(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2, output="BEZIER")
    s = ob.data.splines[0]
    # four quarter arcs, sampled at their ends, 4 points per sample edge
    # at level 2: 16 arcs
    report("output_bezier_type", r == {"FINISHED"} and s.type == "BEZIER" and
           len(s.bezier_points) == 16 and s.use_cyclic_u, "%r %s %d" %
           (r, s.type, len(s.bezier_points)))
    k = 4.0 / 3.0 * math.tan(2 * math.pi / 16 / 4)  # handle length for 16 arcs
    worst_dir = worst_len = 0.0
    for bp in s.bezier_points:
        p = bp.co
        for h in (bp.handle_left, bp.handle_right):
            d = h - p
            worst_dir = max(worst_dir, abs(d.dot(p)) / max(d.length, 1e-30))
            worst_len = max(worst_len, abs(d.length - k))
    report("output_bezier_handles_free", all(
        bp.handle_left_type == bp.handle_right_type == "FREE" for bp in s.bezier_points))
    report("output_bezier_tangent_handles", worst_dir < 1e-5, "%.3g" % worst_dir)
    report("output_bezier_handle_length", worst_len < 1e-3 * k, "%.3g vs %.3g" % (worst_len, k))
    ev = eval_points(ob)
    check_on_conic("output_bezier_shape", ev, lambda p: math.hypot(p[0], p[1]) - 1.0, 1e-5)


@case
def output_new_object():
    fresh_scene()
    ob = new_curve("orig")
    circle_bezier(ob.data)
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2, output="NEW_OBJECT")
    new = bpy.data.objects.get("orig.conic")
    report("output_new_object", r == {"FINISHED"} and new is not None and
           new.data != ob.data and new.data.splines[0].type == "POLY" and
           len(new.data.splines[0].points) == 16, str(r))
    report("output_new_object_original_untouched", curve_snapshot(ob.data) == before)


@case
def several_splines_objects_and_edit_mode():
    fresh_scene()
    a = new_curve("A")
    b = new_curve("B")
    for ob in (a, b):
        for cx in (0.0, 5.0):
            pts = [(cx + math.cos(i * math.pi / 4), math.sin(i * math.pi / 4), 0.0)
                   for i in range(8)]
            add_poly(ob.data, pts, True)
    select_only(a, b)
    bpy.ops.curve.conic_subdivide(levels=1, keep_corners=False)
    report("object_mode_all_selected", all(len(s.points) == 16 for ob in (a, b)
                                           for s in ob.data.splines))
    # edit mode: only the selected spline
    fresh_scene()
    c = new_curve("C")
    for cx in (0.0, 5.0):
        pts = [(cx + math.cos(i * math.pi / 4), math.sin(i * math.pi / 4), 0.0)
               for i in range(8)]
        add_poly(c.data, pts, True)
    for i, s in enumerate(c.data.splines):
        for p in s.points:
            p.select = i == 1
    select_only(c)
    bpy.ops.object.mode_set(mode="EDIT")
    r = bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    mode = bpy.context.mode
    bpy.ops.object.mode_set(mode="OBJECT")
    counts = sorted(len(s.points) for s in c.data.splines)
    xs = [min(p.co[0] for p in s.points) for s in c.data.splines if len(s.points) == 32]
    report("edit_mode_selected_spline_only", r == {"FINISHED"} and counts == [8, 32] and
           xs and xs[0] > 3.0 and mode == "EDIT_CURVE", "%r %r %r %s" % (r, counts, xs, mode))
    sel = {len(s.points): [p.select for p in s.points] for s in c.data.splines}
    report("edit_mode_selection_as_subdivide", all(sel[32]) and not any(sel[8]),
           "selected: %d of 32, %d of 8" % (sum(sel[32]), sum(sel[8])))
    # Every spline has a selected point (one only partly, one with a hidden
    # point): every result point selected and shown, in both objects in the
    # mode, whatever the spline type.
    fresh_scene()
    objs = []
    for name in ("D", "E"):
        ob = new_curve(name)
        add_poly(ob.data, [(math.cos(i * math.pi / 4), math.sin(i * math.pi / 4), 0.0)
                           for i in range(8)], True)
        circle_bezier(ob.data)
        objs.append(ob)
    for ob in objs:
        poly, bez = ob.data.splines[0], ob.data.splines[1]
        for i, p in enumerate(poly.points):
            p.select = i == 2
        poly.points[5].hide = True
        for i, bp in enumerate(bez.bezier_points):
            bp.select_control_point = bp.select_left_handle = bp.select_right_handle = i == 0
    select_only(*objs)
    bpy.ops.object.mode_set(mode="EDIT")
    r = bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    bpy.ops.object.mode_set(mode="OBJECT")
    flags = []
    for ob in objs:
        for s in ob.data.splines:
            pts = s.points if s.type != "BEZIER" else s.bezier_points
            flags += [(p.select if s.type != "BEZIER" else p.select_control_point, p.hide)
                      for p in pts]
    # the hidden point stays hidden (and unselected, as Blender keeps hidden
    # points), one per object; every other point selected and shown
    report("edit_mode_all_splines_selected_shown", r == {"FINISHED"} and len(flags) > 2 * 30 and
           flags.count((False, True)) == 2 and
           all(f == (True, False) for f in flags if f != (False, True)),
           "%r, %d points, %d selected, %d hidden" %
           (r, len(flags), sum(f[0] for f in flags), sum(f[1] for f in flags)))


@case
def undo_restores():
    """Operators called from Python push no undo step of their own (the UI
    pushes one for an operator with the UNDO flag when the user runs it), so
    the test pushes the steps the UI would: before and after the operator."""
    report("undo_flag", "UNDO" in bpy.types.CURVE_OT_conic_subdivide.bl_options and
           "UNDO" in bpy.types.CURVE_OT_adaptive_to_poly.bl_options)
    fresh_scene()
    ob = new_curve("undo")
    circle_bezier(ob.data)
    add_poly(ob.data, [(3, 0, 0), (4, 1, 0), (5, 0, 0)], False, [1, 2, 3], [0, 1, 0])
    select_only(ob)
    before = curve_snapshot(ob.data)
    bpy.ops.ed.undo_push(message="before conic subdivide")
    bpy.ops.curve.conic_subdivide(levels=3)
    bpy.ops.ed.undo_push(message="Conic Subdivide")
    after = curve_snapshot(bpy.data.objects["undo"].data)
    report("undo_changed", after != before)
    r = bpy.ops.ed.undo()
    restored = curve_snapshot(bpy.data.objects["undo"].data)
    report("undo_restores_exactly", r == {"FINISHED"} and restored == before,
           "undo %r" % r)
    bpy.ops.ed.redo()
    report("redo_reapplies", curve_snapshot(bpy.data.objects["undo"].data) == after)


@case
def undo_in_edit_mode():
    """Edit mode: the operator writes the edit-mode splines directly; the
    edit-mode undo steps around it restore them exactly."""
    fresh_scene()
    ob = new_curve("undo_edit")
    add_poly(ob.data, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                       for i in range(6)], True)
    for p in ob.data.splines[0].points:
        p.select = True
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.ed.undo_push(message="before")
    # a hexagon turns by 60 degrees: rounded only without Keep Corners
    r = bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    done = len(ob.data.splines[0].points)
    bpy.ops.ed.undo_push(message="Conic Subdivide")
    bpy.ops.ed.undo()
    bpy.ops.object.mode_set(mode="OBJECT")
    n = len(bpy.data.objects["undo_edit"].data.splines[0].points)
    report("undo_edit_mode", r == {"FINISHED"} and done == 24 and n == 6,
           "%r, %d points, %d after undo" % (r, done, n))
    # Every spline exactly restored (and brought back by redo) when the
    # operator rebuilt splines in Edit Mode: a Bezier spline became POLY, so
    # the splines after it were rebuilt too.
    fresh_scene()
    ob = new_curve("undo_edit2")
    add_poly(ob.data, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                       for i in range(6)], True, [1, 2, 3, 4, 5, 6])
    circle_bezier(ob.data, 2.0)
    add_poly(ob.data, [(5, 0, 0), (6, 1, 0), (7, 0, 0)], False)
    for sp in ob.data.splines:
        for p in sp.points:
            p.select = True
        for b in sp.bezier_points:
            b.select_control_point = True
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    before = [full_snapshot(sp) for sp in ob.data.splines]
    bpy.ops.ed.undo_push(message="before")
    r = bpy.ops.curve.conic_subdivide(levels=2)
    bpy.ops.ed.undo_push(message="Conic Subdivide")
    cu = bpy.data.objects["undo_edit2"].data
    after = [full_snapshot(sp) for sp in cu.splines]
    bpy.ops.ed.undo()
    cu = bpy.data.objects["undo_edit2"].data
    restored = [full_snapshot(sp) for sp in cu.splines]
    bpy.ops.ed.redo()
    cu = bpy.data.objects["undo_edit2"].data
    redone = [full_snapshot(sp) for sp in cu.splines]
    mode = bpy.context.mode
    bpy.ops.object.mode_set(mode="OBJECT")
    report("undo_edit_mode_exact", r == {"FINISHED"} and after != before and
           restored == before and mode == "EDIT_CURVE", "%r, mode %s" % (r, mode))
    report("redo_edit_mode_exact", redone == after)


@case
def poll_false_for_mesh():
    fresh_scene()
    bpy.ops.mesh.primitive_cube_add()
    cube = bpy.context.active_object
    select_only(cube)
    report("poll_false_mesh", not bpy.ops.curve.conic_subdivide.poll() and
           not bpy.ops.curve.adaptive_to_poly.poll())
    ob = new_curve("c")
    circle_bezier(ob.data)
    select_only(ob)
    report("poll_true_curve", bpy.ops.curve.conic_subdivide.poll())


@case
def degenerate_splines_reported():
    fresh_scene()
    ob = new_curve("mixed")
    cu = ob.data
    good = [(math.cos(i * math.pi / 4), math.sin(i * math.pi / 4), 0.0) for i in range(8)]
    add_poly(cu, [(0, 0, 0)], False)                                  # 1 point
    add_poly(cu, [(1, 1, 0), (1, 1, 0), (1, 1, 0)], True)             # duplicates
    add_poly(cu, [(0, 0, 0), (float("nan"), 1, 0), (2, 0, 0)], False)  # NaN
    add_poly(cu, [(0, 0, 0), (1, 0, 1), (1, 1, 0), (0, 1, 1)], True)  # non-planar
    add_poly(cu, good, True)
    bad_before = [spline_snapshot(s) for s in list(cu.splines)[:4]]
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    splines = list(cu.splines)
    after = [spline_snapshot(s) for s in splines]

    def same(x, y):  # NaN-aware comparison
        return repr(x) == repr(y)
    kept = all(any(same(b, a) for a in after) for b in bad_before)
    report("degenerate_others_processed", r == {"FINISHED"} and len(splines) == 5 and
           sorted(len(s.points) for s in splines)[-1] == 32, "%r %d" % (r, len(splines)))
    report("degenerate_left_unchanged", kept)
    # one WARNING per bad spline, naming the object and the spline, then
    # the INFO summary
    reps = last_reports()
    warns = [m for lv, m in reps if lv == "WARNING"]
    want = [("mixed, spline 0:", "at least"), ("mixed, spline 1:", "coincide"),
            ("mixed, spline 2:", "non-finite"), ("mixed, spline 3:", "not planar")]
    ok = len(warns) == 4 and all(w.startswith(a) and b in w for w, (a, b) in zip(warns, want))
    report("degenerate_warnings_name_splines", ok, repr(reps))
    report("degenerate_info_summary", reps and reps[-1][0] == "INFO" and
           "1 spline" in reps[-1][1] and "4 left unchanged" in reps[-1][1], repr(reps))
    # all bad: cancelled, nothing changed
    fresh_scene()
    ob = new_curve("allbad")
    add_poly(ob.data, [(0, 0, 0)], False)
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    report("degenerate_only_cancelled", r == {"CANCELLED"} and
           curve_snapshot(ob.data) == before, str(r))


@case
def keep_corners_and_modes():
    fresh_scene()
    ob = new_curve("square")
    sq = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0)]
    add_poly(ob.data, sq, True)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=2, keep_corners=True, corner_angle=math.radians(60))
    st = poly_co(ob.data.splines[0])
    off = max(min(abs(p[0]), abs(p[0] - 2), abs(p[1]), abs(p[1] - 2)) for p in st)
    # straight runs between corners stay as they are (path.h): the square
    report("keep_corners_straight_edges", st == [tuple(map(float, q)) for q in sq] and
           off == 0.0, "%d points, %.3g off the square" % (len(st), off))
    # ... with its corners found by the default settings too (90 > 40 degrees)
    fresh_scene()
    ob = new_curve("square_default")
    add_poly(ob.data, sq, True)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=2)
    report("keep_corners_default_square", len(poly_co(ob.data.splines[0])) == 4)
    fresh_scene()
    ob = new_curve("square_round")
    add_poly(ob.data, sq, True)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    st = poly_co(ob.data.splines[0])
    off = max(min(abs(p[0]), abs(p[0] - 2), abs(p[1]), abs(p[1] - 2)) for p in st)
    report("no_corners_rounds_the_square", off > 0.05, "%.3g" % off)
    # Bezier output keeps the corners too: the drawn curve stays on the edges
    fresh_scene()
    ob = new_curve("square_bez")
    add_poly(ob.data, sq, True)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=1, keep_corners=True,
                                      corner_angle=math.radians(60), output="BEZIER")
    ev = eval_points(ob)
    off = max(min(abs(p[0]), abs(p[0] - 2), abs(p[1]), abs(p[1] - 2)) for p in ev)
    report("keep_corners_bezier_output", r == {"FINISHED"} and len(ev) > 8 and off < 1e-5,
           "%r %d %.3g" % (r, len(ev), off))
    # Fidelity: a tighter one samples the drawn cubics more, every output
    # point stays within it; on the exact circle the result is the circle
    # (the 4/3 tan(pi/8) cubics are 2.7e-4 off the circle between their
    # middles and ends: within 1e-3 of the size they count as the circle,
    # within 1e-5 the result follows the drawn cubics instead)
    for fid in (1e-3, 1e-5):
        fresh_scene()
        ob = new_curve("c_fid")
        circle_bezier(ob.data)
        src = ob.data.copy()
        select_only(ob)
        r = bpy.ops.curve.conic_subdivide(levels=3, fidelity=fid)
        st = poly_co(ob.data.splines[0])
        report("mode_fidelity_%g_finished" % fid, r == {"FINISHED"} and len(st) >= 32,
               "%r %d" % (r, len(st)))
        fidelity_check("mode_fidelity_%g_on_drawn_curve" % fid, src.splines[0], st, True, fid)
        if fid == 1e-3:
            check_on_conic("mode_fidelity_%g_circle" % fid, st,
                           lambda p: math.hypot(p[0], p[1]) - 1.0, 4 * F32)
        else:
            report("mode_fidelity_1e-05_more_points", len(st) > 32, str(len(st)))
        bpy.data.curves.remove(src)
    # a 2D curve keeps z exactly 0
    fresh_scene()
    ob = new_curve("flat")
    ob.data.dimensions = "2D"
    add_poly(ob.data, [(math.cos(i), math.sin(i) * 0.5, 0) for i in range(6)], True)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
    st = poly_co(ob.data.splines[0])
    report("curve_2d_z_exact", len(st) >= 24 and all(p[2] == 0.0 for p in st))
    # non-planar alone: cancelled, unchanged
    fresh_scene()
    ob = new_curve("twisted")
    add_poly(ob.data, [(0, 0, 0), (1, 0, 0.5), (1, 1, 0), (0, 1, 0.5)], True)
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    report("nonplanar_unchanged", r == {"CANCELLED"} and curve_snapshot(ob.data) == before,
           str(r))
    reps = last_reports()
    report("nonplanar_warning", len(reps) == 1 and reps[0][0] == "WARNING" and
           reps[0][1].startswith("twisted, spline 0: spline is not planar"), repr(reps))


def order_fixture(name):
    """Five splines in a row along x, each kind once: 0 POLY hexagon, 1
    Bezier circle, 2 non-planar POLY (left unchanged), 3 NURBS arc, 4
    non-planar Bezier with AUTO/VECTOR handles (left unchanged); odd
    settings on the unchanged ones so a lossy copy would show."""
    ob = new_curve(name)
    cu = ob.data
    cu.materials.append(bpy.data.materials.new(name + "m0"))
    cu.materials.append(bpy.data.materials.new(name + "m1"))
    add_poly(cu, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                  for i in range(6)], True)
    sp = circle_bezier(cu)
    for b in sp.bezier_points:
        b.co.x += 10
        b.handle_left.x += 10
        b.handle_right.x += 10
    sp = add_poly(cu, [(20, 0, 0), (21, 0, 0.5), (21, 1, 0), (20, 1, 0.5)], True,
                  [0.5, 1.5, 2.5, 3.5], [0.1, 0.2, 0.3, 0.4])
    sp.material_index = 1
    sp.resolution_u = 7
    sp.use_smooth = False
    sp.tilt_interpolation = "EASE"
    sp.radius_interpolation = "CARDINAL"
    for i, p in enumerate(sp.points):
        p.weight_softbody = 0.25 * (i + 1)
        p.select = i % 2 == 0
    add_nurbs(cu, [(30, 0, 0), (31, 2, 0), (33, 2.5, 0), (34, 0, 0), (35, -1, 0)],
              [1, 0.5, 2, 1, 1], 3, endpoint=True)
    sp = add_bezier(cu, [(40, 0, 0), (41, 1, 1), (42, 0, 0), (43, 1, -1)],
                    [(0.3, 0, 0.2)] * 4, False)
    for i, b in enumerate(sp.bezier_points):
        b.handle_left_type = ("AUTO", "VECTOR", "ALIGNED", "FREE")[i]
        b.radius = 1 + i
        b.select_right_handle = i == 2
    return ob


def spline_xmin(sp):
    """Which of order_fixture's splines this is: 0, 10, .., 40."""
    pts = sp.bezier_points if sp.type == "BEZIER" else sp.points
    xs = [p.co[0] for p in pts]
    return 10 * math.floor((min(xs) + max(xs)) / 20)


@case
def spline_order_kept():
    """Results keep their splines' places, and the splines left alone keep
    every value (object mode: all splines; edit mode: the selected ones)."""
    for mode in ("OBJECT", "EDIT"):
        fresh_scene()
        ob = order_fixture("order_" + mode)
        cu = ob.data
        if mode == "EDIT":
            # select splines 1 and 3 only
            for i, sp in enumerate(cu.splines):
                for p in sp.points:
                    p.select = i == 3
                for b in sp.bezier_points:
                    b.select_control_point = i == 1
                    b.select_left_handle = b.select_right_handle = False
        select_only(ob)
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="EDIT")
        before = [full_snapshot(sp) for sp in ob.data.splines]
        r = bpy.ops.curve.conic_subdivide(levels=2, keep_corners=False)
        cu = ob.data
        xs = [spline_xmin(sp) for sp in cu.splines]
        types = [sp.type for sp in cu.splines]
        kept = [0, 2, 4] if mode == "EDIT" else [2, 4]
        same = [full_snapshot(cu.splines[i]) == before[i] for i in kept] \
            if len(cu.splines) == 5 else []
        changed = [i for i in range(min(5, len(cu.splines)))
                   if full_snapshot(cu.splines[i]) != before[i]]
        tag = mode.lower()
        report("order_kept_" + tag, r == {"FINISHED"} and xs == [0, 10, 20, 30, 40],
               "%r %r %r" % (r, xs, types))
        report("order_untouched_exact_" + tag, same and all(same), repr(same))
        report("order_processed_" + tag,
               changed == ([1, 3] if mode == "EDIT" else [0, 1, 3]) and
               types == ["POLY", "POLY", "POLY", "POLY", "BEZIER"], "%r %r" % (changed, types))
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="OBJECT")
            after_edit = [full_snapshot(sp) for sp in ob.data.splines]
            report("order_kept_after_leaving_edit_mode",
                   [after_edit[i] for i in kept] == [before[i] for i in kept] and
                   [spline_xmin(sp) for sp in ob.data.splines] == [0, 10, 20, 30, 40])


@case
def edit_mode_works_in_place():
    """In Edit Mode the operator writes Blender's edit-mode splines
    directly: it stays in Edit Mode, and the Object Mode data (what a copy of
    the curve holds until Edit Mode is left) is not touched."""
    fresh_scene()
    ob = new_curve("inplace")
    add_poly(ob.data, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                       for i in range(6)], True)
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.curve.select_all(action="SELECT")
    r = bpy.ops.curve.conic_subdivide(levels=1, keep_corners=False)
    objdata = ob.data.copy()  # copies the Object Mode splines only
    n_obj = len(objdata.splines[0].points)
    bpy.data.curves.remove(objdata)
    n_edit = len(ob.data.splines[0].points)
    mode = bpy.context.mode
    bpy.ops.object.mode_set(mode="OBJECT")
    n_after = len(ob.data.splines[0].points)
    report("edit_mode_no_mode_switch", r == {"FINISHED"} and mode == "EDIT_CURVE" and
           n_edit == 12 and n_obj == 6 and n_after == 12,
           "%r %s edit %d object %d after %d" % (r, mode, n_edit, n_obj, n_after))
    # New Object from Edit Mode takes the edited splines, not the stale
    # Object Mode ones; the original stays as it is in Edit Mode
    fresh_scene()
    ob = new_curve("editnew")
    add_poly(ob.data, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                       for i in range(6)], True)
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.curve.select_all(action="DESELECT")
    sp = add_poly(ob.data, [(5 + math.cos(i * math.pi / 2), math.sin(i * math.pi / 2), 0)
                            for i in range(4)], True)  # made in Edit Mode
    for p in sp.points:
        p.select = True
    before = [full_snapshot(s) for s in ob.data.splines]
    r = bpy.ops.curve.conic_subdivide(levels=2, output="NEW_OBJECT", keep_corners=False)
    orig_same = [full_snapshot(s) for s in ob.data.splines] == before
    bpy.ops.object.mode_set(mode="OBJECT")
    new = bpy.data.objects.get("editnew.conic")
    counts = [len(s.points) for s in new.data.splines] if new else []
    report("edit_mode_new_object_uses_edit_data", r == {"FINISHED"} and counts == [6, 16] and
           orig_same and len(ob.data.splines) == 2, "%r %r %s" % (r, counts, orig_same))


@case
def scan_and_minimal_writes():
    """_conica.scan (the one C pass behind the operators' input checks), and
    the writes the operators leave out: radius, tilt and hide are written
    only where the result differs from what Blender holds (a refilled point
    keeps its flags and values, a new one has radius 1, tilt 0, shown), so
    the result must carry them exactly as before; a plain success reports
    nothing."""
    scan = conica_pkg()._conica.scan
    nan, inf = float("nan"), float("inf")
    report("scan_first_bad_and_max",
           scan(array.array("f", [1, -3, 2, nan, 9]), 10.0) == (3, 3.0) and
           scan([1.0, -3.0, 2.0], inf) == (-1, 3.0) and
           scan(array.array("d", [1, -11, 2]), 10.0) == (1, 1.0) and
           scan(array.array("f"), 1.0) == (-1, 0.0) and
           scan([1.0, inf], inf) == (1, 1.0) and
           scan([2.0, 0.5, 0.0, 1.0], inf, True) == (2, 2.0) and
           scan([2.0, -0.5], inf, True) == (1, 2.0) and
           scan([2.0, -0.5], inf) == (-1, 2.0),
           repr([scan(array.array("f", [1, -3, 2, nan, 9]), 10.0),
                 scan([2.0, 0.5, 0.0], inf, True)]))
    ok_err = False
    try:
        scan([1.0], nan)
    except conica_pkg()._conica.ConicaError:
        ok_err = True
    report("scan_refuses_nan_limit", ok_err)
    hexagon = [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0) for i in range(6)]
    # edit mode, a hidden point and non-default radius/tilt on one spline,
    # defaults on the other: all points shown and selected afterwards, radius
    # and tilt interpolated on the first, 1 and 0 on the second
    fresh_scene()
    ob = new_curve("minwrites")
    sp0 = add_poly(ob.data, hexagon, True, radius=[1, 2, 3, 4, 5, 6], tilt=[0, .1, .2, .3, .4, .5])
    add_poly(ob.data, [(p[0] + 5, p[1], 0) for p in hexagon], True)
    select_only(ob)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.curve.select_all(action="SELECT")
    ob.data.splines[1].points[4].hide = True
    r = bpy.ops.curve.conic_subdivide(levels=1, keep_corners=False)
    sps = list(ob.data.splines)
    flags = [(p.hide, p.select) for s in sps for p in s.points]
    rad0 = [p.radius for p in sps[0].points]
    tilt0 = [p.tilt for p in sps[0].points]
    defaults = all(p.radius == 1.0 and p.tilt == 0.0 for p in sps[1].points)
    reps = last_reports()
    bpy.ops.object.mode_set(mode="OBJECT")
    # 12 + 10 points: none inserted next to the hidden point, which stays
    # hidden and unselected
    report("edit_mode_result_shown_and_selected", r == {"FINISHED"} and len(flags) == 22 and
           flags.count((True, False)) == 1 and
           all(f == (False, True) for f in flags if f != (True, False)), repr(flags))
    report("edit_mode_radius_tilt_written", len(rad0) == 12 and
           all(abs(rad0[2 * i] - (i + 1)) < 1e-6 and abs(tilt0[2 * i] - 0.1 * i) < 1e-6
               for i in range(6)) and 1.0 < rad0[1] < 2.0 and 1.0 < rad0[11] < 6.0,
           "%r %r" % (rad0, tilt0))
    report("edit_mode_default_radius_tilt_kept", defaults)
    report("plain_success_reports_nothing", reps == [], repr(reps))
    del sp0


@case
def edit_mode_bezier_handle_selection():
    """A Bezier spline whose only selected parts are handles counts as
    selected, as for Blender's own operators."""
    for key in ("select_left_handle", "select_right_handle"):
        fresh_scene()
        ob = new_curve("handles")
        circle_bezier(ob.data)
        circle_bezier(ob.data, 2.0)
        for i, sp in enumerate(ob.data.splines):
            for j, b in enumerate(sp.bezier_points):
                b.select_control_point = b.select_left_handle = b.select_right_handle = False
                if i == 1 and j == 2:
                    setattr(b, key, True)
        select_only(ob)
        bpy.ops.object.mode_set(mode="EDIT")
        r = bpy.ops.curve.conic_subdivide(levels=3)
        bpy.ops.object.mode_set(mode="OBJECT")
        kinds = [(s.type, len(s.points) if s.type == "POLY" else len(s.bezier_points))
                 for s in ob.data.splines]
        report("edit_mode_" + key, r == {"FINISHED"} and
               kinds == [("BEZIER", 4), ("POLY", 32)], "%r %r" % (r, kinds))


@case
def shape_keys_refused():
    """Inserting points would need every shape key to grow with them:
    curves with shape keys are reported and left unchanged, in both modes."""
    for mode in ("OBJECT", "EDIT"):
        fresh_scene()
        ob = new_curve("keyed")
        add_poly(ob.data, [(math.cos(i * math.pi / 3), math.sin(i * math.pi / 3), 0)
                           for i in range(6)], True)
        select_only(ob)
        ob.shape_key_add(name="Basis")
        kb = ob.shape_key_add(name="Big")
        for d in kb.data:
            d.co = d.co * 2
        before = curve_snapshot(ob.data)
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="EDIT")
            bpy.ops.curve.select_all(action="SELECT")
        r = bpy.ops.curve.conic_subdivide(levels=2)
        reps = last_reports()
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="OBJECT")
        keys = [len(k.data) for k in ob.data.shape_keys.key_blocks]
        report("shape_keys_refused_" + mode.lower(), r == {"CANCELLED"} and
               curve_snapshot(ob.data) == before and keys == [6, 6] and
               reps and reps[0][0] == "WARNING" and "keyed: has shape keys" in reps[0][1],
               "%r %r %r" % (r, keys, reps))


def bezier_deviation(sp_pts, poly, centre):
    """Largest distance from the polyline poly (float32 points as stored)
    to the closed Bezier circle-like spline given by sp_pts [(co, hl, hr)]
    (double), both taken relative to centre (so the differences keep their
    digits). Each polyline vertex and the points at 1/4, 1/2, 3/4 of every
    segment are projected onto the Bezier by Newton's method on
    (B(t) - q) . B'(t) = 0, started at the parameter of q's angle around
    the centre (the spline is star-shaped around it). Independent of the
    add-on."""
    n = len(sp_pts)
    segs = []
    for i in range(n):
        a, b = sp_pts[i], sp_pts[(i + 1) % n]
        segs.append([tuple(p[k] - centre[k] for k in range(3))
                     for p in (a[0], a[2], b[1], b[0])])

    def at(seg, t):
        p0, p1, p2, p3 = seg
        u = 1.0 - t
        pt = [u ** 3 * p0[k] + 3 * u * u * t * p1[k] + 3 * u * t * t * p2[k] + t ** 3 * p3[k]
              for k in range(3)]
        d1 = [3 * u * u * (p1[k] - p0[k]) + 6 * u * t * (p2[k] - p1[k]) +
              3 * t * t * (p3[k] - p2[k]) for k in range(3)]
        d2 = [6 * u * (p2[k] - 2 * p1[k] + p0[k]) + 6 * t * (p3[k] - 2 * p2[k] + p1[k])
              for k in range(3)]
        return pt, d1, d2

    def distance(q):
        ang = math.atan2(q[1], q[0]) % (2 * math.pi)
        x = ang / (2 * math.pi) * n
        best = float("inf")
        for si in (int(x) % n, (int(x) + 1) % n, (int(x) - 1) % n):
            t = min(1.0, max(0.0, x - int(x))) if si == int(x) % n else 0.5
            for _ in range(30):
                pt, d1, d2 = at(segs[si], t)
                r = [pt[k] - q[k] for k in range(3)]
                f = sum(r[k] * d1[k] for k in range(3))
                df = sum(d1[k] * d1[k] + r[k] * d2[k] for k in range(3))
                if df <= 0:
                    break
                t2 = min(1.0, max(0.0, t - f / df))
                if abs(t2 - t) < 1e-15:
                    t = t2
                    break
                t = t2
            pt = at(segs[si], t)[0]
            best = min(best, math.sqrt(sum((pt[k] - q[k]) ** 2 for k in range(3))))
        return best

    rel = [tuple(p[k] - centre[k] for k in range(3)) for p in poly]
    worst = 0.0
    m = len(rel)
    for i in range(m):
        a, b = rel[i], rel[(i + 1) % m]
        for f in (0.0, 0.25, 0.5, 0.75):
            q = tuple(a[k] + f * (b[k] - a[k]) for k in range(3))
            worst = max(worst, distance(q))
    return worst


def offset_circle(name, R, centre):
    """A 4-point Bezier circle of radius R whose stored coordinates lie
    around centre (not an object offset: the spline's own coordinates)."""
    ob = new_curve(name)
    sp = circle_bezier(ob.data, R)
    for bp in sp.bezier_points:
        for key in ("co", "handle_left", "handle_right"):
            v = getattr(bp, key)
            setattr(bp, key, tuple(v[k] + centre[k] for k in range(3)))
    pts = [(tuple(b.co), tuple(b.handle_left), tuple(b.handle_right))
           for b in sp.bezier_points]
    return ob, pts


@case
def float32_tolerance_clamped():
    """Curve to Polyline below what float32 can hold at the spline's size:
    clamped to the achievable tolerance with a warning stating it, and the
    stored polyline is within that (measured against the Bezier in double);
    a tolerance above it is kept and met, silently."""
    ops = conica_pkg().operators
    for R, centre, tol, label in ((1.0, (1e4, 0.0, 0.0), 1e-5, "x1e4"),
                                  (1.0, (1e4, 0.0, 0.0), 1e-3, "x1e4_1e-3"),
                                  (1e5, (0.0, 0.0, 0.0), 1e-7, "r1e5"),
                                  (1.0, (1e4, 0.0, 0.0), 1e-2, "x1e4_kept")):
        fresh_scene()
        ob, pts = offset_circle("far", R, centre)
        m = max(abs(c) for p in pts for v in p for c in v)
        achievable = ops.FLOAT32_TOL_SPACINGS * ops.float32_spacing(m)
        select_only(ob)
        r = bpy.ops.curve.adaptive_to_poly(tolerance=tol)
        warns = [msg for lv, msg in last_reports() if lv == "WARNING"]
        sp = ob.data.splines[0]
        poly = poly_co(sp)
        dev = bezier_deviation(pts, poly, centre)
        if tol < achievable:
            want = "far, spline 0: tolerance %.3g is below" % tol
            report("float32_clamp_warns_" + label, r == {"FINISHED"} and len(warns) == 1 and
                   warns[0].startswith(want) and
                   ("achievable tolerance %.3g" % achievable) in warns[0], repr(last_reports()))
            report("float32_clamp_met_" + label, dev <= achievable and len(poly) < 20000,
                   "deviation %.4g, achievable %.4g, %d points" % (dev, achievable, len(poly)))
        else:
            report("float32_tolerance_kept_" + label, r == {"FINISHED"} and not warns and
                   dev <= tol, "deviation %.4g for %.4g; %r" % (dev, tol, warns))


@case
def huge_and_nonfinite_coordinates_refused():
    """A coordinate beyond 1e30 (3.4e38 is what Blender stores for co = inf)
    or NaN is refused by both operators, naming spline and point as Python
    numbers them (from 0), and the scene stays exactly as it was."""
    cases = [("poly_inf", "POLY", "co", float("inf"), "beyond \u00b11e+30"),
             ("poly_nan", "POLY", "co", float("nan"), "non-finite coordinate"),
             ("bez_inf", "BEZIER", "handle_right", float("inf"), "right handle coordinate beyond"),
             ("bez_big", "BEZIER", "co", 2e30, "beyond \u00b11e+30")]
    for label, kind, key, value, words in cases:
        for op in ("conic_subdivide", "adaptive_to_poly"):
            if kind == "POLY" and op == "adaptive_to_poly":
                continue  # POLY splines are already polylines
            fresh_scene()
            ob = new_curve("huge")
            ring = [(math.cos(i * math.pi / 6), math.sin(i * math.pi / 6), 0.0)
                    for i in range(12)]
            add_poly(ob.data, ring, True)  # spline 0 is fine
            if kind == "POLY":
                sp = add_poly(ob.data, ring, True)
                p = sp.points[3]
                p.co = (value, p.co[1], p.co[2], p.co[3])
                stored = sp.points[3].co[0]
            else:
                sp = circle_bezier(ob.data)
                bp = sp.bezier_points[3]
                v = getattr(bp, key)
                setattr(bp, key, (value, v[1], v[2]))
                stored = getattr(sp.bezier_points[3], key)[0]
            before = [full_snapshot(s) for s in ob.data.splines]
            select_only(ob)
            getattr(bpy.ops.curve, op)()
            warns = [msg for lv, msg in last_reports() if lv == "WARNING"]
            # spline 0 is processed; spline 1 is kept exactly as it was
            bad_kept = full_snapshot(ob.data.splines[1]) == before[1]
            report("refused_%s_%s" % (label, op),
                   len(warns) == 1 and warns[0].startswith("huge, spline 1: point 3 has a") and
                   words in warns[0] and bad_kept,
                   "stored %r; %r" % (stored, last_reports()))
    # the spline alone: cancelled, and the whole curve byte for byte unchanged
    fresh_scene()
    ob = new_curve("huge")
    sp = circle_bezier(ob.data)
    sp.bezier_points[2].co = (float("inf"), 0.0, 0.0)
    report("inf_stored_as_float32_max", sp.bezier_points[2].co[0] in (float("inf"), 3.4028234663852886e38),
           repr(sp.bezier_points[2].co[0]))
    before = [full_snapshot(s) for s in ob.data.splines]
    select_only(ob)
    r1 = bpy.ops.curve.conic_subdivide()
    r2 = bpy.ops.curve.adaptive_to_poly()
    report("huge_only_cancelled_unchanged", r1 == r2 == {"CANCELLED"} and
           [full_snapshot(s) for s in ob.data.splines] == before, "%r %r" % (r1, r2))


def surface_eval():
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    try:
        import surface_eval as se
    finally:
        sys.path.pop(0)
    return se


@case
def surface_to_mesh_within_tolerance():
    """Surface to Mesh (Adaptive) on Blender's own Add > Surface primitives:
    measured by an evaluator of the test's own (tests/blender/surface_eval.py,
    from the control net, weights, orders and knots Blender exposes; first
    checked against Blender's own conversion), every vertex lies on the
    surface, every face (centre and edge midpoints) within the tolerance,
    and fewer vertices than Blender's uniform conversion at the same
    measured deviation."""
    se = surface_eval()
    ops = conica_pkg().operators
    tol = 1e-2
    for prim in ("surface", "cylinder", "sphere", "torus"):
        fresh_scene()
        getattr(bpy.ops.surface, "primitive_nurbs_surface_%s_add" % prim)()
        ob = bpy.context.active_object
        sp = ob.data.splines[0]
        dist = se.Distance(se.Surface(sp, ops.nurbs_knots))
        dg = bpy.context.evaluated_depsgraph_get()
        ev = ob.evaluated_get(dg)
        me = ev.to_mesh()
        ref = float(dist.many(se.mesh_arrays(me)[0]).max())
        nb = len(me.vertices)
        ev.to_mesh_clear()
        # the evaluator and Blender agree: Blender's own vertices are on it
        report("surface_eval_matches_blender_" + prim, ref < 1e-5,
               "Blender's %d vertices up to %.3g off the evaluated surface" % (nb, ref))
        select_only(ob)
        r = bpy.ops.object.conic_surface_to_mesh(tolerance=tol)
        new = bpy.context.active_object
        ok = r == {"FINISHED"} and new is not ob and new.type == "MESH"
        report("surface_to_mesh_runs_" + prim, ok, "%r %r" % (r, last_reports()))
        if not ok:
            continue
        dv, df = se.mesh_deviation(new.data, dist)
        report("surface_vertices_on_surface_" + prim, dv < 1e-5,
               "vertices up to %.3g off" % dv)
        report("surface_faces_within_tolerance_" + prim, df <= tol,
               "faces up to %.4g off for %g (%d vertices; Blender's default %d)"
               % (df, tol, len(new.data.vertices), nb))
        # Blender's uniform conversion at the same measured deviation (the
        # smallest resolution r that measures no more) has more vertices:
        # no r whose mesh has at most as many vertices as ours measures as
        # little (r grows until Blender's mesh is the bigger one; its
        # deviation is measured only below that)
        ours, theirs, closest = len(new.data.vertices), None, None
        for r in range(1, 33):
            for spl in ob.data.splines:
                spl.resolution_u = spl.resolution_v = r
            ev = ob.evaluated_get(bpy.context.evaluated_depsgraph_get())
            me = ev.to_mesh()
            n = len(me.vertices)
            d = max(se.mesh_deviation(me, dist)) if n <= ours else None
            ev.to_mesh_clear()
            if d is None:
                theirs = (r, n)
                break
            closest = (r, n, d)
            if d <= df:
                break
        report("surface_fewer_vertices_than_blender_" + prim,
               theirs is not None,
               "%d vertices at %.4g; Blender's largest mesh that is not bigger %r "
               "(r, vertices, deviation) measures more; r = %r has more vertices"
               % (ours, df, closest, theirs))
        report("surface_original_kept_" + prim, ob.name in bpy.data.objects and
               not ob.select_get() and new.select_get())
    # far from the origin a tolerance below float32's reach is raised to
    # the achievable one with a warning, and the faces stay within that
    fresh_scene()
    bpy.ops.surface.primitive_nurbs_surface_sphere_add()
    ob = bpy.context.active_object
    sp = ob.data.splines[0]
    for pt in sp.points:
        x, y, z, wt = pt.co
        pt.co = (x + 1e4, y, z, wt)
    dist = se.Distance(se.Surface(sp, ops.nurbs_knots))
    select_only(ob)
    r = bpy.ops.object.conic_surface_to_mesh(tolerance=1e-6)
    new = bpy.context.active_object
    warns = [m for lv, m in last_reports() if lv == "WARNING"]
    achievable = ops.FLOAT32_TOL_SPACINGS * ops.float32_spacing(1e4 + 1.0)
    ok = r == {"FINISHED"} and new is not ob and len(warns) == 1 and \
        "used the achievable tolerance" in warns[0]
    df = se.mesh_deviation(new.data, dist)[1] if ok else None
    report("surface_float32_tolerance_raised", ok and df <= achievable,
           "%r %r faces %r off for %g" % (r, last_reports(), df, achievable))
    # a surface with a huge coordinate is refused, nothing made
    fresh_scene()
    bpy.ops.surface.primitive_nurbs_surface_surface_add()
    ob = bpy.context.active_object
    ob.data.splines[0].points[5].co = (float("inf"), 0.0, 0.0, 1.0)
    select_only(ob)
    n_objects = len(bpy.data.objects)
    r = bpy.ops.object.conic_surface_to_mesh(tolerance=tol)
    warns = [m for lv, m in last_reports() if lv == "WARNING"]
    report("surface_huge_refused", r == {"CANCELLED"} and len(bpy.data.objects) == n_objects and
           len(warns) == 1 and warns[0].startswith("SurfPatch, spline 0: point 5 has a "
                                                    "coordinate that is not finite or beyond"),
           "%r %r" % (r, last_reports()))
    # undo (the steps the UI would push around it) removes the mesh and
    # leaves the surface exactly as it was; redo brings the mesh back
    fresh_scene()
    bpy.ops.surface.primitive_nurbs_surface_torus_add()
    ob = bpy.context.active_object
    name = ob.name
    before = (sorted(o.name for o in bpy.data.objects), full_snapshot(ob.data.splines[0]))
    select_only(ob)
    bpy.ops.ed.undo_push(message="before surface to mesh")
    bpy.ops.object.conic_surface_to_mesh(tolerance=tol)
    bpy.ops.ed.undo_push(message="Surface to Mesh (Adaptive)")
    made = name + ".mesh" in bpy.data.objects
    r = bpy.ops.ed.undo()
    after = (sorted(o.name for o in bpy.data.objects),
             full_snapshot(bpy.data.objects[name].data.splines[0]))
    report("surface_undo_restores", made and r == {"FINISHED"} and after == before,
           "%r %r" % (r, after[0]))
    bpy.ops.ed.redo()
    report("surface_redo_reapplies", name + ".mesh" in bpy.data.objects)
    # poll: not for a curve object
    fresh_scene()
    ob = new_curve("notsurface")
    circle_bezier(ob.data)
    select_only(ob)
    report("surface_poll_false_for_curve", not bpy.ops.object.conic_surface_to_mesh.poll())


# ---------------------------------------------------------------- Blender's own data

def ops_mod():
    return importlib.import_module("conica.operators")



def mesh_to_curve(verts=None, edges=None, circle=0, scale=(1.0, 1.0, 1.0)):
    """A curve made as a user makes one: a mesh (a circle of `circle`
    vertices, or the given outline), Object > Convert > Curve. Blender
    writes POLY splines with w = 0 at every point."""
    fresh_scene()
    if circle:
        bpy.ops.mesh.primitive_circle_add(vertices=circle, radius=1.0)
        ob = bpy.context.active_object
    else:
        me = bpy.data.meshes.new("outline")
        me.from_pydata(verts, edges, [])
        ob = bpy.data.objects.new("outline", me)
        bpy.context.scene.collection.objects.link(ob)
        select_only(ob)
    if scale != (1.0, 1.0, 1.0):
        ob.scale = scale
        bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    bpy.ops.object.convert(target="CURVE")
    ob = bpy.context.active_object
    select_only(ob)
    return ob


@case
def mesh_converted_curves():
    """Mesh circles, ellipses and an outline converted to curves (POLY
    splines whose w is 0) go through both operators; Conic Subdivide's
    level-5 points lie on the circle within 2 float32 ulps of the radius."""
    for n in (6, 12, 64):
        ob = mesh_to_curve(circle=n)
        sp = ob.data.splines[0]
        ws = {p.co[3] for p in sp.points}
        r2 = bpy.ops.curve.adaptive_to_poly()
        reps2 = last_reports()
        # a hexagon turns by 60 degrees at each vertex: a corner unless
        # Keep Corners is off
        r = bpy.ops.curve.conic_subdivide(levels=5, keep_corners=n != 6)
        sp = ob.data.splines[0]
        ulp = ops_mod().float32_spacing(1.0)
        err = max(abs(math.hypot(p.co[0], p.co[1]) - 1.0) for p in sp.points)
        report("mesh_circle_%d_on_circle" % n, r == {"FINISHED"} and ws == {0.0} and
               sp.type == "POLY" and len(sp.points) == n * 32 and err <= 2 * ulp,
               "%r w %r, %d points, %.3g ulps %r" % (r, ws, len(sp.points), err / ulp,
                                                     last_reports()))
        report("mesh_circle_%d_adaptive_accepts" % n, r2 == {"CANCELLED"} and
               reps2 == [("INFO", "Curve to Polyline (Adaptive): nothing to do; the spline "
                                  "is already Poly")], "%r %r" % (r2, reps2))
    ob = mesh_to_curve(circle=6)
    r = bpy.ops.curve.conic_subdivide(levels=5)
    reps = last_reports()
    report("mesh_hexagon_corners_say_so", r == {"CANCELLED"} and len(reps) == 1 and
           reps[0][0] == "INFO" and "turn off Keep Corners" in reps[0][1] and
           len(ob.data.splines[0].points) == 6, "%r %r" % (r, reps))
    # ellipses: circles scaled 2 x 1 and 1 x 3 (the scale applied to the mesh)
    for sx, sy in ((2.0, 1.0), (1.0, 3.0)):
        ob = mesh_to_curve(circle=32, scale=(sx, sy, 1.0))
        r = bpy.ops.curve.conic_subdivide(levels=5)
        pts = ob.data.splines[0].points
        # distance from the ellipse, to first order: |F| / |grad F|
        worst = 0.0
        for p in pts:
            x, y = p.co[0], p.co[1]
            f = (x / sx) ** 2 + (y / sy) ** 2 - 1.0
            g = 2.0 * math.hypot(x / sx ** 2, y / sy ** 2)
            worst = max(worst, abs(f) / g)
        # a POLY spline's tangents are estimated from its points, exact for
        # a circle's evenly spaced ones, not for an ellipse's: the result is
        # a smooth curve through the points near the ellipse (docs/blender.md)
        ulp = ops_mod().float32_spacing(max(sx, sy))
        report("mesh_ellipse_%gx%g_near_ellipse" % (sx, sy), r == {"FINISHED"} and
               len(pts) == 32 * 32 and worst <= 1e-3 * max(sx, sy),
               "%r %d points, %.3g off (%.3g ulps)" % (r, len(pts), worst, worst / ulp))
    # an outline no one drew as a curve: an L-shaped mesh outline with a
    # rounded corner, edges only
    outline = [(0, 0, 0), (3, 0, 0), (3, 1, 0), (1.7, 1, 0), (1.3, 1.1, 0), (1.1, 1.5, 0),
               (1, 2, 0), (1, 3, 0), (0, 3, 0)]
    edges = [(i, (i + 1) % len(outline)) for i in range(len(outline))]
    for op, name in ((bpy.ops.curve.conic_subdivide, "subdivide"),
                     (bpy.ops.curve.adaptive_to_poly, "adaptive")):
        ob = mesh_to_curve(verts=outline, edges=edges)
        r = op()
        reps = last_reports()
        sp = ob.data.splines[0]
        ok = not any(lv != "INFO" for lv, _ in reps) and sp.type == "POLY"
        if name == "subdivide":
            ok = ok and r == {"FINISHED"} and len(sp.points) > len(outline)
        else:
            ok = ok and r == {"CANCELLED"} and len(sp.points) == len(outline)
        report("mesh_outline_%s_accepts" % name, ok,
               "%r %r %d points" % (r, reps, len(sp.points)))
    # NURBS keep their weight check: weight 0 is refused, naming the point
    fresh_scene()
    ob = new_curve("w0")
    add_nurbs(ob.data, [(math.cos(k), math.sin(k), 0) for k in range(5)], [1, 1, 0, 1, 1], 3)
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    reps = last_reports()
    report("nurbs_weight_0_refused", r == {"CANCELLED"} and curve_snapshot(ob.data) == before and
           reps == [("WARNING", "w0, spline 0: point 2 has weight 0.0; weights must be "
                                "positive numbers")], "%r %r" % (r, reps))


@case
def blender_shapes_accepted():
    """Other shapes of Blender's own data: text converted to curves, a
    cyclic flag toggled after the points were made, radius-0 points."""
    fresh_scene()
    bpy.ops.object.text_add()
    txt = bpy.context.active_object
    txt.data.body = "Os"
    bpy.ops.object.convert(target="CURVE")
    ob = bpy.context.active_object
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    reps = last_reports()
    report("text_converted_subdivides", r == {"FINISHED"} and
           not any(lv == "WARNING" for lv, _ in reps), "%r %r" % (r, reps))
    # cyclic toggled on after creation, and one point of radius 0
    fresh_scene()
    ob = new_curve("toggled")
    sp = add_poly(ob.data, [(math.cos(i * math.pi / 6), math.sin(i * math.pi / 6), 0.0)
                            for i in range(12)], False, radius=[1.0] * 11 + [0.0])
    sp.use_cyclic_u = True
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    sp = ob.data.splines[0]
    report("cyclic_toggled_radius_0", r == {"FINISHED"} and len(sp.points) == 48 and
           sp.use_cyclic_u and sp.points[44].radius == 0.0 and
           max(abs(math.hypot(p.co[0], p.co[1]) - 1.0) for p in sp.points) < 1e-6,
           "%r %d %r" % (r, len(sp.points), last_reports()))
    # Grease Pencil: 3.4 converts strokes to curves only with
    # gpencil.convert, which needs a 3D View (not in background mode); not
    # tested here (docs/blender.md says so)


def _points_bytes(cu):
    """Every point of cu as raw bytes (co, radius, tilt, hide, select)."""
    out = []
    for sp in cu.splines:
        pts = sp.bezier_points if sp.type == "BEZIER" else sp.points
        for key, width, tc in (("co", 3 if sp.type == "BEZIER" else 4, "f"),
                               ("radius", 1, "f"), ("tilt", 1, "f"), ("hide", 1, "b"),
                               ("select" if sp.type != "BEZIER" else "select_control_point",
                                1, "b")):
            buf = array.array(tc, bytes(array.array(tc).itemsize * width * len(pts)))
            pts.foreach_get(key, buf)
            out.append(buf.tobytes())
    return b"".join(out)


@case
def linked_and_override_untouched():
    """A curve linked from another .blend, an object override whose curve
    stays linked and an override of the curve itself: poll() refuses with
    Blender's message naming the library, the data stays byte-identical;
    a local curve selected with them is processed, the linked one reported."""
    fresh_scene()
    ob = new_curve("Lib")
    add_poly(ob.data, [(math.cos(i * math.pi / 4), math.sin(i * math.pi / 4), 0.0)
                       for i in range(8)], True)
    lib = os.path.join(TMP, "lib.blend")
    bpy.data.libraries.write(lib, {ob})
    fresh_scene()
    with bpy.data.libraries.load(lib, link=True) as (src, dst):
        dst.objects = ["Lib"]
    lob = dst.objects[0]
    bpy.context.scene.collection.objects.link(lob)
    before = _points_bytes(lob.data)
    for op, name in ((bpy.ops.curve.conic_subdivide, "subdivide"),
                     (bpy.ops.curve.adaptive_to_poly, "adaptive")):
        select_only(lob)
        try:
            op()
            msg = None
        except RuntimeError as exc:
            msg = str(exc)
        report("linked_refused_%s" % name, msg is not None and
               "Cannot edit library linked or non-editable override data: curve 'Lib' is "
               "linked from " + lib in msg and _points_bytes(lob.data) == before, repr(msg))
    # an override of the object (its curve stays linked), then of the curve
    ov = lob.override_create()
    bpy.context.scene.collection.objects.link(ov)
    bpy.context.view_layer.update()
    for stage in ("object", "data"):
        if stage == "data":
            ov.data = ov.data.override_create()
        before = _points_bytes(ov.data)
        select_only(ov)
        try:
            bpy.ops.curve.conic_subdivide(levels=2)
            msg = None
        except RuntimeError as exc:
            msg = str(exc)
        report("override_%s_refused" % stage, msg is not None and lib in msg and
               "Cannot edit library linked or non-editable override data" in msg and
               _points_bytes(ov.data) == before, repr(msg))
    # with a local curve selected too: that one is processed
    loc = new_curve("Local")
    circle_bezier(loc.data)
    select_only(loc, lob)
    before = _points_bytes(lob.data)
    r = bpy.ops.curve.conic_subdivide(levels=1)
    reps = last_reports()
    report("linked_skipped_local_done", r == {"FINISHED"} and _points_bytes(lob.data) == before and
           loc.data.splines[0].type == "POLY" and
           any(lv == "WARNING" and m.startswith("Lib: Cannot edit library linked") and lib in m
               for lv, m in reps), "%r %r" % (r, reps))


def _hidden_fixture(name):
    ob = new_curve(name)
    sp = add_poly(ob.data, [(math.cos(i * math.pi / 8), math.sin(i * math.pi / 8), 0.0)
                            for i in range(16)], True)
    for i in (3, 4, 5):
        sp.points[i].hide = True
    return ob


@case
def hidden_points_stay():
    """16-point cyclic POLY with points 3-5 hidden, as Blender's Subdivide:
    those points stay where they were and hidden, no point is inserted on a
    segment with a hidden end (2-3, 3-4, 4-5, 5-6), the rest is subdivided."""
    for mode in ("OBJECT", "EDIT"):
        fresh_scene()
        ob = _hidden_fixture("hid")
        src = poly_co(ob.data.splines[0])
        select_only(ob)
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="EDIT")
            bpy.ops.curve.select_all(action="SELECT")
        r = bpy.ops.curve.conic_subdivide(levels=3, keep_corners=False)
        if mode == "EDIT":
            bpy.ops.object.mode_set(mode="OBJECT")
        sp = ob.data.splines[0]
        pts = poly_co(sp)
        hid = [i for i, p in enumerate(sp.points) if p.hide]
        # 16 * 8 points less 4 segments of 7 inner points
        ok = r == {"FINISHED"} and len(pts) == 128 - 28 and hid == [17, 18, 19]
        ok = ok and all(dist(pts[h], src[k]) < 1e-6 for h, k in zip(hid, (3, 4, 5)))
        ok = ok and dist(pts[16], src[2]) < 1e-6 and dist(pts[20], src[6]) < 1e-6
        ok = ok and not any(sp.points[h].select for h in hid)
        report("hidden_points_stay_%s" % mode.lower(), ok,
               "%r %d points, hidden %r" % (r, len(pts), hid))
    # a Bezier spline with a hidden point: refused in Blender's words
    fresh_scene()
    ob = new_curve("hidbez")
    circle_bezier(ob.data)
    ob.data.splines[0].bezier_points[1].hide = True
    before = curve_snapshot(ob.data)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    reps = last_reports()
    report("hidden_bezier_refused", r == {"CANCELLED"} and curve_snapshot(ob.data) == before and
           len(reps) == 1 and "has hidden points" in reps[0][1] and "Alt H" in reps[0][1],
           "%r %r" % (r, reps))


@case
def noop_anchors_messages_tooltips():
    """A run that changes nothing says so and is CANCELLED (no undo step);
    Curve to Polyline (Adaptive) makes every anchor of an AUTO-handle
    Bezier a vertex; messages speak Blender's words; tooltips are one line."""
    fresh_scene()
    ob = new_curve("sq")
    add_poly(ob.data, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], True)
    select_only(ob)
    before = curve_snapshot(ob.data)
    r = bpy.ops.curve.conic_subdivide(levels=1)
    reps = last_reports()
    report("noop_info_cancelled", r == {"CANCELLED"} and curve_snapshot(ob.data) == before and
           len(reps) == 1 and reps[0][0] == "INFO" and "nothing to change" in reps[0][1],
           "%r %r" % (r, reps))
    # 8 anchors, AUTO handles (Blender computes them), alternating radii
    fresh_scene()
    ob = new_curve("auto8")
    sp = ob.data.splines.new("BEZIER")
    sp.bezier_points.add(7)
    for i, bp in enumerate(sp.bezier_points):
        a, rr = 2 * math.pi * i / 8, 1.0 + 0.3 * (i % 2)
        bp.co = (rr * math.cos(a), rr * math.sin(a), 0.0)
        bp.handle_left_type = bp.handle_right_type = "AUTO"
    sp.use_cyclic_u = True
    anchors = [tuple(bp.co) for bp in sp.bezier_points]
    select_only(ob)
    r = bpy.ops.curve.adaptive_to_poly(tolerance=1e-3)
    pts = poly_co(ob.data.splines[0])
    miss = [k for k, a in enumerate(anchors) if min(dist(a, p) for p in pts) > 1e-6]
    report("adaptive_every_anchor_a_vertex", r == {"FINISHED"} and not miss,
           "%r anchors without a vertex: %r" % (r, miss))
    # a legal NURBS weight of 1e30: refused, in spline terms
    fresh_scene()
    ob = new_curve("w30")
    add_nurbs(ob.data, [(math.cos(k), math.sin(k), 0) for k in range(5)], [1, 1, 1e30, 1, 1], 3)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=2)
    reps = last_reports()
    words = " ".join(m for _, m in reps)
    report("messages_blender_words_weight", reps and "segment" not in words and
           "subpath" not in words and "w30, spline 0" in words, "%r %r" % (r, reps))
    # level 8 on a spline whose result exceeds the point budget
    fresh_scene()
    ob = new_curve("big")
    n = 20000
    add_poly(ob.data, [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n), 0.0)
                       for i in range(n)], True)
    select_only(ob)
    r = bpy.ops.curve.conic_subdivide(levels=8)
    reps = last_reports()
    words = " ".join(m for _, m in reps)
    report("messages_blender_words_levels", r == {"CANCELLED"} and "subpath" not in words and
           "Levels" in words and len(ob.data.splines[0].points) == n, "%r %r" % (r, reps))
    # tooltips without hard line breaks; tolerances shown with 6 decimals
    texts = []
    rnas = [op.get_rna_type() for op in (bpy.ops.curve.conic_subdivide,
                                         bpy.ops.curve.adaptive_to_poly,
                                         bpy.ops.object.conic_surface_to_mesh)]
    for rna in rnas:
        texts.append(rna.description)
        texts += [p.description for p in rna.properties]
    report("tooltips_one_line", all("\n" not in t for t in texts) and all(texts[:1]),
           repr([t for t in texts if "\n" in t]))
    precs = [rnas[0].properties["fidelity"].precision, rnas[1].properties["tolerance"].precision,
             rnas[2].properties["tolerance"].precision, rnas[2].properties["fidelity"].precision]
    report("redo_values_six_decimals", precs == [6, 6, 6, 6], repr(precs))


@case
def surface_operator_like_blender():
    """Surface to Mesh: its poll holds on its own result (the redo panel,
    F9), a redo with a new tolerance re-runs it; the default tolerance is
    relative to the size; a vertex budget refuses, with the count, what
    would be too big; far-from-origin points are bounded by float32."""
    fresh_scene()
    bpy.ops.surface.primitive_nurbs_surface_sphere_add(radius=1.0)
    ob = bpy.context.active_object
    select_only(ob)
    bpy.ops.ed.undo_push(message="before")
    r1 = bpy.ops.object.conic_surface_to_mesh(tolerance=1e-2)
    mesh1 = bpy.context.active_object
    n1 = len(mesh1.data.vertices)
    poll_after = bpy.ops.object.conic_surface_to_mesh.poll()
    # the redo panel's re-run: undo to the state before, run again with the
    # new value (what ED_undo_operator_repeat does)
    bpy.ops.ed.undo_push(message="Surface to Mesh (Adaptive)")
    bpy.ops.ed.undo()
    r2 = bpy.ops.object.conic_surface_to_mesh(tolerance=1e-3)
    n2 = len(bpy.context.active_object.data.vertices)
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    report("surface_redo_poll_and_rerun", r1 == r2 == {"FINISHED"} and poll_after and
           n2 > n1 and len(meshes) == 1, "%r %r poll %r %d -> %d, %d meshes" %
           (r1, r2, poll_after, n1, n2, len(meshes)))
    # default (Fidelity 1e-3 of the size): the same count at radius 1 and 100
    counts = []
    for radius in (1.0, 100.0):
        fresh_scene()
        bpy.ops.surface.primitive_nurbs_surface_sphere_add(radius=radius)
        select_only(bpy.context.active_object)
        r = bpy.ops.object.conic_surface_to_mesh()
        counts.append((r, len(bpy.context.active_object.data.vertices) if r == {"FINISHED"}
                       else 0))
    report("surface_default_relative", counts[0] == counts[1] and counts[0][0] == {"FINISHED"} and
           0 < counts[0][1] < 20000, repr(counts))
    # a patch point at x = 1e6: the default finishes; an absolute 1e-3 is
    # raised to float32's floor there and refused by the budget, with the count
    for tol, want in ((0.0, {"FINISHED"}), (1e-3, {"CANCELLED"})):
        fresh_scene()
        bpy.ops.surface.primitive_nurbs_surface_surface_add()
        sf = bpy.context.active_object
        sf.data.splines[0].points[5].co = (1e6, 0.0, 0.0, 1.0)
        select_only(sf)
        n_obj = len(bpy.data.objects)
        r = bpy.ops.object.conic_surface_to_mesh(tolerance=tol, max_vertices=20000)
        reps = last_reports()
        ok = r == want
        if want == {"CANCELLED"}:
            ok = ok and len(bpy.data.objects) == n_obj and \
                any("Vertex Budget of 20000" in m and "(about " in m for _, m in reps)
        else:
            ok = ok and len(bpy.context.active_object.data.vertices) <= 20000
        report("surface_far_point_%s" % ("default" if tol == 0.0 else "absolute"), ok,
               "%r %r" % (r, reps))


@case
def surface_grid_where_it_sits():
    """Surface to Mesh plots the net moved to the origin and moves the grid
    back: Blender's sphere and the same sphere 8192 along x (exact in
    float32 and double) give the same grid, shifted, and the far one does
    not take longer (libconica's certified bound alone made 11 808 vertices
    in 21 s of it at x = 1e4 against 4 988 in 0.2 s here)."""
    ops = ops_mod()
    fresh_scene()
    bpy.ops.surface.primitive_nurbs_surface_sphere_add()
    sp = bpy.context.active_object.data.splines[0]
    ctrl, nu, nv, du, dv, ku, kv, w, _cu, _cv = ops.surface_patch(sp)
    far = array.array("d", (c + (8192.0 if k % 3 == 0 else 0.0) for k, c in enumerate(ctrl)))
    tol = 2e-3
    t0 = time.process_time()
    g0, gu0, gv0 = ops.surface_grid(ctrl, nu, nv, du, dv, ku, kv, w, tol, 10 ** 6)
    t1 = time.process_time()
    g1, gu1, gv1 = ops.surface_grid(far, nu, nv, du, dv, ku, kv, w, tol, 10 ** 6)
    t2 = time.process_time()
    moved = max((abs(b - a - (8192.0 if k % 3 == 0 else 0.0))
                 for k, (a, b) in enumerate(zip(g0, g1))), default=math.inf)
    report("surface_grid_where_it_sits", (gu0, gv0) == (gu1, gv1) and moved < 1e-9,
           "%d x %d at the origin, %d x %d at x = 8192, points moved by up to %.3g "
           "(CPU %.3f s, %.3f s)" % (gu0, gv0, gu1, gv1, moved, t1 - t0, t2 - t1))


def _three_circles(name):
    ob = new_curve(name)
    for k in range(3):
        add_poly(ob.data, [(3 * k + math.cos(2 * math.pi * i / 12),
                            math.sin(2 * math.pi * i / 12), 0.0) for i in range(12)], True)
    select_only(ob)
    return ob


@case
def escape_cancels_unchanged():
    """Esc between chunks (job.py): headless Blender has no events, so the
    operators' own cancel path is driven by job.simulated_escape, which
    stops a run after n chunks exactly as Esc does. The scene is left as it
    was (no spline, point, object or mesh changes), the run is CANCELLED
    (no undo step) and says so; the same run without it finishes."""
    jobmod = importlib.import_module(conica_pkg().__name__ + ".job")
    results = []
    try:
        for edit in (False, True):
            fresh_scene()
            ob = _three_circles("esc")
            if edit:
                bpy.ops.object.mode_set(mode="EDIT")
                bpy.ops.curve.select_all(action="SELECT")
            for n in (1, 3):
                before = [full_snapshot(sp) for sp in ob.data.splines]
                jobmod.simulated_escape = n
                r = bpy.ops.curve.conic_subdivide(levels=4)
                jobmod.simulated_escape = None
                after = [full_snapshot(sp) for sp in ob.data.splines]
                msg = [m for _, m in last_reports()]
                ok = r == {"CANCELLED"} and after == before and \
                    msg == ["Conic Subdivide: cancelled after %d of 3 splines; nothing changed"
                            % n]
                results.append(("curve edit=%s n=%d" % (edit, n), ok, r, msg))
            r = bpy.ops.curve.conic_subdivide(levels=4)
            results.append(("curve edit=%s to the end" % edit, r == {"FINISHED"} and
                            [len(sp.points) for sp in ob.data.splines] == [192] * 3, r,
                            [len(sp.points) for sp in ob.data.splines]))
            if edit:
                bpy.ops.object.mode_set(mode="OBJECT")
        fresh_scene()
        for k in range(2):
            bpy.ops.surface.primitive_nurbs_surface_sphere_add(location=(3 * k, 0, 0))
        for o in bpy.data.objects:
            o.select_set(True)
        names = sorted(o.name for o in bpy.data.objects)
        meshes = len(bpy.data.meshes)
        jobmod.simulated_escape = 1
        r = bpy.ops.object.conic_surface_to_mesh(tolerance=1e-2)
        jobmod.simulated_escape = None
        results.append(("surface", r == {"CANCELLED"} and
                        sorted(o.name for o in bpy.data.objects) == names and
                        len(bpy.data.meshes) == meshes, r, last_reports()))
        r = bpy.ops.object.conic_surface_to_mesh(tolerance=1e-2)
        results.append(("surface to the end", r == {"FINISHED"} and
                        len(bpy.data.objects) == 4, r, last_reports()))
        # invoke() without a window (headless, or a script's INVOKE_DEFAULT)
        # runs to the end at once
        fresh_scene()
        _three_circles("inv")
        r = bpy.ops.curve.conic_subdivide("INVOKE_DEFAULT", levels=8)
        results.append(("invoke without a window", r == {"FINISHED"}, r, last_reports()))
    finally:
        jobmod.simulated_escape = None
    for name, ok, r, why in results:
        report("escape_cancels_unchanged: " + name, ok, "%r %r" % (r, why))


class _FakeWM:
    """The window manager calls a modal run makes, recorded."""

    def __init__(self):
        self.calls = []

    def __getattr__(self, name):
        def call(*args, **kw):
            self.calls.append(name)
            return "timer" if name == "event_timer_add" else None
        return call


class _FakeEvent:
    def __init__(self, kind):
        self.type = kind


@case
def modal_run_escape_and_finish():
    """job.ModalRun's invoke/modal on a stand-in operator (Blender-free:
    a window manager and events of its own, since headless Blender sends
    none): big work starts a modal run with progress and a timer; timer
    events process chunks; Esc stops it with the writes never made,
    progress ended, the timer removed; without Esc the writes come after
    the last chunk."""
    jobmod = importlib.import_module(conica_pkg().__name__ + ".job")

    class Stand(jobmod.ModalRun):
        bl_label = "Stand"

        def __init__(self, n):
            self.n, self.made, self.finished, self.reports = 0, n, False, []

        def _start(self, context):
            def chunks():
                for _ in range(self.made):
                    time.sleep(0.02)
                    self.n += 1
                    yield
            return jobmod.Job(chunks(), self.made), jobmod.LONG_WORK

        def _finish(self, context):
            self.finished = True
            return {"FINISHED"}

        def _report(self, level, message):
            self.reports.append((level, message))

    class Ctx:
        def __init__(self):
            self.window = object()
            self.window_manager = _FakeWM()

    ctx, op = Ctx(), Stand(20)
    r0 = op.invoke(ctx, None)
    r1 = op.modal(ctx, _FakeEvent("TIMER"))
    r2 = op.modal(ctx, _FakeEvent("MOUSEMOVE"))
    seen = op.n
    r3 = op.modal(ctx, _FakeEvent("ESC"))
    calls = ctx.window_manager.calls
    report("modal_run_escape", r0 == r1 == r2 == {"RUNNING_MODAL"} and r3 == {"CANCELLED"} and
           0 < seen < 20 and op.n == seen and not op.finished and
           calls[:3] == ["progress_begin", "event_timer_add", "modal_handler_add"] and
           "event_timer_remove" in calls and calls[-1] == "progress_end" and
           op.reports == [("INFO", "Stand: cancelled after %d of 20 splines; nothing changed"
                           % seen)], "%r %r %d %r %r" % ((r0, r1, r2, r3), calls, seen,
                                                         op.finished, op.reports))
    ctx, op = Ctx(), Stand(5)
    rs = [op.invoke(ctx, None)]
    while rs[-1] == {"RUNNING_MODAL"} and len(rs) < 50:
        rs.append(op.modal(ctx, _FakeEvent("TIMER")))
    report("modal_run_finish", rs[-1] == {"FINISHED"} and op.finished and op.n == 5 and
           ctx.window_manager.calls[-1] == "progress_end", "%r %d" % (rs, op.n))
    # a small run does not go modal: invoke() does it all
    ctx, op = Ctx(), Stand(3)
    op._start = lambda context: (jobmod.Job(iter([None] * 3), 3), 10)
    r = op.invoke(ctx, None)
    report("modal_run_small_at_once", r == {"FINISHED"} and op.finished and
           not ctx.window_manager.calls, "%r %r" % (r, ctx.window_manager.calls))


@case
def save_and_reload():
    fresh_scene()
    ob = new_curve("saved")
    circle_bezier(ob.data)
    select_only(ob)
    bpy.ops.curve.conic_subdivide(levels=2)
    snap = curve_snapshot(ob.data)
    path = os.path.join(TMP, "saved.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    ob2 = bpy.data.objects.get("saved")
    report("save_reload", ob2 is not None and curve_snapshot(ob2.data) == snap)
    # the add-on still works after loading a file
    select_only(ob2)
    r = bpy.ops.curve.conic_subdivide(levels=1)
    report("works_after_reload", r == {"FINISHED"} and len(ob2.data.splines[0].points) == 32,
           str(len(ob2.data.splines[0].points)))


failed = [n for n, ok in RESULTS if not ok]
print("SUMMARY %d passed, %d failed" % (len(RESULTS) - len(failed), len(failed)))
shutil.rmtree(TMP, ignore_errors=True)
sys.exit(1 if failed else 0)
