/* SPDX-License-Identifier: MIT */
/* scadprofile beside OpenSCAD's own import() on real glyph outlines.
 *
 * Every glyph of a fixed string (DejaVu Sans and Serif, FreeType's exact
 * quadratic outlines) becomes one SVG file whose width/height are given in
 * mm with a viewBox, so scadprofile and OpenSCAD's import() both map user
 * units to mm by the document (not by 96 or 72 dpi); half of the files are
 * written without Z (open subpaths ending where they start, as opentype.js
 * writes glyphs). Then, per file:
 *  - build/bin/scadprofile --tolerance T (T = 0.1, 0.01 mm), the polygon
 *    read from the .scad file at full precision, and OpenSCAD's rendering of
 *    that file (`openscad -o x.svg`);
 *  - OpenSCAD's import() of the file at its defaults, exported the same way;
 *  - both measured against the exact outline (mapped to mm as the document
 *    says) by the independent checker of tests/support: Hausdorff distance
 *    both ways, filled area, contours, bounding box (do the units agree?);
 *  - the scadprofile tolerance whose measured deviation matches import()'s,
 *    by bisection, and the points each needs at that deviation;
 *  - scadprofile's CPU time and peak RSS per run (fork/exec + wait4).
 * Prints markdown tables, asserts nothing. Without openscad on PATH only the
 * scadprofile part runs. */
#define _DEFAULT_SOURCE /* wait4 */
#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fidelity.h"
#include "glyphs.h"

#define TEXT "Sphinx gR&8 QZ@%$ao"
/* The em square in mm: capitals ~14.6 mm, x-height ~10.6 mm tall. */
#define EM_MM 20.0
/* Font units -> SVG user units; a power of two, so every coordinate of the
 * SVG (font units are integers or half-integers) is exact in decimal. */
#define USER_PER_UNIT 0.0625
/* Margin around the glyph's box, font units. */
#define MARGIN_UNITS 64.0
/* The tolerances of the main table, mm. */
static const double TOLS[] = {0.1, 0.01};
#define NTOLS (sizeof TOLS / sizeof TOLS[0])
/* Timed runs of scadprofile per file and tolerance (for p99). */
#define REPEATS 5
/* Runs of `scadprofile --version`: the cost of starting the program. */
#define STARTUP_RUNS 50
/* Equal-deviation search: T in [D / MATCH_RANGE, D * MATCH_RANGE], log
 * bisection steps. */
#define MATCH_RANGE 4.0
#define BISECT_STEPS 8
/* The checker is accurate to ~1e-12 of the size: a deviation above
 * T + TOL_SLACK_MM exceeds the tolerance. */
#define TOL_SLACK_MM 1e-9
/* OpenSCAD exports 6 significant digits; the glyph is centred on the origin
 * before export, so coordinates (|v| < 10 mm) keep 5 decimals: 5e-6 mm. A
 * bounding box farther than deviation + BBOX_SLACK_MM from the exact one
 * means the two tools read the units differently. */
#define BBOX_SLACK_MM 1e-4
/* Checker sampling (curve samples per segment, points inside each edge):
 * half the defaults' (64, 8), for quadratic glyph segments it gives the
 * same figures to every printed digit at a third of the run time. */
static const ts_sampling SAMPLING = {32, 4};
/* Sample density for the exact bounding box. */
#define BOX_SAMPLES 256
/* Targets of the issue, per scadprofile run on an icon-sized file. */
#define TARGET_CPU_S 0.1
#define TARGET_RSS_MB 32.0
#define MAX_GLYPHS 64
#define MAX_RUNS 4096
#define MAX_NOTES 64
#define PATHLEN 512

/* Polygons read back: contour k is vertices start[k] .. start[k + 1). */
typedef struct polyset {
    double *xy;
    size_t n, cap;
    size_t *start;
    size_t nc, ccap;
} polyset;

typedef struct measure {
    int ok;
    size_t points, contours;
    double dev;      /* Hausdorff distance, both directions, mm */
    double area_err; /* |filled area - exact|, mm^2 */
    double box_err;  /* largest difference of a bounding-box side, mm */
} measure;

typedef struct glyph {
    char label[32];   /* "Sans 'g'" */
    int close;        /* written with Z */
    ts_outline mm;    /* exact outline in mm, as both tools should map it */
    double box[4];    /* its bounding box: xmin, ymin, xmax, ymax */
    double center[2]; /* translation to the origin before OpenSCAD exports */
    double area;      /* exact filled area, mm^2 */
    size_t contours;
    int curved; /* has a quadratic or cubic segment */
    char svg[PATHLEN];
    measure at[NTOLS]; /* scadprofile at TOLS[j] */
    measure imp;       /* import() */
    measure match;     /* scadprofile at match_t, the equal-deviation tolerance */
    double match_t;
} glyph;

typedef struct cost {
    double cpu; /* user + system seconds */
    double rss; /* peak resident set, MB */
} cost;

/* One row of the main table. */
typedef struct row {
    const char *tool;
    double tol; /* 0: import() */
    int close;
    size_t files, points, contours, glyph_contours, drawn_contours, drawn_files;
    double dev_max, ratio_max, area_max, rel_max, drawn_dev_max, box_max;
    double dev[MAX_GLYPHS];
    size_t ndev;
    const char *worst;
} row;

