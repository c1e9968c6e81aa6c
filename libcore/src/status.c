/* SPDX-License-Identifier: MIT */
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const messages[CONICA_CODE_COUNT_] = {
    [CONICA_OK] = "success",
    [CONICA_ERR_ARG] = "invalid argument",
    [CONICA_ERR_NOMEM] = "out of memory",
    [CONICA_ERR_PARSE] = "malformed input",
    [CONICA_ERR_IO] = "input/output error",
    [CONICA_ERR_LIMIT] = "limit exceeded",
    [CONICA_ERR_DEGENERATE] = "degenerate geometry",
    [CONICA_ERR_NONFINITE] = "NaN or infinite value",
    [CONICA_ERR_NUMERIC] = "numerical failure",
    [CONICA_ERR_UNSUPPORTED] = "unsupported input",
};

const char *conica_strerror(conica_code code)
{
    if ((unsigned)code >= CONICA_CODE_COUNT_)
        return "unknown status";
    return messages[code];
}

const char *conica_version(void)
{
    return CONICA_VERSION_STRING;
}

conica_code conica__fail(conica_status *st, conica_code code, size_t line,
                         size_t offset, const char *fmt, ...)
{
    if (st) {
        va_list ap;
        st->code = code;
        st->line = line;
        st->offset = offset;
        va_start(ap, fmt);
        vsnprintf(st->message, sizeof st->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

void conica__ok(conica_status *st)
{
    if (st) {
        st->code = CONICA_OK;
        st->line = 0;
        st->offset = 0;
        st->message[0] = '\0';
    }
}
