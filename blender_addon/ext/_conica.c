/* SPDX-License-Identifier: GPL-3.0-or-later */
/*
 * _conica: the thin CPython extension behind the Blender add-on.
 *
 * It moves flat float data (what bpy's foreach_get fills and foreach_set
 * accepts) in and out of libcore, which is linked in statically so the
 * add-on is self-contained. Everything that touches many points runs in C
 * with the GIL released: the plane fit of a 3D spline, the projection into
 * the plane and back, libcore's curve front end (conica/path.h: drawn
 * Bezier and NURBS splines smoothed by conic subdivision or flattened
 * within a fidelity tolerance, POLY splines interpolated; corners and
 * tangents are its rules), the interpolation of per-point attributes
 * (radius, tilt) and the Bezier handles along the conic tangents. Python
 * only reads and writes Blender's data, so the add-on stays fast (the
 * benchmark compares it with Blender's own curve.subdivide).
 *
 * Every libcore status becomes a Python exception (a subclass of
 * ConicaError that also derives from the matching built-in exception)
 * carrying libcore's message; bad input of any kind (wrong lengths, NaN,
 * empty, too many levels, non-numbers) raises, never crashes.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#ifdef _WIN32
#include <windows.h> /* GetSystemInfo: the Windows build (docs/blender.md) */
#endif

#include "conica/bspline.h"
#include "conica/common.h"
#include "conica/curve.h"
#include "conica/path.h"
#include "conica/plot.h"
#include "conica/subdiv.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Built against CPython's stable ABI (PEP 384) at the version below, so one
 * _conica.abi3.so loads in every CPython from it on: Blender 3.4 (Debian),
 * 4.1-5.x. 3.11 is the lowest version that will do: the buffer protocol
 * (PyObject_GetBuffer, Py_buffer), which reads foreach_get's arrays without
 * a copy per item, entered the limited API in 3.11. The Makefile defines
 * Py_LIMITED_API to this value; tests/cli/blender.sh checks that the .so
 * imports nothing outside the stable ABI list of that version. */
#define CX_LIMITED_API 0x030B0000
#if !defined(Py_LIMITED_API) || Py_LIMITED_API != CX_LIMITED_API
#error "build with -DPy_LIMITED_API=0x030B0000 (see blender_addon/module.mk)"
#endif

/* Largest flat input the module copies (values, not points): a Blender
 * curve with more than 16 M points is far beyond interactive use. */
#define CX_MAX_INPUT_VALUES ((size_t)1 << 26)
/* Default and hard cap of output points per call: Blender stores every
 * point as 4 floats plus radius, tilt, weight; 2^24 points is ~1 GB there. */
#define CX_DEFAULT_MAX_POINTS ((size_t)1 << 22)
#define CX_HARD_MAX_POINTS ((size_t)1 << 24)
#define CX_MAX_ATTRS 8
/* Largest coordinate magnitude accepted: squared distances of points must
 * stay finite (1e150^2 = 1e300 < DBL_MAX), and libconica's subdivision
 * hangs on coordinates near 1e308 (reported to its owner). Blender's float32
 * coordinates end at 3.4e38, so no Blender curve comes near this. */
#define CX_MAX_ABS_COORD 1e150
/* Smallest extent (largest side of the bounding box) of a 3D spline that
 * can be put into its plane: below DBL_MIN the coordinates relative to the
 * centroid are subnormal, with fewer than 53 significant bits, and their
 * squares and the size underflow to 0. Such a spline is degenerate
 * (DegenerateError), not "non-planar". */
#define CX_MIN_PLANE_SIZE DBL_MIN

typedef struct cx_state {
    PyObject *error;       /* ConicaError */
    PyObject *arg_error;   /* ArgumentError(ConicaError, ValueError) */
    PyObject *limit_error; /* LimitError(ConicaError, ValueError) */
    PyObject *degenerate;  /* DegenerateError(ConicaError, ValueError) */
    PyObject *nonfinite;   /* NonFiniteError(ConicaError, ValueError) */
    PyObject *nonplanar;   /* NonPlanarError(ConicaError, ValueError) */
    PyObject *numeric;     /* NumericError(ConicaError, RuntimeError) */
    PyObject *nomem;       /* OutOfMemoryError(ConicaError, MemoryError) */
    PyObject *unsupported; /* UnsupportedError(ConicaError, NotImplementedError) */
    PyObject *array_type;  /* array.array */
} cx_state;

static cx_state *cx_get_state(PyObject *module)
{
    return (cx_state *)PyModule_GetState(module);
}

static PyObject *cx_exc_for(cx_state *s, conica_code code)
{
    switch (code) {
    case CONICA_ERR_ARG: return s->arg_error;
    case CONICA_ERR_LIMIT: return s->limit_error;
    case CONICA_ERR_DEGENERATE: return s->degenerate;
    case CONICA_ERR_NONFINITE: return s->nonfinite;
    case CONICA_ERR_NUMERIC: return s->numeric;
    case CONICA_ERR_NOMEM: return s->nomem;
    case CONICA_ERR_UNSUPPORTED: return s->unsupported;
    default: return s->error;
    }
}

/* Raise the exception for a libcore status; returns NULL for chaining. */
static PyObject *cx_raise(cx_state *s, conica_code code, const conica_status *st)
{
    const char *msg = (st && st->message[0]) ? st->message : conica_strerror(code);
    PyObject *exc = cx_exc_for(s, code);
    PyObject *val = Py_BuildValue("(s)", msg);
    if (val == NULL)
        return NULL;
    PyObject *inst = PyObject_Call(exc, val, NULL);
    Py_DECREF(val);
    if (inst == NULL)
        return NULL;
    PyObject *pycode = PyLong_FromLong((long)code);
    if (pycode == NULL || PyObject_SetAttrString(inst, "code", pycode) < 0) {
        Py_XDECREF(pycode);
        Py_DECREF(inst);
        return NULL;
    }
    Py_DECREF(pycode);
    PyErr_SetObject(exc, inst);
    Py_DECREF(inst);
    return NULL;
}

static PyObject *cx_raisef(PyObject *exc, const char *fmt, ...)
{
    char buf[320];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    PyErr_SetString(exc, buf);
    return NULL;
}

static double cx_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ------------------------------------------------------------ input/output */

/* A float item format of the buffer protocol: 'f' or 'd', native order. */
static int cx_float_format(const char *fmt, Py_ssize_t itemsize)
{
    if (fmt == NULL)
        return 0; /* unsigned bytes: not floats */
    if (*fmt == '@' || *fmt == '=')
        fmt++;
#if PY_LITTLE_ENDIAN
    else if (*fmt == '<')
        fmt++;
#else
    else if (*fmt == '>' || *fmt == '!')
        fmt++;
#endif
    if (fmt[0] == 'd' && fmt[1] == '\0' && itemsize == 8)
        return 'd';
    if (fmt[0] == 'f' && fmt[1] == '\0' && itemsize == 4)
        return 'f';
    return 0;
}

/* 1 when obj is a contiguous float32 buffer (array('f'), Blender's
 * foreach_get targets), else 0; never raises. */
static int cx_is_float32_buffer(PyObject *obj)
{
    Py_buffer view;
    int f32;
    if (!PyObject_CheckBuffer(obj))
        return 0;
    if (PyObject_GetBuffer(obj, &view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) != 0) {
        PyErr_Clear();
        return 0;
    }
    f32 = cx_float_format(view.format, view.itemsize) == 'f';
    PyBuffer_Release(&view);
    return f32;
}

/* TypeError "what[i]: expected <expected>, got <type name>" (no [i] when
 * i < 0). The limited API has no tp_name: the name comes from
 * PyType_GetName (3.11). */
static void cx_type_error(const char *what, Py_ssize_t i, const char *expected, PyObject *obj)
{
    PyObject *name = PyType_GetName(Py_TYPE(obj));
    if (name == NULL)
        return;
    if (i >= 0)
        PyErr_Format(PyExc_TypeError, "%s[%zd]: expected %s, got %U", what, i, expected, name);
    else
        PyErr_Format(PyExc_TypeError, "%s: expected %s, got %U", what, expected, name);
    Py_DECREF(name);
}

/* float(item) into *v; 0 with an exception set on failure. Only a
 * TypeError (not a number) becomes our message naming the item: anything
 * else raised while __float__ runs (KeyboardInterrupt, SystemExit,
 * RecursionError, MemoryError, the caller's own exception) propagates
 * unchanged. */
static int cx_item_double(PyObject *item, const char *what, Py_ssize_t i, double *v)
{
    *v = PyFloat_AsDouble(item);
    if (*v == -1.0 && PyErr_Occurred()) {
        if (!PyErr_ExceptionMatches(PyExc_TypeError))
            return 0;
        PyErr_Clear();
        cx_type_error(what, i, "a number", item);
        return 0;
    }
    return 1;
}

/* An iterable that is no sequence, read with its iterator into a growing
 * array: at most CX_MAX_INPUT_VALUES items are taken (one more is a
 * ValueError), so an endless generator costs the cap, not all memory. */
static int cx_read_iterable(PyObject *obj, const char *what, double **out, size_t *n)
{
    PyObject *it = PyObject_GetIter(obj), *item;
    double *d = NULL;
    size_t len = 0, cap = 0;
    if (it == NULL) {
        if (!PyErr_ExceptionMatches(PyExc_TypeError))
            return 0;
        PyErr_Clear();
        cx_type_error(what, -1, "a flat sequence of numbers", obj);
        return 0;
    }
    while ((item = PyIter_Next(it)) != NULL) {
        if (len == CX_MAX_INPUT_VALUES) {
            Py_DECREF(item);
            PyErr_Format(PyExc_ValueError, "%s: more than %zu values (the limit)", what,
                         CX_MAX_INPUT_VALUES);
            break;
        }
        if (len == cap) {
            size_t nc = cap ? 2 * cap : 256;
            double *t = PyMem_Realloc(d, nc * sizeof *d);
            if (t == NULL) {
                Py_DECREF(item);
                PyErr_NoMemory();
                break;
            }
            d = t;
            cap = nc;
        }
        int ok = cx_item_double(item, what, (Py_ssize_t)len, &d[len]);
        Py_DECREF(item);
        if (!ok)
            break;
        len++;
    }
    Py_DECREF(it);
    if (PyErr_Occurred()) {
        PyMem_Free(d);
        return 0;
    }
    if (d == NULL && (d = PyMem_Malloc(sizeof *d)) == NULL) {
        PyErr_NoMemory();
        return 0;
    }
    *out = d;
    *n = len;
    return 1;
}

/*
 * Copy a flat float sequence or buffer into a new double array (free with
 * PyMem_Free). Buffers (array('f'/'d'), memoryviews of them, Blender's
 * foreach_get targets) are copied directly; any other sequence is read
 * item by item with float(). Returns 0 and sets an exception on failure.
 *
 * float() of an item may run Python (__float__, __index__) that changes
 * the sequence: clearing or growing a list frees the item array that
 * PySequence_Fast_ITEMS points into (issue 17). The items are therefore
 * read from a tuple snapshot that owns a reference to each of them.
 */
static int cx_read_doubles(PyObject *obj, const char *what, double **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    if (PyObject_CheckBuffer(obj)) {
        Py_buffer view;
        if (PyObject_GetBuffer(obj, &view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) == 0) {
            int kind = cx_float_format(view.format, view.itemsize);
            if (kind == 0) {
                PyErr_Format(PyExc_TypeError,
                             "%s: buffer of format '%s' is not float32/float64 "
                             "(use array('f') or array('d'))",
                             what, view.format ? view.format : "B");
                PyBuffer_Release(&view);
                return 0;
            }
            size_t count = (size_t)(view.len / view.itemsize);
            if (count > CX_MAX_INPUT_VALUES) {
                PyErr_Format(PyExc_ValueError, "%s: %zu values exceed the limit of %zu", what,
                             count, CX_MAX_INPUT_VALUES);
                PyBuffer_Release(&view);
                return 0;
            }
            double *d = PyMem_Malloc((count ? count : 1) * sizeof *d);
            if (d == NULL) {
                PyBuffer_Release(&view);
                PyErr_NoMemory();
                return 0;
            }
            if (kind == 'd') {
                memcpy(d, view.buf, count * sizeof *d);
            } else {
                const float *f = view.buf;
                for (size_t i = 0; i < count; i++)
                    d[i] = (double)f[i];
            }
            PyBuffer_Release(&view);
            *out = d;
            *n = count;
            return 1;
        }
        PyErr_Clear(); /* not contiguous: read it as a sequence */
    }
    if (PyUnicode_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "%s: expected a flat sequence of numbers, got str", what);
        return 0;
    }
    /* any other iterable (a generator, an endless itertools.count()) is
     * read item by item up to the cap, never to its end first */
    if (!PyList_Check(obj) && !PyTuple_Check(obj) && !PySequence_Check(obj))
        return cx_read_iterable(obj, what, out, n);
    /* a list over the cap is refused before the snapshot copies it */
    if (PyList_Check(obj) && (size_t)PyList_Size(obj) > CX_MAX_INPUT_VALUES) {
        PyErr_Format(PyExc_ValueError, "%s: %zd values exceed the limit of %zu", what,
                     PyList_Size(obj), CX_MAX_INPUT_VALUES);
        return 0;
    }
    PyObject *seq = PySequence_Tuple(obj); /* a tuple is returned as itself */
    if (seq == NULL) {
        if (PyErr_Occurred() && !PyErr_ExceptionMatches(PyExc_TypeError))
            return 0; /* MemoryError, or an error raised by the sequence itself */
        PyErr_Clear();
        cx_type_error(what, -1, "a flat sequence of numbers", obj);
        return 0;
    }
    Py_ssize_t len = PyTuple_Size(seq);
    if ((size_t)len > CX_MAX_INPUT_VALUES) {
        Py_DECREF(seq);
        PyErr_Format(PyExc_ValueError, "%s: %zd values exceed the limit of %zu", what, len,
                     CX_MAX_INPUT_VALUES);
        return 0;
    }
    double *d = PyMem_Malloc((size_t)(len ? len : 1) * sizeof *d);
    if (d == NULL) {
        Py_DECREF(seq);
        PyErr_NoMemory();
        return 0;
    }
    for (Py_ssize_t i = 0; i < len; i++) {
        PyObject *item = PyTuple_GetItem(seq, i); /* borrowed: the tuple keeps it alive */
        if (!cx_item_double(item, what, i, &d[i])) {
            PyMem_Free(d);
            Py_DECREF(seq);
            return 0;
        }
    }
    Py_DECREF(seq);
    *out = d;
    *n = (size_t)len;
    return 1;
}

/* Index of the first non-finite value, or n. */
static size_t cx_first_nonfinite(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return i;
    return n;
}

/* Index of the first value beyond +-CX_MAX_ABS_COORD, or n. */
static size_t cx_first_huge(const double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (fabs(v[i]) > CX_MAX_ABS_COORD)
            return i;
    return n;
}

/* New array.array of typecode 'd' or 'f' holding n values of v (stride
 * `dim` values per item, padded with `pad` to `stride` when stride > dim). */