static const char *g_scadprofile;
static const char *g_dir;
static int g_openscad;
static char g_notes[MAX_NOTES][160];
static size_t g_nnotes;
static cost g_runs[NTOLS + 1][MAX_RUNS]; /* per tolerance; last: bisection */
static size_t g_nruns[NTOLS + 1];
/* OpenSCAD's CPU seconds to render the files, summed: scadprofile's per
 * tolerance, then import()'s. */
static double g_render[NTOLS + 1];
/* scadprofile --fit F for every run when CONICA_BENCH_FIT=F is set. */
static const char *g_fit;

static void note(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (g_nnotes < MAX_NOTES)
        vsnprintf(g_notes[g_nnotes], sizeof g_notes[0], fmt, ap);
    va_end(ap);
    g_nnotes++;
}

/* ------------------------------------------------------------ processes */

/* Run argv (PATH searched when use_path), stdout and stderr to `log`
 * (NULL: /dev/null); the exit status, or -1 when it could not run. */
static int spawn(char *const argv[], int use_path, const char *log, cost *c)
{
    struct rusage ru;
    int status;
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        int fd = open(log ? log : "/dev/null", O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        if (use_path)
            execvp(argv[0], argv);
        else
            execv(argv[0], argv);
        _exit(127);
    }
    if (wait4(pid, &status, 0, &ru) < 0)
        return -1;
    if (c) {
        c->cpu = (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
                 (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
        c->rss = (double)ru.ru_maxrss / 1024.0; /* Linux: kilobytes */
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static int on_path(const char *prog)
{
    const char *p = getenv("PATH");
    char buf[PATHLEN];
    while (p && *p) {
        size_t n = strcspn(p, ":");
        if (n > 0 && n + strlen(prog) + 2 < sizeof buf) {
            memcpy(buf, p, n);
            snprintf(buf + n, sizeof buf - n, "/%s", prog);
            if (access(buf, X_OK) == 0)
                return 1;
        }
        p += n + (p[n] == ':');
    }
    return 0;
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    long n;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (buf = malloc((size_t)n + 1)) != NULL) {
        size_t got = fread(buf, 1, (size_t)n, f);
        buf[got] = '\0';
    }
    fclose(f);
    return buf;
}

/* Copy an executable; 0 on success. */
static int copy_exe(const char *from, const char *to)
{
    char buf[1 << 16];
    size_t n;
    int rc = 0;
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    if (!out) {
        if (in)
            fclose(in);
        return -1;
    }
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, n, out) != n)
            rc = -1;
    if (ferror(in))
        rc = -1;
    fclose(in);
    if (fclose(out) != 0)
        rc = -1;
    return rc == 0 ? chmod(to, 0700) : -1;
}

/* out = g_dir/name (PATHLEN bytes; the temporary directory's name is short). */
static void in_dir(char *out, const char *name)
{
    if (snprintf(out, PATHLEN, "%s/%s", g_dir, name) >= PATHLEN)
        out[0] = '\0';
}

/* ------------------------------------------------------------ polygons */

static void ps_init(polyset *p)
{
    memset(p, 0, sizeof *p);
}

static void ps_free(polyset *p)
{
    free(p->xy);
    free(p->start);
    ps_init(p);
}

static int ps_begin(polyset *p)
{
    if (p->nc + 2 > p->ccap) {
        size_t cap = p->ccap ? 2 * p->ccap : 16;
        size_t *s = realloc(p->start, cap * sizeof *s);
        if (!s)
            return -1;
        p->start = s;
        p->ccap = cap;
    }
    p->start[p->nc++] = p->n;
    p->start[p->nc] = p->n;
    return 0;
}

static int ps_point(polyset *p, double x, double y)
{
    if (p->n + 1 > p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 256;
        double *xy = realloc(p->xy, 2 * cap * sizeof *xy);
        if (!xy)
            return -1;
        p->xy = xy;
        p->cap = cap;
    }
    p->xy[2 * p->n] = x;
    p->xy[2 * p->n + 1] = y;
    p->n++;
    p->start[p->nc] = p->n;
    return 0;
}

/* Drop a closing vertex equal to the first, and contours under 3 points. */
static void ps_end(polyset *p)
{
    size_t s = p->start[p->nc - 1];
    if (p->n - s >= 2 && p->xy[2 * s] == p->xy[2 * p->n - 2] &&
        p->xy[2 * s + 1] == p->xy[2 * p->n - 1])
        p->n--;
    if (p->n - s < 3) {
        p->n = s;
        p->nc--;
    }
    p->start[p->nc] = p->n;
}

/* scadprofile's file: `NAME_points() = [[x,y],...];` and
 * `NAME_paths() = [[i,...],...];` */
static int parse_scad(const char *path, polyset *out)
{
    char *text = slurp(path), *s, *e;
    double *pts = NULL;
    size_t np = 0, cap = 0;
    int rc = -1;
    if (!text)
        return -1;
    s = strstr(text, "_points() = [");
    if (!s)
        goto done;
    s += strlen("_points() = [");
    for (;;) {
        double x, y;
        while (*s == ' ' || *s == '\n' || *s == ',')
            s++;
        if (*s != '[')
            break;
        x = strtod(s + 1, &e);
        if (*e != ',')
            goto done;
        y = strtod(e + 1, &s);
        if (*s != ']')
            goto done;
        s++;
        if (np + 1 > cap) {
            double *q = realloc(pts, 2 * (cap = cap ? 2 * cap : 256) * sizeof *q);
            if (!q)
                goto done;
            pts = q;
        }
        pts[2 * np] = x;
        pts[2 * np + 1] = y;
        np++;
    }
    s = strstr(s, "_paths() = [");
    if (!s)
        goto done;
    s += strlen("_paths() = [");
    for (;;) {
        while (*s == ' ' || *s == '\n' || *s == ',')
            s++;
        if (*s != '[')
            break;
        s++;
        if (ps_begin(out))
            goto done;
        for (;;) {
            unsigned long k = strtoul(s, &e, 10);
            if (e == s || k >= np || ps_point(out, pts[2 * k], pts[2 * k + 1]))
                goto done;
            s = e;
            while (*s == ' ' || *s == '\n')
                s++;
            if (*s == ',')
                s++;
            else if (*s == ']') {
                s++;
                break;
            } else
                goto done;
        }
        ps_end(out);
    }
    rc = out->nc ? 0 : -1;
done:
    free(pts);
    free(text);
    return rc;
}

/* OpenSCAD's SVG export: `d="M x,y L x,y ... z M ..."`, y negated; the
 * glyph was translated by -center before export. */
static int parse_openscad_svg(const char *path, const double center[2], polyset *out)
{
    char *text = slurp(path), *s;
    int rc = 0;
    if (!text)
        return -1;
    for (s = strstr(text, " d=\""); s && rc == 0; s = strstr(s, " d=\"")) {
        int open = 0;
        for (s += 4; *s && *s != '"' && rc == 0;) {
            char *e;
            double x, y;
            if (*s == 'M') {
                if (open)
                    ps_end(out);
                rc = ps_begin(out);
                open = 1;
                s++;
            } else if (*s == 'z' || *s == 'Z') {
                if (open)
                    ps_end(out);
                open = 0;
                s++;
            } else if (*s == 'L' || *s == ' ' || *s == '\n' || *s == ',') {
                s++;
            } else {
                x = strtod(s, &e);
                if (e == s || *e != ',' || !open) {
                    rc = -1;
                    break;
                }
                y = strtod(e + 1, &s);
                rc = ps_point(out, x + center[0], -y + center[1]);
            }
        }
        if (open && rc == 0)
            ps_end(out);
    }
    free(text);
    return rc == 0 && out->nc ? 0 : -1;
}

/* ------------------------------------------------------------ measuring */

static int inside(const double *xy, size_t n, double x, double y)
{
    int in = 0;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
        double yi = xy[2 * i + 1], yj = xy[2 * j + 1];
        if ((yi > y) != (yj > y) && x < xy[2 * j] + (y - yj) / (yi - yj) * (xy[2 * i] - xy[2 * j]))
            in = !in;
    }
    return in;
}

