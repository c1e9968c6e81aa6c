/* SPDX-License-Identifier: MIT */
/* The SVG document: safe load and faithful save through libxml2, the
 * viewport, element selection with inherited fill-rule, and the two
 * high-level calls (extract polylines / rewrite geometry in place). */
#include "svg_internal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <libxml/parser.h>
#include <libxml/parserInternals.h>
#include <libxml/SAX2.h>
#include <libxml/tree.h>
#include <libxml/xmlsave.h>

#include "conica/subdiv.h"
#include "numparse.h"
#include "svg_encoding.h"

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
/* libxml2's caps on one token under XML_PARSE_HUGE (XML_MAX_HUGE_LENGTH in
 * its parser.c, not in the 2.9 headers); without it XML_MAX_TEXT_LENGTH and
 * XML_MAX_NAME_LENGTH (parserInternals.h) apply. */
#define SVG_XML_HUGE_LENGTH 1000000000



struct conica_svg_doc {
    xmlDocPtr xml;
    char decl[SVG_MAX_DECL + 1]; /* the input's XML declaration, verbatim ("" if none) */
    char *src;                   /* the input's bytes, which a save splices into */
    size_t srclen;
    int rewritten; /* conica_svg_process() changed the tree */
    conica_svg__enc enc; /* the input's encoding: src is its UTF-8 form, saves convert back */
};

conica_svg_limits conica_svg_limits_defaults(void)
{
    conica_svg_limits l;
    l.max_bytes = CONICA_SVG_DEFAULT_MAX_BYTES;
    l.max_depth = CONICA_SVG_DEFAULT_MAX_DEPTH;
    l.max_elements = CONICA_SVG_DEFAULT_MAX_ELEMENTS;
    l.max_path_bytes = CONICA_SVG_DEFAULT_MAX_PATH_BYTES;
    l.max_points = CONICA_SVG_DEFAULT_MAX_POINTS;
    l.max_attributes = CONICA_SVG_DEFAULT_MAX_ATTRIBUTES;
    l.max_namespaces = CONICA_SVG_DEFAULT_MAX_NAMESPACES;
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
    s.precision = 7; /* svgsmooth asks for 0: digits from the tolerance */
    s.limits = conica_svg_limits_defaults();
    return s;
}

/* ------------------------------------------------------------ load/save */

typedef struct load_state {
    int refused;               /* an entity declaration was refused */
    conica_code code;          /* CONICA_ERR_UNSUPPORTED (entity) or CONICA_ERR_LIMIT */
    size_t line;
    char why[200];
    const conica_svg_limits *lim;
    size_t depth, elements;    /* open elements, elements seen */
    startElementNsSAX2Func start;
    endElementNsSAX2Func end;
    /* libxml2's errors, through xml_error() instead of its stderr lines:
     * the first one (what the failure reports) and how many there were */
    size_t xml_errors;
    int xml_code, xml_domain;  /* libxml2's xmlParserErrors code and domain of the first */
    size_t xml_line;
    char xml_msg[200];
} load_state;

/* Stop the parse; line is where the problem is (read before stopping:
 * xmlStopParser() resets the input). */
static void refuse(xmlParserCtxtPtr ctxt, load_state *ls, conica_code code, size_t line)
{
    ls->refused = 1;
    ls->code = code;
    ls->line = line;
    xmlStopParser(ctxt);
}

/* Line of the start tag being reported: the parser stands at its end, and
 * a start tag holds no other '<' (not even in attribute values), so the
 * newlines back to the last '<' are the tag's own. */
static size_t start_tag_line(xmlParserCtxtPtr ctxt)
{
    size_t line = (size_t)xmlSAX2GetLineNumber(ctxt);
    const xmlChar *p, *base;
    if (!ctxt->input || !ctxt->input->cur || !ctxt->input->base)
        return line;
    base = ctxt->input->base;
    for (p = ctxt->input->cur; p > base && p[-1] != '<'; p--)
        if (p[-1] == '\n' && line > 1)
            line--;
    return line;
}

static void entity_decl(void *ctx, const xmlChar *name, int type, const xmlChar *publicId,
                        const xmlChar *systemId, xmlChar *content)
{
    xmlParserCtxtPtr ctxt = ctx;
    load_state *ls = ctxt->_private;
    const char *why = NULL;
    if (ls->refused)
        return;
    if (type != XML_INTERNAL_GENERAL_ENTITY || publicId || systemId)
        why = "external or parameter entity (XXE)";
    else if (!content || strlen((const char *)content) > SVG_MAX_ENTITY_TEXT)
        why = "entity text too long";
    else if (strchr((const char *)content, '&') || strchr((const char *)content, '%') ||
             strchr((const char *)content, '<'))
        why = "entity refers to other entities or markup (entity expansion attack)";
    if (why) {
        snprintf(ls->why, sizeof ls->why, "entity '%s' refused: %s", (const char *)name, why);
        refuse(ctxt, ls, CONICA_ERR_UNSUPPORTED, (size_t)xmlSAX2GetLineNumber(ctxt));
        return;
    }
    xmlSAX2EntityDecl(ctx, name, type, publicId, systemId, content);
}

/* libxml2's structured error handler (sax->serror): every error and
 * warning of the parse arrives here instead of on stderr (with
 * XML_PARSE_NOERROR libxml2 still prints some, e.g. SAX2's "huge text
 * node", through its validity channel). An error of any level but a
 * warning fails the load even when libxml2 leaves wellFormed set: after
 * "huge text node" it stops with wellFormed == 1 and a partial tree, and
 * a save would silently drop the rest of the document (issue 17). */
#if LIBXML_VERSION >= 21200
static void xml_error(void *ctx, const xmlError *e)
#else
static void xml_error(void *ctx, xmlErrorPtr e)
#endif
{
    xmlParserCtxtPtr ctxt = ctx;
    load_state *ls = ctxt ? ctxt->_private : NULL;
    if (!ls || !e || e->level == XML_ERR_WARNING || e->level == XML_ERR_NONE)
        return;
    if (ls->xml_errors++ == 0) {
        ls->xml_code = e->code;
        ls->xml_domain = e->domain;
        ls->xml_line = e->line > 0 ? (size_t)e->line : 0;
        snprintf(ls->xml_msg, sizeof ls->xml_msg, "%s",
                 e->message ? e->message : "not well-formed XML");
    }
}

/* Depth and element caps, counted as the parser goes: a document over a
 * cap stops at the element that crosses it, before the rest is built (so
 * memory stays proportional to the caps, not to the input). */
static void start_element(void *ctx, const xmlChar *localname, const xmlChar *prefix,
                          const xmlChar *URI, int nb_namespaces, const xmlChar **namespaces,
                          int nb_attributes, int nb_defaulted, const xmlChar **attributes)
{
    xmlParserCtxtPtr ctxt = ctx;
    load_state *ls = ctxt->_private;
    if (ls->refused)
        return;
    ls->depth++;
    if (++ls->elements > ls->lim->max_elements) {
        snprintf(ls->why, sizeof ls->why, "more than %zu elements (--max-elements)",
                 ls->lim->max_elements);
        refuse(ctxt, ls, CONICA_ERR_LIMIT, start_tag_line(ctxt));
        return;
    }
    if (ls->depth > ls->lim->max_depth) {
        snprintf(ls->why, sizeof ls->why, "elements nested deeper than %zu (--max-depth)",
                 ls->lim->max_depth);
        refuse(ctxt, ls, CONICA_ERR_LIMIT, start_tag_line(ctxt));
        return;
    }
    ls->start(ctx, localname, prefix, URI, nb_namespaces, namespaces, nb_attributes,
              nb_defaulted, attributes);
}