static PyObject *cx_make_array(cx_state *s, char typecode, const double *v, size_t items,
                               int dim, int stride, double pad)
{
    size_t count = items * (size_t)stride;
    size_t esize = typecode == 'f' ? sizeof(float) : sizeof(double);
    /* Callers make all the arrays of a result, then check them: after one
     * failed, make no more (calling array() with an exception set is an
     * error of its own). */
    if (PyErr_Occurred())
        return NULL;
    if (typecode == 'f') {
        /* a finite double beyond float32's range would become inf: refuse
         * it rather than hand Blender an infinite coordinate */
        for (size_t i = 0; i < items * (size_t)dim; i++)
            if (isfinite(v[i]) && isinf((float)v[i])) {
                return cx_raisef(s->limit_error,
                                 "value %.17g (item %zu) is not representable in float32 "
                                 "(largest %g); use typecode='d'",
                                 v[i], i / (size_t)dim, (double)FLT_MAX);
            }
    }
    /* The array is made at its full size first (one zero item repeated)
     * and filled through its buffer: no bytes object to copy from, so a
     * result of millions of points touches its memory once (fresh pages
     * cost more than the copy itself). */
    char tc[2] = {typecode, '\0'};
    static const char zeros[sizeof(double)] = {0};
    PyObject *one = PyObject_CallFunction(s->array_type, "sy#", tc, zeros, (Py_ssize_t)esize);
    if (one == NULL)
        return NULL;
    PyObject *arr = PySequence_Repeat(one, (Py_ssize_t)count);
    Py_DECREF(one);
    if (arr == NULL || count == 0)
        return arr;
    Py_buffer view;
    if (PyObject_GetBuffer(arr, &view, PyBUF_WRITABLE | PyBUF_C_CONTIGUOUS) < 0) {
        Py_DECREF(arr);
        return NULL;
    }
    char *raw = view.buf;
    if (stride == dim && typecode == 'd') {
        memcpy(raw, v, count * sizeof(double));
    } else if (stride == dim) {
        float *f = (float *)(void *)raw; /* array data comes from malloc: aligned */
        for (size_t i = 0; i < count; i++)
            f[i] = (float)v[i];
    } else if (typecode == 'f') {
        float *f = (float *)(void *)raw;
        float fpad = (float)pad;
        for (size_t i = 0; i < items; i++) {
            const double *src = v + i * (size_t)dim;
            float *dst = f + i * (size_t)stride;
            for (int k = 0; k < dim; k++)
                dst[k] = (float)src[k];
            for (int k = dim; k < stride; k++)
                dst[k] = fpad;
        }
    } else {
        for (size_t i = 0; i < items; i++) {
            for (int k = 0; k < stride; k++) {
                double x = k < dim ? v[i * (size_t)dim + (size_t)k] : pad;
                size_t at = (i * (size_t)stride + (size_t)k) * esize;
                if (typecode == 'f') {
                    float f = (float)x;
                    memcpy(raw + at, &f, sizeof f);
                } else {
                    memcpy(raw + at, &x, sizeof x);
                }
            }
        }
    }
    PyBuffer_Release(&view);
    return arr;
}

static int cx_typecode(cx_state *s, PyObject *obj, char *out)
{
    if (obj == NULL) {
        *out = 'd';
        return 1;
    }
    const char *t = PyUnicode_Check(obj) ? PyUnicode_AsUTF8AndSize(obj, NULL) : NULL;
    if (t == NULL || (strcmp(t, "d") != 0 && strcmp(t, "f") != 0)) {
        PyErr_Clear();
        PyErr_SetString(s->arg_error, "typecode must be 'd' or 'f'");
        return 0;
    }
    *out = t[0];
    return 1;
}

/* ------------------------------------------------------------ plane fit */

/*
 * Eigen decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations
 * (converges quadratically; 3x3 needs a handful of sweeps). Eigenvalues go
 * to w (ascending), eigenvectors to the columns of v.
 */
static void cx_eigen_sym3(double a_in[3][3], double w[3], double v[3][3])
{
    double a[3][3];
    memcpy(a, a_in, sizeof a);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            v[i][j] = i == j ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        double diag = fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2]);
        if (off == 0.0 || off <= 1e-300 || off < DBL_EPSILON * 1e-3 * diag)
            break;
        for (int p = 0; p < 2; p++) {
            for (int q = p + 1; q < 3; q++) {
                if (a[p][q] == 0.0)
                    continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
                for (int k = 0; k < 3; k++) { /* A <- A J */
                    double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - sn * akq;
                    a[k][q] = sn * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) { /* A <- J^T A */
                    double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - sn * aqk;
                    a[q][k] = sn * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - sn * vkq;
                    v[k][q] = sn * vkp + c * vkq;
                }
            }
        }
    }
    int idx[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (a[idx[j]][idx[j]] < a[idx[i]][idx[i]]) {
                int t = idx[i];
                idx[i] = idx[j];
                idx[j] = t;
            }
    double vv[3][3];
    for (int j = 0; j < 3; j++) {
        w[j] = a[idx[j]][idx[j]];
        for (int i = 0; i < 3; i++)
            vv[i][j] = v[i][idx[j]];
    }
    memcpy(v, vv, sizeof vv);
}

typedef struct cx_plane {
    double origin[3], normal[3], u[3], v[3];
    double deviation; /* largest distance of a point from the plane */
    double size;      /* bounding-box diagonal */
    double extent;    /* largest side of the bounding box */
} cx_plane;

/*
 * Best-fit plane of n 3D points: through the centroid, normal along the
 * eigenvector of the smallest eigenvalue of the covariance matrix (total
 * least squares). Coordinates are taken relative to the centroid first so
 * the result does not depend on where the spline sits, and scaled by the
 * largest extent so that neither the covariance nor the size underflows
 * for a tiny spline (squares of extents below ~1.5e-154 would).
 */
static void cx_fit_plane(const double *p, size_t n, cx_plane *pl)
{
    double c[3] = {0, 0, 0}, lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = hi[k] = p[k];
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            double x = p[3 * i + (size_t)k];
            c[k] += x;
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (int k = 0; k < 3; k++)
        c[k] /= (double)n;
    /* Second pass: the mean of (p - c) removes the centroid's rounding. */
    double d[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            d[k] += p[3 * i + (size_t)k] - c[k];
    for (int k = 0; k < 3; k++)
        c[k] += d[k] / (double)n;
    double ext = 0.0;
    for (int k = 0; k < 3; k++)
        if (hi[k] - lo[k] > ext)
            ext = hi[k] - lo[k];
    /* 1/ext when that is finite; the caller rejects a spline whose extent
     * is below CX_MIN_PLANE_SIZE before using the plane. */
    double scale = isfinite(ext) && ext >= CX_MIN_PLANE_SIZE ? 1.0 / ext : 1.0;
    double cov[3][3] = {{0}};
    for (size_t i = 0; i < n; i++) {
        double q[3] = {(p[3 * i] - c[0]) * scale, (p[3 * i + 1] - c[1]) * scale,
                       (p[3 * i + 2] - c[2]) * scale};
        for (int r = 0; r < 3; r++)
            for (int s = 0; s < 3; s++)
                cov[r][s] += q[r] * q[s];
    }
    double w[3], v[3][3];
    cx_eigen_sym3(cov, w, v);
    for (int k = 0; k < 3; k++) {
        pl->origin[k] = c[k];
        pl->normal[k] = v[k][0];
        pl->u[k] = v[k][2];
    }
    /* v = normal x u: a right-handed frame, so a curve counter-clockwise
     * seen from +normal stays counter-clockwise in (u, v). */
    pl->v[0] = pl->normal[1] * pl->u[2] - pl->normal[2] * pl->u[1];
    pl->v[1] = pl->normal[2] * pl->u[0] - pl->normal[0] * pl->u[2];
    pl->v[2] = pl->normal[0] * pl->u[1] - pl->normal[1] * pl->u[0];
    double dev = 0.0;
    for (size_t i = 0; i < n; i++) {
        double q = 0.0;
        for (int k = 0; k < 3; k++)
            q += (p[3 * i + (size_t)k] - c[k]) * pl->normal[k];
        if (fabs(q) > dev)
            dev = fabs(q);
    }
    pl->deviation = dev;
    double e2 = 0.0;
    for (int k = 0; k < 3; k++)
        e2 += ((hi[k] - lo[k]) * scale) * ((hi[k] - lo[k]) * scale);
    pl->size = sqrt(e2) / scale;
    pl->extent = ext;
}

static void cx_to_plane(const cx_plane *pl, const double *p3, size_t n, double *p2, int is_vector)
{
    for (size_t i = 0; i < n; i++) {
        double q[3];
        for (int k = 0; k < 3; k++)
            q[k] = p3[3 * i + (size_t)k] - (is_vector ? 0.0 : pl->origin[k]);
        p2[2 * i] = q[0] * pl->u[0] + q[1] * pl->u[1] + q[2] * pl->u[2];
        p2[2 * i + 1] = q[0] * pl->v[0] + q[1] * pl->v[1] + q[2] * pl->v[2];
    }
}

static void cx_from_plane(const cx_plane *pl, const double *p2, size_t n, double *p3, int is_vector)
{
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            p3[3 * i + (size_t)k] = (is_vector ? 0.0 : pl->origin[k]) + p2[2 * i] * pl->u[k] +
                                    p2[2 * i + 1] * pl->v[k];
}

/* ------------------------------------------------------------ subdivision */

/* One run of the scheme on a whole spline, in 2D plane coordinates. Corners
 * and the normals of drawn curves are the path front end's (conica/path.h,
 * curve() below); this is the bare scheme on points and normals. */
typedef struct cx_job {
    /* inputs */
    size_t n;
    int closed;
    const double *xy;      /* 2n */
    const double *nrm;     /* 2n normals, or NULL */
    conica_subdiv_settings set;
    /* outputs */
    conica_curve out;
    size_t *inflections;
    size_t ninflections;
    double seconds;
    conica_status st;
} cx_job;

/* Runs without the GIL (no Python calls in here). */
static conica_code cx_run(cx_job *j)
{
    conica_curve in;
    conica_curve_init(&in);
    conica_subdiv_info info;
    conica_subdiv_info_init(&info);
    conica_code rc = conica_curve_set(j->xy, j->nrm, j->n, j->closed, &in, &j->st);
    if (rc == CONICA_OK) {
        double t0 = cx_now();
        rc = conica_subdivide(&in, &j->set, &j->out, &info, &j->st);
        j->seconds += cx_now() - t0;
    }
    conica_curve_free(&in);
    if (rc == CONICA_OK && info.inflections > 0 && info.inflection_index) {
        j->inflections = malloc(info.inflections * sizeof *j->inflections);
        if (j->inflections == NULL) {
            rc = CONICA_ERR_NOMEM;
            j->st.code = rc;
            snprintf(j->st.message, sizeof j->st.message, "out of memory");
        } else {
            memcpy(j->inflections, info.inflection_index,
                   info.inflections * sizeof *j->inflections);
            j->ninflections = info.inflections;
        }
    }
    conica_subdiv_info_free(&info);
    return rc;
}
/*
 * Find each input vertex in the output: the scheme keeps old vertices
 * bit-for-bit (CONIS §1.1), in order, so one forward scan finds
 * them. anchor[] gets n + 1 entries (the last closes the curve). Returns 0
 * when a vertex is missing (cannot happen with libcore's guarantee).
 */
static int cx_find_anchors(const double *inxy, size_t n, int closed, const double *oxy, size_t N,
                           size_t *anchor)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        while (k < N && !(oxy[2 * k] == inxy[2 * i] && oxy[2 * k + 1] == inxy[2 * i + 1]))
            k++;
        if (k == N)
            return 0;
        anchor[i] = k++;
    }
    anchor[n] = closed ? N : anchor[n - 1];
    return 1;
}

/* Distance of two 2D points (sqrt of the sum: hypot's overflow care costs
 * 10% of a call here and plane coordinates stay far below 1e150). */
static double cx_dist2(const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    return sqrt(dx * dx + dy * dy);
}

/*
 * Interpolate m attributes per input vertex onto the output: the anchors
 * keep their values, the points in between get values linear in the chord
 * length between their two anchors. cum (N + 1 values) receives the
 * cumulative chord length; an attribute equal on every input vertex (the
 * usual radius 1, tilt 0) is copied without arithmetic.
 */
static void cx_interp_attrs(const size_t *anchor, size_t n, int closed, const double *attr, int m,
                            const double *oxy, size_t N, double *cum, double *oattr)
{
    cum[0] = 0.0;
    for (size_t t = 0; t < N; t++) {
        size_t u = t + 1 < N ? t + 1 : 0;
        cum[t + 1] = cum[t] + (t + 1 < N || closed ? cx_dist2(oxy + 2 * t, oxy + 2 * u) : 0.0);
    }
    for (int q = 0; q < m; q++) {
        size_t i = 1;
        while (i < n && attr[i * (size_t)m + (size_t)q] == attr[(size_t)q])
            i++;
        if (i == n) { /* constant */
            for (size_t t = 0; t < N; t++)
                oattr[t * (size_t)m + (size_t)q] = attr[(size_t)q];
            continue;
        }
        for (i = 0; i < n; i++) {
            size_t a = anchor[i], b = anchor[i + 1];
            double v0 = attr[i * (size_t)m + (size_t)q];
            if (!closed && i + 1 == n) {
                oattr[a * (size_t)m + (size_t)q] = v0;
                continue;
            }
            double v1 = attr[((i + 1) % n) * (size_t)m + (size_t)q];
            double total = cum[b] - cum[a];
            for (size_t t = a; t < b; t++) {
                double f = total > 0 ? (cum[t] - cum[a]) / total : (double)(t - a) / (double)(b - a);
                oattr[t * (size_t)m + (size_t)q] = v0 + f * (v1 - v0);
            }
        }
    }
}

/*
 * After lifting back from the plane: the old vertices get their exact input
 * coordinates again (the projection round trip would move them by an ulp),
 * and a coordinate that all input points share (z of a 2D curve, x of a
 * curve in a YZ plane) is set exactly on every output point and handle.
 */
static void cx_restore_exact(const double *in3, size_t n, const size_t *anchor, double *o3,
                             size_t N, double *hl3, double *hr3)
{
    for (size_t i = 0; i < n; i++)
        memcpy(o3 + 3 * anchor[i], in3 + 3 * i, 3 * sizeof *o3);
    for (int k = 0; k < 3; k++) {
        size_t i = 1;
        while (i < n && in3[3 * i + (size_t)k] == in3[(size_t)k])
            i++;
        if (i < n)
            continue;
        for (size_t j = 0; j < N; j++) {
            o3[3 * j + (size_t)k] = in3[(size_t)k];
            if (hl3)
                hl3[3 * j + (size_t)k] = in3[(size_t)k];
            if (hr3)
                hr3[3 * j + (size_t)k] = in3[(size_t)k];
        }
    }
}

/*
 * Cubic Bezier handles along the conic tangents. Each output edge s (points
 * s and s+1) comes with the midpoint mid[s] of the curve between them: the
 * scheme's edge point one level further. Written as a rational quadratic
 * Bezier (p0, C, p1; weight w), with C the intersection of the tangent
 * lines, the arc's midpoint satisfies m - M = w/(1+w) (C - M) with M the
 * chord midpoint; the cubic through the same ends and tangents that matches
 * the arc's midpoint has handles p0 + 4/3 w/(1+w) (C - p0) (for a circle
 * this is the classical 4/3 tan(theta/4) r). Where the tangents do not meet
 * ahead of the chord (inflection) the handles are a third of the chord
 * along the tangents. An edge without a midpoint (hasmid[s] == 0: a
 * straight or flattened piece) gets handles a third of the chord along the
 * chord, so it stays the straight edge it is. nout holds the normal each
 * point leaves with, nin the one it arrives with (they differ at corners).
 */
