/* SPDX-License-Identifier: MIT */
/**
 * @file common.h
 * @brief Export macro, status codes and the status record shared by every
 *        libconica module.
 *
 * Conventions for the whole API (read once, they hold everywhere):
 * - Arguments come as inputs, then outputs, then an optional
 *   `conica_status *` (may be NULL). On failure outputs are left untouched.
 * - Point arrays are `const double *xy, size_t n`: n points, interleaved
 *   x0,y0,x1,y1,... (so 2n doubles).
 * - `*_init` gives an empty value that is always safe to `*_free`; `*_free`
 *   accepts NULL and empty values. Memory returned inside a struct belongs
 *   to that struct and is released by its `*_free`.
 * - There is no global state: every function is reentrant.
 */
#ifndef CONICA_COMMON_H
#define CONICA_COMMON_H

#include <stddef.h>

#if defined(CONICA_BUILDING) || defined(__GNUC__)
#define CONICA_API __attribute__((visibility("default")))
#else
#define CONICA_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Status codes returned by every call that can fail. */
typedef enum conica_code {
    CONICA_OK = 0,          /**< success */
    CONICA_ERR_ARG,         /**< invalid argument (NULL, bad size, bad setting) */
    CONICA_ERR_NOMEM,       /**< out of memory */
    CONICA_ERR_PARSE,       /**< malformed input text */
    CONICA_ERR_IO,          /**< reading or writing a file failed */
    CONICA_ERR_LIMIT,       /**< a configured size or time limit would be exceeded */
    CONICA_ERR_DEGENERATE,  /**< degenerate geometry (too few or coincident points, zero normals) */
    CONICA_ERR_NONFINITE,   /**< NaN or infinite input value */
    CONICA_ERR_NUMERIC,     /**< a numerical method failed to produce a finite result */
    CONICA_ERR_UNSUPPORTED, /**< valid input this build or mode cannot handle */
    CONICA_CODE_COUNT_      /**< number of codes (not a status) */
} conica_code;

/** Optional progress report of a long call (the `progress` member of its
 *  settings): `done` of `total` units of work so far, `done` rising to
 *  `total`. Called from the calling thread only, between pieces of work, a
 *  few hundred times per call at most; `ctx` is the settings'
 *  `progress_ctx`. The call's result does not depend on it. */
typedef void (*conica_progress_fn)(void *ctx, size_t done, size_t total);

/** Optional, caller-owned detail for a failed call. */
typedef struct conica_status {
    conica_code code;  /**< same as the returned code */
    size_t line;       /**< 1-based line of a parse error, 0 if none */
    size_t offset;     /**< 0-based byte offset of a parse error, or index of the offending item */
    char message[256]; /**< human-readable detail, always NUL-terminated */
} conica_status;

/** @brief Short English description of a code (static storage, never NULL). */
CONICA_API const char *conica_strerror(conica_code code);

/** @brief Library version string, e.g. "0.1.0". */
CONICA_API const char *conica_version(void);

#ifdef __cplusplus
}
#endif

#endif
