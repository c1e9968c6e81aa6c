/* SPDX-License-Identifier: MIT */
/* Outer contours and holes from containment and the fill rules. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Scan lines per axis for the convexity estimate. */
#define CONVEXITY_SCAN_LINES 64

void conica_scad_layout_init(conica_scad_layout *l)
{
    if (l)
        memset(l, 0, sizeof *l);
}

void conica_scad_layout_free(conica_scad_layout *l)
{
    if (!l)
        return;
    free(l->paths);
    memset(l, 0, sizeof *l);
}

/* Winding number of contour k around q (Sunday's algorithm with the exact
 * orientation test); q must not lie on k. */
static int winding(const conica_scad_contour *k, const double *q)
{
    int w = 0;
    for (size_t i = 0; i < k->n; i++) {
        const double *a = &k->xy[2 * i], *b = &k->xy[2 * ((i + 1) % k->n)];
        if (a[1] <= q[1]) {
            if (b[1] > q[1] && conica__orient2d(a, b, q) > 0)
                w++;
        } else if (b[1] <= q[1] && conica__orient2d(a, b, q) < 0) {
            w--;
        }
    }
    return w;
}

typedef struct info {
    double area;            /* signed */
    double box[4];          /* xmin, ymin, xmax, ymax */
    size_t parent;          /* smallest containing contour, SIZE_MAX if none */
    int inside, outside;    /* filled just inside / just outside */
} info;

static int filled(int w, conica_scad_fill rule)
{
    return rule == CONICA_SCAD_FILL_EVENODD ? (w & 1) != 0 : w != 0;
}

/* Cells per axis of the grid that finds each contour's parent, and the most
 * cells a contour's box may cover before it goes to the list of large
 * contours instead (so the grid holds at most SCAD_GRID_MAX_COVER entries
 * per contour). */
#define SCAD_GRID_MAX_CELLS 1024
#define SCAD_GRID_MAX_COVER 16

/* The arrangement's order on contours: by |area|, ties by index (the lower
 * index counts as the larger, as the parent rule below needs). */
static int before(const info *in, size_t a, size_t b)
{
    double fa = fabs(in[a].area), fb = fabs(in[b].area);
    return fa < fb || (fa == fb && a < b);
}

/* Sort v[0..n) by `before` (tmp: n scratch entries). C's qsort() has no
 * context argument, so a bottom-up merge sort: O(n log n) on any input. */
static void sort_by_area(const info *in, size_t *v, size_t n, size_t *tmp)
{
    for (size_t w = 1; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t a = lo, b = mid, k = lo;
            while (a < mid && b < hi)
                tmp[k++] = before(in, v[b], v[a]) ? v[b++] : v[a++];
            while (a < mid)
                tmp[k++] = v[a++];
            while (b < hi)
                tmp[k++] = v[b++];
        }
        memcpy(v, tmp, n * sizeof *v);
    }
}

/* In v[0..n) (sorted by `before`), the first contour d that is larger than
 * c (|area| larger, or equal with d < c) whose box holds q and whose
 * winding around q is not 0; SIZE_MAX if none. */
static size_t first_container(const conica_scad_profile *p, const info *in, const size_t *v,
                              size_t n, size_t c, const double *q)
{
    double ac = fabs(in[c].area);
    size_t lo = 0, hi = n;
    while (lo < hi) { /* first entry with |area| >= ac */
        size_t mid = lo + (hi - lo) / 2;
        if (fabs(in[v[mid]].area) < ac)
            lo = mid + 1;
        else
            hi = mid;
    }
    for (size_t i = lo; i < n; i++) {
        size_t d = v[i];
        if (fabs(in[d].area) == ac && d >= c)
            continue;
        if (q[0] < in[d].box[0] || q[0] > in[d].box[2] || q[1] < in[d].box[1] ||
            q[1] > in[d].box[3])
            continue;
        if (winding(&p->contours[d], q) != 0)
            return d;
    }
    return SIZE_MAX;
}

