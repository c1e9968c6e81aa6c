/* SPDX-License-Identifier: MIT */
/* Tests of libcore/src/curve.c and numparse.c: the `v`/`vn` text format,
 * the locale-independent number reader, and normal estimation. */
#include "conica_test.h"

#include <locale.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/curve.h"
#include "numparse.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* fixed seeds, reproducible everywhere */
static ct_rng rng;
static uint64_t rng_next(void)
{
    return ct_rng_next(&rng);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static conica_code parse_str(const char *text, conica_curve *c, conica_status *st)
{
    return conica_curve_parse(text, strlen(text), c, st);
}

/* ------------------------------------------------------------ numbers */

static int num(const char *s, double *v, size_t *used)
{
    return conica__parse_double(s, strlen(s), v, used);
}

TEST_CASE("number reader: plain and exponent forms", "[numparse]")
{
    static const struct {
        const char *text;
        double value;
        size_t used;
    } cases[] = {
        {"0", 0.0, 1},         {"1", 1.0, 1},           {"-2.5", -2.5, 4},
        {"+.5", 0.5, 3},       {"5.", 5.0, 2},          {"1e5", 1e5, 3},
        {"1E+5", 1e5, 4},      {"-2.5e-3", -2.5e-3, 7}, {"0.1", 0.1, 3},
        {"000123.4500", 123.45, 11}, {"1e", 1.0, 1},    {"2e+", 2.0, 1},
        {"3.0x", 3.0, 3},      {"7 8", 7.0, 1},         {"4.9e-324", 4.9e-324, 8},
        {"1e-400", 0.0, 6},    {"1.7976931348623157e308", 1.7976931348623157e308, 22},
        {"9007199254740993", 9007199254740992.0, 16}, /* halfway: ties to even */
        {"0.30000000000000004", 0.30000000000000004, 19},
        {"1e00000000000000000000000000003", 1e3, 31},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double v = -99.0;
        size_t used = 0;
        INFO("text '%s'", cases[i].text);
        CHECK_EQ(num(cases[i].text, &v, &used), CONICA__NUM_OK);
        CHECK(same_bits(v, cases[i].value));
        CHECK_EQ(used, cases[i].used);
    }
    {
        double v = 1.0;
        size_t used = 0;
        CHECK_EQ(num("-0.0", &v, &used), CONICA__NUM_OK);
        CHECK(v == 0.0 && signbit(v));
    }
}

TEST_CASE("number reader: what is not a number", "[numparse]")
{
    static const char *const bad[] = {"", "-", "+", ".", "-.", "e5", "abc", ",5", " 1", "0x"};
    static const char *const nonfinite[] = {"nan", "NaN", "-inf", "Infinity", "1e400", "-1e99999999999"};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double v = 42.0;
        size_t used = 7;
        INFO("text '%s'", bad[i]);
        if (strcmp(bad[i], "0x") == 0) { /* reads the 0, stops at x */
            CHECK_EQ(num(bad[i], &v, &used), CONICA__NUM_OK);
            CHECK_EQ(used, 1u);
            continue;
        }
        CHECK_EQ(num(bad[i], &v, &used), CONICA__NUM_SYNTAX);
        CHECK(v == 42.0);
        CHECK_EQ(used, 7u);
    }
    for (i = 0; i < sizeof nonfinite / sizeof nonfinite[0]; i++) {
        double v = 42.0;
        size_t used = 0;
        INFO("text '%s'", nonfinite[i]);
        CHECK_EQ(num(nonfinite[i], &v, &used), CONICA__NUM_NONFINITE);
        CHECK(v == 42.0);
        CHECK_EQ(used, strlen(nonfinite[i]));
    }
}

TEST_CASE("number reader: length-bounded, never reads past len", "[numparse]")
{
    double v = 0;
    size_t used = 0;
    /* "12345" with len 3 is 123 */
    CHECK_EQ(conica__parse_double("12345", 3, &v, &used), CONICA__NUM_OK);
    CHECK(v == 123.0);
    CHECK_EQ(used, 3u);
    /* exponent cut off by len: "1e5" with len 2 is 1 */
    CHECK_EQ(conica__parse_double("1e5", 2, &v, &used), CONICA__NUM_OK);
    CHECK(v == 1.0);
    CHECK_EQ(used, 1u);
}

TEST_CASE("number reader: %.17g of random doubles round-trips bit-exactly", "[numparse]")
{
    long i, mismatches = 0;
    ct_rng_init(&rng, 0x9E3779B97F4A7C15ull);
    for (i = 0; i < 200000; i++) {
        uint64_t bits = rng_next();
        double x, y = 0;
        size_t used;
        char buf[64];
        memcpy(&x, &bits, sizeof x);
        if (!isfinite(x))
            continue;
        snprintf(buf, sizeof buf, "%.17g", x);
        if (num(buf, &y, &used) != CONICA__NUM_OK || !same_bits(x, y) || used != strlen(buf))
            mismatches++;
    }
    CHECK_EQ(mismatches, 0);
}

