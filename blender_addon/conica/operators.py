# SPDX-License-Identifier: GPL-3.0-or-later
# Operators of the Conica add-on: curve.conic_subdivide and
# curve.adaptive_to_poly. Python only moves Blender's data in and out
# (foreach_get/foreach_set on flat arrays); the geometry runs in _conica,
# which hands every spline to libcore's curve front end (conica/path.h):
# Bezier and NURBS splines are drawn curves, the ground truth the result
# stays within the fidelity tolerance of; POLY splines are points to
# interpolate. Corners, tangents at joins and straight pieces are its rules.
#
# Both operators first compute every spline's result and only then modify
# the scene, so a failure leaves the scene unchanged; a spline that cannot
# be processed (degenerate, NaN, non-planar) is reported and kept as it is.
# A POLY spline's w is ignored (Blender's mesh-to-curve conversion writes
# 0 there); linked and override data is never written (editable.py);
# hidden points of POLY splines stay as they are (hidden.py); a run that
# changes nothing reports so and is CANCELLED (no undo step).
#
# Edit Mode: for a curve object in Edit Mode, Curve.splines is Blender's
# edit-mode list (RNA reads BKE_curve_nurbs_get(), which returns
# editnurb->nurbs then), and splines.new()/remove() and points.add() work on
# it. The operators read and write that list directly, as Blender's own
# edit-mode operators do, instead of leaving Edit Mode and coming back
# (which cost more than Blender's whole Subdivide, see the README); the
# edit-mode undo step pushed after the operator stores the new list.
import array
import itertools
import math
import re
import time

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty

from . import _conica, editable, hidden, job

# A 3D spline is processed in its best-fit plane when its points lie within
# PLANE_TOL of its size from that plane (issue 8). Blender stores
# coordinates as float32, which alone moves a point up to sqrt(3) * 2^-24
# of its largest coordinate off any plane: that much is allowed on top, or
# a planar circle far from the origin would count as non-planar.
PLANE_TOL = 1e-6
FLOAT32_SLACK = 2.0 ** -22

# Output budget per spline (points), far above interactive use.
MAX_POINTS = 1 << 22

# Largest coordinate magnitude the operators accept. Blender stores
# coordinates as float32, whose finite range ends at 3.4e38, and a
# coordinate set to inf from Python is stored as that finite 3.4e38; a
# spline that far out has no geometry worth subdividing (the squared
# distances the fit needs overflow float32's range long before), so
# anything beyond 1e30 is refused like NaN, naming the point.
MAX_COORD = 1e30

# Curve to Polyline writes float32 points: each is rounded by up to half
# the float32 spacing in each coordinate, sqrt(3)/2 spacing in all, on top
# of the plotter's distance. The smallest tolerance the stored polyline can
# honour is therefore FLOAT32_TOL_SPACINGS spacings of float32 at the
# spline's largest coordinate (the curve lies in the hull of its control
# points, so no point of it is larger); a request below that is clamped to
# it with a warning, and the plotter runs with the rounding subtracted.
FLOAT32_TOL_SPACINGS = 2.0
FLOAT32_ROUNDING = math.sqrt(3.0) / 2.0

# Messages number splines and points from 0, as Blender's Python tooltips
# and console do (splines[0].points[3] is "spline 0, point 3").

# Timings of the last run (seconds), read by the benchmark.
last_timing = {}

# Reports of the last run, [(level, message)], in the order they were made:
# what the user sees in the status bar and the Info editor (the tests read
# them here, since Python cannot read an operator's reports back).
last_reports = []


_ONE_F32 = array.array("f", [1.0]).tobytes()


def _zeros(n, typecode="f"):
    return array.array(typecode, bytes((4 if typecode == "f" else 8) * n))


