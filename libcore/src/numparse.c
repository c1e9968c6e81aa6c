/* SPDX-License-Identifier: MIT */
/* Locale-independent, correctly rounded decimal -> double conversion.
 *
 * How it stays exact without the locale:
 * 1. We parse the grammar ourselves and collect the significant decimal
 *    digits and a decimal exponent: value = D * 10^E, D an integer.
 * 2. Fast path (Clinger 1990): when D has at most 19 digits, D <= 2^53 and
 *    |E| <= 22, both D and 10^|E| are exact doubles, so one IEEE multiply
 *    or divide gives the correctly rounded result. (A long double path is
 *    deliberately not used: rounding to 64 bits and then to 53 can round
 *    twice.) The fast path is only taken when FLT_EVAL_METHOD == 0, i.e.
 *    when double arithmetic really is done in double.
 * 3. Otherwise we write the digits as a canonical token "[-]DDDDe[-]N" into
 *    a small stack buffer and call strtod on it. That token contains no
 *    decimal point, so LC_NUMERIC cannot change how strtod reads it
 *    (strtod never groups digits); glibc's strtod is correctly rounded.
 *    Tokens longer than CANON_DIGITS significant digits are cut there with
 *    a sticky non-zero digit appended: 767 significant digits decide the
 *    rounding of any double, so the cut never changes the result.
 *    (The Conica tools never call setlocale() anyway, so their LC_NUMERIC
 *    is "C"; the canonical token makes library callers that do safe too.)
 * 4. The long double reader (conica__parse_long_double, for precise mode)
 *    scans the same grammar into the same token and always calls strtold,
 *    correctly rounded to the 64-bit significand of x87 long double by
 *    glibc. The cut must then keep CANON_DIGITS_L digits: the longest
 *    decimal expansion of a midpoint between two long doubles (the
 *    smallest binade, (2^65 - 1) 2^-16446) has 11 515 significant digits
 *    (11 564 for IEEE binary128, 768 for double).
 */
#include "numparse.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Significant digits kept for the slow path (> 767, see above). */
#define CANON_DIGITS 780
/* The same for long double (> 11 564, see above). */
#define CANON_DIGITS_L 11600
/* Exponents beyond this saturate: 10^100000 overflows and 10^-100000
 * underflows any double whatever the digits (at most 2^31 of them). */
#define EXP_SATURATE 100000L
/* Largest power of ten that is an exact double. */
#define FAST_MAX_POW10 22

static const double pow10_exact[FAST_MAX_POW10 + 1] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int lower(char c)
{
    return (c >= 'A' && c <= 'Z') ? c - 'A' + 'a' : c;
}

/* Case-insensitive match of the literal word at s[0..len). */
static int match_word(const char *s, size_t len, const char *word)
{
    size_t i, n = strlen(word);
    if (len < n)
        return 0;
    for (i = 0; i < n; i++)
        if (lower(s[i]) != word[i])
            return 0;
    return 1;
}

/* A scanned number: significant digits canon[1..nd], value
 * canon * 10^dexp, sticky when non-zero digits beyond `cap` were dropped. */
typedef struct scanned {
    size_t nd, pos;
    long long dexp;
    int neg, sticky;
} scanned;

/* Scan the grammar of conica__parse_double into canon (cap significant
 * digits at most, canon holding cap + 40 bytes). Returns CONICA__NUM_OK
 * with *sc filled (nd == 0 for a zero), or the literal's result with
 * *consumed set for CONICA__NUM_NONFINITE. */
static int scan_number(const char *s, size_t len, char *canon, size_t cap, scanned *sc,
                       size_t *consumed)
{
    size_t i = 0, nd = 0, int_digits = 0, frac_digits = 0;
    long long dexp = 0; /* value = digits-in-canon * 10^(dexp + exp10) */
    long exp10 = 0;
    int neg = 0, sticky = 0, seen_nonzero = 0;

    if (i < len && (s[i] == '+' || s[i] == '-'))
        neg = s[i++] == '-';
    if (i < len && (lower(s[i]) == 'n' || lower(s[i]) == 'i')) {
        size_t n = 0;
        if (match_word(s + i, len - i, "nan"))
            n = 3;
        else if (match_word(s + i, len - i, "infinity"))
            n = 8;
        else if (match_word(s + i, len - i, "inf"))
            n = 3;
        if (n == 0)
            return CONICA__NUM_SYNTAX;
        *consumed = i + n;
        return CONICA__NUM_NONFINITE;
    }

    /* Mantissa: collect significant digits (leading zeros dropped). */
    for (; i < len && is_digit(s[i]); i++, int_digits++) {
        int d = s[i] - '0';
        if (!seen_nonzero && d == 0)
            continue;
        seen_nonzero = 1;
        if (nd < cap)
            canon[1 + nd++] = s[i];
        else {
            dexp++; /* integer digit beyond the kept ones: scales by 10 */
            sticky |= d != 0;
        }
    }
    if (i < len && s[i] == '.') {
        i++;
        for (; i < len && is_digit(s[i]); i++, frac_digits++) {
            int d = s[i] - '0';
            if (!seen_nonzero && d == 0) {
                dexp--; /* 0.00d = d * 10^-3 */
                continue;
            }
            seen_nonzero = 1;
            if (nd < cap) {
                canon[1 + nd++] = s[i];
                dexp--;
            } else
                sticky |= d != 0;
        }
    }
    if (int_digits + frac_digits == 0)
        return CONICA__NUM_SYNTAX;

    /* Exponent: only consumed when it has digits. */
    if (i < len && (s[i] == 'e' || s[i] == 'E')) {
        size_t j = i + 1;
        int eneg = 0;
        if (j < len && (s[j] == '+' || s[j] == '-'))
            eneg = s[j++] == '-';
        if (j < len && is_digit(s[j])) {
            for (; j < len && is_digit(s[j]); j++)
                if (exp10 < EXP_SATURATE)
                    exp10 = exp10 * 10 + (s[j] - '0');
            if (eneg)
                exp10 = -exp10;
            i = j;
        }
    }
    sc->pos = i;
    sc->neg = neg;
    sc->nd = nd;
    sc->sticky = sticky;
    sc->dexp = 0;
    if (nd == 0) /* all digits zero */
        return CONICA__NUM_OK;
    /* Trailing zeros of the kept digits only scale the value. */
    if (!sticky)
        while (nd > 1 && canon[nd] == '0') {
            nd--;
            dexp++;
        }
    sc->nd = nd;
    sc->dexp = dexp + exp10;
    return CONICA__NUM_OK;
}

