/* SPDX-License-Identifier: MIT */
/* conica_svg_render(): the rendering tree walk of SVG 1.1/2 as librsvg 2.54
 * paints it -- which elements are rendered (display, non-rendered
 * containers, `<switch>`), transforms, the root and nested viewports
 * (viewBox, preserveAspectRatio, overflow clips), `<use>` instances of
 * elements, `<symbol>` and `<svg>`, lengths and units, basic shapes (the
 * paths of svg_shape.c), and the warnings for what is not drawn. Styles come
 * from svg_style.c; the scene's memory and its flat SVG form live in
 * svg_scene.c. */
#include "svg_render_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Levels of elements being rendered at once (XML nesting plus the nesting
 * of `<use>` instances), so the walk's recursion stays bounded whatever the
 * document's depth and use caps. */
#define RENDER_MAX_LEVEL ((size_t)4096)

/* Kinds of warnings (one per element and kind). */
enum {
    W_TEXT, W_IMAGE, W_FOREIGN, W_CLIP, W_MASK, W_FILTER, W_FILTER_MISSING, W_MARKERS,
    W_TRANSFORM_BAD, W_TRANSFORM_SINGULAR, W_CSS_TRANSFORM, W_PATH_DATA, W_POINTS, W_DASHES,
    W_JOIN, W_PAR, W_NON_SCALING, W_KINDS
};

typedef struct use_chain {
    xmlNodePtr use;
    const struct use_chain *up;
} use_chain;

/* What the walk carries down. */
typedef struct frame {
    conica_svg_matrix ctm; /* the element's parent user space to the output frame */
    double vw, vh;         /* the nearest viewport's size in that user space (for %) */
    const double *clip;    /* the current clip polygon (output frame), NULL: none */
    size_t nclip;
    int selected;
    int hidden;            /* an ancestor group has opacity 0 */
    size_t use_depth;
    const use_chain *uses;
} frame;

typedef struct rctx {
    const conica_svg_render_settings *s;
    conica_svg_scene *out;
    conica_svg__ids ids;
    conica_svg__sheet *sheet;
    conica_svg__style **lv; /* one style per level (stable pointers) */
    size_t nlv;
    size_t instances, segments;
    size_t css_budget;      /* selector-matching steps left */
    uintptr_t *warned;      /* open-addressing set of node | kind */
    size_t nwarned, capwarned;
    const char **select;    /* sorted --select ids */
    size_t nselect;
    conica_status *st;
    conica_code rc;
} rctx;

/* ------------------------------------------------------------ matrices */

void conica_svg_matrix_apply(const conica_svg_matrix *m, double x, double y, double out[2])
{
    out[0] = fma(m->a, x, fma(m->c, y, m->e));
    out[1] = fma(m->b, x, fma(m->d, y, m->f));
}

/* p * q: q applied first. */
static conica_svg_matrix mat_mul(const conica_svg_matrix *p, const conica_svg_matrix *q)
{
    conica_svg_matrix r;
    r.a = fma(p->a, q->a, p->c * q->b);
    r.b = fma(p->b, q->a, p->d * q->b);
    r.c = fma(p->a, q->c, p->c * q->d);
    r.d = fma(p->b, q->c, p->d * q->d);
    r.e = fma(p->a, q->e, fma(p->c, q->f, p->e));
    r.f = fma(p->b, q->e, fma(p->d, q->f, p->f));
    return r;
}

static conica_svg_matrix mat_make(double a, double b, double c, double d, double e, double f)
{
    conica_svg_matrix m;
    m.a = a, m.b = b, m.c = c, m.d = d, m.e = e, m.f = f;
    return m;
}

/* a*d - b*c by Kahan's algorithm with an FMA (CONIS §2.3): the
 * determinant is exact enough to tell a singular matrix from a small one. */
static double mat_det(const conica_svg_matrix *m)
{
    double w = m->b * m->c;
    double e = fma(-m->b, m->c, w);
    double f = fma(m->a, m->d, -w);
    return f + e;
}

static int mat_invertible(const conica_svg_matrix *m)
{
    double det = mat_det(m);
    return det != 0.0 && isfinite(det) && isfinite(m->e) && isfinite(m->f);
}

static int blank(char ch)
{
    return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' || ch == '\f';
}

/* The transform attribute (SVG 1.1, 7.6): 1 ok, 0 invalid (then the
 * attribute is ignored, as in librsvg). */
