/* SPDX-License-Identifier: MIT */
/* The .scad writer: compact round-trip numbers, points, paths, modules. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <errno.h>
#include <string.h>

size_t conica_scad_format_double(double v, char *buf, size_t cap)
{
    /* The shortest of 15, 16 and 17 significant digits that reads back to
     * the same double (17 always does). strtod and %g follow LC_NUMERIC;
     * the tools never call setlocale, so both use the C locale's '.'. */
    static const char *const fmts[3] = {"%.15g", "%.16g", "%.17g"};
    int len = 0;
    if (!buf || cap == 0)
        return 0;
    if (v == 0.0 || !isfinite(v)) /* -0 prints as 0; non-finite never reaches here */
        v = 0.0;
    for (int i = 0; i < 3; i++) {
        len = snprintf(buf, cap, fmts[i], v);
        if (len < 0 || (size_t)len >= cap)
            break;
        if (strtod(buf, NULL) == v)
            break;
    }
    return len < 0 ? 0 : (size_t)len;
}

/* ------------------------------------------------------------ rounding */

/* v correctly rounded to d significant digits (1..17) by printf, read
 * back. */
static double to_digits(double v, int d)
{
    char buf[48];
    snprintf(buf, sizeof buf, "%.*e", d - 1, v);
    return strtod(buf, NULL);
}

/* The fewest significant digits d <= maxd whose decimal is within h of v,
 * that decimal's double in *r; 0 digits: *r = 0 (|v| <= h). Returns -1
 * when even maxd digits are too few. 17 digits always read back to v. The
 * error shrinks as digits are added (the nearest d-digit decimal is a
 * (d+1)-digit one too), so the search starts where the grid 10^k <= 2h
 * surely suffices and walks down while it still holds. */
static int fewest_digits(double v, double h, int maxd, double *r)
{
    double a = fabs(v), x;
    int d;
    if (a <= h) {
        *r = 0.0;
        return 0;
    }
    if (maxd > 17)
        maxd = 17;
    d = (int)floor(log10(a)) - (int)floor(log10(2 * h)) + 1;
    if (d < 1)
        d = 1;
    if (d > maxd)
        d = maxd;
    x = to_digits(v, d);
    while (!(fabs(x - v) <= h)) { /* log10 near a power of ten can be off by one */
        if (d >= maxd)
            return -1;
        x = to_digits(v, ++d);
    }
    while (d > 1) {
        double y = to_digits(v, d - 1);
        if (!(fabs(y - v) <= h))
            break;
        x = y;
        d--;
    }
    *r = x;
    return d;
}

conica_code conica_scad_round(const conica_scad_profile *p, double h, conica_scad_profile *out,
                              conica_status *st)
{
    conica_scad_profile q;
    double big = 0.0;
    if (!p || !out || !(h > 0) || !isfinite(h))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "rounding needs a profile and h > 0");
    for (size_t c = 0; c < p->ncontours; c++)
        for (size_t i = 0; i < 2 * p->contours[c].n; i++)
            big = fmax(big, fabs(p->contours[c].xy[i]));
    /* "exactly": to within rounding noise of the profile's size, on the
     * decimal grid of CONICA_SCAD_EXACT_MAX_DIGITS digits at that size */
    double hx = fmin(h, big * CONICA_SCAD_EXACT_REL);
    int grid = big > 0 ? (int)floor(log10(big)) - CONICA_SCAD_EXACT_MAX_DIGITS + 1 : 0;
    conica_scad_profile_init(&q);
    for (size_t g = 0; g < p->ngroups; g++)
        if (conica_scad_add_group(&q, p->groups[g].name, p->groups[g].fill, p->groups[g].line,
                                  NULL, st) != CONICA_OK) {
            conica_scad_profile_free(&q);
            return st ? st->code : CONICA_ERR_NOMEM;
        }
    for (size_t c = 0; c < p->ncontours; c++) {
        const conica_scad_contour *k = &p->contours[c];
        double *xy = malloc(2 * k->n * sizeof *xy);
        if (!xy) {
            conica_scad_profile_free(&q);
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
        }
        for (size_t i = 0; i < 2 * k->n; i++) {
            double v = k->xy[i], r = v, e; /* v as it is if no digits do */
            int d = fewest_digits(v, h, 17, &r);
            /* digits down to the grid: a small number gets no more
             * decimals than the largest (0.195443844 from 80 - 79.804556156
             * is no input number: noise of 80 is 1e-14, not 1e-9) */
            int dx = d + CONICA_SCAD_EXACT_EXTRA_DIGITS;
            if (v != 0.0 && (int)floor(log10(fabs(v))) - grid + 1 < dx)
                dx = (int)floor(log10(fabs(v))) - grid + 1;
            if (hx < h && dx >= 1 && fewest_digits(v, hx, dx, &e) >= 0)
                r = e;
            xy[i] = r == 0.0 ? 0.0 : r; /* no -0 */
        }
        conica_code rc = conica_scad_add_contour(&q, k->group, xy, k->n, st);
        free(xy);
        if (rc != CONICA_OK) {
            conica_scad_profile_free(&q);
            return rc;
        }
        q.contours[q.ncontours - 1].subpath = k->subpath;
    }
    conica_scad_profile_free(out);
    *out = q;
    conica__ok(st);
    return CONICA_OK;
}

