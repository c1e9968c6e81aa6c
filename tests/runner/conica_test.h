/* SPDX-License-Identifier: MIT */
/*
 * conica_test.h - a small Catch2-compatible test runner for C11 and C++17.
 *
 *     #include "conica_test.h"
 *
 *     TEST_CASE("circle stays a circle", "[subdiv][conic]") {
 *         double r = 1.0;
 *         REQUIRE(r > 0);
 *         SECTION("one level") { CHECK_NEAR(r, 1.0, 1e-12); }
 *         SECTION("two levels") { CHECK_REL(r * 2.0, 2.0, 1e-15); }
 *     }
 *
 * The runner library provides main(); link the test object with
 * libconica_test.a. The command line, console summary, reporters and exit
 * codes follow Catch2 3.7.1 (see README.md).
 *
 * Semantics worth knowing:
 * - A case re-runs once per leaf SECTION (Catch2's discovery: each run enters
 *   at most one new leaf path).
 * - REQUIRE*, FAIL and SKIP end the current run of the case with longjmp.
 *   Code after them does not run, so do not rely on cleanup after a failed
 *   REQUIRE (memory allocated by the test body leaks in that case) and never
 *   use them where a C++ object with a non-trivial destructor is alive in
 *   the frames being left.
 * - Do not `return` or `break` out of a SECTION body; fall off its end.
 * - INFO/CAPTURE messages live until the end of the current run of the case
 *   or of the SECTION they were issued in; a second INFO from the same source
 *   line replaces the first (so INFO inside a loop shows the current pass).
 * - Format strings of INFO, SKIP, FAIL need at least the format argument.
 */
#ifndef CONICA_TEST_H
#define CONICA_TEST_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__) || defined(__clang__)
#define CT_PRINTF(f, a) __attribute__((format(printf, f, a)))
#define CT_NORETURN __attribute__((noreturn))
#define CT_CONSTRUCTOR __attribute__((constructor))
#define CT_UNUSED __attribute__((unused))
#else
#error "conica_test.h needs GCC or Clang (constructor attribute)"
#endif

/* ------------------------------------------------------------ registration */

/** One registered test case (static storage in the test file). */
typedef struct ct_case {
    const char *name;
    const char *tags; /* "[a][b]" */
    const char *file;
    int line;
    void (*fn)(void);
    struct ct_case *next; /* owned by the runner */
} ct_case;

/** Called from the constructor TEST_CASE generates. */
void ct_register(ct_case *tc);

#define CT_CAT2_(a, b) a##b
#define CT_CAT_(a, b) CT_CAT2_(a, b)

/* __COUNTER__ (GCC, Clang) keeps generated names unique even when several
 * macros share a source line. */
#define TEST_CASE(name, tags) CT_TEST_CASE2_(name, tags, __COUNTER__)
#define CT_TEST_CASE2_(name, tags, n) CT_TEST_CASE_(name, tags, \
    CT_CAT_(ct_fn_, n), CT_CAT_(ct_case_, n), CT_CAT_(ct_reg_, n))
#define CT_TEST_CASE_(name, tags, fn, cs, reg)                             \
    static void fn(void);                                                  \
    static ct_case cs = {name, tags, __FILE__, __LINE__, fn, NULL};        \
    CT_CONSTRUCTOR static void reg(void) { ct_register(&cs); }            \
    static void fn(void)

/* ------------------------------------------------------------ sections */

int ct_section_enter(const char *file, int line, const char *name);
int ct_section_enter_fmt(const char *file, int line, const char *fmt, ...)
    CT_PRINTF(3, 4);
int ct_section_leave(void);

#define SECTION(name) CT_SECTION_(CT_CAT_(ct_sec_, __COUNTER__), \
    ct_section_enter(__FILE__, __LINE__, name))
/* DYNAMIC_SECTION("point %d", i): a section whose name is formatted. */
#define DYNAMIC_SECTION(...) CT_SECTION_(CT_CAT_(ct_sec_, __COUNTER__), \
    ct_section_enter_fmt(__FILE__, __LINE__, __VA_ARGS__))
#define CT_SECTION_(v, enter) for (int v = (enter); v; v = ct_section_leave())

/* ------------------------------------------------------------ assertions */

/* Every ct_check_* returns 1 when the assertion passed. When `req` is set
 * (REQUIRE forms) a failure ends the run of the case and does not return. */
int ct_check_bool(const char *file, int line, const char *macro,
                  const char *expr, int ok, int req);
int ct_check_int(const char *file, int line, const char *macro,
                 const char *ea, const char *eb, const char *op,
                 long long a, long long b, int req);
int ct_check_uint(const char *file, int line, const char *macro,
                  const char *ea, const char *eb, const char *op,
                  unsigned long long a, unsigned long long b, int req);
int ct_check_cmp_d(const char *file, int line, const char *macro,
                   const char *ea, const char *eb, const char *op,
                   double a, double b, int req);
int ct_check_near(const char *file, int line, const char *macro,
                  const char *ea, const char *eb, const char *et,
                  double a, double b, double tol, int req);