TEST_CASE("number reader: agrees with glibc strtod on long and halfway inputs", "[numparse]")
{
    /* strtod in the C locale (this test never changes the locale) is the
     * correctly rounded oracle; the cases are the hard ones: more than 19
     * digits, exact midpoints between doubles, subnormals. */
    long i, mismatches = 0;
    ct_rng_init(&rng, 12345);
    for (i = 0; i < 20000; i++) {
        char buf[1100];
        size_t k = 0, used = 0;
        double a = 0, b;
        if (i % 2) {
            int nd = (int)(rng_next() % 900) + 1, j;
            for (j = 0; j < nd; j++)
                buf[k++] = (char)('0' + rng_next() % 10);
            snprintf(buf + k, sizeof buf - k, "e%d", (int)(rng_next() % 1000) - 800);
        } else {
            uint64_t bits = rng_next() >> 1;
            double x, nx;
            memcpy(&x, &bits, sizeof x);
            if (!isfinite(x) || x == 0.0 || !isfinite(nx = nextafter(x, INFINITY)))
                continue;
            snprintf(buf, sizeof buf, "%.40Lg", ((long double)x + (long double)nx) / 2);
        }
        b = strtod(buf, NULL);
        if (!isfinite(b))
            continue;
        if (num(buf, &a, &used) != CONICA__NUM_OK || !same_bits(a, b) || used != strlen(buf))
            mismatches++;
    }
    CHECK_EQ(mismatches, 0);
}

/* ------------------------------------------------------------ parser */

static void expect_error(const char *text, conica_code code, size_t line, const char *fragment);

TEST_CASE("parse: points, normals, comments, blank lines, CRLF", "[curve][parse]")
{
    conica_curve c;
    conica_status st;
    const char *text = "# a comment\r\n"
                       "% another\r\n"
                       "\r\n"
                       "v 1 2\r\n"
                       "  v\t-3.5e1   4.25 \r\n"
                       "v .5 -0\r\n"
                       "\t\n"
                       "vn 1 0\r\n"
                       "vn 0 1\r\n"
                       "vn -1E-2 1e+2"; /* no final newline */
    conica_curve_init(&c);
    REQUIRE_EQ(parse_str(text, &c, &st), CONICA_OK);
    REQUIRE_EQ(c.n, 3u);
    REQUIRE(c.nxy != NULL);
    CHECK(c.closed);
    CHECK(c.xy[0] == 1 && c.xy[1] == 2);
    CHECK(c.xy[2] == -35 && c.xy[3] == 4.25);
    CHECK(c.xy[4] == 0.5 && c.xy[5] == 0);
    CHECK(c.nxy[0] == 1 && c.nxy[1] == 0);
    CHECK(c.nxy[4] == -1e-2 && c.nxy[5] == 1e2);
    conica_curve_free(&c);
    CHECK(c.xy == NULL && c.n == 0);
}

TEST_CASE("parse: a UTF-8 byte order mark is skipped", "[curve][parse]")
{
    conica_curve c;
    conica_curve_init(&c);
    REQUIRE_EQ(parse_str("\xEF\xBB\xBFv 1 2\nv 3 4\nv 5 6\n", &c, NULL), CONICA_OK);
    CHECK_EQ(c.n, 3u);
    CHECK(c.xy[0] == 1.0);
    CHECK_EQ(conica_curve_line_of_point("\xEF\xBB\xBFv 1 2\nv 3 4\n", 15, 1, 0), 2);
    conica_curve_free(&c);
    expect_error("v 1 2\n\xEF\xBB\xBFv 3 4\n", CONICA_ERR_PARSE, 2, "unknown line");
}

TEST_CASE("parse: points without normals", "[curve][parse]")
{
    conica_curve c;
    conica_curve_init(&c);
    REQUIRE_EQ(parse_str("v 0 0\nv 1 0\nv 0 1\n", &c, NULL), CONICA_OK);
    CHECK_EQ(c.n, 3u);
    CHECK(c.nxy == NULL);
    conica_curve_free(&c);
}

TEST_CASE("parse: buffer is not NUL-terminated and is read only up to len", "[curve][parse]")
{
    const char text[] = "v 1 2\nv 3 4\nv 5 6 garbage";
    conica_curve c;
    conica_curve_init(&c);
    /* stop right after "v 5 6" */
    REQUIRE_EQ(conica_curve_parse(text, strlen(text) - 8, &c, NULL), CONICA_OK);
    CHECK_EQ(c.n, 3u);
    CHECK(c.xy[5] == 6);
    conica_curve_free(&c);
}

