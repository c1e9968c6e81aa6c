/* SPDX-License-Identifier: MIT */
/* The DXF reader's public API (conica/dxf.h): the sections of a file
 * (HEADER units, the LAYER table, BLOCKS, ENTITIES), INSERT expansion with
 * its transforms and caps, what is skipped and why (one warning per type),
 * then the pieces chained into a conica_path. Two passes: the first
 * records the units, layers, where each block and the entities start; the
 * second draws the model space, reading each block again from its offset
 * whenever it is inserted (nothing but one entity a level is held).
 * Calls dxf_lex, dxf_entity, dxf_geom, dxf_chain and path. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dxf_internal.h"
#include "internal.h"

/* Skip reasons counted per entity type, one warning each at the end. */
#define MAX_SKIP_KINDS 64
/* Longest entity type or layer name kept for messages. */
#define NAME_CAP 64
/* Upper bound of the nesting cap a caller may set. */
#define MAX_DEPTH_CAP 64

typedef struct block {
    const char *name;
    size_t nlen;
    double base[2];
    size_t pos, line; /* where its first entity starts */
    int busy;         /* being inserted (recursion check) */
} block;

typedef struct layer {
    const char *name;
    size_t nlen;
    int hidden; /* frozen (70 bit 1) or off (colour < 0) */
} layer;

typedef struct skip {
    char type[NAME_CAP];
    const char *why;
    size_t count, line;
} skip;

typedef struct reader {
    const char *buf;
    size_t len;
    conica_dxf_settings s;
    int decimals;
    int insunits, measurement;
    block *blk;
    size_t nblk, blkcap;
    layer *lay;
    size_t nlay, laycap;
    char **used; /* layers drawn from (NUL-terminated copies) */
    size_t nused;
    int have_entities;
    size_t ent_pos, ent_line;
    conica__dxf_geom geom, hatch;
    skip skips[MAX_SKIP_KINDS];
    size_t nskips, skipped, drawn, visited, hatches;
    size_t widths_warned;
} reader;

conica_dxf_limits conica_dxf_limits_defaults(void)
{
    conica_dxf_limits l;
    l.max_bytes = CONICA_DXF_DEFAULT_MAX_BYTES;
    l.max_entities = CONICA_DXF_DEFAULT_MAX_ENTITIES;
    l.max_vertices = CONICA_DXF_DEFAULT_MAX_VERTICES;
    l.max_knots = CONICA_DXF_DEFAULT_MAX_KNOTS;
    l.max_points = CONICA_DXF_DEFAULT_MAX_POINTS;
    l.max_depth = CONICA_DXF_DEFAULT_MAX_DEPTH;
    return l;
}

conica_dxf_settings conica_dxf_defaults(void)
{
    conica_dxf_settings s;
    memset(&s, 0, sizeof s);
    s.limits = conica_dxf_limits_defaults();
    s.unit_mm = 1;
    s.unitless_mm = 1;
    return s;
}

void conica_dxf_drawing_init(conica_dxf_drawing *d)
{
    memset(d, 0, sizeof *d);
    conica_path_init(&d->path);
    d->file_unit_mm = 1;
    d->file_unit = "unitless";
}

void conica_dxf_drawing_free(conica_dxf_drawing *d)
{
    if (!d)
        return;
    conica_path_free(&d->path);
    free(d->sub_line);
    for (size_t i = 0; i < d->nlayers; i++)
        free(d->layers[i]);
    free(d->layers);
    conica_dxf_drawing_init(d);
}

int conica_dxf_sniff(const char *buf, size_t len)
{
    size_t i = 0, j;
    static const char bin[] = "AutoCAD Binary DXF";
    if (len >= sizeof bin - 1 && memcmp(buf, bin, sizeof bin - 1) == 0)
        return 1;
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0)
        i = 3;
    while (i < len && (buf[i] == ' ' || buf[i] == '\t'))
        i++;
    if (len - i >= 3 && memcmp(buf + i, "999", 3) == 0)
        return 1;
    if (i >= len || buf[i] != '0')
        return 0;
    for (j = i + 1; j < len && (buf[j] == ' ' || buf[j] == '\t' || buf[j] == '\r'); j++)
        ;
    if (j >= len || buf[j] != '\n')
        return 0;
    for (j++; j < len && (buf[j] == ' ' || buf[j] == '\t'); j++)
        ;
    return len - j >= 7 && memcmp(buf + j, "SECTION", 7) == 0;
}

