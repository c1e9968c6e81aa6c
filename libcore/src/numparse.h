/* SPDX-License-Identifier: MIT */
/* Locale-independent, correctly rounded decimal -> double reader shared by
 * libcore's text parsers (curve files here; spline and SVG parsers reuse it).
 *
 * Why not strtod: strtod obeys LC_NUMERIC, so a program that called
 * setlocale(LC_ALL, "") in a German locale would read "1.5" as 1. The
 * reader below validates the grammar itself and never looks at the locale:
 * see numparse.c for how it stays correctly rounded. */
#ifndef CONICA_NUMPARSE_H
#define CONICA_NUMPARSE_H

#include <stddef.h>

/* Results of conica__parse_double(). */
enum {
    CONICA__NUM_OK = 0,      /* *out holds a finite, correctly rounded value */
    CONICA__NUM_SYNTAX = 1,  /* no number starts at s */
    CONICA__NUM_NONFINITE = 2,/* "nan"/"inf"/"infinity" literal, or a value beyond DBL_MAX */
};

/*
 * Read one decimal number at the start of s[0..len): grammar
 *     [+-]? ( digits [ '.' digits? ] | '.' digits ) ( [eE] [+-]? digits )?
 * No leading whitespace, no hex, no digit grouping. An 'e' not followed by
 * an exponent is not consumed. On CONICA__NUM_OK, *out is the correctly
 * rounded double (round-half-even) and *consumed the bytes read; on
 * CONICA__NUM_NONFINITE, *consumed still covers the offending token (so a
 * caller can report it) and *out is untouched; on CONICA__NUM_SYNTAX both
 * are untouched. The input is never written to and need not be
 * NUL-terminated.
 */
int conica__parse_double(const char *s, size_t len, double *out, size_t *consumed);

/* The same grammar and results for long double (precise mode): *out is
 * the correctly rounded long double (the 64-bit significand of x87 long
 * double on x86-64), CONICA__NUM_NONFINITE beyond LDBL_MAX. */
int conica__parse_long_double(const char *s, size_t len, long double *out, size_t *consumed);

#endif
