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
