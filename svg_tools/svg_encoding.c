/* SPDX-License-Identifier: MIT */
/* The character encoding of an SVG document (svg_encoding.h): detection as
 * the XML recommendation's Appendix F describes it (byte-order mark, the
 * first four bytes of "<?xml", then the declaration's encoding name), the
 * conversion of the whole document to UTF-8 for the parser and the byte
 * scans, and the conversion of what a save writes back into the
 * document's own encoding. Conversions go through iconv (glibc), the
 * library libxml2 itself uses for every encoding it does not build in, so
 * every encoding libxml2 reads is read here too. Calls iconv only. */
#include "svg_encoding.h"

#include <errno.h>
#include <iconv.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How far into the document the declaration is looked for. */
#define ENC_DECL_SCAN 512

static int lower(int c)
{
    return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c;
}

static int name_is(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (lower((unsigned char)*a) != lower((unsigned char)*b))
            return 0;
    return *a == *b;
}

/* Names that need no conversion: UTF-8 and its subset ASCII. */
static int is_utf8(const char *n)
{
    return name_is(n, "UTF-8") || name_is(n, "UTF8") || name_is(n, "US-ASCII") ||
           name_is(n, "ASCII");
}

/* The encoding name of an XML declaration in s (ASCII-compatible bytes),
 * "" when there is none. */
static void decl_encoding(const char *s, size_t len, char *name, size_t cap)
{
    const char *p = s, *end = s + len, *q;
    name[0] = '\0';
    if (len < 6 || memcmp(s, "<?xml", 5) != 0)
        return;
    for (q = p + 5; q + 1 < end && !(q[0] == '?' && q[1] == '>'); q++)
        ;
    end = q;
    for (p = s + 5; p + 8 <= end; p++) {
        const char *v;
        size_t k = 0;
        char quote;
        if (memcmp(p, "encoding", 8) != 0)
            continue;
        v = p + 8;
        while (v < end && (*v == ' ' || *v == '\t' || *v == '\r' || *v == '\n'))
            v++;
        if (v == end || *v != '=')
            return;
        v++;
        while (v < end && (*v == ' ' || *v == '\t' || *v == '\r' || *v == '\n'))
            v++;
        if (v == end || (*v != '"' && *v != '\''))
            return;
        quote = *v++;
        while (v < end && *v != quote && k + 1 < cap)
            name[k++] = *v++;
        name[v < end && *v == quote ? k : 0] = '\0';
        return;
    }
}

static void set_name(conica_svg__enc *enc, const char *n)
{
    snprintf(enc->name, sizeof enc->name, "%s", n);
}

/* The name, byte-order mark and detection of Appendix F. Returns 0, or 1
 * with why filled. */
static int detect(const unsigned char *b, size_t len, conica_svg__enc *enc, char *why, size_t cap)
{
    char declared[CONICA_SVG_ENC_NAME_MAX];
    memset(enc, 0, sizeof *enc);
    if (len >= 4 && b[0] == 0 && b[1] == 0 && b[2] == 0xFE && b[3] == 0xFF) {
        set_name(enc, "UTF-32BE");
        enc->bomlen = 4;
    } else if (len >= 4 && b[0] == 0xFF && b[1] == 0xFE && b[2] == 0 && b[3] == 0) {
        set_name(enc, "UTF-32LE");
        enc->bomlen = 4;
    } else if (len >= 2 && b[0] == 0xFE && b[1] == 0xFF) {
        set_name(enc, "UTF-16BE");
        enc->bomlen = 2;
    } else if (len >= 2 && b[0] == 0xFF && b[1] == 0xFE) {
        set_name(enc, "UTF-16LE");
        enc->bomlen = 2;
    } else if (len >= 3 && b[0] == 0xEF && b[1] == 0xBB && b[2] == 0xBF) {
        return 0; /* UTF-8 with its mark: read as it is */
    } else if (len >= 4 && b[0] == 0 && b[1] == 0 && b[2] == 0 && b[3] == '<') {
        set_name(enc, "UTF-32BE");
    } else if (len >= 4 && b[0] == '<' && b[1] == 0 && b[2] == 0 && b[3] == 0) {
        set_name(enc, "UTF-32LE");
    } else if (len >= 2 && b[0] == 0 && b[1] == '<') {
        set_name(enc, "UTF-16BE");
    } else if (len >= 2 && b[0] == '<' && b[1] == 0) {
        set_name(enc, "UTF-16LE");
    } else if (len >= 4 && b[0] == 0x4C && b[1] == 0x6F && b[2] == 0xA7 && b[3] == 0x94) {
        /* EBCDIC "<?xm": the characters of a declaration are the same in
         * every EBCDIC code page, so read it through one of them */
        char head[4 * ENC_DECL_SCAN], *in = (char *)b, *o = head;
        size_t il = len < ENC_DECL_SCAN ? len : ENC_DECL_SCAN, ol = sizeof head, n;
        iconv_t cd = iconv_open("UTF-8", "IBM037");
        if (cd != (iconv_t)-1) {
            (void)iconv(cd, &in, &il, &o, &ol); /* up to the first byte it cannot read */
            iconv_close(cd);
        }
        n = (size_t)(o - head);
        decl_encoding(head, n, declared, sizeof declared);
        if (!declared[0]) {
            snprintf(why, cap, "an EBCDIC document without an encoding declaration "
                               "(which code page it is cannot be told)");
            return 1;
        }
        set_name(enc, declared);
        return 0;
    } else {
        decl_encoding((const char *)b, len < ENC_DECL_SCAN ? len : ENC_DECL_SCAN, declared,
                      sizeof declared);
        if (declared[0] && !is_utf8(declared) && !name_is(declared, "UTF-16") &&
            !name_is(declared, "UTF-32"))
            set_name(enc, declared);
        return 0;
    }
    memcpy(enc->bom, b, enc->bomlen);
    return 0;
}

