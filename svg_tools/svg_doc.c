/* The SVG document: safe load and faithful save through libxml2, the
 * viewport, element selection with inherited fill-rule, and the two
 * high-level calls (extract polylines / rewrite geometry in place). */
#include "svg_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/SAX2.h>
#include <libxml/tree.h>
#include <libxml/xmlsave.h>

#include "conica/subdiv.h"
#include "numparse.h"

#define SVG_NS "http://www.w3.org/2000/svg"
/* Internal entities that are short plain text (Illustrator's
 * `<!ENTITY ns_svg "http://www.w3.org/2000/svg">`) cannot amplify: a
 * reference expands to at most this many bytes and never to another
 * reference. Anything else (nested references: billion laughs; SYSTEM or
 * PUBLIC: XXE; parameter entities) is refused. */
#define SVG_MAX_ENTITY_TEXT 1024
/* Cap on other attributes we read (id, style, fill-rule, lengths): longer
 * values are treated as absent. */
#define SVG_MAX_PLAIN_ATTR ((size_t)1 << 16)
/* Longest XML declaration kept verbatim (longer ones are rewritten by libxml2). */
#define SVG_MAX_DECL 255
/* Bytes handed to libxml2's push parser at a time. */
#define SVG_PARSE_CHUNK ((size_t)1 << 16)



struct conica_svg_doc {
    xmlDocPtr xml;
    char decl[SVG_MAX_DECL + 1]; /* the input's XML declaration, verbatim ("" if none) */
};

conica_svg_limits conica_svg_limits_defaults(void)
{
    conica_svg_limits l;
    l.max_bytes = CONICA_SVG_DEFAULT_MAX_BYTES;
    l.max_depth = CONICA_SVG_DEFAULT_MAX_DEPTH;
    l.max_elements = CONICA_SVG_DEFAULT_MAX_ELEMENTS;
    l.max_path_bytes = CONICA_SVG_DEFAULT_MAX_PATH_BYTES;
    l.max_points = CONICA_SVG_DEFAULT_MAX_POINTS;
    return l;
}

conica_svg_settings conica_svg_defaults(void)
{
    conica_svg_settings s;
    memset(&s, 0, sizeof s);
    s.mode = CONICA_SVG_SMOOTH;
    s.levels = 4;
    s.tolerance = 0.0;
    s.corner_angle_deg = 40.0;
    s.precision = 7;
    s.limits = conica_svg_limits_defaults();
    return s;
}

/* ------------------------------------------------------------ load/save */

typedef struct load_state {
    int refused;
    char why[160];
} load_state;

static void entity_decl(void *ctx, const xmlChar *name, int type, const xmlChar *publicId,
                        const xmlChar *systemId, xmlChar *content)
{
    xmlParserCtxtPtr ctxt = ctx;
    load_state *ls = ctxt->_private;
    const char *why = NULL;
    if (type != XML_INTERNAL_GENERAL_ENTITY || publicId || systemId)
        why = "external or parameter entity (XXE)";
    else if (!content || strlen((const char *)content) > SVG_MAX_ENTITY_TEXT)
        why = "entity text too long";
    else if (strchr((const char *)content, '&') || strchr((const char *)content, '%') ||
             strchr((const char *)content, '<'))
        why = "entity refers to other entities or markup (entity expansion attack)";
    if (why) {
        ls->refused = 1;
        snprintf(ls->why, sizeof ls->why, "entity '%s' refused: %s", (const char *)name, why);
        xmlStopParser(ctxt);
        return;
    }
    xmlSAX2EntityDecl(ctx, name, type, publicId, systemId, content);
}

static void trim_newline(char *s)
{
    size_t n = strlen(s);
    while (n && (s[n - 1] == '\n' || s[n - 1] == '\r' || s[n - 1] == ' '))
        s[--n] = '\0';
}

/* The element after n in document order below root (elements only: entity
 * references and text are never entered), tracking the nesting depth;
 * NULL at the end. No recursion, so deep documents cannot exhaust the stack. */
static xmlNodePtr next_element(xmlNodePtr n, xmlNodePtr root, size_t *depth)
{
    xmlNodePtr c = n->children;
    while (c && c->type != XML_ELEMENT_NODE)
        c = c->next;
    if (c) {
        ++*depth;
        return c;
    }
    for (;;) {
        xmlNodePtr nx;
        if (n == root)
            return NULL;
        nx = n->next;
        while (nx && nx->type != XML_ELEMENT_NODE)
            nx = nx->next;
        if (nx)
            return nx;
        n = n->parent;
        --*depth;
        if (!n)
            return NULL;
    }
}

