/* SPDX-License-Identifier: MIT */
/* Internal helpers shared by libcore's translation units (conica__ prefix). */
#ifndef CONICA_INTERNAL_H
#define CONICA_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "conica/common.h"

#define CONICA_VERSION_STRING "0.1.0"

#if defined(__GNUC__)
#if defined(__MINGW32__)
/* MinGW-w64 (the Windows build of the Blender add-on) is built with
 * __USE_MINGW_ANSI_STDIO=1, whose vsnprintf is C99's (%zu); plain `printf`
 * there means Microsoft's, which has no %zu. */
#define CONICA__PRINTF(a, b) __attribute__((format(gnu_printf, a, b)))
#else
#define CONICA__PRINTF(a, b) __attribute__((format(printf, a, b)))
#endif
/* A small function on a hot path that gcc -O2 leaves out of line (called
 * from more than one place): inlined anyway. */
#define CONICA__HOT_INLINE inline __attribute__((always_inline))
/* A branch taken nearly always (the compiler lays that path out straight). */
#define CONICA__LIKELY(c) __builtin_expect(!!(c), 1)
#else
#define CONICA__LIKELY(c) (c)
#define CONICA__PRINTF(a, b)
#define CONICA__HOT_INLINE inline
#endif

/* Fill *st (if not NULL) and return code. */
conica_code conica__fail(conica_status *st, conica_code code, size_t line,
                         size_t offset, const char *fmt, ...) CONICA__PRINTF(5, 6);
/* Mark *st (if not NULL) as success. */
void conica__ok(conica_status *st);

/* Sign (-1, 0, 1) of the orientation of (a, b, c) (1: c lies to the left
 * of a -> b), exact for finite input: a floating-point filter, then an
 * exact expansion sum of the six products (orient.c). */
int conica__orient2d(const double *a, const double *b, const double *c);
/* The same determinant in double, and in *err a bound on its error (inf or
 * NaN where a product overflows): its sign is certain where |det| > *err,
 * and |det| compares with a threshold t certainly where ||det| - t| > *err
 * (orient.c). */
double conica__orient2d_approx(const double *a, const double *b, const double *c, double *err);

/* Least and largest value of the scalar Bézier s_0..s_p (1 <= p <= 3) over
 * [u0, u1] within [0, 1], exactly, and where (ulo, uhi may be NULL):
 * plot_guaranteed.c. */
void conica__bern_range(const double *s, int p, double u0, double u1, double *lo, double *ulo,
                        double *hi, double *uhi);

/* Checked size arithmetic: every size computed from input goes through
 * these (one place for the overflow rule). Each stores the result in *r and
 * returns 0, or returns 1 and leaves *r alone when the exact value does not
 * fit a size_t. */
static inline int conica__mul_size(size_t a, size_t b, size_t *r)
{
    if (b != 0 && a > SIZE_MAX / b)
        return 1;
    *r = a * b;
    return 0;
}
static inline int conica__add_size(size_t a, size_t b, size_t *r)
{
    if (a > SIZE_MAX - b)
        return 1;
    *r = a + b;
    return 0;
}
/* A double to size_t, truncated toward zero: 1 for NaN, a negative value
 * or one at or above 2^64 (the conversion would be undefined, C11
 * 6.3.1.4), *r untouched then. SIZE_MAX itself rounds up to 2^64 as a
 * double, so the bound is the power of two, compared exactly. */
static inline int conica__size_from_double(double x, size_t *r)
{
    if (!(x >= 0) || !(x < 18446744073709551616.0))
        return 1;
    if (SIZE_MAX < UINT64_MAX && x > (double)SIZE_MAX)
        return 1; /* a 32-bit size_t */
    *r = (size_t)x;
    return 0;
}
/* The same clamped to [0, hi]: NaN and negatives give 0, anything above
 * hi (Inf included) gives hi. */
static inline size_t conica__size_clamp(double x, size_t hi)
{
    size_t r;
    if (!(x > 0))
        return 0;
    if (conica__size_from_double(x, &r) || r > hi)
        return hi;
    return r;
}
/* Subdivision's inflection edges read at the coordinates' own rounding
 * (subdiv_infl.c): need[e] (edge e, e + 1; n edges closed, n - 1 open)
 * holds the exact side tests' result on entry; between two vertices whose
 * turn is outside the rounding (the larger of noise and a few ulps of the
 * |coordinate| of the turn's three points), two or more sign changes become their parity.
 * The points are xyd (double) or, when it is NULL, xyl. Returns the
 * number of edges left marked. */
size_t conica__infl_at_rounding(const double *xyd, const long double *xyl, size_t n, int closed,
                                double noise, unsigned char *need);
/* Subdivision's working origin (subdiv_origin.c): per coordinate the
 * centre of the points' range when its magnitude is at least the range's
 * width (then p - c is exact for every point), else 0. The points are xyd
 * (double) or, when it is NULL, xyl; n >= 0. */
void conica__subdiv_origin(const double *xyd, const long double *xyl, size_t n, long double c[2]);

#endif
