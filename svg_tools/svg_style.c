/* SPDX-License-Identifier: MIT */
/* The CSS side of the render: `<style>` sheets (a small tokenizer and
 * selector matcher), the cascade of presentation attributes, sheet rules
 * and the style attribute (CSS Cascade 4: !important, specificity, source
 * order; SVG 2, 6.8: presentation attributes first, at specificity 0),
 * property values (CSS Color 4 colours, paints, lengths) and inheritance.
 * Only the properties that decide what is painted where are kept
 * (svg_render_internal.h lists them). Why not a library: Debian 12 has no
 * maintained C CSS parser with selector matching and no global state
 * (libcroco was removed; NetSurf's libcss is not packaged as a library);
 * docs/svg-rendering.md says more. Calls the id index and libxml2 only. */
#include "svg_render_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "numparse.h"

/* Compound selectors in one selector, simple selectors in one compound,
 * and steps of one match (the backtracking over ancestors and siblings of
 * `a b > c ~ d` is bounded by this; a match that needs more fails). */
#define CSS_MAX_COMPOUNDS 32
#define CSS_MAX_SIMPLES 32
#define CSS_MAX_MATCH_STEPS 4096
/* Declarations of one style attribute kept on the stack before the heap. */
#define CSS_LOCAL_DECLS 64
/* href hops followed from a gradient to the one that holds its stops. */
#define PAINT_MAX_HREF 16

/* ------------------------------------------------------------ properties */

enum {
    P_FILL = 0, P_STROKE, P_FILL_OPACITY, P_STROKE_OPACITY, P_OPACITY, P_DISPLAY,
    P_VISIBILITY, P_FILL_RULE, P_STROKE_WIDTH, P_LINEJOIN, P_LINECAP, P_MITERLIMIT,
    P_DASHARRAY, P_DASHOFFSET, P_VECTOR_EFFECT, P_COLOR, P_FONT_SIZE, P_OVERFLOW,
    P_CLIP_PATH, P_MASK, P_FILTER, P_MARKER_START, P_MARKER_MID, P_MARKER_END,
    P_PRESENTATION, /* the properties above are also presentation attributes */
    P_MARKER = P_PRESENTATION, P_TRANSFORM, P_COUNT
};

static const char *const prop_names[P_COUNT] = {
    "fill", "stroke", "fill-opacity", "stroke-opacity", "opacity", "display",
    "visibility", "fill-rule", "stroke-width", "stroke-linejoin", "stroke-linecap",
    "stroke-miterlimit", "stroke-dasharray", "stroke-dashoffset", "vector-effect", "color",
    "font-size", "overflow", "clip-path", "mask", "filter", "marker-start", "marker-mid",
    "marker-end", "marker", "transform"};

static char lower(char c)
{
    return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c;
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
}

/* s[0..n) equals the lower-case word w, ignoring ASCII case. */
static int ieq(const char *s, size_t n, const char *w)
{
    size_t i;
    for (i = 0; i < n && w[i]; i++)
        if (lower(s[i]) != w[i])
            return 0;
    return i == n && !w[i];
}

static void trim(const char **s, size_t *n)
{
    while (*n && is_blank(**s))
        ++*s, --*n;
    while (*n && is_blank((*s)[*n - 1]))
        --*n;
}

static int prop_find(const char *s, size_t n)
{
    int p;
    for (p = 0; p < P_COUNT; p++)
        if (ieq(s, n, prop_names[p]))
            return p;
    return -1;
}

/* ------------------------------------------------------------ numbers, lengths */

size_t conica_svg__read_number(const char *s, size_t n, double *v)
{
    size_t i = 0, used = 0;
    while (i < n && is_blank(s[i]))
        i++;
    if (conica__parse_double(s + i, n - i, v, &used) != CONICA__NUM_OK)
        return 0;
    return i + used;
}

int conica_svg__parse_len(const char *s, size_t n, double font_size, conica_svg__len *out)
{
    double v;
    size_t k = conica_svg__read_number(s, n, &v), u;
    const char *unit;
    conica_svg__len r;
    if (!k)
        return 0;
    unit = s + k;
    n -= k;
    for (u = 0; u < n && !is_blank(unit[u]); u++)
        ;
    for (k = u; k < n; k++)
        if (!is_blank(unit[k]))
            return 0;
    r.percent = 0;
    if (u == 1 && unit[0] == '%') {
        r.percent = 1;
        r.v = v;
    } else if (u == 2 && ieq(unit, 2, "em")) {
        r.v = v * font_size;
    } else if (u == 2 && ieq(unit, 2, "ex")) {
        r.v = 0.5 * v * font_size;
    } else {
        char name[4] = {0, 0, 0, 0};
        size_t i;
        if (u > 2)
            return 0;
        for (i = 0; i < u; i++)
            name[i] = unit[i] == 'q' ? 'Q' : lower(unit[i]);
        r.v = conica_svg_convert_length(v, name, "px");
    }
    if (!isfinite(r.v))
        return 0;
    *out = r;
    return 1;
}

/* ------------------------------------------------------------ colours */

/* CSS Color 4, 6.1: the named colours, sorted. */
static const char *const named_colors[] = {
    "aliceblue", "antiquewhite", "aqua", "aquamarine", "azure", "beige", "bisque", "black",
    "blanchedalmond", "blue", "blueviolet", "brown", "burlywood", "cadetblue", "chartreuse",
    "chocolate", "coral", "cornflowerblue", "cornsilk", "crimson", "cyan", "darkblue",
    "darkcyan", "darkgoldenrod", "darkgray", "darkgreen", "darkgrey", "darkkhaki",
    "darkmagenta", "darkolivegreen", "darkorange", "darkorchid", "darkred", "darksalmon",
    "darkseagreen", "darkslateblue", "darkslategray", "darkslategrey", "darkturquoise",
    "darkviolet", "deeppink", "deepskyblue", "dimgray", "dimgrey", "dodgerblue", "firebrick",
    "floralwhite", "forestgreen", "fuchsia", "gainsboro", "ghostwhite", "gold", "goldenrod",
    "gray", "green", "greenyellow", "grey", "honeydew", "hotpink", "indianred", "indigo",
    "ivory", "khaki", "lavender", "lavenderblush", "lawngreen", "lemonchiffon", "lightblue",
    "lightcoral", "lightcyan", "lightgoldenrodyellow", "lightgray", "lightgreen", "lightgrey",
    "lightpink", "lightsalmon", "lightseagreen", "lightskyblue", "lightslategray",
    "lightslategrey", "lightsteelblue", "lightyellow", "lime", "limegreen", "linen", "magenta",
    "maroon", "mediumaquamarine", "mediumblue", "mediumorchid", "mediumpurple",
    "mediumseagreen", "mediumslateblue", "mediumspringgreen", "mediumturquoise",
    "mediumvioletred", "midnightblue", "mintcream", "mistyrose", "moccasin", "navajowhite",
    "navy", "oldlace", "olive", "olivedrab", "orange", "orangered", "orchid", "palegoldenrod",
    "palegreen", "paleturquoise", "palevioletred", "papayawhip", "peachpuff", "peru", "pink",
    "plum", "powderblue", "purple", "rebeccapurple", "red", "rosybrown", "royalblue",
    "saddlebrown", "salmon", "sandybrown", "seagreen", "seashell", "sienna", "silver",
    "skyblue", "slateblue", "slategray", "slategrey", "snow", "springgreen", "steelblue", "tan",
    "teal", "thistle", "tomato", "turquoise", "violet", "wheat", "white", "whitesmoke",
    "yellow", "yellowgreen"};