/* Filled area whatever the orientation the tool wrote: a contour inside an
 * odd number of others is a hole (glyph contours do not cross). */
static double filled_area(const polyset *p)
{
    double a = 0;
    for (size_t k = 0; k < p->nc; k++) {
        const double *xy = p->xy + 2 * p->start[k];
        size_t n = p->start[k + 1] - p->start[k];
        int depth = 0;
        for (size_t m = 0; m < p->nc; m++)
            if (m != k)
                depth +=
                    inside(p->xy + 2 * p->start[m], p->start[m + 1] - p->start[m], xy[0], xy[1]);
        a += (depth % 2 ? -1 : 1) * fabs(ts_poly_area(xy, n));
    }
    return a;
}

static measure measure_polys(const glyph *g, const polyset *p)
{
    measure m;
    ts_poly *polys = malloc((p->nc ? p->nc : 1) * sizeof *polys);
    ts_hausdorff h;
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    memset(&m, 0, sizeof m);
    if (!polys || !p->nc) {
        free(polys);
        return m;
    }
    for (size_t k = 0; k < p->nc; k++) {
        polys[k].xy = p->xy + 2 * p->start[k];
        polys[k].n = p->start[k + 1] - p->start[k];
        polys[k].closed = 1;
    }
    for (size_t i = 0; i < p->n; i++) {
        box[0] = fmin(box[0], p->xy[2 * i]);
        box[1] = fmin(box[1], p->xy[2 * i + 1]);
        box[2] = fmax(box[2], p->xy[2 * i]);
        box[3] = fmax(box[3], p->xy[2 * i + 1]);
    }
    if (ts_hausdorff_measure(g->mm.c, g->mm.n, polys, p->nc, &SAMPLING, &h) == TS_OK) {
        m.ok = 1;
        m.dev = h.max;
        m.points = p->n;
        m.contours = p->nc;
        m.area_err = fabs(filled_area(p) - g->area);
        for (int i = 0; i < 4; i++)
            m.box_err = fmax(m.box_err, fabs(box[i] - g->box[i]));
    }
    free(polys);
    return m;
}

/* scadprofile --tolerance tol on the glyph's file, measured when `check`;
 * the run's cost in *c. */
