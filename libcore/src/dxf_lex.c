/* SPDX-License-Identifier: MIT */
/* DXF group-code/value pairs (ASCII DXF, LF or CRLF): a code line, a value
 * line. The type of a value follows from its code by the table of the DXF
 * reference ("Group Code Value Types"); numbers are read by
 * conica__parse_double (no C locale) and checked as they are read, so a
 * malformed or non-finite number is an error at its line wherever it is.
 * Calls numparse only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dxf_internal.h"
#include "internal.h"
#include "numparse.h"

/* Group codes are at most four digits (and a sign) in every DXF version. */
#define DXF_MAX_CODE 9999
/* Largest magnitude of an integer group (32-bit codes; 160-169 are 64-bit,
 * held to what a double represents exactly). */
#define DXF_MAX_INT32 2147483647.0
#define DXF_MAX_INT64 9007199254740992.0

/* Value type of each range of group codes (DXF reference, "Group Code
 * Value Types"); codes in no range are strings. */
static const struct {
    int lo, hi;
    conica__dxf_type type;
} code_types[] = {
    {0, 9, CONICA__DXF_STR},       {10, 59, CONICA__DXF_DBL},     {60, 79, CONICA__DXF_INT},
    {90, 99, CONICA__DXF_INT},     {100, 109, CONICA__DXF_STR},   {110, 149, CONICA__DXF_DBL},
    {160, 179, CONICA__DXF_INT},   {210, 239, CONICA__DXF_DBL},   {270, 299, CONICA__DXF_INT},
    {300, 369, CONICA__DXF_STR},   {370, 389, CONICA__DXF_INT},   {390, 399, CONICA__DXF_STR},
    {400, 409, CONICA__DXF_INT},   {410, 419, CONICA__DXF_STR},   {420, 429, CONICA__DXF_INT},
    {430, 439, CONICA__DXF_STR},   {440, 459, CONICA__DXF_INT},   {460, 469, CONICA__DXF_DBL},
    {470, 481, CONICA__DXF_STR},   {999, 1009, CONICA__DXF_STR},  {1010, 1059, CONICA__DXF_DBL},
    {1060, 1071, CONICA__DXF_INT},
};

static conica__dxf_type type_of(int code)
{
    for (size_t i = 0; i < sizeof code_types / sizeof code_types[0]; i++)
        if (code >= code_types[i].lo && code <= code_types[i].hi)
            return code_types[i].type;
    return CONICA__DXF_STR;
}

void conica__dxf_lex_at(conica__dxf_lexer *lx, const char *buf, size_t len, size_t pos,
                        size_t line)
{
    lx->buf = buf;
    lx->len = len;
    lx->pos = pos;
    lx->line = line;
    lx->peeked = 0;
}

/* The next line [*s, *s + *n) without its end; 0 at the end of input. */
static int next_line(conica__dxf_lexer *lx, const char **s, size_t *n)
{
    if (lx->pos >= lx->len)
        return 0;
    const char *b = lx->buf + lx->pos;
    const char *e = memchr(b, '\n', lx->len - lx->pos);
    size_t m = e ? (size_t)(e - b) : lx->len - lx->pos;
    lx->pos += m + (e ? 1 : 0);
    lx->line++;
    if (m > 0 && b[m - 1] == '\r')
        m--;
    *s = b;
    *n = m;
    return 1;
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static void trim(const char **s, size_t *n)
{
    while (*n > 0 && is_blank(**s)) {
        (*s)++;
        (*n)--;
    }
    while (*n > 0 && is_blank((*s)[*n - 1]))
        (*n)--;
}

/* Digits after the decimal point less the exponent: how finely the number
 * was written (0 for integers). */
static int decimals_of(const char *s, size_t n)
{
    int d = 0, exp = 0, neg = 0;
    size_t i = 0;
    while (i < n && s[i] != '.' && s[i] != 'e' && s[i] != 'E')
        i++;
    if (i < n && s[i] == '.')
        for (i++; i < n && s[i] >= '0' && s[i] <= '9'; i++)
            d++;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-'))
            neg = s[i++] == '-';
        for (; i < n && s[i] >= '0' && s[i] <= '9' && exp < 1000; i++)
            exp = 10 * exp + (s[i] - '0');
    }
    d += neg ? exp : -exp;
    return d < 0 ? 0 : d > 40 ? 40 : d;
}