static void end_element(void *ctx, const xmlChar *localname, const xmlChar *prefix,
                        const xmlChar *URI)
{
    xmlParserCtxtPtr ctxt = ctx;
    load_state *ls = ctxt->_private;
    if (ls->refused)
        return;
    ls->depth--;
    ls->end(ctx, localname, prefix, URI);
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

/* libxml2's message for an error, made to say what was hit where libxml2
 * only names its internals. */
static void explain_xml_error(const char *msg, int huge, char *out, size_t cap)
{
    if (strstr(msg, "Huge input lookup") || strstr(msg, "AttValue length too long") ||
        strstr(msg, "huge text node") || strstr(msg, "Text node too long"))
        snprintf(out, cap,
                 "XML: an attribute value, text node or comment is longer than libxml2's "
                 "limit of %d bytes (libxml2: %s)",
                 huge ? SVG_XML_HUGE_LENGTH : XML_MAX_TEXT_LENGTH, msg);
    else if (strstr(msg, "Name too long") || strstr(msg, "NCName too long"))
        snprintf(out, cap, "XML: a name is longer than libxml2's limit of %d bytes (libxml2: %s)",
                 huge ? SVG_XML_HUGE_LENGTH : XML_MAX_NAME_LENGTH, msg);
    else {
        /* libxml2 prefixes some messages with its function's name
         * ("xmlParseCharRef: invalid xmlChar value 0"): the user needs
         * what is wrong, not where inside libxml2 it was noticed */
        const char *m = msg, *q = msg;
        long v;
        char *end;
        if (strncmp(q, "xml", 3) == 0) {
            while ((*q >= 'A' && *q <= 'Z') || (*q >= 'a' && *q <= 'z') ||
                   (*q >= '0' && *q <= '9') || *q == '_')
                q++;
            if (q[0] == ':' && q[1] == ' ')
                m = q + 2;
        }
        if (strncmp(m, "invalid xmlChar value ", 22) == 0 &&
            ((v = strtol(m + 22, &end, 10)), end != m + 22))
            snprintf(out, cap, "XML: a character reference to code point %ld, which XML does "
                               "not allow in a document", v);
        else
            snprintf(out, cap, "XML: %s", m);
    }
}

/* ------------------------------------------------------------ start-tag scan */

/* Position of the first occurrence of the n-byte string `pat` in
 * [p, end), or NULL. */
static const char *scan_find(const char *p, const char *end, const char *pat, size_t n)
{
    while (p && (size_t)(end - p) >= n) {
        p = memchr(p, pat[0], (size_t)(end - p) - n + 1);
        if (!p || memcmp(p, pat, n) == 0)
            return p;
        p++;
    }
    return NULL;
}

static int scan_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/* Past a <!DOCTYPE ...> (p after "<!"): quoted strings, comments and the
 * internal subset's brackets skipped, so a '>' inside them does not end
 * it. NULL when it does not end (libxml2 then says what is wrong). */
static const char *scan_skip_decl(const char *p, const char *end)
{
    int brackets = 0;
    while (p < end) {
        char c = *p;
        if (c == '"' || c == '\'') {
            p = memchr(p + 1, c, (size_t)(end - p - 1));
            if (!p)
                return NULL;
        } else if (c == '<' && end - p >= 4 && memcmp(p, "<!--", 4) == 0) {
            p = scan_find(p + 4, end, "-->", 3);
            if (!p)
                return NULL;
            p += 2;
        } else if (c == '<' && end - p >= 2 && p[1] == '?') {
            /* a processing instruction: its text may hold a lone quote */
            p = scan_find(p + 2, end, "?>", 2);
            if (!p)
                return NULL;
            p++;
        } else if (c == '[') {
            brackets++;
        } else if (c == ']') {
            brackets--;
        } else if (c == '>' && brackets <= 0) {
            return p + 1;
        }
        p++;
    }
    return NULL;
}

/* At p, just after a '<': past the comment, CDATA section, DOCTYPE or
 * processing instruction that starts there (NULL when it does not end), or
 * p itself when none does. */
static const char *scan_skip_markup(const char *p, const char *end)
{
    if (*p == '!') {
        if (end - p >= 3 && memcmp(p, "!--", 3) == 0)
            return scan_find(p + 3, end, "-->", 3);
        if (end - p >= 8 && memcmp(p, "![CDATA[", 8) == 0)
            return scan_find(p + 8, end, "]]>", 3);
        return scan_skip_decl(p + 1, end);
    }
    if (*p == '?')
        return scan_find(p + 1, end, "?>", 2);
    return p;
}

/* Line of byte `at` of buf (1-based). */
static size_t scan_line(const char *buf, const char *at)
{
    const char *q;
    size_t line = 1;
    for (q = buf; (q = memchr(q, '\n', (size_t)(at - q))) != NULL; q++)
        line++;
    return line;
}

/* Elements that declare namespaces, innermost last: what is in scope. */
typedef struct scan_scope {
    size_t depth; /* nesting depth of the element */
    size_t count; /* its declarations */
} scan_scope;

/* Count the attributes of every start tag and the namespace declarations
 * in scope at it, in one linear pass, and refuse the first element over a
 * cap before libxml2 parses anything. libxml2 appends each attribute by
 * walking the element's list and checks it against all earlier ones
 * (quadratic in the attributes of one element: 10^5 on a <path> took 17 s
 * to minutes), and looks every prefix up through all declarations in scope
 * (255 nested <g> with 64 declarations each made every element below cost
 * 0.3 ms: minutes for a large document). Comments, CDATA sections,
 * processing instructions and the DOCTYPE are skipped; a construct that
 * does not end stops the scan without a verdict (libxml2 reports it).
 * Returns 0, or 1 with ls filled. */
static int scan_start_tags(const char *buf, size_t len, const conica_svg_limits *lim,
                           load_state *ls)
{
    const char *p = buf, *end = buf + len;
    scan_scope *scope = NULL;
    size_t nscope = 0, cap = 0, depth = 0, in_scope = 0;
    int verdict = 0;
    while (!verdict && p < end && (p = memchr(p, '<', (size_t)(end - p))) != NULL) {
        const char *tag = p, *name, *q;
        size_t natt = 0, nns = 0, nlen;
        p++;
        if (p == end)
            break;
        if ((q = scan_skip_markup(p, end)) != p) {
            if (!q)
                break;
            p = q;
            continue;
        }
        if (*p == '/') {
            /* an end tag holds no quotes: the next '<' is past it */
            if (nscope && scope[nscope - 1].depth == depth)
                in_scope -= scope[--nscope].count;
            if (depth)
                depth--;
            continue;
        }
        name = p;
        while (p < end && !scan_space(*p) && *p != '>' && *p != '/')
            p++;
        nlen = (size_t)(p - name);
        if (nlen > 64)
            nlen = 64;
        for (;;) {
            const char *an;
            int is_ns;
            while (p < end && scan_space(*p))
                p++;
            if (p == end)
                goto out;
            if (*p == '>' || *p == '/')
                break;
            /* not an attribute (libxml2 reports it): on to the next tag */
            an = p;
            while (p < end && *p != '=' && !scan_space(*p) && *p != '>' && *p != '/')
                p++;
            /* xmlns="..." or xmlns:prefix="..." declares a namespace */
            is_ns = p - an >= 5 && memcmp(an, "xmlns", 5) == 0 && (p - an == 5 || an[5] == ':');
            while (p < end && scan_space(*p))
                p++;
            if (p == end || *p != '=')
                break;
            p++;
            while (p < end && scan_space(*p))
                p++;
            if (p == end || (*p != '"' && *p != '\''))
                break;
            p = memchr(p + 1, *p, (size_t)(end - p - 1));
            if (!p)
                goto out; /* an attribute value that never ends */
            p++;
            if (is_ns ? in_scope + ++nns > lim->max_namespaces : ++natt > lim->max_attributes) {
                if (is_ns)
                    snprintf(ls->why, sizeof ls->why,
                             "element <%.*s> has more than %zu namespace declarations in scope "
                             "(--max-namespaces)",
                             (int)nlen, name, lim->max_namespaces);
                else
                    snprintf(ls->why, sizeof ls->why,
                             "element <%.*s> has more than %zu attributes (--max-attributes)",
                             (int)nlen, name, lim->max_attributes);
                ls->code = CONICA_ERR_LIMIT;
                verdict = 1;
                break;
            }
        }
        if (verdict) {
            ls->line = scan_line(buf, tag);
            break;
        }
        if (p == end || (*p != '>' && *p != '/'))
            continue; /* a malformed tag: counted so far, opens no scope */
        if (*p == '/')
            continue; /* <x/>: opens no scope */
        depth++;
        if (nns) {
            if (nscope == cap) {
                size_t nc = cap ? 2 * cap : 16;
                scan_scope *t = realloc(scope, nc * sizeof *t);
                if (!t) {
                    snprintf(ls->why, sizeof ls->why, "out of memory");
                    ls->code = CONICA_ERR_NOMEM;
                    ls->line = 0;
                    verdict = 1;
                    break;
                }
                scope = t;
                cap = nc;
            }
            scope[nscope].depth = depth;
            scope[nscope++].count = nns;
            in_scope += nns;
        }
    }
out:
    free(scope);
    if (verdict)
        ls->refused = 1;
    return verdict;
}

/* doc_load() on UTF-8 bytes; `converted`: they were converted from the
 * encoding the declaration names, which libxml2 must then not switch to. */
static conica_code doc_parse(const char *buf, size_t len, const conica_svg_limits *lim,
                             conica_svg_doc **out, char *take, int converted, conica_status *st)
{
    conica_svg_limits def = conica_svg_limits_defaults();
    xmlParserCtxtPtr ctxt;
    xmlDocPtr xml;
    load_state ls;
    conica_svg_doc *doc;
    xmlNodePtr root;
    size_t i;
    int opts = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES;
    int huge;

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
    /* XML_PARSE_HUGE always: libxml2's own caps on one text node,
     * attribute value or name (10 MB, 50 kB; 1 GB with it) and on nesting
     * (256; 2048 with it) give way to ours, so a single path of 10^6
     * vertices (a 12 MB d) can be read. What it lets through stays bounded:
     * the document by lim->max_bytes, depth and elements by our own counts
     * in start_element(), entities by entity_decl() (none that can expand,
     * and none substituted), path data by lim->max_path_bytes, the
     * attributes and namespaces of an element by scan_start_tags(). */
    memset(&ls, 0, sizeof ls);
    if (len && scan_start_tags(buf, len, lim, &ls))
        return conica__fail(st, ls.code, ls.line, 0, "%s", ls.why);
    huge = 1;
    opts |= XML_PARSE_HUGE;
    if (converted)
        opts |= XML_PARSE_IGNORE_ENC;
    /* The push parser (it takes the SAX hooks below), fed the first bytes
     * (encoding detection) and then everything else in one call: fed in
     * chunks, it re-scanned an unfinished start tag from its beginning at
     * every chunk, quadratic in one long attribute value (16.5 s for a
     * 12 MB d in 64 KiB chunks, 70 % of it in xmlParseChunk). */
    {
        size_t first = len < 4 ? len : 4;
        ctxt = xmlCreatePushParserCtxt(NULL, NULL, buf, (int)first, NULL);
        if (!ctxt)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        xmlCtxtUseOptions(ctxt, opts);
        memset(&ls, 0, sizeof ls);
        ls.lim = lim;
        ctxt->_private = &ls;
        ctxt->sax->serror = xml_error; /* called with ctxt->userData, the context */
        ctxt->sax->entityDecl = entity_decl;
        ls.start = ctxt->sax->startElementNs;
        ls.end = ctxt->sax->endElementNs;
        ctxt->sax->startElementNs = start_element;
        ctxt->sax->endElementNs = end_element;
        xmlParseChunk(ctxt, buf + first, (int)(len - first), 1);
        xml = ctxt->myDoc;
        ctxt->myDoc = NULL;
    }
    if (ls.refused) {
        xmlFreeDoc(xml);
        xmlFreeParserCtxt(ctxt);
        return conica__fail(st, ls.code, ls.line, 0, "%s", ls.why);
    }
    if (!xml || !ctxt->wellFormed || ls.xml_errors) {
        const xmlError *e = xmlCtxtGetLastError(ctxt);
        char msg[200], text[400];
        size_t line = e ? (size_t)(e->line > 0 ? e->line : 0) : 0;
        int no_root = !xml || !xmlDocGetRootElement(xml);
        conica_code code = CONICA_ERR_PARSE;
        if (ls.xml_errors) {
            /* the first error names the cause; later ones follow from it */
            snprintf(msg, sizeof msg, "%s", ls.xml_msg);
            line = ls.xml_line;
            /* libxml2 files "huge text node" under XML_ERR_NO_MEMORY too */
            if (ls.xml_code == XML_ERR_NO_MEMORY && !strstr(msg, "huge"))
                code = CONICA_ERR_NOMEM;
        } else {
            snprintf(msg, sizeof msg, "%s", e && e->message ? e->message : "not well-formed XML");
        }
        trim_newline(msg);
        if (no_root) {
            /* libxml2 says "Extra content at the end of the document" for
             * an empty file and "Document is empty" for text: say what is
             * wrong for an SVG reader */
            size_t k = len >= 3 && (unsigned char)buf[0] == 0xEF &&
                               (unsigned char)buf[1] == 0xBB && (unsigned char)buf[2] == 0xBF
                           ? 3
                           : 0;
            while (k < len && (buf[k] == ' ' || buf[k] == '\t' || buf[k] == '\r' ||
                               buf[k] == '\n'))
                k++;
            if (k == len)
                snprintf(text, sizeof text, "XML: empty document: no <svg> element");
            else if (buf[k] != '<')
                snprintf(text, sizeof text,
                         "XML: %s: the file does not start with '<', it is not XML "
                         "(no <svg> element)", msg);
            else
                snprintf(text, sizeof text, "XML: no <svg> element (%s)", msg);
        } else if (ls.xml_errors && ls.xml_domain == XML_FROM_NAMESPACE) {
            snprintf(text, sizeof text, "XML: namespace error (libxml2: %s)", msg);
        } else {
            explain_xml_error(msg, huge, text, sizeof text);
        }
        if (ls.xml_errors > 1) {
            size_t k = strlen(text);
            snprintf(text + k, sizeof text - k, " (and %zu more XML error%s after it)",
                     ls.xml_errors - 1, ls.xml_errors > 2 ? "s" : "");
        }
        xmlFreeDoc(xml);
        xmlFreeParserCtxt(ctxt);
        return conica__fail(st, code, line, 0, "%s", text);
    }
    xmlFreeParserCtxt(ctxt);
    root = xmlDocGetRootElement(xml);
    if (!root || xmlStrcmp(root->name, BAD_CAST "svg") != 0) {
        size_t line = root ? (size_t)xmlGetLineNo(root) : 1;
        xmlFreeDoc(xml);
        return conica__fail(st, CONICA_ERR_PARSE, line, 0, "the root element is not <svg>");
    }
    doc = malloc(sizeof *doc);
    if (!doc) {
        xmlFreeDoc(xml);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    doc->xml = xml;
    doc->rewritten = 0;
    doc->src = take ? take : malloc(len ? len : 1);
    if (!doc->src) {
        xmlFreeDoc(xml);
        free(doc);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    if (len && !take)
        memcpy(doc->src, buf, len);
    doc->srclen = len;
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

/* conica_svg_doc_load(); with `take` (== buf) the document keeps buf
 * itself instead of a copy once the load succeeded. A document in another
 * encoding than UTF-8 is parsed, scanned for the caps and spliced as its
 * UTF-8 form (the caps count what the document holds, not its bytes: a
 * UTF-16 document's attributes like its UTF-8 twin's) and saved back in
 * its own encoding (svg_encoding.h). */
static conica_code doc_load(const char *buf, size_t len, const conica_svg_limits *lim,
                            conica_svg_doc **out, char *take, conica_status *st)
{
    conica_svg_limits def = conica_svg_limits_defaults();
    conica_svg__enc enc;
    char *u8 = NULL, why[256];
    size_t u8len = 0, line = 0;
    int nomem = 0;
    conica_code rc;
    if ((!buf && len) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_load: NULL argument");
    if (!lim)
        lim = &def;
    if (len > lim->max_bytes) /* before any conversion */
        return doc_parse(buf, len, lim, out, take, 0, st);
    if (conica_svg__enc_decode(buf, len, lim->max_bytes, &enc, &u8, &u8len, why, sizeof why,
                               &line, &nomem))
        return conica__fail(st,
                            nomem ? CONICA_ERR_NOMEM
                                  : strstr(why, "larger than the limit") ? CONICA_ERR_LIMIT
                                                                          : CONICA_ERR_PARSE,
                            line, 0, "%s", why);
    if (!u8) {
        rc = doc_parse(buf, len, lim, out, take, 0, st);
        if (rc == CONICA_OK)
            (*out)->enc = enc;
        return rc;
    }
    rc = doc_parse(u8, u8len, lim, out, u8, 1, st);
    if (rc != CONICA_OK) {
        free(u8);
        return rc;
    }
    (*out)->enc = enc;
    free(take); /* the document keeps its UTF-8 form instead */
    return CONICA_OK;
}

conica_code conica_svg_doc_load(const char *buf, size_t len, const conica_svg_limits *lim,
                                conica_svg_doc **out, conica_status *st)
{
    return doc_load(buf, len, lim, out, NULL, st);
}

conica_code conica_svg_doc_load_owned(char *buf, size_t len, const conica_svg_limits *lim,
                                      conica_svg_doc **out, conica_status *st)
{
    return doc_load(buf, len, lim, out, buf, st);
}

void conica_svg_doc_free(conica_svg_doc *doc)
{
    if (!doc)
        return;
    xmlFreeDoc(doc->xml);
    free(doc->src);
    free(doc);
}

/* Where the serialiser writes: straight into our buffer (no intermediate
 * xmlBuffer and no copy afterwards). While `skip_decl`, libxml2's own XML
 * declaration is dropped up to its "?>": the input's is already there. */
typedef struct save_sink {
    conica_svg__buf b; /* into memory, or */
    FILE *f;           /* into a file */
    int failed;        /* out of memory or a write error */
    char why[96];      /* "write error: <strerror>" once a write failed */
    int skip_decl;
    char last;     /* previous byte while skipping ("?>" may straddle two writes) */
    char last_out; /* last byte written (the file ends with a newline) */
    conica_svg__encoder enc; /* UTF-8 to the document's encoding */
    int enc_failed;          /* a character the encoding cannot hold */
} save_sink;

/* Bytes in the document's encoding to the file or the buffer. */
static void sink_raw(void *ctx, const char *data, size_t n)
{
    save_sink *k = ctx;
    if (!n || k->failed)
        return;
    if (k->f) {
        if (fwrite(data, 1, n, k->f) != n) {
            k->failed = 1;
            snprintf(k->why, sizeof k->why, "write error: %s", strerror(errno));
        }
    } else {
        conica_svg__buf_put(&k->b, data, n);
        k->failed = k->b.oom;
    }
}

static void sink_put(save_sink *k, const char *data, size_t n)
{
    if (!n || k->failed)
        return;
    if (conica_svg__encoder_put(&k->enc, data, n, sink_raw, k) != 0)
        k->failed = k->enc_failed = 1;
    k->last_out = data[n - 1];
}

/* The write error with its reason, for messages ("write error: No space
 * left on device": the output and the reason, issue 33). */
static const char *sink_why(const save_sink *k)
{
    return k->why[0] ? k->why : "write error";
}

/* A sink into f (NULL: memory) for doc: its byte-order mark first, then
 * everything through the encoder. Returns 0, or 1 with st filled. */
static int sink_begin(save_sink *k, const conica_svg_doc *doc, FILE *f, conica_status *st)
{
    memset(k, 0, sizeof *k);
    k->f = f;
    if (conica_svg__encoder_open(&k->enc, &doc->enc) != 0) {
        conica__fail(st, CONICA_ERR_UNSUPPORTED, 0, 0,
                     "cannot write the document's encoding '%s'", doc->enc.name);
        return 1;
    }
    sink_raw(k, (const char *)doc->enc.bom, doc->enc.bomlen);
    return 0;
}

/* The end of a save: a stateful encoding's final shift; rc as it was, or
 * the write error. */
static conica_code sink_end(save_sink *k, const conica_svg_doc *doc, conica_code rc,
                            conica_status *st)
{
    if (rc == CONICA_OK && !k->failed &&
        conica_svg__encoder_put(&k->enc, NULL, 0, sink_raw, k) != 0)
        k->failed = k->enc_failed = 1;
    if (rc == CONICA_OK && k->failed)
        rc = conica__fail(st, CONICA_ERR_IO, 0, 0, "%s",
                          k->enc_failed ? "a character the document's encoding cannot hold"
                          : k->f        ? sink_why(k)
                                        : "out of memory");
    (void)doc;
    conica_svg__encoder_close(&k->enc);
    return rc;
}

static int save_write(void *ctx, const char *data, int len)
{
    save_sink *k = ctx;
    size_t i = 0, n = len > 0 ? (size_t)len : 0;
    while (k->skip_decl && i < n) {
        char c = data[i++];
        if (k->last == '?' && c == '>')
            k->skip_decl = 0;
        k->last = c;
    }
    sink_put(k, data + i, n - i);
    return k->failed ? -1 : len;
}

static int save_close(void *ctx)
{
    (void)ctx;
    return 0;
}

/* ------------------------------------------------------------ byte-true save */

/* One attribute of a start tag in the original bytes: from the white space
 * before its name to the byte after its closing quote. */
typedef struct src_attr {
    const char *lead;  /* the white space before the name */
    const char *name;
    size_t nlen;
    const char *val;   /* after the opening quote */
    size_t vlen;
    char quote;
} src_attr;

/* The next attribute of a start tag at *p (after the name or the previous
 * attribute): 1 with *a filled and *p past it, 0 at the tag's end (*p at
 * '/' or '>'), -1 when the bytes are not what the parser accepted. */
static int src_next_attr(const char **p, const char *end, src_attr *a)
{
    const char *q = *p;
    a->lead = q;
    while (q < end && scan_space(*q))
        q++;
    if (q == end)
        return -1;
    if (*q == '>' || *q == '/') {
        *p = q;
        return 0;
    }
    if (q == a->lead)
        return -1; /* attributes are separated by white space */
    a->name = q;
    while (q < end && *q != '=' && !scan_space(*q) && *q != '>' && *q != '/')
        q++;
    a->nlen = (size_t)(q - a->name);
    while (q < end && scan_space(*q))
        q++;
    if (q == end || *q != '=' || a->nlen == 0)
        return -1;
    q++;
    while (q < end && scan_space(*q))
        q++;
    if (q == end || (*q != '"' && *q != '\''))
        return -1;
    a->quote = *q;
    a->val = q + 1;
    q = memchr(q + 1, a->quote, (size_t)(end - q - 1));
    if (!q)
        return -1;
    a->vlen = (size_t)(q - a->val);
    *p = q + 1;
    return 1;
}

/* The element's own attribute `name` (not a default declared in a DTD,
 * which xmlHasNsProp() also returns), or NULL. */
static xmlAttrPtr own_attr(xmlNodePtr n, const char *name)
{
    xmlAttrPtr a = xmlHasNsProp(n, BAD_CAST name, NULL);
    return a && a->type == XML_ATTRIBUTE_NODE ? a : NULL;
}

/* conica_svg_process() marks each element whose geometry attribute it
 * rewrote in the node's application field (_private): 1 `d`, 2 `points`,
 * 3 `d` of a shape it converted to a path. */
static void mark_rewritten(xmlNodePtr n, int kind)
{
    n->_private = (void *)(uintptr_t)(kind == 1 || kind == 2 ? 2u : kind == 3 ? 3u : 1u);
}

static const char *mark_name(xmlNodePtr n)
{
    return (uintptr_t)n->_private == 2u ? "points" : "d";
}

/* The geometry attributes a shape converted to a path loses (SVG 2,
 * sections 10.2-10.6). */
static const char *const shape_geometry[] = {"x",  "y",  "width", "height", "rx", "ry", "cx",
                                             "cy", "r",  "x1",    "y1",     "x2", "y2"};

static int is_shape_geometry(const char *name, size_t n)
{
    size_t i;
    for (i = 0; i < sizeof shape_geometry / sizeof shape_geometry[0]; i++)
        if (strlen(shape_geometry[i]) == n && memcmp(shape_geometry[i], name, n) == 0)
            return 1;
    return 0;
}

/* Does the n-byte qualified name s name element or attribute node x? */
static int same_qname(const char *s, size_t n, const xmlChar *prefix, const xmlChar *name)
{
    size_t pl = prefix ? strlen((const char *)prefix) : 0, nl = strlen((const char *)name);
    if (pl)
        return n == pl + 1 + nl && memcmp(s, prefix, pl) == 0 && s[pl] == ':' &&
               memcmp(s + pl + 1, name, nl) == 0;
    return n == nl && memcmp(s, name, nl) == 0;
}

/* "path" with the element's namespace prefix, as written in its tags. */
static void put_path_name(save_sink *k, xmlNodePtr n)
{
    const xmlChar *prefix = n->ns ? n->ns->prefix : NULL;
    if (prefix) {
        sink_put(k, (const char *)prefix, strlen((const char *)prefix));
        sink_put(k, ":", 1);
    }
    sink_put(k, "path", 4);
}

/* A rewritten value with the entity rules of its quote. */
static void put_escaped(save_sink *k, const char *v, char quote)
{
    for (;;) {
        /* runs free of the five characters that may need an entity at once
         * (path data has none of them) */
        size_t run = strcspn(v, "&<>\"'");
        const char *ent;
        sink_put(k, v, run);
        v += run;
        if (!*v)
            return;
        ent = *v == '&'                   ? "&amp;"
              : *v == '<'                 ? "&lt;"
              : *v == '>'                 ? "&gt;"
              : *v == quote && *v == '"'  ? "&quot;"
              : *v == quote && *v == '\'' ? "&apos;"
                                          : NULL;
        if (ent)
            sink_put(k, ent, strlen(ent));
        else
            sink_put(k, v, 1);
        v++;
    }
}

/* The rewritten value of attribute `name` of n (its single text child, as
 * conica_svg_process() left it), or NULL. */
static const char *new_value(xmlNodePtr n, const char *name)
{
    xmlAttrPtr a = xmlHasNsProp(n, BAD_CAST name, NULL);
    if (!a || a->type != XML_ATTRIBUTE_NODE || !a->children || a->children != a->last ||
        a->children->type != XML_TEXT_NODE || !a->children->content)
        return NULL;
    return (const char *)a->children->content;
}

/* How one start tag changes: attribute `mark` takes `value` (appended when
 * the tag has none); a converted shape is renamed to a path and loses its
 * geometry attributes. */
typedef struct rewrite {
    const char *mark;
    const char *value;
    int shape;
} rewrite;

/* Write the start tag of element n as rw changes it: every byte outside
 * what changed as it was. name..*p is its name in the bytes; returns 0
 * when the bytes after it are not attributes. */
static int splice_tag(save_sink *k, xmlNodePtr n, const rewrite *rw, const char *name,
                      const char **p, const char *end)
{
    const char *cur;
    size_t ml = strlen(rw->mark);
    src_attr a;
    int r, seen = 0;
    if (k) {
        if (rw->shape)
            put_path_name(k, n);
        else
            sink_put(k, name, (size_t)(*p - name));
    }
    cur = *p;
    while ((r = src_next_attr(p, end, &a)) == 1) {
        if (a.nlen == ml && memcmp(a.name, rw->mark, ml) == 0) {
            if (k) {
                sink_put(k, cur, (size_t)(a.val - cur));
                put_escaped(k, rw->value, a.quote);
            }
            cur = a.val + a.vlen;
            seen = 1;
        } else if (rw->shape && is_shape_geometry(a.name, a.nlen)) {
            if (k)
                sink_put(k, cur, (size_t)(a.lead - cur));
            cur = *p;
        }
    }
    if (r < 0)
        return 0;
    if (k) {
        sink_put(k, cur, (size_t)(*p - cur));
        if (!seen) { /* a new attribute goes last, before the tag's end */
            sink_put(k, " ", 1);
            sink_put(k, rw->mark, ml);
            sink_put(k, "=\"", 2);
            put_escaped(k, rw->value, '"');
            sink_put(k, "\"", 1);
        }
    }
    return 1;
}

/* An element whose start tag the splicer has passed and whose end tag it
 * has not: that end tag must name it (a converted shape's is renamed). */
typedef struct open_tag {
    xmlNodePtr n;
    int shape;
} open_tag;

/* Writes the original bytes with rewritten attribute values spliced in,
 * element by element: the start tags of the bytes (a scan that skips
 * comments, CDATA, processing instructions and the DOCTYPE, as
 * scan_start_tags() does) are matched in order to the tree's elements, by
 * name. It can stop after any element's start tag and go on later, so
 * that conica_svg_process_write() writes each element as it is made. With
 * k NULL nothing is written, only matched. */
typedef struct splicer {
    save_sink *k;
    int from_tree; /* the rewrites are those conica_svg_process() marked */
    const char *p, *end, *cur; /* scan position; bytes before cur are written */
    xmlNodePtr root, n;        /* the tree's element of the last start tag */
    open_tag *open;
    size_t depth, cap, tdepth;
    int ok; /* 0 once the bytes and the tree do not match */
} splicer;

static void splicer_init(splicer *sp, const conica_svg_doc *doc, save_sink *k, int from_tree)
{
    memset(sp, 0, sizeof *sp);
    sp->k = k;
    sp->from_tree = from_tree;
    sp->p = sp->cur = doc->src;
    sp->end = doc->src + doc->srclen;
    sp->root = xmlDocGetRootElement(doc->xml);
    /* UTF-16 and other encodings this byte scan cannot read */
    sp->ok = sp->root && !memchr(doc->src, '\0', doc->srclen);
}

/* Go on to the start tag of `stop` and write it as *stop_rw changes it
 * (the rewrites marked in the tree apply on the way when from_tree), or
 * with stop NULL to the end of the bytes. Returns 1 when stop's tag was
 * written. */
static int splice_until(splicer *sp, xmlNodePtr stop, const rewrite *stop_rw)
{
    save_sink *k = sp->k;
    const char *p = sp->p, *end = sp->end;
    int hit = 0;
    while (sp->ok && !hit && p < end) {
        const char *name, *q;
        const rewrite *r = NULL;
        rewrite rw;
        xmlNodePtr n;
        size_t nlen;
        if ((q = memchr(p, '<', (size_t)(end - p))) == NULL) {
            p = end;
            break;
        }
        p = q + 1;
        if (p == end)
            break;
        if ((q = scan_skip_markup(p, end)) != p) {
            if (!q)
                sp->ok = 0;
            else
                p = q;
            continue;
        }
        if (*p == '/') {
            open_tag *e;
            p++;
            if (!sp->depth) {
                sp->ok = 0;
                break;
            }
            name = p;
            while (p < end && !scan_space(*p) && *p != '>')
                p++;
            e = &sp->open[--sp->depth];
            if (e->shape) {
                if (k) {
                    sink_put(k, sp->cur, (size_t)(name - sp->cur));
                    put_path_name(k, e->n);
                }
                sp->cur = p;
            } else if (!same_qname(name, (size_t)(p - name), e->n->ns ? e->n->ns->prefix : NULL,
                                   e->n->name)) {
                sp->ok = 0;
            }
            continue;
        }
        name = p;
        while (p < end && !scan_space(*p) && *p != '>' && *p != '/')
            p++;
        nlen = (size_t)(p - name);
        n = sp->n ? next_element(sp->n, sp->root, &sp->tdepth) : sp->root;
        if (!n) {
            sp->ok = 0;
            break;
        }
        sp->n = n;
        if (sp->depth == sp->cap) {
            size_t nc = sp->cap ? 2 * sp->cap : 64;
            open_tag *t = realloc(sp->open, nc * sizeof *t);
            if (!t) {
                sp->ok = 0;
                break;
            }
            sp->open = t;
            sp->cap = nc;
        }
        if (n == stop) {
            r = stop_rw;
            hit = 1;
        } else if (sp->from_tree && n->_private) {
            rw.mark = mark_name(n);
            rw.value = new_value(n, rw.mark);
            rw.shape = (uintptr_t)n->_private == 3u;
            if (!rw.value) {
                sp->ok = 0;
                break;
            }
            r = &rw;
        }
        /* (a converted shape's tree name may already be "path") */
        if (!(r && r->shape) &&
            !same_qname(name, nlen, n->ns ? n->ns->prefix : NULL, n->name)) {
            sp->ok = 0;
            break;
        }
        sp->open[sp->depth].n = n;
        sp->open[sp->depth].shape = r && r->shape;
        if (r) {
            if (k)
                sink_put(k, sp->cur, (size_t)(name - sp->cur));
            if (!splice_tag(k, n, r, name, &p, end)) {
                sp->ok = 0;
                break;
            }
            sp->cur = p;
        } else {
            src_attr a;
            int ra;
            while ((ra = src_next_attr(&p, end, &a)) == 1)
                ;
            if (ra < 0) {
                sp->ok = 0;
                break;
            }
        }
        if (*p != '/')
            sp->depth++;
    }
    sp->p = p;
    return sp->ok && hit;
}

/* The rest of the bytes; 1 when the whole document matched the tree. */
static int splice_finish(splicer *sp)
{
    splice_until(sp, NULL, NULL);
    if (sp->ok && (sp->depth != 0 ||
                   (sp->n ? next_element(sp->n, sp->root, &sp->tdepth) : sp->root) != NULL))
        sp->ok = 0; /* the tree holds elements the bytes do not */
    if (sp->ok && sp->k)
        sink_put(sp->k, sp->cur, (size_t)(sp->end - sp->cur));
    free(sp->open);
    sp->open = NULL;
    return sp->ok;
}

/* The whole document in one go (k NULL: 1 when the bytes and the tree
 * match, so that a second call with k writes all of it). */
static int splice(const conica_svg_doc *doc, save_sink *k, int from_tree)
{
    splicer sp;
    splicer_init(&sp, doc, k, from_tree);
    return splice_finish(&sp);
}

/* Serialise into k (memory or file): the input's declaration, the tree,
 * a final newline. */
static conica_code save_to(const conica_svg_doc *doc, save_sink *k, conica_status *st)
{
    xmlSaveCtxtPtr sc;
    int opts = doc->decl[0] ? 0 : XML_SAVE_NO_DECL;
    long r;
    /* byte for byte as read, the rewritten values spliced in */
    if (splice(doc, NULL, 1)) {
        splice(doc, k, 1);
        if (k->failed)
            return conica__fail(st, k->f ? CONICA_ERR_IO : CONICA_ERR_NOMEM, 0, 0,
                                "%s", k->f ? sink_why(k) : "out of memory");
        return CONICA_OK;
    }
    /* the input's declaration verbatim in place of libxml2's */
    sink_put(k, doc->decl, strlen(doc->decl));
    k->skip_decl = doc->decl[0] != '\0';
    /* no declared encoding means UTF-8: keep non-ASCII text as it was
     * instead of turning it into character references */
    sc = xmlSaveToIO(save_write, save_close, k,
                     doc->xml->encoding && !doc->enc.name[0] ? (const char *)doc->xml->encoding
                                                             : "UTF-8",
                     opts);
    if (!sc)
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "cannot serialise the document");
    r = xmlSaveDoc(sc, doc->xml);
    if (xmlSaveClose(sc) < 0 || r < 0 || k->failed) {
        if (k->f && k->failed)
            return conica__fail(st, CONICA_ERR_IO, 0, 0, "%s", sink_why(k));
        if (k->failed)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "cannot serialise the document");
    }
    /* end the file with a newline, as nearly every input does */
    if (k->last_out != '\n')
        sink_put(k, "\n", 1);
    if (k->failed)
        return conica__fail(st, k->f ? CONICA_ERR_IO : CONICA_ERR_NOMEM, 0, 0,
                            "%s", k->f ? sink_why(k) : "out of memory");
    return CONICA_OK;
}

conica_code conica_svg_doc_save(const conica_svg_doc *doc, char **buf, size_t *len,
                                conica_status *st)
{
    save_sink k;
    conica_code rc;
    if (!doc || !buf || !len)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_save: NULL argument");
    if (sink_begin(&k, doc, NULL, st))
        return CONICA_ERR_UNSUPPORTED;
    rc = sink_end(&k, doc, save_to(doc, &k, st), st);
    if (rc != CONICA_OK) {
        free(k.b.s);
        return rc;
    }
    if (!k.b.s) { /* nothing was written: an empty string */
        conica_svg__buf_put(&k.b, "", 0);
        if (k.b.oom)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    *buf = k.b.s;
    *len = k.b.n;
    return CONICA_OK;
}

conica_code conica_svg_doc_write(const conica_svg_doc *doc, FILE *f, conica_status *st)
{
    save_sink k;
    if (!doc || !f)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_doc_write: NULL argument");
    if (sink_begin(&k, doc, f, st))
        return CONICA_ERR_UNSUPPORTED;
    return sink_end(&k, doc, save_to(doc, &k, st), st);
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

/* As get_attr_cap(), without a copy in the common case of a value that
 * is one text node (no entity reference): *owned is then NULL and the
 * result points into the tree; otherwise *owned is the result (free it
 * with xmlFree()). */
static const char *get_attr_view(xmlNodePtr n, const char *name, size_t cap, int *too_long,
                                 char **owned)
{
    xmlAttrPtr a = xmlHasNsProp(n, BAD_CAST name, NULL);
    *owned = NULL;
    *too_long = 0;
    if (a && a->type == XML_ATTRIBUTE_NODE && a->children && !a->children->next &&
        a->children->type == XML_TEXT_NODE && a->children->content) {
        if (strlen((const char *)a->children->content) > cap) {
            *too_long = 1;
            return NULL;
        }
        return (const char *)a->children->content;
    }
    *owned = get_attr_cap(n, name, cap, too_long);
    return *owned;
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

/* A CSS length: number and unit; 1 on success, 2 when the number is not
 * finite (NaN, Inf, beyond DBL_MAX), 0 otherwise. */
static int parse_length(const char *s, double *v, char unit[4])
{
    size_t k = s ? read_num(s, v) : 0, u = 0;
    if (!k) {
        size_t used = 0;
        double x;
        while (s && (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r'))
            s++;
        return s && conica__parse_double(s, strlen(s), &x, &used) == CONICA__NUM_NONFINITE ? 2
                                                                                       : 0;
    }
    s += k;
    while (u < 3 && ((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '%'))
        unit[u++] = *s++;
    unit[u] = '\0';
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
        s++;
    return *s == '\0';
}

/* CSS absolute units as exact fractions of a millimetre (CSS Values 4,
 * section 6.2: 1in = 2.54cm = 25.4mm = 96px = 72pt = 6pc, 1Q = 0.25mm). */
typedef struct css_unit {
    const char *name;
    long num, den; /* 1 unit = num/den mm */
} css_unit;

static const css_unit *find_unit(const char *u)
{
    static const css_unit units[] = {
        {"", 254, 960},  {"px", 254, 960}, {"mm", 1, 1},    {"cm", 10, 1},
        {"in", 254, 10}, {"pt", 254, 720}, {"pc", 254, 60}, {"Q", 1, 4},
    };
    size_t i;
    for (i = 0; u && i < sizeof units / sizeof units[0]; i++)
        if (!strcmp(u, units[i].name))
            return &units[i];
    return NULL;
}

static long gcd_long(long a, long b)
{
    while (b) {
        long t = a % b;
        a = b;
        b = t;
    }
    return a;
}

double conica_svg_convert_length(double v, const char *from, const char *to)
{
    const css_unit *f = find_unit(from), *t = find_unit(to);
    long num, den, g;
    if (!f || !t)
        return NAN;
    /* one exact fraction, reduced: the same unit (px and "") is the
     * identity, px -> in is v / 96, with at most two roundings otherwise */
    num = f->num * t->den;
    den = f->den * t->num;
    g = gcd_long(num, den);
    num /= g;
    den /= g;
    if (num == den)
        return v;
    if (num == 1)
        return v / (double)den;
    if (den == 1)
        return v * (double)num;
    return v * (double)num / (double)den;
}

static double unit_to_mm(double v, const char *u)
{
    return conica_svg_convert_length(v, u, "mm");
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

/* The render (svg_render.c, svg_style.c) reads the same tree the same way. */
xmlDocPtr conica_svg__doc_xml(const conica_svg_doc *doc)
{
    return doc->xml;
}

char *conica_svg__attr(xmlNodePtr n, const char *name, size_t cap, int *too_long)
{
    return get_attr_cap(n, name, cap, too_long);
}

xmlNodePtr conica_svg__next_element(xmlNodePtr n, xmlNodePtr root)
{
    size_t depth = 0;
    return next_element(n, root, &depth);
}

int conica_svg__is_svg(xmlNodePtr n)
{
    return is_svg_element(n);
}

/* ------------------------------------------------------------ shapes */

/* A user-space length attribute: number with no unit or px. 1 ok, 0 absent
 * (value untouched), -1 unusable (another unit, not a length), -3 not a
 * finite number (*bad = name). */
static int len_attr(xmlNodePtr n, const char *name, double *v, const char **bad)
{
    char unit[4];
    char *a = get_attr(n, name);
    int r;
    if (!a)
        return 0;
    r = parse_length(a, v, unit);
    r = r == 2 ? -3 : r && (!unit[0] || !strcmp(unit, "px")) ? 1 : -1;
    if (r == -3)
        *bad = name;
    xmlFree(a);
    return r;
}

/* rect/circle/ellipse/line as path segments (SVG 2, 10.2-10.5), from
 * attributes in user units. Returns 1 built, 0 nothing to draw, -1
 * unusable attributes, -2 no memory, -3 an attribute that is not a finite
 * number (*bad names it). */
static int shape_path(xmlNodePtr n, conica_svg_path *p, const char **bad)
{
    const char *tag = (const char *)n->name;
    const char *const *names = conica_svg__shape_attrs(tag);
    double v[6] = {0, 0, 0, 0, 0, 0};
    int given[6] = {0, 0, 0, 0, 0, 0}, i, r;
    if (!names)
        return 0;
    for (i = 0; i < 6 && names[i]; i++)
        if ((given[i] = len_attr(n, names[i], &v[i], bad)) < 0)
            return given[i];
    r = conica_svg__shape_path(tag, v, given, p);
    return r;
}

/* ------------------------------------------------------------ walk */

typedef struct item {
    xmlNodePtr node;
    int kind;   /* 0 path, 1 polygon, 2 polyline, 3 shape converted to a path */
} item;

/* The --select list, sorted for binary search, with a flag per entry set
 * when some element of the document carries that id. */
typedef struct selection {
    const char **ids; /* sorted, NULL entries dropped */
    unsigned char *found;
    size_t n;
} selection;

static int cmp_id(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* 0 on success, -1 out of memory. An empty selection (s->select NULL)
 * selects everything. */
static int selection_init(selection *sel, const conica_svg_settings *s)
{
    size_t i;
    memset(sel, 0, sizeof *sel);
    if (!s->select || !s->nselect)
        return 0;
    sel->ids = malloc(s->nselect * sizeof *sel->ids);
    sel->found = calloc(s->nselect, 1);
    if (!sel->ids || !sel->found) {
        free(sel->ids);
        free(sel->found);
        memset(sel, 0, sizeof *sel);
        return -1;
    }
    for (i = 0; i < s->nselect; i++)
        if (s->select[i])
            sel->ids[sel->n++] = s->select[i];
    qsort(sel->ids, sel->n, sizeof *sel->ids, cmp_id);
    return 0;
}

static void selection_free(selection *sel)
{
    free(sel->ids);
    free(sel->found);
}

/* Index of id in the sorted list, or -1. */
static long selection_find(const selection *sel, const char *id)
{
    size_t lo = 0, hi = sel->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        int c = strcmp(id, sel->ids[mid]);
        if (c == 0)
            return (long)mid;
        if (c < 0)
            hi = mid;
        else
            lo = mid + 1;
    }
    return -1;
}

/* Marks the id of element n as present in the document. */
static void selection_mark(selection *sel, xmlNodePtr n)
{
    char *id;
    long k;
    if (!sel->n)
        return;
    id = get_attr(n, "id");
    k = id ? selection_find(sel, id) : -1;
    if (k >= 0) {
        /* equal ids in the list share one flag: mark the whole run */
        size_t a = (size_t)k, b = (size_t)k;
        while (a > 0 && !strcmp(sel->ids[a - 1], id))
            a--;
        while (b + 1 < sel->n && !strcmp(sel->ids[b + 1], id))
            b++;
        memset(sel->found + a, 1, b - a + 1);
    }
    xmlFree(id);
}

/* Selected: the element's id or the id of an ancestor (a group or layer)
 * is in the list. */
static int selected(const conica_svg_settings *s, const selection *sel, xmlNodePtr n)
{
    if (!s->select)
        return 1;
    for (; n && n->type == XML_ELEMENT_NODE; n = n->parent) {
        char *id = get_attr(n, "id");
        int hit = id && selection_find(sel, id) >= 0;
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

void conica_svg__describe(xmlNodePtr n, char *what, size_t size)
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
    if (!(s->simplify >= 0.0) || !isfinite(s->simplify))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "simplify must be finite and >= 0");
    if (!(s->corner_angle_deg >= 0.0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "corner angle must be >= 0");
    if (s->precision < 0 || s->precision > 17)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "precision must be in 1..17 (0: from the tolerance)");
    return CONICA_OK;
}

/* Geometry of one element as segments, or for a polygon or polyline as
 * its points (*pts, malloc'd, *npts of them: no segments needed); 1 got
 * some, 0 nothing to do. */
static int element_path(const conica_svg_settings *s, xmlNodePtr n, int kind, const char *what,
                        conica_svg_path *p, double **pts, size_t *npts, double *precision,
                        conica_code *rc, conica_status *st)
{
    size_t line = (size_t)xmlGetLineNo(n);
    *rc = CONICA_OK;
    *precision = 0.0;
    if (kind == 0) {
        int too_long;
        char *owned;
        const char *d = get_attr_view(n, "d", s->limits.max_path_bytes, &too_long, &owned);
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
        *rc = conica_svg__path_parse_into(d, len, 0, p, st);
        *precision = conica_svg__text_precision(d, len);
        xmlFree(owned);
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
        char *owned;
        const char *a = get_attr_view(n, "points", s->limits.max_path_bytes, &too_long, &owned);
        double *xy = NULL;
        size_t np = 0, bad = 0, len;
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
        *precision = conica_svg__text_precision(a, len);
        xmlFree(owned);
        if (*rc != CONICA_OK)
            return 0;
        if (bad != (size_t)-1)
            warn(s, line, "%s: bad points list at byte %zu; %s", what, bad,
                 np ? "the valid pairs before it are kept" : "element left unchanged");
        if (!np) {
            free(xy);
            return 0;
        }
        *pts = xy;
        *npts = np;
        return 1;
    }
    {
        const char *bad = "";
        int r = shape_path(n, p, &bad);
        if (r == -3)
            warn(s, line, "%s: geometry attribute '%s' is not a finite number (NaN, Inf or "
                 "beyond +-1.8e308); left unchanged", what, bad);
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

/* settings.progress: bytes of geometry data (d, points) in the whole
 * document, done before the element at work, and that element's. */
typedef struct geom_progress {
    const conica_svg_settings *s;
    size_t total, base, len;
} geom_progress;

/* The bytes of n's geometry data: d of a path, points of a polygon or a
 * polyline (kind of geom_kind(); shapes count nothing). */
static size_t geom_bytes(xmlNodePtr n, int kind)
{
    xmlAttrPtr a;
    xmlNodePtr c;
    size_t len = 0;
    if (kind < 0 || kind > 2)
        return 0;
    a = xmlHasNsProp(n, BAD_CAST(kind == 0 ? "d" : "points"), NULL);
    if (!a || a->type != XML_ATTRIBUTE_NODE)
        return 0;
    for (c = a->children; c; c = c->next)
        if (c->type == XML_TEXT_NODE && c->content)
            len += (size_t)xmlStrlen(c->content);
    return len;
}

/* collect()'s kind of an element with geometry data: 0 path, 1 polygon,
 * 2 polyline; -1 for any other (a shape is 3 only with convert_shapes). */
static int geom_kind(xmlNodePtr n)
{
    const char *tag = (const char *)n->name;
    return !strcmp(tag, "path")       ? 0
           : !strcmp(tag, "polygon")  ? 1
           : !strcmp(tag, "polyline") ? 2
                                      : -1;
}

/* conica_path_settings.progress of one element: its segments done, as a
 * share of its bytes. */
static void element_progress(void *ctx, size_t done, size_t total)
{
    const geom_progress *g = ctx;
    size_t at = g->base;
    if (total > 0)
        at += (size_t)((double)g->len * ((double)done / (double)total));
    g->s->progress(g->s->progress_ctx, at < g->total ? at : g->total, g->total);
}

/* Called by collect() after each element's polylines (shapes->elements[idx]
 * and its subpaths), e.g. to write them out and free them at once. */
typedef conica_code (*element_done)(void *ctx, conica_svg_shapes *shapes, size_t idx,
                                    const item *it, conica_status *st);

/* Walk the selected elements, turning each into polylines in *shapes and
 * remembering the node in *items (parallel to shapes->elements); `done`
 * (may be NULL) is called after each element with `done_ctx`. With
 * `timing`, stats->io_seconds gets the walk and the path-data parsing and
 * stats->geometry_seconds the segments-to-polylines step (corners,
 * normals, subdivision or plotting), read from the CPU clock twice per
 * processed element: that clock is a system call (about 1.4 us here),
 * too slow to read per subpath or per curve. */
static conica_code collect(const conica_svg_doc *doc, const conica_svg_settings *s,
                           conica_svg_shapes *shapes, item **items, conica_svg_stats *stats,
                           int timing, element_done done, void *done_ctx, conica_status *st)
{
    xmlNodePtr root = xmlDocGetRootElement(doc->xml), n = root;
    size_t budget = s->limits.max_points, cap = 0, depth = 1;
    double mark = timing ? conica_svg__now() : 0.0;
    conica_code rc = CONICA_OK;
    conica_svg_path p;
    selection sel;
    geom_progress gp;
    conica_svg_path_init(&p);
    *items = NULL;
    memset(&gp, 0, sizeof gp);
    gp.s = s;
    if (s->progress) { /* the total first: one walk, no parsing */
        xmlNodePtr m = root;
        size_t d = 1;
        while (m) {
            if (is_svg_element(m))
                gp.total += geom_bytes(m, geom_kind(m));
            m = next_element(m, root, &d);
        }
        s->progress(s->progress_ctx, 0, gp.total);
    }
    if (selection_init(&sel, s) != 0)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    while (n && rc == CONICA_OK) {
        selection_mark(&sel, n);
        if (is_svg_element(n)) {
            const char *tag = (const char *)n->name;
            int kind = geom_kind(n);
            if (s->progress)
                gp.len = geom_bytes(n, kind);
            if (kind < 0 && s->convert_shapes &&
                (!strcmp(tag, "rect") || !strcmp(tag, "circle") || !strcmp(tag, "ellipse") ||
                 !strcmp(tag, "line")))
                kind = 3;
            if (kind >= 0 && selected(s, &sel, n)) {
                char what[96];
                double prec;
                conica_svg__describe(n, what, sizeof what);
                double *pts = NULL;
                size_t npts = 0;
                p.n = 0;
                p.has_error = 0;
                if (element_path(s, n, kind, what, &p, &pts, &npts, &prec, &rc, st)) {
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
                            free(pts);
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
                    if (timing) {
                        double t = conica_svg__now();
                        stats->io_seconds += t - mark;
                        mark = t;
                    }
                    if (pts)
                        rc = conica_svg__points_polylines(&pts, npts, kind, s, what, idx, prec,
                                                          &budget, &stats->in_vertices, shapes, st);
                    else
                        rc = conica_svg__path_polylines_progress(
                            &p, s, what, el->line, idx, kind, prec, &budget, &stats->in_vertices,
                            shapes, s->progress ? element_progress : NULL, &gp, st);
                    if (timing) {
                        double t = conica_svg__now();
                        stats->geometry_seconds += t - mark;
                        mark = t;
                    }
                    if (rc != CONICA_OK && st)
                        st->line = el->line;
                    el->nsubpaths = shapes->nsubpaths - first;
                    stats->elements++;
                    stats->subpaths += el->nsubpaths;
                    if (rc == CONICA_OK && done)
                        rc = done(done_ctx, shapes, idx, &(*items)[idx], st);
                }
            }
        }
        if (s->progress && gp.len) {
            gp.base += gp.len;
            gp.len = 0;
            s->progress(s->progress_ctx, gp.base < gp.total ? gp.base : gp.total, gp.total);
        }
        n = next_element(n, root, &depth);
    }
    /* an id that names no element is most likely a typo: say so (the run
     * itself succeeds, as a selection that matches nothing did before) */
    if (rc == CONICA_OK) {
        size_t i;
        for (i = 0; i < s->nselect && sel.n; i++) {
            long k = s->select[i] ? selection_find(&sel, s->select[i]) : -1;
            if (k >= 0 && !sel.found[k]) {
                warn(s, 0, "--select: no element has id '%.200s'", s->select[i]);
                sel.found[k] = 1; /* once per id, in the order given */
            }
        }
    }
    selection_free(&sel);
    conica_svg_path_free(&p);
    if (timing)
        stats->io_seconds += conica_svg__now() - mark;
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
        rc = collect(doc, s, &sh, &items, &stats, 0, NULL, NULL, st);
    free(items);
    if (rc != CONICA_OK) {
        conica_svg_shapes_free(&sh);
        return rc;
    }
    conica_svg_shapes_free(out);
    *out = sh;
    return CONICA_OK;
}

/* Append a `points` list to *b ("x,y x,y ..."); 0 when out of memory. */
static int format_points(conica_svg__buf *b, const conica_svg_subpath *sp, size_t nsp,
                         int precision)
{
    size_t i, j;
    int kind = 0;
    conica_svg__buf_put(b, "", 0);
    for (i = 0; i < nsp; i++)
        for (j = 0; j < sp[i].n; j++) {
            conica_svg__put_number(b, sp[i].xy[2 * j], precision, &kind);
            conica_svg__buf_putc(b, ',');
            kind = 0;
            conica_svg__put_number(b, sp[i].xy[2 * j + 1], precision, &kind);
        }
    return !b->oom;
}

/* A text node whose content is `text`, taken over when libxml2 frees with
 * free() (its default: no copy of what may be 100 MB), else copied (text is
 * then freed here). NULL when out of memory (text freed). */
static xmlNodePtr text_node(xmlDocPtr doc, char *text)
{
    xmlNodePtr t;
    if (xmlFree != (xmlFreeFunc)free) {
        t = xmlNewDocText(doc, BAD_CAST text);
        free(text);
        return t;
    }
    t = xmlNewDocText(doc, NULL);
    if (!t) {
        free(text);
        return NULL;
    }
    t->content = BAD_CAST text;
    return t;
}

/* What conica_svg_process() builds before the document changes: one text
 * node (the new value) per element, and the attributes it lacks. When
 * streaming (conica_svg_process_write()), instead each value is formatted
 * into `out`, one buffer for all of them, and written at once. */
typedef struct pending {
    conica_svg_doc *doc;
    const conica_svg_settings *s;
    xmlNodePtr *texts;
    xmlAttrPtr *fresh;
    size_t cap;
    splicer *stream;
    conica_svg__buf out;
} pending;

/* Significant digits for one element's numbers when none are asked for
 * (precision 0): the rounding of a point, at most sqrt(2)/2 units in the
 * last digit of its largest coordinate, stays within
 * CONICA_SVG_ROUNDING_SHARE of the smallest tolerance of its subpaths
 * (flattening's, or smoothing's fidelity: given, or 1e-3 of the subpath's
 * extent, conica/path.h), so the written numbers keep the promise the
 * geometry made. */
static int element_digits(const conica_svg_settings *s, const conica_svg_subpath *sp, size_t nsp)
{
    double big = 0, tol = INFINITY;
    size_t i, j, k;
    int e, p;
    if (s->precision > 0)
        return s->precision;
    for (i = 0; i < nsp; i++) {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, t;
        for (j = 0; j < sp[i].n; j++)
            for (k = 0; k < 2; k++) {
                double v = sp[i].xy[2 * j + k];
                big = fmax(big, fabs(v));
                lo[k] = fmin(lo[k], v);
                hi[k] = fmax(hi[k], v);
            }
        t = s->mode == CONICA_SVG_FLATTEN ? s->tolerance
            : s->fidelity > 0             ? s->fidelity
                                          : 1e-3 * hypot(hi[0] - lo[0], hi[1] - lo[1]);
        if (t > 0 && sp[i].n > 1)
            tol = fmin(tol, t);
    }
    if (!(big > 0) || !isfinite(tol))
        return CONICA_SVG_DEFAULT_DIGITS; /* points only: nothing to keep */
    /* unit in the last of p digits: 10^(e + 1 - p) with 10^e <= big */
    e = (int)floor(log10(big));
    p = e + 1 - (int)floor(log10(CONICA_SVG_ROUNDING_SHARE * 1.4142135623730951 * tol));
    return p < 1 ? 1 : p > 17 ? 17 : p;
}

/* collect()'s hook: write element idx's polylines as its new value and
 * free them, so that the polylines of a large document never all exist at
 * once beside their text (peak memory, and pages touched once less). */
static conica_code format_element(void *ctx, conica_svg_shapes *sh, size_t idx, const item *it,
                                  conica_status *st)
{
    pending *pd = ctx;
    const conica_svg_element *el = &sh->elements[idx];
    conica_svg_subpath *sp = sh->subpaths + el->first_subpath;
    const char *name = it->kind == 0 || it->kind == 3 ? "d" : "points";
    int ok;
    size_t k;
    pd->out.n = 0;
    int digits = element_digits(pd->s, sp, el->nsubpaths);
    if (it->kind == 1 || it->kind == 2)
        ok = format_points(&pd->out, sp, el->nsubpaths, digits);
    else
        ok = conica_svg__format_path_into(&pd->out, sp, el->nsubpaths, digits);
    /* the polylines are written: let them go now (peak memory) */
    for (k = 0; k < el->nsubpaths; k++) {
        free(sp[k].xy);
        sp[k].xy = NULL;
    }
    if (!ok)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory writing path data");
    if (pd->stream) {
        rewrite rw;
        rw.mark = name;
        rw.value = pd->out.s;
        rw.shape = it->kind == 3;
        if (!splice_until(pd->stream, it->node, &rw))
            return conica__fail(st, CONICA_ERR_IO, 0, 0,
                                "cannot match the document's bytes to its elements");
        if (pd->stream->k->failed)
            return conica__fail(st, CONICA_ERR_IO, 0, 0, "%s", sink_why(pd->stream->k));
        return CONICA_OK;
    }
    if (idx >= pd->cap) {
        size_t nc = pd->cap ? 2 * pd->cap : 16;
        xmlNodePtr *tt = realloc(pd->texts, nc * sizeof *tt);
        xmlAttrPtr *tf;
        if (tt)
            pd->texts = tt;
        tf = tt ? realloc(pd->fresh, nc * sizeof *tf) : NULL;
        if (!tt || !tf)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        pd->fresh = tf;
        memset(pd->texts + pd->cap, 0, (nc - pd->cap) * sizeof *tt);
        memset(pd->fresh + pd->cap, 0, (nc - pd->cap) * sizeof *tf);
        pd->cap = nc;
    }
    {
        /* the buffer becomes the text node's content: a value that stays
         * needs its own block, trimmed to size */
        char *text = realloc(pd->out.s, pd->out.n + 1);
        if (!text)
            text = pd->out.s;
        memset(&pd->out, 0, sizeof pd->out);
        pd->texts[idx] = text_node(pd->doc->xml, text);
    }
    if (!pd->texts[idx])
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    if (it->kind == 3 || !own_attr(it->node, name)) {
        pd->fresh[idx] = xmlNewDocProp(pd->doc->xml, BAD_CAST name, NULL);
        if (!pd->fresh[idx])
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    }
    return CONICA_OK;
}

/* conica_svg_process(), or with stream its streaming form: the values go
 * through the splicer as they are made and the tree is not changed. */
static conica_code process(conica_svg_doc *doc, const conica_svg_settings *s,
                           conica_svg_stats *stats, splicer *stream, conica_status *st)
{
    conica_svg_shapes sh;
    conica_svg_stats local;
    item *items = NULL;
    pending pd;
    conica_code rc;
    size_t i, k;
    double t0;
    conica_svg_shapes_init(&sh);
    memset(&local, 0, sizeof local);
    memset(&pd, 0, sizeof pd);
    pd.doc = doc;
    pd.s = s;
    pd.stream = stream;
    /* Everything that allocates comes first (the new values are written as
     * each element's polylines are made): the document changes only when
     * all of it succeeded. */
    rc = collect(doc, s, &sh, &items, &local, stats != NULL, format_element, &pd, st);
    t0 = stats ? conica_svg__now() : 0.0;
    if (rc == CONICA_OK && stream) {
        if (!splice_finish(stream))
            rc = conica__fail(st, CONICA_ERR_IO, 0, 0,
                              "cannot match the document's bytes to its elements");
        else if (stream->k->failed)
            rc = conica__fail(st, CONICA_ERR_IO, 0, 0, "%s", sink_why(stream->k));
    } else if (rc == CONICA_OK) {
        xmlNodePtr *texts = pd.texts;
        xmlAttrPtr *fresh = pd.fresh;
        for (i = 0; i < sh.nelements; i++) {
            xmlNodePtr n = items[i].node;
            xmlAttrPtr a;
            if (items[i].kind == 3) {
                for (k = 0; k < sizeof shape_geometry / sizeof shape_geometry[0]; k++) {
                    a = xmlHasNsProp(n, BAD_CAST shape_geometry[k], NULL);
                    if (a)
                        xmlRemoveProp(a);
                }
                xmlNodeSetName(n, BAD_CAST "path");
            }
            if (fresh[i]) {
                /* appended as xmlSetProp() does (a shape's stray d goes) */
                a = (xmlAttrPtr)xmlAddChild(n, (xmlNodePtr)fresh[i]);
                if (!a)
                    continue; /* not reached: n is an element (texts[i] freed below) */
                fresh[i] = NULL;
            } else {
                a = own_attr(n, items[i].kind == 0 ? "d" : "points");
            }
            /* the value replaced where the attribute stands */
            xmlFreeNodeList(a->children);
            a->children = a->last = texts[i];
            texts[i]->parent = (xmlNodePtr)a;
            texts[i] = NULL;
            mark_rewritten(n, items[i].kind);
            doc->rewritten = 1;
        }
    }
    if (stats)
        local.io_seconds += conica_svg__now() - t0;
    for (i = 0; i < pd.cap; i++) {
        xmlFreeNode(pd.texts[i]);
        if (pd.fresh[i])
            xmlFreeProp(pd.fresh[i]);
    }
    free(pd.texts);
    free(pd.fresh);
    free(pd.out.s);
    free(items);
    conica_svg_shapes_free(&sh);
    if (rc == CONICA_OK && stats)
        *stats = local;
    return rc;
}

conica_code conica_svg_process(conica_svg_doc *doc, const conica_svg_settings *s,
                               conica_svg_stats *stats, conica_status *st)
{
    conica_code rc;
    if (!doc || !s)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_process: NULL argument");
    if ((rc = check_settings(s, st)) != CONICA_OK)
        return rc;
    return process(doc, s, stats, NULL, st);
}

conica_code conica_svg_process_write(conica_svg_doc *doc, const conica_svg_settings *s,
                                     conica_svg_stats *stats, FILE *f, conica_status *st)
{
    save_sink k;
    splicer sp;
    conica_code rc;
    if (!doc || !s || !f)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0,
                            "conica_svg_process_write: NULL argument");
    if ((rc = check_settings(s, st)) != CONICA_OK)
        return rc;
    /* Streaming needs the tree as loaded and bytes it can be matched to;
     * otherwise the same result in two steps. */
    if (doc->rewritten || !splice(doc, NULL, 0)) {
        if ((rc = process(doc, s, stats, NULL, st)) != CONICA_OK)
            return rc;
        return conica_svg_doc_write(doc, f, st);
    }
    if (sink_begin(&k, doc, f, st))
        return CONICA_ERR_UNSUPPORTED;
    splicer_init(&sp, doc, &k, 0);
    rc = process(doc, s, stats, &sp, st);
    free(sp.open);
    return sink_end(&k, doc, rc, st);
}