/* Column (or row) of coordinate v in a grid of g cells of width w from o. */
static size_t cell_of(double v, double o, double w, size_t g)
{
    double k;
    if (!(w > 0) || !(v > o))
        return 0;
    k = (v - o) / w;
    return k < (double)g ? (size_t)k : g - 1;
}

/* Parent of every contour: the smallest one containing its first vertex.
 * Without crossings (validated) any vertex of c is inside or outside
 * another contour, never on it. A parent is strictly larger in the order
 * (|area|, then index), so the parent links form a forest even for the
 * invalid profiles --force arranges (fuzz_scadprofile: two identical
 * subpaths were each other's parent, and the fill states looped forever).
 * Comparing every pair was quadratic (80 000 small overlapping paths: 40 s
 * under --force): candidates come from a uniform grid over the boxes
 * (contours whose box covers few cells) and from one list of the large
 * ones, each sorted by area, so the first container met is the parent.
 * Returns 0, or -1 out of memory. */
static int find_parents(const conica_scad_profile *p, info *in, size_t n)
{
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    size_t g = 1, ncell, nbig = 0, total = 0;
    size_t *start = NULL, *entries = NULL, *big = NULL, *tmp = NULL, *fill = NULL;
    int rc = -1;
    for (size_t c = 0; c < n; c++) {
        box[0] = fmin(box[0], in[c].box[0]);
        box[1] = fmin(box[1], in[c].box[1]);
        box[2] = fmax(box[2], in[c].box[2]);
        box[3] = fmax(box[3], in[c].box[3]);
    }
    {
        /* cells about the size of a typical contour's box (the median of
         * the larger box sides; a sample of at most 1024 contours), at
         * least the extent / sqrt(n), at most SCAD_GRID_MAX_CELLS a side */
        double side[1024], ext = fmax(box[2] - box[0], box[3] - box[1]), cell;
        size_t m = n < 1024 ? n : 1024;
        for (size_t k = 0; k < m; k++) {
            size_t c = k * (n / m);
            side[k] = fmax(in[c].box[2] - in[c].box[0], in[c].box[3] - in[c].box[1]);
        }
        for (size_t k = 1; k < m; k++) /* insertion sort of the sample */
            for (size_t j = k; j > 0 && side[j - 1] > side[j]; j--) {
                double t = side[j];
                side[j] = side[j - 1];
                side[j - 1] = t;
            }
        while (g * g < n && g < SCAD_GRID_MAX_CELLS)
            g++;
        cell = m ? side[m / 2] : 0.0;
        if (ext > 0 && isfinite(ext) && cell > 0 && ext / cell < (double)g)
            g = ext / cell < 1.0 ? 1 : (size_t)(ext / cell);
    }
    ncell = g * g;
    double wx = (box[2] - box[0]) / (double)g, wy = (box[3] - box[1]) / (double)g;
    if (!(wx > 0) || !isfinite(wx))
        wx = 0;
    if (!(wy > 0) || !isfinite(wy))
        wy = 0;
    start = calloc(ncell + 1, sizeof *start);
    fill = calloc(ncell, sizeof *fill);
    big = malloc(n * sizeof *big);
    tmp = malloc(n * sizeof *tmp);
    if (!start || !fill || !big || !tmp)
        goto done;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t c = 0; c < n; c++) {
            size_t x0 = cell_of(in[c].box[0], box[0], wx, g);
            size_t x1 = cell_of(in[c].box[2], box[0], wx, g);
            size_t y0 = cell_of(in[c].box[1], box[1], wy, g);
            size_t y1 = cell_of(in[c].box[3], box[1], wy, g);
            if ((x1 - x0 + 1) * (y1 - y0 + 1) > SCAD_GRID_MAX_COVER) {
                if (pass == 0)
                    big[nbig++] = c;
                continue;
            }
            for (size_t y = y0; y <= y1; y++)
                for (size_t x = x0; x <= x1; x++) {
                    if (pass == 0)
                        start[y * g + x + 1]++;
                    else
                        entries[start[y * g + x] + fill[y * g + x]++] = c;
                }
        }
        if (pass == 0) {
            for (size_t k = 0; k < ncell; k++)
                start[k + 1] += start[k];
            total = start[ncell];
            entries = malloc((total ? total : 1) * sizeof *entries);
            if (!entries)
                goto done;
        }
    }
    for (size_t k = 0; k < ncell; k++)
        sort_by_area(in, entries + start[k], start[k + 1] - start[k], tmp);
    sort_by_area(in, big, nbig, tmp);
    for (size_t c = 0; c < n; c++) {
        const double *q = p->contours[c].xy;
        size_t cell = cell_of(q[1], box[1], wy, g) * g + cell_of(q[0], box[0], wx, g);
        size_t a = first_container(p, in, entries + start[cell], start[cell + 1] - start[cell],
                                   c, q);
        size_t b = first_container(p, in, big, nbig, c, q);
        in[c].parent = a == SIZE_MAX ? b : b == SIZE_MAX ? a : before(in, a, b) ? a : b;
    }
    rc = 0;