/* Finish the canonical token "[+-]DDDD[1]e[-]N" of *sc in canon (which
 * has 40 bytes to spare after the digits). */
static void canon_token(char *canon, size_t size, const scanned *sc)
{
    size_t k = 1 + sc->nd;
    long long dexp = sc->dexp;
    canon[0] = sc->neg ? '-' : '+';
    if (sc->sticky) { /* any non-zero beyond the kept digits */
        canon[k++] = '1';
        dexp--;
    }
    if (dexp > EXP_SATURATE)
        dexp = EXP_SATURATE;
    if (dexp < -EXP_SATURATE)
        dexp = -EXP_SATURATE;
    snprintf(canon + k, size - k, "e%lld", dexp);
}

int conica__parse_double(const char *s, size_t len, double *out, size_t *consumed)
{
    char canon[CANON_DIGITS + 40];
    scanned sc;
    size_t nd, pos;
    long long dexp;
    int neg, sticky;
    int r = scan_number(s, len, canon, CANON_DIGITS, &sc, consumed);
    if (r != CONICA__NUM_OK)
        return r;
    nd = sc.nd;
    pos = sc.pos;
    dexp = sc.dexp;
    neg = sc.neg;
    sticky = sc.sticky;
    if (nd == 0) {
        *out = neg ? -0.0 : 0.0;
        *consumed = pos;
        return CONICA__NUM_OK;
    }

#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD == 0
    if (!sticky && nd <= 19 && dexp >= -FAST_MAX_POW10 && dexp <= FAST_MAX_POW10 + 15) {
        uint64_t d = 0;
        size_t k;
        for (k = 1; k <= nd; k++)
            d = d * 10 + (uint64_t)(canon[k] - '0');
        if (d <= ((uint64_t)1 << 53)) {
            long long e = dexp;
            int ok = 1;
            /* D * 10^e with e > 22: move the excess into D while it stays exact. */
            while (e > FAST_MAX_POW10) {
                if (d > ((uint64_t)1 << 53) / 10) {
                    ok = 0;
                    break;
                }
                d *= 10;
                e--;
            }
            if (ok) {
                double v = (double)d; /* exact: d <= 2^53 */
                v = e >= 0 ? v * pow10_exact[e] : v / pow10_exact[-e];
                *out = neg ? -v : v;
                *consumed = pos;
                return CONICA__NUM_OK;
            }
        }
    }
#endif

    /* Slow path: canonical token without a decimal point, then strtod. */
    {
        char *end;
        double v;
        canon_token(canon, sizeof canon, &sc);
        v = strtod(canon, &end);
        if (!isfinite(v)) {
            *consumed = pos;
            return CONICA__NUM_NONFINITE;
        }
        *out = v;
        *consumed = pos;
        return CONICA__NUM_OK;
    }
}

int conica__parse_long_double(const char *s, size_t len, long double *out, size_t *consumed)
{
    char canon[CANON_DIGITS_L + 40];
    scanned sc;
    char *end;
    long double v;
    int r = scan_number(s, len, canon, CANON_DIGITS_L, &sc, consumed);
    if (r != CONICA__NUM_OK)
        return r;
    if (sc.nd == 0) {
        *out = sc.neg ? -0.0L : 0.0L;
        *consumed = sc.pos;
        return CONICA__NUM_OK;
    }
    canon_token(canon, sizeof canon, &sc);
    v = strtold(canon, &end);
    *consumed = sc.pos;
    if (!isfinite(v))
        return CONICA__NUM_NONFINITE;
    *out = v;
    return CONICA__NUM_OK;
}