static size_t count_lines(const char *s, size_t n)
{
    size_t k = 1, i;
    for (i = 0; i < n; i++)
        k += s[i] == '\n';
    return k;
}

/* Convert every printable ASCII character (and the white space) to enc
 * and back: what a save writes must survive the trip. */
static int holds_ascii(const char *name)
{
    char probe[100], back[100], mid[800];
    size_t n = 0, i;
    int c, ok = 0;
    iconv_t to = iconv_open(name, "UTF-8"), from;
    if (to == (iconv_t)-1)
        return 0;
    from = iconv_open("UTF-8", name);
    if (from == (iconv_t)-1) {
        iconv_close(to);
        return 0;
    }
    for (c = ' '; c <= '~'; c++)
        probe[n++] = (char)c;
    probe[n++] = '\t';
    probe[n++] = '\n';
    probe[n++] = '\r';
    {
        char *in = probe, *out = mid, *in2, *out2 = back;
        size_t il = n, ol = sizeof mid, il2, ol2 = sizeof back;
        if (iconv(to, &in, &il, &out, &ol) != (size_t)-1 &&
            iconv(to, NULL, NULL, &out, &ol) != (size_t)-1 && il == 0) {
            in2 = mid;
            il2 = sizeof mid - ol;
            if (iconv(from, &in2, &il2, &out2, &ol2) != (size_t)-1 && il2 == 0 &&
                sizeof back - ol2 == n) {
                ok = 1;
                for (i = 0; i < n; i++)
                    ok &= back[i] == probe[i];
            }
        }
    }
    iconv_close(to);
    iconv_close(from);
    return ok;
}