static int is_named_color(const char *s, size_t n)
{
    size_t lo = 0, hi = sizeof named_colors / sizeof named_colors[0];
    char w[24];
    size_t i;
    if (n == 0 || n >= sizeof w)
        return 0;
    for (i = 0; i < n; i++)
        w[i] = lower(s[i]);
    w[n] = '\0';
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(w, named_colors[mid]);
        if (!c)
            return 1;
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    return 0;
}

static int hexval(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                        : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* A colour: 1 valid (*visible: alpha > 0), 2 currentColor, 0 invalid.
 * A trailing SVG 1.1 icc-color(...) is allowed. */
static int parse_color(const char *s, size_t n, int *visible)
{
    size_t i;
    trim(&s, &n);
    if (n > 10 && !memcmp(s + n - 1, ")", 1)) {
        /* "#fff icc-color(...)": drop the icc part */
        for (i = 0; i + 10 <= n; i++)
            if (ieq(s + i, 10, "icc-color(") && i > 0 && is_blank(s[i - 1])) {
                n = i;
                trim(&s, &n);
                break;
            }
    }
    if (!n)
        return 0;
    if (ieq(s, n, "currentcolor"))
        return 2;
    if (ieq(s, n, "transparent")) {
        *visible = 0;
        return 1;
    }
    if (s[0] == '#') {
        for (i = 1; i < n; i++)
            if (hexval(s[i]) < 0)
                return 0;
        if (n == 4 || n == 7) {
            *visible = 1;
            return 1;
        }
        if (n == 5) {
            *visible = hexval(s[4]) != 0;
            return 1;
        }
        if (n == 9) {
            *visible = hexval(s[7]) != 0 || hexval(s[8]) != 0;
            return 1;
        }
        return 0;
    }
    for (i = 0; i < n && s[i] != '('; i++)
        ;
    if (i < n) {
        /* rgb()/rgba()/hsl()/hsla(): 3 components and an optional alpha */
        double v[4] = {0, 0, 0, 1};
        size_t k = 0, j = i + 1;
        if (!(ieq(s, i, "rgb") || ieq(s, i, "rgba") || ieq(s, i, "hsl") || ieq(s, i, "hsla")) ||
            s[n - 1] != ')')
            return 0;
        while (j < n - 1 && k < 4) {
            size_t used = conica_svg__read_number(s + j, n - 1 - j, &v[k]);
            if (!used)
                return 0;
            j += used;
            if (j < n - 1 && s[j] == '%') {
                if (k == 3)
                    v[k] /= 100.0;
                j++;
            } else if (j + 3 <= n - 1 && ieq(s + j, 3, "deg")) {
                j += 3;
            }
            k++;
            while (j < n - 1 && (is_blank(s[j]) || s[j] == ',' || s[j] == '/'))
                j++;
        }
        if (j != n - 1 || k < 3)
            return 0;
        *visible = v[3] > 0.0;
        return 1;
    }
    if (is_named_color(s, n)) {
        *visible = 1;
        return 1;
    }
    return 0;
}

/* ------------------------------------------------------------ ids */

typedef struct id_pair {
    char *id;
    xmlNodePtr node;
    size_t order;
} id_pair;

static int cmp_pair(const void *a, const void *b)
{
    const id_pair *x = a, *y = b;
    int c = strcmp(x->id, y->id);
    return c ? c : x->order < y->order ? -1 : x->order > y->order;
}

int conica_svg__ids_build(xmlNodePtr root, conica_svg__ids *ids)
{
    id_pair *pairs = NULL;
    size_t n = 0, cap = 0, i, k;
    xmlNodePtr e = root;
    memset(ids, 0, sizeof *ids);
    /* document order without recursion */
    while (e) {
        char *id = conica_svg__attr(e, "id", CONICA_SVG__MAX_ATTR, NULL);
        if (id) {
            if (n == cap) {
                size_t nc = cap ? 2 * cap : 64;
                id_pair *t = realloc(pairs, nc * sizeof *t);
                if (!t) {
                    xmlFree(id);
                    goto oom;
                }
                pairs = t;
                cap = nc;
            }
            pairs[n].id = id;
            pairs[n].node = e;
            pairs[n].order = n;
            n++;
        }
        e = conica_svg__next_element(e, root);
    }
    if (n)
        qsort(pairs, n, sizeof *pairs, cmp_pair);
    ids->id = malloc((n ? n : 1) * sizeof *ids->id);
    ids->node = malloc((n ? n : 1) * sizeof *ids->node);
    if (!ids->id || !ids->node)
        goto oom;
    /* the first element with an id wins, as in librsvg */
    for (i = 0, k = 0; i < n; i++) {
        if (k && !strcmp(ids->id[k - 1], pairs[i].id)) {
            xmlFree(pairs[i].id);
            continue;
        }
        ids->id[k] = pairs[i].id;
        ids->node[k++] = pairs[i].node;
    }
    ids->n = k;
    free(pairs);
    return 0;
oom:
    for (i = 0; i < n; i++)
        xmlFree(pairs[i].id);
    free(pairs);
    free(ids->id);
    free(ids->node);
    memset(ids, 0, sizeof *ids);
    return -1;
}

void conica_svg__ids_free(conica_svg__ids *ids)
{
    size_t i;
    if (!ids)
        return;
    for (i = 0; i < ids->n; i++)
        xmlFree(ids->id[i]);
    free(ids->id);
    free(ids->node);
    memset(ids, 0, sizeof *ids);
}

xmlNodePtr conica_svg__ids_find(const conica_svg__ids *ids, const char *id, size_t len)
{
    size_t lo = 0, hi = ids->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        const char *m = ids->id[mid];
        int c = strncmp(id, m, len);
        if (!c && m[len] != '\0')
            c = -1;
        if (!c)
            return ids->node[mid];
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    return NULL;
}

/* ------------------------------------------------------------ paints */

/* url(#id) at s: the id (*id, *idlen) and the rest after ')' (*rest); 0 not
 * a url. A url to another document has *idlen == 0. */
static int parse_url(const char *s, size_t n, const char **id, size_t *idlen, const char **rest,
                     size_t *restn)
{
    size_t i = 4, j;
    char q = 0;
    if (n < 5 || !ieq(s, 4, "url("))
        return 0;
    while (i < n && is_blank(s[i]))
        i++;
    if (i < n && (s[i] == '"' || s[i] == '\''))
        q = s[i++];
    for (j = i; j < n && (q ? s[j] != q : s[j] != ')' && !is_blank(s[j])); j++)
        ;
    if (j >= n)
        return 0;
    *id = s + i;
    *idlen = j - i;
    if (*idlen && **id == '#') {
        ++*id;
        --*idlen;
    } else {
        *idlen = 0;
    }
    if (q)
        j++;
    while (j < n && is_blank(s[j]))
        j++;
    if (j >= n || s[j] != ')')
        return 0;
    *rest = s + j + 1;
    *restn = n - j - 1;
    return 1;
}

static int is_tag(xmlNodePtr n, const char *tag)
{
    return n && conica_svg__is_svg(n) && !strcmp((const char *)n->name, tag);
}

/* A gradient with stops, following href to the gradient it takes them from
 * (SVG 2, 14.2.3); a gradient without stops paints nothing (14.2.4). */
static int gradient_has_stops(xmlNodePtr g, const conica_svg__ids *ids)
{
    int hop;
    for (hop = 0; g && hop < PAINT_MAX_HREF; hop++) {
        xmlNodePtr c;
        char *href;
        for (c = g->children; c; c = c->next)
            if (is_tag(c, "stop"))
                return 1;
        href = conica_svg__attr(g, "href", CONICA_SVG__MAX_ATTR, NULL);
        if (!href) {
            xmlChar *x = xmlGetNsProp(g, BAD_CAST "href", BAD_CAST "http://www.w3.org/1999/xlink");
            href = (char *)x;
        }
        if (!href)
            return 0;
        g = href[0] == '#' ? conica_svg__ids_find(ids, href + 1, strlen(href + 1)) : NULL;
        xmlFree(href);
        if (g && !is_tag(g, "linearGradient") && !is_tag(g, "radialGradient"))
            g = NULL;
    }
    return 0;
}

/* fill/stroke: none, a colour, currentColor, url(#id) [fallback]. 1 valid. */
static int parse_paint(const char *s, size_t n, const conica_svg__ids *ids, int *paint)
{
    const char *id, *rest;
    size_t idlen, restn;
    int vis = 0, r;
    trim(&s, &n);
    if (ieq(s, n, "none")) {
        *paint = CONICA_SVG__PAINT_NONE;
        return 1;
    }
    if (ieq(s, n, "context-fill") || ieq(s, n, "context-stroke")) {
        *paint = CONICA_SVG__PAINT_NONE; /* only inside markers, which are not drawn */
        return 1;
    }
    if (parse_url(s, n, &id, &idlen, &rest, &restn)) {
        xmlNodePtr t = idlen ? conica_svg__ids_find(ids, id, idlen) : NULL;
        trim(&rest, &restn);
        if (t && (is_tag(t, "linearGradient") || is_tag(t, "radialGradient"))) {
            *paint = gradient_has_stops(t, ids) ? CONICA_SVG__PAINT_COLOR : CONICA_SVG__PAINT_NONE;
            return 1;
        }
        if (t && is_tag(t, "pattern")) {
            *paint = CONICA_SVG__PAINT_COLOR;
            return 1;
        }
        /* no such paint server: the fallback, or none (librsvg 2.54) */
        if (!restn || ieq(rest, restn, "none")) {
            *paint = CONICA_SVG__PAINT_NONE;
            return 1;
        }
        s = rest;
        n = restn;
    }
    r = parse_color(s, n, &vis);
    if (r == 2)
        *paint = CONICA_SVG__PAINT_CURRENT;
    else if (r == 1)
        *paint = vis ? CONICA_SVG__PAINT_COLOR : CONICA_SVG__PAINT_NONE;
    return r != 0;
}

/* opacity values: a number or a percentage, clamped to [0, 1]. */
static int parse_opacity(const char *s, size_t n, double *out)
{
    double v;
    size_t k = conica_svg__read_number(s, n, &v);
    if (!k)
        return 0;
    s += k;
    n -= k;
    if (n && *s == '%') {
        v /= 100.0;
        s++;
        n--;
    }
    trim(&s, &n);
    if (n)
        return 0;
    *out = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    return 1;
}

/* stroke-dasharray: none or a list of non-negative lengths. */
static int parse_dasharray(const char *s, size_t n, double font_size, conica_svg__style *o)
{
    conica_svg__len d[CONICA_SVG_MAX_DASHES];
    size_t k = 0, i = 0;
    int too_long = 0;
    trim(&s, &n);
    if (ieq(s, n, "none")) {
        o->ndash = 0;
        o->dash_too_long = 0;
        return 1;
    }
    while (i < n) {
        size_t j = i;
        conica_svg__len l;
        while (j < n && !is_blank(s[j]) && s[j] != ',')
            j++;
        if (!conica_svg__parse_len(s + i, j - i, font_size, &l) || l.v < 0.0)
            return 0;
        if (k < CONICA_SVG_MAX_DASHES)
            d[k++] = l;
        else
            too_long = 1;
        while (j < n && is_blank(s[j]))
            j++;
        if (j < n && s[j] == ',')
            j++;
        while (j < n && is_blank(s[j]))
            j++;
        i = j;
    }
    if (!k)
        return 0;
    if (k % 2) {
        /* an odd list is repeated (SVG 1.1, 11.4) */
        if (2 * k > CONICA_SVG_MAX_DASHES)
            too_long = 1;
        else
            for (i = 0; i < k; i++)
                d[k + i] = d[i];
        k *= 2;
    }
    o->dash_too_long = too_long;
    o->ndash = too_long ? 0 : k;
    if (!too_long)
        memcpy(o->dash, d, k * sizeof d[0]);
    return 1;
}

/* font-size: a length (em and % of the parent's size) or a keyword. */
static int parse_font_size(const char *s, size_t n, double parent, double *out)
{
    static const struct { const char *name; double px; } kw[] = {
        {"xx-small", 9}, {"x-small", 10}, {"small", 13}, {"medium", 16},
        {"large", 18},   {"x-large", 24}, {"xx-large", 32}};
    conica_svg__len l;
    size_t i;
    trim(&s, &n);
    for (i = 0; i < sizeof kw / sizeof kw[0]; i++)
        if (ieq(s, n, kw[i].name)) {
            *out = kw[i].px;
            return 1;
        }
    if (ieq(s, n, "larger") || ieq(s, n, "smaller")) {
        *out = s[0] == 'l' || s[0] == 'L' ? parent * 1.2 : parent / 1.2;
        return 1;
    }
    if (!conica_svg__parse_len(s, n, parent, &l) || l.v < 0.0)
        return 0;
    *out = l.percent ? parent * l.v / 100.0 : l.v;
    return 1;
}

/* The index of s[0..n) in the NULL-terminated list of lower-case words
 * into *out; 0 when it is none of them. */
static int keyword(const char *s, size_t n, const char *const *words, int *out)
{
    int i;
    for (i = 0; words[i]; i++)
        if (ieq(s, n, words[i])) {
            *out = i;
            return 1;
        }
    return 0;
}

/* One declaration into *o (parent for inherit, the initial style for
 * initial); 1 when the value is valid and was applied. */
static int apply(int p, const char *s, size_t n, const conica_svg__style *parent,
                 const conica_svg__ids *ids, conica_svg__style *o)
{
    conica_svg__len l;
    double v;
    int k;
    trim(&s, &n);
    if (!n)
        return 0;
    /* CSS-wide keywords: inherit only; librsvg 2.54 reads initial and
     * unset as invalid values (the declaration is dropped) */
    if (ieq(s, n, "initial") || ieq(s, n, "unset"))
        return 0;
    if (ieq(s, n, "inherit")) {
        const conica_svg__style *from = parent;
        switch (p) {
        case P_FILL: o->fill = from->fill; break;
        case P_STROKE: o->stroke = from->stroke; break;
        case P_FILL_OPACITY: o->fill_opacity = from->fill_opacity; break;
        case P_STROKE_OPACITY: o->stroke_opacity = from->stroke_opacity; break;
        case P_OPACITY: o->opacity = from->opacity; break;
        case P_DISPLAY: o->display_none = from->display_none; break;
        case P_VISIBILITY: o->visible = from->visible; break;
        case P_FILL_RULE: o->fill_rule = from->fill_rule; break;
        case P_STROKE_WIDTH: o->stroke_width = from->stroke_width; break;
        case P_LINEJOIN: o->join = from->join; o->join_unsupported = from->join_unsupported; break;
        case P_LINECAP: o->cap = from->cap; break;
        case P_MITERLIMIT: o->miterlimit = from->miterlimit; break;
        case P_DASHARRAY:
            o->ndash = from->ndash;
            o->dash_too_long = from->dash_too_long;
            memcpy(o->dash, from->dash, sizeof o->dash);
            break;
        case P_DASHOFFSET: o->dashoffset = from->dashoffset; break;
        case P_VECTOR_EFFECT: o->non_scaling = from->non_scaling; break;
        case P_COLOR: o->color_visible = from->color_visible; break;
        case P_FONT_SIZE: o->font_size = from->font_size; break;
        case P_OVERFLOW: o->overflow_visible = from->overflow_visible; break;
        case P_CLIP_PATH: o->clip_path = from->clip_path; break;
        case P_MASK: o->mask = from->mask; break;
        case P_FILTER: o->filter = from->filter; o->filter_missing = from->filter_missing; break;
        case P_MARKER_START: case P_MARKER_MID: case P_MARKER_END: {
            int bit = 1 << (p - P_MARKER_START);
            o->markers = (o->markers & ~bit) | (from->markers & bit);
            break;
        }
        case P_MARKER: o->markers = from->markers; break;
        default: break;
        }
        return 1;
    }
    switch (p) {
    case P_FILL:
        return parse_paint(s, n, ids, &o->fill);
    case P_STROKE:
        return parse_paint(s, n, ids, &o->stroke);
    case P_FILL_OPACITY:
        return parse_opacity(s, n, &o->fill_opacity);
    case P_STROKE_OPACITY:
        return parse_opacity(s, n, &o->stroke_opacity);
    case P_OPACITY:
        return parse_opacity(s, n, &o->opacity);
    case P_DISPLAY:
        for (k = 0; (size_t)k < n; k++)
            if (!((s[k] >= 'a' && s[k] <= 'z') || (s[k] >= 'A' && s[k] <= 'Z') || s[k] == '-'))
                return 0;
        o->display_none = ieq(s, n, "none");
        return 1;
    case P_VISIBILITY: {
        static const char *const w[] = {"hidden", "visible", "collapse", NULL};
        if (!keyword(s, n, w, &k))
            return 0;
        o->visible = k == 1;
        return 1;
    }
    case P_FILL_RULE: {
        /* conica_svg_fill_rule order */
        static const char *const w[] = {"nonzero", "evenodd", NULL};
        return keyword(s, n, w, &o->fill_rule);
    }
    case P_STROKE_WIDTH:
        if (!conica_svg__parse_len(s, n, o->font_size, &l) || l.v < 0.0)
            return 0;
        o->stroke_width = l;
        return 1;
    case P_LINEJOIN: {
        /* conica_svg_linejoin order, then SVG 2's joins librsvg draws as miter */
        static const char *const w[] = {"miter", "round", "bevel", "miter-clip", "arcs", NULL};
        if (!keyword(s, n, w, &k))
            return 0;
        o->join_unsupported = k > CONICA_SVG_JOIN_BEVEL;
        o->join = o->join_unsupported ? CONICA_SVG_JOIN_MITER : k;
        return 1;
    }
    case P_LINECAP: {
        static const char *const w[] = {"butt", "round", "square", NULL}; /* conica_svg_linecap */
        return keyword(s, n, w, &o->cap);
    }
    case P_MITERLIMIT:
        if (conica_svg__read_number(s, n, &v) != n || !(v >= 1.0))
            return 0;
        o->miterlimit = v;
        return 1;
    case P_DASHARRAY:
        return parse_dasharray(s, n, o->font_size, o);
    case P_DASHOFFSET:
        if (!conica_svg__parse_len(s, n, o->font_size, &l))
            return 0;
        o->dashoffset = l;
        return 1;
    case P_VECTOR_EFFECT:
        if (ieq(s, n, "non-scaling-stroke"))
            o->non_scaling = 1;
        else if (ieq(s, n, "none") || ieq(s, n, "non-scaling-size") ||
                 ieq(s, n, "non-rotation") || ieq(s, n, "fixed-position"))
            o->non_scaling = 0;
        else
            return 0;
        return 1;
    case P_COLOR:
        k = parse_color(s, n, &o->color_visible);
        if (k == 2)
            o->color_visible = parent->color_visible; /* currentColor in color: inherit */
        return k != 0;
    case P_FONT_SIZE:
        return parse_font_size(s, n, parent->font_size, &o->font_size);
    case P_OVERFLOW:
        if (ieq(s, n, "visible") || ieq(s, n, "auto"))
            o->overflow_visible = 1;
        else if (ieq(s, n, "hidden") || ieq(s, n, "scroll") || ieq(s, n, "clip"))
            o->overflow_visible = 0;
        else
            return 0;
        return 1;
    case P_CLIP_PATH:
    case P_MASK:
        *(p == P_CLIP_PATH ? &o->clip_path : &o->mask) = !ieq(s, n, "none");
        return 1;
    case P_FILTER: {
        const char *id, *rest;
        size_t idlen, restn;
        o->filter_missing = 0;
        o->filter = !ieq(s, n, "none");
        if (parse_url(s, n, &id, &idlen, &rest, &restn)) {
            xmlNodePtr t = idlen ? conica_svg__ids_find(ids, id, idlen) : NULL;
            /* a reference to no filter element: the element is not
             * rendered (Filter Effects 1, 5.1; librsvg does so) */
            o->filter_missing = !is_tag(t, "filter");
        }
        return 1;
    }
    case P_MARKER_START:
    case P_MARKER_MID:
    case P_MARKER_END:
    case P_MARKER: {
        int bits = p == P_MARKER ? 7 : 1 << (p - P_MARKER_START);
        const char *id, *rest;
        size_t idlen, restn;
        if (ieq(s, n, "none")) {
            o->markers &= ~bits;
        } else if (parse_url(s, n, &id, &idlen, &rest, &restn)) {
            /* only a reference to a marker element draws one */
            xmlNodePtr t = idlen ? conica_svg__ids_find(ids, id, idlen) : NULL;
            if (is_tag(t, "marker"))
                o->markers |= bits;
            else
                o->markers &= ~bits;
        } else {
            return 0;
        }
        return 1;
    }
    case P_TRANSFORM:
        o->css_transform = !ieq(s, n, "none");
        return 1;
    default:
        return 0;
    }
}

void conica_svg__style_initial(conica_svg__style *s)
{
    memset(s, 0, sizeof *s);
    s->fill = CONICA_SVG__PAINT_COLOR; /* black */
    s->stroke = CONICA_SVG__PAINT_NONE;
    s->color_visible = 1;
    s->fill_opacity = s->stroke_opacity = s->opacity = 1.0;
    s->visible = 1;
    s->fill_rule = CONICA_SVG_NONZERO;
    s->stroke_width.v = 1.0;
    s->join = CONICA_SVG_JOIN_MITER;
    s->cap = CONICA_SVG_CAP_BUTT;
    s->miterlimit = 4.0;
    s->font_size = CONICA_SVG__DEFAULT_FONT_SIZE;
}

/* ------------------------------------------------------------ sheets */

typedef struct css_str {
    const char *s;
    size_t n;
} css_str;

enum { S_ID, S_CLASS, S_ATTR, S_FIRST_CHILD, S_LAST_CHILD, S_ROOT, S_NEVER };
enum { A_EXISTS, A_EQ, A_WORD, A_DASH, A_PREFIX, A_SUFFIX, A_SUBSTR };

typedef struct css_simple {
    int kind, op, icase;
    css_str name, value;
} css_simple;

typedef struct css_compound {
    css_str type;     /* n == 0: any element */
    size_t first, n;  /* its simple selectors */
    char comb;        /* combinator to the compound on its left: ' ', '>', '+', '~' (0: none) */
} css_compound;

typedef struct css_selector {
    size_t first, n;         /* its compounds, left to right */
    uint32_t spec;           /* specificity a.b.c, 8 bits each */
    size_t decl_first, ndecl;
} css_selector;

typedef struct css_decl {
    int prop;
    int important;
    css_str value;
} css_decl;

struct conica_svg__sheet {
    char *text;
    size_t len;
    css_simple *simples;
    size_t nsimples, capsimples;
    css_compound *comps;
    size_t ncomps, capcomps;
    css_selector *sels;
    size_t nsels, capsels;
    css_decl *decls;
    size_t ndecls, capdecls;
};

/* Grow *arr (element size sz) to hold one more; 0 when out of memory. */
static int grow(void **arr, size_t *cap, size_t n, size_t sz)
{
    if (n < *cap)
        return 1;
    {
        size_t nc = *cap ? 2 * *cap : 16;
        void *t = realloc(*arr, nc * sz);
        if (!t)
            return 0;
        *arr = t;
        *cap = nc;
    }
    return 1;
}

static int is_ident_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '-' || c == '_' || (unsigned char)c >= 0x80 || c == '\\';
}