static measure run_scadprofile(const glyph *g, double tol, const char *out, int check, cost *c)
{
    char t[40], *argv[11];
    int k = 7;
    polyset p;
    measure m;
    memset(&m, 0, sizeof m);
    snprintf(t, sizeof t, "%.17g", tol);
    argv[0] = (char *)g_scadprofile;
    argv[1] = "--tolerance";
    argv[2] = t;
    argv[3] = "-o";
    argv[4] = (char *)out;
    argv[5] = "--module"; /* the rendering .scad calls profile() */
    argv[6] = "profile";
    if (g_fit) {
        argv[k++] = "--fit";
        argv[k++] = (char *)g_fit;
    }
    argv[k++] = (char *)g->svg;
    argv[k] = NULL;
    if (spawn(argv, 0, NULL, c) != 0) {
        note("%s: scadprofile --tolerance %g failed", g->label, tol);
        return m;
    }
    if (!check) {
        m.ok = 1;
        return m;
    }
    ps_init(&p);
    if (parse_scad(out, &p) == 0)
        m = measure_polys(g, &p);
    else
        note("%s: cannot read scadprofile's output at T = %g", g->label, tol);
    ps_free(&p);
    return m;
}

/* One run of the equal-deviation search, its cost recorded. */
static measure search_run(const glyph *g, double tol, const char *out)
{
    cost c;
    measure m = run_scadprofile(g, tol, out, 1, &c);
    if (m.ok && g_nruns[NTOLS] < MAX_RUNS)
        g_runs[NTOLS][g_nruns[NTOLS]++] = c;
    return m;
}

/* `openscad -o x.svg` of a two-line .scad (`pre` then the translated
 * `body`), measured. */
static measure run_openscad(const glyph *g, const char *pre, const char *body, const char *what,
                            size_t render)
{
    cost rc;
    char scad[PATHLEN], svg[PATHLEN], log[PATHLEN], text[2 * PATHLEN], *argv[5], *l;
    polyset p;
    measure m;
    memset(&m, 0, sizeof m);
    in_dir(scad, "openscad.scad");
    in_dir(svg, "openscad.svg");
    in_dir(log, "openscad.log");
    snprintf(text, sizeof text, "%stranslate([%.17g, %.17g]) %s;\n", pre, -g->center[0],
             -g->center[1], body);
    if (ts_write_file(scad, text) != TS_OK)
        return m;
    remove(svg);
    argv[0] = "openscad";
    argv[1] = "-o";
    argv[2] = svg;
    argv[3] = scad;
    argv[4] = NULL;
    if (spawn(argv, 1, log, &rc) != 0) {
        note("%s: openscad failed (%s)", g->label, what);
        return m;
    }
    g_render[render] += rc.cpu;
    if ((l = slurp(log)) != NULL) {
        if (strstr(l, "WARNING") || strstr(l, "ERROR"))
            note("%s: openscad warns (%s)", g->label, what);
        free(l);
    }
    ps_init(&p);
    if (parse_openscad_svg(svg, g->center, &p) == 0)
        m = measure_polys(g, &p);
    else
        note("%s: cannot read OpenSCAD's export (%s)", g->label, what);
    ps_free(&p);
    return m;
}

/* ------------------------------------------------------------ glyph files */