static void expect_error(const char *text, conica_code code, size_t line, const char *fragment)
{
    conica_curve c;
    conica_status st;
    conica_code rc;
    double sentinel[2] = {7, 8};
    conica_curve_init(&c);
    /* a previous content that must survive the failure */
    REQUIRE_EQ(conica_curve_set(sentinel, NULL, 1, 0, &c, NULL), CONICA_OK);
    memset(&st, 0, sizeof st);
    rc = parse_str(text, &c, &st);
    INFO("input '%s' -> %d line %zu: %s", text, (int)rc, st.line, st.message);
    CHECK_EQ(rc, code);
    CHECK_EQ(st.code, code);
    CHECK_EQ(st.line, line);
    CHECK(strstr(st.message, fragment) != NULL);
    CHECK_EQ(c.n, 1u);
    CHECK(c.xy[0] == 7 && c.xy[1] == 8 && c.nxy == NULL && !c.closed);
    conica_curve_free(&c);
}

TEST_CASE("parse: errors name the line", "[curve][parse][errors]")
{
    expect_error("v 1 2\nv 1\n", CONICA_ERR_PARSE, 2, "1 number");
    expect_error("v 1 2\n\n# c\nv\n", CONICA_ERR_PARSE, 4, "0 numbers");
    expect_error("v 1 2 3\n", CONICA_ERR_PARSE, 1, "more than 2");
    expect_error("v 1 2\nv 1 x\n", CONICA_ERR_PARSE, 2, "'x' is not a number");
    expect_error("v 1,5 2\n", CONICA_ERR_PARSE, 1, "'1,5' is not a number");
    expect_error("v 1.5.2 2\n", CONICA_ERR_PARSE, 1, "not a number");
    expect_error("v 1 2\r\nv 3 4\r\nvn 1 0\r\n", CONICA_ERR_PARSE, 3, "1 'vn' lines for 2 'v'");
    expect_error("v 1 2\nvn 1 0\nvn 0 1\n", CONICA_ERR_PARSE, 3, "2 'vn' lines for 1 'v'");
    expect_error("v 1 2\n1 2\n", CONICA_ERR_PARSE, 2, "unknown line");
    expect_error("v 1 2\nvt 1 2\n", CONICA_ERR_PARSE, 2, "unknown line");
    expect_error("v 1 2\nv nan 2\n", CONICA_ERR_NONFINITE, 2, "not a finite number");
    expect_error("v 1 2\nv 1 -inf\n", CONICA_ERR_NONFINITE, 2, "not a finite number");
    expect_error("v 1 1e999\n", CONICA_ERR_NONFINITE, 1, "not a finite number");
    expect_error("v 1 2\nv 3 4\nvn 1 0\nvn 0 0\n", CONICA_ERR_DEGENERATE, 4, "zero normal");
    expect_error("", CONICA_ERR_PARSE, 0, "no 'v x y' lines");
    expect_error("# only a comment\n", CONICA_ERR_PARSE, 1, "no 'v x y' lines");
}

TEST_CASE("parse: NULL arguments", "[curve][parse][errors]")
{
    conica_curve c;
    conica_curve_init(&c);
    CHECK_EQ(conica_curve_parse(NULL, 5, &c, NULL), CONICA_ERR_ARG);
    CHECK_EQ(conica_curve_parse("v 1 2", 5, NULL, NULL), CONICA_ERR_ARG);
}

TEST_CASE("parse_ex: the point cap is counted before allocating and names its line",
          "[curve][parse][limits]")
{
    const char *text = "# four points\nv 0 0\nv 1 0\nv 1 1\nv 0 1\nvn 0 -1\nvn 1 0\nvn 0 1\n"
                       "vn -1 0\n";
    const char *no_normals = "v 0 0\nv 1 0\nv 1 1\nv 0 1\n";
    const double old_xy[] = {7, 8};
    conica_curve c;
    conica_status st;
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(old_xy, NULL, 1, 0, &c, NULL), CONICA_OK);

    SECTION("one point over the cap: CONICA_ERR_LIMIT on the line past it, output untouched") {
        CHECK_EQ(conica_curve_parse_ex(text, strlen(text), 3, &c, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 5); /* the fourth `v` line */
        CHECK(strstr(st.message, "more than 3 points") != NULL);
        CHECK_EQ_U(c.n, 1);
        CHECK_EQ(c.xy[0], 7);
    }
    SECTION("the normals are capped too") {
        /* 3 `v` lines pass a cap of 3, the fourth `vn` line does not */
        const char *t = "v 0 0\nv 1 0\nv 1 1\nvn 0 -1\nvn 1 0\nvn 0 1\nvn 1 1\n";
        CHECK_EQ(conica_curve_parse_ex(t, strlen(t), 3, &c, &st), CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 7);
        CHECK(strstr(st.message, "more than 3 normals") != NULL);
        CHECK_EQ_U(c.n, 1);
    }
    SECTION("exactly at the cap is accepted") {
        CHECK_EQ(conica_curve_parse_ex(text, strlen(text), 4, &c, &st), CONICA_OK);
        CHECK_EQ_U(c.n, 4);
        REQUIRE(c.nxy != NULL);
        CHECK_EQ(c.nxy[2], 1);
        CHECK_EQ(conica_curve_parse_ex(no_normals, strlen(no_normals), 4, &c, &st), CONICA_OK);
        CHECK_EQ_U(c.n, 4);
        CHECK(c.nxy == NULL);
    }
    SECTION("0 means the default cap; conica_curve_parse is parse_ex with the default") {
        conica_curve d;
        conica_curve_init(&d);
        CHECK_EQ(conica_curve_parse_ex(text, strlen(text), 0, &c, &st), CONICA_OK);
        CHECK_EQ(conica_curve_parse(text, strlen(text), &d, &st), CONICA_OK);
        REQUIRE_EQ_U(c.n, d.n);
        CHECK(memcmp(c.xy, d.xy, 2 * c.n * sizeof *c.xy) == 0);
        CHECK(memcmp(c.nxy, d.nxy, 2 * c.n * sizeof *c.nxy) == 0);
        conica_curve_free(&d);
    }
    SECTION("a cap above the default is allowed") {
        CHECK_EQ(conica_curve_parse_ex(text, strlen(text), CONICA_CURVE_MAX_INPUT_POINTS * 4, &c,
                                       &st),
                 CONICA_OK);
        CHECK_EQ_U(c.n, 4);
    }
    SECTION("a cap of 1 refuses the second point; errors before the cap keep their own code") {
        CHECK_EQ(conica_curve_parse_ex(no_normals, strlen(no_normals), 1, &c, &st),
                 CONICA_ERR_LIMIT);
        CHECK_EQ(st.line, 2);
        CHECK_EQ(conica_curve_parse_ex("bogus\nv 0 0\nv 1 1\n", 18, 1, &c, &st),
                 CONICA_ERR_PARSE);
        CHECK_EQ(st.line, 1);
    }
    CHECK_EQ(conica_curve_parse_ex(NULL, 5, 3, &c, NULL), CONICA_ERR_ARG);
    conica_curve_free(&c);
}