/* millimetres per unit of $INSUNITS code u (DXF reference), 0: none */
static double insunits_mm(int u, const char **name)
{
    static const struct {
        double mm;
        const char *name;
    } t[] = {
        {0, "unitless"},   {25.4, "in"},      {304.8, "ft"},       {1609344, "mi"},
        {1, "mm"},         {10, "cm"},        {1000, "m"},         {1e6, "km"},
        {25.4e-6, "uin"},  {0.0254, "mil"},   {914.4, "yd"},       {1e-7, "angstrom"},
        {1e-6, "nm"},      {1e-3, "um"},      {100, "dm"},         {1e4, "dam"},
        {1e5, "hm"},       {1e12, "Gm"},      {1.495978707e14, "au"}, {9.4607304725808e18, "ly"},
        {3.0856776e19, "pc"},
    };
    if (u < 0 || u >= (int)(sizeof t / sizeof t[0]))
        u = 0;
    *name = t[u].name;
    return t[u].mm;
}

static int read_pair(reader *r, conica__dxf_lexer *lx, conica__dxf_pair *p, conica_status *st)
{
    int k = conica__dxf_next(lx, p, st);
    if (lx->decimals > r->decimals)
        r->decimals = lx->decimals;
    return k;
}

static conica_code truncated(const conica__dxf_lexer *lx, const char *what, conica_status *st)
{
    return conica__fail(st, CONICA_ERR_PARSE, lx->line, lx->pos,
                        "truncated: the file ends inside %s (no ENDSEC / EOF)", what);
}

/* Skip to the pair after the section's ENDSEC. */
static conica_code skip_section(reader *r, conica__dxf_lexer *lx, const char *name,
                                conica_status *st)
{
    conica__dxf_pair p;
    int k;
    while ((k = read_pair(r, lx, &p, st)) > 0) {
        if (conica__dxf_is(&p, 0, "ENDSEC"))
            return CONICA_OK;
        if (conica__dxf_is(&p, 0, "EOF")) { /* a writer that forgot the ENDSEC */
            conica__dxf_unread(lx, &p);
            return CONICA_OK;
        }
    }
    return k < 0 ? st->code : truncated(lx, name, st);
}

static conica_code read_header(reader *r, conica__dxf_lexer *lx, conica_status *st)
{
    conica__dxf_pair p;
    int k, want = 0; /* 1: $INSUNITS, 2: $MEASUREMENT */
    while ((k = read_pair(r, lx, &p, st)) > 0) {
        if (conica__dxf_is(&p, 0, "ENDSEC"))
            return CONICA_OK;
        if (p.code == 9)
            want = conica__dxf_is(&p, 9, "$INSUNITS") ? 1 : conica__dxf_is(&p, 9, "$MEASUREMENT") ? 2 : 0;
        else if (p.code == 70 && want == 1)
            r->insunits = (int)p.num;
        else if (p.code == 70 && want == 2)
            r->measurement = (int)p.num;
    }
    return k < 0 ? st->code : truncated(lx, "the HEADER section", st);
}

static conica_code grow(void **a, size_t *cap, size_t n, size_t size, conica_status *st)
{
    if (n < *cap)
        return CONICA_OK;
    size_t nc = *cap ? 2 * *cap : 16;
    void *q = realloc(*a, nc * size);
    if (!q)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    *a = q;
    *cap = nc;
    return CONICA_OK;
}

static conica_code read_tables(reader *r, conica__dxf_lexer *lx, conica_status *st)
{
    conica__dxf_pair p;
    int k, in_layer = 0;
    layer *cur = NULL;
    while ((k = read_pair(r, lx, &p, st)) > 0) {
        if (conica__dxf_is(&p, 0, "ENDSEC"))
            return CONICA_OK;
        if (p.code == 0) {
            cur = NULL;
            if (conica__dxf_is(&p, 0, "LAYER") && in_layer) {
                if (r->nlay >= r->s.limits.max_entities)
                    return conica__fail(st, CONICA_ERR_LIMIT, p.line, p.pos,
                                        "more than %zu layers (max_entities)",
                                        r->s.limits.max_entities);
                if (grow((void **)&r->lay, &r->laycap, r->nlay, sizeof *r->lay, st) != CONICA_OK)
                    return CONICA_ERR_NOMEM;
                cur = &r->lay[r->nlay++];
                cur->name = "0";
                cur->nlen = 1;
                cur->hidden = 0;
            } else if (conica__dxf_is(&p, 0, "ENDTAB")) {
                in_layer = 0;
            }
        } else if (p.code == 2 && !cur) {
            in_layer = conica__dxf_is(&p, 2, "LAYER");
        } else if (cur && p.code == 2) {
            cur->name = p.s;
            cur->nlen = p.n;
        } else if (cur && p.code == 70) {
            cur->hidden |= ((long long)p.num & 1) != 0;
        } else if (cur && p.code == 62) {
            cur->hidden |= p.num < 0;
        }
    }
    return k < 0 ? st->code : truncated(lx, "the TABLES section", st);
}