static void cx_handles(const double *fxy, const double *nin, const double *nout,
                       const double *mid, const unsigned char *hasmid, size_t N, int closed,
                       double *left, double *right)
{
    size_t segs = closed ? N : N - 1;
    for (size_t i = 0; i < N; i++) { /* defaults for open ends */
        left[2 * i] = right[2 * i] = fxy[2 * i];
        left[2 * i + 1] = right[2 * i + 1] = fxy[2 * i + 1];
    }
    for (size_t s = 0; s < segs; s++) {
        size_t a = s, b = (s + 1) % N;
        double p0x = fxy[2 * a], p0y = fxy[2 * a + 1], p1x = fxy[2 * b], p1y = fxy[2 * b + 1];
        double cx = p1x - p0x, cy = p1y - p0y, chord = hypot(cx, cy);
        double h0x = p0x, h0y = p0y, h1x = p1x, h1y = p1y;
        int done = 0;
        if (hasmid && !hasmid[s]) {
            h0x = p0x + cx / 3; h0y = p0y + cy / 3;
            h1x = p1x - cx / 3; h1y = p1y - cy / 3;
            done = 1;
        }
        double mx = mid[2 * s], my = mid[2 * s + 1];
        /* leaving tangent at the start, arriving one at the end (they
         * differ at kept corners) */
        double t0x = -nout[2 * a + 1], t0y = nout[2 * a], t1x = -nin[2 * b + 1], t1y = nin[2 * b];
        /* orient the tangents along the chord */
        if (t0x * cx + t0y * cy < 0) { t0x = -t0x; t0y = -t0y; }
        if (t1x * cx + t1y * cy < 0) { t1x = -t1x; t1y = -t1y; }
        double l0 = hypot(t0x, t0y), l1 = hypot(t1x, t1y);
        if (l0 > 0) { t0x /= l0; t0y /= l0; }
        if (l1 > 0) { t1x /= l1; t1y /= l1; }
        if (!done && l0 > 0 && l1 > 0 && chord > 0) {
            /* p0 + a t0 = p1 - b t1  ->  a t0 + b t1 = p1 - p0 */
            double det = t0x * t1y - t0y * t1x;
            if (fabs(det) > 1e-12) {
                double aa = (cx * t1y - cy * t1x) / det;
                double bb = (t0x * cy - t0y * cx) / det;
                if (aa > 0 && bb > 0 && aa < 4 * chord && bb < 4 * chord) {
                    double Cx = p0x + aa * t0x, Cy = p0y + aa * t0y;
                    double Mx = 0.5 * (p0x + p1x), My = 0.5 * (p0y + p1y);
                    double dcm = hypot(Cx - Mx, Cy - My);
                    double sfac = dcm > 0 ? hypot(mx - Mx, my - My) / dcm : 0.5;
                    if (sfac > 1.0) sfac = 1.0;
                    double k = 4.0 / 3.0 * sfac;
                    h0x = p0x + k * (Cx - p0x); h0y = p0y + k * (Cy - p0y);
                    h1x = p1x + k * (Cx - p1x); h1y = p1y + k * (Cy - p1y);
                    done = 1;
                }
            }
        }
        if (!done) {
            /* a third of the chord along the (unit) tangents, or along the
             * chord itself where a tangent is missing */
            double c3 = chord / 3.0;
            if (l0 > 0 && l1 > 0) {
                h0x = p0x + c3 * t0x; h0y = p0y + c3 * t0y;
                h1x = p1x - c3 * t1x; h1y = p1y - c3 * t1y;
            } else {
                h0x = p0x + cx / 3; h0y = p0y + cy / 3;
                h1x = p1x - cx / 3; h1y = p1y - cy / 3;
            }
        }
        size_t ia = s, ib = (s + 1) % N;
        right[2 * ia] = h0x; right[2 * ia + 1] = h0y;
        left[2 * ib] = h1x; left[2 * ib + 1] = h1y;
    }
    /* open ends: mirror the one handle so the end tangent is kept */
    if (!closed && N >= 2) {
        left[0] = 2 * fxy[0] - right[0];
        left[1] = 2 * fxy[1] - right[1];
        size_t e = N - 1;
        right[2 * e] = 2 * fxy[2 * e] - left[2 * e];
        right[2 * e + 1] = 2 * fxy[2 * e + 1] - left[2 * e + 1];
    }
}

static int cx_parse_normal_method(const char *s, conica_normal_method *out)
{
    if (strcmp(s, "area") == 0) { *out = CONICA_NORMALS_AREA; return 1; }
    if (strcmp(s, "circle") == 0) { *out = CONICA_NORMALS_CIRCLE; return 1; }
    return 0;
}

PyDoc_STRVAR(subdivide_doc,
"subdivide(points, normals=None, *, dim=2, closed=False, levels=3, precise=False,\n"
"          estimate=False, normal_method='area', inflections=True, tangents=False,\n"
"          attrs=None, nattrs=0, handles=False, plane_tol=1e-6, abs_tol=0.0,\n"
"          stride=0, typecode='d',\n"
"          max_points=4194304, want_normals=True, precision=None)\n"
"--\n\n"
"Conic-preserving subdivision of one point-normal polygon (the CONIS paper, Section 1.1),\n"
"the bare scheme: no corners, the points and normals as given. Blender curves go\n"
"through curve(), which owns corners and the normals of drawn curves.\n\n"
"points: flat x,y (dim=2) or x,y,z (dim=3) values, a buffer of float32/float64\n"
"or any sequence of numbers. A 3D spline is processed in its best-fit plane;\n"
"it must be planar within plane_tol * size + abs_tol (NonPlanarError).\n"
"normals: one vector per point (dim values each) or None (estimated);\n"
"tangents=True: the vectors are tangents (direction of travel) and are turned\n"
"into normals in the plane.\n"
"attrs: nattrs values per point (radius, tilt, ...) interpolated onto the output.\n"
"handles=True also returns Bezier handles along the conic tangents.\n"
"stride > dim pads every output point with 1.0 (stride 4 = Blender's POLY 'co').\n"
"want_normals=False skips the output normals (None is returned for them).\n"
"precision: how far the input points may be from the curve they sample by\n"
"rounding (absolute); the scheme then reads no inflection and no turn into\n"
"that noise. None: float32 rounding when points is a float32 buffer\n"
"(array('f'), Blender's foreach_get), else 0 (exact).\n\n"
"Returns (points, normals, attrs or None, inflections, info) or, with handles=True,\n"
"(points, normals, attrs, inflections, info, left_handles, right_handles).\n"
"info is a dict: points, inflections, seconds (libcore), plane data.");

/* dim is 2 or 3 and stride (0: dim) between dim and 4: 1, or raise and 0. */
static int cx_check_layout(cx_state *S, int dim, int *stride)
{
    if (dim != 2 && dim != 3) {
        cx_raisef(S->arg_error, "dim must be 2 or 3, got %d", dim);
        return 0;
    }
    if (*stride == 0)
        *stride = dim;
    if (*stride < dim || *stride > 4) {
        cx_raisef(S->arg_error, "stride must be between dim (%d) and 4, got %d", dim, *stride);
        return 0;
    }
    return 1;
}

/* nattrs in 0..CX_MAX_ATTRS, given exactly when attrs is: 1, or raise and 0. */
static int cx_check_attrs(cx_state *S, PyObject *oattrs, int nattrs)
{
    if (nattrs < 0 || nattrs > CX_MAX_ATTRS) {
        cx_raisef(S->arg_error, "nattrs must be 0..%d, got %d", CX_MAX_ATTRS, nattrs);
        return 0;
    }
    if ((oattrs == Py_None) != (nattrs == 0)) {
        cx_raisef(S->arg_error, "attrs and nattrs > 0 go together");
        return 0;
    }
    return 1;
}

/* The plane fit refused the spline: raise and say so (1), or 0. */
static int cx_plane_refused(cx_state *S, int tiny, int nonplanar, const cx_plane *pl,
                            double plane_tol, double abs_tol)
{
    if (tiny) {
        cx_raisef(S->degenerate,
                  "spline is too small: its extent %.3g is below %.3g, the smallest "
                  "normal double", pl->extent, CX_MIN_PLANE_SIZE);
        return 1;
    }
    if (nonplanar) {
        cx_raisef(S->nonplanar,
                  "spline is not planar: its points are up to %.3g from their best-fit plane, "
                  "more than %.3g (%.3g of its size %.3g)",
                  pl->deviation, plane_tol * pl->size + abs_tol, plane_tol, pl->size);
        return 1;
    }
    return 0;
}

/* precision= of subdivide() and curve(): None leaves *out as it is, a
 * finite number >= 0 is stored; else raise and return 0. */
static int cx_read_precision(cx_state *S, PyObject *o, double *out)
{
    double v;
    if (o == Py_None)
        return 1;
    v = PyFloat_AsDouble(o);
    if (v == -1.0 && PyErr_Occurred())
        return 0;
    if (!isfinite(v) || v < 0) {
        cx_raisef(S->arg_error, "precision must be None or a finite number >= 0");
        return 0;
    }
    *out = v;
    return 1;
}