static const char *locale_names[] = {"de_DE.UTF-8", "de_DE.utf8", "de_DE", "fr_FR.UTF-8",
                                     "fr_FR.utf8", "ru_RU.UTF-8", NULL};

/* No decimal-comma locale installed (Debian images ship only C/POSIX):
 * compile a one-category locale with localedef into a temporary LOCPATH.
 * glibc reads LOCPATH at every setlocale() call. Returns the locale name
 * or NULL; *dir receives the directory to remove. */
static const char *make_comma_locale(char *dir, size_t cap)
{
    char cmd[1024];
    FILE *f;
    const char *got;
    snprintf(dir, cap, "%s/conica-locale.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir))
        return NULL;
    snprintf(cmd, sizeof cmd, "%s/comma.src", dir);
    f = fopen(cmd, "w");
    if (!f)
        return NULL;
    fputs("LC_NUMERIC\ndecimal_point \"<U002C>\"\nthousands_sep \"<U002E>\"\n"
          "grouping 3;3\nEND LC_NUMERIC\n",
          f);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "localedef -c -i '%s/comma.src' -f UTF-8 '%s/xx_XX.UTF-8' >/dev/null 2>&1", dir, dir);
    if (system(cmd) == -1)
        return NULL;
    setenv("LOCPATH", dir, 1);
    got = setlocale(LC_NUMERIC, "xx_XX.UTF-8");
    return got && strcmp(localeconv()->decimal_point, ",") == 0 ? got : NULL;
}

TEST_CASE("parse and write ignore LC_NUMERIC (decimal comma locale)", "[curve][locale]")
{
    const char *got = NULL;
    char dir[512] = "";
    size_t i;
    conica_curve c;
    char *text = NULL;
    size_t len = 0;
    FILE *f;
    for (i = 0; locale_names[i] && !got; i++)
        got = setlocale(LC_NUMERIC, locale_names[i]);
    if (!got)
        got = make_comma_locale(dir, sizeof dir);
    if (!got) {
        setlocale(LC_NUMERIC, "C");
        SKIP("no locale with a decimal comma (none installed, localedef failed)");
    }
    INFO("locale %s, decimal point '%s'", got, localeconv()->decimal_point);
    conica_curve_init(&c);
    CHECK_EQ(parse_str("v 1.5 -2.25e1\nv 0.1 3\n", &c, NULL), CONICA_OK);
    CHECK(c.n == 2 && c.xy[0] == 1.5 && c.xy[1] == -22.5 && c.xy[2] == 0.1);
    {
        /* the slow path (more than 19 digits) too */
        double v = 0;
        size_t used = 0;
        CHECK_EQ(num("0.1000000000000000055511151231257827", &v, &used), CONICA__NUM_OK);
        CHECK(v == 0.1);
        CHECK_EQ(used, strlen("0.1000000000000000055511151231257827"));
    }
    f = open_memstream(&text, &len);
    REQUIRE(f != NULL);
    CHECK_EQ(conica_curve_write(f, &c, NULL), CONICA_OK);
    fclose(f);
    CHECK(strstr(text, "v 1.5 -22.5\n") != NULL);
    CHECK(strchr(text, ',') == NULL);
    free(text);
    conica_curve_free(&c);
    setlocale(LC_NUMERIC, "C");
    if (dir[0]) {
        char cmd[600];
        unsetenv("LOCPATH");
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
        CHECK(system(cmd) == 0);
    }
}

