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
            if (b[1] > q[1] && conica__scad_orient(a, b, q) > 0)
                w++;
        } else if (b[1] <= q[1] && conica__scad_orient(a, b, q) < 0) {
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

/* Fill state just inside (with_self) or just outside contour c: the union
 * over groups of each group's rule applied to the winding of that group's
 * contours enclosing the point (c's ancestors, plus c itself inside). */
static int fill_state(const conica_scad_profile *p, const info *in, size_t c, int with_self)
{
    for (size_t a = with_self ? c : in[c].parent; a != SIZE_MAX; a = in[a].parent) {
        size_t g = p->contours[a].group;
        int w = 0, seen_before = 0;
        /* each group once: skip if a nearer chain member already did it */
        for (size_t b = with_self ? c : in[c].parent; b != a; b = in[b].parent)
            if (p->contours[b].group == g)
                seen_before = 1;
        if (seen_before)
            continue;
        for (size_t b = a; b != SIZE_MAX; b = in[b].parent)
            if (p->contours[b].group == g)
                w += in[b].area > 0 ? 1 : -1;
        if (filled(w, p->groups[g].fill))
            return 1;
    }
    return 0;
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
    /* Parent: the smallest contour containing c's first vertex. Without
     * crossings (validated) any vertex of c is inside or outside another
     * contour, never on it. A parent is strictly larger in the order
     * (|area|, then index), so the parent links form a forest even for the
     * invalid profiles --force arranges (fuzz_scadprofile: two identical
     * subpaths were each other's parent, and fill_state() looped forever). */
    for (size_t c = 0; c < n; c++) {
        const double *q = p->contours[c].xy;
        double best = INFINITY, ac = fabs(in[c].area);
        for (size_t d = 0; d < n; d++) {
            double ad = fabs(in[d].area);
            if (!(ad > ac || (ad == ac && d < c)) || !(ad < best))
                continue;
            if (q[0] < in[d].box[0] || q[0] > in[d].box[2] || q[1] < in[d].box[1] ||
                q[1] > in[d].box[3])
                continue;
            if (winding(&p->contours[d], q) != 0) {
                best = fabs(in[d].area);
                in[c].parent = d;
            }
        }
    }
    for (size_t c = 0; c < n; c++) {
        in[c].inside = fill_state(p, in, c, 1);
        in[c].outside = fill_state(p, in, c, 0);
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
