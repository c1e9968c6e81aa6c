# SPDX-License-Identifier: MIT
# The _conica extension on its own, in plain CPython (no Blender):
#   /usr/bin/python3 tests/python/test_conica_ext.py EXT_DIR
# EXT_DIR holds the built _conica*.so (BUILD/blender/conica). Every case runs
# in its own interpreter (the same python, the same environment: run it with
# PYTHONMALLOC=debug, as tests/cli/python_ext.sh does), so a case that
# crashes the interpreter is one failed case, not the end of the suite.
# Prints `PASS name` or `FAIL name: why` per case, then `SUMMARY p f`.
import array
import math
import os
import subprocess
import sys

CASES = []


def case(fn):
    CASES.append(fn)
    return fn


def conica():
    sys.path.insert(0, EXT_DIR)
    import _conica  # noqa: E402 - the path is only known at run time
    return _conica


def expect(exc, fn, *args, **kw):
    """fn(*args, **kw) raises exc; returns its message."""
    try:
        fn(*args, **kw)
    except exc as e:  # noqa: PERF203
        return str(e)
    raise AssertionError("%s(...) did not raise %s" % (fn.__name__, exc.__name__))


SQUARE = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]


class Clears:
    """A number whose float() empties (or fills) a list while it is read."""

    def __init__(self, target, value, grow=False):
        self.target = target
        self.value = value
        self.grow = grow

    def __float__(self):
        if self.grow:
            self.target.extend([0.5] * 100000)  # the list's array is reallocated
        else:
            self.target.clear()  # the list's array is freed
        return self.value


def hostile(values, grow=False):
    """A list of `values` whose first item mutates the list when read."""
    lst = list(values)
    lst[0] = Clears(lst, lst[0], grow)
    return lst


# ---------------------------------------------------------------- issue 17.1

@case
def reproducer_float_clears_list():
    # the reproducer: segfaulted (use after free) before the fix
    c = conica()
    pts = None

    class S:
        __float__ = lambda self: (pts.clear(), 1.0)[1]  # noqa: E731

    pts = [S()] + SQUARE * 50000
    msg = expect(c.ArgumentError, c.subdivide, pts, closed=True, levels=1)
    assert "400001 values" in msg, msg


@case
def every_sequence_argument_survives_mutation():
    c = conica()
    sq = SQUARE
    for grow in (False, True):
        r = c.subdivide(hostile(SQUARE * 1, grow), closed=True, levels=1)
        assert r[4]["points"] == 8, r[4]
        normals = [0.0, -1.0, 1.0, 0.0, 0.0, 1.0, -1.0, 0.0]
        r = c.subdivide(sq, hostile(normals, grow), closed=True, levels=1)
        # curve(): points, handles and attrs go through the same reader
        p3 = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]
        h3 = [0.1, 0.0, 0.0, 1.0, 0.1, 0.0, 0.9, 1.0, 0.0, 0.0, 0.9, 0.0]
        r = c.curve("POLY", hostile(p3, grow), closed=True, levels=1, corner_angle=math.pi)
        assert len(r[0]) == 3 * 8, len(r[0])
        c.curve("BEZIER", p3, hostile(h3, grow), h3, closed=True, levels=1)
        c.curve("BEZIER", p3, h3, hostile(h3, grow), closed=True, levels=1)
        c.curve("POLY", p3, closed=True, levels=1, attrs=hostile([1.0, 0.0] * 4, grow), nattrs=2)
        r = c.subdivide(sq, closed=True, levels=1, attrs=hostile([1.0, 2.0, 3.0, 4.0], grow),
                        nattrs=1)
        assert len(r[2]) == 8, r[2]
        ctrl = [0.0, 0.0, 1.0, 1.0, 2.0, 0.0]
        knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
        c.plot(hostile(ctrl, grow), dim=2, degree=2, knots=knots, tolerance=0.01)
        c.plot(ctrl, dim=2, degree=2, knots=hostile(knots, grow), tolerance=0.01)
        c.plot(ctrl, dim=2, degree=2, knots=knots, weights=hostile([1.0, 2.0, 1.0], grow),
               tolerance=0.01)
        c.plot(ctrl, dim=2, degree=2, knots=knots, attrs=hostile([1.0, 2.0, 3.0], grow),
               nattrs=1, tolerance=0.01)
        c.fit_plane(hostile([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], grow))


