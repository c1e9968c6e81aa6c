/* SPDX-License-Identifier: MIT */
/* libFuzzer target: conic subdivision (CONIS) on arbitrary numbers.
 *
 * Input layout (every byte optional; missing bytes read as 0):
 *   byte 0  point count 1..24          byte 1  levels 0..4
 *   byte 2  flags: closed, precise, estimate_normals, reference_compatible,
 *           force_svd, normalize_normals, plain_quadratic, no inflections
 *   byte 3  patch_grow 1..4, normal method, has normals, entry point
 *           (conica_subdivide / conica_subdividel / conica_subdivide_curvel)
 *   then    2n coordinates and (with normals) 2n normal components, each
 *           from fz_double(): NaN, Inf, denormals, 1e300, duplicates, raw bits.
 * Output budget 1<<14 points. On success every output value must be finite
 * and the point count must be what conica_subdiv_count() promises plus the
 * inserted inflections. */
#include "fuzz_common.h"

#include "conica/curve.h"
#include "conica/subdiv.h"

#define FZ_MAX_POINTS ((size_t)1 << 14)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_reader r;
    double xy[48], nxy[48], prev = 0;
    conica_curve in;
    conica_status st;
    conica_subdiv_info info;
    conica_code rc;
    fz_init(&r, data, size);
    size_t n = fz_range(&r, 1, 24);
    int levels = (int)fz_range(&r, 0, 4);
    unsigned flags = fz_u8(&r), more = fz_u8(&r);
    int has_normals = (more >> 3) & 1;
    for (size_t i = 0; i < 2 * n; i++)
        xy[i] = prev = fz_double(&r, i >= 2 ? xy[i - 2] : prev);
    for (size_t i = 0; i < 2 * n; i++)
        nxy[i] = prev = fz_double(&r, i >= 2 ? nxy[i - 2] : prev);

    conica_subdiv_settings s = conica_subdiv_defaults();
    s.levels = levels;
    s.precise = (int)((flags >> 1) & 1);
    s.estimate_normals = (int)((flags >> 2) & 1);
    s.reference_compatible = (int)((flags >> 3) & 1);
    s.force_svd = (int)((flags >> 4) & 1);
    s.normalize_normals = (int)((flags >> 5) & 1);
    s.plain_quadratic = (int)((flags >> 6) & 1);
    s.insert_inflections = !((flags >> 7) & 1);
    s.patch_grow = (int)(more & 3) + 1;
    s.normal_method = (more >> 2) & 1 ? CONICA_NORMALS_CIRCLE : CONICA_NORMALS_AREA;
    s.max_points = FZ_MAX_POINTS;
    int closed = (int)(flags & 1);
    unsigned entry = (more >> 4) % 3u;

    memset(&st, 0, sizeof st);
    conica_curve_init(&in);
    conica_subdiv_info_init(&info);
    rc = conica_curve_set(xy, has_normals ? nxy : NULL, n, closed, &in, &st);
    fz_check_status(rc, &st);
    if (rc != CONICA_OK)
        return 0;
    size_t expect = conica_subdiv_count(n, closed, levels);
    if (entry == 0) {
        conica_curve out;
        conica_curve_init(&out);
        rc = conica_subdivide(&in, &s, &out, &info, &st);
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            FZ_ASSERT(out.n <= FZ_MAX_POINTS && out.nxy != NULL);
            FZ_ASSERT(expect == 0 || out.n >= expect);
            for (size_t i = 0; i < 2 * out.n; i++)
                FZ_ASSERT(isfinite(out.xy[i]) && isfinite(out.nxy[i]));
        } else {
            FZ_ASSERT(out.n == 0 && out.xy == NULL);
        }
        conica_curve_free(&out);
    } else {
        conica_curvel out;
        conica_curvel_init(&out);
        if (entry == 1) {
            rc = conica_subdividel(&in, &s, &out, &info, &st);
        } else {
            conica_curvel inl;
            long double lxy[48], lnxy[48];
            for (size_t i = 0; i < 2 * n; i++) {
                lxy[i] = xy[i];
                lnxy[i] = nxy[i];
            }
            inl.n = inl.cap = n;
            inl.xy = lxy;
            inl.nxy = has_normals ? lnxy : NULL;
            inl.closed = closed;
            rc = conica_subdivide_curvel(&inl, &s, &out, &info, &st);
        }
        fz_check_status(rc, &st);
        if (rc == CONICA_OK) {
            FZ_ASSERT(out.n <= FZ_MAX_POINTS);
            for (size_t i = 0; i < 2 * out.n; i++)
                FZ_ASSERT(isfinite(out.xy[i]));
        }
        conica_curvel_free(&out);
    }
    conica_subdiv_info_free(&info);
    conica_curve_free(&in);
    return 0;
}