done:
    free(start);
    free(fill);
    free(entries);
    free(big);
    free(tmp);
    return rc;
}

/* Fill state just inside and just outside every contour: the union over
 * groups of each group's rule applied to the winding of that group's
 * contours enclosing the point (the contour's ancestors, plus itself
 * inside). One walk down the parent forest keeps each group's winding
 * along the current chain and how many groups are filled, so a contour
 * costs O(1) (walking each chain per contour was quadratic in the depth).
 * Returns 0, or -1 out of memory. */
static int fill_states(const conica_scad_profile *p, info *in, size_t n)
{
    size_t *first = calloc(n + 1, sizeof *first), *child = malloc((n ? n : 1) * sizeof *child);
    size_t *stack = malloc((n ? n : 1) * sizeof *stack), *cursor = calloc(n, sizeof *cursor);
    size_t *cnt = calloc(n, sizeof *cnt);
    long *w = calloc(p->ngroups ? p->ngroups : 1, sizeof *w);
    int rc = -1;
    if (!first || !child || !stack || !cursor || !cnt || !w)
        goto done;
    for (size_t c = 0; c < n; c++)
        if (in[c].parent != SIZE_MAX)
            first[in[c].parent + 1]++;
    for (size_t c = 0; c < n; c++)
        first[c + 1] += first[c];
    for (size_t c = 0; c < n; c++)
        if (in[c].parent != SIZE_MAX)
            child[first[in[c].parent] + cursor[in[c].parent]++] = c;
    memset(cursor, 0, n * sizeof *cursor);
    for (size_t root = 0; root < n; root++) {
        size_t top = 0;
        if (in[root].parent != SIZE_MAX)
            continue;
        stack[top++] = root;
        /* entering a node: its group's winding changes by its orientation */
        for (int entering = 1; top > 0;) {
            size_t c = stack[top - 1], gi = p->contours[c].group;
            conica_scad_fill rule = p->groups[gi].fill;
            long sgn = in[c].area > 0 ? 1 : -1;
            if (entering) {
                size_t outside = in[c].parent == SIZE_MAX ? 0 : cnt[in[c].parent];
                long old = w[gi];
                w[gi] = old + sgn;
                cnt[c] = outside - (size_t)filled((int)old, rule) +
                         (size_t)filled((int)w[gi], rule);
                in[c].inside = cnt[c] > 0;
                in[c].outside = outside > 0;
            }
            if (cursor[c] < first[c + 1] - first[c]) {
                stack[top++] = child[first[c] + cursor[c]++];
                entering = 1;
            } else {
                w[gi] -= sgn; /* leaving */
                top--;
                entering = 0;
            }
        }
    }
    rc = 0;
done:
    free(first);
    free(child);
    free(stack);
    free(cursor);
    free(cnt);
    free(w);
    return rc;
}