static PyObject *cx_subdivide(PyObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"points", "normals", "dim", "closed", "levels", "precise",
                             "estimate", "normal_method", "inflections", "tangents",
                             "attrs", "nattrs", "handles",
                             "plane_tol", "abs_tol", "stride", "typecode", "max_points",
                             "want_normals", "precision", NULL};
    cx_state *S = cx_get_state(self);
    PyObject *opoints, *onormals = Py_None, *oattrs = Py_None, *oprec = Py_None;
    PyObject *otype = NULL;
    int dim = 2, closed = 0, levels = 3, precise = 0, estimate = 0, inflections = 1;
    int tangents = 0, nattrs = 0, handles = 0, stride = 0, want_normals = 1;
    const char *method = "area";
    double plane_tol = 1e-6, abs_tol = 0.0;
    Py_ssize_t max_points = (Py_ssize_t)CX_DEFAULT_MAX_POINTS;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|O$ipippsppOipddiOnpO:subdivide", kwlist,
                                     &opoints, &onormals, &dim, &closed, &levels, &precise,
                                     &estimate, &method, &inflections, &tangents, &oattrs,
                                     &nattrs, &handles, &plane_tol, &abs_tol, &stride, &otype,
                                     &max_points, &want_normals, &oprec))
        return NULL;
    double precision = -1.0; /* None: from the points' storage, below */
    if (!cx_read_precision(S, oprec, &precision))
        return NULL;
    char typecode;
    if (!cx_typecode(S, otype, &typecode))
        return NULL;
    if (!cx_check_layout(S, dim, &stride))
        return NULL;
    if (levels < 0 || levels > CONICA_SUBDIV_MAX_LEVELS)
        return cx_raisef(S->limit_error, "levels must be 0..%d, got %d",
                         CONICA_SUBDIV_MAX_LEVELS, levels);
    if (max_points < 1 || (size_t)max_points > CX_HARD_MAX_POINTS)
        return cx_raisef(S->limit_error, "max_points must be 1..%zu, got %zd",
                         CX_HARD_MAX_POINTS, max_points);
    if (!cx_check_attrs(S, oattrs, nattrs))
        return NULL;
    if (!isfinite(plane_tol) || plane_tol < 0 || !isfinite(abs_tol) || abs_tol < 0)
        return cx_raisef(S->arg_error, "plane_tol and abs_tol must be finite and >= 0");
    conica_normal_method nm;
    if (!cx_parse_normal_method(method, &nm))
        return cx_raisef(S->arg_error, "normal_method must be 'area' or 'circle', got '%s'",
                         method);

    PyObject *result = NULL;
    double *pts = NULL, *nrm = NULL, *attrs = NULL;
    double *xy = NULL, *nin2 = NULL;
    double *fin_xy = NULL, *fin_n = NULL, *fin_attr = NULL, *hl = NULL, *hr = NULL;
    double *mids = NULL;
    double *o3 = NULL, *on3 = NULL, *hl3 = NULL, *hr3 = NULL;
    size_t *anchor = NULL;
    size_t npts_v = 0, nn = 0, na = 0;
    cx_job job;
    memset(&job, 0, sizeof job);
    conica_curve_init(&job.out);

    int f32 = cx_is_float32_buffer(opoints);
    if (!cx_read_doubles(opoints, "points", &pts, &npts_v))
        goto done;
    if (npts_v % (size_t)dim != 0) {
        cx_raisef(S->arg_error, "points: %zu values is not a multiple of dim=%d", npts_v, dim);
        goto done;
    }
    size_t n = npts_v / (size_t)dim;
    if (n < 2 || (closed && n < 3)) {
        cx_raisef(S->degenerate, "a%s curve needs at least %d points, got %zu",
                  closed ? " closed" : "n open", closed ? 3 : 2, n);
        goto done;
    }
    size_t bad = cx_first_nonfinite(pts, npts_v);
    if (bad < npts_v) {
        cx_raisef(S->nonfinite, "point %zu has a non-finite coordinate", bad / (size_t)dim);
        goto done;
    }
    if ((bad = cx_first_huge(pts, npts_v)) < npts_v) {
        cx_raisef(S->limit_error, "point %zu has a coordinate beyond +-%g", bad / (size_t)dim,
                  CX_MAX_ABS_COORD);
        goto done;
    }
    if (onormals != Py_None) {
        if (!cx_read_doubles(onormals, "normals", &nrm, &nn))
            goto done;
        if (nn != npts_v) {
            cx_raisef(S->arg_error, "normals: %zu values for %zu points of dim %d", nn, n, dim);
            goto done;
        }
        if ((bad = cx_first_nonfinite(nrm, nn)) < nn) {
            cx_raisef(S->nonfinite, "normal %zu is not finite", bad / (size_t)dim);
            goto done;
        }
    }
    if (nattrs > 0) {
        if (!cx_read_doubles(oattrs, "attrs", &attrs, &na))
            goto done;
        if (na != n * (size_t)nattrs) {
            cx_raisef(S->arg_error, "attrs: %zu values for %zu points x %d attributes", na, n,
                      nattrs);
            goto done;
        }
        if ((bad = cx_first_nonfinite(attrs, na)) < na) {
            cx_raisef(S->nonfinite, "attribute of point %zu is not finite", bad / (size_t)nattrs);
            goto done;
        }
    }
    int run_levels = levels + (handles ? 1 : 0);
    if (run_levels > CONICA_SUBDIV_MAX_LEVELS) {
        cx_raisef(S->limit_error, "levels %d (+1 for handles) exceed %d", levels,
                  CONICA_SUBDIV_MAX_LEVELS);
        goto done;
    }
    size_t expect = conica_subdiv_count(n, closed, run_levels);
    if (expect == 0 || expect > (size_t)max_points * (handles ? 2u : 1u) + 1) {
        cx_raisef(S->limit_error,
                  "%zu points at %d levels would give more than max_points=%zd points", n,
                  levels, max_points);
        goto done;
    }

    xy = malloc(2 * n * sizeof *xy);
    nin2 = nrm ? malloc(2 * n * sizeof *nin2) : NULL;
    if (xy == NULL || (nrm && nin2 == NULL)) {
        PyErr_NoMemory();
        goto done;
    }
    cx_plane pl;
    memset(&pl, 0, sizeof pl);
    conica_code rc = CONICA_OK;
    int nonplanar = 0, tiny = 0;
    Py_BEGIN_ALLOW_THREADS
    if (dim == 3) {
        cx_fit_plane(pts, n, &pl);
        if (pl.extent > 0.0 && pl.extent < CX_MIN_PLANE_SIZE) {
            tiny = 1; /* coincident points (extent 0) are libcore's to report */
        } else if (pl.deviation > plane_tol * pl.size + abs_tol) {
            nonplanar = 1;
        } else {
            cx_to_plane(&pl, pts, n, xy, 0);
            if (nrm)
                cx_to_plane(&pl, nrm, n, nin2, 1);
        }
    } else {
        memcpy(xy, pts, 2 * n * sizeof *xy);
        if (nrm)
            memcpy(nin2, nrm, 2 * n * sizeof *nin2);
    }
    if (!nonplanar && !tiny && tangents && nin2) {
        /* tangent (tx, ty) -> normal (ty, -tx): right of the direction of
         * travel, libcore's orientation (curve.h) */
        for (size_t i = 0; i < n; i++) {
            double tx = nin2[2 * i], ty = nin2[2 * i + 1];
            nin2[2 * i] = ty;
            nin2[2 * i + 1] = -tx;
        }
    }
    if (!nonplanar && !tiny) {
        job.n = n;
        job.closed = closed;
        job.xy = xy;
        job.nrm = nin2;
        job.set = conica_subdiv_defaults();
        job.set.levels = run_levels;
        job.set.precise = precise;
        job.set.estimate_normals = estimate || nrm == NULL;
        job.set.normal_method = nm;
        job.set.insert_inflections = inflections;
        if (precision >= 0) {
            job.set.noise = precision;
        } else if (f32) {
            double max_abs = 0.0;
            for (size_t i = 0; i < npts_v; i++)
                max_abs = fabs(pts[i]) > max_abs ? fabs(pts[i]) : max_abs;
            job.set.noise = conica_path_float32_precision(max_abs);
        }
        job.set.max_points = (size_t)max_points * (handles ? 2u : 1u) + 1;
        /* The GIL is released: use the cores (libcore splits a level's edges
         * only when each thread gets enough of them, and its results are
         * bit-identical for any thread count). */
        {
#ifdef _WIN32
            SYSTEM_INFO si;
            GetSystemInfo(&si);
            long ncpu = (long)si.dwNumberOfProcessors;
#else
            long ncpu = sysconf(_SC_NPROCESSORS_ONLN);
#endif
            job.set.threads = ncpu > 1 ? (int)(ncpu < 8 ? ncpu : 8) : 1;
        }
        rc = cx_run(&job);
    }
    Py_END_ALLOW_THREADS
    if (cx_plane_refused(S, tiny, nonplanar, &pl, plane_tol, abs_tol))
        goto done;
    if (rc != CONICA_OK) {
        cx_raise(S, rc, &job.st);
        goto done;
    }

    /* Decimate when one extra level was run for the handles. */
    size_t N = job.out.n;
    size_t F = N;
    if (handles) {
        /* the even points are the result, the odd ones the midpoints */
        N = closed ? F / 2 : (F + 1) / 2;
        fin_xy = malloc(2 * N * sizeof *fin_xy);
        fin_n = malloc(2 * N * sizeof *fin_n);
        mids = malloc(2 * N * sizeof *mids);
        hl = malloc(2 * N * sizeof *hl);
        hr = malloc(2 * N * sizeof *hr);
        if (!fin_xy || !fin_n || !mids || !hl || !hr) {
            PyErr_NoMemory();
            goto done;
        }
        for (size_t i = 0; i < N; i++) {
            memcpy(fin_xy + 2 * i, job.out.xy + 4 * i, 2 * sizeof(double));
            memcpy(fin_n + 2 * i, job.out.nxy + 4 * i, 2 * sizeof(double));
            if (2 * i + 1 < F)
                memcpy(mids + 2 * i, job.out.xy + 4 * i + 2, 2 * sizeof(double));
        }
        cx_handles(fin_xy, fin_n, fin_n, mids, NULL, N, closed, hl, hr);
    }
    const double *rxy = handles ? fin_xy : job.out.xy;
    const double *rn = handles ? fin_n : job.out.nxy;
    anchor = malloc((n + 1) * sizeof *anchor);
    if (anchor == NULL) {
        PyErr_NoMemory();
        goto done;
    }
    if (!cx_find_anchors(xy, n, closed, rxy, N, anchor)) {
        cx_raisef(S->numeric, "could not find the input vertices in the output");
        goto done;
    }
    if (nattrs > 0) {
        fin_attr = malloc((N ? N : 1) * (size_t)nattrs * sizeof *fin_attr);
        double *cum = malloc((N + 1) * sizeof *cum);
        if (fin_attr == NULL || cum == NULL) {
            free(cum);
            PyErr_NoMemory();
            goto done;
        }
        cx_interp_attrs(anchor, n, closed, attrs, nattrs, rxy, N, cum, fin_attr);
        free(cum);
    }
    if (dim == 3) {
        o3 = malloc(3 * N * sizeof *o3);
        on3 = malloc(3 * N * sizeof *on3);
        if (handles) {
            hl3 = malloc(3 * N * sizeof *hl3);
            hr3 = malloc(3 * N * sizeof *hr3);
        }
        if (!o3 || !on3 || (handles && (!hl3 || !hr3))) {
            PyErr_NoMemory();
            goto done;
        }
        cx_from_plane(&pl, rxy, N, o3, 0);
        if (want_normals)
            cx_from_plane(&pl, rn, N, on3, 1);
        if (handles) {
            cx_from_plane(&pl, hl, N, hl3, 0);
            cx_from_plane(&pl, hr, N, hr3, 0);
        }
        cx_restore_exact(pts, n, anchor, o3, N, hl3, hr3);
    }
    {
        /* inflection indices refer to the run output; map to the result */
        size_t keep = 0;
        for (size_t k = 0; k < job.ninflections; k++) {
            size_t v = job.inflections[k];
            if (handles) {
                if (v % 2)
                    continue;
                v /= 2;
            }
            job.inflections[keep++] = v;
        }
        job.ninflections = keep;
    }
    PyObject *ap = cx_make_array(S, typecode, dim == 3 ? o3 : rxy, N, dim, stride, 1.0);
    PyObject *an = want_normals ? cx_make_array(S, typecode, dim == 3 ? on3 : rn, N, dim, dim, 0.0)
                                : (Py_INCREF(Py_None), Py_None);
    PyObject *aa = nattrs > 0 ? cx_make_array(S, typecode, fin_attr, N, nattrs, nattrs, 0.0)
                              : (Py_INCREF(Py_None), Py_None);
    PyObject *infl = PyTuple_New((Py_ssize_t)job.ninflections);
    PyObject *info = Py_BuildValue(
        "{s:n,s:n,s:d,s:d,s:d,s:(ddd),s:(ddd)}", "points", (Py_ssize_t)N,
        "inflections", (Py_ssize_t)job.ninflections, "seconds",
        job.seconds, "plane_deviation", pl.deviation, "size", pl.size, "plane_origin",
        pl.origin[0], pl.origin[1], pl.origin[2], "plane_normal", pl.normal[0], pl.normal[1],
        pl.normal[2]);
    PyObject *al = NULL, *ar = NULL;
    if (handles) {
        al = cx_make_array(S, typecode, dim == 3 ? hl3 : hl, N, dim, dim, 0.0);
        ar = cx_make_array(S, typecode, dim == 3 ? hr3 : hr, N, dim, dim, 0.0);
    }
    int ok = ap && an && aa && infl && info && (!handles || (al && ar));
    for (size_t k = 0; ok && k < job.ninflections; k++) {
        PyObject *ik = PyLong_FromSize_t(job.inflections[k]);
        /* PyTuple_SetItem steals ik, also when it fails */
        ok = ik != NULL && PyTuple_SetItem(infl, (Py_ssize_t)k, ik) == 0;
    }
    if (ok) {
        if (handles)
            result = PyTuple_Pack(7, ap, an, aa, infl, info, al, ar);
        else
            result = PyTuple_Pack(5, ap, an, aa, infl, info);
    }
    Py_XDECREF(ap);
    Py_XDECREF(an);
    Py_XDECREF(aa);
    Py_XDECREF(infl);
    Py_XDECREF(info);
    Py_XDECREF(al);
    Py_XDECREF(ar);

done:
    PyMem_Free(pts);
    PyMem_Free(nrm);
    PyMem_Free(attrs);
    free(xy);
    free(nin2);
    conica_curve_free(&job.out);
    free(job.inflections);
    free(fin_xy);
    free(fin_n);
    free(mids);
    free(fin_attr);
    free(hl);
    free(hr);
    free(o3);
    free(on3);
    free(hl3);
    free(hr3);
    free(anchor);
    return result;
}

/* ------------------------------------------------------------ plotting */

/*
 * Parameters of the plotted points. The plotter reports points, not
 * parameters; its vertices lie on the curve and come in parameter order, so
 * each one is found again: the nearest of a dense sampling (32 per knot
 * span) at or after the previous point's sample, then Newton steps on
 * f(t) = C'(t).(C(t) - q) inside the neighbouring samples. The ends are the
 * domain ends. Needed for the exact tangents and the attributes.
 */
#define CX_SAMPLES_PER_SPAN 32

static conica_code cx_plot_params(const conica_bspline *sp, const double *pts, int dim, size_t N,
                                  double *params, conica_status *st)
{
    if (sp->dim == 1) { /* a function plots as (t, f(t)): the parameter is x */
        for (size_t i = 0; i < N; i++)
            params[i] = pts[i * (size_t)dim];
        return CONICA_OK;
    }
    double a, b;
    conica_bspline_domain(sp, &a, &b);
    size_t spans = 0;
    for (size_t i = (size_t)sp->degree; i < sp->n; i++)
        if (sp->knots[i + 1] > sp->knots[i])
            spans++;
    size_t M = spans * CX_SAMPLES_PER_SPAN + 1;
    double *ts = malloc(M * sizeof *ts), *ps = malloc(M * (size_t)dim * sizeof *ps);
    if (ts == NULL || ps == NULL) {
        free(ts);
        free(ps);
        return CONICA_ERR_NOMEM;
    }
    size_t m = 0;
    for (size_t i = (size_t)sp->degree; i < sp->n; i++) {
        double k0 = sp->knots[i], k1 = sp->knots[i + 1];
        if (!(k1 > k0))
            continue;
        for (int j = 0; j < CX_SAMPLES_PER_SPAN; j++)
            ts[m++] = k0 + (k1 - k0) * (double)j / CX_SAMPLES_PER_SPAN;
    }
    ts[m++] = b;
    conica_code rc = CONICA_OK;
    for (size_t j = 0; j < m && rc == CONICA_OK; j++)
        rc = conica_bspline_eval(sp, ts[j], ps + j * (size_t)dim, st);
    size_t jprev = 0;
    for (size_t i = 0; i < N && rc == CONICA_OK; i++) {
        const double *q = pts + i * (size_t)dim;
        if (i == 0 || i + 1 == N) {
            params[i] = i == 0 ? a : b;
            continue;
        }
        size_t best = jprev;
        double bd = INFINITY;
        for (size_t j = jprev; j < m; j++) {
            double d2 = 0.0;
            for (int k = 0; k < dim; k++) {
                double d = ps[j * (size_t)dim + (size_t)k] - q[k];
                d2 += d * d;
            }
            if (d2 < bd) {
                bd = d2;
                best = j;
            }
        }
        double lo = ts[best > 0 ? best - 1 : 0], hi = ts[best + 1 < m ? best + 1 : m - 1];
        double t = ts[best];
        for (int it = 0; it < 12 && rc == CONICA_OK; it++) {
            double c0[3], c1[3], c2[3] = {0, 0, 0};
            rc = conica_bspline_eval(sp, t, c0, st);
            if (rc == CONICA_OK)
                rc = conica_bspline_eval_deriv(sp, t, 1, c1, st);
            if (rc == CONICA_OK && sp->degree >= 2)
                rc = conica_bspline_eval_deriv(sp, t, 2, c2, st);
            if (rc != CONICA_OK)
                break;
            double f = 0.0, fp = 0.0;
            for (int k = 0; k < dim; k++) {
                double d = c0[k] - q[k];
                f += c1[k] * d;
                fp += c2[k] * d + c1[k] * c1[k];
            }
            if (!(fp > 0))
                break;
            double tn = t - f / fp;
            if (tn < lo) tn = lo;
            if (tn > hi) tn = hi;
            if (tn == t)
                break;
            t = tn;
        }
        params[i] = t;
        jprev = best;
    }
    free(ts);
    free(ps);
    return rc;
}

/* Attributes (radius, tilt): spline functions with the curve's knots and
 * weights, evaluated at the plotted points' parameters. */
static conica_code cx_plot_attrs(int degree, const double *knots, size_t nknots,
                                 const double *attrs, int nattrs, size_t n, const double *w,
                                 const double *params, size_t N, double *out, conica_status *st)
{
    conica_bspline fs;
    conica_bspline_init(&fs);
    double *col = malloc((n ? n : 1) * sizeof *col);
    if (col == NULL)
        return CONICA_ERR_NOMEM;
    conica_code rc = CONICA_OK;
    for (int q = 0; q < nattrs && rc == CONICA_OK; q++) {
        for (size_t i = 0; i < n; i++)
            col[i] = attrs[i * (size_t)nattrs + (size_t)q];
        rc = conica_bspline_set(degree, 1, knots, nknots, col, n, w, &fs, st);
        for (size_t i = 0; i < N && rc == CONICA_OK; i++) {
            double v[2];
            rc = conica_bspline_eval(&fs, params[i], v, st);
            out[i * (size_t)nattrs + (size_t)q] = v[0];
        }
        conica_bspline_free(&fs);
    }
    free(col);
    return rc;
}

PyDoc_STRVAR(plot_doc,
"plot(ctrl, *, dim=3, degree, knots, weights=None, tolerance, attrs=None, nattrs=0,\n"
"     typecode='d', max_points=4194304, tangents=False)\n"
"    -> (points, attrs or None, info) or, with tangents=True,\n"
"       (points, attrs or None, info, tangents, params)\n"
"--\n\n"
"Plot a (rational) B-spline with libconica's guaranteed adaptive plotter\n"
"(after Dahl's thesis): the polyline stays within `tolerance` (absolute, curve units)\n"
"of the curve over the domain [knots[degree], knots[n]]. ctrl holds n\n"
"points of dim values, knots n + degree + 1 values, weights n positive values\n"
"or None. attrs (nattrs values per control point, e.g. radius and tilt) are\n"
"evaluated as a spline function with the same knots at the output points.\n"
"tangents=True also returns the curve's first derivative at each point and the\n"
"points' parameters (recovered by projection: the plotter reports points only).\n"
"info: dict with points and knots_inserted.");

