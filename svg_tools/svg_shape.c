/* SPDX-License-Identifier: MIT */
/* Basic shapes and points lists as path segments, the paths SVG 2 defines
 * for them (10.2-10.6): one place for svgsmooth's --convert-shapes and the
 * render (svg_render.c), which differ only in how they read the lengths.
 * Calls conica_svg__path_push() and conica_svg__arc_to_centre(). */
#include "svg_internal.h"

#include <string.h>

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

const char *const *conica_svg__shape_attrs(const char *tag)
{
    static const char *const rect[] = {"x", "y", "width", "height", "rx", "ry", NULL};
    static const char *const circle[] = {"cx", "cy", "r", NULL};
    static const char *const ellipse[] = {"cx", "cy", "rx", "ry", NULL};
    static const char *const line[] = {"x1", "y1", "x2", "y2", NULL};
    if (!strcmp(tag, "rect"))
        return rect;
    if (!strcmp(tag, "circle"))
        return circle;
    if (!strcmp(tag, "ellipse"))
        return ellipse;
    if (!strcmp(tag, "line"))
        return line;
    return NULL;
}

int conica_svg__shape_path(const char *tag, const double v[6], const int given[6],
                           conica_svg_path *p)
{
    pbuild b;
    memset(&b, 0, sizeof b);
    b.p = p;
    b.ok = 1;
    if (!strcmp(tag, "rect")) {
        double x = v[0], y = v[1], w = v[2], h = v[3], rx, ry;
        if (!(w > 0.0) || !(h > 0.0))
            return 0;
        rx = given[4] ? v[4] : given[5] ? v[5] : 0.0; /* auto: the other radius */
        ry = given[5] ? v[5] : given[4] ? v[4] : 0.0;
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
        double cx = v[0], cy = v[1], rx = v[2], ry;
        if (tag[0] == 'c') {
            ry = rx;
        } else {
            /* auto: the other radius */
            ry = given[3] ? v[3] : rx;
            rx = given[2] ? rx : ry;
        }
        if (!(rx > 0.0) || !(ry > 0.0))
            return 0;
        pb_move(&b, cx + rx, cy);
        pb_arc(&b, rx, ry, cx, cy + ry);
        pb_arc(&b, rx, ry, cx - rx, cy);
        pb_arc(&b, rx, ry, cx, cy - ry);
        pb_arc(&b, rx, ry, cx + rx, cy);
        pb_close(&b);
    } else if (!strcmp(tag, "line")) {
        pb_move(&b, v[0], v[1]);
        pb_line(&b, v[2], v[3]);
    } else {
        return 0;
    }
    return b.ok ? 1 : -2;
}

int conica_svg__points_path(const double *xy, size_t np, int closed, conica_svg_path *p)
{
    pbuild b;
    size_t i;
    memset(&b, 0, sizeof b);
    b.p = p;
    b.ok = 1;
    for (i = 0; i < np; i++) {
        if (i == 0)
            pb_move(&b, xy[0], xy[1]);
        else
            pb_line(&b, xy[2 * i], xy[2 * i + 1]);
    }
    if (np && closed)
        pb_close(&b);
    return b.ok;
}