static int parse_transform(const char *s, conica_svg_matrix *out)
{
    static const char *const fn[] = {"matrix", "translate", "scale", "rotate", "skewX", "skewY"};
    static const int nmin[] = {6, 1, 1, 1, 1, 1}, nmax[] = {6, 2, 2, 3, 1, 1};
    conica_svg_matrix m = mat_make(1, 0, 0, 1, 0, 0);
    size_t n = strlen(s), i = 0;
    for (;;) {
        double v[6];
        int k = -1, j, cnt = 0;
        conica_svg_matrix t;
        while (i < n && (blank(s[i]) || s[i] == ','))
            i++;
        if (i >= n)
            break;
        for (j = 0; j < 6; j++) {
            size_t l = strlen(fn[j]);
            if (n - i >= l && !memcmp(s + i, fn[j], l)) {
                k = j;
                i += l;
                break;
            }
        }
        if (k < 0)
            return 0;
        while (i < n && blank(s[i]))
            i++;
        if (i >= n || s[i] != '(')
            return 0;
        i++;
        for (;;) {
            size_t used;
            while (i < n && blank(s[i]))
                i++;
            if (i >= n || s[i] == ')')
                break; /* librsvg 2.54 reads a missing last ')' as there */
            if (cnt >= 6)
                return 0;
            used = conica_svg__read_number(s + i, n - i, &v[cnt]);
            if (!used)
                return 0;
            i += used;
            cnt++;
            while (i < n && blank(s[i]))
                i++;
            if (i < n && s[i] == ',')
                i++;
        }
        i++;
        if (cnt < nmin[k] || cnt > nmax[k] || (k == 3 && cnt == 2))
            return 0;
        switch (k) {
        case 0:
            t = mat_make(v[0], v[1], v[2], v[3], v[4], v[5]);
            break;
        case 1:
            t = mat_make(1, 0, 0, 1, v[0], cnt > 1 ? v[1] : 0.0);
            break;
        case 2:
            t = mat_make(v[0], 0, 0, cnt > 1 ? v[1] : v[0], 0, 0);
            break;
        case 3: {
            double a = v[0] * (M_PI / 180.0), c = cos(a), sn = sin(a);
            /* exact quarter turns keep axis-aligned shapes axis-aligned */
            if (fmod(v[0], 90.0) == 0.0) {
                int q = (int)fmod(fmod(v[0] / 90.0, 4.0) + 4.0, 4.0);
                c = q == 0 ? 1 : q == 2 ? -1 : 0;
                sn = q == 1 ? 1 : q == 3 ? -1 : 0;
            }
            t = mat_make(c, sn, -sn, c, 0, 0);
            if (cnt == 3) {
                conica_svg_matrix a1 = mat_make(1, 0, 0, 1, v[1], v[2]),
                                  a2 = mat_make(1, 0, 0, 1, -v[1], -v[2]);
                t = mat_mul(&a1, &t);
                t = mat_mul(&t, &a2);
            }
            break;
        }
        case 4:
            t = mat_make(1, 0, tan(v[0] * (M_PI / 180.0)), 1, 0, 0);
            break;
        default:
            t = mat_make(1, tan(v[0] * (M_PI / 180.0)), 0, 1, 0, 0);
            break;
        }
        m = mat_mul(&m, &t);
    }
    *out = m;
    return 1;
}

/* ------------------------------------------------------------ clips */

static double poly_area2(const double *p, size_t n)
{
    double a = 0.0;
    size_t i;
    for (i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        a += p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
    }
    return a;
}

static void poly_ccw(double *p, size_t n)
{
    size_t i;
    if (poly_area2(p, n) >= 0.0)
        return;
    for (i = 0; i < n / 2; i++) {
        size_t j = n - 1 - i;
        double x = p[2 * i], y = p[2 * i + 1];
        p[2 * i] = p[2 * j];
        p[2 * i + 1] = p[2 * j + 1];
        p[2 * j] = x;
        p[2 * j + 1] = y;
    }
}

/* The intersection of convex polygon a (na points) with the convex,
 * counter-clockwise polygon b (Sutherland-Hodgman): a new array of *nout
 * points (NULL with *nout == 0 when empty), or NULL with *nout == 1 when
 * out of memory. */
static double *clip_convex(const double *a, size_t na, const double *b, size_t nb, size_t *nout)
{
    size_t cap = na + nb + 1, n = na, i, k;
    double *cur = malloc(2 * cap * sizeof *cur), *nxt = malloc(2 * cap * sizeof *nxt);
    if (!cur || !nxt) {
        free(cur);
        free(nxt);
        *nout = 1;
        return NULL;
    }
    memcpy(cur, a, 2 * na * sizeof *a);
    for (k = 0; k < nb && n; k++) {
        const double *p = b + 2 * k, *q = b + 2 * ((k + 1) % nb);
        double ex = q[0] - p[0], ey = q[1] - p[1];
        size_t m = 0;
        for (i = 0; i < n; i++) {
            const double *u = cur + 2 * i, *w = cur + 2 * ((i + 1) % n);
            double su = ex * (u[1] - p[1]) - ey * (u[0] - p[0]);
            double sw = ex * (w[1] - p[1]) - ey * (w[0] - p[0]);
            if (su >= 0.0 && m < cap) {
                nxt[2 * m] = u[0];
                nxt[2 * m + 1] = u[1];
                m++;
            }
            if (((su >= 0.0) != (sw >= 0.0)) && m < cap) {
                double t = su / (su - sw);
                nxt[2 * m] = u[0] + t * (w[0] - u[0]);
                nxt[2 * m + 1] = u[1] + t * (w[1] - u[1]);
                m++;
            }
        }
        {
            double *t = cur;
            cur = nxt;
            nxt = t;
        }
        n = m;
    }
    free(nxt);
    if (n < 3 || !(fabs(poly_area2(cur, n)) > 0.0)) {
        free(cur);
        *nout = 0;
        return NULL;
    }
    *nout = n;
    return cur;
}

/* The rectangle (x, y, w, h) of user space m, intersected with f's clip,
 * as f2's clip in *owned; 0 when nothing is left (f2 draws nothing), -1 out
 * of memory. */
static int push_clip(const frame *f, const conica_svg_matrix *m, double x, double y, double w,
                     double h, frame *f2, double **owned)
{
    double r[8];
    size_t n;
    conica_svg_matrix_apply(m, x, y, r);
    conica_svg_matrix_apply(m, x + w, y, r + 2);
    conica_svg_matrix_apply(m, x + w, y + h, r + 4);
    conica_svg_matrix_apply(m, x, y + h, r + 6);
    poly_ccw(r, 4);
    if (!f->clip) {
        *owned = malloc(sizeof r);
        if (!*owned)
            return -1;
        memcpy(*owned, r, sizeof r);
        n = 4;
    } else {
        *owned = clip_convex(f->clip, f->nclip, r, 4, &n);
        if (!*owned)
            return n ? -1 : 0;
    }
    f2->clip = *owned;
    f2->nclip = n;
    return 1;
}

/* ------------------------------------------------------------ helpers */

static int is(xmlNodePtr n, const char *tag)
{
    return !strcmp((const char *)n->name, tag);
}

static char *attr(xmlNodePtr n, const char *name)
{
    return conica_svg__attr(n, name, CONICA_SVG__MAX_ATTR, NULL);
}