static PyObject *cx_plot(PyObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"ctrl", "dim", "degree", "knots", "weights", "tolerance",
                             "attrs", "nattrs", "typecode", "max_points", "tangents", NULL};
    cx_state *S = cx_get_state(self);
    PyObject *octrl, *oknots = NULL, *ow = Py_None, *oattrs = Py_None, *otype = NULL;
    int dim = 3, degree = -1, nattrs = 0, want_tan = 0;
    double tol = -1.0;
    Py_ssize_t max_points = (Py_ssize_t)CX_DEFAULT_MAX_POINTS;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|$iiOOdOiOnp:plot", kwlist, &octrl, &dim,
                                     &degree, &oknots, &ow, &tol, &oattrs, &nattrs, &otype,
                                     &max_points, &want_tan))
        return NULL;
    char typecode;
    if (!cx_typecode(S, otype, &typecode))
        return NULL;
    if (dim < 1 || dim > 3)
        return cx_raisef(S->arg_error, "dim must be 1, 2 or 3, got %d", dim);
    if (degree < 1)
        return cx_raisef(S->arg_error, "degree must be given and >= 1, got %d", degree);
    if (!(tol > 0) || !isfinite(tol))
        return cx_raisef(S->arg_error, "tolerance must be a positive finite number");
    if (max_points < 2 || (size_t)max_points > CX_HARD_MAX_POINTS)
        return cx_raisef(S->limit_error, "max_points must be 2..%zu, got %zd",
                         CX_HARD_MAX_POINTS, max_points);
    if (!cx_check_attrs(S, oattrs, nattrs))
        return NULL;
    if (oknots == NULL)
        return cx_raisef(S->arg_error, "knots must be given");

    PyObject *result = NULL;
    double *ctrl = NULL, *knots = NULL, *w = NULL, *attrs = NULL, *oatt = NULL;
    double *params = NULL, *tans = NULL;
    size_t nc = 0, nk = 0, nw = 0, na = 0;
    conica_bspline sp;
    conica_bspline_init(&sp);
    conica_polyline pl;
    conica_polyline_init(&pl);
    conica_status st;
    memset(&st, 0, sizeof st);
    if (!cx_read_doubles(octrl, "ctrl", &ctrl, &nc) ||
        !cx_read_doubles(oknots, "knots", &knots, &nk))
        goto done;
    if (ow != Py_None && !cx_read_doubles(ow, "weights", &w, &nw))
        goto done;
    if (nattrs > 0 && !cx_read_doubles(oattrs, "attrs", &attrs, &na))
        goto done;
    if (nc % (size_t)dim != 0) {
        cx_raisef(S->arg_error, "ctrl: %zu values is not a multiple of dim=%d", nc, dim);
        goto done;
    }
    size_t n = nc / (size_t)dim;
    if (n < (size_t)degree + 1) {
        cx_raisef(S->degenerate, "a degree-%d spline needs at least %zu control points, got %zu",
                  degree, (size_t)degree + 1, n); /* degree + 1 overflows int at INT_MAX */
        goto done;
    }
    if (nk != n + (size_t)degree + 1) {
        cx_raisef(S->arg_error, "knots: %zu values, a degree-%d spline with %zu control "
                  "points needs %zu", nk, degree, n, n + (size_t)degree + 1);
        goto done;
    }
    if (w && nw != n) {
        cx_raisef(S->arg_error, "weights: %zu values for %zu control points", nw, n);
        goto done;
    }
    if (attrs && na != n * (size_t)nattrs) {
        cx_raisef(S->arg_error, "attrs: %zu values for %zu points x %d attributes", na, n,
                  nattrs);
        goto done;
    }
    if (attrs && cx_first_nonfinite(attrs, na) < na) {
        cx_raisef(S->nonfinite, "attrs: non-finite value");
        goto done;
    }
    conica_code rc;
    Py_BEGIN_ALLOW_THREADS
    rc = conica_bspline_set(degree, dim, knots, nk, ctrl, n, w, &sp, &st);
    if (rc == CONICA_OK) {
        conica_plot_settings set = conica_plot_defaults();
        set.method = CONICA_PLOT_GUARANTEED;
        set.abs_tolerance = tol;
        set.max_points = (size_t)max_points;
        conica_plot_stats stats;
        memset(&stats, 0, sizeof stats);
        rc = conica_plot(&sp, &set, &pl, &stats, &st);
    }
    if (rc == CONICA_OK && (attrs || want_tan)) {
        params = malloc((pl.n ? pl.n : 1) * sizeof *params);
        rc = params ? cx_plot_params(&sp, pl.xy, pl.dim, pl.n, params, &st) : CONICA_ERR_NOMEM;
    }
    if (rc == CONICA_OK && attrs) {
        oatt = malloc((pl.n ? pl.n : 1) * (size_t)nattrs * sizeof *oatt);
        rc = oatt ? cx_plot_attrs(degree, knots, nk, attrs, nattrs, n, w, params, pl.n, oatt, &st)
                  : CONICA_ERR_NOMEM;
    }
    if (rc == CONICA_OK && want_tan) {
        tans = malloc((pl.n ? pl.n : 1) * (size_t)pl.dim * sizeof *tans);
        if (tans == NULL)
            rc = CONICA_ERR_NOMEM;
        for (size_t i = 0; i < pl.n && rc == CONICA_OK; i++) {
            double *ti = tans + i * (size_t)pl.dim;
            if (sp.dim == 1) { /* graph (t, f(t)): tangent (1, f'(t)) */
                ti[0] = 1.0;
                rc = conica_bspline_eval_deriv(&sp, params[i], 1, ti + 1, &st);
            } else {
                rc = conica_bspline_eval_deriv(&sp, params[i], 1, ti, &st);
            }
        }
    }
    Py_END_ALLOW_THREADS
    if (rc != CONICA_OK) {
        cx_raise(S, rc, &st);
        goto done;
    }
    {
        PyObject *ap = cx_make_array(S, typecode, pl.xy, pl.n, pl.dim, pl.dim, 0.0);
        PyObject *aa = attrs ? cx_make_array(S, typecode, oatt, pl.n, nattrs, nattrs, 0.0)
                             : (Py_INCREF(Py_None), Py_None);
        PyObject *info = Py_BuildValue("{s:n,s:n}", "points", (Py_ssize_t)pl.n, "pieces",
                                       (Py_ssize_t)pl.npieces);
        PyObject *at = NULL, *apar = NULL;
        if (want_tan) {
            at = cx_make_array(S, typecode, tans, pl.n, pl.dim, pl.dim, 0.0);
            apar = cx_make_array(S, 'd', params, pl.n, 1, 1, 0.0);
        }
        if (ap && aa && info && (!want_tan || (at && apar)))
            result = want_tan ? PyTuple_Pack(5, ap, aa, info, at, apar)
                              : PyTuple_Pack(3, ap, aa, info);
        Py_XDECREF(ap);
        Py_XDECREF(aa);
        Py_XDECREF(info);
        Py_XDECREF(at);
        Py_XDECREF(apar);
    }
done:
    PyMem_Free(ctrl);
    PyMem_Free(knots);
    PyMem_Free(w);
    PyMem_Free(attrs);
    free(oatt);
    free(params);
    free(tans);
    conica_bspline_free(&sp);
    conica_polyline_free(&pl);
    return result;
}

/* ------------------------------------------------------------ curves (path.h) */

/*
 * Blender splines through libcore's curve front end (conica/path.h): BEZIER
 * and NURBS splines are drawn curves (their segments, or the Bezier pieces
 * of the NURBS), POLY splines samples to interpolate. path.h owns every
 * rule about them (corners, tangents at joins, straight segments, the
 * fidelity to the drawn curve); this only puts a spline into its plane,
 * hands it over, and carries radius and tilt, exact anchors and the Bezier
 * handles of the result back.
 */
#define CX_PATH_MAX_LEVELS 16 /* conica_path_settings.levels: 0..16 */
/* path.h's default corner angle in radians (curve()'s corner_angle). */
#define CX_CORNER_ANGLE (CONICA_PATH_DEFAULT_CORNER_DEG * M_PI / 180.0)
#define CX_NONE SIZE_MAX

typedef enum cx_kind { CX_BEZIER, CX_NURBS, CX_POLY } cx_kind;

typedef struct cx_curve_job {
    /* inputs, in plane coordinates */
    cx_kind kind;
    size_t n;
    int closed, smooth, handles;
    int normals; /* the caller wants onxy (else it stays NULL: less memory) */
    const double *xy, *hl, *hr; /* 2n each; hl, hr: BEZIER only */
    const double *w;            /* NURBS: n weights or NULL */
    const double *knots;        /* NURBS: n + degree + 1 */
    size_t nknots;
    int degree;
    const double *attrs;        /* n * nattrs */
    int nattrs;
    conica_path_settings set;
    /* outputs, in plane coordinates (a closed POLY result is rotated to
     * start at input point 0) */
    size_t N;
    double *oxy, *onxy, *oattr, *ohl, *ohr;
    size_t *exact;              /* N: the input point an output point is, or CX_NONE */
    conica_path_result res;
    double seconds;
    conica_status st;
} cx_curve_job;

static conica_code cx_fail(conica_status *st, conica_code code, const char *msg)
{
    st->code = code;
    snprintf(st->message, sizeof st->message, "%s", msg);
    return code;
}

/* The spline as a one-subpath path: Bezier segment i (anchors i, i+1)
 * tagged i; the Bezier pieces of a NURBS; the points of a POLY spline.
 * *s_end: the segments drawn before conica_path_close (which may add a
 * straight closing edge). */
static conica_code cx_build_path(const cx_curve_job *j, conica_path *p, conica_bspline *bs,
                                 size_t *s_end, conica_status *st)
{
    conica_code rc = CONICA_OK;
    *s_end = 0;
    if (j->kind == CX_POLY)
        return conica_path_samples(p, j->xy, NULL, j->n, j->closed, 0, st);
    if (j->kind == CX_NURBS) {
        rc = conica_bspline_set(j->degree, 2, j->knots, j->nknots, j->xy, j->n, j->w, bs, st);
        if (rc == CONICA_OK)
            rc = conica_path_bspline(p, bs, 0, st);
    } else {
        size_t segs = j->closed ? j->n : j->n - 1;
        rc = conica_path_move_to(p, j->xy[0], j->xy[1], 0, st);
        for (size_t i = 0; i < segs && rc == CONICA_OK; i++) {
            size_t k = (i + 1) % j->n;
            double c[6] = {j->hr[2 * i], j->hr[2 * i + 1], j->hl[2 * k], j->hl[2 * k + 1],
                           j->xy[2 * k], j->xy[2 * k + 1]};
            rc = conica_path_bezier_to(p, 3, c, NULL, i, st);
        }
    }
    *s_end = p->nseg;
    if (rc == CONICA_OK && j->closed)
        rc = conica_path_close(p, st);
    return rc;
}

/* NURBS: the knot interval [ua, ub] of every path segment drawn from the
 * spline (s < s_end), found by matching its control points with the
 * spline's Bezier pieces in order (conica_path_bspline skips pieces of zero
 * size, so segment and piece indices may differ). */
static conica_code cx_piece_params(const conica_path *p, const conica_bspline *bs, size_t s_end,
                                   double *ua, double *ub, conica_status *st)
{
    conica_bspline bz;
    conica_bspline_init(&bz);
    conica_code rc = conica_bspline_to_bezier(bs, &bz, st);
    size_t nb = rc == CONICA_OK ? conica_bspline_bezier_count(&bz) : 0, k = 0;
    int d = bz.degree;
    double ctrl[2 * (CONICA_PATH_MAX_DEGREE + 1)];
    for (size_t s = 0; s < s_end && rc == CONICA_OK; s++) {
        const double *q = p->pt + 3 * p->seg[s].first;
        int found = 0;
        while (k < nb && !found && rc == CONICA_OK) {
            double a, b;
            rc = conica_bspline_bezier_piece(&bz, k++, ctrl, NULL, &a, &b, st);
            found = rc == CONICA_OK && p->seg[s].degree == d;
            for (int i = 1; i <= d && found; i++)
                if (ctrl[2 * i] != q[3 * i] || ctrl[2 * i + 1] != q[3 * i + 1])
                    found = 0;
            if (found) {
                ua[s] = a;
                ub[s] = b;
            }
        }
        if (rc == CONICA_OK && !found)
            rc = cx_fail(st, CONICA_ERR_NUMERIC, "a NURBS piece is missing from the path");
    }
    conica_bspline_free(&bz);
    return rc;
}

/* Unit normal (right of the direction of travel, libcore's side) of the
 * tangent drawn segment s arrives at its end with: towards its end from
 * the last control point that differs from it. */
static int cx_seg_end_normal(const conica_path *p, size_t s, double n[2])
{
    const double *q = p->pt + 3 * p->seg[s].first;
    int d = p->seg[s].degree;
    for (int i = d - 1; i >= 0; i--) {
        double tx = q[3 * d] - q[3 * i], ty = q[3 * d + 1] - q[3 * i + 1], l = hypot(tx, ty);
        if (l > 0) {
            n[0] = ty / l;
            n[1] = -tx / l;
            return 1;
        }
    }
    return 0;
}

/* Unit normal (libcore's side) of the chord from a to b; 0 if they coincide. */
static int cx_chord_normal(const double *a, const double *b, double n[2])
{
    double tx = b[0] - a[0], ty = b[1] - a[1], l = hypot(tx, ty);
    if (!(l > 0))
        return 0;
    n[0] = ty / l;
    n[1] = -tx / l;
    return 1;
}

static int cx_same2(const double *a, const double *b)
{
    return a[0] == b[0] && a[1] == b[1];
}

/*
 * Bezier handles of the result L (N points): the midpoint of every edge is
 * the point between its ends in F, the same path smoothed one level
 * further (the scheme is interpolatory: F holds L's points bit for bit, in
 * order, and one new point on each subdivided edge; a straight or
 * flattened edge has none). At corners each side keeps its own tangent:
 * the drawn segment's that arrives there (the path's normal is the leaving
 * side's), or for samples the first edge of F on each side.
 */