static conica_code read_blocks(reader *r, conica__dxf_lexer *lx, conica_status *st)
{
    conica__dxf_pair p;
    int k;
    block *cur = NULL;
    int in_head = 0;
    while ((k = read_pair(r, lx, &p, st)) > 0) {
        if (conica__dxf_is(&p, 0, "ENDSEC"))
            return CONICA_OK;
        if (p.code == 0) {
            if (in_head && cur) { /* the first pair after the BLOCK's own groups */
                cur->pos = p.pos;
                cur->line = p.line - 1;
                in_head = 0;
            }
            if (conica__dxf_is(&p, 0, "BLOCK")) {
                if (r->nblk >= r->s.limits.max_entities)
                    return conica__fail(st, CONICA_ERR_LIMIT, p.line, p.pos,
                                        "more than %zu blocks (max_entities)",
                                        r->s.limits.max_entities);
                if (grow((void **)&r->blk, &r->blkcap, r->nblk, sizeof *r->blk, st) != CONICA_OK)
                    return CONICA_ERR_NOMEM;
                cur = &r->blk[r->nblk++];
                memset(cur, 0, sizeof *cur);
                cur->name = "";
                in_head = 1;
            } else if (conica__dxf_is(&p, 0, "ENDBLK")) {
                cur = NULL;
            }
        } else if (in_head && cur) {
            if (p.code == 2) {
                cur->name = p.s;
                cur->nlen = p.n;
            } else if (p.code == 10) {
                cur->base[0] = p.num;
            } else if (p.code == 20) {
                cur->base[1] = p.num;
            }
        }
    }
    return k < 0 ? st->code : truncated(lx, "the BLOCKS section", st);
}

/* Pass 1: units, layers, blocks, where the entities are. */
static conica_code scan(reader *r, conica_status *st)
{
    conica__dxf_lexer lx;
    conica__dxf_pair p, q;
    int k;
    conica_code rc;
    memset(&lx, 0, sizeof lx);
    conica__dxf_lex_at(&lx, r->buf, r->len, 0, 0);
    if (r->len >= 3 && memcmp(r->buf, "\xEF\xBB\xBF", 3) == 0)
        lx.pos = 3;
    while ((k = read_pair(r, &lx, &p, st)) > 0) {
        if (p.code == 999)
            continue;
        if (conica__dxf_is(&p, 0, "EOF"))
            return CONICA_OK;
        if (!conica__dxf_is(&p, 0, "SECTION"))
            return conica__fail(st, CONICA_ERR_PARSE, p.line, p.pos,
                                "expected '0 SECTION', found group %d '%.*s'", p.code,
                                (int)(p.n < 40 ? p.n : 40), p.s);
        if ((k = read_pair(r, &lx, &q, st)) <= 0 || q.code != 2)
            return k < 0 ? st->code
                         : conica__fail(st, CONICA_ERR_PARSE, p.line, p.pos,
                                        "a SECTION without a name (group 2)");
        if (conica__dxf_is(&q, 2, "HEADER"))
            rc = read_header(r, &lx, st);
        else if (conica__dxf_is(&q, 2, "TABLES"))
            rc = read_tables(r, &lx, st);
        else if (conica__dxf_is(&q, 2, "BLOCKS"))
            rc = read_blocks(r, &lx, st);
        else if (conica__dxf_is(&q, 2, "ENTITIES")) {
            r->have_entities = 1;
            r->ent_pos = lx.pos;
            r->ent_line = lx.line;
            rc = skip_section(r, &lx, "the ENTITIES section", st);
        } else
            rc = skip_section(r, &lx, "a section", st);
        if (rc != CONICA_OK)
            return rc;
    }
    return k < 0 ? st->code : CONICA_OK; /* no EOF marker: the end of the file will do */
}