static int convexity(const conica_scad_profile *p, const conica_scad_path *paths, size_t np)
{
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    size_t best = 0;
    for (size_t i = 0; i < np; i++) {
        const conica_scad_contour *k = &p->contours[paths[i].contour];
        for (size_t j = 0; j < k->n; j++) {
            box[0] = fmin(box[0], k->xy[2 * j]);
            box[1] = fmin(box[1], k->xy[2 * j + 1]);
            box[2] = fmax(box[2], k->xy[2 * j]);
            box[3] = fmax(box[3], k->xy[2 * j + 1]);
        }
    }
    for (size_t axis = 0; axis < 2; axis++) {
        for (int s = 0; s < CONVEXITY_SCAN_LINES; s++) {
            double at = box[1 - axis] + (box[3 - axis] - box[1 - axis]) * (s + 0.5) /
                                            CONVEXITY_SCAN_LINES;
            size_t crossings = 0;
            for (size_t i = 0; i < np; i++) {
                const conica_scad_contour *k = &p->contours[paths[i].contour];
                for (size_t j = 0; j < k->n; j++) {
                    double u = k->xy[2 * j + 1 - axis], v = k->xy[2 * ((j + 1) % k->n) + 1 - axis];
                    crossings += (u > at) != (v > at);
                }
            }
            if (crossings > best)
                best = crossings;
        }
    }
    best /= 2;
    return best < 1 ? 1 : best > 1000000 ? 1000000 : (int)best;
}

conica_code conica_scad_arrange(const conica_scad_profile *p, conica_scad_layout *out,
                                conica_status *st)
{
    size_t n;
    if (!p || !out || p->ncontours == 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "empty profile");
    n = p->ncontours;
    info *in = calloc(n, sizeof *in);
    conica_scad_path *paths = calloc(n, sizeof *paths);
    if (!in || !paths) {
        free(in);
        free(paths);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    for (size_t c = 0; c < n; c++) {
        const conica_scad_contour *k = &p->contours[c];
        in[c].area = 0.5 * conica__scad_area2(k->xy, k->n);
        in[c].box[0] = in[c].box[1] = INFINITY;
        in[c].box[2] = in[c].box[3] = -INFINITY;
        for (size_t j = 0; j < k->n; j++) {
            in[c].box[0] = fmin(in[c].box[0], k->xy[2 * j]);
            in[c].box[1] = fmin(in[c].box[1], k->xy[2 * j + 1]);
            in[c].box[2] = fmax(in[c].box[2], k->xy[2 * j]);
            in[c].box[3] = fmax(in[c].box[3], k->xy[2 * j + 1]);
        }
        in[c].parent = SIZE_MAX;
    }
    if (find_parents(p, in, n) != 0 || fill_states(p, in, n) != 0) {
        free(in);
        free(paths);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    size_t np = 0, outers = 0, holes = 0, dropped = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t c = 0; c < n; c++) {
            if (in[c].inside == in[c].outside) {
                dropped += pass == 0;
                continue;
            }
            int hole = !in[c].inside;
            if (hole != pass)
                continue;
            size_t par = in[c].parent;
            while (par != SIZE_MAX && in[par].inside == in[par].outside)
                par = in[par].parent;
            paths[np].contour = c;
            paths[np].hole = hole;
            paths[np].reversed = hole ? in[c].area > 0 : in[c].area < 0;
            paths[np].parent = par;
            np++;
            if (hole)
                holes++;
            else
                outers++;
        }
    }
    free(in);
    if (np == 0) {
        free(paths);
        return conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                                 "no filled region: every contour cancels out under the fill rule");
    }
    conica_scad_layout_free(out);
    out->paths = paths;
    out->npaths = np;
    out->outers = outers;
    out->holes = holes;
    out->dropped = dropped;
    out->convexity = convexity(p, paths, np);
    conica__ok(st);
    return CONICA_OK;
}