static conica_code cx_curve_handles(cx_curve_job *j, const conica_path *p,
                                    const conica_path_polyline *L,
                                    const conica_path_polyline *F, conica_status *st)
{
    size_t N = L->n, NF = F ? F->n : 0, segs = j->closed ? N : N - 1;
    size_t *pos = malloc(N * sizeof *pos);
    double *nin = malloc(2 * N * sizeof *nin), *nout = malloc(2 * N * sizeof *nout);
    double *mid = malloc(2 * N * sizeof *mid);
    unsigned char *has = calloc(N, 1);
    conica_code rc = CONICA_OK;
    if (!pos || !nin || !nout || !mid || !has) {
        rc = cx_fail(st, CONICA_ERR_NOMEM, "out of memory");
        goto out;
    }
    memcpy(nin, L->nxy, 2 * N * sizeof *nin);
    memcpy(nout, L->nxy, 2 * N * sizeof *nout);
    memset(mid, 0, 2 * N * sizeof *mid);
    if (F) {
        size_t b = 0;
        for (size_t k = 0; k < N; k++) {
            while (b < NF && !cx_same2(F->xy + 2 * b, L->xy + 2 * k))
                b++;
            if (b == NF) {
                rc = cx_fail(st, CONICA_ERR_NUMERIC,
                             "the handles' refinement lost a point of the result");
                goto out;
            }
            pos[k] = b++;
        }
        for (size_t s = 0; s < segs; s++) {
            size_t a = pos[s], e = s + 1 < N ? pos[s + 1] : NF + pos[0];
            if (e - a >= 2) { /* one point between (the middle one if more) */
                size_t m = (a + (e - a) / 2) % NF;
                memcpy(mid + 2 * s, F->xy + 2 * m, 2 * sizeof *mid);
                has[s] = 1;
            }
        }
    }
    for (size_t k = 0; k < N; k++) {
        if (!(L->flags[k] & CONICA_PATH_PT_CORNER))
            continue;
        if (j->kind != CX_POLY) {
            size_t s = L->seg[k];
            if (L->t[k] < 1.0 && k == 0 && j->closed) /* arrives by the last segment */
                s = p->sub[0].first + p->sub[0].n - 1;
            if (L->t[k] >= 1.0 || (k == 0 && j->closed))
                cx_seg_end_normal(p, s, nin + 2 * k);
        } else if (F) {
            size_t b = pos[k];
            if (b > 0 || j->closed)
                cx_chord_normal(F->xy + 2 * ((b + NF - 1) % NF), F->xy + 2 * b, nin + 2 * k);
            if (b + 1 < NF || j->closed)
                cx_chord_normal(F->xy + 2 * b, F->xy + 2 * ((b + 1) % NF), nout + 2 * k);
        }
    }
    cx_handles(L->xy, nin, nout, mid, has, N, j->closed, j->ohl, j->ohr);
out:
    free(pos);
    free(nin);
    free(nout);
    free(mid);
    free(has);
    return rc;
}

/* Radius, tilt, ...: linear in the segment parameter between the two
 * anchors (BEZIER) or samples (POLY) of the point's segment; NURBS: spline
 * functions with the curve's knots and weights at the point's parameter.
 * A column equal on every input point is copied without arithmetic. */
static conica_code cx_curve_attrs(cx_curve_job *j, const conica_path *p,
                                  const conica_path_polyline *L, const double *ua,
                                  const double *ub, size_t s_end, conica_status *st)
{
    size_t N = L->n, n = j->n, m = (size_t)j->nattrs;
    const double *A = j->attrs;
    if (j->kind == CX_NURBS) {
        double *par = malloc(N * sizeof *par), lo, hi;
        if (!par)
            return cx_fail(st, CONICA_ERR_NOMEM, "out of memory");
        lo = j->knots[j->degree];
        hi = j->knots[n];
        for (size_t k = 0; k < N; k++) {
            size_t s = L->seg[k];
            double u = s < s_end ? ua[s] + L->t[k] * (ub[s] - ua[s]) : hi;
            par[k] = u < lo ? lo : u > hi ? hi : u;
        }
        conica_code rc = cx_plot_attrs(j->degree, j->knots, j->nknots, A, j->nattrs, n, j->w,
                                       par, N, j->oattr, st);
        free(par);
        return rc;
    }
    for (size_t q = 0; q < m; q++) {
        size_t i = 1;
        while (i < n && A[i * m + q] == A[q])
            i++;
        for (size_t k = 0; k < N; k++) {
            size_t a, b, s = L->seg[k];
            if (i == n) { /* constant */
                j->oattr[k * m + q] = A[q];
                continue;
            }
            if (j->kind == CX_BEZIER) {
                a = p->seg[s].tag;
                b = (a + 1) % n;
            } else {
                const conica_path_subpath *sp = &p->sub[0];
                size_t next = s + 1 < sp->first + sp->n ? s + 1 : sp->first;
                a = p->smptag[s];
                b = p->smptag[next];
            }
            double t = L->t[k], v0 = A[a * m + q], v1 = A[b * m + q];
            j->oattr[k * m + q] = v0 == v1 ? v0 : (1.0 - t) * v0 + t * v1;
        }
    }
    return CONICA_OK;
}

/* Rotate the N items of `width` doubles in a so that item z comes first. */
static void cx_rotate(double *a, size_t N, size_t width, size_t z, double *tmp)
{
    if (a == NULL || z == 0)
        return;
    memcpy(tmp, a + z * width, (N - z) * width * sizeof *a);
    memcpy(tmp + (N - z) * width, a, z * width * sizeof *a);
    memcpy(a, tmp, N * width * sizeof *a);
}

/* Build the path, run the front end and collect the outputs. Runs without
 * the GIL (no Python calls in here). */
static conica_code cx_curve_run(cx_curve_job *j)
{
    conica_path p;
    conica_path_result fine;
    conica_bspline bs;
    double *ua = NULL, *ub = NULL;
    size_t s_end = 0;
    conica_status *st = &j->st;
    conica_path_init(&p);
    conica_path_result_init(&fine);
    conica_bspline_init(&bs);
    conica_code rc = cx_build_path(j, &p, &bs, &s_end, st);
    if (rc == CONICA_OK && j->kind == CX_NURBS && j->nattrs > 0) {
        ua = malloc((p.nseg ? p.nseg : 1) * sizeof *ua);
        ub = malloc((p.nseg ? p.nseg : 1) * sizeof *ub);
        rc = ua && ub ? cx_piece_params(&p, &bs, s_end, ua, ub, st)
                      : cx_fail(st, CONICA_ERR_NOMEM, "out of memory");
    }
    if (rc == CONICA_OK) {
        double t0 = cx_now();
        rc = j->smooth ? conica_path_smooth(&p, &j->set, &j->res, st)
                       : conica_path_flatten(&p, &j->set, &j->res, st);
        if (rc == CONICA_OK && j->handles && j->smooth) {
            conica_path_settings s2 = j->set;
            s2.levels++;
            s2.max_points = 2 * j->set.max_points + 1;
            rc = conica_path_smooth(&p, &s2, &fine, st);
        }
        j->seconds = cx_now() - t0;
    }
    const conica_path_polyline *L = rc == CONICA_OK && j->res.n == 1 ? &j->res.lines[0] : NULL;
    if (rc == CONICA_OK && (L == NULL || L->n < 2))
        rc = cx_fail(st, CONICA_ERR_DEGENERATE, "nothing is drawn: every segment has zero size");
    size_t N = L ? L->n : 0;
    if (rc == CONICA_OK) {
        j->N = N;
        j->oxy = malloc(2 * N * sizeof *j->oxy);
        j->onxy = j->normals ? malloc(2 * N * sizeof *j->onxy) : NULL;
        j->exact = malloc(N * sizeof *j->exact);
        j->oattr = j->nattrs ? malloc(N * (size_t)j->nattrs * sizeof *j->oattr) : NULL;
        j->ohl = j->handles ? malloc(2 * N * sizeof *j->ohl) : NULL;
        j->ohr = j->handles ? malloc(2 * N * sizeof *j->ohr) : NULL;
        if (!j->oxy || (j->normals && !j->onxy) || !j->exact || (j->nattrs && !j->oattr) ||
            (j->handles && (!j->ohl || !j->ohr)))
            rc = cx_fail(st, CONICA_ERR_NOMEM, "out of memory");
    }
    if (rc == CONICA_OK) {
        memcpy(j->oxy, L->xy, 2 * N * sizeof *j->oxy);
        if (j->onxy)
            memcpy(j->onxy, L->nxy, 2 * N * sizeof *j->onxy);
        /* output points that are input points, bit for bit in the plane */
        for (size_t k = 0; k < N; k++) {
            size_t s = L->seg[k], a = CX_NONE, b = CX_NONE;
            j->exact[k] = CX_NONE;
            if (!(L->flags[k] & CONICA_PATH_PT_VERTEX))
                continue;
            if (j->kind == CX_BEZIER) {
                a = p.seg[s].tag;
                b = (a + 1) % j->n;
            } else if (j->kind == CX_POLY) {
                a = p.smptag[s];
            } else {
                a = 0;
                b = j->n - 1;
            }
            if (a != CX_NONE && cx_same2(L->xy + 2 * k, j->xy + 2 * a))
                j->exact[k] = a;
            else if (b != CX_NONE && cx_same2(L->xy + 2 * k, j->xy + 2 * b))
                j->exact[k] = b;
        }
    }
    if (rc == CONICA_OK && j->nattrs > 0)
        rc = cx_curve_attrs(j, &p, L, ua, ub, s_end, st);
    if (rc == CONICA_OK && j->handles)
        rc = cx_curve_handles(j, &p, L, j->smooth ? &fine.lines[0] : NULL, st);
    if (rc == CONICA_OK && j->closed && j->kind == CX_POLY) {
        /* the samples of a closed POLY spline with corners come out from
         * its first corner on: start at input point 0 again */
        size_t z = 0;
        while (z < N && j->exact[z] != 0)
            z++;
        if (z > 0 && z < N) {
            size_t w = j->nattrs > 2 ? (size_t)j->nattrs : 2;
            double *tmp = malloc(N * w * sizeof *tmp);
            size_t *ex = malloc(N * sizeof *ex);
            if (!tmp || !ex) {
                rc = cx_fail(st, CONICA_ERR_NOMEM, "out of memory");
            } else {
                cx_rotate(j->oxy, N, 2, z, tmp);
                cx_rotate(j->onxy, N, 2, z, tmp);
                cx_rotate(j->oattr, N, (size_t)j->nattrs, z, tmp);
                cx_rotate(j->ohl, N, 2, z, tmp);
                cx_rotate(j->ohr, N, 2, z, tmp);
                for (size_t k = 0; k < N; k++)
                    ex[k] = j->exact[(k + z) % N];
                memcpy(j->exact, ex, N * sizeof *ex);
            }
            free(tmp);
            free(ex);
        }
    }
    free(ua);
    free(ub);
    conica_bspline_free(&bs);
    conica_path_result_free(&fine);
    conica_path_free(&p);
    return rc;
}

static int cx_parse_kind(const char *s, cx_kind *out)
{
    if (strcmp(s, "BEZIER") == 0) { *out = CX_BEZIER; return 1; }
    if (strcmp(s, "NURBS") == 0) { *out = CX_NURBS; return 1; }
    if (strcmp(s, "POLY") == 0) { *out = CX_POLY; return 1; }
    return 0;
}

/* Read an optional flat array of `want` values (want == 0: any length),
 * finite, beyond no CX_MAX_ABS_COORD when `coords`. Returns 0 with an
 * exception set on failure. */
static int cx_read_checked(cx_state *S, PyObject *obj, const char *what, size_t want, int coords,
                           double **out, size_t *n)
{
    if (!cx_read_doubles(obj, what, out, n))
        return 0;
    if (want && *n != want) {
        cx_raisef(S->arg_error, "%s: %zu values, %zu expected", what, *n, want);
        return 0;
    }
    size_t bad = cx_first_nonfinite(*out, *n);
    if (bad < *n) {
        cx_raisef(S->nonfinite, "%s: value %zu is non-finite", what, bad);
        return 0;
    }
    if (coords && (bad = cx_first_huge(*out, *n)) < *n) {
        cx_raisef(S->limit_error, "%s: value %zu is beyond +-%g", what, bad, CX_MAX_ABS_COORD);
        return 0;
    }
    return 1;
}

PyDoc_STRVAR(curve_doc,
"curve(kind, points, handles_left=None, handles_right=None, *, dim=3, closed=False,\n"
"      weights=None, degree=0, knots=None, mode='smooth', levels=3,\n"
"      corner_angle=CORNER_ANGLE, fidelity=REL_TOLERANCE, tolerance=0.0,\n"
"      precision=None, plane_tol=1e-6, abs_tol=0.0, attrs=None, nattrs=0,\n"
"      handles=False, stride=0, typecode='d', max_points=4194304, want_normals=False)\n"
"--\n\n"
"One Blender spline through libconica's curve front end (conica/path.h).\n\n"
"kind 'BEZIER': points are the anchors, handles_left/handles_right their handles;\n"
"segment i is the cubic (anchor i, right handle i, left handle i+1, anchor i+1),\n"
"closed adds the segment back to anchor 0. 'NURBS': points are the control\n"
"points of a B-spline of `degree` with `knots` (n + degree + 1) and optional\n"
"positive weights, drawn over its domain (a cyclic spline comes wrapped, as\n"
"Blender evaluates it). 'POLY': points to interpolate. Values are flat x,y,z\n"
"(dim=3) or x,y (dim=2); a 3D spline is processed in its best-fit plane and\n"
"must be planar within plane_tol * size + abs_tol (NonPlanarError).\n\n"
"mode 'smooth': conic-preserving subdivision (levels) whose limit curve stays\n"
"within the fidelity tolerance of a drawn curve; 'flatten': a polyline within\n"
"it. The tolerance is `tolerance` (absolute) if > 0, else fidelity times the\n"
"spline's size (bounding-box diagonal of its anchors and the handles that shape\n"
"it, or of its control points). Joins whose tangents turn by more than\n"
"corner_angle (radians; >= pi: none) stay corners. precision: how far the input\n"
"coordinates may be off (absolute); None: float32 rounding of the largest one.\n"
"attrs: nattrs values per input point (radius, tilt) carried to the output:\n"
"linear in the segment parameter (BEZIER, POLY), as spline functions with the\n"
"same knots and weights (NURBS). handles=True also returns Bezier handles along\n"
"the curve's tangents (corners keep each side's own). stride > dim pads every\n"
"output point with 1.0 (stride 4 = Blender's POLY 'co').\n\n"
"Returns (points, normals or None, attrs or None, info) or, with handles=True,\n"
"(points, normals, attrs, info, left_handles, right_handles). info: points,\n"
"corners, inflections, samples, refinements, fallbacks, deviation, tolerance,\n"
"precision, worst_ratio, seconds (libcore), size and plane data.");