static const char *str_of(const conica__dxf_ent *e, int code, size_t *n)
{
    for (size_t i = 1; i < e->n; i++)
        if (e->p[i].code == code) {
            *n = e->p[i].n;
            return e->p[i].s;
        }
    *n = 0;
    return NULL;
}

static double num_of(const conica__dxf_ent *e, int code, double dflt)
{
    for (size_t i = 1; i < e->n; i++)
        if (e->p[i].code == code)
            return e->p[i].num;
    return dflt;
}

static void note_skip(reader *r, const conica__dxf_pair *head, const char *why)
{
    size_t n = head->n < NAME_CAP - 1 ? head->n : NAME_CAP - 1;
    r->skipped++;
    for (size_t i = 0; i < r->nskips; i++)
        if (r->skips[i].why == why && strlen(r->skips[i].type) == n &&
            memcmp(r->skips[i].type, head->s, n) == 0) {
            r->skips[i].count++;
            return;
        }
    if (r->nskips == MAX_SKIP_KINDS)
        return; /* counted in r->skipped, reported as "other" */
    skip *s = &r->skips[r->nskips++];
    memcpy(s->type, head->s, n);
    s->type[n] = '\0';
    s->why = why;
    s->count = 1;
    s->line = head->line;
}

static int name_eq(const char *a, size_t an, const char *b)
{
    return strlen(b) == an && memcmp(a, b, an) == 0;
}

/* Is the layer to be read? */
static int layer_wanted(const reader *r, const char *name, size_t n, const char **why)
{
    if (r->s.nlayers) {
        for (size_t i = 0; i < r->s.nlayers; i++)
            if (name_eq(name, n, r->s.layers[i]))
                return 1;
        *why = "not on a selected layer (--layer)";
        return 0;
    }
    for (size_t i = 0; i < r->nlay; i++)
        if (r->lay[i].nlen == n && memcmp(r->lay[i].name, name, n) == 0 && r->lay[i].hidden) {
            *why = "on a frozen or switched-off layer";
            return 0;
        }
    return 1;
}

/* The index of a used layer (added on first use). */
static conica_code layer_index(reader *r, const char *name, size_t n, size_t *idx,
                               conica_status *st)
{
    if (n > NAME_CAP - 1)
        n = NAME_CAP - 1;
    for (size_t i = 0; i < r->nused; i++)
        if (name_eq(name, n, r->used[i])) {
            *idx = i;
            return CONICA_OK;
        }
    char **q = realloc(r->used, (r->nused + 1) * sizeof *q);
    if (!q)
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    r->used = q;
    if (!(q[r->nused] = malloc(n + 1)))
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
    memcpy(q[r->nused], name, n);
    q[r->nused][n] = '\0';
    *idx = r->nused++;
    return CONICA_OK;
}

static block *find_block(reader *r, const char *name, size_t n)
{
    for (size_t i = 0; i < r->nblk; i++)
        if (r->blk[i].nlen == n && memcmp(r->blk[i].name, name, n) == 0)
            return &r->blk[i];
    return NULL;
}

static conica_code walk(reader *r, size_t pos, size_t line, const conica__dxf_xf *xf, int depth,
                        const char *blayer, size_t blen, conica_status *st);

