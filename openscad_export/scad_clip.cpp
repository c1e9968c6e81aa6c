// SPDX-License-Identifier: MIT
// The C face of Clipper for scadprofile's regions (scad_clip.h): polygon
// sets in doubles, booleans under a fill rule, offsets for strokes and for
// the check of a fit. Calls only Clipper (libpolyclipping) and libcore's
// status helpers; no exception leaves this file.
#include <clipper.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <unordered_map>

#include "scad_clip.h"

extern "C" {
#include "internal.h"
}

namespace {

using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

struct key_hash {
    size_t operator()(const IntPoint &p) const noexcept
    {
        unsigned long long h = (unsigned long long)p.X * 0x9E3779B97F4A7C15ull;
        return (size_t)(h ^ ((unsigned long long)p.Y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2)));
    }
};
struct key_eq {
    bool operator()(const IntPoint &a, const IntPoint &b) const noexcept
    {
        return a.X == b.X && a.Y == b.Y;
    }
};
// Integer point -> the exact doubles of the input vertex it came from.
typedef std::unordered_map<IntPoint, std::pair<double, double>, key_hash, key_eq> snap_map;

struct range_error {};

cInt to_int(double v, double scale)
{
    double r = std::nearbyint(v * scale);
    if (!(std::fabs(r) <= CONICA__CLIP_MAX_INT))
        throw range_error();
    return (cInt)r;
}

void to_paths(const conica__polys *p, double scale, bool closed, Paths &out, snap_map *snap)
{
    out.reserve(out.size() + p->n);
    for (size_t i = 0; i < p->n; i++) {
        Path q;
        size_t a = p->start[i], b = p->start[i + 1];
        q.reserve(b - a);
        for (size_t k = a; k < b; k++) {
            IntPoint ip(to_int(p->xy[2 * k], scale), to_int(p->xy[2 * k + 1], scale));
            if (!q.empty() && q.back() == ip)
                continue;
            q.push_back(ip);
            if (snap)
                snap->emplace(ip, std::make_pair(p->xy[2 * k], p->xy[2 * k + 1]));
        }
        if (closed && q.size() > 1 && q.front() == q.back())
            q.pop_back();
        if (q.size() >= (closed ? 3u : 2u))
            out.push_back(std::move(q));
    }
}

// Paths -> polys, snapping input vertices back to their doubles; the
// polygons of zero area Clipper can leave (a spike folded flat) go.
int from_paths(const Paths &in, double scale, const snap_map *snap, conica__polys *out)
{
    conica__polys r;
    conica__polys_init(&r);
    double *buf = NULL;
    size_t bcap = 0;
    for (const Path &q : in) {
        if (q.size() < 3 || ClipperLib::Area(q) == 0.0)
            continue;
        if (q.size() > bcap) {
            double *nb = (double *)realloc(buf, 2 * q.size() * sizeof *nb);
            if (!nb) {
                free(buf);
                conica__polys_free(&r);
                return -1;
            }
            buf = nb;
            bcap = q.size();
        }
        for (size_t k = 0; k < q.size(); k++) {
            auto it = snap ? snap->find(q[k]) : snap_map::const_iterator();
            if (snap && it != snap->end()) {
                buf[2 * k] = it->second.first;
                buf[2 * k + 1] = it->second.second;
            } else {
                buf[2 * k] = (double)q[k].X / scale;
                buf[2 * k + 1] = (double)q[k].Y / scale;
            }
        }
        if (conica__polys_add(&r, buf, q.size()) != 0) {
            free(buf);
            conica__polys_free(&r);
            return -1;
        }
    }
    free(buf);
    conica__polys_free(out);
    *out = r;
    return 0;
}

conica_code fail_range(conica_status *st)
{
    return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                        "coordinates too large for the tolerance: the polygon booleans work "
                        "on a grid of 1/100 of the tolerance and take at most 2.3e18 steps");
}

template <class F> conica_code guarded(conica_status *st, F f)
{
    try {
        return f();
    } catch (const range_error &) {
        return fail_range(st);
    } catch (const std::bad_alloc &) {
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    } catch (...) {
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "the polygon library (Clipper) refused the geometry "
                            "(coordinates beyond its range)");
    }
}

ClipperLib::PolyFillType fill_of(conica__clip_fill r)
{
    return r == CONICA__CLIP_EVENODD ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
}

} // namespace

