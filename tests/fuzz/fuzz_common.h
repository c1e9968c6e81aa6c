/* SPDX-License-Identifier: MIT */
/*
 * fuzz_common.h - helpers shared by the libFuzzer targets in tests/fuzz/.
 *
 * A target decodes the fuzzer's bytes with a `fz_reader` (every read past
 * the end yields zeros, so any input is a valid program), calls the library
 * the way the tools do, and checks the API contract with FZ_ASSERT: a
 * violated contract aborts, which libFuzzer reports as a crash and saves as
 * a reproducer.
 */
#ifndef CONICA_FUZZ_COMMON_H
#define CONICA_FUZZ_COMMON_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "conica/common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FZ_ASSERT(cond)                                                          \
    do {                                                                         \
        if (!(cond)) {                                                           \
            fprintf(stderr, "%s:%d: contract violated: %s\n", __FILE__, __LINE__, \
                    #cond);                                                      \
            abort();                                                             \
        }                                                                        \
    } while (0)

typedef struct fz_reader {
    const uint8_t *p;
    size_t n, i;
} fz_reader;

static inline void fz_init(fz_reader *r, const uint8_t *p, size_t n)
{
    r->p = p;
    r->n = n;
    r->i = 0;
}

static inline unsigned fz_u8(fz_reader *r)
{
    return r->i < r->n ? r->p[r->i++] : 0u;
}

/* A value in [lo, hi] (hi - lo < 256). */
static inline unsigned fz_range(fz_reader *r, unsigned lo, unsigned hi)
{
    return lo + fz_u8(r) % (hi - lo + 1u);
}

/*
 * A double from the bytes, biased toward the values that break numerics:
 * NaN, infinities, signed zeros, denormals, the extremes of the range,
 * 1e300, a repeat of the previous value (duplicate points), small integers
 * and, otherwise, 8 raw bytes (any bit pattern).
 */
static inline double fz_double(fz_reader *r, double prev)
{
    unsigned sel = fz_u8(r);
    switch (sel % 24u) {
    case 0: return NAN;
    case 1: return INFINITY;
    case 2: return -INFINITY;
    case 3: return 0.0;
    case 4: return -0.0;
    case 5: return 4.9406564584124654e-324; /* smallest denormal */
    case 6: return 2.2250738585072009e-308; /* largest denormal */
    case 7: return DBL_MIN;
    case 8: return DBL_MAX;
    case 9: return 1e300;
    case 10: return -1e300;
    case 11: return 1e-300;
    case 12: case 13: case 14: return prev; /* duplicates */
    case 15: {
        uint64_t u = 0;
        double d;
        for (int k = 0; k < 8; k++)
            u = (u << 8) | fz_u8(r);
        memcpy(&d, &u, sizeof d);
        return d;
    }
    case 16: return prev + ldexp((double)((int)fz_u8(r) - 128), -40); /* near-duplicate */
    default: return ((double)fz_u8(r) - 128.0) / 8.0 + (double)(sel % 7u);
    }
}

/* The status message is always NUL-terminated and the code matches. */
static inline void fz_check_status(conica_code rc, const conica_status *st)
{
    FZ_ASSERT(memchr(st->message, '\0', sizeof st->message) != NULL);
    FZ_ASSERT(rc == CONICA_OK || st->code == rc);
    FZ_ASSERT((int)rc >= 0 && rc < CONICA_CODE_COUNT_);
}

/* A copy of the input in its own exact-size allocation, so that reading one
 * byte past `len` is an AddressSanitizer report (the parsers take (buf, len)
 * and must never rely on a terminator). */
static inline char *fz_copy(const uint8_t *data, size_t size)
{
    char *b = malloc(size ? size : 1);
    if (b && size)
        memcpy(b, data, size);
    return b;
}

#endif
