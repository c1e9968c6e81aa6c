/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the SVG render -- conica_svg_doc_load (small caps),
 * conica_svg_render (CSS sheets and cascade, use expansion, viewports,
 * units) with small instance/use/segment caps and the unit and
 * unpainted flag taken from the input length, then conica_svg_scene_write
 * to /dev/null-like memory; checks the scene's invariants (counts, even
 * dash lists, clips of at least three points). */
#include "fuzz_common.h"

#include "conica_svg.h"
#include "conica_svg_render.h"

static void fz_warn(void *ctx, size_t line, const char *message)
{
    (void)ctx;
    (void)line;
    FZ_ASSERT(message != NULL);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const units[] = {"px", "mm", "in", "pt"};
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
    rc = conica_svg_doc_load(buf, size, &lim, &doc, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        conica_svg_render_settings rs = conica_svg_render_defaults();
        conica_svg_scene sc;
        size_t i;
        rs.unit = units[size % 4];
        rs.unpainted = (int)(size & 4);
        rs.max_instances = 1u << 14;
        rs.max_use_depth = 8;
        rs.max_segments = 1u << 16;
        rs.warn = fz_warn;
        conica_svg_scene_init(&sc);
        rc = conica_svg_render(doc, &rs, &sc, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            size_t segs = 0;
            FILE *f = fopen("/dev/null", "w");
            FZ_ASSERT(sc.n <= sc.cap);
            for (i = 0; i < sc.n; i++) {
                const conica_svg_item *it = &sc.items[i];
                FZ_ASSERT(it->path.n > 0);
                FZ_ASSERT(it->st.ndash % 2 == 0 && it->st.ndash <= CONICA_SVG_MAX_DASHES);
                FZ_ASSERT(it->nclip == 0 || (it->nclip >= 3 && it->clip != NULL));
                FZ_ASSERT(rs.unpainted || it->fill || it->stroke);
                FZ_ASSERT(memchr(it->name, '\0', sizeof it->name) != NULL);
                segs += it->path.n;
            }
            FZ_ASSERT(segs <= rs.max_segments);
            if (f) {
                rc = conica_svg_scene_write(&sc, f, &st);
                fz_check_status(rc, &st);
                fclose(f);
            }
        } else {
            FZ_ASSERT(sc.n == 0);
        }
        conica_svg_scene_free(&sc);
    }
    conica_svg_doc_free(doc);
    free(buf);
    return 0;
}