static PyObject *cx_curve(PyObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"kind", "points", "handles_left", "handles_right", "dim",
                             "closed", "weights", "degree", "knots", "mode", "levels",
                             "corner_angle", "fidelity", "tolerance", "precision",
                             "plane_tol", "abs_tol", "attrs", "nattrs", "handles", "stride",
                             "typecode", "max_points", "want_normals", NULL};
    cx_state *S = cx_get_state(self);
    const char *kind_s, *mode = "smooth";
    PyObject *opoints, *ohl = Py_None, *ohr = Py_None, *ow = Py_None, *oknots = Py_None;
    PyObject *oprec = Py_None, *oattrs = Py_None, *otype = NULL;
    int dim = 3, closed = 0, degree = 0, levels = 3, nattrs = 0, handles = 0, stride = 0;
    int want_normals = 0;
    double corner_angle = CX_CORNER_ANGLE;
    double fidelity = CONICA_PATH_DEFAULT_REL_TOLERANCE, tolerance = 0.0, precision = 0.0;
    double plane_tol = 1e-6, abs_tol = 0.0;
    Py_ssize_t max_points = (Py_ssize_t)CX_DEFAULT_MAX_POINTS;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "sO|OO$ipOiOsidddOddOipiOnp:curve", kwlist,
                                     &kind_s, &opoints, &ohl, &ohr, &dim, &closed, &ow, &degree,
                                     &oknots, &mode, &levels, &corner_angle, &fidelity,
                                     &tolerance, &oprec, &plane_tol, &abs_tol, &oattrs, &nattrs,
                                     &handles, &stride, &otype, &max_points, &want_normals))
        return NULL;
    cx_kind kind;
    char typecode;
    if (!cx_parse_kind(kind_s, &kind))
        return cx_raisef(S->arg_error, "kind must be 'BEZIER', 'NURBS' or 'POLY', got '%s'",
                         kind_s);
    if (!cx_typecode(S, otype, &typecode))
        return NULL;
    int smooth = strcmp(mode, "smooth") == 0;
    if (!smooth && strcmp(mode, "flatten") != 0)
        return cx_raisef(S->arg_error, "mode must be 'smooth' or 'flatten', got '%s'", mode);
    if (!cx_check_layout(S, dim, &stride))
        return NULL;
    int top = CX_PATH_MAX_LEVELS - (handles ? 1 : 0);
    if (levels < 0 || levels > top)
        return cx_raisef(S->limit_error, "levels must be 0..%d%s, got %d", top,
                         handles ? " with handles" : "", levels);
    if (max_points < 2 || (size_t)max_points > CX_HARD_MAX_POINTS)
        return cx_raisef(S->limit_error, "max_points must be 2..%zu, got %zd",
                         CX_HARD_MAX_POINTS, max_points);
    if (!cx_check_attrs(S, oattrs, nattrs))
        return NULL;
    if (!isfinite(corner_angle) || corner_angle < 0)
        return cx_raisef(S->arg_error, "corner_angle must be a finite angle >= 0");
    if (!isfinite(tolerance) || tolerance < 0 ||
        (!(tolerance > 0) && !(isfinite(fidelity) && fidelity > 0)))
        return cx_raisef(S->arg_error, "fidelity must be a positive finite fraction (or give "
                         "a positive absolute tolerance)");
    if (!cx_read_precision(S, oprec, &precision))
        return NULL;
    if (!isfinite(plane_tol) || plane_tol < 0 || !isfinite(abs_tol) || abs_tol < 0)
        return cx_raisef(S->arg_error, "plane_tol and abs_tol must be finite and >= 0");
    if ((kind == CX_BEZIER) != (ohl != Py_None) || (kind == CX_BEZIER) != (ohr != Py_None))
        return cx_raisef(S->arg_error, "handles_left and handles_right go with kind 'BEZIER' "
                         "(and only with it)");
    if (kind != CX_NURBS && (ow != Py_None || oknots != Py_None || degree != 0))
        return cx_raisef(S->arg_error, "weights, degree and knots go with kind 'NURBS'");
    if (kind == CX_NURBS && (oknots == Py_None || degree < 1 || degree > CONICA_PATH_MAX_DEGREE))
        return cx_raisef(S->arg_error, "a NURBS needs knots and a degree of 1..%d, got %d",
                         CONICA_PATH_MAX_DEGREE, degree);

    PyObject *result = NULL;
    double *pts = NULL, *hl = NULL, *hr = NULL, *w = NULL, *knots = NULL, *attrs = NULL;
    double *xy = NULL, *hl2 = NULL, *hr2 = NULL, *shape = NULL;
    double *o3 = NULL, *on3 = NULL, *hl3 = NULL, *hr3 = NULL;
    size_t nv = 0, nh = 0, nw = 0, nk = 0, na = 0;
    cx_curve_job job;
    memset(&job, 0, sizeof job);
    conica_path_result_init(&job.res);

    if (!cx_read_checked(S, opoints, "points", 0, 1, &pts, &nv))
        goto done;
    if (nv % (size_t)dim != 0) {
        cx_raisef(S->arg_error, "points: %zu values is not a multiple of dim=%d", nv, dim);
        goto done;
    }
    size_t n = nv / (size_t)dim;
    size_t need = kind == CX_NURBS ? (size_t)degree + 1 : (kind == CX_POLY && closed) ? 3 : 2;
    if (n < need) {
        cx_raisef(S->degenerate, "a%s %s spline needs at least %zu points, has %zu",
                  closed ? " cyclic" : "n open", kind_s, need, n);
        goto done;
    }
    if (kind == CX_BEZIER &&
        (!cx_read_checked(S, ohl, "handles_left", nv, 1, &hl, &nh) ||
         !cx_read_checked(S, ohr, "handles_right", nv, 1, &hr, &nh)))
        goto done;
    if (kind == CX_NURBS) {
        if (!cx_read_checked(S, oknots, "knots", n + (size_t)degree + 1, 0, &knots, &nk))
            goto done;
        if (ow != Py_None && !cx_read_checked(S, ow, "weights", n, 0, &w, &nw))
            goto done;
        for (size_t i = 0; w && i < n; i++)
            if (!(w[i] > 0)) {
                cx_raisef(S->arg_error, "weights: weight %zu is not positive", i);
                goto done;
            }
    }
    if (nattrs > 0 && !cx_read_checked(S, oattrs, "attrs", n * (size_t)nattrs, 0, &attrs, &na))
        goto done;

    /* The points that shape the drawn curve (an open spline's outer handles
     * do not): they decide the plane, the size and the precision. */
    size_t nshape = n;
    if (kind == CX_BEZIER)
        nshape = closed ? 3 * n : 3 * n - 2;
    shape = malloc(nshape * (size_t)dim * sizeof *shape);
    xy = malloc(2 * n * sizeof *xy);
    if (kind == CX_BEZIER) {
        hl2 = malloc(2 * n * sizeof *hl2);
        hr2 = malloc(2 * n * sizeof *hr2);
    }
    if (!shape || !xy || (kind == CX_BEZIER && (!hl2 || !hr2))) {
        PyErr_NoMemory();
        goto done;
    }
    {
        size_t d = (size_t)dim, at = 0;
        memcpy(shape, pts, n * d * sizeof *shape);
        at = n;
        for (size_t i = 0; kind == CX_BEZIER && i < n; i++) {
            if (closed || i + 1 < n)
                memcpy(shape + d * at++, hr + d * i, d * sizeof *shape);
            if (closed || i > 0)
                memcpy(shape + d * at++, hl + d * i, d * sizeof *shape);
        }
    }
    cx_plane pl;
    memset(&pl, 0, sizeof pl);
    double max_abs = 0.0;
    for (size_t i = 0; i < nshape * (size_t)dim; i++)
        if (fabs(shape[i]) > max_abs)
            max_abs = fabs(shape[i]);
    conica_code rc = CONICA_OK;
    int nonplanar = 0, tiny = 0, coincide = 0;
    Py_BEGIN_ALLOW_THREADS
    if (dim == 3) {
        cx_fit_plane(shape, nshape, &pl);
        if (pl.extent == 0.0) {
            coincide = 1;
        } else if (pl.extent < CX_MIN_PLANE_SIZE) {
            tiny = 1;
        } else if (pl.deviation > plane_tol * pl.size + abs_tol) {
            nonplanar = 1;
        } else {
            cx_to_plane(&pl, pts, n, xy, 0);
            if (kind == CX_BEZIER) {
                cx_to_plane(&pl, hl, n, hl2, 0);
                cx_to_plane(&pl, hr, n, hr2, 0);
            }
        }
    } else {
        double lo[2] = {shape[0], shape[1]}, hi[2] = {shape[0], shape[1]};
        for (size_t i = 0; i < nshape; i++)
            for (int k = 0; k < 2; k++) {
                double v = shape[2 * i + (size_t)k];
                lo[k] = v < lo[k] ? v : lo[k];
                hi[k] = v > hi[k] ? v : hi[k];
            }
        pl.size = hypot(hi[0] - lo[0], hi[1] - lo[1]);
        pl.u[0] = pl.v[1] = pl.normal[2] = 1.0;
        coincide = !(hi[0] > lo[0]) && !(hi[1] > lo[1]);
        memcpy(xy, pts, 2 * n * sizeof *xy);
        if (kind == CX_BEZIER) {
            memcpy(hl2, hl, 2 * n * sizeof *hl2);
            memcpy(hr2, hr, 2 * n * sizeof *hr2);
        }
    }
    if (!nonplanar && !tiny && !coincide) {
        job.kind = kind;
        job.n = n;
        job.closed = closed;
        job.smooth = smooth;
        job.handles = handles;
        job.normals = want_normals;
        job.xy = xy;
        job.hl = hl2;
        job.hr = hr2;
        job.w = w;
        job.knots = knots;
        job.nknots = nk;
        job.degree = degree;
        job.attrs = attrs;
        job.nattrs = nattrs;
        job.set = conica_path_defaults();
        job.set.tolerance = tolerance > 0 ? tolerance : fidelity * pl.size;
        job.set.corner_angle = corner_angle;
        job.set.precision = oprec == Py_None ? conica_path_float32_precision(max_abs) : precision;
        job.set.levels = levels;
        job.set.max_points = (size_t)max_points;
        job.set.vertex_joins = kind == CX_BEZIER; /* every anchor a vertex */
        /* Conic Subdivide promises n 2^levels points (docs/blender.md) */
        job.set.exact_levels = 1;
        rc = cx_curve_run(&job);
    }
    if (rc == CONICA_OK && !nonplanar && !tiny && !coincide) {
        size_t N = job.N;
        if (dim == 3) {
            o3 = malloc(3 * N * sizeof *o3);
            on3 = want_normals ? malloc(3 * N * sizeof *on3) : NULL;
            hl3 = handles ? malloc(3 * N * sizeof *hl3) : NULL;
            hr3 = handles ? malloc(3 * N * sizeof *hr3) : NULL;
            if (!o3 || (want_normals && !on3) || (handles && (!hl3 || !hr3))) {
                rc = cx_fail(&job.st, CONICA_ERR_NOMEM, "out of memory");
            } else {
                cx_from_plane(&pl, job.oxy, N, o3, 0);
                if (on3)
                    cx_from_plane(&pl, job.onxy, N, on3, 1);
                if (handles) {
                    cx_from_plane(&pl, job.ohl, N, hl3, 0);
                    cx_from_plane(&pl, job.ohr, N, hr3, 0);
                }
                /* input points come back with their exact coordinates, and a
                 * coordinate every shaping point shares (z of a 2D curve)
                 * is set exactly everywhere */
                for (size_t k = 0; k < N; k++)
                    if (job.exact[k] != CX_NONE)
                        memcpy(o3 + 3 * k, pts + 3 * job.exact[k], 3 * sizeof *o3);
                for (size_t c = 0; c < 3; c++) {
                    size_t i = 1;
                    while (i < nshape && shape[3 * i + c] == shape[c])
                        i++;
                    for (size_t k = 0; i == nshape && k < N; k++) {
                        o3[3 * k + c] = shape[c];
                        if (handles) {
                            hl3[3 * k + c] = shape[c];
                            hr3[3 * k + c] = shape[c];
                        }
                    }
                }
            }
        }
    }
    Py_END_ALLOW_THREADS
    if (coincide) {
        cx_raisef(S->degenerate, "the spline's points coincide (its size is 0)");
        goto done;
    }
    if (cx_plane_refused(S, tiny, nonplanar, &pl, plane_tol, abs_tol))
        goto done;
    if (rc != CONICA_OK) {
        cx_raise(S, rc, &job.st);
        goto done;
    }
    {
        size_t N = job.N;
        const conica_path_result *R = &job.res;
        const conica_path_polyline *L = &R->lines[0];
        PyObject *ap = cx_make_array(S, typecode, dim == 3 ? o3 : job.oxy, N, dim, stride, 1.0);
        const double *rn = dim == 3 ? on3 : job.onxy;
        PyObject *an = want_normals ? cx_make_array(S, typecode, rn, N, dim, dim, 0.0)
                                    : (Py_INCREF(Py_None), Py_None);
        PyObject *aa = nattrs > 0 ? cx_make_array(S, typecode, job.oattr, N, nattrs, nattrs, 0.0)
                                  : (Py_INCREF(Py_None), Py_None);
        PyObject *info = Py_BuildValue(
            "{s:n,s:n,s:n,s:n,s:n,s:n,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:(ddd),s:(ddd)}", "points",
            (Py_ssize_t)N, "corners", (Py_ssize_t)R->corners, "inflections",
            (Py_ssize_t)R->inflections, "samples", (Py_ssize_t)R->samples, "refinements",
            (Py_ssize_t)R->refinements, "fallbacks", (Py_ssize_t)R->fallbacks, "deviation",
            L->deviation, "tolerance", job.set.tolerance, "precision", job.set.precision,
            "worst_ratio", R->worst_ratio, "seconds", job.seconds, "plane_deviation",
            pl.deviation, "size", pl.size, "plane_origin", pl.origin[0], pl.origin[1],
            pl.origin[2], "plane_normal", pl.normal[0], pl.normal[1], pl.normal[2]);
        PyObject *al = NULL, *ar = NULL;
        if (handles) {
            al = cx_make_array(S, typecode, dim == 3 ? hl3 : job.ohl, N, dim, dim, 0.0);
            ar = cx_make_array(S, typecode, dim == 3 ? hr3 : job.ohr, N, dim, dim, 0.0);
        }
        if (ap && an && aa && info && (!handles || (al && ar)))
            result = handles ? PyTuple_Pack(6, ap, an, aa, info, al, ar)
                             : PyTuple_Pack(4, ap, an, aa, info);
        Py_XDECREF(ap);
        Py_XDECREF(an);
        Py_XDECREF(aa);
        Py_XDECREF(info);
        Py_XDECREF(al);
        Py_XDECREF(ar);
    }
done:
    PyMem_Free(pts);
    PyMem_Free(hl);
    PyMem_Free(hr);
    PyMem_Free(w);
    PyMem_Free(knots);
    PyMem_Free(attrs);
    free(xy);
    free(hl2);
    free(hr2);
    free(shape);
    free(o3);
    free(on3);
    free(hl3);
    free(hr3);
    free(job.oxy);
    free(job.onxy);
    free(job.oattr);
    free(job.ohl);
    free(job.ohr);
    free(job.exact);
    conica_path_result_free(&job.res);
    return result;
}
/* ------------------------------------------------------------ plane fit API */

PyDoc_STRVAR(fit_plane_doc,
"fit_plane(points) -> (origin, normal, u, v, deviation, size)\n"
"--\n\n"
"Best-fit plane of flat x,y,z points (total least squares through the\n"
"centroid; smallest eigenvector of the 3x3 covariance by Jacobi rotations).\n"
"u, v span the plane (right-handed with normal); deviation is the largest\n"
"distance of a point from the plane, size the bounding-box diagonal.");