TEST_CASE("write then parse is bit-exact (%.17g)", "[curve][write]")
{
    size_t n = 1000, i;
    double *xy = malloc(2 * n * sizeof *xy), *nxy = malloc(2 * n * sizeof *nxy);
    conica_curve a, b;
    char *text = NULL;
    size_t len = 0;
    FILE *f;
    long mismatches = 0;
    REQUIRE(xy && nxy);
    ct_rng_init(&rng, 777);
    for (i = 0; i < 2 * n; i++) {
        uint64_t bits = rng_next();
        double x;
        memcpy(&x, &bits, sizeof x);
        if (!isfinite(x))
            x = (double)bits * 1e-300;
        xy[i] = x;
        nxy[i] = (double)(rng_next() >> 11) * 0x1p-53 - 0.5;
    }
    conica_curve_init(&a);
    conica_curve_init(&b);
    REQUIRE_EQ(conica_curve_set(xy, nxy, n, 1, &a, NULL), CONICA_OK);
    f = open_memstream(&text, &len);
    REQUIRE(f != NULL);
    REQUIRE_EQ(conica_curve_write(f, &a, NULL), CONICA_OK);
    fclose(f);
    REQUIRE_EQ(conica_curve_parse(text, len, &b, NULL), CONICA_OK);
    REQUIRE_EQ(b.n, n);
    REQUIRE(b.nxy != NULL);
    for (i = 0; i < 2 * n; i++)
        mismatches += !same_bits(a.xy[i], b.xy[i]) + !same_bits(a.nxy[i], b.nxy[i]);
    CHECK_EQ(mismatches, 0);
    free(text);
    free(xy);
    free(nxy);
    conica_curve_free(&a);
    conica_curve_free(&b);
}

TEST_CASE("the reference's example inputs all parse", "[curve][parse][data]")
{
    static const char *const names[] = {
        "5pointOpenCircle", "ExLetG_sub0", "ExStar_sub0", "ExStep_sub0", "ex6_sub0E",
        "ex6_sub0F", "example1", "example10", "example11", "example12", "example13",
        "example2", "example3", "example4", "example5", "example6", "example7",
        "example8", "example9", "lG2", "tau_example2", "tau_sub0", "tst"};
    size_t i;
    ct_data_dir_or_skip();
    for (i = 0; i < sizeof names / sizeof names[0]; i++) {
        char path[256], buf[1 << 16];
        size_t len, nv = 0, nvn = 0, k;
        FILE *f;
        conica_curve c;
        conica_status st;
        char rel[64];
        snprintf(rel, sizeof rel, "conis/input/%s.txt", names[i]);
        REQUIRE(ct_data_path(path, sizeof path, rel));
        f = fopen(path, "rb");
        INFO("%s", path);
        REQUIRE(f != NULL);
        len = fread(buf, 1, sizeof buf, f);
        fclose(f);
        /* count the lines the simple way, to compare */
        for (k = 0; k + 1 < len; k++)
            if (k == 0 || buf[k - 1] == '\n') {
                if (buf[k] == 'v' && buf[k + 1] == ' ')
                    nv++;
                else if (buf[k] == 'v' && buf[k + 1] == 'n')
                    nvn++;
            }
        conica_curve_init(&c);
        CHECK_EQ(conica_curve_parse(buf, len, &c, &st), CONICA_OK);
        CHECK_EQ(c.n, nv);
        CHECK((c.nxy != NULL) == (nvn > 0));
        conica_curve_free(&c);
    }
}

/* ------------------------------------------------------------ normals */

static void regular_polygon(size_t n, double cx, double cy, double r, int cw, double *xy)
{
    size_t i;
    for (i = 0; i < n; i++) {
        double t = 2 * M_PI * (double)i / (double)n * (cw ? -1 : 1) + 0.3;
        xy[2 * i] = cx + r * cos(t);
        xy[2 * i + 1] = cy + r * sin(t);
    }
}

TEST_CASE("normals of a regular polygon are the exact circle normals, CW and CCW",
          "[curve][normals]")
{
    double xy[2 * 13];
    int cw, method;
    for (cw = 0; cw <= 1; cw++)
        for (method = 0; method <= 1; method++) {
            conica_curve c;
            size_t i;
            double worst = 0;
            double cx = 1e6, cy = -3e5, r = 2.5e-2;
            regular_polygon(13, cx, cy, r, cw, xy);
            conica_curve_init(&c);
            REQUIRE_EQ(conica_curve_set(xy, NULL, 13, 1, &c, NULL), CONICA_OK);
            REQUIRE_EQ(conica_curve_estimate_normals(&c, (conica_normal_method)method, NULL),
                       CONICA_OK);
            REQUIRE(c.nxy != NULL);
            for (i = 0; i < 13; i++) {
                /* the exact outward normal, from the angle we sampled at */
                double t = 2 * M_PI * (double)i / 13.0 * (cw ? -1 : 1) + 0.3;
                double ex = cos(t), ey = sin(t);
                double d = hypot(c.nxy[2 * i] - ex, c.nxy[2 * i + 1] - ey);
                if (d > worst)
                    worst = d;
                CHECK_NEAR(hypot(c.nxy[2 * i], c.nxy[2 * i + 1]), 1.0, 1e-15);
            }
            INFO("cw %d method %d worst %g", cw, method, worst);
            /* the points sit 4e7 radii from the origin: their own rounding
             * is ~1e-10 of the radius, which bounds what any estimate gets */
            CHECK(worst < 8 * (nextafter(cx, INFINITY) - cx) / r);
            conica_curve_free(&c);
        }
}

