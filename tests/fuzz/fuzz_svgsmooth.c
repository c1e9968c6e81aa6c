/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the whole svgsmooth pipeline in memory --
 * conica_svg_doc_load (small caps), conica_svg_extract, conica_svg_process,
 * conica_svg_doc_save (the byte-true splice) -- with the mode, levels and
 * --simplify taken from the input length so one corpus exercises them all. */
#include "fuzz_common.h"

#include "conica_svg.h"

static void fz_warn(void *ctx, size_t line, const char *message)
{
    (void)ctx;
    (void)line;
    FZ_ASSERT(message != NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_svg_doc *doc = NULL;
    conica_status st;
    conica_code rc;
    conica_svg_limits lim = conica_svg_limits_defaults();
    if (!buf)
        return 0;
    memset(&st, 0, sizeof st);
    lim.max_bytes = 1u << 20;
    lim.max_depth = 64;
    lim.max_elements = 4096;
    lim.max_path_bytes = 1u << 16;
    lim.max_points = 1u << 15;
    rc = conica_svg_doc_load(buf, size, &lim, &doc, &st);
    fz_check_status(rc, &st);
    FZ_ASSERT((rc == CONICA_OK) == (doc != NULL));
    if (rc == CONICA_OK) {
        conica_svg_settings set = conica_svg_defaults();
        conica_svg_shapes sh;
        conica_svg_viewport vp;
        conica_svg_stats stats;
        set.limits = lim;
        set.mode = (conica_svg_mode)(size % 3);
        set.levels = (int)(size % 4);
        set.tolerance = set.mode == CONICA_SVG_FLATTEN ? 0.05 : (size % 8 == 7 ? 0.5 : 0.0);
        set.convert_shapes = (int)(size & 8);
        set.simplify = size % 5 == 4 ? 0.5 : 0.0; /* conica/simplify.h on traced outlines */
        set.precision = (int)(size % 17) + 1;
        set.warn = fz_warn;
        rc = conica_svg_doc_viewport(doc, &vp, &st);
        fz_check_status(rc, &st);
        conica_svg_shapes_init(&sh);
        rc = conica_svg_extract(doc, &set, &sh, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK)
            for (size_t i = 0; i < sh.nsubpaths; i++)
                FZ_ASSERT(sh.subpaths[i].element < sh.nelements);
        conica_svg_shapes_free(&sh);
        rc = conica_svg_process(doc, &set, &stats, &st);
        fz_check_status(rc, &st);
        char *out = NULL;
        size_t olen = 0;
        rc = conica_svg_doc_save(doc, &out, &olen, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            FZ_ASSERT(out != NULL && out[olen] == '\0');
            /* The saved document loads again (entities were refused, so
             * nothing can expand on the second pass). */
            conica_svg_doc *again = NULL;
            conica_svg_limits big = conica_svg_limits_defaults();
            rc = conica_svg_doc_load(out, olen, &big, &again, &st);
            fz_check_status(rc, &st);
            conica_svg_doc_free(again);
        }
        conica_svg_buffer_free(out);
    }
    conica_svg_doc_free(doc);
    free(buf);
    return 0;
}