/* INSERT: the block under scale, rotation and the column/row array. */
static conica_code insert(reader *r, const conica__dxf_ent *e, const conica__dxf_xf *xf,
                          int depth, const char *lname, size_t llen, conica_status *st)
{
    size_t n, line = e->p[0].line;
    const char *name = str_of(e, 2, &n);
    conica__dxf_xf ocs;
    block *b = name ? find_block(r, name, n) : NULL;
    if (!b) {
        if (r->s.warn) {
            char m[160];
            snprintf(m, sizeof m, "INSERT of a block '%.*s' the file does not define: skipped",
                     (int)(n < 60 ? n : 60), name ? name : "");
            r->s.warn(r->s.warn_ctx, line, m);
        }
        r->skipped++;
        return CONICA_OK;
    }
    if (b->busy)
        return conica__fail(st, CONICA_ERR_PARSE, line, 0,
                            "block '%.*s' inserts itself (recursive blocks)",
                            (int)(n < 60 ? n : 60), name);
    if (depth + 1 > r->s.limits.max_depth)
        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                            "INSERTs nested deeper than %d (max_depth)", r->s.limits.max_depth);
    if (!conica__dxf_ocs(e, &ocs)) {
        note_skip(r, &e->p[0], "not in the drawing plane (extrusion not +-z)");
        return CONICA_OK;
    }
    double sx = num_of(e, 41, 1), sy = num_of(e, 42, 1), rot = num_of(e, 50, 0);
    double cols = num_of(e, 70, 1), rows = num_of(e, 71, 1);
    double cs = num_of(e, 44, 0), rs = num_of(e, 45, 0), c, s;
    double ix = num_of(e, 10, 0), iy = num_of(e, 20, 0);
    if (cols < 1)
        cols = 1;
    if (rows < 1)
        rows = 1;
    if (sx == 0 || sy == 0) {
        note_skip(r, &e->p[0], "scaled to nothing (scale 0)");
        return CONICA_OK;
    }
    if (cols * rows > (double)r->s.limits.max_entities)
        return conica__fail(st, CONICA_ERR_LIMIT, line, 0,
                            "INSERT array of %g x %g copies exceeds max_entities (%zu)", cols, rows,
                            r->s.limits.max_entities);
    conica__dxf_sincos_deg(rot, &c, &s);
    b->busy = 1;
    conica_code rc = CONICA_OK;
    for (size_t j = 0; j < (size_t)rows && rc == CONICA_OK; j++)
        for (size_t i = 0; i < (size_t)cols && rc == CONICA_OK; i++) {
            /* x -> ins + R (offset + S (x - base)): the array offsets are in
             * the rotated, unscaled frame */
            double ox = (double)i * cs, oy = (double)j * rs;
            conica__dxf_xf t;
            t.m[0] = c * sx;
            t.m[1] = -s * sy;
            t.m[3] = s * sx;
            t.m[4] = c * sy;
            double bx = ox - sx * b->base[0], by = oy - sy * b->base[1];
            t.m[2] = ix + c * bx - s * by;
            t.m[5] = iy + s * bx + c * by;
            conica__dxf_xf a = conica__dxf_xf_mul(&ocs, &t), full = conica__dxf_xf_mul(xf, &a);
            rc = walk(r, b->pos, b->line, &full, depth + 1, lname, llen, st);
        }
    b->busy = 0;
    return rc;
}

/* One entity of the model space or of a block. */
static conica_code entity(reader *r, const conica__dxf_ent *e, const conica__dxf_xf *xf,
                          int depth, const char *blayer, size_t blen, conica_status *st)
{
    const conica__dxf_pair *head = &e->p[0];
    size_t ln, hn;
    const char *lname = str_of(e, 8, &ln), *why = NULL, *hs = str_of(e, 5, &hn);
    conica_code rc;
    if (++r->visited > r->s.limits.max_entities)
        return conica__fail(st, CONICA_ERR_LIMIT, head->line, head->pos,
                            "more than %zu entities (max_entities, INSERTs expanded)",
                            r->s.limits.max_entities);
    if (!lname) {
        lname = "0";
        ln = 1;
    }
    /* an entity of a block on layer 0 takes the layer of its INSERT */
    if (blayer && ln == 1 && lname[0] == '0') {
        lname = blayer;
        ln = blen;
    }
    if (depth == 0 && num_of(e, 67, 0) != 0) {
        note_skip(r, head, "in paper space");
        return CONICA_OK;
    }
    if (num_of(e, 60, 0) != 0) {
        note_skip(r, head, "invisible (group 60)");
        return CONICA_OK;
    }
    if (!layer_wanted(r, lname, ln, &why)) {
        note_skip(r, head, why);
        return CONICA_OK;
    }
    if (conica__dxf_is(head, 0, "INSERT"))
        return insert(r, e, xf, depth, lname, ln, st);
    conica__dxf_ctx c;
    int known = 0;
    memset(&c, 0, sizeof c);
    c.lim = &r->s.limits;
    c.warn = r->s.warn;
    c.warn_ctx = r->s.warn_ctx;
    c.widths_warned = r->widths_warned;
    int hatch = conica__dxf_is(head, 0, "HATCH");
    c.geom = hatch ? &r->hatch : &r->geom;
    c.hatch_group = r->hatches * 1024 * 1024; /* every HATCH's paths apart */
    c.info.line = head->line;
    if (hs) {
        size_t m = hn < sizeof c.info.handle - 1 ? hn : sizeof c.info.handle - 1;
        memcpy(c.info.handle, hs, m);
        c.info.handle[m] = '\0';
    }
    if ((rc = layer_index(r, lname, ln, &c.info.layer, st)) != CONICA_OK)
        return rc;
    rc = conica__dxf_entity(&c, e, xf, &known, st);
    r->widths_warned = c.widths_warned;
    if (hatch)
        r->hatches++;
    if (rc != CONICA_OK) {
        if (st && !st->line)
            st->line = head->line;
        return rc;
    }
    if (!known) {
        static const char *const planar[] = {"ARC", "CIRCLE", "ELLIPSE", "LWPOLYLINE", "HATCH"};
        int is_planar = 0;
        for (size_t i = 0; i < sizeof planar / sizeof planar[0]; i++)
            is_planar |= conica__dxf_is(head, 0, planar[i]);
        note_skip(r, head,
                  is_planar || conica__dxf_is(head, 0, "POLYLINE") ||
                          conica__dxf_is(head, 0, "SPLINE")
                      ? "3D or not in the drawing plane"
                      : "not profile geometry");
        return CONICA_OK;
    }
    r->drawn++;
    return CONICA_OK;
}