static void warn(rctx *c, xmlNodePtr n, int kind, const char *fmt, ...) CONICA__PRINTF(4, 5);
static void warn(rctx *c, xmlNodePtr n, int kind, const char *fmt, ...)
{
    char msg[400], what[96];
    uintptr_t key = (uintptr_t)n * W_KINDS + (uintptr_t)kind;
    size_t h, i;
    va_list ap;
    if (!c->s->warn)
        return;
    /* once per element and kind: an open-addressing set */
    if (2 * (c->nwarned + 1) > c->capwarned) {
        size_t nc = c->capwarned ? 2 * c->capwarned : 64, k;
        uintptr_t *t = calloc(nc, sizeof *t);
        if (!t)
            return; /* warnings are best effort: repeat rather than fail */
        for (k = 0; k < c->capwarned; k++)
            if (c->warned[k]) {
                size_t j = (size_t)(c->warned[k] * 2654435761u) & (nc - 1);
                while (t[j])
                    j = (j + 1) & (nc - 1);
                t[j] = c->warned[k];
            }
        free(c->warned);
        c->warned = t;
        c->capwarned = nc;
    }
    h = (size_t)(key * 2654435761u) & (c->capwarned - 1);
    for (i = h; c->warned[i]; i = (i + 1) & (c->capwarned - 1))
        if (c->warned[i] == key)
            return;
    c->warned[i] = key;
    c->nwarned++;
    conica_svg__describe(n, what, sizeof what);
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    {
        char full[512];
        snprintf(full, sizeof full, "%s: %s", what, msg);
        c->s->warn(c->s->warn_ctx, (size_t)xmlGetLineNo(n), full);
    }
}