/* An identifier at s[*i..n); 0 when there is none. */
static int read_ident(const char *s, size_t n, size_t *i, css_str *out)
{
    size_t j = *i;
    while (j < n && (is_ident_char(s[j]) || (s[j] == '|' && 0)))
        j += s[j] == '\\' && j + 1 < n ? 2 : 1;
    if (j == *i)
        return 0;
    out->s = s + *i;
    out->n = j - *i;
    *i = j;
    return 1;
}

/* Parse one selector s[0..n) into the sheet; 1 ok, 0 unsupported or
 * invalid, -1 no memory. */
static int parse_selector(conica_svg__sheet *sh, const char *s, size_t n, css_selector *sel)
{
    size_t i = 0, ncomp = 0;
    unsigned a = 0, b = 0, c = 0;
    char comb = 0;
    trim(&s, &n);
    if (!n)
        return 0;
    sel->first = sh->ncomps;
    while (i < n) {
        css_compound cp;
        int any = 0;
        memset(&cp, 0, sizeof cp);
        cp.first = sh->nsimples;
        cp.comb = ncomp ? comb : 0;
        if (s[i] == '*') {
            i++;
            any = 1;
        } else if (read_ident(s, n, &i, &cp.type)) {
            any = 1;
            c++;
        }
        while (i < n && (s[i] == '#' || s[i] == '.' || s[i] == '[' || s[i] == ':')) {
            css_simple sp;
            memset(&sp, 0, sizeof sp);
            if (cp.n >= CSS_MAX_SIMPLES)
                return 0;
            if (s[i] == '#' || s[i] == '.') {
                sp.kind = s[i] == '#' ? S_ID : S_CLASS;
                i++;
                if (!read_ident(s, n, &i, &sp.name))
                    return 0;
                if (sp.kind == S_ID)
                    a++;
                else
                    b++;
            } else if (s[i] == '[') {
                i++;
                while (i < n && is_blank(s[i]))
                    i++;
                if (!read_ident(s, n, &i, &sp.name))
                    return 0;
                while (i < n && is_blank(s[i]))
                    i++;
                sp.kind = S_ATTR;
                sp.op = A_EXISTS;
                if (i < n && s[i] != ']') {
                    static const char ops[] = "=~|^$*";
                    const char *o = i < n ? strchr(ops, s[i]) : NULL;
                    if (!o || !s[i])
                        return 0;
                    if (s[i] == '=') {
                        sp.op = A_EQ;
                        i++;
                    } else {
                        sp.op = A_WORD + (int)(o - ops) - 1;
                        if (i + 1 >= n || s[i + 1] != '=')
                            return 0;
                        i += 2;
                    }
                    while (i < n && is_blank(s[i]))
                        i++;
                    if (i < n && (s[i] == '"' || s[i] == '\'')) {
                        char q = s[i++];
                        size_t j = i;
                        while (j < n && s[j] != q)
                            j++;
                        if (j >= n)
                            return 0;
                        sp.value.s = s + i;
                        sp.value.n = j - i;
                        i = j + 1;
                    } else if (!read_ident(s, n, &i, &sp.value)) {
                        return 0;
                    }
                    while (i < n && is_blank(s[i]))
                        i++;
                    if (i < n && (s[i] == 'i' || s[i] == 'I')) {
                        sp.icase = 1;
                        i++;
                        while (i < n && is_blank(s[i]))
                            i++;
                    }
                }
                if (i >= n || s[i] != ']')
                    return 0;
                i++;
                b++;
            } else {
                css_str name;
                int elem = i + 1 < n && s[i + 1] == ':';
                i += elem ? 2 : 1;
                if (!read_ident(s, n, &i, &name))
                    return 0;
                if (i < n && s[i] == '(')
                    return 0; /* :not(), :nth-child(): not supported */
                sp.kind = elem ? S_NEVER
                          : ieq(name.s, name.n, "first-child") ? S_FIRST_CHILD
                          : ieq(name.s, name.n, "last-child") ? S_LAST_CHILD
                          : ieq(name.s, name.n, "root") ? S_ROOT
                          : S_NEVER; /* :hover, :link, ... never match a static picture */
                if (elem)
                    c++;
                else
                    b++;
            }
            if (!grow((void **)&sh->simples, &sh->capsimples, sh->nsimples, sizeof sp))
                return -1;
            sh->simples[sh->nsimples++] = sp;
            cp.n++;
            any = 1;
        }
        if (!any || ncomp >= CSS_MAX_COMPOUNDS)
            return 0;
        if (!grow((void **)&sh->comps, &sh->capcomps, sh->ncomps, sizeof cp))
            return -1;
        sh->comps[sh->ncomps++] = cp;
        ncomp++;
        /* combinator */
        comb = 0;
        while (i < n && is_blank(s[i])) {
            comb = ' ';
            i++;
        }
        if (i < n && (s[i] == '>' || s[i] == '+' || s[i] == '~')) {
            comb = s[i++];
            while (i < n && is_blank(s[i]))
                i++;
        }
        if (i < n && !comb)
            return 0;
        if (i >= n && comb && comb != ' ')
            return 0;
    }
    sel->n = ncomp;
    sel->spec = (a > 255 ? 255u : a) << 16 | (b > 255 ? 255u : b) << 8 | (c > 255 ? 255u : c);
    return 1;
}