static PyObject *cx_fit_plane_py(PyObject *self, PyObject *arg)
{
    cx_state *S = cx_get_state(self);
    double *p;
    size_t nv;
    if (!cx_read_doubles(arg, "points", &p, &nv))
        return NULL;
    if (nv % 3 != 0 || nv == 0) {
        PyMem_Free(p);
        return cx_raisef(S->arg_error, "points: %zu values is not a positive multiple of 3", nv);
    }
    size_t bad = cx_first_nonfinite(p, nv);
    if (bad < nv) {
        PyMem_Free(p);
        return cx_raisef(S->nonfinite, "point %zu has a non-finite coordinate", bad / 3);
    }
    /* the covariance and the size overflow beyond this (NaN plane) */
    if ((bad = cx_first_huge(p, nv)) < nv) {
        PyMem_Free(p);
        return cx_raisef(S->limit_error, "point %zu has a coordinate beyond +-%g", bad / 3,
                         CX_MAX_ABS_COORD);
    }
    cx_plane pl;
    Py_BEGIN_ALLOW_THREADS
    cx_fit_plane(p, nv / 3, &pl);
    Py_END_ALLOW_THREADS
    PyMem_Free(p);
    if (pl.extent < CX_MIN_PLANE_SIZE)
        return cx_raisef(S->degenerate,
                         "no plane: the points' extent %.3g is below %.3g (coincident points)",
                         pl.extent, CX_MIN_PLANE_SIZE);
    {
        const double *all[] = {pl.origin, pl.normal, pl.u, pl.v};
        for (int q = 0; q < 4; q++)
            for (int k = 0; k < 3; k++)
                if (!isfinite(all[q][k]))
                    return cx_raisef(S->numeric, "the plane fit did not give a finite plane");
        if (!isfinite(pl.deviation) || !isfinite(pl.size))
            return cx_raisef(S->numeric, "the plane fit did not give a finite plane");
    }
    return Py_BuildValue("(ddd)(ddd)(ddd)(ddd)dd", pl.origin[0], pl.origin[1], pl.origin[2],
                         pl.normal[0], pl.normal[1], pl.normal[2], pl.u[0], pl.u[1], pl.u[2],
                         pl.v[0], pl.v[1], pl.v[2], pl.deviation, pl.size);
}

/* ------------------------------------------------------------ value scan */

PyDoc_STRVAR(scan_doc,
"scan(values, limit, positive=False) -> (index, max_abs)\n"
"--\n\n"
"One pass over flat values (a float buffer or a sequence of numbers). index:\n"
"the first value that is not finite, is beyond limit in magnitude or, with\n"
"positive=True, is not above 0; -1 if there is none. max_abs: the largest\n"
"magnitude before index (of all values when index is -1; 0.0 for none).\n"
"The add-on checks coordinates, weights, radii and tilts with it.");

static PyObject *cx_scan(PyObject *self, PyObject *args)
{
    cx_state *S = cx_get_state(self);
    PyObject *obj;
    double limit;
    int positive = 0;
    if (!PyArg_ParseTuple(args, "Od|p:scan", &obj, &limit, &positive))
        return NULL;
    if (isnan(limit) || limit < 0)
        return cx_raisef(S->arg_error, "limit must be a number >= 0 (inf: no limit)");
    double *v = NULL;
    size_t n = 0;
    if (!cx_read_doubles(obj, "values", &v, &n))
        return NULL;
    Py_ssize_t bad = -1;
    double m = 0.0;
    for (size_t i = 0; i < n; i++) {
        double a = fabs(v[i]);
        if (!isfinite(a) || a > limit || (positive && !(v[i] > 0))) {
            bad = (Py_ssize_t)i;
            break;
        }
        m = a > m ? a : m;
    }
    PyMem_Free(v);
    return Py_BuildValue("(nd)", bad, m);
}

/* ------------------------------------------------------------ module */

PyDoc_STRVAR(version_doc, "version() -> libcore's version string");

static PyObject *cx_version(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return PyUnicode_FromString(conica_version());
}

/* ------------------------------------------------------------ surface */

PyDoc_STRVAR(surface_doc,
"surface(ctrl, *, nu, nv, degree_u, degree_v, knots_u, knots_v, weights=None,\n"
"        tolerance, max_points=4194304)\n"
"--\n\n"
"A tensor-product NURBS surface plotted to a quad grid whose every quad is\n"
"certified by libconica: the surface and the quad (bilinear, or either of\n"
"its two triangles) are within `tolerance` (absolute) of each other, by a\n"
"convex-hull bound per cell. ctrl: nu*nv control points, x,y,z each,\n"
"index ((i*nv)+j)*3 (i along u); weights: nu*nv positive values or None;\n"
"knots_u: nu + degree_u + 1 values, knots_v likewise.\n\n"
"Returns (points, gu, gv, info): points an array('d') of gu*gv x,y,z grid\n"
"points, index ((i*gv)+j)*3, every one on the surface; info: points,\n"
"seconds, bound (the largest certified quad deviation).");

static PyObject *cx_surface(PyObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"ctrl", "nu", "nv", "degree_u", "degree_v", "knots_u",
                             "knots_v", "weights", "tolerance", "max_points", NULL};
    cx_state *S = cx_get_state(self);
    PyObject *octrl, *oku = NULL, *okv = NULL, *ow = Py_None;
    Py_ssize_t nu = -1, nv = -1, max_points = (Py_ssize_t)CX_DEFAULT_MAX_POINTS;
    int du = -1, dv = -1;
    double tol = -1.0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "O|$nniiOOOdn:surface", kwlist, &octrl, &nu,
                                     &nv, &du, &dv, &oku, &okv, &ow, &tol, &max_points))
        return NULL;
    if (nu < 2 || nv < 2)
        return cx_raisef(S->arg_error, "nu and nv must be given and >= 2, got %zd, %zd", nu,
                         nv);
    if (du < 1 || dv < 1)
        return cx_raisef(S->arg_error, "degree_u and degree_v must be given and >= 1");
    if (!(tol > 0) || !isfinite(tol))
        return cx_raisef(S->arg_error, "tolerance must be a positive finite number");
    if (max_points < 4 || (size_t)max_points > CX_HARD_MAX_POINTS)
        return cx_raisef(S->limit_error, "max_points must be 4..%zu, got %zd",
                         CX_HARD_MAX_POINTS, max_points);
    if (oku == NULL || okv == NULL)
        return cx_raisef(S->arg_error, "knots_u and knots_v must be given");

    PyObject *result = NULL;
    double *ctrl = NULL, *ku = NULL, *kv = NULL, *w = NULL;
    size_t nc = 0, nku = 0, nkv = 0, nw = 0;
    conica_bspline_surface sf;
    conica_bspline_surface_init(&sf);
    conica_quadgrid g;
    conica_quadgrid_init(&g);
    conica_status st;
    memset(&st, 0, sizeof st);
    if (!cx_read_checked(S, octrl, "ctrl", 0, 1, &ctrl, &nc) ||
        !cx_read_checked(S, oku, "knots_u", 0, 0, &ku, &nku) ||
        !cx_read_checked(S, okv, "knots_v", 0, 0, &kv, &nkv))
        goto done;
    if (ow != Py_None && !cx_read_checked(S, ow, "weights", 0, 0, &w, &nw))
        goto done;
    if ((size_t)nu > CX_MAX_INPUT_VALUES / 3 / (size_t)nv) {
        /* the product itself would overflow the message */
        cx_raisef(S->limit_error, "ctrl: %zd x %zd control points exceed the limit of %zu values",
                  nu, nv, (size_t)CX_MAX_INPUT_VALUES);
        goto done;
    }
    if (nc != 3 * (size_t)nu * (size_t)nv) {
        cx_raisef(S->arg_error, "ctrl: %zu values, %zd x %zd control points need %zu", nc, nu,
                  nv, 3 * (size_t)nu * (size_t)nv);
        goto done;
    }
    if (w && nw != (size_t)nu * (size_t)nv) {
        cx_raisef(S->arg_error, "weights: %zu values for %zd x %zd control points", nw, nu, nv);
        goto done;
    }
    conica_code rc;
    double seconds = 0.0, stats_bound = 0.0;
    Py_BEGIN_ALLOW_THREADS
    rc = conica_bspline_surface_set(du, dv, 3, ku, nku, kv, nkv, ctrl, (size_t)nu, (size_t)nv,
                                    w, &sf, &st);
    if (rc == CONICA_OK) {
        conica_plot_settings set = conica_plot_defaults();
        set.method = CONICA_PLOT_GUARANTEED;
        set.abs_tolerance = tol;
        set.max_points = (size_t)max_points;
        conica_plot_stats stats;
        memset(&stats, 0, sizeof stats);
        double t0 = cx_now();
        rc = conica_plot_surface_certified(&sf, &set, &g, &stats, &st);
        seconds = cx_now() - t0;
        stats_bound = stats.bound;
    }
    Py_END_ALLOW_THREADS
    if (rc != CONICA_OK) {
        cx_raise(S, rc, &st);
        goto done;
    }
    {
        PyObject *ap = cx_make_array(S, 'd', g.xyz, g.nu * g.nv, 3, 3, 0.0);
        PyObject *info = Py_BuildValue("{s:n,s:d,s:d}", "points",
                                       (Py_ssize_t)(g.nu * g.nv), "seconds", seconds, "bound",
                                       stats_bound);
        if (ap && info)
            result = Py_BuildValue("(OnnO)", ap, (Py_ssize_t)g.nu, (Py_ssize_t)g.nv, info);
        Py_XDECREF(ap);
        Py_XDECREF(info);
    }
done:
    PyMem_Free(ctrl);
    PyMem_Free(ku);
    PyMem_Free(kv);
    PyMem_Free(w);
    conica_bspline_surface_free(&sf);
    conica_quadgrid_free(&g);
    return result;
}

static PyMethodDef cx_methods[] = {
    {"subdivide", (PyCFunction)(void (*)(void))cx_subdivide, METH_VARARGS | METH_KEYWORDS,
     subdivide_doc},
    {"curve", (PyCFunction)(void (*)(void))cx_curve, METH_VARARGS | METH_KEYWORDS, curve_doc},
    {"plot", (PyCFunction)(void (*)(void))cx_plot, METH_VARARGS | METH_KEYWORDS, plot_doc},
    {"surface", (PyCFunction)(void (*)(void))cx_surface, METH_VARARGS | METH_KEYWORDS,
     surface_doc},
    {"fit_plane", cx_fit_plane_py, METH_O, fit_plane_doc},
    {"scan", cx_scan, METH_VARARGS, scan_doc},
    {"version", cx_version, METH_NOARGS, version_doc},
    {NULL, NULL, 0, NULL}};

static int cx_traverse(PyObject *m, visitproc visit, void *arg)
{
    cx_state *s = cx_get_state(m);
    Py_VISIT(s->error);
    Py_VISIT(s->arg_error);
    Py_VISIT(s->limit_error);
    Py_VISIT(s->degenerate);
    Py_VISIT(s->nonfinite);
    Py_VISIT(s->nonplanar);
    Py_VISIT(s->numeric);
    Py_VISIT(s->nomem);
    Py_VISIT(s->unsupported);
    Py_VISIT(s->array_type);
    return 0;
}

static int cx_clear(PyObject *m)
{
    cx_state *s = cx_get_state(m);
    Py_CLEAR(s->error);
    Py_CLEAR(s->arg_error);
    Py_CLEAR(s->limit_error);
    Py_CLEAR(s->degenerate);
    Py_CLEAR(s->nonfinite);
    Py_CLEAR(s->nonplanar);
    Py_CLEAR(s->numeric);
    Py_CLEAR(s->nomem);
    Py_CLEAR(s->unsupported);
    Py_CLEAR(s->array_type);
    return 0;
}

static void cx_free(void *m)
{
    cx_clear((PyObject *)m);
}

static struct PyModuleDef cx_module = {
    PyModuleDef_HEAD_INIT,
    "_conica",
    "Conic-preserving subdivision and adaptive spline plotting (libconica) for Blender.",
    sizeof(cx_state),
    cx_methods,
    NULL,
    cx_traverse,
    cx_clear,
    cx_free};

/* Create `name` deriving from ConicaError and `builtin`, add it to m. */
static PyObject *cx_add_exc(PyObject *m, const char *name, PyObject *base, PyObject *builtin,
                            const char *doc)
{
    char full[96];
    snprintf(full, sizeof full, "_conica.%s", name);
    PyObject *bases = builtin ? PyTuple_Pack(2, base, builtin) : PyTuple_Pack(1, base);
    if (bases == NULL)
        return NULL;
    PyObject *e = PyErr_NewExceptionWithDoc(full, doc, bases, NULL);
    Py_DECREF(bases);
    if (e == NULL)
        return NULL;
    Py_INCREF(e);
    if (PyModule_AddObject(m, name, e) < 0) {
        Py_DECREF(e);
        Py_DECREF(e);
        return NULL;
    }
    return e;
}

PyMODINIT_FUNC PyInit__conica(void);

PyMODINIT_FUNC PyInit__conica(void)
{
    PyObject *m = PyModule_Create(&cx_module);
    if (m == NULL)
        return NULL;
    cx_state *s = cx_get_state(m);
    PyObject *arraymod = PyImport_ImportModule("array");
    if (arraymod == NULL)
        goto fail;
    s->array_type = PyObject_GetAttrString(arraymod, "array");
    Py_DECREF(arraymod);
    if (s->array_type == NULL)
        goto fail;
    s->error = PyErr_NewExceptionWithDoc("_conica.ConicaError",
                                         "Base class of every error libconica reports; "
                                         "`code` holds libconica's status code.",
                                         PyExc_Exception, NULL);
    if (s->error == NULL)
        goto fail;
    Py_INCREF(s->error);
    if (PyModule_AddObject(m, "ConicaError", s->error) < 0) {
        Py_DECREF(s->error);
        goto fail;
    }
    if (!(s->arg_error = cx_add_exc(m, "ArgumentError", s->error, PyExc_ValueError,
                                    "An invalid argument (size, setting).")) ||
        !(s->limit_error = cx_add_exc(m, "LimitError", s->error, PyExc_ValueError,
                                      "A size limit (levels, points) would be exceeded.")) ||
        !(s->degenerate = cx_add_exc(m, "DegenerateError", s->error, PyExc_ValueError,
                                     "Degenerate geometry (too few or coincident points).")) ||
        !(s->nonfinite = cx_add_exc(m, "NonFiniteError", s->error, PyExc_ValueError,
                                    "NaN or infinite input.")) ||
        !(s->nonplanar = cx_add_exc(m, "NonPlanarError", s->error, PyExc_ValueError,
                                    "A 3D spline that is not planar within the tolerance.")) ||
        !(s->numeric = cx_add_exc(m, "NumericError", s->error, PyExc_RuntimeError,
                                  "A numerical method failed.")) ||
        !(s->nomem = cx_add_exc(m, "OutOfMemoryError", s->error, PyExc_MemoryError,
                                "Out of memory.")) ||
        !(s->unsupported = cx_add_exc(m, "UnsupportedError", s->error,
                                      PyExc_NotImplementedError, "Valid but unsupported input.")))
        goto fail;
    /* ABI and PY_MIN_VERSION: what the add-on's import check compares with
     * the running Python */
    if (PyModule_AddStringConstant(m, "ABI", "abi3") < 0 ||
        PyModule_AddObject(m, "PY_MIN_VERSION",
                           Py_BuildValue("(ii)", CX_LIMITED_API >> 24,
                                         (CX_LIMITED_API >> 16) & 0xff)) < 0 ||
        PyModule_AddIntConstant(m, "MAX_LEVELS", CONICA_SUBDIV_MAX_LEVELS) < 0 ||
        PyModule_AddIntConstant(m, "MAX_POINTS", (long)CX_HARD_MAX_POINTS) < 0 ||
        PyModule_AddIntConstant(m, "MAX_PATH_LEVELS", CX_PATH_MAX_LEVELS) < 0 ||
        PyModule_AddObject(m, "CORNER_ANGLE", PyFloat_FromDouble(CX_CORNER_ANGLE)) < 0 ||
        PyModule_AddObject(m, "REL_TOLERANCE",
                           PyFloat_FromDouble(CONICA_PATH_DEFAULT_REL_TOLERANCE)) < 0)
        goto fail;
    return m;
fail:
    Py_DECREF(m);
    return NULL;
}
