/* SPDX-License-Identifier: MIT */
/* Internal interfaces of the DXF reader (conica/dxf.h), one concept a file:
 *   dxf_lex.c     group-code/value pairs, typed by a table, with lines
 *   dxf_geom.c    pieces: entities as exact line/Bézier segments, transformed
 *   dxf_entity.c  one builder per entity type (LINE, ARC, ..., HATCH)
 *   dxf_chain.c   pieces joined into closed contours of a conica_path
 *   dxf_read.c    sections, tables, blocks, INSERT expansion, the public API
 * None of them knows SVG or OpenSCAD. */
#ifndef CONICA_DXF_INTERNAL_H
#define CONICA_DXF_INTERNAL_H

#include <stddef.h>

#include "conica/dxf.h"

/* ------------------------------------------------------------ lexer */

typedef enum conica__dxf_type { CONICA__DXF_STR, CONICA__DXF_DBL, CONICA__DXF_INT } conica__dxf_type;

/* One group: its code, the line of the code, the value (trimmed of the
 * line end; numbers also of blanks) and, for numeric codes, the number. */
typedef struct conica__dxf_pair {
    int code;
    conica__dxf_type type;
    size_t line;
    size_t pos;   /* byte offset of its code line */
    const char *s;
    size_t n;
    double num;
} conica__dxf_pair;

/* A cursor over the pairs of a file (blocks are read again from their
 * offset, so nothing but one entity is ever held). */
typedef struct conica__dxf_lexer {
    const char *buf;
    size_t len, pos, line;
    int decimals; /* most digits after the point of a coordinate (codes 10..39) */
    int peeked;
    conica__dxf_pair peek;
} conica__dxf_lexer;

/* The pairs of one entity (a POLYLINE with its VERTEXes and SEQEND). */
typedef struct conica__dxf_ent {
    conica__dxf_pair *p;
    size_t n, cap;
} conica__dxf_ent;

/* A cursor at byte pos, line `line` (1-based) of buf. */
void conica__dxf_lex_at(conica__dxf_lexer *lx, const char *buf, size_t len, size_t pos,
                        size_t line);
/* The next pair: 1, 0 at the end of the input, or -1 with *st filled
 * (a code without value, a code that is not an integer, a number that
 * does not parse or is not finite, with the line). */
int conica__dxf_next(conica__dxf_lexer *lx, conica__dxf_pair *p, conica_status *st);
/* Push back the pair just read (one at most). */
void conica__dxf_unread(conica__dxf_lexer *lx, const conica__dxf_pair *p);
/* Does pair p have code `code` and the string value s? */
int conica__dxf_is(const conica__dxf_pair *p, int code, const char *s);
/* Read pairs up to (not including) the next code 0 into *e (cleared
 * first), at most max pairs; after a POLYLINE (or an INSERT with
 * attributes) up to its SEQEND. 1 ok, 0 end of input, -1 error. */
int conica__dxf_read_entity(conica__dxf_lexer *lx, const conica__dxf_pair *head,
                            conica__dxf_ent *e, size_t max, conica_status *st);
void conica__dxf_ent_free(conica__dxf_ent *e);

/* ------------------------------------------------------------ pieces */

/* x' = a x + b y + c, y' = d x + e y + f */
typedef struct conica__dxf_xf {
    double m[6];
} conica__dxf_xf;

typedef struct conica__dxf_seg {
    int degree;
    size_t pt; /* degree + 1 control points from here (x, y, w triples) */
} conica__dxf_seg;

/* One entity (or one HATCH edge) as a chain of segments. */
typedef struct conica__dxf_piece {
    size_t seg, nseg;
    int closed;       /* closed by its entity (CIRCLE, closed polyline, ...) */
    size_t line;      /* DXF line of the entity */
    size_t group;     /* pieces join only within one group (0: entities; k: HATCH path k) */
    const char *type; /* static entity type name */
    char handle[24];
    size_t layer;     /* index into the layer list */
} conica__dxf_piece;