/* Calls fn(ctx, prop, value, important) for each known declaration in
 * s[0..n); returns fn's first non-zero result, else 0. */
typedef int (*decl_fn)(void *ctx, int prop, const char *v, size_t vn, int important);

static int parse_decls(const char *s, size_t n, decl_fn fn, void *ctx)
{
    size_t i = 0;
    while (i < n) {
        size_t start = i, colon = (size_t)-1, end;
        int depth = 0;
        char q = 0;
        for (; i < n; i++) {
            char ch = s[i];
            if (q) {
                if (ch == q)
                    q = 0;
            } else if (ch == '"' || ch == '\'') {
                q = ch;
            } else if (ch == '(') {
                depth++;
            } else if (ch == ')') {
                depth -= depth > 0;
            } else if (ch == ':' && colon == (size_t)-1) {
                colon = i;
            } else if (ch == ';' && !depth) {
                break;
            }
        }
        end = i;
        if (i < n)
            i++;
        if (colon != (size_t)-1) {
            const char *name = s + start, *v = s + colon + 1;
            size_t nn = colon - start, vn = end - colon - 1;
            int p, imp = 0, r;
            trim(&name, &nn);
            trim(&v, &vn);
            /* !important at the end */
            if (vn >= 10) {
                size_t k = vn;
                while (k && is_ident_char(v[k - 1]))
                    k--;
                if (ieq(v + k, vn - k, "important")) {
                    size_t bang = k;
                    while (bang && is_blank(v[bang - 1]))
                        bang--;
                    if (bang && v[bang - 1] == '!') {
                        imp = 1;
                        vn = bang - 1;
                        trim(&v, &vn);
                    }
                }
            }
            p = prop_find(name, nn);
            if (p == P_MARKER) {
                int k;
                for (k = P_MARKER_START; k <= P_MARKER_END; k++)
                    if ((r = fn(ctx, k, v, vn, imp)) != 0)
                        return r;
            } else if (p >= 0 && (r = fn(ctx, p, v, vn, imp)) != 0) {
                return r;
            }
        }
    }
    return 0;
}