int conica_svg__enc_decode(const char *buf, size_t len, size_t max_out, conica_svg__enc *enc,
                           char **out, size_t *outlen, char *why, size_t cap, size_t *line,
                           int *nomem)
{
    iconv_t cd;
    char *dst = NULL, *in, *o;
    size_t dcap, il, ol, used;
    *out = NULL;
    *outlen = 0;
    *line = 0;
    *nomem = 0;
    if (detect((const unsigned char *)buf, len, enc, why, cap))
        return 1;
    if (!enc->name[0])
        return 0;
    cd = iconv_open("UTF-8", enc->name);
    if (cd == (iconv_t)-1) {
        snprintf(why, cap, "the document's encoding '%s' is not supported", enc->name);
        return 1;
    }
    if (!holds_ascii(enc->name)) {
        iconv_close(cd);
        snprintf(why, cap,
                 "the document's encoding '%s' cannot hold the path data a save writes "
                 "(ASCII letters, digits and signs); nothing written",
                 enc->name);
        return 1;
    }
    /* UTF-16 to UTF-8 grows at most 3/2, one byte to UTF-8 at most 3x */
    dcap = len < 64 ? 256 : (len - enc->bomlen) * 2;
    in = (char *)buf + enc->bomlen;
    il = len - enc->bomlen;
    used = 0;
    for (;;) {
        size_t r;
        if (!dst || used + 8 > dcap) {
            char *t;
            if (dst)
                dcap *= 2;
            if (dcap > max_out + 8)
                dcap = max_out + 8;
            t = used + 8 > dcap ? NULL : realloc(dst, dcap);
            if (!t) {
                free(dst);
                iconv_close(cd);
                if (used + 8 > dcap) {
                    snprintf(why, cap, "the document as UTF-8 is larger than the limit of %zu "
                                       "bytes", max_out);
                    return 1;
                }
                *nomem = 1;
                snprintf(why, cap, "out of memory");
                return 1;
            }
            dst = t;
        }
        o = dst + used;
        ol = dcap - used - 1;
        r = iconv(cd, &in, &il, &o, &ol);
        used = (size_t)(o - dst);
        if (r != (size_t)-1 && il == 0)
            break;
        if (r == (size_t)-1 && errno == E2BIG)
            continue;
        *line = count_lines(dst, used);
        snprintf(why, cap, "%s at byte %zu: not valid %s",
                 errno == EINVAL ? "the document ends inside a character" : "a byte sequence",
                 (size_t)(in - buf), enc->name);
        free(dst);
        iconv_close(cd);
        return 1;
    }
    iconv_close(cd);
    if (used > max_out) {
        free(dst);
        snprintf(why, cap, "the document as UTF-8 is larger than the limit of %zu bytes",
                 max_out);
        return 1;
    }
    dst[used] = '\0';
    *out = dst;
    *outlen = used;
    return 0;
}

int conica_svg__encoder_open(conica_svg__encoder *e, const conica_svg__enc *enc)
{
    memset(e, 0, sizeof *e);
    if (!enc || !enc->name[0])
        return 0;
    {
        iconv_t cd = iconv_open(enc->name, "UTF-8");
        if (cd == (iconv_t)-1)
            return 1;
        e->cd = cd;
    }
    return 0;
}

/* Convert *in (il bytes) into put; returns 0 (all done), 1 (a character
 * without a form), 2 (an incomplete sequence left in *in). */
static int convert(conica_svg__encoder *e, char **in, size_t *il,
                   void (*put)(void *, const char *, size_t), void *ctx)
{
    char buf[4096];
    for (;;) {
        char *o = buf;
        size_t ol = sizeof buf, r;
        r = iconv((iconv_t)e->cd, in, il, &o, &ol);
        if (o > buf)
            put(ctx, buf, (size_t)(o - buf));
        if (r != (size_t)-1 && (!in || *il == 0))
            return 0;
        if (r == (size_t)-1 && errno == E2BIG)
            continue;
        if (r == (size_t)-1 && errno == EINVAL)
            return 2;
        return 1;
    }
}

int conica_svg__encoder_put(conica_svg__encoder *e, const char *data, size_t n,
                            void (*put)(void *ctx, const char *bytes, size_t count), void *ctx)
{
    char *in;
    size_t il;
    int r;
    if (!e->cd) {
        if (data && n)
            put(ctx, data, n);
        return 0;
    }
    if (!data) {
        if (e->ncarry)
            return 1;
        return convert(e, NULL, NULL, put, ctx) != 0;
    }
    /* finish a sequence the last call left open, a byte at a time */
    while (e->ncarry && n) {
        e->carry[e->ncarry++] = *data++;
        n--;
        in = e->carry;
        il = e->ncarry;
        r = convert(e, &in, &il, put, ctx);
        if (r == 1)
            return 1;
        if (r == 0)
            e->ncarry = 0;
        else if (e->ncarry >= 4)
            return 1;
    }
    if (!n)
        return 0;
    in = (char *)data;
    il = n;
    r = convert(e, &in, &il, put, ctx);
    if (r == 2) {
        if (il > 4)
            return 1;
        memcpy(e->carry, in, il);
        e->ncarry = il;
        return 0;
    }
    return r;
}

void conica_svg__encoder_close(conica_svg__encoder *e)
{
    if (e->cd)
        iconv_close((iconv_t)e->cd);
    e->cd = NULL;
    e->ncarry = 0;
}