static conica_code walk(reader *r, size_t pos, size_t line, const conica__dxf_xf *xf, int depth,
                        const char *blayer, size_t blen, conica_status *st)
{
    conica__dxf_lexer lx;
    conica__dxf_pair p;
    conica__dxf_ent e;
    conica_code rc = CONICA_OK;
    int k = 0;
    /* an entity's groups: its vertices (a few groups each) and some more */
    size_t max_groups = 8 * r->s.limits.max_vertices + 4096;
    memset(&lx, 0, sizeof lx);
    memset(&e, 0, sizeof e);
    conica__dxf_lex_at(&lx, r->buf, r->len, pos, line);
    while (rc == CONICA_OK && (k = read_pair(r, &lx, &p, st)) > 0) {
        if (p.code != 0)
            continue; /* stray groups between entities (999 comments, ...) */
        if (conica__dxf_is(&p, 0, "ENDSEC") || conica__dxf_is(&p, 0, "ENDBLK") ||
            conica__dxf_is(&p, 0, "EOF"))
            break;
        if ((k = conica__dxf_read_entity(&lx, &p, &e, max_groups, st)) < 0) {
            rc = st ? st->code : CONICA_ERR_PARSE;
            break;
        }
        rc = entity(r, &e, xf, depth, blayer, blen, st);
        if (k == 0)
            break;
    }
    if (rc == CONICA_OK && k < 0)
        rc = st ? st->code : CONICA_ERR_PARSE;
    conica__dxf_ent_free(&e);
    return rc;
}

static void report_skips(const reader *r)
{
    size_t listed = 0;
    if (!r->s.warn)
        return;
    for (size_t i = 0; i < r->nskips; i++) {
        char m[256];
        const skip *s = &r->skips[i];
        snprintf(m, sizeof m, "%zu %s entit%s skipped: %s", s->count, s->type,
                 s->count == 1 ? "y" : "ies", s->why);
        r->s.warn(r->s.warn_ctx, s->line, m);
        listed += s->count;
    }
    if (r->skipped > listed) {
        char m[128];
        snprintf(m, sizeof m, "%zu other entities skipped", r->skipped - listed);
        r->s.warn(r->s.warn_ctx, 0, m);
    }
}

static void extents(const conica__dxf_geom *g, double *diag)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < g->npt; i++)
        for (int c = 0; c < 2; c++) {
            double v = g->pt[3 * i + (size_t)c];
            lo[c] = fmin(lo[c], v);
            hi[c] = fmax(hi[c], v);
        }
    *diag = g->npt ? hypot(hi[0] - lo[0], hi[1] - lo[1]) : 0;
}

static void reader_free(reader *r)
{
    free(r->blk);
    free(r->lay);
    for (size_t i = 0; i < r->nused; i++)
        free(r->used[i]);
    free(r->used);
    conica__dxf_geom_free(&r->geom);
    conica__dxf_geom_free(&r->hatch);
}

static conica_code check_settings(const char *buf, size_t len, const conica_dxf_limits *l,
                                  conica_status *st)
{
    static const char bin[] = "AutoCAD Binary DXF";
    if (!buf && len)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_dxf_read: NULL buffer");
    if (!l || l->max_depth < 1 || l->max_depth > MAX_DEPTH_CAP || !l->max_entities ||
        !l->max_vertices || !l->max_knots || !l->max_points)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "DXF limits out of range");
    if (len > l->max_bytes)
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                            "input larger than the limit of %zu bytes (max_bytes)", l->max_bytes);
    if (len >= sizeof bin - 1 && memcmp(buf, bin, sizeof bin - 1) == 0)
        return conica__fail(st, CONICA_ERR_UNSUPPORTED, 1, 0,
                            "binary DXF is not supported: save the drawing as ASCII DXF");
    return CONICA_OK;
}

