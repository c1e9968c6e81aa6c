/* SPDX-License-Identifier: MIT */
/* libFuzzer target: SVG path data. conica_svg_path_parse() on the whole
 * input, the polylines of what it kept (mode from the input length, small
 * budgets), their formatting, and conica_svg_points_parse() on the same
 * bytes. */
#include "fuzz_common.h"

#include "conica_svg.h"

#define FZ_MAX_SEGMENTS 4096

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_svg_path p;
    conica_status st;
    conica_code rc;
    if (!buf)
        return 0;
    memset(&st, 0, sizeof st);
    conica_svg_path_init(&p);
    rc = conica_svg_path_parse(buf, size, FZ_MAX_SEGMENTS, &p, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        FZ_ASSERT(p.n <= FZ_MAX_SEGMENTS);
        FZ_ASSERT(memchr(p.error, '\0', sizeof p.error) != NULL);
        FZ_ASSERT(!p.has_error || p.error_offset <= size);
        for (size_t i = 0; i < p.n; i++)
            FZ_ASSERT(p.seg[i].offset <= size);
        conica_svg_settings set = conica_svg_defaults();
        conica_svg_shapes sh;
        set.mode = (conica_svg_mode)(size % 3);
        set.levels = (int)(size % 4);
        set.tolerance = set.mode == CONICA_SVG_FLATTEN ? 0.01 : 0.0;
        set.limits.max_points = 1u << 15;
        conica_svg_shapes_init(&sh);
        rc = conica_svg_path_polylines(&p, &set, &sh, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK && sh.nsubpaths > 0) {
            char *out = NULL;
            size_t olen = 0;
            rc = conica_svg_format_path(sh.subpaths, sh.nsubpaths, 7, &out, &olen, &st);
            fz_check_status(rc, &st);
            if (rc == CONICA_OK) {
                FZ_ASSERT(out && strlen(out) == olen);
                /* What we write must read back without an error. */
                conica_svg_path q;
                conica_svg_path_init(&q);
                FZ_ASSERT(conica_svg_path_parse(out, olen, 0, &q, NULL) == CONICA_OK);
                FZ_ASSERT(!q.has_error);
                conica_svg_path_free(&q);
            }
            free(out);
        }
        conica_svg_shapes_free(&sh);
    }
    conica_svg_path_free(&p);

    double *xy = NULL;
    size_t n = 0, eoff = 0;
    rc = conica_svg_points_parse(buf, size, FZ_MAX_SEGMENTS, &xy, &n, &eoff, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK)
        FZ_ASSERT(n <= FZ_MAX_SEGMENTS && (n == 0 || xy != NULL));
    free(xy);
    free(buf);
    return 0;
}
