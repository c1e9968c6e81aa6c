/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the DXF reader conica_dxf_read() (conica/dxf.h) with
 * small caps, both open-outline modes chosen by the first byte, then
 * flattening of what it read (every contour closed, one DXF line per
 * contour, finite points), and conica_dxf_spline() on the same bytes. */
#include "fuzz_common.h"

#include "conica/dxf.h"

static void warn(void *ctx, size_t line, const char *msg)
{
    (void)ctx;
    (void)line;
    FZ_ASSERT(msg != NULL && strlen(msg) < 1024);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_dxf_settings s = conica_dxf_defaults();
    conica_dxf_drawing d;
    conica_status st;
    conica_code rc;
    if (!buf)
        return 0;
    memset(&st, 0, sizeof st);
    s.limits.max_entities = 4096;
    s.limits.max_vertices = 4096;
    s.limits.max_knots = 4096;
    s.limits.max_points = 1 << 16;
    s.limits.max_depth = 8;
    s.open_mode = size && (data[0] & 1) ? CONICA_DXF_OPEN_CLOSE : CONICA_DXF_OPEN_ERROR;
    s.warn = warn;
    conica_dxf_drawing_init(&d);
    rc = conica_dxf_read(buf, size, &s, &d, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        conica_path_settings ps = conica_path_defaults();
        conica_path_result r;
        FZ_ASSERT(d.path.nsub > 0 && d.gap > 0);
        for (size_t i = 0; i < d.path.nsub; i++)
            FZ_ASSERT(d.path.sub[i].closed && d.sub_line[i] >= 1);
        ps.max_points = 1 << 16;
        conica_path_result_init(&r);
        rc = conica_path_flatten(&d.path, &ps, &r, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK)
            for (size_t i = 0; i < r.n; i++)
                for (size_t k = 0; k < 2 * r.lines[i].n; k++)
                    FZ_ASSERT(isfinite(r.lines[i].xy[k]));
        conica_path_result_free(&r);
    }
    conica_dxf_drawing_free(&d);
    conica_bspline bs;
    conica_bspline_init(&bs);
    rc = conica_dxf_spline(buf, size, NULL, &s.limits, &bs, NULL, &st);
    fz_check_status(rc, &st);
    FZ_ASSERT(rc != CONICA_OK || (bs.n >= (size_t)bs.degree + 1 && (bs.dim == 2 || bs.dim == 3)));
    conica_bspline_free(&bs);
    free(buf);
    return 0;
}