conica_code conica_svg_doc_load(const char *buf, size_t len, const conica_svg_limits *lim,
                                conica_svg_doc **out, conica_status *st)
{
    conica_svg_limits def = conica_svg_limits_defaults();
    xmlParserCtxtPtr ctxt;
    xmlDocPtr xml;
    load_state ls;
    conica_svg_doc *doc;
    xmlNodePtr n, root;
    size_t depth = 1, count = 0, i;
    int opts = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES;

    if ((!buf && len) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_load: NULL argument");
    if (!lim)
        lim = &def;
    if (len > lim->max_bytes)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                "document has %zu bytes, more than the limit of %zu", len,
                                lim->max_bytes);
    if (len > (size_t)0x7fffffff)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0, "document larger than 2 GiB");
    /* The push parser, fed in chunks: it lets go of consumed input, so
     * large documents parse without XML_PARSE_HUGE (whose absence keeps
     * libxml2's own caps on names, text nodes and entity amplification). */
    {
        size_t first = len < 4 ? len : 4, off;
        ctxt = xmlCreatePushParserCtxt(NULL, NULL, buf, (int)first, NULL);
        if (!ctxt)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        xmlCtxtUseOptions(ctxt, opts);
        memset(&ls, 0, sizeof ls);
        ctxt->_private = &ls;
        ctxt->sax->entityDecl = entity_decl;
        for (off = first; !ls.refused;) {
            size_t k = len - off < SVG_PARSE_CHUNK ? len - off : SVG_PARSE_CHUNK;
            int last = off + k == len;
            if (xmlParseChunk(ctxt, buf + off, (int)k, last) != 0 || last)
                break;
            off += k;
        }
        xml = ctxt->myDoc;
        ctxt->myDoc = NULL;
    }
    if (ls.refused) {
        size_t line = (size_t)xmlSAX2GetLineNumber(ctxt);
        xmlFreeDoc(xml);
        xmlFreeParserCtxt(ctxt);
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, line, 0, "%s", ls.why);
    }
    if (!xml || !ctxt->wellFormed) {
        const xmlError *e = xmlCtxtGetLastError(ctxt);
        char msg[200];
        size_t line = e ? (size_t)(e->line > 0 ? e->line : 0) : 0;
        snprintf(msg, sizeof msg, "%s", e && e->message ? e->message : "not well-formed XML");
        trim_newline(msg);
        xmlFreeDoc(xml);
        xmlFreeParserCtxt(ctxt);
        return conica__fail(st, CONICA_ERR_PARSE, line, 0, "XML: %s", msg);
    }
    xmlFreeParserCtxt(ctxt);
    root = xmlDocGetRootElement(xml);
    if (!root || xmlStrcmp(root->name, BAD_CAST "svg") != 0) {
        size_t line = root ? (size_t)xmlGetLineNo(root) : 1;
        xmlFreeDoc(xml);
        return conica__fail(st, CONICA_ERR_PARSE, line, 0, "the root element is not <svg>");
    }
    /* Caps on nesting and element count (walk without recursion). */
    n = root;
    while (n) {
        if (++count > lim->max_elements) {
            size_t line = (size_t)xmlGetLineNo(n);
            xmlFreeDoc(xml);
            return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                                    "more than %zu elements (--max-elements)", lim->max_elements);
        }
        if (depth > lim->max_depth) {
            size_t line = (size_t)xmlGetLineNo(n);
            xmlFreeDoc(xml);
            return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                                    "elements nested deeper than %zu (--max-depth)", lim->max_depth);
        }
        n = next_element(n, root, &depth);
    }
    doc = malloc(sizeof *doc);
    if (!doc) {
        xmlFreeDoc(xml);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    doc->xml = xml;
    i = 0;
    if (len >= 3 && (unsigned char)buf[0] == 0xEF && (unsigned char)buf[1] == 0xBB &&
        (unsigned char)buf[2] == 0xBF)
        i = 3;
    doc->decl[0] = '\0';
    if (len >= i + 6 && memcmp(buf + i, "<?xml", 5) == 0) {
        /* libxml2 would write its own declaration (adding encoding="UTF-8"
         * where the input had none): keep the input's text instead */
        size_t k;
        for (k = i; k + 1 < len && k - i < SVG_MAX_DECL - 1; k++)
            if (buf[k] == '?' && buf[k + 1] == '>') {
                memcpy(doc->decl, buf + i, k + 2 - i);
                doc->decl[k + 2 - i] = '\0';
                break;
            }
    }
    *out = doc;
    return CONICA_OK;
}

void conica_svg_doc_free(conica_svg_doc *doc)
{
    if (!doc)
        return;
    xmlFreeDoc(doc->xml);
    free(doc);
}