/* ------------------------------------------------------------ names */

/* Words OpenSCAD's lexer (2021.01, src/lexer.l) turns into tokens, so they
 * cannot name a module or function: `module for()` is a syntax error.
 * `include` and `use` are lexed only before `<`, but are kept out too. */
static const char *const scad_keywords[] = {
    "assert", "each", "echo", "else", "false", "for", "function", "if",
    "include", "let", "module", "true", "undef", "use",
};
/* OpenSCAD's built-in modules (2021.01 and later: src/builtin.cc and the
 * modules it registers). A module of that name replaces the built-in for
 * the whole file and every file that `include`s it: `module polygon()`
 * calls itself, `module translate()` makes OpenSCAD stop with "Recursion
 * detected", `module circle()` silently changes the user's own circles. */
static const char *const scad_builtin_modules[] = {
    "children", "circle", "color", "cube", "cylinder", "difference", "dxf_linear_extrude",
    "dxf_rotate_extrude", "fill", "group", "hull", "import", "import_dxf", "import_off",
    "import_stl", "intersection", "intersection_for", "linear_extrude", "minkowski", "mirror",
    "multmatrix", "offset", "parent_module", "polygon", "polyhedron", "projection", "render",
    "resize", "roof", "rotate", "rotate_extrude", "scale", "sphere", "square", "surface",
    "text", "translate", "union",
};
/* Its built-in functions: modules and functions live apart in OpenSCAD,
 * but a library module named `len` or `str` is a trap for its users all
 * the same, so these are refused too. */
static const char *const scad_builtin_functions[] = {
    "abs", "acos", "asin", "atan", "atan2", "ceil", "chr", "concat", "cos", "cross",
    "dxf_cross", "dxf_dim", "exp", "floor", "fontmetrics", "is_bool", "is_function",
    "is_list", "is_num", "is_object", "is_string", "is_undef", "len", "ln", "log", "lookup",
    "max", "min", "norm", "object", "ord", "pow", "rands", "round", "search", "sign", "sin",
    "sqrt", "str", "tan", "textmetrics", "version", "version_num",
};