class SplineData:
    """A spline's points read with foreach_get (float32, as Blender stores)."""

    __slots__ = ("type", "n", "co", "weights", "hl", "hr", "radius", "tilt",
                 "selected", "hidden", "default_attrs", "cyclic", "_max_abs")

    def __init__(self, sp):
        self.type = sp.type
        self.cyclic = sp.use_cyclic_u
        if sp.type == "BEZIER":
            pts = sp.bezier_points
            n = len(pts)
            self.co = _zeros(3 * n)
            self.hl = _zeros(3 * n)
            self.hr = _zeros(3 * n)
            pts.foreach_get("co", self.co)
            pts.foreach_get("handle_left", self.hl)
            pts.foreach_get("handle_right", self.hr)
            self.weights = None
            # a Bezier point counts as selected when its anchor or either
            # handle is, as for Blender's own operators
            sel = array.array("b", bytes(n))
            for key in ("select_control_point", "select_left_handle", "select_right_handle"):
                pts.foreach_get(key, sel)
                if any(sel):
                    break
        else:
            pts = sp.points
            n = len(pts)
            co4 = _zeros(4 * n)
            pts.foreach_get("co", co4)
            self.co = _zeros(3 * n)
            self.co[0::3] = co4[0::4]
            self.co[1::3] = co4[1::4]
            self.co[2::3] = co4[2::4]
            # A POLY spline is not rational: Blender ignores its w (mesh to
            # curve conversion writes 0.0 there), so the operators do too;
            # only a NURBS spline's weights are read and checked.
            self.weights = co4[3::4] if sp.type == "NURBS" else None
            self.hl = self.hr = None
            sel = array.array("b", bytes(n))
            pts.foreach_get("select", sel)
        hide = array.array("b", bytes(n))
        pts.foreach_get("hide", hide)
        self.hidden = hide if any(hide) else None
        self.n = n
        self.radius = _zeros(n)
        self.tilt = _zeros(n)
        pts.foreach_get("radius", self.radius)
        pts.foreach_get("tilt", self.tilt)
        # radius 1 and tilt 0 everywhere, Blender's values for new points:
        # the result of a POLY or BEZIER spline then has them everywhere too
        # (_conica copies a constant column exactly; a NURBS's attributes are
        # spline functions, evaluated with rounding), compared as bytes
        self.default_attrs = (sp.type != "NURBS" and self.radius.tobytes() == _ONE_F32 * n and
                              self.tilt.tobytes() == bytes(4 * n))
        self.selected = any(sel)
        self._max_abs = None

    def max_abs(self):
        """Largest |coordinate| of the points and handles (check() finds it
        on its way; of the values before the first non-finite one)."""
        if self._max_abs is None:
            self._max_abs = max((_conica.scan(a, math.inf)[1]
                                 for a in (self.co, self.hl, self.hr) if a), default=0.0)
        return self._max_abs

    def check(self):
        """Refuse NaN, infinite and huge (> MAX_COORD) coordinates, non-positive
        weights and non-finite radius or tilt, naming the point. One C pass
        per array (_conica.scan), which also gives the largest coordinate
        magnitude for max_abs() and abs_tol(). Raises _conica.NonFiniteError."""
        self._max_abs = 0.0
        for arr, what in ((self.co, ""), (self.hl, "left handle "), (self.hr, "right handle ")):
            if not arr:
                continue
            i, m = _conica.scan(arr, MAX_COORD)
            self._max_abs = max(self._max_abs, m)
            if i < 0:
                continue
            v, axis = arr[i], "xyz"[i % 3]
            if not math.isfinite(v):
                raise _conica.NonFiniteError(
                    "point %d has a non-finite %scoordinate (%s = %r)"
                    % (i // 3, what, axis, v))
            raise _conica.NonFiniteError(
                "point %d has a %scoordinate beyond \u00b1%g (%s = %.3g; Blender "
                "stores an infinite coordinate as 3.4e+38)"
                % (i // 3, what, MAX_COORD, axis, v))
        if self.weights:
            w = self.weights
            i = _conica.scan(w, math.inf, True)[0]
            if i >= 0:
                raise _conica.NonFiniteError("point %d has weight %r; weights must be "
                                             "positive numbers" % (i, w[i]))
        for arr, what in ((self.radius, "radius"), (self.tilt, "tilt")):
            i = _conica.scan(arr, math.inf)[0]
            if i >= 0:
                raise _conica.NonFiniteError("point %d has a non-finite %s (%r)"
                                             % (i, what, arr[i]))

    def attrs(self):
        a = _zeros(2 * self.n)
        a[0::2] = self.radius
        a[1::2] = self.tilt
        return a

    def abs_tol(self):
        """Float32 slack of the plane test at the largest coordinate."""
        return FLOAT32_SLACK * self.max_abs()


def float32_spacing(m):
    """Spacing of float32 values at magnitude m (its ulp); the smallest
    normal spacing for m = 0."""
    if m <= 0.0:
        return 2.0 ** -149
    return math.ldexp(1.0, math.frexp(m)[1] - 24)


# ---------------------------------------------------------------- NURBS

def nurbs_knots(pnts, order, cyclic, endpoint, bezier):
    """The knot vector Blender 3.4+ uses for a NURBS spline (BKE curve.cc,
    calcknots): pnts + order (+ order - 1 when cyclic) knots; for a cyclic
    spline the control points are then extended by the first order - 1."""
    repeat_inner = order - 1 if bezier else 1
    if endpoint:
        head = order - (1 if cyclic else 0)
    else:
        head = min(2, repeat_inner) if bezier else 1
    tail = 2 * order - 1 if cyclic else (order if endpoint else 0)
    count = pnts + order + (order - 1 if cyclic else 0)
    knots = [0.0] * count
    r = head
    current = 0.0
    offset = 1 if (endpoint and cyclic) else 0
    if offset:
        knots[0] = current
        current += 1.0
    for i in range(offset, count - tail):
        knots[i] = current
        r -= 1
        if r == 0:
            current += 1.0
            r = repeat_inner
    tail_index = count - tail
    for i in range(tail):
        knots[tail_index + i] = current + (knots[i] - knots[0])
    return knots


def nurbs_spline(sp, data):
    """(degree, knots, ctrl, weights, attrs) of a NURBS spline as Blender
    evaluates it (order clamped to the point count; cyclic splines wrapped)."""
    n = data.n
    order = max(2, min(sp.order_u, n))
    cyclic = data.cyclic
    knots = nurbs_knots(n, order, cyclic, sp.use_endpoint_u, sp.use_bezier_u)
    ctrl, w, attrs = data.co, data.weights, data.attrs()
    if cyclic:
        extra = order - 1
        ctrl = ctrl + ctrl[:3 * extra]
        w = w + w[:extra]
        attrs = attrs + attrs[:2 * extra]
    return order - 1, knots, ctrl, w, attrs


def spline_curve(sp, data, want_attrs=True, **kw):
    """Run one spline through _conica.curve (libcore's curve front end):
    a BEZIER spline as its cubic segments, a NURBS spline with the knots
    and weights Blender evaluates it with, a POLY spline as points. kw: the
    mode and its settings, handles, stride. want_attrs=False leaves radius
    and tilt out (the result's attrs are then None). Raises _conica.ConicaError."""
    common = dict(dim=3, closed=data.cyclic, plane_tol=PLANE_TOL, abs_tol=data.abs_tol(),
                  nattrs=2 if want_attrs else 0, typecode="f", max_points=MAX_POINTS)
    common.update(kw)
    if data.type == "POLY" and data.hidden is not None:
        # radius, tilt and the markers that find the input points again
        a = _zeros((2 + hidden.NCOLS) * data.n)
        a[0::4], a[1::4] = data.radius, data.tilt
        marks = hidden.index_columns(data.n)
        a[2::4], a[3::4] = array.array("f", marks[0::2]), array.array("f", marks[1::2])
        common["nattrs"] = 2 + hidden.NCOLS
        return _conica.curve("POLY", data.co, attrs=a, **common)
    if data.type == "BEZIER":
        return _conica.curve("BEZIER", data.co, data.hl, data.hr,
                             attrs=data.attrs() if want_attrs else None, **common)
    if data.type == "NURBS":
        degree, knots, ctrl, w, attrs = nurbs_spline(sp, data)
        return _conica.curve("NURBS", ctrl, degree=degree, knots=knots, weights=w,
                             attrs=attrs if want_attrs else None, **common)
    return _conica.curve("POLY", data.co, attrs=data.attrs() if want_attrs else None, **common)


# ---------------------------------------------------------------- helpers

def curve_objects(context):
    """(objects, edit): the curve objects to work on, each data-block once."""
    edit = context.mode == "EDIT_CURVE"
    if edit:
        objs = getattr(context, "objects_in_mode", None)
        if objs is None:
            objs = [o for o in context.view_layer.objects if o.mode == "EDIT"]
        objs = [o for o in objs if o.type == "CURVE"]
    else:
        objs = [o for o in context.selected_objects if o.type == "CURVE"]
        ao = context.active_object
        if not objs and ao is not None and ao.type == "CURVE" and ao.select_get():
            objs = [ao]
    seen, out = set(), []
    for o in objs:
        if o.data.as_pointer() not in seen:
            seen.add(o.data.as_pointer())
            out.append(o)
    return out, edit


def poll_curves(cls, context):
    """A curve object to work on whose data may be written (editable.py);
    else False, with Blender's message naming the library."""
    ao = context.active_object
    if context.mode == "EDIT_CURVE":
        return ao is not None and ao.type == "CURVE"
    objs = [o for o in context.selected_objects if o.type == "CURVE"]
    if ao is not None and ao.type == "CURVE" and ao not in objs:
        objs.append(ao)
    return bool(objs) and editable.poll_editable(cls, objs)


class _Result:
    __slots__ = ("index", "kind", "co", "attrs", "hl", "hr", "cyclic", "material",
                 "smooth", "resolution", "selected", "hidden", "hide", "default_attrs",
                 "t_core")

    def __init__(self):
        self.t_core = 0.0  # seconds inside libcore (measured in C)
        self.hide = None   # with hidden points: the result's hide flags


# Per-point attributes that copy_spline() carries over exactly.
_POINT_KEYS = (("co", 4, "f"), ("radius", 1, "f"), ("tilt", 1, "f"),
               ("weight_softbody", 1, "f"), ("select", 1, "b"), ("hide", 1, "b"))
_BEZIER_KEYS = (("co", 3, "f"), ("handle_left", 3, "f"), ("handle_right", 3, "f"),
                ("radius", 1, "f"), ("tilt", 1, "f"), ("weight_softbody", 1, "f"),
                ("select_control_point", 1, "b"), ("select_left_handle", 1, "b"),
                ("select_right_handle", 1, "b"), ("hide", 1, "b"))
# Spline settings copy_spline() carries over. They are set after the points
# are added (Blender clamps the order to the point count) and before the
# point data is written: setting some of them recomputes automatic Bezier
# handles (use_cyclic_u does), which would move the copied handles.
_SPLINE_KEYS = ("use_cyclic_u", "use_cyclic_v", "resolution_u", "resolution_v",
                "use_smooth", "hide", "material_index", "tilt_interpolation",
                "radius_interpolation", "use_endpoint_u", "use_endpoint_v",
                "use_bezier_u", "use_bezier_v", "order_u", "order_v")


def copy_spline(cu, src):
    """Append an exact copy of spline src (of any curve) to cu.splines."""
    sp = cu.splines.new(src.type)
    if src.type == "BEZIER":
        pts, dst, keys = src.bezier_points, sp.bezier_points, _BEZIER_KEYS
    else:
        pts, dst, keys = src.points, sp.points, _POINT_KEYS
    n = len(pts)
    if n > 1:
        dst.add(n - 1)
    for key in _SPLINE_KEYS:
        setattr(sp, key, getattr(src, key))
    if src.type == "BEZIER":
        # foreach_get/foreach_set cannot move enum values (Blender 3.4 reads
        # nothing and writes nothing): handle types one by one. New points
        # are FREE (Blender zero-fills them, HD_FREE == 0); every set of
        # another type recomputes handles, which the raw writes below undo.
        for a, b in zip(pts, dst):
            for key in ("handle_left_type", "handle_right_type"):
                value = getattr(a, key)
                if value != "FREE":
                    setattr(b, key, value)
    for key, width, tc in keys:
        buf = array.array(tc, bytes(array.array(tc).itemsize * width * n))
        pts.foreach_get(key, buf)
        dst.foreach_set(key, buf)
    return sp


def _fill_poly(sp, r, select):
    n = len(r.co) // 4
    have = len(sp.points)
    if n > have:
        sp.points.add(n - have)
    sp.points.foreach_set("co", r.co)
    # Points refilled in place keep their radius, tilt and hide; new points
    # come with radius 1, tilt 0, shown: only what differs is written.
    if not r.default_attrs:
        sp.points.foreach_set("radius", r.attrs[0::2])
        sp.points.foreach_set("tilt", r.attrs[1::2])
    if r.hidden is not None:
        # the hidden input points, still hidden (hidden.py); the rest shown
        sp.points.foreach_set("hide", r.hide)
    if select:
        sel = array.array("b", [r.selected]) * n
        if r.hidden is not None and r.selected:
            sel = array.array("b", [1 - h for h in r.hide])
        sp.points.foreach_set("select", sel)


def _fill_bezier(sp, r, select):
    """Fill a NEW Bezier spline: its points are FREE (Blender zero-fills
    them, HD_FREE == 0), so Blender keeps our handles as given."""
    n = len(r.co) // 3
    bp = sp.bezier_points
    bp.add(n - len(bp))
    bp.foreach_set("co", r.co)
    bp.foreach_set("handle_left", r.hl)
    bp.foreach_set("handle_right", r.hr)
    if not r.default_attrs:  # new points have radius 1, tilt 0 (see _fill_poly)
        bp.foreach_set("radius", r.attrs[0::2])
        bp.foreach_set("tilt", r.attrs[1::2])
    if r.hidden is not None:
        bp.foreach_set("hide", r.hide)
    if select:
        for key in ("select_control_point", "select_left_handle", "select_right_handle"):
            bp.foreach_set(key, array.array("b", [r.selected]) * n)


def _result_count(r):
    return len(r.co) // (4 if r.kind == "POLY" else 3)


def _fits_in_place(src, r):
    """A POLY result can refill a POLY spline in place when the points only
    grow: splines cannot change type or drop points from Python without
    being rebuilt. Bezier results always go to a new spline, whose points
    are all FREE: an existing point's handle type (AUTO, ALIGNED, ...) can
    only be changed one point at a time, each change recomputing handles."""
    return r.kind == "POLY" and src.type == "POLY" and _result_count(r) >= len(src.points)


def _new_spline(cu, src, r, select):
    sp = cu.splines.new(r.kind)
    sp.use_cyclic_u = r.cyclic  # before the points: see _SPLINE_KEYS
    for key in ("material_index", "use_smooth", "resolution_u", "tilt_interpolation",
                "radius_interpolation"):
        setattr(sp, key, getattr(src, key))
    if r.kind == "POLY":
        _fill_poly(sp, r, select)
    else:
        _fill_bezier(sp, r, select)
    return sp


def write_results(cu, results, select, source=None):
    """Write the results into cu, keeping the order of the splines.

    POLY results for a POLY spline that only gains points refill it in
    place (cheap). Splines can only be appended, so
    from the first result that cannot be written in place on, that spline
    and every following one are appended anew, in order (a result, or an
    exact copy of an untouched spline), and the old ones removed.

    With source (a list of splines; cu then holds none), every spline is
    appended: a result or a copy of the source spline."""
    by_index = {r.index: r for r in results}
    if source is not None:
        for i, src in enumerate(source):
            r = by_index.get(i)
            if r is None:
                copy_spline(cu, src)
            else:
                _new_spline(cu, src, r, select)
        return
    old = list(cu.splines)
    active = cu.splines.active
    active_i = next((i for i, sp in enumerate(old) if active is not None and
                     sp.as_pointer() == active.as_pointer()), -1)
    active_n = (len(active.bezier_points) if active.type == "BEZIER" else
                len(active.points)) if active_i >= 0 else 0
    first = len(old)
    for i in sorted(by_index):
        if not _fits_in_place(old[i], by_index[i]):
            first = i
            break
    for i in sorted(by_index):
        if i >= first:
            break
        r = by_index[i]
        _fill_poly(old[i], r, select)
    for i in range(first, len(old)):
        r = by_index.get(i)
        if r is None:
            copy_spline(cu, old[i])
        else:
            _new_spline(cu, old[i], r, select)
    for sp in old[first:]:
        cu.splines.remove(sp)
    # Blender keeps the active spline and point as indices. The spline keeps
    # its index; when it lost points the active point index may now be past
    # its end (Blender reads it unchecked), so the active spline is unset.
    if active_i >= 0 and active_i in by_index and \
            _result_count(by_index[active_i]) < active_n:
        cu.splines.active = None


def _new_object_copy(context, ob, edit):
    """A copy of ob with a copy of its curve. In Edit Mode the data-block
    copy holds the Object Mode splines, not the edited ones: the caller
    then rebuilds the splines from the edit-mode list (write_results with
    source), so the copy gets no splines here."""
    new = ob.copy()
    new.data = ob.data.copy()
    new.name = ob.name + ".conic"
    if edit:
        new.data.splines.clear()
    for coll in ob.users_collection:
        coll.objects.link(new)
    return new


OUTPUT_ITEMS = [
    ("REPLACE", "Replace (Poly)", "Replace the splines by POLY splines through the new points"),
    ("BEZIER", "Replace (Bézier)",
     "Replace the splines by Bézier splines with handles along the conic tangents"),
    ("NEW_OBJECT", "New Object", "Put the result in a new object; the original stays untouched"),
]


def same_points(co4, data):
    """True when a POLY result (x, y, z, 1 per point, float32) holds exactly
    the spline's own points: the run would change nothing."""
    if len(co4) != 4 * data.n:
        return False
    return co4[0::4] == data.co[0::3] and co4[1::4] == data.co[1::3] and \
        co4[2::4] == data.co[2::3]


# libcore's messages speak of paths, subpaths and segments; Blender users
# see splines, points and levels. Each pattern: (regular expression, the
# sentence in Blender's words; groups of the match and op are its fields).
_LIBRARY_WORDS = (
    (r"subpath \d+: the result would exceed the limit of (\d+) points",
     lambda m, op: "the result would have more than %s points; use fewer Levels (now %d)"
     % (m.group(1), getattr(op, "levels", 0))),
    (r"(control point|weight) \d+ of a segment is not (finite|a positive number)",
     lambda m, op: "its points or weights are too far apart in size to evaluate in double "
     "precision (Blender draws it, but its pieces overflow); bring the weights closer "
     "to 1"),
)


def blender_words(exc, op):
    """The message of a ConicaError in Blender's terms (spline, point,
    levels), for the reports."""
    msg = str(exc)
    for pattern, say in _LIBRARY_WORDS:
        m = re.search(pattern, msg)
        if m:
            return say(m, op)
    return msg


class _Run:
    """What a curve operator's run has computed so far (job.py's chunks
    fill it; _finish writes it)."""

    def __init__(self, edit, t_start):
        self.edit, self.t_start = edit, t_start
        self.plans = []  # (object, [_Result])
        self.problems = []
        self.skipped = self.unchanged = 0
        self.t_lib = self.t_core = self.t_read = 0.0


class _CurveOperator(job.ModalRun):
    """Shared driver: collect, compute everything (in chunks, job.py), then
    write."""

    def nothing_message(self, edit, skipped, unchanged):
        if unchanged:
            return ("%s: nothing to change; the %sspline%s %s straight between corners "
                    "(turn off Keep Corners or raise Corner Angle to round them)"
                    % (self.bl_label, "selected " if edit else "", "" if unchanged == 1 else "s",
                       "is" if unchanged == 1 else "are"))
        if skipped:
            return "%s: nothing to do; the %sspline%s %s already Poly" % (
                self.bl_label, "selected " if edit else "", "" if skipped == 1 else "s",
                "is" if skipped == 1 else "are")
        return "%s: nothing to do; no %sspline to process" % (
            self.bl_label, "selected " if edit else "")

    @classmethod
    def poll(cls, context):
        return poll_curves(cls, context)

    def process(self, ob, sp, data):  # -> _Result or raises _conica.ConicaError
        raise NotImplementedError

    def wants(self, sp, data, edit):
        return (not edit) or data.selected

    def _report(self, level, message):
        self.report({level}, message)
        last_reports.append((level, message))

    def note(self, message):
        """A warning about the spline being processed that does not stop it."""
        self._notes.append("%s: %s" % (self._where, message))

    def work(self, n):  # -> estimated output points of a spline of n points
        raise NotImplementedError

    def _start(self, context):
        """The run's Job (job.py) and its estimated output points, or
        CANCELLED when no curve is selected."""
        last_reports.clear()
        self._notes = []
        self._where = ""
        objs, edit = curve_objects(context)
        if not objs:
            self._report("ERROR", "No curve object selected")
            return {"CANCELLED"}
        self._run = run = _Run(edit, time.perf_counter())
        splines = [sp for ob in objs for sp in ob.data.splines]
        work = sum(self.work(len(sp.points) + len(sp.bezier_points)) for sp in splines) \
            if len(splines) > 1 else 0
        return job.Job(self._chunks(objs, run), len(splines)), work

    def _chunks(self, objs, run):
        """Compute every spline's result into run (one yield per spline);
        the scene is not touched."""
        for ob in objs:
            results = []
            locked = editable.locked_reason(ob)
            if locked is not None:
                run.problems.append("%s: %s; left unchanged" % (ob.name, locked))
                yield from range(len(ob.data.splines))
                continue
            if ob.data.shape_keys is not None:
                # Points inserted between shape-keyed points would need every
                # key block to grow with them (Blender's own edit operators
                # track that internally; Python cannot): refuse, unchanged.
                run.problems.append("%s: has shape keys, which %s cannot carry over; "
                                    "left unchanged" % (ob.name, self.bl_label))
                yield from range(len(ob.data.splines))
                continue
            for i, sp in enumerate(ob.data.splines):
                r = self._spline(ob, i, sp, run)
                if r is not None:
                    results.append(r)
                yield
            if results:
                run.plans.append((ob, results))

    def _spline(self, ob, i, sp, run):
        """One spline's _Result, or None (not wanted, skipped, unchanged or
        refused: counted in run)."""
        edit = run.edit
        t0 = time.perf_counter()
        data = SplineData(sp)
        run.t_read += time.perf_counter() - t0
        if not self.wants(sp, data, edit):
            return None
        self._where = "%s, spline %d" % (ob.name, i)
        try:
            data.check()
            if data.hidden is not None and (data.type != "POLY" or
                                            self.output == "BEZIER"):
                raise _conica.ConicaError(
                    "has hidden points, which %s leaves as they are only on "
                    "Poly splines with Poly output; reveal them (Alt H) to "
                    "process the spline" % self.bl_label)
            r = self.process(ob, sp, data)
        except _conica.ConicaError as exc:
            run.problems.append("%s, spline %d: %s" % (ob.name, i, blender_words(exc, self)))
            return None
        if r is None:
            run.skipped += 1
            return None
        if r[0].kind == "POLY" and data.type == "POLY" and same_points(r[0].co, data):
            run.unchanged += 1  # nothing to insert (straight between corners)
            return None
        run.t_lib += r[1]
        r = r[0]
        run.t_core += r.t_core
        r.index = i
        r.cyclic = data.cyclic
        r.material = sp.material_index
        r.smooth = sp.use_smooth
        r.resolution = sp.resolution_u
        r.selected = edit
        r.hidden = data.hidden
        r.default_attrs = data.default_attrs and r.attrs is None
        return r

    def _finish(self, context):
        """Write every result (the scene changes here only) and report."""
        run = self._run
        edit, plans, problems = run.edit, run.plans, run.problems
        skipped, unchanged = run.skipped, run.unchanged
        t_write = time.perf_counter()
        done = 0
        for ob, results in plans:
            if self.output == "NEW_OBJECT":
                target = _new_object_copy(context, ob, edit)
                write_results(target.data, results, edit,
                              source=list(ob.data.splines) if edit else None)
            else:
                target = ob
                write_results(target.data, results, edit)
            target.data.update_tag()
            done += len(results)
        t_end = time.perf_counter()
        last_timing.clear()
        # read/write: bpy data transfer; extension: the _conica calls
        # (conversion + libcore); libcore: measured inside the C code.
        last_timing.update(total=t_end - run.t_start, read=run.t_read, extension=run.t_lib,
                           libcore=run.t_core, write=t_end - t_write, splines=done)
        for p in self._notes + problems:
            self._report("WARNING", p)
        if done == 0:
            # CANCELLED: no undo step for a run that changed nothing
            if not problems:
                self._report("INFO", self.nothing_message(edit, skipped, unchanged))
            return {"CANCELLED"}
        # A summary goes with the warnings, saying what was done besides; a
        # plain success is silent, as Blender's own Subdivide (the result is
        # in the viewport, and every report costs: bpy.ops prints it).
        if problems or self._notes:
            msg = "%s: %d spline%s" % (self.bl_label, done, "" if done == 1 else "s")
            if problems:
                msg += ", %d left unchanged (see the warnings)" % len(problems)
            self._report("INFO", msg)
        return {"FINISHED"}


FIDELITY_HELP = ("Largest distance of the result from the drawn curve, as a fraction of "
                 "the spline's size (the diagonal of its bounding box)")


def exact_value(layout, label, value, unit=""):
    """A row under a tolerance field with its value in %g form: the field
    shows at most 6 decimals (Blender's UI limit), which reads 1e-7 as 0."""
    row = layout.row()
    row.alignment = "RIGHT"
    row.label(text="%s = %.3g%s" % (label, value, unit))


class CURVE_OT_conic_subdivide(_CurveOperator, bpy.types.Operator):
    """Subdivide curves so that circles, ellipses and other conics stay exact"""
    # one line: Blender shows a docstring's line breaks in the tooltip
    bl_description = ("Subdivide curves so that circles, ellipses and other conics stay "
                      "exact (conic-preserving interpolatory subdivision), staying faithful "
                      "to the drawn Bézier and NURBS curves")
    bl_idname = "curve.conic_subdivide"
    bl_label = "Conic Subdivide"
    bl_options = {"REGISTER", "UNDO"}

    levels: IntProperty(
        name="Levels", description="Subdivision levels; each doubles the segments",
        default=3, min=1, max=8, options={"SKIP_SAVE"})
    keep_corners: BoolProperty(
        name="Keep Corners", default=True,
        description="Keep joins where the curve turns by more than the corner angle "
                    "(Bezier handles that kink, polygon vertices) as sharp corners")
    corner_angle: FloatProperty(
        name="Corner Angle", subtype="ANGLE", default=_conica.CORNER_ANGLE,
        min=math.radians(1.0), max=math.radians(179.0),
        description="Turning angle above which a join is a corner")
    fidelity: FloatProperty(
        name="Fidelity", default=_conica.REL_TOLERANCE, min=1e-6, max=0.1, precision=6,
        step=0.01, description=FIDELITY_HELP)
    output: EnumProperty(name="Output", items=OUTPUT_ITEMS, default="REPLACE")

    def work(self, n):
        return n << self.levels

    def process(self, ob, sp, data):
        kind = "BEZIER" if self.output == "BEZIER" else "POLY"
        t0 = time.perf_counter()
        res = spline_curve(
            sp, data, want_attrs=not data.default_attrs, mode="smooth", levels=self.levels,
            corner_angle=self.corner_angle if self.keep_corners else math.pi,
            fidelity=self.fidelity, handles=kind == "BEZIER",
            stride=4 if kind == "POLY" else 3)
        t_lib = time.perf_counter() - t0
        r = _Result()
        r.kind = kind
        r.t_core = res[3]["seconds"]
        r.co, r.attrs = res[0], res[2]
        r.hl, r.hr = (res[4], res[5]) if kind == "BEZIER" else (None, None)
        if data.hidden is not None:  # POLY output of a POLY spline (see _spline)
            kept = hidden.drop_hidden_segments(r.co, r.attrs, data.hidden, data.cyclic, 4)
            if kept is None:
                raise _conica.ConicaError("has hidden points whose places in the result "
                                          "could not be told; reveal them (Alt H)")
            r.co, r.attrs, r.hide = kept
        return r, t_lib

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "levels")
        row = layout.row(heading="Keep Corners")
        row.prop(self, "keep_corners", text="")
        sub = row.row()
        sub.active = self.keep_corners
        sub.prop(self, "corner_angle", text="")
        layout.prop(self, "fidelity")
        exact_value(layout, "Fidelity", self.fidelity, " of the spline's size")
        layout.prop(self, "output")


class CURVE_OT_adaptive_to_poly(_CurveOperator, bpy.types.Operator):
    """Convert Bézier and NURBS splines to Poly splines within a distance of the curve"""
    bl_description = ("Convert Bézier and NURBS splines to Poly splines that stay within a "
                      "distance of the curve, with as few points as the adaptive plotter "
                      "needs and a point at every Bézier anchor")
    bl_idname = "curve.adaptive_to_poly"
    bl_label = "Curve to Polyline (Adaptive)"
    bl_options = {"REGISTER", "UNDO"}

    tolerance: FloatProperty(
        name="Tolerance", subtype="DISTANCE", default=1e-3, min=1e-7, soft_max=1.0,
        precision=6, step=0.01,
        description="Largest distance between the polyline and the curve. Below what "
                    "float32 coordinates can hold at the spline's size (2 float32 "
                    "spacings at its largest coordinate) it is raised to that, with a "
                    "warning")
    output: EnumProperty(name="Output", items=[OUTPUT_ITEMS[0], OUTPUT_ITEMS[2]],
                         default="REPLACE")

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        layout.prop(self, "tolerance")
        exact_value(layout, "Tolerance", self.tolerance, " m")
        layout.prop(self, "output")

    def work(self, n):  # a few tens of points per segment at the default
        return 32 * n

    def process(self, ob, sp, data):
        if data.type == "POLY":
            return None  # already a polyline
        if data.n < 2:
            raise _conica.DegenerateError("a spline needs at least 2 points, has %d" % data.n)
        spacing = float32_spacing(data.max_abs())
        achievable = FLOAT32_TOL_SPACINGS * spacing
        tol = self.tolerance
        if tol < achievable:
            self.note("tolerance %.3g is below what float32 coordinates near %.3g can "
                      "hold; used the achievable tolerance %.3g" %
                      (tol, data.max_abs(), achievable))
            tol = achievable
        t0 = time.perf_counter()
        res = spline_curve(sp, data, want_attrs=not data.default_attrs, mode="flatten", stride=4,
                           tolerance=tol - FLOAT32_ROUNDING * spacing)
        t_lib = time.perf_counter() - t0
        r = _Result()
        r.kind = "POLY"
        r.t_core = res[3]["seconds"]
        r.co, r.attrs = res[0], res[2]
        r.hl = r.hr = None
        return r, t_lib


# ---------------------------------------------------------------- surfaces

def surface_patch(sp):
    """(ctrl, nu, nv, degree_u, degree_v, knots_u, knots_v, weights, cyclic_u,
    cyclic_v) of a NURBS surface spline as Blender evaluates it: the knot
    vectors of nurbs_knots() per direction (Blender builds both with the same
    rule from the order, Endpoint, Bezier and Cyclic settings of that
    direction), the control net wrapped by order - 1 rows and columns in a
    cyclic direction, in libcore's layout (index (i * nv + j), i along u).
    Blender stores the net with u running fastest (points[v * nu + u])."""
    pu, pv = sp.point_count_u, sp.point_count_v
    co4 = _zeros(4 * pu * pv)
    sp.points.foreach_get("co", co4)
    _check_net(co4)
    ou, ov = max(2, min(sp.order_u, pu)), max(2, min(sp.order_v, pv))
    cu, cv = sp.use_cyclic_u, sp.use_cyclic_v
    ku = nurbs_knots(pu, ou, cu, sp.use_endpoint_u, sp.use_bezier_u)
    kv = nurbs_knots(pv, ov, cv, sp.use_endpoint_v, sp.use_bezier_v)
    nu = pu + (ou - 1 if cu else 0)
    nv = pv + (ov - 1 if cv else 0)
    ctrl = _zeros(3 * nu * nv, "d")
    w = _zeros(nu * nv, "d")
    for i in range(nu):  # the control net: tens of points, not the output
        for j in range(nv):
            src = 4 * ((j % pv) * pu + (i % pu))
            dst = i * nv + j
            ctrl[3 * dst:3 * dst + 3] = array.array("d", co4[src:src + 3])
            w[dst] = co4[src + 3]
    return ctrl, nu, nv, ou - 1, ov - 1, ku, kv, w, cu, cv


def _check_net(co4):
    """Refuse NaN, huge (beyond MAX_COORD) coordinates and non-positive
    weights of a surface's control net (x, y, z, w per point), naming the
    point as Blender's Python numbers it (points[k], from 0)."""
    xyz = co4[0::4] + co4[1::4] + co4[2::4]
    w = co4[3::4]
    if math.isfinite(sum(xyz)) and max(xyz) <= MAX_COORD and -min(xyz) <= MAX_COORD and \
            math.isfinite(sum(w)) and min(w) > 0.0:
        return
    for k in range(len(w)):
        p = co4[4 * k:4 * k + 4]
        if not all(math.isfinite(c) and abs(c) <= MAX_COORD for c in p[:3]):
            raise _conica.NonFiniteError(
                "point %d has a coordinate that is not finite or beyond \u00b1%g (%s)"
                % (k, MAX_COORD, ", ".join("%.3g" % c for c in p[:3])))
        if not (math.isfinite(p[3]) and p[3] > 0.0):
            raise _conica.NonFiniteError("point %d has weight %r; weights must be positive "
                                         "numbers" % (k, p[3]))


def surface_grid(ctrl, nu, nv, du, dv, ku, kv, w, tol, budget):
    """(grid, gu, gv) of _conica.surface for a control net moved so that its
    bounding box's centre is the origin, the grid moved back: a translation
    changes no distance, and the plotter's cell bounds and rounding slack
    scale with the size of the coordinates, not of the surface."""
    centre = [(max(ctrl[k::3]) + min(ctrl[k::3])) / 2 for k in range(3)]
    moved = array.array("d", (c - centre[k % 3] for k, c in enumerate(ctrl)))
    grid, gu, gv, _info = _conica.surface(
        moved, nu=nu, nv=nv, degree_u=du, degree_v=dv, knots_u=ku,
        knots_v=kv, weights=w, tolerance=tol, max_points=budget)
    for k in range(3):  # back where it was (float adds in C, via map)
        grid[k::3] = array.array("d", map(centre[k].__add__, grid[k::3]))
    return grid, gu, gv


def surface_grid_mesh(grid, gu, gv, cyclic_u, cyclic_v):
    """(verts, faces) of the plotted quad grid; in a cyclic direction the
    last grid line is the first one again and is dropped, the quads wrap."""
    pts = list(zip(grid[0::3], grid[1::3], grid[2::3]))  # grid line i: pts[i * gv:]
    nu = gu - 1 if cyclic_u else gu
    nv = gv - 1 if cyclic_v else gv
    verts = pts[:nu * gv] if nv == gv else \
        list(itertools.chain.from_iterable(pts[i * gv:i * gv + nv] for i in range(nu)))
    # quad (i, j): i nv + j, i2 nv + j, i2 nv + j2, i nv + j2 with i2 = i + 1,
    # j2 = j + 1 (mod nu, nv in a cyclic direction); one row at a time
    j2 = list(range(1, nv)) + ([0] if cyclic_v else [])
    faces = []
    for i in range(nu if cyclic_u else nu - 1):
        a, b = i * nv, (i + 1) % nu * nv
        faces.extend(zip(range(a, a + len(j2)), range(b, b + len(j2)),
                         map(b.__add__, j2), map(a.__add__, j2)))
    return verts, faces


# The object property that marks a mesh made by Surface to Mesh, so that
# its poll() accepts the operator's own result: the redo panel and F9
# (Adjust Last Operation) re-run an operator only while its poll() holds in
# the context it left behind (the new mesh active, the surface deselected).
SURFACE_MARK = "conica_surface_to_mesh"

# Default vertex budget of one run of Surface to Mesh.
SURFACE_BUDGET = 1000000


def surface_size(ctrl):
    """Diagonal of the bounding box of a control net (flat x, y, z): the
    surface lies in the net's hull, so this is its size for Fidelity."""
    return math.sqrt(sum((max(ctrl[k::3]) - min(ctrl[k::3])) ** 2 for k in range(3)))


def _budget_message(exc, budget):
    """'would need about N vertices' from libcore's limit message."""
    m = re.search(r"about ([0-9.e+]+) points would meet", str(exc))
    need = (" (about %d)" % float(m.group(1))) if m else ""
    return ("the mesh would need more than the Vertex Budget of %d vertices%s; raise "
            "the Tolerance or Fidelity, or the budget" % (budget, need))


class OBJECT_OT_conic_surface_to_mesh(job.ModalRun, bpy.types.Operator):
    """Convert NURBS surfaces to meshes adaptively"""
    bl_description = ("Convert NURBS surfaces to meshes adaptively: every vertex on the "
                      "surface, grid lines placed where the curvature needs them, every "
                      "quad within the tolerance of the surface (a certified bound)")
    bl_idname = "object.conic_surface_to_mesh"
    bl_label = "Surface to Mesh (Adaptive)"
    bl_options = {"REGISTER", "UNDO"}

    fidelity: FloatProperty(
        name="Fidelity", default=1e-3, min=1e-6, max=0.1, precision=6, step=0.01,
        description="Largest distance of the mesh from the surface, as a fraction of the "
                    "surface's size (the diagonal of its control net's bounding box); used "
                    "when Tolerance is 0")
    tolerance: FloatProperty(
        name="Tolerance", subtype="DISTANCE", default=0.0, min=0.0, soft_max=1.0,
        precision=6, step=0.01,
        description="Largest distance of the mesh's faces from the surface and of the "
                    "surface from the mesh (a certified bound per quad); 0 uses Fidelity. "
                    "Below what float32 coordinates can hold at the surface's size (2 "
                    "float32 spacings at its largest coordinate) it is raised to that, "
                    "with a warning")
    max_vertices: IntProperty(
        name="Vertex Budget", default=SURFACE_BUDGET, min=4, max=MAX_POINTS,
        description="Largest number of vertices one run may make; a surface that would "
                    "need more is refused with the count before any vertex is made")

    @classmethod
    def poll(cls, context):
        if context.mode != "OBJECT":
            return False
        ao = context.active_object
        if ao is not None and (ao.type == "SURFACE" or SURFACE_MARK in ao.keys()):
            return True
        return any(o.type == "SURFACE" for o in context.selected_objects)

    def _report(self, level, message):
        self.report({level}, message)
        last_reports.append((level, message))

    def draw(self, context):
        layout = self.layout
        layout.use_property_split = True
        col = layout.column()
        col.active = self.tolerance == 0.0
        col.prop(self, "fidelity")
        exact_value(col, "Fidelity", self.fidelity, " of the size")
        layout.prop(self, "tolerance")
        exact_value(layout, "Tolerance", self.tolerance, " m (0: use Fidelity)")
        layout.prop(self, "max_vertices")

    def _tolerance(self, ctrl, where, problems):
        """(requested, plotter's) tolerance of one patch: Tolerance, or
        Fidelity times the net's size; raised to what float32 can hold."""
        # the plotter bounds every quad's distance from the surface (both
        # ways, either triangulation); the mesh's float32 vertices move by
        # up to FLOAT32_ROUNDING spacings at the net's largest coordinate
        # (the surface lies in the net's hull), as Curve to Polyline's points
        big = max(max(ctrl), -min(ctrl))
        spacing = float32_spacing(big)
        achievable = FLOAT32_TOL_SPACINGS * spacing
        tol = self.tolerance if self.tolerance > 0.0 else self.fidelity * surface_size(ctrl)
        if tol < achievable:
            if self.tolerance > 0.0:  # Fidelity's floor at a far net says nothing new
                problems.append("%s: tolerance %.3g is below what float32 coordinates near "
                                "%.3g can hold; used the achievable tolerance %.3g"
                                % (where, tol, big, achievable))
            tol = achievable
        return tol, tol - FLOAT32_ROUNDING * spacing

    def _start(self, context):
        """The run's Job (job.py, one chunk per spline) and a work estimate
        that makes invoke() modal for more than one spline (any one may
        take seconds)."""
        last_reports.clear()
        objs = [o for o in context.selected_objects if o.type == "SURFACE"]
        ao = context.active_object
        if not objs and ao is not None and ao.type == "SURFACE":
            objs = [ao]
        jobs = [(ob, i, sp) for ob in objs for i, sp in enumerate(ob.data.splines)]
        self._plans, self._problems = {}, []
        return (job.Job(self._chunks(jobs), len(jobs)),
                job.LONG_WORK if len(jobs) > 1 else 0)

    def _chunks(self, jobs):
        self._budget = self.max_vertices
        for ob, i, sp in jobs:
            self._plan(ob, i, sp)
            yield

    def _plan(self, ob, i, sp):
        """One spline's mesh part into self._plans, or a problem."""
        problems = self._problems
        where = "%s, spline %d" % (ob.name, i)
        if sp.point_count_v < 2 or sp.point_count_u < 2:
            problems.append("%s: one row of control points is a curve, not a "
                            "surface; left out" % where)
            return
        try:
            ctrl, nu, nv, du, dv, ku, kv, w, cu, cv = surface_patch(sp)
            tol, plot_tol = self._tolerance(ctrl, where, problems)
            if self._budget < 4:
                raise _conica.LimitError("over budget")
            grid, gu, gv = surface_grid(ctrl, nu, nv, du, dv, ku, kv, w,
                                        plot_tol, self._budget)
        except _conica.LimitError as exc:
            problems.append("%s: %s" % (where, _budget_message(exc, self.max_vertices)))
            return
        except _conica.ConicaError as exc:
            problems.append("%s: %s" % (where, exc))
            return
        self._budget -= gu * gv
        self._plans.setdefault(ob, []).append(
            (surface_grid_mesh(grid, gu, gv, cu, cv), sp.material_index))

    def _finish(self, context):
        """Make the meshes (the scene changes here only) and report."""
        plans, problems = self._plans, self._problems
        for p in problems:
            self._report("WARNING", p)
        if not plans:
            if not problems:
                self._report("INFO", "%s: nothing to do; no surface object selected"
                             % self.bl_label)
            return {"CANCELLED"}
        made = [self._make_mesh(context, ob, parts) for ob, parts in plans.items()]
        for ob in plans:
            ob.select_set(False)
        for new in made:
            new.select_set(True)
        context.view_layer.objects.active = made[0]
        self._report("INFO", "%s: %d object%s, %d vertices" % (
            self.bl_label, len(made), "" if len(made) == 1 else "s",
            sum(len(o.data.vertices) for o in made)))
        return {"FINISHED"}

    def _make_mesh(self, context, ob, parts):
        verts, faces, mats = [], [], []
        for (v, f), mat in parts:
            base = len(verts)
            verts.extend(v)
            faces.extend(f if base == 0 else (tuple(base + k for k in q) for q in f))
            mats.extend([mat] * len(f))
        me = bpy.data.meshes.new(ob.name + ".mesh")
        me.from_pydata(verts, [], faces)
        for m in ob.data.materials:
            me.materials.append(m)
        if mats:
            me.polygons.foreach_set("material_index", array.array("i", mats))
        me.update()
        new = bpy.data.objects.new(ob.name + ".mesh", me)
        new.matrix_world = ob.matrix_world.copy()
        new[SURFACE_MARK] = ob.name
        # into the surface's collections that may be written (a linked
        # collection may not), else the scene's
        colls = [c for c in ob.users_collection if c.library is None and
                 getattr(c, "override_library", None) is None]
        for coll in colls or [context.scene.collection]:
            coll.objects.link(new)
        return new


# ---------------------------------------------------------------- menus

def _menu_edit(self, context):
    self.layout.separator()
    self.layout.operator(CURVE_OT_conic_subdivide.bl_idname)
    self.layout.operator(CURVE_OT_adaptive_to_poly.bl_idname)


def _menu_object(self, context):
    ob = context.active_object
    if ob is not None and ob.type == "CURVE":
        self.layout.separator()
        self.layout.operator(CURVE_OT_conic_subdivide.bl_idname)
        self.layout.operator(CURVE_OT_adaptive_to_poly.bl_idname)


def _menu_convert(self, context):
    self.layout.separator()
    self.layout.operator(CURVE_OT_adaptive_to_poly.bl_idname)
    self.layout.operator(CURVE_OT_conic_subdivide.bl_idname)
    self.layout.operator(OBJECT_OT_conic_surface_to_mesh.bl_idname)


MENUS = [
    ("VIEW3D_MT_edit_curve_segments", _menu_edit),
    ("VIEW3D_MT_edit_curve_context_menu", _menu_edit),
    ("VIEW3D_MT_object_convert", _menu_convert),
    ("VIEW3D_MT_object_context_menu", _menu_object),
]

CLASSES = (CURVE_OT_conic_subdivide, CURVE_OT_adaptive_to_poly,
           OBJECT_OT_conic_surface_to_mesh)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    for name, fn in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.append(fn)


def unregister():
    for name, fn in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.remove(fn)
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