TEST_CASE("normals at the origin are exact to rounding", "[curve][normals]")
{
    double xy[2 * 8];
    conica_curve c;
    size_t i;
    regular_polygon(8, 0, 0, 3, 0, xy);
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 8, 1, &c, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    for (i = 0; i < 8; i++) {
        double t = 2 * M_PI * (double)i / 8.0 + 0.3;
        CHECK_NEAR(c.nxy[2 * i], cos(t), 1e-15);
        CHECK_NEAR(c.nxy[2 * i + 1], sin(t), 1e-15);
    }
    conica_curve_free(&c);
}

TEST_CASE("circle normals are exact on unevenly spaced circle points; area ones are not",
          "[curve][normals]")
{
    static const double t[] = {0.0, 0.2, 1.1, 1.3, 2.9, 3.5, 4.9};
    double xy[2 * 7];
    conica_curve a, b;
    size_t i;
    double worst_circle = 0, worst_area = 0;
    for (i = 0; i < 7; i++) {
        xy[2 * i] = 5 * cos(t[i]);
        xy[2 * i + 1] = 5 * sin(t[i]);
    }
    conica_curve_init(&a);
    conica_curve_init(&b);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 7, 1, &a, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 7, 1, &b, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&a, CONICA_NORMALS_CIRCLE, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&b, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    for (i = 0; i < 7; i++) {
        double dc = hypot(a.nxy[2 * i] - cos(t[i]), a.nxy[2 * i + 1] - sin(t[i]));
        double da = hypot(b.nxy[2 * i] - cos(t[i]), b.nxy[2 * i + 1] - sin(t[i]));
        worst_circle = dc > worst_circle ? dc : worst_circle;
        worst_area = da > worst_area ? da : worst_area;
    }
    CHECK(worst_circle < 1e-14);
    CHECK(worst_area > 1e-2);
    conica_curve_free(&a);
    conica_curve_free(&b);
}

/* Unit normal at p of the circle through p, q, r (exact construction in
 * long double), oriented like (ox, oy). */
static void circle_normal3(const double *p, const double *q, const double *r, double ox,
                           double oy, double *nx, double *ny)
{
    long double ax = (long double)q[0] - p[0], ay = (long double)q[1] - p[1];
    long double bx = (long double)r[0] - p[0], by = (long double)r[1] - p[1];
    long double aa = ax * ax + ay * ay, bb = bx * bx + by * by, d = 2 * (ax * by - ay * bx);
    long double cx = (by * aa - ay * bb) / d, cy = (ax * bb - bx * aa) / d;
    long double l = sqrtl(cx * cx + cy * cy);
    *nx = (double)(-cx / l);
    *ny = (double)(-cy / l);
    if (*nx * ox + *ny * oy < 0) {
        *nx = -*nx;
        *ny = -*ny;
    }
}

TEST_CASE("open curves: ends use the circle through their three points, orientation from the turn",
          "[curve][normals]")
{
    /* an arc turning left (counter-clockwise) then the same arc reversed */
    double xy[2 * 5] = {2, 0, 1, 1, 0, 1.5, -1, 1, -2, 0};
    int rev;
    for (rev = 0; rev <= 1; rev++) {
        double p[2 * 5], nx, ny;
        conica_curve c;
        size_t i, n = 5;
        for (i = 0; i < n; i++) {
            size_t j = rev ? n - 1 - i : i;
            p[2 * i] = xy[2 * j];
            p[2 * i + 1] = xy[2 * j + 1];
        }
        conica_curve_init(&c);
        REQUIRE_EQ(conica_curve_set(p, NULL, n, 0, &c, NULL), CONICA_OK);
        REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, NULL), CONICA_OK);
        /* the arc bulges upward: every normal points up and away */
        for (i = 0; i < n; i++)
            CHECK(c.nxy[2 * i + 1] > 0);
        circle_normal3(p, p + 2, p + 4, 0, 1, &nx, &ny);
        CHECK_NEAR(c.nxy[0], nx, 1e-15);
        CHECK_NEAR(c.nxy[1], ny, 1e-15);
        circle_normal3(p + 8, p + 6, p + 4, 0, 1, &nx, &ny);
        CHECK_NEAR(c.nxy[8], nx, 1e-15);
        CHECK_NEAR(c.nxy[9], ny, 1e-15);
        /* not the end edge's normal (the old, reference rule): the tangent
         * at an end of a convex arc is not its chord */
        CHECK(fabs(c.nxy[0] * (p[2] - p[0]) + c.nxy[1] * (p[3] - p[1])) > 0.1);
        conica_curve_free(&c);
    }
}

