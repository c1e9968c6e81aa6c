/* SPDX-License-Identifier: MIT */
/* Glyph outlines through FreeType, and SVG writing of outlines (glyphs.h). */
#include "glyphs.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef TS_HAVE_FREETYPE
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#endif

int ts_font_available(const char *path)
{
#ifdef TS_HAVE_FREETYPE
    FILE *f = path ? fopen(path, "rb") : NULL;
    if (!f)
        return 0;
    fclose(f);
    return 1;
#else
    (void)path;
    return 0;
#endif
}

void ts_text_init(ts_text *t)
{
    memset(t, 0, sizeof *t);
}

void ts_text_free(ts_text *t)
{
    size_t i;
    if (!t)
        return;
    for (i = 0; i < t->n; i++)
        ts_outline_free(&t->glyph[i]);
    free(t->glyph);
    free(t->cp);
    free(t->x);
    ts_text_init(t);
}

/* Next code point of a NUL-terminated UTF-8 string; 0 at the end, -1 when
 * the bytes are not UTF-8 (overlong forms and surrogates included). */
static long utf8_next(const unsigned char **s)
{
    const unsigned char *p = *s;
    unsigned long cp;
    int extra, i;
    if (p[0] < 0x80) {
        cp = p[0];
        extra = 0;
    } else if ((p[0] & 0xE0) == 0xC0) {
        cp = p[0] & 0x1Fu;
        extra = 1;
    } else if ((p[0] & 0xF0) == 0xE0) {
        cp = p[0] & 0x0Fu;
        extra = 2;
    } else if ((p[0] & 0xF8) == 0xF0) {
        cp = p[0] & 0x07u;
        extra = 3;
    } else {
        return -1;
    }
    for (i = 1; i <= extra; i++) {
        if ((p[i] & 0xC0) != 0x80)
            return -1;
        cp = (cp << 6) | (p[i] & 0x3Fu);
    }
    if ((extra == 1 && cp < 0x80) || (extra == 2 && cp < 0x800) ||
        (extra == 3 && cp < 0x10000) || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
        return -1;
    if (cp != 0)
        *s = p + extra + 1;
    return (long)cp;
}

#ifdef TS_HAVE_FREETYPE
/* FT_Outline_Decompose computes the implied on-curve point between two
 * off-curve points as an integer mean, which would round half-integers.
 * With shift 1 it doubles every coordinate first, so the mean is exact;
 * the callbacks halve it back. */
#define TS_FT_SHIFT 1
#define TS_FT_UNIT 2.0

typedef struct decomp {
    const FT_Outline *ft;
    ts_outline *o; /* o->c has ft->n_contours slots; o->n are started */
    size_t cap;    /* segment capacity of the current contour */
    double cur[2], dx;
} decomp;

static void ft_point(const decomp *d, const FT_Vector *v, double out[2])
{
    out[0] = (double)v->x / TS_FT_UNIT + d->dx;
    out[1] = (double)v->y / TS_FT_UNIT;
}

static int on_move(const FT_Vector *to, void *user)
{
    decomp *d = user;
    int k = (int)d->o->n;
    ts_contour *c;
    if (k >= d->ft->n_contours)
        return 1;
    /* a contour of m points has at most m + 1 segments (the closing one) */
    d->cap = (size_t)(d->ft->contours[k] - (k ? d->ft->contours[k - 1] : -1)) + 1;
    c = &d->o->c[d->o->n];
    c->seg = malloc(d->cap * sizeof *c->seg);
    if (!c->seg)
        return 1;
    c->n = 0;
    c->closed = 1;
    d->o->n++;
    ft_point(d, to, d->cur);
    return 0;
}

static int add_seg(decomp *d, int degree, const FT_Vector *a, const FT_Vector *b,
                   const FT_Vector *e)
{
    const FT_Vector *v[3] = {a, b, e};
    ts_contour *c;
    ts_seg *s;
    int k;
    if (d->o->n == 0)
        return 1;
    c = &d->o->c[d->o->n - 1];
    if (c->n == d->cap)
        return 1;
    s = &c->seg[c->n];
    memset(s, 0, sizeof *s);
    s->degree = degree;
    s->p[0][0] = d->cur[0];
    s->p[0][1] = d->cur[1];
    for (k = 0; k < degree; k++)
        ft_point(d, v[k + 3 - degree], s->p[k + 1]);
    /* a contour whose last point repeats its first closes with nothing */
    if (degree == 1 && s->p[1][0] == s->p[0][0] && s->p[1][1] == s->p[0][1])
        return 0;
    d->cur[0] = s->p[degree][0];
    d->cur[1] = s->p[degree][1];
    c->n++;
    return 0;
}

static int on_line(const FT_Vector *to, void *user)
{
    return add_seg(user, 1, NULL, NULL, to);
}

static int on_conic(const FT_Vector *ctl, const FT_Vector *to, void *user)
{
    return add_seg(user, 2, NULL, ctl, to);
}

static int on_cubic(const FT_Vector *c1, const FT_Vector *c2, const FT_Vector *to, void *user)
{
    return add_seg(user, 3, c1, c2, to);
}

/* Load glyph `cp` of `face` shifted right by dx into *out (fresh). */
static ts_code load_glyph(FT_Face face, unsigned long cp, double dx, ts_outline *out,
                          double *advance)
{
    static const FT_Outline_Funcs funcs = {on_move, on_line, on_conic, on_cubic,
                                           TS_FT_SHIFT, 0};
    FT_UInt gi = FT_Get_Char_Index(face, (FT_ULong)cp);
    ts_outline o;
    decomp d;
    size_t i, kept;
    ts_outline_init(&o);
    if (gi == 0)
        return TS_ERR_NO_GLYPH;
    if (FT_Load_Glyph(face, gi, FT_LOAD_NO_SCALE) ||
        face->glyph->format != FT_GLYPH_FORMAT_OUTLINE)
        return TS_ERR_FREETYPE;
    d.ft = &face->glyph->outline;
    d.o = &o;
    d.cap = 0;
    d.dx = dx;
    if (d.ft->n_contours > 0) {
        o.c = calloc((size_t)d.ft->n_contours, sizeof *o.c);
        if (!o.c)
            return TS_ERR_NOMEM;
        if (FT_Outline_Decompose(&face->glyph->outline, &funcs, &d)) {
            ts_outline_free(&o);
            return TS_ERR_FREETYPE;
        }
    }
    for (i = kept = 0; i < o.n; i++) { /* drop single-point contours */
        if (o.c[i].n == 0)
            free(o.c[i].seg);
        else
            o.c[kept++] = o.c[i];
    }
    o.n = kept;
    if (advance) /* font units under FT_LOAD_NO_SCALE */
        *advance = (double)face->glyph->advance.x;
    *out = o;
    return TS_OK;
}

static ts_code open_face(const char *path, FT_Library *lib, FT_Face *face)
{
    if (!ts_font_available(path))
        return TS_ERR_NO_FONT;
    if (FT_Init_FreeType(lib))
        return TS_ERR_FREETYPE;
    if (FT_New_Face(*lib, path, 0, face)) {
        FT_Done_FreeType(*lib);
        return TS_ERR_FREETYPE;
    }
    return TS_OK;
}

static void close_face(FT_Library lib, FT_Face face)
{
    FT_Done_Face(face);
    FT_Done_FreeType(lib);
}

ts_code ts_glyph_outline(const char *font_path, unsigned long codepoint, ts_outline *out,
                         double *advance)
{
    FT_Library lib;
    FT_Face face;
    ts_code rc = open_face(font_path, &lib, &face);
    if (rc != TS_OK)
        return rc;
    rc = load_glyph(face, codepoint, 0.0, out, advance);
    close_face(lib, face);
    return rc;
}

ts_code ts_text_outlines(const char *font_path, const char *utf8, ts_text *out)
{
    const unsigned char *s = (const unsigned char *)utf8;
    size_t n = 0, cap = strlen(utf8); /* bytes >= code points */
    FT_Library lib;
    FT_Face face;
    ts_text t;
    ts_code rc;
    long cp;
    ts_text_init(&t);
    t.cp = malloc((cap ? cap : 1) * sizeof *t.cp);
    if (!t.cp)
        return TS_ERR_NOMEM;
    while ((cp = utf8_next(&s)) > 0)
        t.cp[n++] = (unsigned long)cp;
    if (cp < 0) {
        free(t.cp);
        return TS_ERR_ARG;
    }
    if ((rc = open_face(font_path, &lib, &face)) != TS_OK) {
        free(t.cp);
        return rc;
    }
    t.glyph = calloc(n ? n : 1, sizeof *t.glyph);
    t.x = calloc(n ? n : 1, sizeof *t.x);
    rc = t.glyph && t.x ? TS_OK : TS_ERR_NOMEM;
    for (; rc == TS_OK && t.n < n; t.n++) {
        double adv = 0.0;
        t.x[t.n] = t.advance;
        rc = load_glyph(face, t.cp[t.n], t.advance, &t.glyph[t.n], &adv);
        if (rc != TS_OK)
            break;
        t.advance += adv;
    }
    t.units_per_em = face->units_per_EM;
    t.ascender = face->ascender;
    t.descender = face->descender;
    close_face(lib, face);
    if (rc != TS_OK) {
        ts_text_free(&t);
        return rc;
    }
    *out = t;
    return TS_OK;
}

#else /* !TS_HAVE_FREETYPE: every loader says so, the tests skip */

ts_code ts_glyph_outline(const char *font_path, unsigned long codepoint, ts_outline *out,
                         double *advance)
{
    (void)font_path, (void)codepoint, (void)out, (void)advance;
    return TS_ERR_NO_FREETYPE;
}

ts_code ts_text_outlines(const char *font_path, const char *utf8, ts_text *out)
{
    const unsigned char *s = (const unsigned char *)utf8;
    long cp;
    (void)font_path, (void)out;
    while ((cp = utf8_next(&s)) > 0)
        continue;
    return cp < 0 ? TS_ERR_ARG : TS_ERR_NO_FREETYPE;
}
#endif

/* ------------------------------------------------------------ SVG */

ts_svg_opts ts_svg_defaults(void)
{
    ts_svg_opts o;
    o.digits = 10;
    o.close = 1;
    o.scale = 1.0;
    o.x0 = o.y0 = 0.0;
    return o;
}

/* Growing string; `err` sticks after the first failed allocation. */
typedef struct sbuf {
    char *s;
    size_t len, cap;
    int err;
} sbuf;

#if defined(__GNUC__) || defined(__clang__)
__attribute__((format(printf, 2, 3)))
#endif
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    va_list ap;
    int k;
    if (b->err)
        return;
    for (;;) {
        size_t room = b->cap - b->len;
        va_start(ap, fmt);
        k = vsnprintf(b->s ? b->s + b->len : NULL, room, fmt, ap);
        va_end(ap);
        if (k < 0) {
            b->err = 1;
            return;
        }
        if ((size_t)k < room) {
            b->len += (size_t)k;
            return;
        }
        {
            size_t ncap = 2 * b->cap + (size_t)k + 64;
            char *ns = realloc(b->s, ncap);
            if (!ns) {
                b->err = 1;
                return;
            }
            b->s = ns;
            b->cap = ncap;
        }
    }
}

