/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the scadprofile pipeline in memory, through the same
 * library calls as openscad_export/scadprofile.c: the input kind is
 * detected from the content as the tool does for stdin (SVG, .spl spline or
 * point-normal text); points are refined to a tolerance
 * (conica_scad_refine) or subdivided a few levels, splines plotted and
 * thinned, SVG extracted and thinned; then conica_scad_validate,
 * conica_scad_arrange and conica_scad_write into a memory stream. Budgets
 * are small so one input runs in milliseconds. */
#include "fuzz_common.h"

#include "conica/bspline.h"
#include "conica/curve.h"
#include "conica/plot.h"
#include "conica/subdiv.h"
#include "conica_scad.h"
#include "conica_svg.h"

#define FZ_MAX_DENSE ((size_t)1 << 14)

typedef enum { K_POINTS, K_SVG, K_SPLINE } fz_kind;

static fz_kind detect(const char *buf, size_t len)
{
    size_t i = 0;
    while (i < len && (buf[i] == ' ' || buf[i] == '\t' || buf[i] == '\r' || buf[i] == '\n'))
        i++;
    if (i < len && buf[i] == '<')
        return K_SVG;
    if (len - i >= 6 && memcmp(buf + i, "degree", 6) == 0)
        return K_SPLINE;
    return K_POINTS;
}

static void add(conica_scad_profile *prof, const char *name, conica_scad_fill fill,
                const double *xy, size_t n)
{
    conica_status st;
    size_t g;
    conica_code rc = conica_scad_add_group(prof, name, fill, 1, &g, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        rc = conica_scad_add_contour(prof, g, xy, n, &st);
        fz_check_status(rc, &st);
    }
}

static void thin_and_add(conica_scad_profile *prof, const char *name, conica_scad_fill fill,
                         const double *xy, size_t n, double tol)
{
    double *pts = NULL;
    size_t m = 0;
    conica_status st;
    if (n > 3) {
        conica_code rc = conica_scad_thin(xy, n, 1, tol, &pts, &m, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            FZ_ASSERT(m <= n);
            add(prof, name, fill, pts, m);
        }
        free(pts);
    } else if (n > 0) {
        add(prof, name, fill, xy, n);
    }
}

static void load_points(const char *buf, size_t len, size_t size, conica_scad_profile *prof)
{
    conica_curve in, sub;
    conica_status st;
    conica_curve_init(&in);
    conica_curve_init(&sub);
    if (conica_curve_parse(buf, len, &in, &st) == CONICA_OK && in.n >= 3) {
        in.closed = 1;
        if (size % 2) {
            conica_subdiv_settings s = conica_subdiv_defaults();
            s.levels = (int)(size % 5);
            s.max_points = FZ_MAX_DENSE;
            conica_code rc = conica_subdivide(&in, &s, &sub, NULL, &st);
            fz_check_status(rc, &st);
            if (rc == CONICA_OK)
                add(prof, "points", CONICA_SCAD_FILL_NONZERO, sub.xy, sub.n);
        } else {
            double *pts = NULL;
            size_t n = 0;
            conica_scad_refine_info info;
            double tol = ldexp(1.0, -(int)(size % 24));
            conica_code rc = conica_scad_refine(&in, tol, FZ_MAX_DENSE, &pts, &n, &info, &st);
            fz_check_status(rc, &st);
            if (rc == CONICA_OK) {
                FZ_ASSERT(info.dense_points <= FZ_MAX_DENSE && n <= info.dense_points);
                add(prof, "points", CONICA_SCAD_FILL_NONZERO, pts, n);
            }
            free(pts);
        }
    }
    conica_curve_free(&in);
    conica_curve_free(&sub);
}

static void load_spline(const char *buf, size_t len, size_t size, conica_scad_profile *prof)
{
    conica_bspline s;
    conica_polyline pl;
    conica_status st;
    conica_bspline_init(&s);
    conica_polyline_init(&pl);
    if (conica_bspline_parse(buf, len, &s, &st) == CONICA_OK && s.dim == 2) {
        conica_plot_settings ps = conica_plot_defaults();
        double tol = ldexp(1.0, -(int)(size % 20));
        ps.method = CONICA_PLOT_GUARANTEED;
        ps.abs_tolerance = tol / 256;
        ps.max_points = FZ_MAX_DENSE;
        ps.max_knots = FZ_MAX_DENSE;
        ps.max_iterations = 1u << 18;
        conica_code rc = conica_plot(&s, &ps, &pl, NULL, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            FZ_ASSERT(pl.n <= FZ_MAX_DENSE && pl.dim == 2);
            size_t n = pl.n;
            if (n >= 2 && pl.xy[0] == pl.xy[2 * n - 2] && pl.xy[1] == pl.xy[2 * n - 1])
                n--;
            thin_and_add(prof, "spline", CONICA_SCAD_FILL_NONZERO, pl.xy, n, tol);
        }
    }
    conica_polyline_free(&pl);
    conica_bspline_free(&s);
}