typedef struct sheet_decl_ctx {
    conica_svg__sheet *sh;
} sheet_decl_ctx;

static int sheet_decl(void *ctx, int prop, const char *v, size_t vn, int important)
{
    conica_svg__sheet *sh = ((sheet_decl_ctx *)ctx)->sh;
    css_decl d;
    if (sh->ndecls >= CONICA_SVG_MAX_CSS_DECLS)
        return 2;
    if (!grow((void **)&sh->decls, &sh->capdecls, sh->ndecls, sizeof d))
        return -1;
    d.prop = prop;
    d.important = important;
    d.value.s = v;
    d.value.n = vn;
    sh->decls[sh->ndecls++] = d;
    return 0;
}

/* The end of a block that opens at s[i] == '{' (nested braces and strings
 * skipped): the index of its '}', or n. */
static size_t block_end(const char *s, size_t n, size_t i)
{
    int depth = 0;
    char q = 0;
    for (; i < n; i++) {
        if (q) {
            if (s[i] == q)
                q = 0;
        } else if (s[i] == '"' || s[i] == '\'') {
            q = s[i];
        } else if (s[i] == '{') {
            depth++;
        } else if (s[i] == '}' && --depth == 0) {
            return i;
        }
    }
    return n;
}

static void warnf(conica_svg_warn_fn warn, void *ctx, size_t line, const char *what,
                  const char *s, size_t n)
{
    char msg[256];
    if (!warn)
        return;
    trim(&s, &n);
    snprintf(msg, sizeof msg, "<style>: %s '%.*s'", what, (int)(n > 80 ? 80 : n), s);
    warn(ctx, line, msg);
}

