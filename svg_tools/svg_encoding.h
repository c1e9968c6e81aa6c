/* SPDX-License-Identifier: MIT */
/* The character encoding of an SVG document, for reading and for the
 * byte-true save (svg_encoding.c): a document in any encoding is read as
 * UTF-8 (libxml2 parses that copy, our caps are counted on it) and written
 * back in its own encoding, byte for byte outside the rewritten values.
 * Internal to the SVG layer (conica_svg__ prefix; calls iconv only). */
#ifndef CONICA_SVG_ENCODING_H
#define CONICA_SVG_ENCODING_H

#include <stddef.h>

/* The longest encoding name kept (IANA names are at most 40 bytes). */
#define CONICA_SVG_ENC_NAME_MAX 48

typedef struct conica_svg__enc {
    char name[CONICA_SVG_ENC_NAME_MAX]; /* iconv's name; "" for UTF-8 (no conversion) */
    unsigned char bom[4];               /* the byte-order mark the input started with */
    size_t bomlen;
} conica_svg__enc;

/* The encoding of buf (the byte-order mark, the first bytes of "<?xml",
 * then the declaration's encoding="..."), and when it is not UTF-8 (or
 * ASCII) the document converted to UTF-8 without its byte-order mark in
 * *out (malloc'd, *outlen bytes, at most max_out), else *out NULL. An
 * encoding that cannot hold every printable ASCII character (what a save
 * writes into the document) is refused here, before anything is written.
 * Returns 0, or 1 with a message in why and the line (1-based, 0 unknown)
 * of a byte that is not valid in the encoding. Set *nomem on out of
 * memory. */
int conica_svg__enc_decode(const char *buf, size_t len, size_t max_out, conica_svg__enc *enc,
                           char **out, size_t *outlen, char *why, size_t cap, size_t *line,
                           int *nomem);

/* The output side: UTF-8 bytes in, the document's encoding out. */
typedef struct conica_svg__encoder {
    void *cd;            /* iconv_t, NULL for UTF-8 */
    char carry[8];       /* an incomplete UTF-8 sequence held for the next write */
    size_t ncarry;
} conica_svg__encoder;

/* Open an encoder for enc (no-op for UTF-8). Returns 0, or 1. */
int conica_svg__encoder_open(conica_svg__encoder *e, const conica_svg__enc *enc);
/* Convert n bytes (a sequence may straddle calls), handing the result to
 * put(ctx, bytes, count). Returns 0, or 1 when a character has no form in
 * the encoding. With data NULL: the end (a stateful encoding's final
 * shift, an incomplete sequence is an error). */
int conica_svg__encoder_put(conica_svg__encoder *e, const char *data, size_t n,
                            void (*put)(void *ctx, const char *bytes, size_t count), void *ctx);
void conica_svg__encoder_close(conica_svg__encoder *e);

#endif