static int selected_id(const rctx *c, xmlNodePtr n)
{
    char *id;
    size_t lo = 0, hi = c->nselect;
    int hit = 0;
    if (!c->nselect)
        return 0;
    id = attr(n, "id");
    while (id && lo < hi && !hit) {
        size_t mid = lo + (hi - lo) / 2;
        int k = strcmp(id, c->select[mid]);
        if (!k)
            hit = 1;
        else if (k < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    xmlFree(id);
    return hit;
}

/* A length attribute against viewport size ref (for %); *v untouched when
 * the attribute is absent or not a length. 1 read, 0 not. */
static int len_attr(xmlNodePtr n, const char *name, double ref, double font_size, double *v)
{
    char *a = attr(n, name);
    conica_svg__len l;
    int ok;
    if (!a)
        return 0;
    ok = conica_svg__parse_len(a, strlen(a), font_size, &l);
    xmlFree(a);
    if (!ok)
        return 0;
    *v = l.percent ? l.v / 100.0 * ref : l.v;
    return 1;
}

static double diag(const frame *f)
{
    return sqrt(0.5 * (f->vw * f->vw + f->vh * f->vh));
}

static double resolve(const conica_svg__len *l, double ref)
{
    return l->percent ? l->v / 100.0 * ref : l->v;
}

/* viewBox: 1 valid (w, h > 0), 0 absent or invalid, -1 zero or negative
 * size (rendering disabled, SVG 1.1 7.7). */
static int parse_viewbox(xmlNodePtr n, double vb[4])
{
    char *a = attr(n, "viewBox");
    size_t i = 0, len;
    int k, r = 1;
    if (!a)
        return 0;
    len = strlen(a);
    for (k = 0; k < 4 && r; k++) {
        size_t used;
        while (i < len && (blank(a[i]) || a[i] == ','))
            i++;
        used = conica_svg__read_number(a + i, len - i, &vb[k]);
        if (!used)
            r = 0;
        i += used;
    }
    xmlFree(a);
    if (r && !(vb[2] > 0.0 && vb[3] > 0.0))
        r = -1;
    return r;
}

/* preserveAspectRatio (SVG 1.1, 7.8): align x, y in {0, .5, 1} (or *none)
 * and slice; absent: xMidYMid meet. 0 when the value does not start with
 * an align value (after an optional defer): librsvg 2.54 then draws
 * nothing of the element; what follows the align is read as meet unless
 * it is slice. */
static int parse_par(xmlNodePtr n, int *none, double *ax, double *ay, int *slice)
{
    static const char *const al[] = {"xMinYMin", "xMidYMin", "xMaxYMin", "xMinYMid", "xMidYMid",
                                     "xMaxYMid", "xMinYMax", "xMidYMax", "xMaxYMax"};
    char *a = attr(n, "preserveAspectRatio");
    const char *p;
    int k, ok = 1;
    *none = 0;
    *ax = *ay = 0.5;
    *slice = 0;
    if (!a)
        return 1;
    p = a;
    while (blank(*p))
        p++;
    if (!strncmp(p, "defer", 5) && blank(p[5]))
        for (p += 5; blank(*p); p++)
            ;
    if (!strncmp(p, "none", 4) && (!p[4] || blank(p[4]))) {
        *none = 1;
    } else {
        for (k = 0; k < 9; k++)
            if (!strncmp(p, al[k], 8) && (!p[8] || blank(p[8])))
                break;
        if (k < 9) {
            *ax = 0.5 * (k % 3);
            *ay = 0.5 * (k / 3);
            for (p += 8; blank(*p); p++)
                ;
            *slice = !strncmp(p, "slice", 5);
        } else {
            ok = 0;
        }
    }
    xmlFree(a);
    return ok;
}

/* The viewBox-to-viewport transform (SVG 1.1, 7.8) for the viewport (x, y,
 * w, h) and element n's viewBox vb and preserveAspectRatio. */
static conica_svg_matrix viewbox_matrix(xmlNodePtr n, const double vb[4], double x, double y,
                                        double w, double h)
{
    int none, slice;
    double ax, ay, sx = w / vb[2], sy = h / vb[3];
    parse_par(n, &none, &ax, &ay, &slice);
    if (!none) {
        double s = slice ? (sx > sy ? sx : sy) : (sx < sy ? sx : sy);
        sx = sy = s;
    }
    return mat_make(sx, 0, 0, sy, x - vb[0] * sx + ax * (w - vb[2] * sx),
                    y - vb[1] * sy + ay * (h - vb[3] * sy));
}

/* ------------------------------------------------------------ items */

static void name_item(const frame *f, xmlNodePtr n, char *buf, size_t size)
{
    char what[96];
    conica_svg__describe(n, what, sizeof what);
    if (f->uses) {
        char u[96];
        conica_svg__describe(f->uses->use, u, sizeof u);
        snprintf(buf, size, "%.44s via %.44s", what, u);
    } else {
        snprintf(buf, size, "%s", what);
    }
}

static int paint_ok(int paint, const conica_svg__style *st)
{
    return paint == CONICA_SVG__PAINT_COLOR ||
           (paint == CONICA_SVG__PAINT_CURRENT && st->color_visible);
}

/* The geometry of element n into *p (user space); 1 some, 0 none. */
static int geometry(rctx *c, xmlNodePtr n, const frame *f, const conica_svg__style *st,
                    conica_svg_path *p)
{
    size_t left = c->s->max_segments > c->segments ? c->s->max_segments - c->segments : 0;
    if (is(n, "path")) {
        char *d = conica_svg__attr(n, "d", (size_t)-1, NULL);
        conica_code rc;
        if (!d)
            return 0;
        rc = conica_svg_path_parse(d, strlen(d), left + 1, p, c->st);
        xmlFree(d);
        if (rc == CONICA_ERR_LIMIT) {
            c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                                 "more than %zu path segments in the picture",
                                 c->s->max_segments);
            return 0;
        }
        if (rc != CONICA_OK) {
            c->rc = rc;
            return 0;
        }
        if (p->has_error)
            warn(c, n, W_PATH_DATA, "bad path data at byte %zu: %s; %s", p->error_offset,
                 p->error, p->n ? "the part before it is drawn" : "nothing drawn");
        return p->n > 0;
    }
    if (is(n, "polygon") || is(n, "polyline")) {
        char *a = conica_svg__attr(n, "points", (size_t)-1, NULL);
        double *xy = NULL;
        size_t np = 0, bad = 0;
        conica_code rc;
        if (!a)
            return 0;
        rc = conica_svg_points_parse(a, strlen(a), left + 1, &xy, &np, &bad, c->st);
        xmlFree(a);
        if (rc != CONICA_OK) {
            c->rc = rc;
            if (c->st)
                c->st->line = (size_t)xmlGetLineNo(n);
            return 0;
        }
        if (bad != (size_t)-1) {
            /* librsvg 2.54 draws nothing of a list with an error (SVG 1.1,
             * 9.7.1 would keep the pairs before it) */
            warn(c, n, W_POINTS, "bad points list at byte %zu: not drawn (as librsvg 2.54)", bad);
            free(xy);
            return 0;
        }
        if (!conica_svg__points_path(xy, np, is(n, "polygon"), p)) {
            free(xy);
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return 0;
        }
        free(xy);
        return np > 1;
    }
    {
        const char *const *names = conica_svg__shape_attrs((const char *)n->name);
        double v[6] = {0, 0, 0, 0, 0, 0};
        int given[6] = {0, 0, 0, 0, 0, 0}, i, r;
        if (!names)
            return 0;
        for (i = 0; i < 6 && names[i]; i++) {
            const char *nm = names[i];
            /* percentages of the viewport's width (x), height (y) or its
             * normalised diagonal (r) */
            double ref = nm[0] == 'x' || nm[0] == 'w' || !strcmp(nm, "cx") || !strcmp(nm, "rx")
                             ? f->vw
                         : nm[0] == 'y' || nm[0] == 'h' || !strcmp(nm, "cy") || !strcmp(nm, "ry")
                             ? f->vh
                             : diag(f);
            given[i] = len_attr(n, nm, ref, st->font_size, &v[i]);
            /* negative rx/ry are invalid: auto (SVG 2, 10.2) */
            if (given[i] && v[i] < 0.0 && (!strcmp(nm, "rx") || !strcmp(nm, "ry")))
                given[i] = 0, v[i] = 0.0;
        }
        r = conica_svg__shape_path((const char *)n->name, v, given, p);
        if (r == -2)
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        return r == 1;
    }
}

static void draw_shape(rctx *c, xmlNodePtr n, const frame *f, const conica_svg_matrix *ctm,
                       const conica_svg__style *st)
{
    conica_svg_item it;
    conica_svg_scene *out = c->out;
    double w = resolve(&st->stroke_width, diag(f));
    int fill, stroke, is_line = is(n, "line");
    size_t k;
    if (!st->visible || !f->selected)
        return;
    fill = !is_line && !f->hidden && paint_ok(st->fill, st) && st->fill_opacity > 0.0;
    stroke = !f->hidden && paint_ok(st->stroke, st) && st->stroke_opacity > 0.0 && w > 0.0;
    if (!fill && !stroke && !c->s->unpainted)
        return;
    memset(&it, 0, sizeof it);
    conica_svg_path_init(&it.path);
    if (!geometry(c, n, f, st, &it.path)) {
        conica_svg_path_free(&it.path);
        return;
    }
    if (it.path.n > c->s->max_segments - c->segments) {
        conica_svg_path_free(&it.path);
        c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                             "more than %zu path segments in the picture", c->s->max_segments);
        return;
    }
    c->segments += it.path.n;
    if (st->markers && (fill || stroke) && !is(n, "rect") && !is(n, "circle") &&
        !is(n, "ellipse"))
        warn(c, n, W_MARKERS, "markers (marker-start/mid/end) are not drawn");
    it.line = (size_t)xmlGetLineNo(n);
    name_item(f, n, it.name, sizeof it.name);
    it.ctm = *ctm;
    it.fill = fill;
    it.fill_rule = (conica_svg_fill_rule)st->fill_rule;
    it.stroke = stroke;
    it.st.width = w;
    it.st.join = (conica_svg_linejoin)st->join;
    it.st.cap = (conica_svg_linecap)st->cap;
    it.st.miterlimit = st->miterlimit;
    it.st.non_scaling = st->non_scaling;
    if (stroke && st->non_scaling)
        warn(c, n, W_NON_SCALING, "vector-effect non-scaling-stroke: the width is taken in the "
             "output frame as SVG 2 defines (librsvg 2.54 scales it with the element)");
    if (stroke && st->join_unsupported)
        warn(c, n, W_JOIN, "stroke-linejoin miter-clip/arcs drawn as miter (as librsvg 2.54)");
    if (stroke && st->dash_too_long)
        warn(c, n, W_DASHES, "stroke-dasharray has more than %d entries: drawn solid",
             CONICA_SVG_MAX_DASHES);
    if (st->ndash) {
        double sum = 0.0;
        for (k = 0; k < st->ndash; k++)
            sum += it.st.dash[k] = resolve(&st->dash[k], diag(f));
        if (sum > 0.0 && isfinite(sum)) {
            it.st.ndash = st->ndash;
            it.st.dashoffset = resolve(&st->dashoffset, diag(f));
        } else {
            memset(it.st.dash, 0, sizeof it.st.dash);
        }
    }
    if (st->non_scaling) {
        /* lengths of the host frame (CSS px at 96 per inch) in the output unit */
        const char *u = out->unit;
        it.st.width = conica_svg_convert_length(it.st.width, "px", u);
        for (k = 0; k < it.st.ndash; k++)
            it.st.dash[k] = conica_svg_convert_length(it.st.dash[k], "px", u);
        it.st.dashoffset = conica_svg_convert_length(it.st.dashoffset, "px", u);
    }
    if (f->clip) {
        it.clip = malloc(2 * f->nclip * sizeof *it.clip);
        if (!it.clip) {
            conica_svg_path_free(&it.path);
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return;
        }
        memcpy(it.clip, f->clip, 2 * f->nclip * sizeof *it.clip);
        it.nclip = f->nclip;
    }
    if (out->n == out->cap) {
        size_t nc = out->cap ? 2 * out->cap : 16;
        conica_svg_item *t = realloc(out->items, nc * sizeof *t);
        if (!t) {
            conica_svg_path_free(&it.path);
            free(it.clip);
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return;
        }
        out->items = t;
        out->cap = nc;
    }
    out->items[out->n++] = it;
}