/* Parse the text of one `<style>` element (its bytes in sh->text). */
static conica_code parse_sheet(conica_svg__sheet *sh, size_t from, size_t to, size_t line,
                               conica_svg_warn_fn warn, void *wctx, conica_status *st)
{
    char *s = sh->text;
    size_t i = from;
    /* comments become blanks, so nothing below sees them */
    {
        size_t k;
        char q = 0;
        for (k = from; k < to; k++) {
            if (q) {
                if (s[k] == q)
                    q = 0;
            } else if (s[k] == '"' || s[k] == '\'') {
                q = s[k];
            } else if (s[k] == '/' && k + 1 < to && s[k + 1] == '*') {
                size_t e = k + 2;
                while (e + 1 < to && !(s[e] == '*' && s[e + 1] == '/'))
                    e++;
                e = e + 1 < to ? e + 2 : to;
                memset(s + k, ' ', e - k);
                k = e - 1;
            }
        }
    }
    while (i < to) {
        size_t j, open, close;
        while (i < to && is_blank(s[i]))
            i++;
        if (i + 4 <= to && !memcmp(s + i, "<!--", 4)) {
            i += 4;
            continue;
        }
        if (i + 3 <= to && !memcmp(s + i, "-->", 3)) {
            i += 3;
            continue;
        }
        if (i >= to)
            break;
        if (s[i] == '@') {
            /* at-rules: up to ';' or through their block */
            for (j = i; j < to && s[j] != ';' && s[j] != '{'; j++)
                ;
            if (j < to && s[j] == '{')
                j = block_end(s, to, j);
            {
                size_t k = i + 1;
                css_str name = {NULL, 0};
                read_ident(s, to, &k, &name);
                if (!ieq(name.s, name.n, "charset") && !ieq(name.s, name.n, "namespace") &&
                    !ieq(name.s, name.n, "font-face"))
                    warnf(warn, wctx, line, "at-rule not read, its rules are not applied:", s + i,
                          j - i < 40 ? j - i : 40);
            }
            i = j < to ? j + 1 : to;
            continue;
        }
        /* the prelude ends at a '{' outside () and [] blocks and strings
         * (CSS Syntax 3, 5.4.3: an unclosed '[' swallows the rest) */
        {
            int depth = 0;
            char q = 0;
            for (open = i; open < to; open++) {
                char ch = s[open];
                if (q) {
                    if (ch == q)
                        q = 0;
                } else if (ch == '"' || ch == '\'') {
                    q = ch;
                } else if (ch == '(' || ch == '[') {
                    depth++;
                } else if ((ch == ')' || ch == ']') && depth) {
                    depth--;
                } else if (ch == '{' && !depth) {
                    break;
                }
            }
        }
        if (open >= to) {
            warnf(warn, wctx, line, "unterminated CSS rule, not applied:", s + i,
                  to - i < 40 ? to - i : 40);
            break;
        }
        close = block_end(s, to, open);
        {
            size_t d0 = sh->ndecls, s0 = sh->nsels, c0 = sh->ncomps, p0 = sh->nsimples, k, a;
            int ok = 1;
            sheet_decl_ctx dc;
            int r;
            dc.sh = sh;
            r = parse_decls(s + open + 1, close - open - 1, sheet_decl, &dc);
            if (r == 2)
                return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                                    "<style>: more than %zu CSS declarations",
                                    CONICA_SVG_MAX_CSS_DECLS);
            if (r < 0)
                return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            /* the selector list, split at top-level commas */
            for (a = i, k = i; k <= open && ok; k++) {
                if (k == open || s[k] == ',') {
                    css_selector sel;
                    int pr;
                    if (sh->nsels >= CONICA_SVG_MAX_CSS_RULES)
                        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                                            "<style>: more than %zu CSS selectors",
                                            CONICA_SVG_MAX_CSS_RULES);
                    memset(&sel, 0, sizeof sel);
                    pr = parse_selector(sh, s + a, k - a, &sel);
                    if (pr < 0)
                        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                    if (!pr) {
                        ok = 0;
                        break;
                    }
                    sel.decl_first = d0;
                    sel.ndecl = sh->ndecls - d0;
                    if (!grow((void **)&sh->sels, &sh->capsels, sh->nsels, sizeof sel))
                        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                    sh->sels[sh->nsels++] = sel;
                    a = k + 1;
                }
            }
            if (!ok) {
                /* CSS: one bad selector drops the whole rule */
                warnf(warn, wctx, line, "selector not supported, rule not applied:", s + i,
                      open - i);
                sh->nsels = s0;
                sh->ncomps = c0;
                sh->nsimples = p0;
                sh->ndecls = d0;
            }
        }
        i = close < to ? close + 1 : to;
    }
    return CONICA_OK;
}