conica_code conica_svg_doc_save(const conica_svg_doc *doc, char **buf, size_t *len,
                                conica_status *st)
{
    xmlBufferPtr xb;
    xmlSaveCtxtPtr sc;
    char *s;
    size_t n;
    size_t dl;
    int opts = doc && doc->decl[0] ? 0 : XML_SAVE_NO_DECL;
    if (!doc || !buf || !len)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_save: NULL argument");
    xb = xmlBufferCreate();
    if (!xb)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    /* no declared encoding means UTF-8: keep non-ASCII text as it was
     * instead of turning it into character references */
    sc = xmlSaveToBuffer(xb, doc->xml->encoding ? (const char *)doc->xml->encoding : "UTF-8",
                         opts);
    if (!sc) {
        xmlBufferFree(xb);
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "cannot serialise the document");
    }
    if (xmlSaveDoc(sc, doc->xml) < 0) {
        xmlSaveClose(sc);
        xmlBufferFree(xb);
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "cannot serialise the document");
    }
    xmlSaveClose(sc);
    {
        /* replace libxml2's declaration line by the input's */
        const char *body = (const char *)xmlBufferContent(xb);
        size_t blen = (size_t)xmlBufferLength(xb), skip = 0;
        dl = strlen(doc->decl);
        if (dl && blen >= 5 && memcmp(body, "<?xml", 5) == 0) {
            const char *e = strstr(body, "?>");
            skip = e ? (size_t)(e + 2 - body) : 0;
        } else {
            dl = 0;
        }
        n = dl + blen - skip;
        s = malloc(n + 2);
        if (!s) {
            xmlBufferFree(xb);
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
        memcpy(s, doc->decl, dl);
        memcpy(s + dl, body + skip, blen - skip);
    }
    if (n && s[n - 1] != '\n') /* end the file with a newline, as nearly every input does */
        s[n++] = '\n';
    s[n] = '\0';
    xmlBufferFree(xb);
    *buf = s;
    *len = n;
    return CONICA_OK;
}

void conica_svg_buffer_free(char *buf)
{
    free(buf);
}

/* ------------------------------------------------------------ attributes */

/* The value of attribute `name` (no namespace), entity references expanded,
 * or NULL when absent or when the expanded value would exceed cap bytes
 * (then *too_long is set, if given). The length is summed before anything
 * is expanded: a value made of many references to a 1 KB entity must not
 * grow a few bytes of input into gigabytes. Free with xmlFree(). */
static char *get_attr_cap(xmlNodePtr n, const char *name, size_t cap, int *too_long)
{
    xmlAttrPtr a = xmlHasNsProp(n, BAD_CAST name, NULL);
    xmlNodePtr c;
    size_t total = 0;
    if (too_long)
        *too_long = 0;
    if (!a || a->type != XML_ATTRIBUTE_NODE)
        return NULL;
    for (c = a->children; c; c = c->next) {
        if (c->type == XML_TEXT_NODE && c->content) {
            total += (size_t)xmlStrlen(c->content);
        } else if (c->type == XML_ENTITY_REF_NODE) {
            xmlEntityPtr ent = xmlGetDocEntity(n->doc, c->name);
            total += ent && ent->content ? (size_t)xmlStrlen(ent->content) : 0;
        }
        if (total > cap) {
            if (too_long)
                *too_long = 1;
            return NULL;
        }
    }
    return (char *)xmlNodeListGetString(n->doc, a->children, 1);
}

static char *get_attr(xmlNodePtr n, const char *name)
{
    return get_attr_cap(n, name, SVG_MAX_PLAIN_ATTR, NULL);
}

/* A number at s (after optional whitespace), locale free; returns the
 * bytes consumed or 0. */
