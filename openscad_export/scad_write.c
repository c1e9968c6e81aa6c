/* The .scad writer: compact round-trip numbers, points, paths, modules. */
#include "scad_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
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

/* Words OpenSCAD's lexer (2021.01, src/lexer.l) turns into tokens, so they
 * cannot name a module or function: `module for()` is a syntax error.
 * `include` and `use` are lexed only before `<`, but are kept out too. */
static const char *const scad_keywords[] = {
    "assert", "each", "echo", "else", "false", "for", "function", "if",
    "include", "let", "module", "true", "undef", "use",
};
/* Built-in modules the written file calls: a module of that name would
 * replace the built-in (`module polygon() polygon(...)` recurses). */
static const char *const scad_called_builtins[] = {
    "linear_extrude", "polygon", "rotate_extrude",
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
    for (size_t i = 0; i < sizeof scad_called_builtins / sizeof scad_called_builtins[0]; i++)
        if (strcmp(s, scad_called_builtins[i]) == 0)
            return "the name of a built-in module the generated file calls";
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
    o.instantiate = 1;
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
    char num[40];
    const char *name;
    size_t base = 0;
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

    if (o->header)
        write_comment(f, o->header);
    fprintf(f, "// %zu outer contour%s, %zu hole%s (outer counter-clockwise, holes clockwise).\n",
            l->outers, l->outers == 1 ? "" : "s", l->holes, l->holes == 1 ? "" : "s");
    fprintf(f, "// Use it from a model:  use <this-file.scad>  then  %s();\n\n", name);

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

    fprintf(f, "module %s() polygon(points=%s_points(), paths=%s_paths(), convexity=%d);\n",
            name, name, name, l->convexity > 0 ? l->convexity : 1);
    if (o->extrude) {
        conica_scad_format_double(o->extrude_height, num, sizeof num);
        fprintf(f,
                "\nmodule %s_extruded(height=%s, center=false)\n"
                "  linear_extrude(height=height, center=center, convexity=%d) %s();\n",
                name, num, l->convexity > 0 ? l->convexity : 1, name);
    }
    if (o->revolve) {
        conica_scad_format_double(o->revolve_angle, num, sizeof num);
        fprintf(f,
                "\nmodule %s_revolved(angle=%s)\n"
                "  rotate_extrude(angle=angle, convexity=%d) %s();\n",
                name, num, l->convexity > 0 ? l->convexity : 1, name);
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
    if (ferror(f))
        return conica__fail(st, CONICA_ERR_IO, 0, 0, "write error");
    conica__ok(st);
    return CONICA_OK;
}