void conica_svg__sheet_free(conica_svg__sheet *sh)
{
    if (!sh)
        return;
    free(sh->text);
    free(sh->simples);
    free(sh->comps);
    free(sh->sels);
    free(sh->decls);
    free(sh);
}

conica_code conica_svg__sheet_read(xmlNodePtr root, conica_svg_warn_fn warn, void *warn_ctx,
                                   conica_svg__sheet **out, conica_status *st)
{
    conica_svg__sheet *sh = NULL;
    xmlNodePtr e = root;
    size_t total = 0;
    conica_code rc = CONICA_OK;
    *out = NULL;
    /* pass 1: size of all sheets */
    for (int pass = 0; pass < 2 && rc == CONICA_OK; pass++) {
        e = root;
        if (pass == 1) {
            if (!total)
                return CONICA_OK;
            sh = calloc(1, sizeof *sh);
            if (!sh || !(sh->text = malloc(total + 1))) {
                free(sh);
                return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            }
            *out = sh;
        }
        while (e) {
            if (e->type == XML_ELEMENT_NODE && is_tag(e, "style")) {
                /* every sheet is CSS, whatever its type says: librsvg 2.54
                 * applies `<style type="text/other">` too */
                {
                    xmlNodePtr c;
                    size_t from = (*out) ? (*out)->len : 0;
                    for (c = e->children; c; c = c->next) {
                        size_t k;
                        if ((c->type != XML_TEXT_NODE && c->type != XML_CDATA_SECTION_NODE) ||
                            !c->content)
                            continue;
                        k = strlen((const char *)c->content);
                        if (pass == 0) {
                            total += k;
                            if (total > CONICA_SVG_MAX_CSS_BYTES)
                                return conica__fail(st, CONICA_ERR_LIMIT, (size_t)xmlGetLineNo(e),
                                                    0, "<style>: more than %zu bytes of CSS",
                                                    CONICA_SVG_MAX_CSS_BYTES);
                        } else {
                            memcpy(sh->text + sh->len, c->content, k);
                            sh->len += k;
                        }
                    }
                    if (pass == 1) {
                        rc = parse_sheet(sh, from, sh->len, (size_t)xmlGetLineNo(e), warn,
                                         warn_ctx, st);
                        if (rc != CONICA_OK)
                            break;
                    }
                }
            }
            e = conica_svg__next_element(e, root);
        }
    }
    if (rc != CONICA_OK) {
        conica_svg__sheet_free(*out);
        *out = NULL;
    }
    return rc;
}

/* ------------------------------------------------------------ matching */

/* The value of attribute name of n without a copy where possible. */
static const char *attr_view(xmlNodePtr n, const char *name, size_t nn, char **owned)
{
    char buf[64];
    xmlAttrPtr a;
    *owned = NULL;
    if (nn >= sizeof buf)
        return NULL;
    memcpy(buf, name, nn);
    buf[nn] = '\0';
    a = xmlHasNsProp(n, BAD_CAST buf, NULL);
    if (!a || a->type != XML_ATTRIBUTE_NODE)
        return NULL;
    if (a->children && !a->children->next && a->children->type == XML_TEXT_NODE &&
        a->children->content)
        return (const char *)a->children->content;
    *owned = conica_svg__attr(n, buf, CONICA_SVG__MAX_ATTR, NULL);
    return *owned;
}

static int str_eq(const char *a, size_t an, const char *b, size_t bn, int icase)
{
    size_t i;
    if (an != bn)
        return 0;
    for (i = 0; i < an; i++)
        if (icase ? lower(a[i]) != lower(b[i]) : a[i] != b[i])
            return 0;
    return 1;
}

/* Whitespace-separated word w in list v. */
static int has_word(const char *v, const char *w, size_t wn, int icase)
{
    size_t i = 0, n = strlen(v);
    while (i < n) {
        size_t j;
        while (i < n && is_blank(v[i]))
            i++;
        for (j = i; j < n && !is_blank(v[j]); j++)
            ;
        if (j > i && str_eq(v + i, j - i, w, wn, icase))
            return 1;
        i = j;
    }
    return 0;
}

static xmlNodePtr prev_element(xmlNodePtr n)
{
    for (n = n->prev; n && n->type != XML_ELEMENT_NODE; n = n->prev)
        ;
    return n;
}

static xmlNodePtr next_element_sibling(xmlNodePtr n)
{
    for (n = n->next; n && n->type != XML_ELEMENT_NODE; n = n->next)
        ;
    return n;
}

static xmlNodePtr parent_element(xmlNodePtr n)
{
    n = n->parent;
    return n && n->type == XML_ELEMENT_NODE ? n : NULL;
}