static size_t read_num(const char *s, double *v)
{
    size_t i = 0, used = 0;
    while (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')
        i++;
    if (conica__parse_double(s + i, strlen(s + i), v, &used) != CONICA__NUM_OK)
        return 0;
    return i + used;
}

/* A CSS length: number and unit; 1 on success. */
static int parse_length(const char *s, double *v, char unit[4])
{
    size_t k = s ? read_num(s, v) : 0, u = 0;
    if (!k)
        return 0;
    s += k;
    while (u < 3 && ((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '%'))
        unit[u++] = *s++;
    unit[u] = '\0';
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
        s++;
    return *s == '\0';
}

static double unit_to_mm(double v, const char *u)
{
    if (!*u || !strcmp(u, "px"))
        return v * 25.4 / 96.0;
    if (!strcmp(u, "mm"))
        return v;
    if (!strcmp(u, "cm"))
        return 10.0 * v;
    if (!strcmp(u, "in"))
        return 25.4 * v;
    if (!strcmp(u, "pt"))
        return v * 25.4 / 72.0;
    if (!strcmp(u, "pc"))
        return v * 25.4 / 6.0;
    if (!strcmp(u, "Q"))
        return 0.25 * v;
    return NAN;
}

conica_code conica_svg_doc_viewport(const conica_svg_doc *doc, conica_svg_viewport *out,
                                    conica_status *st)
{
    conica_svg_viewport vp;
    xmlNodePtr root;
    char *a;
    if (!doc || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_viewport: NULL argument");
    memset(&vp, 0, sizeof vp);
    vp.width_mm = vp.height_mm = NAN;
    root = xmlDocGetRootElement(doc->xml);
    if ((a = get_attr(root, "width")) != NULL) {
        vp.has_width = parse_length(a, &vp.width, vp.width_unit);
        if (vp.has_width)
            vp.width_mm = unit_to_mm(vp.width, vp.width_unit);
        xmlFree(a);
    }
    if ((a = get_attr(root, "height")) != NULL) {
        vp.has_height = parse_length(a, &vp.height, vp.height_unit);
        if (vp.has_height)
            vp.height_mm = unit_to_mm(vp.height, vp.height_unit);
        xmlFree(a);
    }
    if ((a = get_attr(root, "viewBox")) != NULL) {
        const char *p = a;
        int i, ok = 1;
        for (i = 0; i < 4 && ok; i++) {
            size_t k;
            while (*p == ',' || *p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
                p++;
            k = read_num(p, &vp.viewbox[i]);
            ok = k > 0;
            p += k;
        }
        vp.has_viewbox = ok && vp.viewbox[2] > 0.0 && vp.viewbox[3] > 0.0;
        if (!vp.has_viewbox)
            memset(vp.viewbox, 0, sizeof vp.viewbox);
        xmlFree(a);
    }
    if (vp.has_viewbox) {
        /* a missing width/height is 100%: unknown in mm */
        vp.mm_per_unit_x = vp.has_width ? vp.width_mm / vp.viewbox[2] : NAN;
        vp.mm_per_unit_y = vp.has_height ? vp.height_mm / vp.viewbox[3] : NAN;
    } else {
        vp.mm_per_unit_x = vp.mm_per_unit_y = 25.4 / 96.0;
    }
    *out = vp;
    return CONICA_OK;
}

/* fill-rule from a presentation attribute or a style declaration;
 * -1 when the element does not set it. */
static int own_fill_rule(xmlNodePtr n)
{
    int r = -1;
    char *a = get_attr(n, "fill-rule");
    if (a) {
        if (strstr(a, "evenodd"))
            r = CONICA_SVG_EVENODD;
        else if (strstr(a, "nonzero"))
            r = CONICA_SVG_NONZERO;
        xmlFree(a);
    }
    a = get_attr(n, "style");
    if (a) {
        /* style wins over the attribute; the last declaration wins */
        const char *p = a;
        while ((p = strstr(p, "fill-rule")) != NULL) {
            const char *v = p + 9;
            while (*v == ' ' || *v == '\t')
                v++;
            if (*v == ':') {
                v++;
                while (*v == ' ' || *v == '\t')
                    v++;
                if (!strncmp(v, "evenodd", 7))
                    r = CONICA_SVG_EVENODD;
                else if (!strncmp(v, "nonzero", 7))
                    r = CONICA_SVG_NONZERO;
            }
            p += 9;
        }
        xmlFree(a);
    }
    return r;
}

static conica_svg_fill_rule fill_rule_of(xmlNodePtr n)
{
    for (; n && n->type == XML_ELEMENT_NODE; n = n->parent) {
        int r = own_fill_rule(n);
        if (r >= 0)
            return (conica_svg_fill_rule)r;
    }
    return CONICA_SVG_NONZERO;
}

static int has_transform(xmlNodePtr n)
{
    for (; n && n->type == XML_ELEMENT_NODE; n = n->parent)
        if (xmlHasProp(n, BAD_CAST "transform"))
            return 1;
    return 0;
}

static int is_svg_element(xmlNodePtr n)
{
    return n->type == XML_ELEMENT_NODE &&
           (!n->ns || (n->ns->href && !xmlStrcmp(n->ns->href, BAD_CAST SVG_NS)));
}

/* ------------------------------------------------------------ shapes */

typedef struct pbuild {
    conica_svg_path *p;
    double x, y, sx, sy;
    int ok;
} pbuild;

/* A MOVE or LINE from the current point to (x, y). */
static void pb_to(pbuild *b, conica_svg_seg_type type, double x, double y)
{
    conica_svg_seg g;
    memset(&g, 0, sizeof g);
    g.type = type;
    g.cmd = type == CONICA_SVG_SEG_MOVE ? 'M' : 'L';
    g.x0 = b->x;
    g.y0 = b->y;
    g.x1 = b->x = x;
    g.y1 = b->y = y;
    if (type == CONICA_SVG_SEG_MOVE) {
        b->sx = x;
        b->sy = y;
    }
    b->ok = b->ok && conica_svg__path_push(b->p, &g);
}

static void pb_move(pbuild *b, double x, double y)
{
    pb_to(b, CONICA_SVG_SEG_MOVE, x, y);
}

static void pb_line(pbuild *b, double x, double y)
{
    pb_to(b, CONICA_SVG_SEG_LINE, x, y);
}

static void pb_arc(pbuild *b, double rx, double ry, double x, double y)
{
    conica_svg_seg g;
    memset(&g, 0, sizeof g);
    g.cmd = 'A';
    g.x0 = b->x;
    g.y0 = b->y;
    g.x1 = x;
    g.y1 = y;
    g.sweep = 1;
    if (conica_svg__arc_to_centre(&g, rx, ry, 0.0))
        b->ok = b->ok && conica_svg__path_push(b->p, &g);
    b->x = x;
    b->y = y;
}

static void pb_close(pbuild *b)
{
    conica_svg_seg g;
    memset(&g, 0, sizeof g);
    g.type = CONICA_SVG_SEG_CLOSE;
    g.cmd = 'Z';
    g.x0 = b->x;
    g.y0 = b->y;
    g.x1 = b->x = b->sx;
    g.y1 = b->y = b->sy;
    b->ok = b->ok && conica_svg__path_push(b->p, &g);
}

/* A user-space length attribute: number with no unit or px. 1 ok, 0 absent
 * (value untouched), -1 unusable. */
static int len_attr(xmlNodePtr n, const char *name, double *v)
{
    char unit[4];
    char *a = get_attr(n, name);
    int r;
    if (!a)
        return 0;
    r = parse_length(a, v, unit) && (!unit[0] || !strcmp(unit, "px")) ? 1 : -1;
    xmlFree(a);
    return r;
}

/* rect/circle/ellipse/line as path segments (SVG 2, 10.2-10.5).
 * Returns 1 built, 0 nothing to draw, -1 unusable attributes, -2 no memory. */
static int shape_path(xmlNodePtr n, conica_svg_path *p)
{
    const char *tag = (const char *)n->name;
    pbuild b;
    double v[6] = {0, 0, 0, 0, 0, 0};
    int r[6] = {0, 0, 0, 0, 0, 0}, i;
    memset(&b, 0, sizeof b);
    b.p = p;
    b.ok = 1;
    if (!strcmp(tag, "rect")) {
        static const char *names[6] = {"x", "y", "width", "height", "rx", "ry"};
        double x, y, w, h, rx, ry;
        for (i = 0; i < 6; i++)
            if ((r[i] = len_attr(n, names[i], &v[i])) < 0)
                return -1;
        x = v[0], y = v[1], w = v[2], h = v[3];
        if (!(w > 0.0) || !(h > 0.0))
            return 0;
        rx = r[4] ? v[4] : r[5] ? v[5] : 0.0; /* auto: the other radius */
        ry = r[5] ? v[5] : r[4] ? v[4] : 0.0;
        rx = rx < 0 ? 0 : rx > 0.5 * w ? 0.5 * w : rx;
        ry = ry < 0 ? 0 : ry > 0.5 * h ? 0.5 * h : ry;
        if (rx > 0.0 && ry > 0.0) {
            pb_move(&b, x + rx, y);
            pb_line(&b, x + w - rx, y);
            pb_arc(&b, rx, ry, x + w, y + ry);
            pb_line(&b, x + w, y + h - ry);
            pb_arc(&b, rx, ry, x + w - rx, y + h);
            pb_line(&b, x + rx, y + h);
            pb_arc(&b, rx, ry, x, y + h - ry);
            pb_line(&b, x, y + ry);
            pb_arc(&b, rx, ry, x + rx, y);
        } else {
            pb_move(&b, x, y);
            pb_line(&b, x + w, y);
            pb_line(&b, x + w, y + h);
            pb_line(&b, x, y + h);
        }
        pb_close(&b);
    } else if (!strcmp(tag, "circle") || !strcmp(tag, "ellipse")) {
        double cx, cy, rx, ry;
        int circle = tag[0] == 'c';
        if (len_attr(n, "cx", &v[0]) < 0 || len_attr(n, "cy", &v[1]) < 0)
            return -1;
        if (circle) {
            if (len_attr(n, "r", &v[2]) < 0)
                return -1;
            v[3] = v[2];
        } else {
            r[2] = len_attr(n, "rx", &v[2]);
            r[3] = len_attr(n, "ry", &v[3]);
            if (r[2] < 0 || r[3] < 0)
                return -1;
            if (!r[2])
                v[2] = v[3];
            if (!r[3])
                v[3] = v[2];
        }
        cx = v[0], cy = v[1], rx = v[2], ry = v[3];
        if (!(rx > 0.0) || !(ry > 0.0))
            return 0;
        pb_move(&b, cx + rx, cy);
        pb_arc(&b, rx, ry, cx, cy + ry);
        pb_arc(&b, rx, ry, cx - rx, cy);
        pb_arc(&b, rx, ry, cx, cy - ry);
        pb_arc(&b, rx, ry, cx + rx, cy);
        pb_close(&b);
    } else if (!strcmp(tag, "line")) {
        static const char *names[4] = {"x1", "y1", "x2", "y2"};
        for (i = 0; i < 4; i++)
            if (len_attr(n, names[i], &v[i]) < 0)
                return -1;
        pb_move(&b, v[0], v[1]);
        pb_line(&b, v[2], v[3]);
    } else {
        return 0;
    }
    return b.ok ? 1 : -2;
}

/* ------------------------------------------------------------ walk */

typedef struct item {
    xmlNodePtr node;
    int kind;   /* 0 path, 1 polygon, 2 polyline, 3 shape converted to a path */
} item;

/* Selected: the element's id or the id of an ancestor (a group or layer)
 * is in the list. */
static int selected(const conica_svg_settings *s, xmlNodePtr n)
{
    if (!s->select)
        return 1;
    for (; n && n->type == XML_ELEMENT_NODE; n = n->parent) {
        size_t i;
        int hit = 0;
        char *id = get_attr(n, "id");
        for (i = 0; id && i < s->nselect && !hit; i++)
            hit = s->select[i] && !strcmp(s->select[i], id);
        xmlFree(id);
        if (hit)
            return 1;
    }
    return 0;
}

static void warn(const conica_svg_settings *s, size_t line, const char *fmt, ...)
    CONICA__PRINTF(3, 4);
static void warn(const conica_svg_settings *s, size_t line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    if (!s->warn)
        return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    s->warn(s->warn_ctx, line, msg);
}

static void describe(xmlNodePtr n, char *what, size_t size)
{
    char *id = get_attr(n, "id");
    if (id)
        snprintf(what, size, "%s '%.60s'", (const char *)n->name, id);
    else
        snprintf(what, size, "%s (no id)", (const char *)n->name);
    xmlFree(id);
}

static conica_code check_settings(const conica_svg_settings *s, conica_status *st)
{
    if (s->mode != CONICA_SVG_SMOOTH && s->mode != CONICA_SVG_FLATTEN && s->mode != CONICA_SVG_KEEP)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "unknown mode");
    if (s->mode == CONICA_SVG_FLATTEN && !(s->tolerance > 0.0 && isfinite(s->tolerance)))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "flattening needs a tolerance > 0");
    if (s->levels < 0 || s->levels > CONICA_SUBDIV_MAX_LEVELS)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "levels must be in 0..%d",
                                CONICA_SUBDIV_MAX_LEVELS);
    if (!(s->tolerance >= 0.0) || !isfinite(s->tolerance))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "tolerance must be finite and >= 0");
    if (!(s->corner_angle_deg >= 0.0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "corner angle must be >= 0");
    if (s->precision < 1 || s->precision > 17)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "precision must be in 1..17");
    return CONICA_OK;
}