const char *conica_scad_name_problem(const char *s)
{
    size_t n = 0;
    if (!s || !*s)
        return "an empty name";
    if (!((s[0] >= 'A' && s[0] <= 'Z') || (s[0] >= 'a' && s[0] <= 'z') || s[0] == '_'))
        return "not an OpenSCAD identifier (it must start with a letter or '_')";
    for (; s[n]; n++) {
        char c = s[n];
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
              c == '_'))
            return "not an OpenSCAD identifier (letters, digits and '_' only)";
    }
    if (n > CONICA_SCAD_MAX_MODULE_NAME)
        return "too long for a module name";
    for (size_t i = 0; i < sizeof scad_keywords / sizeof scad_keywords[0]; i++)
        if (strcmp(s, scad_keywords[i]) == 0)
            return "an OpenSCAD reserved word";
    for (size_t i = 0; i < sizeof scad_builtin_modules / sizeof scad_builtin_modules[0]; i++)
        if (strcmp(s, scad_builtin_modules[i]) == 0)
            return "the name of an OpenSCAD built-in module (a module of that name would "
                   "replace it)";
    for (size_t i = 0; i < sizeof scad_builtin_functions / sizeof scad_builtin_functions[0]; i++)
        if (strcmp(s, scad_builtin_functions[i]) == 0)
            return "the name of an OpenSCAD built-in function";
    return NULL;
}

int conica_scad_valid_name(const char *s)
{
    return conica_scad_name_problem(s) == NULL;
}

conica_scad_write_options conica_scad_write_defaults(void)
{
    conica_scad_write_options o;
    memset(&o, 0, sizeof o);
    o.module = "profile";
    o.extrude_height = 10.0;
    o.revolve_angle = 360.0;
    o.instantiate = 0;
    return o;
}

/* Write the header text as // comments, one per line, without control
 * characters (a newline inside a file name must not end the comment). */
static void write_comment(FILE *f, const char *text)
{
    const char *p = text;
    while (*p) {
        fputs("// ", f);
        while (*p && *p != '\n') {
            unsigned char c = (unsigned char)*p++;
            fputc(c < 0x20 || c == 0x7f ? '?' : c, f);
        }
        fputc('\n', f);
        if (*p == '\n')
            p++;
    }
}