/* ------------------------------------------------------------ walk */

/* The computed style of n (svg_style.c) into *out; 0 on failure (c->rc set). */
static int compute_style(rctx *c, xmlNodePtr n, const conica_svg__style *parent,
                         conica_svg__style *out)
{
    int r = conica_svg__style_compute(n, parent, c->sheet, &c->ids, &c->css_budget, out);
    if (r == -2)
        c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                             "CSS selector matching takes more than %zu steps",
                             CONICA_SVG_MAX_CSS_MATCH_STEPS);
    else if (r != 0)
        c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    return r == 0;
}

/* Counts element n drawn at level (caps on nesting and instances) and
 * makes sure the styles of that level and the next exist; 0 on failure
 * (c->rc set). */
static int enter(rctx *c, xmlNodePtr n, size_t level)
{
    if (level >= RENDER_MAX_LEVEL) {
        c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                             "elements and <use> instances nested more than %zu deep",
                             RENDER_MAX_LEVEL);
        return 0;
    }
    if (++c->instances > c->s->max_instances) {
        c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                             "more than %zu elements drawn (<use> copies included)",
                             c->s->max_instances);
        return 0;
    }
    if (level >= c->nlv) {
        /* one style per level, allocated as the walk first goes that deep */
        conica_svg__style **t = realloc(c->lv, (level + 2) * sizeof *t);
        if (!t) {
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return 0;
        }
        c->lv = t;
        while (c->nlv < level + 2) {
            c->lv[c->nlv] = malloc(sizeof **c->lv);
            if (!c->lv[c->nlv]) {
                c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                return 0;
            }
            c->nlv++;
        }
    }
    return 1;
}

static void render_node(rctx *c, xmlNodePtr n, const frame *f, size_t level,
                        const conica_svg__style *parent);

static void render_children(rctx *c, xmlNodePtr n, const frame *f, size_t level,
                            const conica_svg__style *st)
{
    xmlNodePtr k;
    for (k = n->children; k && c->rc == CONICA_OK; k = k->next)
        if (k->type == XML_ELEMENT_NODE)
            render_node(c, k, f, level + 1, st);
}

/* `<switch>`: the first direct child whose conditions hold (SVG 1.1, 5.8.2;
 * systemLanguage matched against English, as rsvg-convert's C locale). */
static void render_switch(rctx *c, xmlNodePtr n, const frame *f, size_t level,
                          const conica_svg__style *st)
{
    xmlNodePtr k;
    for (k = n->children; k; k = k->next) {
        char *ext, *lang;
        int ok;
        if (k->type != XML_ELEMENT_NODE || !conica_svg__is_svg(k))
            continue;
        ext = attr(k, "requiredExtensions");
        lang = attr(k, "systemLanguage");
        ok = !ext && (!lang || !strncmp(lang, "en", 2) || strstr(lang, ", en") ||
                      strstr(lang, ",en"));
        xmlFree(ext);
        xmlFree(lang);
        if (ok) {
            render_node(c, k, f, level + 1, st);
            return;
        }
    }
}

/* A viewport element (nested svg, or symbol through use) at (x, y, w, h)
 * of user space ctm: its viewBox, clip (unless overflow is visible; only
 * with clip) and children. */
