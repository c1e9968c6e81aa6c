/* SPDX-License-Identifier: MIT */
/* A rendered scene as one flat SVG document (conica_svg_scene_write()):
 * every item a <path> of its local data under its matrix, in the root
 * frame, clipped by its clip polygon, painted opaque black, so that
 * rsvg-convert of it and of the original document can be compared pixel by
 * pixel. Calls the number formatter of svg_path.c. */
#include "svg_render_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Significant digits written: round trip of a double. */
#define SCENE_DIGITS 17

static void num(conica_svg__buf *b, double v)
{
    char t[48];
    size_t n = conica_svg__format_number(v, SCENE_DIGITS, t);
    conica_svg__buf_put(b, t, n);
}

static void put(conica_svg__buf *b, const char *s)
{
    conica_svg__buf_put(b, s, strlen(s));
}

static void nums(conica_svg__buf *b, const double *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (i)
            conica_svg__buf_putc(b, ' ');
        num(b, v[i]);
    }
}

/* Path data of a parsed path, every segment written absolutely. */
static void path_data(conica_svg__buf *b, const conica_svg_path *p)
{
    size_t i;
    for (i = 0; i < p->n; i++) {
        const conica_svg_seg *g = &p->seg[i];
        double v[7];
        if (i)
            conica_svg__buf_putc(b, ' ');
        switch (g->type) {
        case CONICA_SVG_SEG_MOVE:
            put(b, "M");
            v[0] = g->x1, v[1] = g->y1;
            nums(b, v, 2);
            break;
        case CONICA_SVG_SEG_LINE:
            put(b, "L");
            v[0] = g->x1, v[1] = g->y1;
            nums(b, v, 2);
            break;
        case CONICA_SVG_SEG_QUAD:
            put(b, "Q");
            v[0] = g->c[0], v[1] = g->c[1], v[2] = g->x1, v[3] = g->y1;
            nums(b, v, 4);
            break;
        case CONICA_SVG_SEG_CUBIC:
            put(b, "C");
            v[0] = g->c[0], v[1] = g->c[1], v[2] = g->c[2], v[3] = g->c[3];
            v[4] = g->x1, v[5] = g->y1;
            nums(b, v, 6);
            break;
        case CONICA_SVG_SEG_ARC:
            put(b, "A");
            v[0] = g->rx, v[1] = g->ry, v[2] = g->phi * (180.0 / M_PI);
            v[3] = g->large_arc ? 1 : 0, v[4] = g->sweep ? 1 : 0, v[5] = g->x1, v[6] = g->y1;
            nums(b, v, 7);
            break;
        default:
            put(b, "Z");
            break;
        }
    }
}

static int same_clip(const conica_svg_item *a, const conica_svg_item *b)
{
    return a->nclip == b->nclip &&
           (!a->nclip || !memcmp(a->clip, b->clip, 2 * a->nclip * sizeof *a->clip));
}

static const char *const joins[] = {"miter", "round", "bevel"};
static const char *const caps[] = {"butt", "round", "square"};

conica_code conica_svg_scene_write(const conica_svg_scene *s, FILE *f, conica_status *st)
{
    conica_svg__buf b;
    size_t i, j, *clip_of;
    if (!s || !f)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_scene_write: NULL argument");
    memset(&b, 0, sizeof b);
    clip_of = malloc((s->n ? s->n : 1) * sizeof *clip_of);
    if (!clip_of)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    put(&b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"");
    if (s->has_size) {
        put(&b, " width=\"");
        num(&b, s->width);
        put(&b, s->unit);
        put(&b, "\" height=\"");
        num(&b, s->height);
        put(&b, s->unit);
        put(&b, "\" viewBox=\"0 0 ");
        num(&b, s->width);
        conica_svg__buf_putc(&b, ' ');
        num(&b, s->height);
        put(&b, "\"");
    }
    put(&b, ">\n");
    if (!s->has_size) {
        /* no root frame: user units are px, the scene is in its unit */
        double k = conica_svg_convert_length(1.0, s->unit, "px");
        put(&b, "<g transform=\"scale(");
        num(&b, isfinite(k) ? k : 1.0);
        put(&b, ")\">\n");
    }
    /* one clipPath per distinct clip, named by the first item that has it */
    for (i = 0; i < s->n; i++) {
        clip_of[i] = i;
        if (!s->items[i].nclip)
            continue;
        for (j = 0; j < i; j++)
            if (s->items[j].nclip && same_clip(&s->items[i], &s->items[j])) {
                clip_of[i] = clip_of[j];
                break;
            }
        if (clip_of[i] != i)
            continue;
        {
            char id[64];
            snprintf(id, sizeof id, "<clipPath id=\"c%zu\"><path d=\"", i);
            put(&b, id);
        }
        for (j = 0; j < s->items[i].nclip; j++) {
            put(&b, j ? " L" : "M");
            nums(&b, s->items[i].clip + 2 * j, 2);
        }
        put(&b, " Z\"/></clipPath>\n");
    }
    for (i = 0; i < s->n; i++) {
        const conica_svg_item *it = &s->items[i];
        double m[6];
        char t[64];
        if (it->nclip) {
            snprintf(t, sizeof t, "<g clip-path=\"url(#c%zu)\">", clip_of[i]);
            put(&b, t);
        }
        put(&b, "<path d=\"");
        path_data(&b, &it->path);
        put(&b, "\" transform=\"matrix(");
        m[0] = it->ctm.a, m[1] = it->ctm.b, m[2] = it->ctm.c, m[3] = it->ctm.d;
        m[4] = it->ctm.e, m[5] = it->ctm.f;
        nums(&b, m, 6);
        put(&b, ")\" fill=\"");
        put(&b, it->fill ? "#000" : "none");
        put(&b, "\" fill-rule=\"");
        put(&b, it->fill_rule == CONICA_SVG_EVENODD ? "evenodd" : "nonzero");
        put(&b, "\" stroke=\"");
        put(&b, it->stroke ? "#000" : "none");
        if (it->stroke) {
            put(&b, "\" stroke-width=\"");
            num(&b, it->st.width);
            put(&b, "\" stroke-linejoin=\"");
            put(&b, joins[it->st.join <= CONICA_SVG_JOIN_BEVEL ? it->st.join : 0]);
            put(&b, "\" stroke-linecap=\"");
            put(&b, caps[it->st.cap <= CONICA_SVG_CAP_SQUARE ? it->st.cap : 0]);
            put(&b, "\" stroke-miterlimit=\"");
            num(&b, it->st.miterlimit);
            if (it->st.ndash) {
                put(&b, "\" stroke-dasharray=\"");
                nums(&b, it->st.dash, it->st.ndash);
                put(&b, "\" stroke-dashoffset=\"");
                num(&b, it->st.dashoffset);
            }
            if (it->st.non_scaling)
                put(&b, "\" vector-effect=\"non-scaling-stroke");
        }
        put(&b, "\"/>");
        if (it->nclip)
            put(&b, "</g>");
        conica_svg__buf_putc(&b, '\n');
    }
    if (!s->has_size)
        put(&b, "</g>\n");
    put(&b, "</svg>\n");
    free(clip_of);
    if (b.oom) {
        free(b.s);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    if (fwrite(b.s, 1, b.n, f) != b.n) {
        free(b.s);
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "write error");
    }
    free(b.s);
    conica__ok(st);
    return CONICA_OK;
}
