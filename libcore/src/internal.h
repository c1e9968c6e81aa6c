/* SPDX-License-Identifier: MIT */
/* Internal helpers shared by libcore's translation units (conica__ prefix). */
#ifndef CONICA_INTERNAL_H
#define CONICA_INTERNAL_H

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

#endif