/* Geometry of one element as segments; 1 got some, 0 nothing to do. */
static int element_path(const conica_svg_settings *s, xmlNodePtr n, int kind, const char *what,
                        conica_svg_path *p, conica_code *rc, conica_status *st)
{
    size_t line = (size_t)xmlGetLineNo(n);
    *rc = CONICA_OK;
    if (kind == 0) {
        int too_long;
        char *d = get_attr_cap(n, "d", s->limits.max_path_bytes, &too_long);
        size_t len;
        if (too_long) {
            *rc = conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                               "%s: path data exceeds the limit of %zu bytes (--max-path-bytes)",
                               what, s->limits.max_path_bytes);
            return 0;
        }
        if (!d)
            return 0;
        len = strlen(d);
        *rc = conica_svg_path_parse(d, len, 0, p, st);
        xmlFree(d);
        if (*rc != CONICA_OK) {
            if (st)
                st->line = line;
            return 0;
        }
        if (p->has_error)
            warn(s, line, "%s: bad path data at byte %zu: %s; %s", what, p->error_offset,
                 p->error, p->n ? "the valid part before it is kept" : "element left unchanged");
        return p->n > 0;
    }
    if (kind == 1 || kind == 2) {
        int too_long;
        char *a = get_attr_cap(n, "points", s->limits.max_path_bytes, &too_long);
        double *xy = NULL;
        size_t np = 0, bad = 0, len, i;
        pbuild b;
        if (too_long) {
            *rc = conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                               "%s: points exceed the limit of %zu bytes (--max-path-bytes)", what,
                               s->limits.max_path_bytes);
            return 0;
        }
        if (!a)
            return 0;
        len = strlen(a);
        *rc = conica_svg_points_parse(a, len, 0, &xy, &np, &bad, st);
        xmlFree(a);
        if (*rc != CONICA_OK)
            return 0;
        if (bad != (size_t)-1)
            warn(s, line, "%s: bad points list at byte %zu; %s", what, bad,
                 np ? "the valid pairs before it are kept" : "element left unchanged");
        memset(&b, 0, sizeof b);
        b.p = p;
        b.ok = 1;
        for (i = 0; i < np; i++) {
            if (i == 0)
                pb_move(&b, xy[0], xy[1]);
            else
                pb_line(&b, xy[2 * i], xy[2 * i + 1]);
        }
        if (np && kind == 1)
            pb_close(&b);
        free(xy);
        if (!b.ok) {
            *rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return 0;
        }
        return np > 0;
    }
    {
        int r = shape_path(n, p);
        if (r == -2) {
            *rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            return 0;
        }
        if (r == -1)
            warn(s, line, "%s: geometry attributes in units other than user units/px; left unchanged",
                 what);
        return r == 1;
    }
}