static void render_viewport(rctx *c, xmlNodePtr n, const frame *f, const conica_svg_matrix *ctm,
                            double x, double y, double w, double h, int clip, size_t level,
                            const conica_svg__style *st)
{
    frame f2 = *f;
    double vb[4], *owned = NULL;
    int has_vb = parse_viewbox(n, vb), none, slice;
    double ax, ay;
    if (!(w > 0.0) || !(h > 0.0) || has_vb < 0)
        return; /* a zero-size viewport or viewBox disables rendering */
    if (!parse_par(n, &none, &ax, &ay, &slice)) {
        warn(c, n, W_PAR, "preserveAspectRatio is not valid: not drawn (as librsvg 2.54)");
        return;
    }
    if (clip && !st->overflow_visible) {
        int r = push_clip(f, ctm, x, y, w, h, &f2, &owned);
        if (r < 0) {
            c->rc = conica__fail(c->st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return;
        }
        if (!r)
            return;
    }
    if (has_vb) {
        conica_svg_matrix vm = viewbox_matrix(n, vb, x, y, w, h);
        f2.ctm = mat_mul(ctm, &vm);
        f2.vw = vb[2];
        f2.vh = vb[3];
    } else {
        conica_svg_matrix t = mat_make(1, 0, 0, 1, x, y);
        f2.ctm = mat_mul(ctm, &t);
        f2.vw = w;
        f2.vh = h;
    }
    render_children(c, n, &f2, level, st);
    free(owned);
}

static void render_use(rctx *c, xmlNodePtr n, const frame *f, const conica_svg_matrix *ctm,
                       size_t level, const conica_svg__style *st)
{
    char *href = attr(n, "href");
    xmlNodePtr t;
    const use_chain *u;
    use_chain link;
    frame f2 = *f;
    double x = 0, y = 0, w = -1, h = -1;
    conica_svg_matrix tr;
    if (!href)
        href = (char *)xmlGetNsProp(n, BAD_CAST "href", BAD_CAST "http://www.w3.org/1999/xlink");
    t = href && href[0] == '#' ? conica_svg__ids_find(&c->ids, href + 1, strlen(href + 1)) : NULL;
    xmlFree(href);
    if (!t || t->type != XML_ELEMENT_NODE)
        return;
    /* a reference cycle: the target contains this use or one it is drawn in */
    link.use = n;
    link.up = f->uses;
    for (u = &link; u; u = u->up) {
        xmlNodePtr a;
        for (a = u->use; a; a = a->parent)
            if (a == t) {
                c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                                     "<use> at line %ld references an element that contains it "
                                     "(a reference cycle)", xmlGetLineNo(n));
                return;
            }
    }
    if (f->use_depth + 1 > c->s->max_use_depth) {
        c->rc = conica__fail(c->st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(n), 0,
                             "<use> nested more than %zu deep", c->s->max_use_depth);
        return;
    }
    len_attr(n, "x", f->vw, st->font_size, &x);
    len_attr(n, "y", f->vh, st->font_size, &y);
    len_attr(n, "width", f->vw, st->font_size, &w);
    len_attr(n, "height", f->vh, st->font_size, &h);
    tr = mat_make(1, 0, 0, 1, x, y);
    f2.ctm = mat_mul(ctm, &tr);
    f2.use_depth = f->use_depth + 1;
    f2.uses = &link;
    if (conica_svg__is_svg(t) && is(t, "symbol")) {
        conica_svg__style *sst;
        if (!enter(c, t, level + 1))
            return;
        /* the symbol's style inherits from the use */
        sst = c->lv[level + 1];
        if (!compute_style(c, t, st, sst))
            return;
        if (sst->display_none)
            return;
        f2.selected = f2.selected || selected_id(c, t);
        /* librsvg 2.54 clips no symbol instance, whatever its overflow */
        render_viewport(c, t, &f2, &f2.ctm, 0, 0, w >= 0 ? w : f->vw, h >= 0 ? h : f->vh, 0,
                        level + 1, sst);
        return;
    }
    /* an <svg> target keeps its own width and height: librsvg 2.54 does
     * not take the use's (SVG 1.1, 5.6 would) */
    render_node(c, t, &f2, level + 1, st);
}