static void sb_point(sbuf *b, const ts_svg_opts *o, const double p[2])
{
    double x = o->x0 + o->scale * p[0], y = o->y0 - o->scale * p[1];
    /* x + 0.0 turns -0 into 0 (round to nearest) */
    sb_printf(b, "%.*g %.*g", o->digits, x + 0.0, o->digits, y + 0.0);
}

static int seg_is_plain(const ts_seg *s)
{
    return s->degree >= 1 && s->degree <= 3 && (s->degree != 2 || s->w == 0.0 || s->w == 1.0);
}

/* Append the path data of `ol` to b; TS_ERR_ARG for what SVG cannot say. */
static ts_code sb_outline(sbuf *b, const ts_outline *ol, const ts_svg_opts *o)
{
    static const char cmd[4] = {0, 'L', 'Q', 'C'};
    size_t i, j;
    for (i = 0; i < ol->n; i++) {
        const ts_contour *c = &ol->c[i];
        size_t n = c->n;
        if (n == 0)
            continue;
        for (j = 0; j < n; j++)
            if (!seg_is_plain(&c->seg[j]))
                return TS_ERR_ARG;
        /* Z draws the closing line itself */
        if (o->close && c->closed && n > 1 && c->seg[n - 1].degree == 1 &&
            c->seg[n - 1].p[1][0] == c->seg[0].p[0][0] && c->seg[n - 1].p[1][1] == c->seg[0].p[0][1])
            n--;
        sb_printf(b, "M");
        sb_point(b, o, c->seg[0].p[0]);
        for (j = 0; j < n; j++) {
            const ts_seg *s = &c->seg[j];
            int k;
            sb_printf(b, "%c", cmd[s->degree]);
            for (k = 1; k <= s->degree; k++) {
                if (k > 1)
                    sb_printf(b, " ");
                sb_point(b, o, s->p[k]);
            }
        }
        if (o->close && c->closed)
            sb_printf(b, "Z");
    }
    return TS_OK;
}

