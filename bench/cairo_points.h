/* SPDX-License-Identifier: MIT */
/* The points of a flattened cairo path (cairo_copy_path_flat's move-to
 * and line-to points) into xy[2 cap], for the benchmarks that compare
 * with cairo (bench_flatten.c, bench_arcs.c). Include after <cairo.h>. */
#ifndef CONICA_BENCH_CAIRO_POINTS_H
#define CONICA_BENCH_CAIRO_POINTS_H

#include <stddef.h>

/* Flattens cr's current path, returns the point count (at most cap). */
static inline size_t bench_cairo_points(cairo_t *cr, double *xy, size_t cap)
{
    cairo_path_t *path = cairo_copy_path_flat(cr);
    size_t n = 0;
    for (int i = 0; i < path->num_data; i += path->data[i].header.length) {
        const cairo_path_data_t *d = &path->data[i];
        if ((d->header.type == CAIRO_PATH_MOVE_TO || d->header.type == CAIRO_PATH_LINE_TO) &&
            n < cap) {
            xy[2 * n] = d[1].point.x;
            xy[2 * n + 1] = d[1].point.y;
            n++;
        }
    }
    cairo_path_destroy(path);
    return n;
}

#endif
