/* SPDX-License-Identifier: MIT */
/* Status messages and ownership of ts_outline (see ts_outline.h). */
#include "ts_outline.h"

#include <stdlib.h>

const char *ts_strerror(ts_code code)
{
    static const char *const msg[] = {
        "ok",
        "test support built without FreeType",
        "font file not found",
        "font has no glyph for the character",
        "FreeType failed to read the font",
        "out of memory",
        "invalid argument",
        "cannot write the file",
    };
    size_t i = (size_t)code;
    return i < sizeof msg / sizeof msg[0] ? msg[i] : "unknown status";
}

void ts_outline_init(ts_outline *o)
{
    o->n = 0;
    o->c = NULL;
}

void ts_outline_free(ts_outline *o)
{
    size_t i;
    if (!o)
        return;
    for (i = 0; i < o->n; i++)
        free(o->c[i].seg);
    free(o->c);
    ts_outline_init(o);
}

ts_code ts_contour_transform(const ts_contour *c, double sx, double sy, double dx, double dy,
                             ts_contour *out)
{
    ts_contour o = *c;
    size_t i;
    int k;
    o.seg = malloc((c->n ? c->n : 1) * sizeof *o.seg);
    if (!o.seg)
        return TS_ERR_NOMEM;
    for (i = 0; i < c->n; i++) {
        o.seg[i] = c->seg[i];
        for (k = 0; k <= c->seg[i].degree && k < 4; k++) {
            o.seg[i].p[k][0] = sx * c->seg[i].p[k][0] + dx;
            o.seg[i].p[k][1] = sy * c->seg[i].p[k][1] + dy;
        }
    }
    *out = o;
    return TS_OK;
}