static int build_glyph(const ts_outline *o, int upem, const char *font, unsigned long cp, int close,
                       size_t index, glyph *g)
{
    double a = EM_MM / upem, b[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    double vw, vh, k = EM_MM / (upem * USER_PER_UNIT);
    ts_svg_opts opt = ts_svg_defaults();
    char *d = NULL, *doc;
    size_t len;

    memset(g, 0, sizeof *g);
    snprintf(g->label, sizeof g->label, "%s '%c'", font, (int)cp);
    g->close = close;
    /* bounding box in font units, rounded out to integers: exact SVG numbers */
    for (size_t i = 0; i < o->n; i++) {
        double *xy;
        size_t n;
        if (ts_contour_sample(&o->c[i], BOX_SAMPLES, &xy, &n) != TS_OK)
            return -1;
        for (size_t j = 0; j < n; j++) {
            b[0] = fmin(b[0], xy[2 * j]);
            b[1] = fmin(b[1], xy[2 * j + 1]);
            b[2] = fmax(b[2], xy[2 * j]);
            b[3] = fmax(b[3], xy[2 * j + 1]);
        }
        free(xy);
    }
    b[0] = floor(b[0]);
    b[1] = floor(b[1]);
    b[2] = ceil(b[2]);
    b[3] = ceil(b[3]);
    /* SVG: X = s (x - xmin + M), Y = s (ymax + M - y), canvas (xmax - xmin +
     * 2 M) s by (ymax - ymin + 2 M) s user units, given as k mm per user
     * unit. A tool that honours width/height/viewBox and flips y about the
     * canvas maps (x, y) to a (x - xmin + M, y - ymin + M) mm, a = k s. */
    opt.scale = USER_PER_UNIT;
    opt.x0 = USER_PER_UNIT * (MARGIN_UNITS - b[0]);
    opt.y0 = USER_PER_UNIT * (b[3] + MARGIN_UNITS);
    opt.close = close;
    opt.digits = 15;
    vw = USER_PER_UNIT * (b[2] - b[0] + 2 * MARGIN_UNITS);
    vh = USER_PER_UNIT * (b[3] - b[1] + 2 * MARGIN_UNITS);
    if (ts_outline_svg_path(o, &opt, &d) != TS_OK)
        return -1;
    len = strlen(d) + 512;
    doc = malloc(len);
    if (!doc) {
        free(d);
        return -1;
    }
    snprintf(doc, len,
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.17gmm\" height=\"%.17gmm\""
             " viewBox=\"0 0 %.17g %.17g\">\n<path id=\"glyph\" d=\"%s\"/>\n</svg>\n",
             vw * k, vh * k, vw, vh, d);
    free(d);
    snprintf(g->svg, sizeof g->svg, "%s/glyph%02zu.svg", g_dir, index);
    if (ts_write_file(g->svg, doc) != TS_OK) {
        free(doc);
        return -1;
    }
    free(doc);

    /* the exact outline in mm */
    g->mm.n = o->n;
    g->mm.c = calloc(o->n, sizeof *g->mm.c);
    if (!g->mm.c)
        return -1;
    for (size_t i = 0; i < o->n; i++) {
        ts_contour *c = &g->mm.c[i];
        c->n = o->c[i].n;
        c->closed = o->c[i].closed;
        c->seg = malloc(c->n * sizeof *c->seg);
        if (!c->seg)
            return -1;
        for (size_t j = 0; j < c->n; j++) {
            c->seg[j] = o->c[i].seg[j];
            g->curved |= c->seg[j].degree > 1;
            for (int q = 0; q <= c->seg[j].degree; q++) {
                c->seg[j].p[q][0] = a * (o->c[i].seg[j].p[q][0] - b[0] + MARGIN_UNITS);
                c->seg[j].p[q][1] = a * (o->c[i].seg[j].p[q][1] - b[1] + MARGIN_UNITS);
            }
        }
    }
    g->contours = o->n;
    g->area = fabs(ts_outline_area(&g->mm));
    g->box[0] = g->box[1] = INFINITY;
    g->box[2] = g->box[3] = -INFINITY;
    for (size_t i = 0; i < g->mm.n; i++) {
        double *xy;
        size_t n;
        if (ts_contour_sample(&g->mm.c[i], BOX_SAMPLES, &xy, &n) != TS_OK)
            return -1;
        for (size_t j = 0; j < n; j++) {
            g->box[0] = fmin(g->box[0], xy[2 * j]);
            g->box[1] = fmin(g->box[1], xy[2 * j + 1]);
            g->box[2] = fmax(g->box[2], xy[2 * j]);
            g->box[3] = fmax(g->box[3], xy[2 * j + 1]);
        }
        free(xy);
    }
    /* a multiple of 1/64 mm: printed exactly in the .scad */
    g->center[0] = round(32 * (g->box[0] + g->box[2])) / 64;
    g->center[1] = round(32 * (g->box[1] + g->box[3])) / 64;
    return 0;
}

/* ------------------------------------------------------------ statistics */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Nearest-rank percentile of v[0..n) (sorted in place). */
static double pct(double *v, size_t n, double q)
{
    size_t r;
    if (!n)
        return NAN;
    qsort(v, n, sizeof *v, cmp_double);
    r = (size_t)ceil(q * (double)n);
    return v[r ? r - 1 : 0];
}

static void add_row(row *r, const glyph *g, const measure *m, const measure *drawn)
{
    if (!m->ok)
        return;
    r->files++;
    r->points += m->points;
    r->contours += m->contours;
    r->glyph_contours += g->contours;
    if (m->dev > r->dev_max) {
        r->dev_max = m->dev;
        r->worst = g->label;
    }
    if (r->tol > 0)
        r->ratio_max = fmax(r->ratio_max, m->dev / r->tol);
    r->area_max = fmax(r->area_max, m->area_err);
    r->rel_max = fmax(r->rel_max, m->area_err / g->area);
    r->box_max = fmax(r->box_max, m->box_err);
    if (r->ndev < MAX_GLYPHS)
        r->dev[r->ndev++] = m->dev;
    if (drawn && drawn->ok) {
        r->drawn_files++;
        r->drawn_contours += drawn->contours;
        r->drawn_dev_max = fmax(r->drawn_dev_max, drawn->dev);
        r->box_max = fmax(r->box_max, drawn->box_err);
    }
}

static void print_row(row *r)
{
    char tol[16] = "-", ratio[16] = "-", drawn[40] = "-", ddev[16] = "-";
    double med = pct(r->dev, r->ndev, 0.5);
    if (!r->files)
        return;
    if (r->tol > 0) {
        snprintf(tol, sizeof tol, "%g", r->tol);
        snprintf(ratio, sizeof ratio, "%.3f", r->ratio_max);
    }
    if (r->drawn_files) {
        snprintf(drawn, sizeof drawn, "%zu/%zu", r->drawn_contours, r->glyph_contours);
        snprintf(ddev, sizeof ddev, "%.4f", r->drawn_dev_max);
    }
    printf("| %s | %s | %s | %zu | %zu | %.4f (%s) | %.4f | %s | %.4f | %.3f%% | %zu/%zu | "
           "%s | %s | %.1e |\n",
           r->tool, tol, r->close ? "closed (Z)" : "open (no Z)", r->files, r->points, r->dev_max,
           r->worst, med, ratio, r->area_max, 100 * r->rel_max, r->contours, r->glyph_contours,
           drawn, ddev, r->box_max);
}

static void print_costs(const char *what, cost *c, size_t n)
{
    double *cpu = malloc((n ? n : 1) * sizeof *cpu), *rss = malloc((n ? n : 1) * sizeof *rss);
    if (!cpu || !rss || !n) {
        free(cpu);
        free(rss);
        return;
    }
    for (size_t i = 0; i < n; i++) {
        cpu[i] = c[i].cpu;
        rss[i] = c[i].rss;
    }
    {
        /* pct sorts: every figure first, then the maxima */
        double c50 = pct(cpu, n, 0.5), c99 = pct(cpu, n, 0.99);
        double r50 = pct(rss, n, 0.5), r99 = pct(rss, n, 0.99);
        printf("| %s | %zu | %.3f | %.3f | %.3f | %.1f | %.1f | %.1f |\n", what, n, c50, c99,
               cpu[n - 1], r50, r99, rss[n - 1]);
    }
    free(cpu);
    free(rss);
}

static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char path[PATHLEN];
    if (!d)
        return;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) {
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            remove(path);
        }
    closedir(d);
    rmdir(dir);
}