static void render_node(rctx *c, xmlNodePtr n, const frame *f, size_t level,
                        const conica_svg__style *parent)
{
    conica_svg__style *st;
    conica_svg_matrix ctm = f->ctm;
    frame f2;
    char *tf;
    static const char *const unrendered[] = {
        "defs", "symbol", "clipPath", "mask", "marker", "pattern", "linearGradient",
        "radialGradient", "filter", "title", "desc", "metadata", "style", "script", "font",
        "font-face", "cursor", "view", "stop", "animate", "animateMotion", "animateTransform",
        "set", "mpath", "glyph", "missing-glyph", "color-profile", "hkern", "vkern", NULL};
    size_t k;
    if (c->rc != CONICA_OK || !conica_svg__is_svg(n))
        return; /* foreign elements are never rendered */
    for (k = 0; unrendered[k]; k++)
        if (is(n, unrendered[k]))
            return;
    if (!enter(c, n, level))
        return;
    st = c->lv[level];
    if (!compute_style(c, n, parent, st))
        return;
    if (st->display_none)
        return;
    if (is(n, "text") || is(n, "tspan") || is(n, "textPath")) {
        warn(c, n, W_TEXT, "text is not drawn (convert it to paths)");
        return;
    }
    if (is(n, "image")) {
        warn(c, n, W_IMAGE, "images are not drawn");
        return;
    }
    if (is(n, "foreignObject")) {
        warn(c, n, W_FOREIGN, "foreignObject content is not drawn");
        return;
    }
    f2 = *f;
    f2.selected = f->selected || selected_id(c, n);
    if ((tf = attr(n, "transform")) != NULL) {
        conica_svg_matrix m;
        if (!parse_transform(tf, &m)) {
            warn(c, n, W_TRANSFORM_BAD, "transform '%.60s' is not valid: ignored", tf);
        } else if (!mat_invertible(&m)) {
            warn(c, n, W_TRANSFORM_SINGULAR, "transform '%.60s' is not invertible: not drawn", tf);
            xmlFree(tf);
            return;
        } else {
            ctm = mat_mul(&f->ctm, &m);
        }
        xmlFree(tf);
    }
    if (st->css_transform)
        warn(c, n, W_CSS_TRANSFORM, "a CSS transform property is not applied");
    if (st->filter_missing) {
        warn(c, n, W_FILTER_MISSING, "filter references no filter element: not drawn");
        return;
    }
    if (st->filter)
        warn(c, n, W_FILTER, "filter is not applied: drawn unfiltered");
    if (st->clip_path)
        warn(c, n, W_CLIP, "clip-path is not applied: drawn unclipped");
    if (st->mask)
        warn(c, n, W_MASK, "mask is not applied: drawn unmasked");
    if (!(st->opacity > 0.0))
        f2.hidden = 1;
    if (is(n, "g") || is(n, "a")) {
        f2.ctm = ctm;
        render_children(c, n, &f2, level, st);
    } else if (is(n, "switch")) {
        f2.ctm = ctm;
        render_switch(c, n, &f2, level, st);
    } else if (is(n, "svg")) {
        double x = 0, y = 0, w = f->vw, h = f->vh;
        len_attr(n, "x", f->vw, st->font_size, &x);
        len_attr(n, "y", f->vh, st->font_size, &y);
        len_attr(n, "width", f->vw, st->font_size, &w);
        len_attr(n, "height", f->vh, st->font_size, &h);
        render_viewport(c, n, &f2, &ctm, x, y, w, h, 1, level, st);
    } else if (is(n, "use")) {
        render_use(c, n, &f2, &ctm, level, st);
    } else if (is(n, "path") || is(n, "rect") || is(n, "circle") || is(n, "ellipse") ||
               is(n, "line") || is(n, "polyline") || is(n, "polygon")) {
        draw_shape(c, n, &f2, &ctm, st);
    }
    /* any other SVG element is not rendered (librsvg) */
}

/* ------------------------------------------------------------ root */

conica_svg_render_settings conica_svg_render_defaults(void)
{
    conica_svg_render_settings s;
    memset(&s, 0, sizeof s);
    s.unit = "px";
    s.max_use_depth = CONICA_SVG_DEFAULT_MAX_USE_DEPTH;
    s.max_instances = CONICA_SVG_DEFAULT_MAX_INSTANCES;
    s.max_segments = CONICA_SVG_DEFAULT_MAX_POINTS;
    return s;
}

/* The root's width or height: 1 an absolute length (*v in the output
 * unit, *px in px), 0 absent, relative or invalid. */
static int root_len(xmlNodePtr root, const char *name, const char *unit, double *v, double *px)
{
    char *a = attr(root, name);
    double num;
    size_t used, n;
    char u[4] = {0, 0, 0, 0};
    int ok = 0;
    if (!a)
        return 0;
    n = strlen(a);
    used = conica_svg__read_number(a, n, &num);
    if (used) {
        size_t i = used, k = 0;
        while (i < n && k < 3 && ((a[i] >= 'a' && a[i] <= 'z') || (a[i] >= 'A' && a[i] <= 'Z')))
            u[k++] = a[i++];
        while (i < n && blank(a[i]))
            i++;
        if (i == n && !(k == 2 && (!strcmp(u, "em") || !strcmp(u, "ex")))) {
            /* the number converted once, exactly where the units agree */
            *v = conica_svg_convert_length(num, u, unit);
            *px = conica_svg_convert_length(num, u, "px");
            ok = isfinite(*v) && *v > 0.0;
        } else if (i == n) {
            *px = num * CONICA_SVG__DEFAULT_FONT_SIZE * (u[1] == 'x' ? 0.5 : 1.0);
            *v = conica_svg_convert_length(*px, "px", unit);
            ok = isfinite(*v) && *v > 0.0;
        }
    }
    xmlFree(a);
    return ok;
}

void conica_svg_scene_init(conica_svg_scene *s)
{
    if (s) {
        memset(s, 0, sizeof *s);
        strcpy(s->unit, "px");
    }
}