@case
def sequences_other_than_lists_still_read():
    c = conica()
    for pts in (tuple(SQUARE), iter(SQUARE), (x for x in SQUARE), array.array("d", SQUARE),
                memoryview(array.array("f", SQUARE))):
        r = c.subdivide(pts, closed=True, levels=1)
        assert r[4]["points"] == 8
    msg = expect(TypeError, c.subdivide, 5, closed=True)
    assert "points: expected a flat sequence of numbers, got int" in msg, msg
    msg = expect(TypeError, c.subdivide, SQUARE[:7] + ["x"], closed=True)
    assert "points[7]: expected a number, got str" in msg, msg


# ---------------------------------------------------------------- issue 17.2

@case
def plot_without_knots_is_an_error_every_time():
    # the second call read an uninitialised pointer and crashed
    c = conica()
    for _ in range(5):
        msg = expect(c.ArgumentError, c.plot, [0, 0, 0, 1, 1, 1, 2, 2, 2], degree=2,
                     tolerance=0.1)
        assert msg == "knots must be given", msg


# ---------------------------------------------------------------- issue 17.7

@case
def float32_output_beyond_its_range_is_refused():
    c = conica()
    big = [0.0, 0.0, 1e39, 0.0, 1e39, 1e39, 0.0, 1e39]
    msg = expect(c.LimitError, c.subdivide, big, closed=True, levels=1, typecode="f")
    assert "not representable in float32" in msg, msg
    r = c.subdivide(big, closed=True, levels=1, typecode="d")  # double: fine
    assert all(math.isfinite(v) for v in r[0])
    ctrl = [0.0, 0.0, 1e39, 1e39, 2e39, 0.0]
    msg = expect(c.LimitError, c.plot, ctrl, dim=2, degree=2, knots=[0, 0, 0, 1, 1, 1],
                 tolerance=1e36, typecode="f")
    assert "not representable in float32" in msg, msg
    # within float32's range: still written as float32
    r = c.subdivide([v * 1e-2 for v in big], closed=True, levels=1, typecode="f")
    assert r[0].typecode == "f" and all(math.isfinite(v) for v in r[0])


@case
def fit_plane_refuses_what_has_no_finite_plane():
    c = conica()
    msg = expect(c.LimitError, c.fit_plane, [1e308, 0, 0, -1e308, 0, 0, 0, 1e308, 0])
    assert "beyond" in msg, msg
    msg = expect(c.DegenerateError, c.fit_plane, [2.0, 3.0, 4.0] * 3)
    assert "coincident" in msg, msg
    msg = expect(c.NonFiniteError, c.fit_plane, [0, 0, float("nan"), 1, 0, 0, 0, 1, 0])
    o, nrm, u, v, dev, size = c.fit_plane([0, 0, 5, 1, 0, 5, 0, 1, 5, 1, 1, 5])
    assert abs(abs(nrm[2]) - 1.0) < 1e-12 and dev < 1e-12 and abs(size - math.sqrt(2)) < 1e-12


@case
def huge_degree_message_does_not_overflow():
    c = conica()
    msg = expect(c.DegenerateError, c.plot, [0, 0, 0, 1, 1, 1, 2, 2, 2], degree=2 ** 31 - 1,
                 knots=[0.0] * 6, tolerance=0.1)
    assert "at least 2147483648 control points" in msg, msg


# ---------------------------------------------------------------- driver

@case
def float32_points_are_read_as_rounded():
    """A dense circle stored in float32 and turned in its plane (what the
    add-on makes of a Blender POLY spline): its rounding is below the sag
    of an edge, so read as exact it makes the scheme insert inflection
    points; subdivide() takes a float32 buffer's rounding as its precision
    (settings.noise) and inserts none, and precision=0 says exact."""
    c = conica()
    n, a = 20000, 1.65
    pts = array.array("f")
    for i in range(n):
        x = float(array.array("f", [math.cos(2 * math.pi * i / n)])[0])
        y = float(array.array("f", [math.sin(2 * math.pi * i / n)])[0])
        pts.extend((math.cos(a) * x - math.sin(a) * y, math.sin(a) * x + math.cos(a) * y))
    r = c.subdivide(pts, closed=True, levels=2, estimate=True, normal_method="circle")
    assert r[4]["inflections"] == 0, r[4]
    assert len(r[0]) == 2 * 4 * n, len(r[0])
    exact = c.subdivide(array.array("d", pts), closed=True, levels=2, estimate=True,
                        normal_method="circle")
    assert exact[4]["inflections"] > 0, exact[4]
    same = c.subdivide(array.array("d", pts), closed=True, levels=2, estimate=True,
                       normal_method="circle", precision=6e-8)
    assert same[4]["inflections"] == 0, same[4]
    msg = expect(c.ArgumentError, c.subdivide, pts, closed=True, precision=-1.0)
    assert "precision" in msg, msg


