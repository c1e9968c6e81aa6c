/* SPDX-License-Identifier: MIT */
/* Tests of the long double side of libcore's text reading (precise mode):
 * conica__parse_long_double (numparse.c) and conica_curvel_parse_ex
 * (curve.c). The oracles are independent of the reader: exact decimal
 * expansions of midpoints between two long doubles built here with a small
 * decimal bignum (round half to even decides them), %.21Lg round trips,
 * and glibc's strtold in the C locale for random long digit strings. */
#include "conica_test.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/curve.h"
#include "conica/subdiv.h"
#include "numparse.h"

/* Digits of the decimal bignum below (a midpoint near 2^-16446 has 11 515). */
#define BIG_DIGITS 12000

static ct_rng rng;

static int numl(const char *s, long double *v, size_t *used)
{
    return conica__parse_long_double(s, strlen(s), v, used);
}

/* Little-endian decimal digits d[0..*n) of an integer. */
static void big_from_u64(unsigned char *d, size_t *n, uint64_t v)
{
    *n = 0;
    do {
        d[(*n)++] = (unsigned char)(v % 10);
        v /= 10;
    } while (v);
}

static void big_mul_add(unsigned char *d, size_t *n, unsigned mul, unsigned add)
{
    size_t i;
    unsigned carry = add;
    for (i = 0; i < *n; i++) {
        unsigned t = d[i] * mul + carry;
        d[i] = (unsigned char)(t % 10);
        carry = t / 10;
    }
    while (carry && *n < BIG_DIGITS) {
        d[(*n)++] = (unsigned char)(carry % 10);
        carry /= 10;
    }
    REQUIRE(carry == 0);
}

/* The exact decimal text of (2m + 1) 2^e ("DIGITSe-K" or "DIGITS"), the
 * midpoint between m 2^(e+1) and (m + 1) 2^(e+1); `extra` digits are
 * appended after the last one (scaling the exponent to match). */
static void midpoint_text(uint64_t m, int e, const char *extra, char *buf, size_t cap)
{
    static unsigned char d[BIG_DIGITS];
    size_t n, i, k = 0, ne = strlen(extra);
    long dexp = 0;
    big_from_u64(d, &n, m);
    big_mul_add(d, &n, 2, 1);
    for (; e > 0; e--)
        big_mul_add(d, &n, 2, 0);
    for (; e < 0; e++) { /* 2^-1 = 5 * 10^-1 */
        big_mul_add(d, &n, 5, 0);
        dexp--;
    }
    REQUIRE(n + ne + 32 < cap);
    for (i = n; i-- > 0;)
        buf[k++] = (char)('0' + d[i]);
    memcpy(buf + k, extra, ne);
    k += ne;
    snprintf(buf + k, cap - k, "e%ld", dexp - (long)ne);
}

TEST_CASE("long double reader: plain forms, zeros, errors", "[numparse][precise]")
{
    long double v = 0;
    size_t used = 0;
    CHECK_EQ(numl("0.1", &v, &used), CONICA__NUM_OK);
    CHECK(v == 0.1L);
    CHECK(v != (long double)0.1); /* more than double's 53 bits */
    CHECK_EQ_U(used, 3);
    CHECK_EQ(numl("-2.5e-3x", &v, &used), CONICA__NUM_OK);
    CHECK(v == -2.5e-3L);
    CHECK_EQ_U(used, 7);
    CHECK_EQ(numl("-0.000", &v, &used), CONICA__NUM_OK);
    CHECK(v == 0.0L && signbit(v));
    CHECK_EQ(numl("1e", &v, &used), CONICA__NUM_OK);
    CHECK(v == 1.0L);
    CHECK_EQ_U(used, 1);
    CHECK_EQ(numl("1e4000", &v, &used), CONICA__NUM_OK); /* within LDBL_MAX */
    CHECK(v == 1e4000L);
    CHECK_EQ(numl("1e5000000", &v, &used), CONICA__NUM_NONFINITE);
    CHECK_EQ(numl("inf", &v, &used), CONICA__NUM_NONFINITE);
    CHECK_EQ(numl("nan", &v, &used), CONICA__NUM_NONFINITE);
    CHECK_EQ(numl(".", &v, &used), CONICA__NUM_SYNTAX);
    CHECK_EQ(numl("e5", &v, &used), CONICA__NUM_SYNTAX);
    CHECK_EQ(numl("0x10", &v, &used), CONICA__NUM_OK); /* "0", then junk */
    CHECK_EQ_U(used, 1);
    CHECK_EQ(conica__parse_long_double("12345", 3, &v, &used), CONICA__NUM_OK);
    CHECK(v == 123.0L);
}