/* Walk the selected elements, turning each into polylines in *shapes and
 * remembering the node in *items (parallel to shapes->elements). */
static conica_code collect(const conica_svg_doc *doc, const conica_svg_settings *s,
                           conica_svg_shapes *shapes, item **items, conica_svg_stats *stats,
                           conica_status *st)
{
    xmlNodePtr root = xmlDocGetRootElement(doc->xml), n = root;
    size_t budget = s->limits.max_points, cap = 0, depth = 1;
    conica_code rc = CONICA_OK;
    conica_svg_path p;
    conica_svg_path_init(&p);
    *items = NULL;
    while (n && rc == CONICA_OK) {
        if (is_svg_element(n)) {
            const char *tag = (const char *)n->name;
            int kind = -1;
            if (!strcmp(tag, "path"))
                kind = 0;
            else if (!strcmp(tag, "polygon"))
                kind = 1;
            else if (!strcmp(tag, "polyline"))
                kind = 2;
            else if (s->convert_shapes && (!strcmp(tag, "rect") || !strcmp(tag, "circle") ||
                                           !strcmp(tag, "ellipse") || !strcmp(tag, "line")))
                kind = 3;
            if (kind >= 0 && selected(s, n)) {
                char what[96];
                double t0 = conica_svg__now(), geo = 0.0;
                describe(n, what, sizeof what);
                p.n = 0;
                p.has_error = 0;
                if (element_path(s, n, kind, what, &p, &rc, st)) {
                    conica_svg_element *el;
                    size_t first = shapes->nsubpaths, idx = shapes->nelements;
                    if (idx == cap) {
                        size_t nc = cap ? 2 * cap : 16;
                        conica_svg_element *te = realloc(shapes->elements, nc * sizeof *te);
                        item *ti;
                        if (te)
                            shapes->elements = te;
                        ti = te ? realloc(*items, nc * sizeof *ti) : NULL;
                        if (!te || !ti) {
                            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                            break;
                        }
                        *items = ti;
                        cap = nc;
                    }
                    el = &shapes->elements[idx];
                    memset(el, 0, sizeof *el);
                    el->id = get_attr(n, "id");
                    snprintf(el->tag, sizeof el->tag, "%s", tag);
                    el->fill_rule = fill_rule_of(n);
                    el->has_transform = has_transform(n);
                    el->line = (size_t)xmlGetLineNo(n);
                    el->first_subpath = first;
                    (*items)[idx].node = n;
                    (*items)[idx].kind = kind;
                    shapes->nelements++;
                    rc = conica_svg__path_polylines(&p, s, what, el->line, idx, kind == 1, &budget,
                                                    &stats->in_vertices, &geo, shapes, st);
                    if (rc != CONICA_OK && st)
                        st->line = el->line;
                    el->nsubpaths = shapes->nsubpaths - first;
                    stats->elements++;
                    stats->subpaths += el->nsubpaths;
                }
                stats->geometry_seconds += geo;
                stats->io_seconds += conica_svg__now() - t0 - geo;
            }
        }
        n = next_element(n, root, &depth);
    }
    conica_svg_path_free(&p);
    {
        size_t i;
        stats->out_points = 0;
        for (i = 0; i < shapes->nsubpaths; i++)
            stats->out_points += shapes->subpaths[i].n;
    }
    return rc;
}