static int match_simple(const css_simple *sp, xmlNodePtr n)
{
    char *owned;
    const char *v;
    int r = 0;
    switch (sp->kind) {
    case S_ID:
        v = attr_view(n, "id", 2, &owned);
        r = v && str_eq(v, strlen(v), sp->name.s, sp->name.n, 0);
        break;
    case S_CLASS:
        v = attr_view(n, "class", 5, &owned);
        r = v && has_word(v, sp->name.s, sp->name.n, 0);
        break;
    case S_ATTR: {
        size_t vn, wn = sp->value.n;
        const char *w = sp->value.s;
        v = attr_view(n, sp->name.s, sp->name.n, &owned);
        if (!v)
            break;
        vn = strlen(v);
        switch (sp->op) {
        case A_EXISTS: r = 1; break;
        case A_EQ: r = str_eq(v, vn, w, wn, sp->icase); break;
        case A_WORD: r = wn && has_word(v, w, wn, sp->icase); break;
        case A_DASH:
            r = str_eq(v, vn, w, wn, sp->icase) ||
                (vn > wn && v[wn] == '-' && str_eq(v, wn, w, wn, sp->icase));
            break;
        case A_PREFIX: r = wn && vn >= wn && str_eq(v, wn, w, wn, sp->icase); break;
        case A_SUFFIX: r = wn && vn >= wn && str_eq(v + vn - wn, wn, w, wn, sp->icase); break;
        case A_SUBSTR: {
            size_t k;
            for (k = 0; wn && k + wn <= vn && !r; k++)
                r = str_eq(v + k, wn, w, wn, sp->icase);
            break;
        }
        default: break;
        }
        break;
    }
    case S_FIRST_CHILD:
        return !prev_element(n);
    case S_LAST_CHILD:
        return !next_element_sibling(n);
    case S_ROOT:
        return !parent_element(n);
    default:
        return 0;
    }
    xmlFree(owned);
    return r;
}

static int match_compound(const conica_svg__sheet *sh, const css_compound *cp, xmlNodePtr n)
{
    size_t i;
    if (cp->type.n && !str_eq((const char *)n->name, strlen((const char *)n->name), cp->type.s,
                              cp->type.n, 0))
        return 0;
    for (i = 0; i < cp->n; i++)
        if (!match_simple(&sh->simples[cp->first + i], n))
            return 0;
    return 1;
}

/* Compound k of sel (and all left of it) matches at n; *steps bounds the
 * backtracking. */
static int match_from(const conica_svg__sheet *sh, const css_selector *sel, size_t k,
                      xmlNodePtr n, size_t *steps)
{
    const css_compound *cp = &sh->comps[sel->first + k];
    if (++*steps > CSS_MAX_MATCH_STEPS || !match_compound(sh, cp, n))
        return 0;
    if (k == 0)
        return 1;
    switch (cp->comb) {
    case '>':
        n = parent_element(n);
        return n && match_from(sh, sel, k - 1, n, steps);
    case '+':
        n = prev_element(n);
        return n && match_from(sh, sel, k - 1, n, steps);
    case '~':
        for (n = prev_element(n); n; n = prev_element(n))
            if (match_from(sh, sel, k - 1, n, steps))
                return 1;
        return 0;
    default:
        for (n = parent_element(n); n; n = parent_element(n))
            if (match_from(sh, sel, k - 1, n, steps))
                return 1;
        return 0;
    }
}

/* ------------------------------------------------------------ cascade */

typedef struct cand {
    uint64_t key; /* importance, level, specificity, order: the higher wins */
    int prop;
    css_str value;
} cand;

typedef struct cand_list {
    cand local[CSS_LOCAL_DECLS];
    cand *c;
    size_t n, cap;
    int oom;
    uint64_t level; /* for style-attribute declarations */
    size_t order;
} cand_list;

static void cand_push(cand_list *l, uint64_t key, int prop, const char *v, size_t vn)
{
    if (l->n == l->cap) {
        size_t nc = 2 * l->cap;
        cand *t = l->c == l->local ? malloc(nc * sizeof *t) : realloc(l->c, nc * sizeof *t);
        if (!t) {
            l->oom = 1;
            return;
        }
        if (l->c == l->local)
            memcpy(t, l->local, sizeof l->local);
        l->c = t;
        l->cap = nc;
    }
    l->c[l->n].key = key;
    l->c[l->n].prop = prop;
    l->c[l->n].value.s = v;
    l->c[l->n].value.n = vn;
    l->n++;
}

static uint64_t make_key(int important, unsigned level, uint32_t spec, size_t order)
{
    return (uint64_t)(important ? 1 : 0) << 63 | (uint64_t)level << 60 |
           (uint64_t)(spec & 0xffffffu) << 32 | (uint64_t)(order & 0xffffffffu);
}

static int style_decl(void *ctx, int prop, const char *v, size_t vn, int important)
{
    cand_list *l = ctx;
    cand_push(l, make_key(important, 2, 0, l->order++), prop, v, vn);
    return l->oom ? -1 : 0;
}

static int cmp_cand(const void *a, const void *b)
{
    const cand *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key;
}

int conica_svg__style_compute(xmlNodePtr n, const conica_svg__style *parent,
                              const conica_svg__sheet *sheet, const conica_svg__ids *ids,
                              size_t *budget, conica_svg__style *out)
{
    conica_svg__style o = *parent;
    cand_list l;
    xmlAttrPtr a;
    char *style = NULL;
    size_t i, order = 0;
    int pass;
    /* non-inherited properties start from their initial values */
    o.display_none = 0;
    o.opacity = 1.0;
    o.overflow_visible = 0;
    o.non_scaling = 0;
    o.clip_path = o.mask = o.filter = o.filter_missing = 0;
    o.css_transform = 0;
    memset(&l, 0, sizeof l);
    l.c = l.local;
    l.cap = CSS_LOCAL_DECLS;
    /* presentation attributes (specificity 0, before every rule) */
    for (a = n->properties; a; a = a->next) {
        int p;
        if (a->ns || !a->children || a->children->next || a->children->type != XML_TEXT_NODE ||
            !a->children->content)
            continue;
        p = prop_find((const char *)a->name, strlen((const char *)a->name));
        if (p >= 0 && p < P_PRESENTATION) {
            const char *v = (const char *)a->children->content;
            cand_push(&l, make_key(0, 0, 0, order++), p, v, strlen(v));
        }
    }
    /* sheet rules */
    for (i = 0; sheet && i < sheet->nsels; i++) {
        const css_selector *sel = &sheet->sels[i];
        size_t steps = 0, k;
        int hit = match_from(sheet, sel, sel->n - 1, n, &steps);
        if (steps > *budget) {
            xmlFree(style);
            if (l.c != l.local)
                free(l.c);
            return -2;
        }
        *budget -= steps;
        if (!hit)
            continue;
        for (k = 0; k < sel->ndecl; k++) {
            const css_decl *d = &sheet->decls[sel->decl_first + k];
            cand_push(&l, make_key(d->important, 1, sel->spec, sel->decl_first + k), d->prop,
                      d->value.s, d->value.n);
        }
    }
    /* the style attribute */
    style = conica_svg__attr(n, "style", CONICA_SVG__MAX_ATTR, NULL);
    if (style)
        parse_decls(style, strlen(style), style_decl, &l);
    if (l.oom) {
        xmlFree(style);
        if (l.c != l.local)
            free(l.c);
        return -1;
    }
    qsort(l.c, l.n, sizeof *l.c, cmp_cand);
    /* color and font-size first: currentColor and em read them */
    for (pass = 0; pass < 2; pass++)
        for (i = 0; i < l.n; i++) {
            int early = l.c[i].prop == P_COLOR || l.c[i].prop == P_FONT_SIZE;
            if (early == !pass)
                apply(l.c[i].prop, l.c[i].value.s, l.c[i].value.n, parent, ids, &o);
        }
    xmlFree(style);
    if (l.c != l.local)
        free(l.c);
    *out = o;
    return 0;
}