static ts_code sb_finish(sbuf *b, ts_code rc, char **out)
{
    if (rc == TS_OK && b->err)
        rc = TS_ERR_NOMEM;
    if (rc != TS_OK) {
        free(b->s);
        return rc;
    }
    *out = b->s;
    return TS_OK;
}

ts_code ts_outline_svg_path(const ts_outline *o, const ts_svg_opts *opt, char **out)
{
    ts_svg_opts d = opt ? *opt : ts_svg_defaults();
    sbuf b = {NULL, 0, 0, 0};
    if (d.digits < 1 || d.digits > 17)
        return TS_ERR_ARG;
    sb_printf(&b, "%s", ""); /* an empty outline gives "" */
    return sb_finish(&b, sb_outline(&b, o, &d), out);
}

ts_code ts_text_svg(const ts_text *t, const ts_svg_opts *opt, char **out)
{
    ts_svg_opts d = opt ? *opt : ts_svg_defaults(), g;
    sbuf b = {NULL, 0, 0, 0};
    ts_code rc = TS_OK;
    double w, h;
    size_t i;
    if (d.digits < 1 || d.digits > 17)
        return TS_ERR_ARG;
    w = d.scale * t->advance + 2.0 * d.x0;
    h = d.scale * (t->ascender - t->descender) + 2.0 * d.y0;
    g = d;
    g.y0 = d.y0 + d.scale * t->ascender;
    sb_printf(&b, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.*g\" height=\"%.*g\""
                  " viewBox=\"0 0 %.*g %.*g\">\n",
              d.digits, w, d.digits, h, d.digits, w, d.digits, h);
    for (i = 0; i < t->n && rc == TS_OK; i++) {
        if (t->glyph[i].n == 0)
            continue;
        sb_printf(&b, "<path id=\"glyph%zu\" d=\"", i);
        rc = sb_outline(&b, &t->glyph[i], &g);
        sb_printf(&b, "\"/>\n");
    }
    sb_printf(&b, "</svg>\n");
    return sb_finish(&b, rc, out);
}

ts_code ts_write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    size_t n = strlen(text);
    int ok;
    if (!f)
        return TS_ERR_IO;
    ok = fwrite(text, 1, n, f) == n;
    ok = (fclose(f) == 0) && ok;
    return ok ? TS_OK : TS_ERR_IO;
}