void conica_svg_shapes_init(conica_svg_shapes *s)
{
    if (s)
        memset(s, 0, sizeof *s);
}

void conica_svg_shapes_free(conica_svg_shapes *s)
{
    size_t i;
    if (!s)
        return;
    for (i = 0; i < s->nelements; i++)
        xmlFree(s->elements[i].id);
    for (i = 0; i < s->nsubpaths; i++)
        free(s->subpaths[i].xy);
    free(s->elements);
    free(s->subpaths);
    memset(s, 0, sizeof *s);
}

conica_code conica_svg_extract(const conica_svg_doc *doc, const conica_svg_settings *s,
                               conica_svg_shapes *out, conica_status *st)
{
    conica_svg_shapes sh;
    conica_svg_stats stats;
    item *items = NULL;
    conica_code rc;
    if (!doc || !s || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_extract: NULL argument");
    if ((rc = check_settings(s, st)) != CONICA_OK)
        return rc;
    conica_svg_shapes_init(&sh);
    memset(&stats, 0, sizeof stats);
    rc = conica_svg_doc_viewport(doc, &sh.viewport, st);
    if (rc == CONICA_OK)
        rc = collect(doc, s, &sh, &items, &stats, st);
    free(items);
    if (rc != CONICA_OK) {
        conica_svg_shapes_free(&sh);
        return rc;
    }
    conica_svg_shapes_free(out);
    *out = sh;
    return CONICA_OK;
}

/* `points` list of a polygon/polyline from its (single) subpath. */
static char *format_points(const conica_svg_subpath *sp, size_t nsp, int precision)
{
    conica_svg__buf b = {NULL, 0, 0, 0};
    size_t i, j;
    int kind = 0;
    conica_svg__buf_put(&b, "", 0);
    for (i = 0; i < nsp; i++)
        for (j = 0; j < sp[i].n; j++) {
            conica_svg__put_number(&b, sp[i].xy[2 * j], precision, &kind);
            conica_svg__buf_putc(&b, ',');
            kind = 0;
            conica_svg__put_number(&b, sp[i].xy[2 * j + 1], precision, &kind);
        }
    if (b.oom) {
        free(b.s);
        return NULL;
    }
    return b.s;
}

conica_code conica_svg_process(conica_svg_doc *doc, const conica_svg_settings *s,
                               conica_svg_stats *stats, conica_status *st)
{
    conica_svg_shapes sh;
    conica_svg_stats local;
    item *items = NULL;
    char **text = NULL;
    conica_code rc;
    size_t i;
    double t0;
    if (!doc || !s)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_process: NULL argument");
    if ((rc = check_settings(s, st)) != CONICA_OK)
        return rc;
    conica_svg_shapes_init(&sh);
    memset(&local, 0, sizeof local);
    rc = collect(doc, s, &sh, &items, &local, st);
    t0 = conica_svg__now();
    /* Format everything first: the document changes only when all succeeded. */
    if (rc == CONICA_OK && sh.nelements) {
        text = calloc(sh.nelements, sizeof *text);
        if (!text)
            rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    for (i = 0; rc == CONICA_OK && i < sh.nelements; i++) {
        const conica_svg_element *el = &sh.elements[i];
        const conica_svg_subpath *sp = sh.subpaths + el->first_subpath;
        size_t len;
        if (items[i].kind == 1 || items[i].kind == 2) {
            text[i] = format_points(sp, el->nsubpaths, s->precision);
            if (!text[i])
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        } else {
            rc = conica_svg_format_path(sp, el->nsubpaths, s->precision, &text[i], &len, st);
        }
    }
    if (rc == CONICA_OK) {
        for (i = 0; i < sh.nelements; i++) {
            xmlNodePtr n = items[i].node;
            if (items[i].kind == 3) {
                static const char *geo[] = {"x", "y", "width", "height", "rx", "ry", "cx",
                                            "cy", "r", "x1", "y1", "x2", "y2"};
                size_t k;
                for (k = 0; k < sizeof geo / sizeof geo[0]; k++) {
                    xmlAttrPtr a = xmlHasNsProp(n, BAD_CAST geo[k], NULL);
                    if (a)
                        xmlRemoveProp(a);
                }
                xmlNodeSetName(n, BAD_CAST "path");
            }
            if (!xmlSetProp(n, BAD_CAST(items[i].kind == 0 || items[i].kind == 3 ? "d" : "points"),
                            BAD_CAST text[i])) {
                rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
                break;
            }
        }
    }
    local.io_seconds += conica_svg__now() - t0;
    if (text)
        for (i = 0; i < sh.nelements; i++)
            free(text[i]);
    free(text);
    free(items);
    conica_svg_shapes_free(&sh);
    if (rc == CONICA_OK && stats)
        *stats = local;
    return rc;
}