# ---- issue 33: the hostile battery's findings in the extension


class Raises:
    """A number whose float() raises exc."""

    def __init__(self, exc):
        self.exc = exc

    def __float__(self):
        raise self.exc


@case
def float_raising_base_exceptions_propagate_unchanged():
    c = conica()
    for exc in (KeyboardInterrupt, SystemExit, RecursionError, MemoryError, ZeroDivisionError):
        pts = list(SQUARE)
        pts[3] = Raises(exc("from __float__"))
        try:
            c.subdivide(pts, closed=True, levels=1)
        except exc as e:
            assert str(e) == "from __float__", (exc, e)
        except BaseException as e:  # noqa: B036 - the point of the case
            raise AssertionError("%s became %s: %s" % (exc.__name__, type(e).__name__, e))
        else:
            raise AssertionError("%s was swallowed" % exc.__name__)
    # a TypeError of __float__ still names the item
    pts = list(SQUARE)
    pts[3] = Raises(TypeError("nope"))
    msg = expect(TypeError, c.subdivide, pts, closed=True, levels=1)
    assert "points[3]" in msg, msg


@case
def endless_iterable_is_capped():
    import itertools
    import resource
    c = conica()
    # a generator is read like a list (up to the cap)
    r = c.subdivide((v for v in SQUARE), closed=True, levels=1)
    assert len(r[0]) == len(c.subdivide(SQUARE, closed=True, levels=1)[0])
    # an endless one stops at the cap instead of eating all memory
    resource.setrlimit(resource.RLIMIT_AS, (3 << 30, 3 << 30))
    msg = expect(ValueError, c.subdivide, itertools.repeat(0.5), closed=True, levels=1)
    assert "more than 67108864 values" in msg, msg
    # an iterator that raises mid-way: its own exception
    def bad():
        yield 0.0
        raise KeyboardInterrupt("mid-way")
    try:
        c.subdivide(bad(), closed=True, levels=1)
    except KeyboardInterrupt as e:
        assert str(e) == "mid-way"
    else:
        raise AssertionError("the iterator's KeyboardInterrupt was swallowed")


BILINEAR = dict(nu=2, nv=2, degree_u=1, degree_v=1, knots_u=[0, 0, 1, 1],
                knots_v=[0, 0, 1, 1])
BILINEAR_CTRL = [0.0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 1]


@case
def surface_tolerance_below_resolution_refused_fast():
    import time
    c = conica()
    for tol in (1e-300, 1e-16):
        t0 = time.process_time()
        msg = expect(c.LimitError, c.surface, BILINEAR_CTRL, tolerance=tol, **BILINEAR)
        assert time.process_time() - t0 < 5, "took %g s" % (time.process_time() - t0)
        assert "below what the coordinates resolve" in msg, msg
    r = c.surface(BILINEAR_CTRL, tolerance=1e-2, **BILINEAR)
    assert r[1] >= 2 and r[2] >= 2, r


@case
def surface_huge_grid_message_has_no_overflowed_product():
    c = conica()
    kw = dict(BILINEAR)
    kw.update(nu=6148914691236517206, nv=3)
    msg = expect(c.LimitError, c.surface, BILINEAR_CTRL, tolerance=1e-2, **kw)
    assert "6148914691236517206 x 3 control points exceed the limit" in msg, msg


def run_one(name):
    for fn in CASES:
        if fn.__name__ == name:
            fn()
            return
    raise SystemExit("no case " + name)


def main():
    passed = failed = 0
    for fn in CASES:
        p = subprocess.run([sys.executable, __file__, EXT_DIR, fn.__name__],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           timeout=120)
        if p.returncode == 0:
            print("PASS %s" % fn.__name__, flush=True)
            passed += 1
        else:
            why = "exit %d" % p.returncode
            if p.returncode < 0:
                why = "killed by signal %d (crash)" % -p.returncode
            print("FAIL %s: %s" % (fn.__name__, why), flush=True)
            for line in p.stdout.splitlines()[-15:]:
                print("  " + line)
            failed += 1
    print("SUMMARY %d %d" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    EXT_DIR = os.path.abspath(sys.argv[1])
    if len(sys.argv) > 2:
        run_one(sys.argv[2])
    else:
        sys.exit(main())