int conica__dxf_next(conica__dxf_lexer *lx, conica__dxf_pair *p, conica_status *st)
{
    const char *s, *v;
    size_t n, vn, cline;
    long code = 0;
    int neg = 0;
    if (lx->peeked) {
        *p = lx->peek;
        lx->peeked = 0;
        return 1;
    }
    /* blank lines between pairs are tolerated at the very end only */
    size_t start;
    do {
        start = lx->pos;
        if (!next_line(lx, &s, &n))
            return 0;
        trim(&s, &n);
    } while (n == 0 && lx->pos >= lx->len);
    cline = lx->line;
    size_t i = 0;
    if (i < n && (s[i] == '-' || s[i] == '+'))
        neg = s[i++] == '-';
    if (i == n) {
        conica__fail(st, CONICA_ERR_PARSE, cline, lx->pos, "expected a group code, found '%.*s'",
                     (int)(n < 40 ? n : 40), s);
        return -1;
    }
    for (; i < n; i++) {
        if (s[i] < '0' || s[i] > '9' || code > DXF_MAX_CODE) {
            conica__fail(st, CONICA_ERR_PARSE, cline, lx->pos,
                         "expected a group code (an integer of at most 4 digits), found '%.*s'",
                         (int)(n < 40 ? n : 40), s);
            return -1;
        }
        code = 10 * code + (s[i] - '0');
    }
    if (code > DXF_MAX_CODE) {
        conica__fail(st, CONICA_ERR_PARSE, cline, lx->pos, "group code %ld is out of range", code);
        return -1;
    }
    if (!next_line(lx, &v, &vn)) {
        conica__fail(st, CONICA_ERR_PARSE, cline, lx->pos,
                     "truncated: group code %ld has no value line (the file ends)", code);
        return -1;
    }
    p->code = (int)(neg ? -code : code);
    p->type = type_of(p->code);
    p->line = cline;
    p->pos = start;
    p->num = 0;
    if (p->type == CONICA__DXF_STR) {
        /* strings keep inner blanks; leading/trailing blanks are padding */
        trim(&v, &vn);
        p->s = v;
        p->n = vn;
        return 1;
    }
    trim(&v, &vn);
    p->s = v;
    p->n = vn;
    size_t used = 0;
    int r = vn ? conica__parse_double(v, vn, &p->num, &used) : CONICA__NUM_SYNTAX;
    if (r == CONICA__NUM_NONFINITE) {
        conica__fail(st, CONICA_ERR_NONFINITE, lx->line, lx->pos,
                     "group %d: '%.*s' is not a finite number", p->code, (int)(vn < 40 ? vn : 40),
                     v);
        return -1;
    }
    /* integers: 16 and 32 bits (codes 160-169: 64), so that every cast to
     * int of a group's value is defined */
    double imax = p->code >= 160 && p->code <= 169 ? DXF_MAX_INT64 : DXF_MAX_INT32;
    if (r != CONICA__NUM_OK || used != vn ||
        (p->type == CONICA__DXF_INT &&
         (!(p->num >= -imax && p->num <= imax) || p->num != floor(p->num)))) {
        conica__fail(st, CONICA_ERR_PARSE, lx->line, lx->pos, "group %d: expected %s, found '%.*s'",
                     p->code, p->type == CONICA__DXF_INT ? "an integer" : "a number",
                     (int)(vn < 40 ? vn : 40), v);
        return -1;
    }
    if (p->code >= 10 && p->code <= 39) {
        int d = decimals_of(v, vn);
        if (d > lx->decimals)
            lx->decimals = d;
    }
    return 1;
}

void conica__dxf_unread(conica__dxf_lexer *lx, const conica__dxf_pair *p)
{
    lx->peek = *p;
    lx->peeked = 1;
}

int conica__dxf_is(const conica__dxf_pair *p, int code, const char *s)
{
    size_t m = strlen(s);
    return p->code == code && p->n == m && memcmp(p->s, s, m) == 0;
}

static int push(conica__dxf_ent *e, const conica__dxf_pair *p, size_t max, conica_status *st)
{
    if (e->n >= max) {
        conica__fail(st, CONICA_ERR_LIMIT, p->line, 0,
                     "entity %.*s has more than %zu groups (the vertex cap)",
                     e->n ? (int)(e->p[0].n < 40 ? e->p[0].n : 40) : 0, e->n ? e->p[0].s : "",
                     max);
        return -1;
    }
    if (e->n == e->cap) {
        size_t nc = e->cap ? 2 * e->cap : 64;
        conica__dxf_pair *q = realloc(e->p, nc * sizeof *q);
        if (!q) {
            conica__fail(st, CONICA_ERR_NOMEM, p->line, 0, "out of memory");
            return -1;
        }
        e->p = q;
        e->cap = nc;
    }
    e->p[e->n++] = *p;
    return 1;
}

int conica__dxf_read_entity(conica__dxf_lexer *lx, const conica__dxf_pair *head,
                            conica__dxf_ent *e, size_t max, conica_status *st)
{
    conica__dxf_pair p;
    int r, follow = conica__dxf_is(head, 0, "POLYLINE");
    e->n = 0;
    if (push(e, head, max, st) < 0)
        return -1;
    for (;;) {
        r = conica__dxf_next(lx, &p, st);
        if (r <= 0)
            return r;
        if (p.code == 66 && p.num != 0 && conica__dxf_is(head, 0, "INSERT"))
            follow = 1; /* attributes follow, up to a SEQEND */
        if (p.code == 0) {
            if (!follow || conica__dxf_is(&p, 0, "SECTION") || conica__dxf_is(&p, 0, "ENDSEC") ||
                conica__dxf_is(&p, 0, "ENDBLK") || conica__dxf_is(&p, 0, "EOF")) {
                conica__dxf_unread(lx, &p);
                return 1;
            }
            if (conica__dxf_is(&p, 0, "SEQEND"))
                follow = 0; /* its own pairs (handle, layer) are read, then the next 0 ends */
        }
        if (push(e, &p, max, st) < 0)
            return -1;
    }
}

void conica__dxf_ent_free(conica__dxf_ent *e)
{
    free(e->p);
    e->p = NULL;
    e->n = e->cap = 0;
}