TEST_CASE("open arc of a circle without normals: end normals are the circle's", "[curve][normals]")
{
    /* Unevenly spaced points on an arc of a circle away from the origin,
     * both directions, both methods: the end normals are radial to within
     * a few rounding units. Collinear ends keep the edge normal. */
    const double t[6] = {-0.9, -0.55, -0.1, 0.3, 0.95, 1.6};
    const double cx = 3.25, cy = -7.5, r = 2.5;
    int rev, m;
    for (m = 0; m < 2; m++) {
        for (rev = 0; rev <= 1; rev++) {
            double p[12];
            conica_curve c;
            size_t i, n = 6;
            for (i = 0; i < n; i++) {
                size_t j = rev ? n - 1 - i : i;
                p[2 * i] = cx + r * cos(t[j]);
                p[2 * i + 1] = cy + r * sin(t[j]);
            }
            conica_curve_init(&c);
            REQUIRE_EQ(conica_curve_set(p, NULL, n, 0, &c, NULL), CONICA_OK);
            REQUIRE_EQ(conica_curve_estimate_normals(
                           &c, m ? CONICA_NORMALS_CIRCLE : CONICA_NORMALS_AREA, NULL),
                       CONICA_OK);
            for (i = 0; i < n; i += n - 1) {
                double ex = (p[2 * i] - cx) / r, ey = (p[2 * i + 1] - cy) / r;
                double s = c.nxy[2 * i] * ex + c.nxy[2 * i + 1] * ey > 0 ? 1.0 : -1.0;
                INFO("method %d reversed %d end %zu", m, rev, i);
                CHECK_NEAR(c.nxy[2 * i], s * ex, 1e-14);
                CHECK_NEAR(c.nxy[2 * i + 1], s * ey, 1e-14);
                /* outward on the arc, like the interior normals (convex arc:
                 * one orientation for all) */
                CHECK(s * (c.nxy[2] * (p[2] - cx) + c.nxy[3] * (p[3] - cy)) > 0);
            }
            conica_curve_free(&c);
        }
    }
    {
        double line[8] = {0, 0, 1, 0, 2, 0, 3, 1};
        conica_curve c;
        conica_curve_init(&c);
        REQUIRE_EQ(conica_curve_set(line, NULL, 4, 0, &c, NULL), CONICA_OK);
        REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, NULL), CONICA_OK);
        CHECK_NEAR(c.nxy[0], 0, 1e-15); /* collinear start: the edge normal */
        CHECK_NEAR(fabs(c.nxy[1]), 1, 1e-15);
        conica_curve_free(&c);
    }
}

TEST_CASE("normals: zero-length edges are skipped, degenerate input is refused",
          "[curve][normals][errors]")
{
    conica_curve c;
    conica_status st;
    size_t i;
    double dup[2 * 5] = {0, 0, 1, 0, 1, 0, 1, 1, 0, 1}; /* (1,0) twice */
    double same[2 * 3] = {2, 2, 2, 2, 2, 2};
    double bad[2 * 3] = {0, 0, NAN, 1, 1, 1};
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(dup, NULL, 5, 1, &c, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_CIRCLE, NULL), CONICA_OK);
    for (i = 0; i < 10; i++)
        CHECK(isfinite(c.nxy[i]));
    CHECK(c.nxy[2] == c.nxy[4] && c.nxy[3] == c.nxy[5]);
    /* corner (1,0) of the CCW square: outward diagonal */
    CHECK_NEAR(c.nxy[2], sqrt(0.5), 1e-15);
    CHECK_NEAR(c.nxy[3], -sqrt(0.5), 1e-15);

    REQUIRE_EQ(conica_curve_set(same, NULL, 3, 1, &c, NULL), CONICA_OK);
    CHECK_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, &st), CONICA_ERR_DEGENERATE);
    CHECK(c.nxy == NULL);
    REQUIRE_EQ(conica_curve_set(same, NULL, 1, 0, &c, NULL), CONICA_OK);
    CHECK_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, &st), CONICA_ERR_DEGENERATE);
    REQUIRE_EQ(conica_curve_set(bad, NULL, 3, 1, &c, NULL), CONICA_OK);
    CHECK_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_AREA, &st), CONICA_ERR_NONFINITE);
    CHECK(c.nxy == NULL);
    CHECK_EQ(conica_curve_estimate_normals(&c, (conica_normal_method)7, &st), CONICA_ERR_ARG);
    conica_curve_free(&c);
}

