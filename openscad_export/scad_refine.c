/* SPDX-License-Identifier: MIT */
/* Tolerance-driven refinement of point-normal curves: conic subdivision
 * (CONIS §1.1) to a dense polyline on the limit curve, then the
 * fewest points (conica_scad_thin). */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "conica/subdiv.h"

/* The dense polyline may use this fraction of the tolerance; the chords get
 * the rest (CONIS subdivision converges quadratically, so each level
 * quarters the dense error and the fraction costs few levels). */
#define REFINE_DENSE_FRACTION (1.0 / 256.0)
/* A level-L vertex sits about 4x the level-L chord error away from the chord
 * joining its two neighbours (sagitta ~ kappa h^2 / 2 vs kappa h^2 / 8);
 * 0.3 > 1/4 keeps the estimate on the safe side. */
#define SAGITTA_TO_CHORD_ERROR 0.3

/* Largest distance of a vertex from the chord joining its neighbours. */
static double max_sagitta(const double *xy, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = &xy[2 * ((i + n - 1) % n)], *b = &xy[2 * ((i + 1) % n)];
        double d = conica__scad_seg_dist2(&xy[2 * i], a, b);
        if (d > s)
            s = d;
    }
    return sqrt(s);
}

conica_code conica_scad_refine(const conica_curve *in, double tol, size_t max_dense, double **out,
                               size_t *nout, conica_scad_refine_info *info, conica_status *st)
{
    conica_subdiv_settings set = conica_subdiv_defaults();
    conica_curve dense;
    conica_code rc;
    double err = INFINITY;
    int level;
    if (!in || !out || !nout || in->n < 3 || !(tol > 0) || !isfinite(tol))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                                 "refining needs a closed curve of >= 3 points and a tolerance > 0");
    if (max_dense == 0)
        max_dense = CONICA_SCAD_DEFAULT_MAX_DENSE;
    /* conica_subdiv_count() does not know the inflection points a
     * non-convex curve gains, so the subdivision itself holds the budget
     * (fuzz_scadprofile: 16 points, 2 inflections, 2^14 cap exceeded). */
    set.max_points = max_dense;
    conica_curve_init(&dense);
    for (level = 1; level <= CONICA_SUBDIV_MAX_LEVELS; level++) {
        size_t count = conica_subdiv_count(in->n, 1, level);
        if (count == 0 || count > max_dense) {
            conica_curve_free(&dense);
            return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                     "tolerance %g needs more than %zu dense points (level %d, "
                                     "estimated error %g); raise the cap or the tolerance",
                                     tol, max_dense, level, err);
        }
        set.levels = level;
        rc = conica_subdivide(in, &set, &dense, NULL, st);
        if (rc == CONICA_ERR_LIMIT) {
            conica_curve_free(&dense);
            return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                "tolerance %g needs more than %zu dense points (level %d with "
                                "its inflection points, estimated error %g); raise the cap or "
                                "the tolerance",
                                tol, max_dense, level, err);
        }
        if (rc != CONICA_OK) {
            conica_curve_free(&dense);
            return rc;
        }
        err = SAGITTA_TO_CHORD_ERROR * max_sagitta(dense.xy, dense.n);
        if (err <= tol * REFINE_DENSE_FRACTION)
            break;
    }
    if (level > CONICA_SUBDIV_MAX_LEVELS) {
        conica_curve_free(&dense);
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                 "tolerance %g not reached in %d levels", tol,
                                 CONICA_SUBDIV_MAX_LEVELS);
    }
    rc = conica_scad_thin(dense.xy, dense.n, 1, tol - err, out, nout, st);
    /* A chord spans a whole number of dense points, and subdivision doubles
     * them, so the count can sit a few per cent above the optimum (a circle
     * at 0.001 of its radius 50: chords of 32.97 dense steps become 32). One
     * more level halves that granularity; keep it when it saves points. */
    if (rc == CONICA_OK && level < CONICA_SUBDIV_MAX_LEVELS) {
        size_t count = conica_subdiv_count(in->n, 1, level + 1);
        conica_curve finer;
        conica_curve_init(&finer);
        set.levels = level + 1;
        if (count != 0 && count <= max_dense &&
            conica_subdivide(in, &set, &finer, NULL, NULL) == CONICA_OK) {
            double fe = SAGITTA_TO_CHORD_ERROR * max_sagitta(finer.xy, finer.n), *pts = NULL;
            size_t m = 0;
            if (fe < tol && conica_scad_thin(finer.xy, finer.n, 1, tol - fe, &pts, &m, NULL) ==
                                CONICA_OK) {
                if (m < *nout) {
                    free(*out);
                    *out = pts;
                    *nout = m;
                    level++;
                    err = fe;
                    conica_curve_free(&dense);
                    dense = finer;
                    conica_curve_init(&finer);
                } else {
                    free(pts);
                }
            }
        }
        conica_curve_free(&finer);
    }
    if (rc == CONICA_OK && info) {
        info->levels = level;
        info->dense_points = dense.n;
        info->dense_error = err;
        info->points = *nout;
    }
    conica_curve_free(&dense);
    return rc;
}