int ct_check_rel(const char *file, int line, const char *macro,
                 const char *ea, const char *eb, const char *et,
                 double a, double b, double rel, int req);
int ct_check_str(const char *file, int line, const char *macro,
                 const char *ea, const char *eb,
                 const char *a, const char *b, int req);
void ct_succeed(const char *file, int line, const char *fmt, ...) CT_PRINTF(3, 4);
void ct_fail_check(const char *file, int line, const char *fmt, ...) CT_PRINTF(3, 4);
CT_NORETURN void ct_fail(const char *file, int line, const char *fmt, ...)
    CT_PRINTF(3, 4);
CT_NORETURN void ct_skip(const char *file, int line, const char *fmt, ...)
    CT_PRINTF(3, 4);
void ct_info(const char *file, int line, const char *fmt, ...) CT_PRINTF(3, 4);
void ct_warn(const char *file, int line, const char *fmt, ...) CT_PRINTF(3, 4);

#define CT_B_(m, req, ...) \
    ct_check_bool(__FILE__, __LINE__, m, #__VA_ARGS__, (__VA_ARGS__) ? 1 : 0, req)
#define REQUIRE(...) ((void)CT_B_("REQUIRE", 1, __VA_ARGS__))
#define CHECK(...) ((void)CT_B_("CHECK", 0, __VA_ARGS__))
#define REQUIRE_FALSE(...) ((void)ct_check_bool(__FILE__, __LINE__, \
    "REQUIRE_FALSE", #__VA_ARGS__, (__VA_ARGS__) ? 0 : 1, 1))
#define CHECK_FALSE(...) ((void)ct_check_bool(__FILE__, __LINE__, \
    "CHECK_FALSE", #__VA_ARGS__, (__VA_ARGS__) ? 0 : 1, 0))

/* Integer comparisons print both operands (signed, or unsigned with _U). */
#define CT_I_(m, op, a, b, req) ct_check_int(__FILE__, __LINE__, m, #a, #b, \
    op, (long long)(a), (long long)(b), req)
#define CT_U_(m, op, a, b, req) ct_check_uint(__FILE__, __LINE__, m, #a, #b, \
    op, (unsigned long long)(a), (unsigned long long)(b), req)
#define REQUIRE_EQ(a, b) ((void)CT_I_("REQUIRE_EQ", "==", a, b, 1))
#define CHECK_EQ(a, b) ((void)CT_I_("CHECK_EQ", "==", a, b, 0))
#define REQUIRE_NE(a, b) ((void)CT_I_("REQUIRE_NE", "!=", a, b, 1))
#define CHECK_NE(a, b) ((void)CT_I_("CHECK_NE", "!=", a, b, 0))
#define REQUIRE_EQ_U(a, b) ((void)CT_U_("REQUIRE_EQ_U", "==", a, b, 1))
#define CHECK_EQ_U(a, b) ((void)CT_U_("CHECK_EQ_U", "==", a, b, 0))

/* Ordered comparisons of numbers (as double, printed with %.17g). */
#define CT_D_(m, op, a, b, req) ct_check_cmp_d(__FILE__, __LINE__, m, #a, #b, \
    op, (double)(a), (double)(b), req)
#define REQUIRE_LT(a, b) ((void)CT_D_("REQUIRE_LT", "<", a, b, 1))
#define CHECK_LT(a, b) ((void)CT_D_("CHECK_LT", "<", a, b, 0))
#define REQUIRE_LE(a, b) ((void)CT_D_("REQUIRE_LE", "<=", a, b, 1))
#define CHECK_LE(a, b) ((void)CT_D_("CHECK_LE", "<=", a, b, 0))
#define REQUIRE_GT(a, b) ((void)CT_D_("REQUIRE_GT", ">", a, b, 1))
#define CHECK_GT(a, b) ((void)CT_D_("CHECK_GT", ">", a, b, 0))
#define REQUIRE_GE(a, b) ((void)CT_D_("REQUIRE_GE", ">=", a, b, 1))
#define CHECK_GE(a, b) ((void)CT_D_("CHECK_GE", ">=", a, b, 0))

/* |a - b| <= abs_tol.  NaN never passes. */
#define REQUIRE_NEAR(a, b, tol) ((void)ct_check_near(__FILE__, __LINE__, \
    "REQUIRE_NEAR", #a, #b, #tol, (double)(a), (double)(b), (double)(tol), 1))
#define CHECK_NEAR(a, b, tol) ((void)ct_check_near(__FILE__, __LINE__, \
    "CHECK_NEAR", #a, #b, #tol, (double)(a), (double)(b), (double)(tol), 0))
/* |a - b| <= rel_tol * max(|a|, |b|).  NaN never passes. */
#define REQUIRE_REL(a, b, rel) ((void)ct_check_rel(__FILE__, __LINE__, \
    "REQUIRE_REL", #a, #b, #rel, (double)(a), (double)(b), (double)(rel), 1))