conica_code conica_dxf_read(const char *buf, size_t len, const conica_dxf_settings *s,
                            conica_dxf_drawing *out, conica_status *st)
{
    reader r;
    conica_code rc;
    conica_dxf_drawing d;
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_dxf_read: NULL output");
    memset(&r, 0, sizeof r);
    r.s = s ? *s : conica_dxf_defaults();
    if (!(r.s.unit_mm > 0) || !isfinite(r.s.unit_mm) || !(r.s.unitless_mm > 0) ||
        !(r.s.gap >= 0) || !isfinite(r.s.gap))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "DXF settings out of range");
    if ((rc = check_settings(buf, len, &r.s.limits, st)) != CONICA_OK)
        return rc;
    r.buf = buf;
    r.len = len;
    r.measurement = -1;
    conica__dxf_geom_init(&r.geom, r.s.limits.max_points);
    conica__dxf_geom_init(&r.hatch, r.s.limits.max_points);
    conica_dxf_drawing_init(&d);
    if ((rc = scan(&r, st)) != CONICA_OK)
        goto fail;
    if (!r.have_entities) {
        rc = conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0, "the file has no ENTITIES section");
        goto fail;
    }
    /* units: $INSUNITS, else $MEASUREMENT (0 imperial: inches), else the caller's */
    d.file_unit_mm = insunits_mm(r.insunits, &d.file_unit);
    if (d.file_unit_mm == 0) {
        if (r.measurement == 1) {
            d.file_unit_mm = 1;
            d.file_unit = "mm ($MEASUREMENT metric)";
        } else if (r.measurement == 0) {
            d.file_unit_mm = 25.4;
            d.file_unit = "in ($MEASUREMENT imperial)";
        } else {
            d.file_unit_mm = r.s.unitless_mm;
            d.file_unit = "unitless";
        }
    }
    double f = d.file_unit_mm / r.s.unit_mm;
    conica__dxf_xf root = {{f, 0, 0, 0, f, 0}};
    if ((rc = walk(&r, r.ent_pos, r.ent_line, &root, 0, NULL, 0, st)) != CONICA_OK)
        goto fail;
    report_skips(&r);
    conica__dxf_geom *g = &r.geom;
    if (g->npc == 0 && r.hatch.npc > 0) {
        g = &r.hatch;
        d.hatch_only = 1;
    } else if (r.hatch.npc > 0 && r.s.warn) {
        char m[200];
        snprintf(m, sizeof m,
                 "%zu HATCH entit%s skipped: hatch boundaries are read only when the drawing "
                 "has no other geometry",
                 r.hatches, r.hatches == 1 ? "y" : "ies");
        r.s.warn(r.s.warn_ctx, 0, m);
    }
    if (g->npc == 0) {
        rc = conica__fail(st, CONICA_ERR_DEGENERATE, 0, 0,
                          "no profile geometry in the model space (%zu entities skipped)",
                          r.skipped);
        goto fail;
    }
    double diag, q = 0.5 * pow(10.0, -(double)r.decimals) * f;
    extents(g, &diag);
    /* a coarse writer (%.6f) rounds every end point: its precision is the
     * gap, as long as that is a small fraction of the drawing (short
     * numbers like "3.0" say nothing about rounding) */
    d.gap = CONICA_DXF_DEFAULT_REL_GAP * diag;
    if (4 * q > d.gap && 4 * q <= CONICA_DXF_PRECISION_GAP_REL * diag)
        d.gap = 4 * q;
    if (r.s.gap > 0)
        d.gap = r.s.gap;
    conica__dxf_chain_opts co;
    co.gap = d.gap;
    co.open_mode = r.s.open_mode;
    co.layer_names = (const char *const *)r.used;
    co.warn = r.s.warn;
    co.warn_ctx = r.s.warn_ctx;
    if ((rc = conica__dxf_chain(g, &co, &d.path, &d.sub_line, &d.joined, &d.closed_open, st)) !=
        CONICA_OK)
        goto fail;
    d.entities = r.drawn;
    d.skipped = r.skipped;
    /* the layers geometry came from (an entity that drew nothing, a TEXT,
     * a skipped HATCH, names its layer without adding one) */
    d.layers = calloc(r.nused + 1, sizeof *d.layers);
    unsigned char *drew = calloc(r.nused + 1, 1);
    if (!d.layers || !drew) {
        free(drew);
        rc = conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        goto fail;
    }
    for (size_t k = 0; k < g->npc; k++)
        drew[g->pc[k].layer] = 1;
    for (size_t i = 0; i < r.nused; i++)
        if (drew[i]) {
            d.layers[d.nlayers++] = r.used[i];
            r.used[i] = NULL;
        }
    free(drew);
    reader_free(&r);
    conica_dxf_drawing_free(out);
    *out = d;
    conica__ok(st);
    return CONICA_OK;