typedef struct conica__dxf_geom {
    conica__dxf_piece *pc;
    size_t npc, pccap;
    conica__dxf_seg *sg;
    size_t nsg, sgcap;
    double *pt; /* x, y, w */
    size_t npt, ptcap;
    size_t max_points;
    int open; /* a piece is being built */
} conica__dxf_geom;

void conica__dxf_geom_init(conica__dxf_geom *g, size_t max_points);
void conica__dxf_geom_free(conica__dxf_geom *g);
conica_code conica__dxf_begin(conica__dxf_geom *g, const conica__dxf_piece *info,
                              conica_status *st);
/* End the open piece (an empty one is dropped). */
void conica__dxf_end(conica__dxf_geom *g, int closed);
conica_code conica__dxf_line(conica__dxf_geom *g, const conica__dxf_xf *xf, double x0, double y0,
                             double x1, double y1, size_t line, conica_status *st);
/* Elliptic arc c + M cos t + m sin t, t from t0 to t1 (radians, signed
 * sweep), as rational quadratics of at most 90 degrees. p0/p1: exact end
 * points to use (or NULL). */
conica_code conica__dxf_arc(conica__dxf_geom *g, const conica__dxf_xf *xf, const double c[2],
                            const double M[2], const double m[2], double t0, double t1,
                            const double *p0, const double *p1, size_t line, conica_status *st);
/* The arc of a polyline edge from p0 to p1 with bulge b (tan of a quarter
 * of the included angle, > 0 counter-clockwise); b == 0: a line. */
conica_code conica__dxf_bulge(conica__dxf_geom *g, const conica__dxf_xf *xf, const double p0[2],
                              const double p1[2], double b, size_t line, conica_status *st);
/* A B-spline's Bézier pieces (dim 2). */
conica_code conica__dxf_spline_pieces(conica__dxf_geom *g, const conica__dxf_xf *xf,
                                      const conica_bspline *bs, size_t line, conica_status *st);
/* cos and sin of an angle in degrees, exact at multiples of 90. */
void conica__dxf_sincos_deg(double deg, double *c, double *s);
void conica__dxf_xf_apply(const conica__dxf_xf *xf, double x, double y, double out[2]);
conica__dxf_xf conica__dxf_xf_mul(const conica__dxf_xf *a, const conica__dxf_xf *b);

/* ------------------------------------------------------------ entities */

/* What an entity builder needs: the limits, where pieces go, what the
 * piece records. */
typedef struct conica__dxf_ctx {
    const conica_dxf_limits *lim;
    conica__dxf_geom *geom;
    conica__dxf_piece info; /* line, type, handle, layer, group of the entity */
    conica_dxf_warn_fn warn;
    void *warn_ctx;
    size_t widths_warned, hatch_group;
} conica__dxf_ctx;

/* The OCS of an entity's extrusion (210/220/230) as a transform: identity
 * for +z, x mirrored for -z; other directions: 0 (not in the plane). */
int conica__dxf_ocs(const conica__dxf_ent *e, conica__dxf_xf *ocs);
/* Draw entity *e (pairs from its type on) under xf. Returns CONICA_OK with
 * *known = 0 for a type the reader does not draw. */
conica_code conica__dxf_entity(conica__dxf_ctx *c, const conica__dxf_ent *e,
                               const conica__dxf_xf *xf, int *known, conica_status *st);
/* The SPLINE entity *e as a B-spline (dim 2, or 3 when z varies). */
conica_code conica__dxf_spline_of(const conica__dxf_ent *e, const conica_dxf_limits *lim,
                                  const char *handle, conica_bspline *out, conica_status *st);

/* ------------------------------------------------------------ chaining */

typedef struct conica__dxf_chain_opts {
    double gap;
    conica_dxf_open open_mode;
    const char *const *layer_names;
    conica_dxf_warn_fn warn;
    void *warn_ctx;
} conica__dxf_chain_opts;

/* The pieces of g as closed subpaths of *path (one line each in *lines,
 * allocated); *joined: contours of several pieces; *closed_open: open
 * outlines closed by a straight edge. */
conica_code conica__dxf_chain(const conica__dxf_geom *g, const conica__dxf_chain_opts *o,
                              conica_path *path, size_t **lines, size_t *joined,
                              size_t *closed_open, conica_status *st);

#endif
