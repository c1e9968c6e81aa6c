/* SPDX-License-Identifier: MIT */
/* libFuzzer target: the point-file reader conica_curve_parse() (`v x y` /
 * `vn nx ny` text) and conica_curve_line_of_point() on what it accepted. */
#include "fuzz_common.h"

#include "conica/curve.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *buf = fz_copy(data, size);
    conica_curve c, sentinel_copy;
    conica_status st;
    conica_code rc;
    static const double one[2] = {7.0, -3.0};
    if (!buf)
        return 0;
    memset(&st, 0, sizeof st);
    conica_curve_init(&c);
    conica_curve_init(&sentinel_copy);
    /* A previous value in the output: it must survive a failed parse. */
    FZ_ASSERT(conica_curve_set(one, NULL, 1, 0, &c, NULL) == CONICA_OK);
    rc = conica_curve_parse(buf, size, &c, &st);
    fz_check_status(rc, &st);
    if (rc == CONICA_OK) {
        FZ_ASSERT(c.n <= CONICA_CURVE_MAX_INPUT_POINTS);
        FZ_ASSERT(c.n == 0 || c.xy != NULL);
        for (size_t i = 0; i < 2 * c.n; i++) {
            FZ_ASSERT(isfinite(c.xy[i]));
            if (c.nxy)
                FZ_ASSERT(isfinite(c.nxy[i]));
        }
        if (c.n > 0) {
            size_t l0 = conica_curve_line_of_point(buf, size, 0, 0);
            size_t l1 = conica_curve_line_of_point(buf, size, c.n - 1, 0);
            FZ_ASSERT(l0 >= 1 && l1 >= l0);
            FZ_ASSERT(conica_curve_line_of_point(buf, size, c.n, 0) == 0);
            if (c.nxy)
                FZ_ASSERT(conica_curve_line_of_point(buf, size, c.n - 1, 1) >= 1);
        }
    } else {
        FZ_ASSERT(c.n == 1 && c.xy[0] == one[0] && c.xy[1] == one[1]);
        /* DEGENERATE: a `vn 0 0` line (a normal without a direction) is
         * refused by the parser, although curve.h does not list the code. */
        FZ_ASSERT(rc == CONICA_ERR_PARSE || rc == CONICA_ERR_NONFINITE ||
                  rc == CONICA_ERR_LIMIT || rc == CONICA_ERR_NOMEM ||
                  rc == CONICA_ERR_DEGENERATE);
    }
    conica_curve_free(&c);
    conica_curve_free(&sentinel_copy);
    free(buf);
    return 0;
}