TEST_CASE("long double reader: %.21Lg of random long doubles round-trips exactly",
          "[numparse][precise]")
{
    long i, mismatches = 0;
    ct_rng_init(&rng, 0x243F6A8885A308D3ull);
    for (i = 0; i < 100000; i++) {
        uint64_t mant = ct_rng_next(&rng) | ((uint64_t)1 << 63);
        int ex = (int)ct_rng_below(&rng, 2 * 1000) - 1000;
        long double x = ldexpl((long double)mant, ex - 63), y = 0;
        size_t used;
        char buf[64];
        if (i % 2)
            x = -x;
        snprintf(buf, sizeof buf, "%.21Lg", x);
        if (numl(buf, &y, &used) != CONICA__NUM_OK || x != y || used != strlen(buf))
            mismatches++;
    }
    CHECK_EQ(mismatches, 0);
}

TEST_CASE("long double reader: exact midpoints round half to even, one digit more decides",
          "[numparse][precise]")
{
    /* (2m+1) 2^(e-1) lies halfway between x = m 2^e and its successor; the
     * 64-bit significand m (top bit set) is odd or even at random. */
    static char buf[BIG_DIGITS + 64];
    long i, mismatches = 0;
    ct_rng_init(&rng, 0x13198A2E03707344ull);
    for (i = 0; i < 3000; i++) {
        uint64_t m = ct_rng_next(&rng) | ((uint64_t)1 << 63);
        int e = (int)ct_rng_below(&rng, 400) - 263; /* x from about 1e-60 to 1e60 */
        long double x = ldexpl((long double)m, e), up = nextafterl(x, INFINITY), v = 0;
        size_t used;
        midpoint_text(m, e - 1, "", buf, sizeof buf);
        if (numl(buf, &v, &used) != CONICA__NUM_OK || v != ((m & 1) ? up : x))
            mismatches++;
        midpoint_text(m, e - 1, "000000000000000000001", buf, sizeof buf);
        if (numl(buf, &v, &used) != CONICA__NUM_OK || v != up)
            mismatches++;
    }
    CHECK_EQ(mismatches, 0);
}

TEST_CASE("long double reader: midpoints needing over 11 000 digits, with a far sticky digit",
          "[numparse][precise]")
{
    /* Near the smallest normal long double the midpoint's expansion has
     * about 11 500 significant digits; a non-zero digit after another 200
     * zeros lies past the reader's kept digits and must still round up. */
    static char buf[BIG_DIGITS + 400];
    char extra[202];
    int i;
    memset(extra, '0', 200);
    extra[200] = '1';
    extra[201] = '\0';
    for (i = 0; i < 3; i++) {
        uint64_t m = ((uint64_t)1 << 63) | ((uint64_t)0x9E3779B97F4A7C15ull >> (i + 1)), mm;
        int e = LDBL_MIN_EXP - 64 + 2 * i; /* x = m 2^e >= LDBL_MIN */
        long double x = ldexpl((long double)m, e), v = 0;
        size_t used;
        mm = m & ~(uint64_t)1; /* even: the midpoint alone rounds down */
        x = ldexpl((long double)mm, e);
        midpoint_text(mm, e - 1, "", buf, sizeof buf);
        CHECK(strlen(buf) > 11000);
        REQUIRE_EQ(numl(buf, &v, &used), CONICA__NUM_OK);
        CHECK(v == x);
        midpoint_text(mm, e - 1, extra, buf, sizeof buf);
        REQUIRE_EQ(numl(buf, &v, &used), CONICA__NUM_OK);
        CHECK(v == nextafterl(x, INFINITY));
    }
}