TEST_CASE("normals do not depend on the scale: curves near 1e308 and 1e-300",
          "[curve][normals]")
{
    static const double scales[] = {1e300, 1.5e308 / 3.0, 1e-300, 4.9e-324 * 1e10};
    double base[2 * 5] = {-1, -1, 1, -1, 2, 0.5, 0, 2, -2, 1};
    conica_curve ref, c;
    size_t k, i;
    conica_curve_init(&ref);
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(base, NULL, 5, 1, &ref, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&ref, CONICA_NORMALS_CIRCLE, NULL), CONICA_OK);
    for (k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        double xy[2 * 5];
        for (i = 0; i < 10; i++)
            xy[i] = base[i] * scales[k];
        INFO("scale %g", scales[k]);
        REQUIRE_EQ(conica_curve_set(xy, NULL, 5, 1, &c, NULL), CONICA_OK);
        REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_CIRCLE, NULL), CONICA_OK);
        for (i = 0; i < 10; i++)
            CHECK_NEAR(c.nxy[i], ref.nxy[i], 1e-15);
    }
    conica_curve_free(&ref);
    conica_curve_free(&c);
}

TEST_CASE("normals: collinear points fall back from circle to area", "[curve][normals]")
{
    double xy[2 * 4] = {0, 0, 1, 0, 2, 0, 3, 0};
    conica_curve c;
    size_t i;
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(xy, NULL, 4, 0, &c, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&c, CONICA_NORMALS_CIRCLE, NULL), CONICA_OK);
    for (i = 0; i < 4; i++) {
        CHECK(c.nxy[2 * i] == 0.0);
        CHECK(fabs(c.nxy[2 * i + 1]) == 1.0);
        CHECK(c.nxy[2 * i + 1] == c.nxy[1]);
    }
    conica_curve_free(&c);
}

TEST_CASE("normals match the reference's on its own examples without vn", "[curve][normals][data]")
{
    /* reference-k5 keeps the input vertices every 32 points (no inflection
     * points are inserted in tau_sub0), so its normals there are the
     * estimated ones the reference started from, normalised. */
    char buf[1 << 15];
    char path[512];
    size_t len, i;
    FILE *f;
    conica_curve in, ref;
    ct_data_dir_or_skip();
    REQUIRE(ct_data_path(path, sizeof path, "conis/input/tau_sub0.txt"));
    f = fopen(path, "rb");
    REQUIRE(f != NULL);
    len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    conica_curve_init(&in);
    conica_curve_init(&ref);
    REQUIRE_EQ(conica_curve_parse(buf, len, &in, NULL), CONICA_OK);
    REQUIRE_EQ(conica_curve_estimate_normals(&in, CONICA_NORMALS_AREA, NULL), CONICA_OK);
    REQUIRE(ct_data_path(path, sizeof path, "conis/reference-k5/tau_sub0.k5.txt"));
    f = fopen(path, "rb");
    REQUIRE(f != NULL);
    len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    REQUIRE_EQ(conica_curve_parse(buf, len, &ref, NULL), CONICA_OK);
    REQUIRE_EQ(ref.n, in.n * 32);
    for (i = 0; i < in.n; i++) {
        CHECK_NEAR(in.nxy[2 * i], ref.nxy[2 * (32 * i)], 1e-15);
        CHECK_NEAR(in.nxy[2 * i + 1], ref.nxy[2 * (32 * i) + 1], 1e-15);
    }
    conica_curve_free(&in);
    conica_curve_free(&ref);
}

TEST_CASE("curve_set copies and frees", "[curve]")
{
    double xy[4] = {1, 2, 3, 4}, nxy[4] = {0, 1, 0, 1};
    conica_curve c;
    conica_curve_init(&c);
    REQUIRE_EQ(conica_curve_set(xy, nxy, 2, 5, &c, NULL), CONICA_OK);
    xy[0] = 99;
    CHECK(c.xy[0] == 1);
    CHECK(c.nxy[3] == 1);
    CHECK(c.closed == 1);
    CHECK_EQ(conica_curve_set(NULL, NULL, 2, 0, &c, NULL), CONICA_ERR_ARG);
    CHECK(c.n == 2);
    conica_curve_free(&c);
    conica_curve_free(&c); /* twice is fine */
    conica_curve_free(NULL);
}

TEST_CASE("line_of_point finds the line of the i-th v and vn line", "[curve][parse]")
{
    const char *text = "# head\nv 0 0\n\nv 1 0\r\n% c\nv 1 1\nvn 0 -1\nvn 1 0\nvn 0 1\n";
    size_t len = strlen(text);
    CHECK_EQ(conica_curve_line_of_point(text, len, 0, 0), 2);
    CHECK_EQ(conica_curve_line_of_point(text, len, 1, 0), 4);
    CHECK_EQ(conica_curve_line_of_point(text, len, 2, 0), 6);
    CHECK_EQ(conica_curve_line_of_point(text, len, 3, 0), 0);
    CHECK_EQ(conica_curve_line_of_point(text, len, 0, 1), 7);
    CHECK_EQ(conica_curve_line_of_point(text, len, 2, 1), 9);
    CHECK_EQ(conica_curve_line_of_point(NULL, 0, 0, 0), 0);
}