static void load_svg(const char *buf, size_t len, size_t size, conica_scad_profile *prof)
{
    conica_svg_doc *doc = NULL;
    conica_svg_limits lim = conica_svg_limits_defaults();
    conica_status st;
    lim.max_bytes = 1u << 20;
    lim.max_depth = 64;
    lim.max_elements = 4096;
    lim.max_path_bytes = 1u << 16;
    lim.max_points = FZ_MAX_DENSE;
    if (conica_svg_doc_load(buf, len, &lim, &doc, &st) != CONICA_OK)
        return;
    conica_svg_viewport vp;
    conica_code rc = conica_svg_doc_viewport(doc, &vp, &st);
    fz_check_status(rc, &st);
    conica_svg_settings set = conica_svg_defaults();
    conica_svg_shapes sh;
    double tol = ldexp(1.0, -(int)(size % 16));
    set.convert_shapes = 1;
    set.limits = lim;
    if (size % 3 == 0) {
        /* scadprofile's own pipeline: flattened, open subpaths filled */
        set.mode = CONICA_SVG_FLATTEN;
        set.tolerance = tol;
        set.close_open = 1;
    } else if (size % 3 == 1) {
        set.mode = CONICA_SVG_SMOOTH;
        set.levels = (int)(size % 4);
        set.tolerance = 0;
    } else {
        set.mode = CONICA_SVG_SMOOTH;
        set.tolerance = tol / 256;
    }
    conica_svg_shapes_init(&sh);
    rc = conica_svg_extract(doc, &set, &sh, &st);
    fz_check_status(rc, &st);
    conica_svg_doc_free(doc);
    if (rc == CONICA_OK) {
        for (size_t e = 0; e < sh.nelements; e++) {
            const conica_svg_element *el = &sh.elements[e];
            for (size_t k = 0; k < el->nsubpaths; k++) {
                const conica_svg_subpath *sp = &sh.subpaths[el->first_subpath + k];
                if (!sp->closed)
                    continue;
                /* y flipped as the tool does, so orientation changes too */
                double *xy = malloc(2 * (sp->n ? sp->n : 1) * sizeof *xy);
                if (!xy)
                    break;
                for (size_t i = 0; i < sp->n; i++) {
                    xy[2 * i] = sp->xy[2 * i];
                    xy[2 * i + 1] = -sp->xy[2 * i + 1];
                }
                thin_and_add(prof, el->id ? el->id : el->tag,
                             el->fill_rule == CONICA_SVG_EVENODD ? CONICA_SCAD_FILL_EVENODD
                                                                 : CONICA_SCAD_FILL_NONZERO,
                             xy, sp->n, tol);
                free(xy);
            }
        }
    }
    conica_svg_shapes_free(&sh);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_scad_profile prof;
    conica_scad_layout lay;
    conica_scad_violation v;
    conica_status st;
    conica_code rc;
    if (!buf)
        return 0;
    conica_scad_profile_init(&prof);
    conica_scad_layout_init(&lay);
    switch (detect(buf, size)) {
    case K_SVG: load_svg(buf, size, size, &prof); break;
    case K_SPLINE: load_spline(buf, size, size, &prof); break;
    default: load_points(buf, size, size, &prof); break;
    }
    free(buf);
    if (prof.ncontours > 0) {
        int revolve = (int)(size & 1);
        rc = conica_scad_validate(&prof, revolve, &v, &st);
        fz_check_status(rc, &st);
        FZ_ASSERT(rc != CONICA_OK || v.problem == CONICA_SCAD_OK);
        /* --force writes an invalid profile too: arrange must survive it */
        if (rc == CONICA_OK || size % 5 == 0) {
            rc = conica_scad_arrange(&prof, &lay, &st);
            fz_check_status(rc, &st);
            if (rc == CONICA_OK) {
                FZ_ASSERT(lay.npaths + lay.dropped == prof.ncontours);
                char *mem = NULL;
                size_t mlen = 0;
                FILE *f = open_memstream(&mem, &mlen);
                if (f) {
                    conica_scad_write_options o = conica_scad_write_defaults();
                    o.module = "fuzz";
                    o.header = "fuzz\nheader";
                    o.extrude = (int)(size & 2);
                    o.extrude_height = 3;
                    o.revolve = revolve;
                    o.revolve_angle = 360;
                    rc = conica_scad_write(f, &prof, &lay, &o, &st);
                    fz_check_status(rc, &st);
                    fclose(f);
                    free(mem);
                }
            }
        }
    }
    conica_scad_layout_free(&lay);
    conica_scad_profile_free(&prof);
    return 0;
}