fail:
    reader_free(&r);
    conica_dxf_drawing_free(&d);
    return rc;
}

conica_code conica_dxf_spline(const char *buf, size_t len, const char *handle,
                              const conica_dxf_limits *lim, conica_bspline *out, size_t *line,
                              conica_status *st)
{
    reader r;
    conica_code rc;
    conica_dxf_limits dl = conica_dxf_limits_defaults();
    conica__dxf_lexer lx;
    conica__dxf_pair p;
    conica__dxf_ent e;
    size_t found = 0, fline = 0;
    char handles[160] = "";
    int k = 0;
    if (!out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_dxf_spline: NULL output");
    memset(&r, 0, sizeof r);
    r.s = conica_dxf_defaults();
    r.s.limits = lim ? *lim : dl;
    if ((rc = check_settings(buf, len, &r.s.limits, st)) != CONICA_OK)
        return rc;
    r.buf = buf;
    r.len = len;
    if ((rc = scan(&r, st)) != CONICA_OK) {
        reader_free(&r);
        return rc;
    }
    memset(&lx, 0, sizeof lx);
    memset(&e, 0, sizeof e);
    conica__dxf_lex_at(&lx, buf, len, r.ent_pos, r.ent_line);
    conica_bspline bs;
    conica_bspline_init(&bs);
    while (r.have_entities && (k = read_pair(&r, &lx, &p, st)) > 0) {
        if (p.code != 0)
            continue;
        if (conica__dxf_is(&p, 0, "ENDSEC") || conica__dxf_is(&p, 0, "EOF"))
            break;
        if ((k = conica__dxf_read_entity(&lx, &p, &e, 8 * r.s.limits.max_vertices + 4096, st)) < 0)
            break;
        if (!conica__dxf_is(&p, 0, "SPLINE"))
            continue;
        size_t hn;
        const char *h = str_of(&e, 5, &hn);
        char hb[24] = "";
        if (h) {
            size_t m = hn < sizeof hb - 1 ? hn : sizeof hb - 1;
            memcpy(hb, h, m);
            hb[m] = '\0';
        }
        if (handle && strcmp(hb, handle) != 0)
            continue;
        found++;
        size_t hl = strlen(handles);
        if (hl + strlen(hb) + 3 < sizeof handles)
            snprintf(handles + hl, sizeof handles - hl, "%s%s", hl ? ", " : "", hb[0] ? hb : "?");
        if (found == 1) {
            fline = p.line;
            if ((rc = conica__dxf_spline_of(&e, &r.s.limits, hb, &bs, st)) != CONICA_OK)
                break;
        }
        if (k == 0)
            break;
    }
    if (rc == CONICA_OK && k < 0)
        rc = st ? st->code : CONICA_ERR_PARSE;
    conica__dxf_ent_free(&e);
    reader_free(&r);
    if (rc == CONICA_OK && found == 0)
        rc = conica__fail(st, CONICA_ERR_ARG, 0, 0,
                          handle ? "no SPLINE with handle '%s' in the model space"
                                 : "no SPLINE in the model space%s",
                          handle ? handle : "");
    if (rc == CONICA_OK && found > 1)
        rc = conica__fail(st, CONICA_ERR_ARG, 0, 0,
                          "%zu SPLINE entities (handles %s): name one by its handle", found,
                          handles);
    if (rc != CONICA_OK) {
        conica_bspline_free(&bs);
        return rc;
    }
    conica_bspline_free(out);
    *out = bs;
    if (line)
        *line = fline;
    conica__ok(st);
    return CONICA_OK;
}