/* ------------------------------------------------------------ main */

int main(int argc, char **argv)
{
    static glyph gl[MAX_GLYPHS];
    static row rows[2][1 + NTOLS];
    static double ratio[3][MAX_GLYPHS], match_t[MAX_GLYPHS];
    const char *fonts[2] = {TS_FONT_SANS, TS_FONT_SERIF}, *names[2] = {"Sans", "Serif"};
    char sp_default[PATHLEN], sp_copy[PATHLEN], tmpl[PATHLEN], out[PATHLEN];
    size_t ng = 0, nratio[3] = {0, 0, 0}, pts_sp[3] = {0, 0, 0}, pts_imp[3] = {0, 0, 0};
    size_t worst_ratio_g = 0, nlist = 0, straight = 0, straight_pts[2] = {0, 0};
    double worst_ratio = 0, dev_imp_sum[3] = {0, 0, 0};
    int keep = 0, per_glyph = 0;
    const char *tmpdir = getenv("TMPDIR");
    struct rusage self;

    g_scadprofile = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--keep") == 0)
            keep = 1;
        else if (strcmp(argv[i], "--glyphs") == 0)
            per_glyph = 1;
        else if (strcmp(argv[i], "--scadprofile") == 0 && i + 1 < argc)
            g_scadprofile = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--scadprofile PATH] [--glyphs] [--keep]\n", argv[0]);
            return 2;
        }
    }
    if (!g_scadprofile) {
        /* build/bench/bench_scad_import -> build/bin/scadprofile */
        const char *slash = strrchr(argv[0], '/');
        snprintf(sp_default, sizeof sp_default, "%.*s%sbin/scadprofile",
                 slash ? (int)(slash - argv[0]) : 0, argv[0], slash ? "/../" : "../");
        g_scadprofile = sp_default;
    }
    if (access(g_scadprofile, X_OK) != 0) {
        printf("%s: not built (make -j2)\n", g_scadprofile);
        return 0;
    }
    g_openscad = on_path("openscad");
    g_fit = getenv("CONICA_BENCH_FIT");
    snprintf(tmpl, sizeof tmpl, "%s/bench-scad-import.XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
    if (!mkdtemp(tmpl)) {
        perror("mkdtemp");
        return 1;
    }
    g_dir = tmpl;
    /* Run a private copy: the tree is shared, and a rebuild of the binary
     * in the middle of the run would fail the runs that meet it. */
    in_dir(sp_copy, "scadprofile");
    if (copy_exe(g_scadprofile, sp_copy) == 0)
        g_scadprofile = sp_copy;

    for (int f = 0; f < 2; f++) {
        ts_text t;
        size_t k = 0;
        ts_text_init(&t);
        if (ts_text_outlines(fonts[f], TEXT, &t) != TS_OK) {
            printf("%s: not available (install fonts-dejavu-core libfreetype-dev)\n", fonts[f]);
            continue;
        }
        for (size_t i = 0; i < t.n && ng < MAX_GLYPHS; i++) {
            if (!t.glyph[i].n)
                continue;
            /* alternate Z / no Z, shifted between the fonts so that every
             * character is written both ways */
            if (build_glyph(&t.glyph[i], t.units_per_em, names[f], t.cp[i],
                            (int)((k + (size_t)f) % 2 == 0), ng, &gl[ng]) == 0)
                ng++;
            else
                ts_outline_free(&gl[ng].mm);
            k++;
        }
        ts_text_free(&t);
    }
    if (!ng) {
        remove_dir(g_dir);
        return 0;
    }

    for (int c = 0; c < 2; c++) {
        rows[c][0].tool = "OpenSCAD import()";
        rows[c][0].close = !c;
        for (size_t j = 0; j < NTOLS; j++) {
            rows[c][1 + j].tool = "scadprofile";
            rows[c][1 + j].tol = TOLS[j];
            rows[c][1 + j].close = !c;
        }
    }
    in_dir(out, "profile.scad");
    for (size_t i = 0; i < ng; i++) {
        glyph *g = &gl[i];
        int c = !g->close;
        measure imp;
        memset(&imp, 0, sizeof imp);
        for (size_t j = 0; j < NTOLS; j++) {
            measure m, drawn;
            cost cst;
            memset(&drawn, 0, sizeof drawn);
            for (int r = 0; r < REPEATS; r++) {
                m = run_scadprofile(g, TOLS[j], out, r == REPEATS - 1, &cst);
                if (m.ok && g_nruns[j] < MAX_RUNS)
                    g_runs[j][g_nruns[j]++] = cst;
            }
            if (!m.ok)
                continue;
            g->at[j] = m;
            if (m.dev > TOLS[j] + TOL_SLACK_MM)
                note("%s: scadprofile exceeds its tolerance: %.6f mm at T = %g", g->label, m.dev,
                     TOLS[j]);
            if (m.contours != g->contours)
                note("%s: scadprofile writes %zu of %zu contours at T = %g", g->label, m.contours,
                     g->contours, TOLS[j]);
            if (g_openscad) {
                char pre[PATHLEN + 16];
                snprintf(pre, sizeof pre, "use <%s>\n", out);
                drawn = run_openscad(g, pre, "profile()", "scadprofile", j);
                if (drawn.ok && drawn.contours != g->contours)
                    note("%s: OpenSCAD draws %zu of %zu contours of scadprofile's file (T = %g)",
                         g->label, drawn.contours, g->contours, TOLS[j]);
            }
            add_row(&rows[c][1 + j], g, &m, g_openscad ? &drawn : NULL);
            if (m.box_err > m.dev + BBOX_SLACK_MM)
                note("%s: scadprofile's box is %.4f mm off (deviation %.4f): units?", g->label,
                     m.box_err, m.dev);
        }
        if (!g_openscad)
            continue;
        {
            char body[PATHLEN + 16];
            snprintf(body, sizeof body, "import(\"%s\")", g->svg);
            imp = run_openscad(g, "", body, "import", NTOLS);
        }
        if (!imp.ok)
            continue;
        g->imp = imp;
        add_row(&rows[c][0], g, &imp, &imp);
        if (imp.box_err > imp.dev + BBOX_SLACK_MM)
            note("%s: import()'s box is %.4f mm off (deviation %.4f): units?", g->label,
                 imp.box_err, imp.dev);
        if (imp.contours != g->contours)
            note("%s: import() draws %zu of %zu contours", g->label, imp.contours, g->contours);
        /* Equal measured deviation: the largest T (log bisection) whose
         * measured deviation stays within import()'s. A glyph of straight
         * edges only is exact in both (the deviation is export rounding). */
        if (!g->curved) {
            straight++;
            straight_pts[0] += imp.points;
            straight_pts[1] += g->at[NTOLS - 1].points;
        } else {
            double d = imp.dev, lo = d / MATCH_RANGE, hi = d * MATCH_RANGE;
            int f = strncmp(g->label, "Sans", 4) == 0 ? 0 : 1;
            measure best = search_run(g, hi, out);
            if (!(best.ok && best.dev <= d)) {
                best = search_run(g, lo, out);
                for (int s = 0; s < BISECT_STEPS && best.ok; s++) {
                    double mid = sqrt(lo * hi);
                    measure m = search_run(g, mid, out);
                    if (!m.ok)
                        break;
                    if (m.dev <= d) {
                        lo = mid;
                        best = m;
                    } else
                        hi = mid;
                }
                if (best.ok && best.dev > d)
                    note("%s: scadprofile at T = %g still deviates %.5f mm > import()'s %.5f",
                         g->label, lo, best.dev, d);
            } else
                lo = hi;
            if (best.ok) {
                double q = (double)best.points / (double)imp.points;
                for (int k = 0; k < 2; k++) {
                    int s = k ? 2 : f;
                    ratio[s][nratio[s]++] = q;
                    pts_sp[s] += best.points;
                    pts_imp[s] += imp.points;
                    dev_imp_sum[s] += d;
                }
                match_t[nlist++] = lo / d;
                g->match = best;
                g->match_t = lo;
                if (q > worst_ratio) {
                    worst_ratio = q;
                    worst_ratio_g = i;
                }
            }
        }
    }

    printf("scadprofile beside OpenSCAD import() on glyph outlines: \"%s\", DejaVu Sans and\n"
           "Serif, %zu files, em = %g mm, every other file without Z; checker: tests/support\n"
           "(Hausdorff both directions, mm)\n\n",
           TEXT, ng, EM_MM);
    printf("scadprofile --fit %s\n\n", g_fit ? g_fit : "inside (default)");
    if (!g_openscad)
        printf("openscad is not on PATH: the import() comparison is skipped.\n\n");
    printf("| tool | T (mm) | subpaths | files | points | worst deviation (glyph) | median "
           "deviation | worst dev / T | area error max (mm²) | area error max (rel.) | contours "
           "written | contours OpenSCAD draws | drawn: worst deviation | bbox worst diff (mm) |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t j = 0; j <= NTOLS; j++)
        for (int c = 0; c < 2; c++)
            print_row(&rows[c][j]);

    if (g_openscad) {
        printf("\nOpenSCAD's CPU seconds to render all the files above (`openscad -o x.svg`, "
               "summed): import() %.2f", g_render[NTOLS]);
        for (size_t j = 0; j < NTOLS; j++)
            printf("; scadprofile T = %g mm: %.2f", TOLS[j], g_render[j]);
        printf("\n");
    }
    if (g_openscad && nratio[2]) {
        double med_t;
        printf("\nPoints at equal measured deviation, glyphs with curves: per glyph, the largest "
               "scadprofile\ntolerance T* whose measured deviation is within import()'s (log "
               "bisection, %d steps in\n[D/%g, %g D]); ratio = scadprofile's points at T* / "
               "import()'s.\n\n",
               BISECT_STEPS, MATCH_RANGE, MATCH_RANGE);
        printf("| font | glyphs | import() mean deviation (mm) | import() points | scadprofile "
               "points at T* | ratio median | ratio max | ratio min "
               "|\n|---|---|---|---|---|---|---|---|\n");
        for (int f = 0; f < 3; f++) {
            size_t n = nratio[f];
            double med, mx, mn;
            if (!n)
                continue;
            med = pct(ratio[f], n, 0.5);
            mx = ratio[f][n - 1];
            mn = ratio[f][0];
            printf("| %s | %zu | %.4f | %zu | %zu | %.3f | %.3f | %.3f |\n",
                   f == 2 ? "both" : names[f], n, dev_imp_sum[f] / (double)n, pts_imp[f], pts_sp[f],
                   med, mx, mn);
        }
        med_t = pct(match_t, nlist, 0.5);
        printf("\nLargest ratio: %s (%.3f). T* / import()'s deviation: median %.2f, "
               "range %.2f .. %.2f.\n",
               gl[worst_ratio_g].label, worst_ratio, med_t, match_t[0], match_t[nlist - 1]);
        printf("%zu glyphs of straight edges only (left out above): import() %zu points, "
               "scadprofile at T = %g %zu.\n",
               straight, straight_pts[0], TOLS[NTOLS - 1], straight_pts[1]);
    }

    if (per_glyph) {
        printf("\nPer glyph (deviation in mm; T* the equal-deviation tolerance):\n\n"
               "| glyph | Z | contours | import() points | import() dev | T* | scadprofile dev "
               "at T* | points at T* | ratio |");
        for (size_t j = 0; j < NTOLS; j++)
            printf(" T = %g: points | dev |", TOLS[j]);
        printf("\n|---|---|---|---|---|---|---|---|---|");
        for (size_t j = 0; j < NTOLS; j++)
            printf("---|---|");
        printf("\n");
        for (size_t i = 0; i < ng; i++) {
            const glyph *g = &gl[i];
            printf("| %s | %s | %zu | %zu | %.5f |", g->label, g->close ? "yes" : "no", g->contours,
                   g->imp.points, g->imp.dev);
            if (g->match.ok && g->imp.points)
                printf(" %.5f | %.5f | %zu | %.3f |", g->match_t, g->match.dev, g->match.points,
                       (double)g->match.points / (double)g->imp.points);
            else
                printf(" - | - | - | - |");
            for (size_t j = 0; j < NTOLS; j++)
                printf(" %zu | %.5f |", g->at[j].points, g->at[j].dev);
            printf("\n");
        }
    }

    getrusage(RUSAGE_SELF, &self);
    printf("\nscadprofile per run (fork/exec, wait4 rusage: user + system CPU s, peak RSS MB; "
           "targets\nfor an icon: p99 CPU < %g s, RSS < %g MB; the forked child's RSS "
           "counts this\nprogram's %.1f MB before exec, a floor for the column):\n\n",
           TARGET_CPU_S, TARGET_RSS_MB, (double)self.ru_maxrss / 1024.0);
    printf("| runs | n | CPU p50 | CPU p99 | CPU max | RSS p50 | RSS p99 | RSS max |\n"
           "|---|---|---|---|---|---|---|---|\n");
    {
        static cost all[(NTOLS + 1) * MAX_RUNS];
        size_t na = 0;
        for (size_t j = 0; j <= NTOLS; j++) {
            char what[64];
            if (j < NTOLS)
                snprintf(what, sizeof what, "T = %g mm, %d runs per file", TOLS[j], REPEATS);
            else
                snprintf(what, sizeof what, "equal-deviation search");
            print_costs(what, g_runs[j], g_nruns[j]);
            memcpy(all + na, g_runs[j], g_nruns[j] * sizeof *all);
            na += g_nruns[j];
        }
        print_costs("all of the above", all, na);
        {
            static cost up[STARTUP_RUNS];
            char *args[3];
            size_t nu = 0;
            args[0] = (char *)g_scadprofile;
            args[1] = "--version";
            args[2] = NULL;
            for (int r = 0; r < STARTUP_RUNS; r++)
                if (spawn(args, 0, NULL, &up[nu]) == 0)
                    nu++;
            print_costs("start-up only (`scadprofile --version`)", up, nu);
        }
    }

    if (g_nnotes) {
        printf("\nNotes:\n");
        for (size_t i = 0; i < g_nnotes && i < MAX_NOTES; i++)
            printf("- %s\n", g_notes[i]);
        if (g_nnotes > MAX_NOTES)
            printf("- ... and %zu more\n", g_nnotes - MAX_NOTES);
    }
    for (size_t i = 0; i < ng; i++)
        ts_outline_free(&gl[i].mm);
    if (keep)
        printf("\nfiles kept in %s\n", g_dir);
    else
        remove_dir(g_dir);
    return 0;
}