#define CHECK_REL(a, b, rel) ((void)ct_check_rel(__FILE__, __LINE__, \
    "CHECK_REL", #a, #b, #rel, (double)(a), (double)(b), (double)(rel), 0))

/* strcmp(a, b) == 0; NULL equals only NULL. */
#define REQUIRE_STR_EQ(a, b) ((void)ct_check_str(__FILE__, __LINE__, \
    "REQUIRE_STR_EQ", #a, #b, (a), (b), 1))
#define CHECK_STR_EQ(a, b) ((void)ct_check_str(__FILE__, __LINE__, \
    "CHECK_STR_EQ", #a, #b, (a), (b), 0))

#define INFO(...) ct_info(__FILE__, __LINE__, __VA_ARGS__)
#define CAPTURE_I(x) ct_info(__FILE__, __LINE__, "%s := %lld", #x, (long long)(x))
#define CAPTURE_U(x) ct_info(__FILE__, __LINE__, "%s := %llu", #x, \
    (unsigned long long)(x))
#define CAPTURE_D(x) ct_info(__FILE__, __LINE__, "%s := %.17g", #x, (double)(x))
#define CAPTURE_S(x) ct_info(__FILE__, __LINE__, "%s := \"%s\"", #x, (x))
#define WARN(...) ct_warn(__FILE__, __LINE__, __VA_ARGS__)
#define SUCCEED(...) ct_succeed(__FILE__, __LINE__, __VA_ARGS__)
#define FAIL(...) ct_fail(__FILE__, __LINE__, __VA_ARGS__)
#define FAIL_CHECK(...) ct_fail_check(__FILE__, __LINE__, __VA_ARGS__)
#define SKIP(...) ct_skip(__FILE__, __LINE__, __VA_ARGS__)

/* ------------------------------------------------------------ helpers */

/** Directory of the shared test data: $CONICA_SHARED_DATA when it names a
 *  directory, else "../shared/data" relative to the working directory (the
 *  repository root under make), else NULL. */
const char *ct_data_dir(void);
/** Like ct_data_dir(), but SKIPs the case with a notice when it is absent. */
const char *ct_data_dir_or_skip(void);
/** Join ct_data_dir() and `rel` into out[cap]. Returns 1 on success, 0 when
 *  there is no data directory or the path does not fit. */
int ct_data_path(char *out, size_t cap, const char *rel);

/** Deterministic generator (xoshiro256**, seeded by splitmix64). Explicit
 *  state, so every property test names its seed. */
typedef struct ct_rng {
    uint64_t s[4];
} ct_rng;
void ct_rng_init(ct_rng *r, uint64_t seed);
uint64_t ct_rng_next(ct_rng *r);
/** Uniform in [0, 1) with 53 random bits. */
double ct_rng_uniform(ct_rng *r);
/** Uniform in [lo, hi). */
double ct_rng_range(ct_rng *r, double lo, double hi);
/** Uniform integer in [0, n) without modulo bias; n == 0 gives 0. */
uint64_t ct_rng_below(ct_rng *r, uint64_t n);
/** Standard normal deviate (Box-Muller). */
double ct_rng_normal(ct_rng *r);

/** The run's --rng-seed value (for tests that want to vary with it). */
uint32_t ct_run_seed(void);
/** Name of the test case being run, or NULL outside a case. */
const char *ct_current_case(void);

/* ------------------------------------------------------------ internals
 * Exposed so the runner can test itself (tests/test_runner.c). */

/** Does the Catch2 test spec `spec` (one command-line argument) select a
 *  test named `name` with tags `tags` ("[a][.b]")? 1 yes, 0 no, -1 invalid
 *  spec. Hidden tests (a tag starting with '.', or [!hide]) match only when
 *  a name or tag pattern selects them. */
int ct_spec_matches(const char *spec, const char *name, const char *tags);
/** The same for several arguments (Catch2 ANDs arguments, commas OR). */
int ct_spec_matches_argv(int argc, const char *const *argv, const char *name,
                         const char *tags);
/** Is a test with these tags hidden? */
int ct_tags_hidden(const char *tags);

/** Section tracker with Catch2's discovery rules, independent of any case. */
typedef struct ct_tracker ct_tracker;
ct_tracker *ct_tracker_new(void);
void ct_tracker_free(ct_tracker *t);
/** Start one run of the body. */
void ct_tracker_start_run(ct_tracker *t);
/** Enter section `name`? 1 when the body should run it (then call leave). */
int ct_tracker_enter(ct_tracker *t, const char *name);
void ct_tracker_leave(ct_tracker *t);
/** The run ended early inside the innermost open section (REQUIRE, SKIP). */
void ct_tracker_fail(ct_tracker *t);
/** End the run normally; returns 1 when the case needs no further runs. */
int ct_tracker_end_run(ct_tracker *t);
/** Restrict runs to one section path (-c NAME, repeatable for depth). */
int ct_tracker_add_filter(ct_tracker *t, const char *name);

#ifdef __cplusplus
}
#endif

#endif /* CONICA_TEST_H */