extern "C" {

void conica__polys_init(conica__polys *p)
{
    memset(p, 0, sizeof *p);
}

void conica__polys_free(conica__polys *p)
{
    if (!p)
        return;
    free(p->start);
    free(p->xy);
    conica__polys_init(p);
}

int conica__polys_add(conica__polys *p, const double *xy, size_t n)
{
    if (p->n + 2 > p->cap) {
        size_t nc = p->cap ? 2 * p->cap : 16;
        size_t *ns = (size_t *)realloc(p->start, nc * sizeof *ns);
        if (!ns)
            return -1;
        p->start = ns;
        p->cap = nc;
    }
    if (p->npts + n > p->ptcap) {
        size_t nc = p->ptcap ? 2 * p->ptcap : 256;
        while (nc < p->npts + n)
            nc *= 2;
        double *nx = (double *)realloc(p->xy, 2 * nc * sizeof *nx);
        if (!nx)
            return -1;
        p->xy = nx;
        p->ptcap = nc;
    }
    if (p->n == 0)
        p->start[0] = 0;
    memcpy(p->xy + 2 * p->npts, xy, 2 * n * sizeof *xy);
    p->npts += n;
    p->start[++p->n] = p->npts;
    return 0;
}

int conica__polys_append(conica__polys *p, const conica__polys *q)
{
    for (size_t i = 0; i < q->n; i++)
        if (conica__polys_add(p, q->xy + 2 * q->start[i], q->start[i + 1] - q->start[i]) != 0)
            return -1;
    return 0;
}

double conica__polys_area2(const conica__polys *p, size_t i)
{
    size_t a = p->start[i], b = p->start[i + 1], n = b - a;
    const double *xy = p->xy + 2 * a;
    double s = 0;
    for (size_t k = 0; k < n; k++) {
        size_t j = (k + 1) % n;
        /* about the first point: the area of a small polygon far from the
         * origin keeps its digits */
        double ax = xy[2 * k] - xy[0], ay = xy[2 * k + 1] - xy[1];
        double bx = xy[2 * j] - xy[0], by = xy[2 * j + 1] - xy[1];
        s += ax * by - bx * ay;
    }
    return s;
}

double conica__polys_max_abs(const conica__polys *p)
{
    double m = 0;
    for (size_t k = 0; k < 2 * p->npts; k++)
        m = std::fmax(m, std::fabs(p->xy[k]));
    return m;
}

int conica__winding_step(const double *u, const double *v, double x, double y)
{
    double c = (v[0] - u[0]) * (y - u[1]) - (x - u[0]) * (v[1] - u[1]);
    if (u[1] <= y)
        return v[1] > y && c > 0;
    return -(v[1] <= y && c < 0);
}

int conica__polys_winding(const conica__polys *p, double x, double y)
{
    int w = 0;
    for (size_t i = 0; i < p->n; i++) {
        size_t a = p->start[i], b = p->start[i + 1], n = b - a;
        const double *xy = p->xy + 2 * a;
        for (size_t k = 0; k < n; k++)
            w += conica__winding_step(xy + 2 * k, xy + 2 * ((k + 1) % n), x, y);
    }
    return w;
}

double conica__clip_scale(double tol, double frac, double max_abs)
{
    if (!(tol > 0) || !(frac > 0))
        return 0;
    /* 0.5 sqrt(2) / scale <= frac tol */
    double need = 0.5 * std::sqrt(2.0) / (frac * tol);
    double s = std::ldexp(1.0, (int)std::ceil(std::log2(need)));
    if (!(max_abs * s <= 0.5 * CONICA__CLIP_MAX_INT))
        return 0;
    return s;
}

conica_code conica__clip_fill_region(const conica__polys *in, conica__clip_fill rule, double scale,
                                     int strict, conica__polys *out, conica_status *st)
{
    return guarded(st, [&]() {
        snap_map snap;
        Paths subj, sol;
        to_paths(in, scale, true, subj, &snap);
        ClipperLib::Clipper c;
        c.StrictlySimple(strict != 0);
        c.AddPaths(subj, ClipperLib::ptSubject, true);
        c.Execute(ClipperLib::ctUnion, sol, fill_of(rule), fill_of(rule));
        if (from_paths(sol, scale, &snap, out) != 0)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        conica__ok(st);
        return CONICA_OK;
    });
}

conica_code conica__clip_bool(conica__clip_op op, const conica__polys *a, const conica__polys *b,
                              double scale, conica__polys *out, conica_status *st)
{
    return guarded(st, [&]() {
        snap_map snap;
        Paths pa, pb, sol;
        to_paths(a, scale, true, pa, &snap);
        to_paths(b, scale, true, pb, &snap);
        ClipperLib::Clipper c;
        c.AddPaths(pa, ClipperLib::ptSubject, true);
        c.AddPaths(pb, ClipperLib::ptClip, true);
        ClipperLib::ClipType ct = op == CONICA__CLIP_UNION          ? ClipperLib::ctUnion
                                  : op == CONICA__CLIP_INTERSECTION ? ClipperLib::ctIntersection
                                                                    : ClipperLib::ctDifference;
        c.Execute(ct, sol, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        if (from_paths(sol, scale, &snap, out) != 0)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        conica__ok(st);
        return CONICA_OK;
    });
}

conica_code conica__clip_offset(const conica__polys *in, conica__clip_end end,
                                conica__clip_join join, double miterlimit, double delta,
                                double arctol, double scale, conica__polys *out,
                                conica_status *st)
{
    return guarded(st, [&]() {
        Paths subj, sol;
        bool closed = end == CONICA__CLIP_END_POLYGON || end == CONICA__CLIP_END_CLOSED_LINE;
        to_paths(in, scale, closed, subj, NULL);
        ClipperLib::ClipperOffset co(miterlimit >= 1 ? miterlimit : 1,
                                     std::fmax(arctol * scale, 0.25));
        ClipperLib::JoinType jt = join == CONICA__CLIP_JOIN_ROUND   ? ClipperLib::jtRound
                                  : join == CONICA__CLIP_JOIN_SQUARE ? ClipperLib::jtSquare
                                                                     : ClipperLib::jtMiter;
        ClipperLib::EndType et = end == CONICA__CLIP_END_POLYGON       ? ClipperLib::etClosedPolygon
                                 : end == CONICA__CLIP_END_CLOSED_LINE ? ClipperLib::etClosedLine
                                 : end == CONICA__CLIP_END_BUTT        ? ClipperLib::etOpenButt
                                 : end == CONICA__CLIP_END_SQUARE      ? ClipperLib::etOpenSquare
                                                                       : ClipperLib::etOpenRound;
        co.AddPaths(subj, jt, et);
        co.Execute(sol, delta * scale);
        if (from_paths(sol, scale, NULL, out) != 0)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        conica__ok(st);
        return CONICA_OK;
    });
}

} // extern "C"