conica_code conica_scad_write(FILE *f, const conica_scad_profile *p, const conica_scad_layout *l,
                              const conica_scad_write_options *o, conica_status *st)
{
    char num[40], box[4][40];
    const char *name;
    size_t base = 0;
    int conv;
    if (!f || !p || !l || !o || l->npaths == 0)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "nothing to write");
    name = o->module ? o->module : "profile";
    if (!conica_scad_valid_name(name))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "module name '%.80s' is %s", name,
                            conica_scad_name_problem(name));
    if (o->extrude && !(isfinite(o->extrude_height) && o->extrude_height > 0))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "extrusion height must be > 0");
    if (o->revolve && !(isfinite(o->revolve_angle) && o->revolve_angle > 0 &&
                        o->revolve_angle <= 360))
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "revolve angle must be in (0, 360]");
    for (size_t i = 0; i < l->npaths; i++)
        if (l->paths[i].contour >= p->ncontours)
            return conica__fail(st, CONICA_ERR_ARG, 0, i, "layout does not match the profile");
    {
        /* the box of the numbers as written (format_double reads back exactly) */
        double b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < l->npaths; i++) {
            const conica_scad_contour *c = &p->contours[l->paths[i].contour];
            for (size_t k = 0; k < c->n; k++) {
                b[0] = fmin(b[0], c->xy[2 * k]);
                b[1] = fmin(b[1], c->xy[2 * k + 1]);
                b[2] = fmax(b[2], c->xy[2 * k]);
                b[3] = fmax(b[3], c->xy[2 * k + 1]);
            }
        }
        for (int i = 0; i < 4; i++)
            conica_scad_format_double(b[i], box[i], sizeof box[i]);
    }
    conv = l->convexity > 0 ? l->convexity : 1;

    if (o->header)
        write_comment(f, o->header);
    fprintf(f, "// %zu outer contour%s, %zu hole%s (outer counter-clockwise, holes clockwise);\n"
               "// bounding box [%s, %s] .. [%s, %s].\n",
            l->outers, l->outers == 1 ? "" : "s", l->holes, l->holes == 1 ? "" : "s", box[0],
            box[1], box[2], box[3]);
    if (o->instantiate)
        fprintf(f, "//\n"
                   "// Ends with a top-level call of %s%s() so that it renders alone;\n"
                   "// `use <this-file.scad>` skips that call (`include` would render it).\n",
                name, o->extrude ? "_extruded" : o->revolve ? "_revolved" : "");
    else
        fprintf(f, "//\n"
                   "// No top-level geometry: `include <this-file.scad>` or `use <...>`.\n");
    fprintf(f, "//   %s(center=false)  the 2D profile; center=true centres its box on [0, 0]\n"
               "//   %s_points()  [[x, y], ...]: outer contours first, then holes\n"
               "//   %s_paths()   [[i, ...], ...]: one index list per contour\n"
               "//   %s_bbox()    [[xmin, ymin], [xmax, ymax]]\n",
            name, name, name, name);
    if (o->extrude)
        fprintf(f, "//   %s_extruded(height, center)  linear_extrude of the profile\n", name);
    if (o->revolve)
        fprintf(f, "//   %s_revolved(angle)  rotate_extrude of the profile (about y)\n", name);
    fputc('\n', f);

    fprintf(f, "function %s_points() = [", name);
    for (size_t i = 0; i < l->npaths; i++) {
        const conica_scad_contour *c = &p->contours[l->paths[i].contour];
        for (size_t k = 0; k < c->n; k++) {
            size_t j = l->paths[i].reversed ? (c->n - k) % c->n : k; /* same first point */
            fputs(i == 0 && k == 0 ? "\n  [" : ",\n  [", f);
            conica_scad_format_double(c->xy[2 * j], num, sizeof num);
            fputs(num, f);
            fputc(',', f);
            conica_scad_format_double(c->xy[2 * j + 1], num, sizeof num);
            fputs(num, f);
            fputc(']', f);
        }
    }
    fputs("];\n\n", f);

    fprintf(f, "function %s_paths() = [", name);
    for (size_t i = 0; i < l->npaths; i++) {
        const conica_scad_contour *c = &p->contours[l->paths[i].contour];
        fputs(i == 0 ? "\n  [" : ",\n  [", f);
        for (size_t k = 0; k < c->n; k++) {
            if (k)
                fputs(k % 20 == 0 ? ",\n   " : ",", f);
            fprintf(f, "%zu", base + k);
        }
        fputc(']', f);
        base += c->n;
    }
    fputs("];\n\n", f);

    fprintf(f, "function %s_bbox() = [[%s,%s],[%s,%s]];\n\n", name, box[0], box[1], box[2],
            box[3]);
    fprintf(f,
            "module %s(center=false)\n"
            "  translate(center ? -(%s_bbox()[0] + %s_bbox()[1]) / 2 : [0, 0])\n"
            "    polygon(points=%s_points(), paths=%s_paths(), convexity=%d);\n",
            name, name, name, name, name, conv);
    if (o->extrude) {
        conica_scad_format_double(o->extrude_height, num, sizeof num);
        fprintf(f,
                "\nmodule %s_extruded(height=%s, center=false)\n"
                "  linear_extrude(height=height, center=center, convexity=%d) %s();\n",
                name, num, conv, name);
    }
    if (o->revolve) {
        conica_scad_format_double(o->revolve_angle, num, sizeof num);
        fprintf(f,
                "\nmodule %s_revolved(angle=%s)\n"
                "  rotate_extrude(angle=angle, convexity=%d) %s();\n",
                name, num, conv, name);
    }
    if (o->instantiate) {
        fputs("\n// Rendered when this file is opened or included; `use <...>` skips it.\n", f);
        if (o->extrude)
            fprintf(f, "%s_extruded();\n", name);
        else if (o->revolve)
            fprintf(f, "%s_revolved();\n", name);
        else
            fprintf(f, "%s();\n", name);
    }
    /* flushed here, so a full disk is named with its reason (issue 33) */
    if (fflush(f) != 0 || ferror(f))
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "write error: %s",
                            strerror(errno ? errno : EIO));
    conica__ok(st);
    return CONICA_OK;
}
