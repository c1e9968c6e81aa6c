/* SPDX-License-Identifier: MIT */
/* svgscene: a document's rendered scene (conica_svg_render()) written as a
 * flat SVG (conica_svg_scene_write()), for the pixel comparisons of
 * tests/cli/svg_render.sh against rsvg-convert. A test tool, not installed.
 *
 *   svgscene [--unit U] [--select ID]... [--unpainted] [--count] IN.svg OUT.svg
 *
 * Warnings go to stderr as "svgscene: warning: IN:LINE: ..."; --count
 * prints the number of items to stdout instead of writing OUT. Exit 0 ok,
 * 1 error (the message names the file and line), 2 usage. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica_svg.h"
#include "conica_svg_render.h"

#define MAX_SELECT 64

static void on_warn(void *ctx, size_t line, const char *msg)
{
    fprintf(stderr, "svgscene: warning: %s:%zu: %s\n", (const char *)ctx, line, msg);
}

static char *slurp(const char *name, size_t *len)
{
    FILE *f = fopen(name, "rb");
    char *buf = NULL;
    size_t cap = 0, n = 0;
    if (!f)
        return NULL;
    for (;;) {
        size_t k;
        if (n == cap) {
            char *t = realloc(buf, cap ? 2 * cap : 65536);
            if (!t) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = t;
            cap = cap ? 2 * cap : 65536;
        }
        k = fread(buf + n, 1, cap - n, f);
        if (!k)
            break;
        n += k;
    }
    fclose(f);
    *len = n;
    return buf;
}

int main(int argc, char **argv)
{
    conica_svg_render_settings rs = conica_svg_render_defaults();
    const char *sel[MAX_SELECT], *in = NULL, *outname = NULL;
    size_t nsel = 0, len = 0;
    int i, count = 0, rc = 1;
    char *buf;
    conica_svg_doc *doc = NULL;
    conica_status st;
    conica_svg_scene sc;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--unit") && i + 1 < argc)
            rs.unit = argv[++i];
        else if (!strcmp(argv[i], "--select") && i + 1 < argc && nsel < MAX_SELECT)
            sel[nsel++] = argv[++i];
        else if (!strcmp(argv[i], "--unpainted"))
            rs.unpainted = 1;
        else if (!strcmp(argv[i], "--count"))
            count = 1;
        else if (!in)
            in = argv[i];
        else if (!outname)
            outname = argv[i];
        else
            in = NULL, i = argc;
    }
    if (!in || (!outname && !count)) {
        fprintf(stderr, "usage: svgscene [--unit U] [--select ID]... [--unpainted] [--count] "
                        "IN.svg OUT.svg\n");
        return 2;
    }
    if (nsel) {
        rs.select = sel;
        rs.nselect = nsel;
    }
    rs.warn = on_warn;
    rs.warn_ctx = (void *)in;
    buf = slurp(in, &len);
    if (!buf) {
        fprintf(stderr, "svgscene: error: %s: cannot read\n", in);
        return 1;
    }
    if (conica_svg_doc_load(buf, len, NULL, &doc, &st) != CONICA_OK) {
        fprintf(stderr, "svgscene: error: %s:%zu: %s\n", in, st.line, st.message);
        free(buf);
        return 1;
    }
    free(buf);
    conica_svg_scene_init(&sc);
    if (conica_svg_render(doc, &rs, &sc, &st) != CONICA_OK) {
        fprintf(stderr, "svgscene: error: %s:%zu: %s\n", in, st.line, st.message);
    } else if (count) {
        printf("%zu\n", sc.n);
        rc = 0;
    } else {
        FILE *f = fopen(outname, "wb");
        if (!f) {
            fprintf(stderr, "svgscene: error: %s: cannot write\n", outname);
        } else {
            if (conica_svg_scene_write(&sc, f, &st) != CONICA_OK)
                fprintf(stderr, "svgscene: error: %s: %s\n", outname, st.message);
            else
                rc = 0;
            if (fclose(f) != 0)
                rc = 1;
        }
    }
    conica_svg_scene_free(&sc);
    conica_svg_doc_free(doc);
    return rc;
}