TEST_CASE("long double reader: agrees with glibc strtold on random long inputs",
          "[numparse][precise]")
{
    long i, mismatches = 0;
    ct_rng_init(&rng, 4242);
    for (i = 0; i < 5000; i++) {
        char buf[1200];
        size_t k = 0, used = 0;
        int nd = (int)ct_rng_below(&rng, 1000) + 1, j;
        long double a = 0, b;
        if (i % 3 == 0)
            buf[k++] = '-';
        for (j = 0; j < nd; j++) {
            buf[k++] = (char)('0' + ct_rng_below(&rng, 10));
            if (j == 0 && i % 2)
                buf[k++] = '.';
        }
        snprintf(buf + k, sizeof buf - k, "e%d", (int)ct_rng_below(&rng, 1200) - 900);
        b = strtold(buf, NULL);
        if (!isfinite(b))
            continue;
        if (numl(buf, &a, &used) != CONICA__NUM_OK || a != b || used != strlen(buf))
            mismatches++;
    }
    CHECK_EQ(mismatches, 0);
}

TEST_CASE("curvel_parse_ex: 25-digit samples keep their long double value",
          "[curve][parse][precise]")
{
    const char *text = "# a circle's samples with 25 digits\n"
                       "v 5.000000000000000000000000 0\n"
                       "v 2.500000000000000000000000 4.330127018922193233818615\n"
                       "v -2.500000000000000000000000 4.330127018922193233818615\n"
                       "vn 1 0\n"
                       "vn 0.5 0.8660254037844386467637232\n"
                       "vn -0.5 0.8660254037844386467637232\n";
    conica_curvel c;
    conica_curve d;
    conica_status st;
    conica_curvel_init(&c);
    conica_curve_init(&d);
    REQUIRE_EQ(conica_curvel_parse_ex(text, strlen(text), 0, &c, &st), CONICA_OK);
    REQUIRE_EQ_U(c.n, 3);
    REQUIRE(c.nxy != NULL);
    CHECK(c.closed == 1);
    CHECK(c.xy[3] == strtold("4.330127018922193233818615", NULL));
    CHECK(c.nxy[3] == strtold("0.8660254037844386467637232", NULL));
    /* the double reader rounds to 53 bits: a different value */
    REQUIRE_EQ(conica_curve_parse(text, strlen(text), &d, NULL), CONICA_OK);
    CHECK((long double)d.xy[3] != c.xy[3]);
    CHECK(d.xy[3] == (double)c.xy[3]);
    conica_curve_free(&d);
    conica_curvel_free(&c);
}

TEST_CASE("curvel_parse_ex: the double reader's errors, lines and cap", "[curve][parse][precise]")
{
    struct {
        const char *text;
        conica_code code;
        size_t line;
    } cases[] = {
        {"v 0 0\nv 1 1e400\n", CONICA_ERR_NONFINITE, 2}, /* beyond double, as in double mode */
        {"v 0 0\nv 1 nan\n", CONICA_ERR_NONFINITE, 2},
        {"v 0 0\nv 1 2x\n", CONICA_ERR_PARSE, 2},
        {"v 0 0\nv 1\n", CONICA_ERR_PARSE, 2},
        {"v 0 0\nv 1 1\nvn 1 0\nvn 0 0\n", CONICA_ERR_DEGENERATE, 4},
        {"v 0 0\nv 1 1\nvn 1 0\n", CONICA_ERR_PARSE, 3},
        {"# nothing\n", CONICA_ERR_PARSE, 1},
        {"v 0 0\nv 1 1\nv 2 2\n", CONICA_ERR_LIMIT, 3},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        conica_curvel c;
        conica_status st;
        INFO("case %zu: %s", i, cases[i].text);
        conica_curvel_init(&c);
        memset(&st, 0, sizeof st);
        CHECK_EQ(conica_curvel_parse_ex(cases[i].text, strlen(cases[i].text), 2, &c, &st),
                 cases[i].code);
        CHECK_EQ_U(st.line, cases[i].line);
        CHECK(c.xy == NULL); /* untouched on failure */
        conica_curvel_free(&c);
    }
    CHECK_EQ(conica_curvel_parse_ex("v 0 0\n", 6, 0, NULL, NULL), CONICA_ERR_ARG);
}