void conica_svg_scene_free(conica_svg_scene *s)
{
    size_t i;
    if (!s)
        return;
    for (i = 0; i < s->n; i++) {
        conica_svg_path_free(&s->items[i].path);
        free(s->items[i].clip);
    }
    free(s->items);
    conica_svg_scene_init(s);
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

conica_code conica_svg_render(const conica_svg_doc *doc, const conica_svg_render_settings *s,
                              conica_svg_scene *out, conica_status *st)
{
    conica_svg_render_settings def = conica_svg_render_defaults();
    conica_svg_scene sc;
    xmlNodePtr root;
    rctx c;
    frame f;
    conica_svg__style initial;
    double W = 0, H = 0, Wpx = 0, Hpx = 0, vb[4] = {0, 0, 0, 0}, *owned = NULL;
    int hw, hh, hvb;
    size_t i;
    if (!doc || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_render: NULL argument");
    if (!s)
        s = &def;
    if (!s->unit || !isfinite(conica_svg_convert_length(1.0, s->unit, "px")))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_render: unknown unit '%.20s'",
                            s->unit ? s->unit : "(null)");
    root = xmlDocGetRootElement(conica_svg__doc_xml(doc));
    conica_svg_scene_init(&sc);
    snprintf(sc.unit, sizeof sc.unit, "%s", s->unit[0] ? s->unit : "px");
    memset(&c, 0, sizeof c);
    c.s = s;
    c.out = &sc;
    c.st = st;
    c.rc = CONICA_OK;
    c.css_budget = CONICA_SVG_MAX_CSS_MATCH_STEPS;
    if (conica_svg__ids_build(root, &c.ids) != 0)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    c.rc = conica_svg__sheet_read(root, s->warn, s->warn_ctx, &c.sheet, st);
    if (c.rc == CONICA_OK && s->select && s->nselect) {
        c.select = malloc(s->nselect * sizeof *c.select);
        if (!c.select)
            c.rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        for (i = 0; c.select && i < s->nselect; i++)
            if (s->select[i])
                c.select[c.nselect++] = s->select[i];
        if (c.select)
            qsort(c.select, c.nselect, sizeof *c.select, cmp_str);
    }
    /* the root viewport (SVG 2, 8.2; librsvg's intrinsic size): absolute
     * width/height, the other from the viewBox's aspect ratio, or the
     * viewBox's size in px */
    hw = root_len(root, "width", sc.unit, &W, &Wpx);
    hh = root_len(root, "height", sc.unit, &H, &Hpx);
    hvb = root && conica_svg__is_svg(root) && is(root, "svg") ? parse_viewbox(root, vb) : 0;
    memset(&f, 0, sizeof f);
    f.selected = !c.nselect;
    if (hvb == 1) {
        if (!hw && !hh) {
            Wpx = vb[2];
            Hpx = vb[3];
            W = conica_svg_convert_length(Wpx, "px", sc.unit);
            H = conica_svg_convert_length(Hpx, "px", sc.unit);
        } else if (!hw) {
            Wpx = Hpx * vb[2] / vb[3];
            W = H * vb[2] / vb[3];
        } else if (!hh) {
            Hpx = Wpx * vb[3] / vb[2];
            H = W * vb[3] / vb[2];
        }
        sc.has_size = 1;
        f.ctm = viewbox_matrix(root, vb, 0, 0, W, H);
        f.vw = vb[2];
        f.vh = vb[3];
    } else {
        double k = conica_svg_convert_length(1.0, "px", sc.unit);
        sc.has_size = hw && hh;
        f.ctm = mat_make(k, 0, 0, k, 0, 0);
        /* without a size, percentages are of 100 px (documented) */
        f.vw = hw ? Wpx : 100.0;
        f.vh = hh ? Hpx : 100.0;
    }
    if (sc.has_size) {
        sc.width = W;
        sc.height = H;
        if (!(W > 0.0 && H > 0.0 && isfinite(W) && isfinite(H)))
            sc.has_size = 0, sc.width = sc.height = 0;
    }
    if (hvb < 0 && s->warn)
        s->warn(s->warn_ctx, root ? (size_t)xmlGetLineNo(root) : 0,
                "svg: viewBox with a zero or negative size: nothing is drawn");
    if (c.rc == CONICA_OK && sc.has_size && hvb >= 0) {
        /* what is painted outside the root viewport is off the canvas */
        conica_svg_matrix id = mat_make(1, 0, 0, 1, 0, 0);
        if (push_clip(&f, &id, 0, 0, sc.width, sc.height, &f, &owned) < 0)
            c.rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    conica_svg__style_initial(&initial);
    if (c.rc == CONICA_OK && root && hvb >= 0) {
        /* the root: its own style and transform, then its children in the
         * frame set up above */
        c.lv = malloc(2 * sizeof *c.lv);
        if (c.lv && (c.lv[0] = malloc(sizeof **c.lv)) != NULL)
            c.nlv = 1;
        if (c.nlv && (c.lv[1] = malloc(sizeof **c.lv)) != NULL)
            c.nlv = 2;
        if (c.nlv < 2) {
            c.rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        } else if (!conica_svg__is_svg(root) || !is(root, "svg")) {
            /* not an SVG document: nothing is painted */
        } else if (!compute_style(&c, root, &initial, c.lv[0])) {
            /* c.rc says why */
        } else if (!c.lv[0]->display_none) {
            char *tf = attr(root, "transform");
            conica_svg_matrix m;
            int draw = 1;
            c.instances = 1;
            if (tf && parse_transform(tf, &m)) {
                if (!mat_invertible(&m))
                    draw = 0, warn(&c, root, W_TRANSFORM_SINGULAR,
                                   "transform is not invertible: not drawn");
                else
                    f.ctm = mat_mul(&f.ctm, &m);
            } else if (tf) {
                warn(&c, root, W_TRANSFORM_BAD, "transform '%.60s' is not valid: ignored", tf);
            }
            xmlFree(tf);
            f.selected = f.selected || selected_id(&c, root);
            if (!(c.lv[0]->opacity > 0.0))
                f.hidden = 1;
            if (c.lv[0]->filter_missing)
                draw = 0, warn(&c, root, W_FILTER_MISSING,
                               "filter references no filter element: not drawn");
            if (draw)
                render_children(&c, root, &f, 0, c.lv[0]);
        }
    }
    for (i = 0; i < c.nlv; i++)
        free(c.lv[i]);
    free(c.lv);
    free(owned);
    if (c.rc == CONICA_OK && s->warn)
        for (i = 0; i < s->nselect; i++)
            if (s->select[i] && !conica_svg__ids_find(&c.ids, s->select[i], strlen(s->select[i]))) {
                char msg[300];
                snprintf(msg, sizeof msg, "select: no element has id '%.200s'", s->select[i]);
                s->warn(s->warn_ctx, 0, msg);
            }
    free(c.warned);
    free(c.select);
    conica_svg__sheet_free(c.sheet);
    conica_svg__ids_free(&c.ids);
    if (c.rc != CONICA_OK) {
        conica_svg_scene_free(&sc);
        return c.rc;
    }
    conica_svg_scene_free(out);
    *out = sc;
    conica__ok(st);
    return CONICA_OK;
}
