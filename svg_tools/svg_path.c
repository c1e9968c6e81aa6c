/* SPDX-License-Identifier: MIT */
/* SVG 2 path data and `points` lists: grammar, absolute segments, arcs in
 * centre parametrisation, and the compact writer.
 *
 * Grammar: SVG 2, section 9.3.9 ("The grammar for path data"), with the
 * error handling of section 9.5.4 (keep everything up to the last complete
 * segment). Numbers go through conica__parse_double (libcore, locale free),
 * whose grammar is exactly SVG's `number`. */
#include "svg_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "numparse.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double conica_svg__now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ------------------------------------------------------------ buffers */

static int buf_reserve(conica_svg__buf *b, size_t extra)
{
    size_t need, cap;
    char *s;
    if (b->oom)
        return 0;
    need = b->n + extra + 1;
    if (need <= b->cap)
        return 1;
    cap = b->cap ? b->cap : 256;
    while (cap < need)
        cap *= 2;
    s = realloc(b->s, cap);
    if (!s) {
        b->oom = 1;
        return 0;
    }
    b->s = s;
    b->cap = cap;
    return 1;
}

void conica_svg__buf_put(conica_svg__buf *b, const char *s, size_t n)
{
    if (!buf_reserve(b, n))
        return;
    memcpy(b->s + b->n, s, n);
    b->n += n;
    b->s[b->n] = '\0';
}

void conica_svg__buf_putc(conica_svg__buf *b, char c)
{
    conica_svg__buf_put(b, &c, 1);
}

/* ------------------------------------------------------------ numbers out */

static const double pow10_tab[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* "00" .. "99": the digits of m two at a time. */
static const char digit_pairs[201] = "00010203040506070809101112131415161718192021222324"
                                     "25262728293031323334353637383940414243444546474849"
                                     "50515253545556575859606162636465666768697071727374"
                                     "75767778798081828384858687888990919293949596979899";

/* The digits of |v| for the fast path: dg[0..nd) without trailing zeros,
 * the first of them at 10^e. dg has room for a 16-byte block copy from
 * any digit (fast_layout). */
typedef struct fast_num {
    char dg[32];
    size_t nd;
    int e;
} fast_num;

/* The `n` digits of m (m < 10^n, n <= 15) at d[0..n), leading zeros
 * included; two at a time, in 32-bit arithmetic while m fits. */
static CONICA__HOT_INLINE void put_digits(char *d, unsigned long long m, size_t n)
{
    while (n >= 2 && m > 0xffffffffu) {
        unsigned r = (unsigned)(m % 100);
        m /= 100;
        n -= 2;
        memcpy(d + n, digit_pairs + 2 * r, 2);
    }
    {
        uint32_t m32 = (uint32_t)m;
        while (n >= 2) {
            unsigned r = m32 % 100;
            m32 /= 100;
            n -= 2;
            memcpy(d + n, digit_pairs + 2 * r, 2);
        }
        if (n)
            d[0] = (char)('0' + (int)m32);
    }
}

/* The fast path of conica_svg__format_number for precision <= 15: scale by
 * an exact power of ten (one rounding), round to an integer of `precision`
 * digits. The result is within half a unit in the last written digit of a
 * up to one rounding of the scaling; only values within about 1e-16
 * (relative) of a rounding tie may differ from printf in the last digit.
 * Returns 0 when it does not apply (printf then does it). */
static CONICA__HOT_INLINE int fast_digits(double a, int precision, fast_num *f)
{
    double r = 0.0;
    uint64_t bits;
    size_t nd;
    int e, k, tries;

    if (precision < 1 || precision > 15 || !(a >= 1e-280 && a <= 1e280))
        return 0;
    /* decimal exponent from the binary one (frexp's, read from the bits
     * of a normal a; log10(2) = 0.30103); the loop below corrects an
     * estimate that is one off */
    memcpy(&bits, &a, sizeof bits);
    e = (int)((bits >> 52) & 0x7ff) - 1022;
    e = (int)floor((double)(e - 1) * 0.30102999566398120);
    for (tries = 0; tries < 3; tries++) {
        k = precision - 1 - e;
        if (k > 22 || k < -22)
            return 0;
        r = nearbyint(k >= 0 ? a * pow10_tab[k] : a / pow10_tab[-k]);
        if (r >= pow10_tab[precision])
            e++;
        else if (r < pow10_tab[precision - 1])
            e--;
        else
            break;
    }
    if (tries == 3)
        return 0;
    memset(f->dg, '0', sizeof f->dg);
    put_digits(f->dg, (unsigned long long)r, (size_t)precision);
    nd = (size_t)precision;
    while (nd > 1 && f->dg[nd - 1] == '0')
        nd--;
    f->nd = nd;
    f->e = e;
    return 1;
}

/* Is the number written in scientific form (as %g: below 1e-4 or at
 * 10^precision and above)? */
static int fast_sci(const fast_num *f, int precision)
{
    return f->e < -4 || f->e >= precision;
}

/* Lay the digits out as %g would, without "0" before "." or "+" and
 * leading zeros in the exponent; returns the bytes written (no NUL). The
 * fixed forms copy digits in 16-byte blocks: out must have room for 40
 * bytes, of which those past the returned count are scratch. */
static CONICA__HOT_INLINE size_t fast_layout(const fast_num *f, int neg, int precision,
                                             char *out)
{
    size_t n = 0, i, nd = f->nd;
    int e = f->e;
    if (neg)
        out[n++] = '-';
    if (fast_sci(f, precision)) {
        unsigned ue = (unsigned)(e < 0 ? -e : e);
        char eb[8];
        size_t ne = 0;
        out[n++] = f->dg[0];
        if (nd > 1) {
            out[n++] = '.';
            for (i = 1; i < nd; i++)
                out[n++] = f->dg[i];
        }
        out[n++] = 'e';
        if (e < 0)
            out[n++] = '-';
        do {
            eb[ne++] = (char)('0' + (int)(ue % 10));
            ue /= 10;
        } while (ue);
        while (ne)
            out[n++] = eb[--ne];
    } else if (e >= 0) {
        /* whole digits before the point (dg is '0'-padded past nd, so an
         * integer's trailing zeros come with the block) */
        size_t whole = (size_t)e + 1;
        memcpy(out + n, f->dg, 16);
        if (nd <= whole) {
            n += whole;
        } else {
            out[n + whole] = '.';
            memcpy(out + n + whole + 1, f->dg + whole, 16);
            n += nd + 1;
        }
    } else {
        /* '.', then -e - 1 zeros (at most 3: e >= -4), then the digits */
        size_t z = (size_t)(-e - 1);
        memcpy(out + n, ".000", 4);
        memcpy(out + n + 1 + z, f->dg, 16);
        n += 1 + z + nd;
    }
    return n;
}

static size_t format_fast(double v, int precision, char out[48])
{
    fast_num f;
    size_t n;
    if (!fast_digits(fabs(v), precision, &f))
        return 0;
    n = fast_layout(&f, v < 0, precision, out);
    out[n] = '\0';
    return n;
}

size_t conica_svg__format_number(double v, int precision, char out[48])
{
    char tmp[64];
    size_t i, n = 0, k;
    char *e;

    if (precision < 1)
        precision = 1;
    if (precision > 17)
        precision = 17;
    if (v == 0.0 || !isfinite(v)) { /* -0 prints as 0; non-finite never reaches here */
        out[0] = '0';
        out[1] = '\0';
        return 1;
    }
    if ((n = format_fast(v, precision, out)) != 0)
        return n;
    snprintf(tmp, sizeof tmp, "%.*g", precision, v);
    /* The locale may print another decimal separator: anything that is not
     * part of the number's own alphabet is the separator. */
    for (i = 0; tmp[i]; i++) {
        char c = tmp[i];
        if (!((c >= '0' && c <= '9') || c == 'e' || c == '-' || c == '+'))
            tmp[i] = '.';
    }
    /* %g already strips trailing zeros of the fraction. Now drop "0" before
     * ".", "+" and leading zeros in the exponent. */
    i = 0;
    if (tmp[i] == '-')
        out[n++] = tmp[i++];
    if (tmp[i] == '0' && tmp[i + 1] == '.')
        i++;
    e = strchr(tmp + i, 'e');
    k = e ? (size_t)(e - tmp) : strlen(tmp);
    for (; i < k; i++)
        out[n++] = tmp[i];
    if (e) {
        i = k + 1;
        out[n++] = 'e';
        if (tmp[i] == '-')
            out[n++] = '-';
        if (tmp[i] == '-' || tmp[i] == '+')
            i++;
        while (tmp[i] == '0' && tmp[i + 1])
            i++;
        for (; tmp[i]; i++)
            out[n++] = tmp[i];
    }
    out[n] = '\0';
    return n;
}

/* The kind of a written number for the separator rule: 1 has '.', 2 an
 * integer, 3 has an exponent. */
static int number_kind(const char *s, size_t n)
{
    int has_dot = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        if (s[i] == 'e')
            return 3;
        has_dot |= s[i] == '.';
    }
    return has_dot ? 1 : 2;
}

/* Write v at dst with the separator the grammar needs before it (none
 * after a letter, none before '-', none before '.' after a number that
 * already has its '.'); returns the bytes written (at most 49; dst needs
 * room for 50, the bytes past those written being scratch). The fast
 * path writes in place: its first character and kind follow from the
 * digits' exponent. */
static CONICA__HOT_INLINE size_t write_number(char *dst, double v, int precision,
                                              int *prev_kind)
{
    char s[48];
    size_t n, k = 0;
    fast_num f;
    if (v != 0.0 && fast_digits(fabs(v), precision, &f)) {
        int sci = fast_sci(&f, precision);
        char first = v < 0 ? '-' : !sci && f.e < 0 ? '.' : '0';
        if (*prev_kind != 0 && !(first == '-' || (first == '.' && *prev_kind == 1)))
            dst[k++] = ' ';
        *prev_kind = sci ? 3 : f.e < 0 || f.nd > (size_t)f.e + 1 ? 1 : 2;
        return k + fast_layout(&f, v < 0, precision, dst + k);
    }
    n = conica_svg__format_number(v, precision, s);
    if (*prev_kind != 0 && !(s[0] == '-' || (s[0] == '.' && *prev_kind == 1)))
        dst[k++] = ' ';
    memcpy(dst + k, s, n);
    *prev_kind = number_kind(s, n);
    return k + n;
}

/* prev_kind: 0 nothing or a letter before, 1 a number with '.' or 'e',
 * 2 an integer. A '-' always separates; a leading '.' separates after a
 * number that already has its '.' (and no exponent, to stay readable). */
void conica_svg__put_number(conica_svg__buf *b, double v, int precision, int *prev_kind)
{
    if (!buf_reserve(b, 50))
        return;
    b->n += write_number(b->s + b->n, v, precision, prev_kind);
    b->s[b->n] = '\0';
}

/* Bytes one number can take with its separator: sign, `precision` digits,
 * '.', "e-308" and a space (or ".0000" of %g's fixed form below 1e-4...
 * within the same count), plus slack. */
#define SVG_NUMBER_MAX_BYTES(precision) ((size_t)(precision) + 12)

int conica_svg__format_path_into(conica_svg__buf *b, const conica_svg_subpath *sp, size_t nsp,
                                 int precision)
{
    size_t i, j, need = 1;
    char *w;
    if (precision < 1)
        precision = 1;
    if (precision > 17)
        precision = 17;
    /* Count, then make room once and write without further checks (STYLE.md
     * item 7). Pages reserved but not written are never touched. */
    for (i = 0; i < nsp; i++) {
        size_t per = 2 * SVG_NUMBER_MAX_BYTES(precision);
        if (sp[i].n > ((size_t)-1 / 4 - need) / per)
            return 0;
        need += sp[i].n * per + 3; /* M, L, Z */
    }
    /* and write_number's scratch past the last number */
    if (!buf_reserve(b, need + 40))
        return 0;
    w = b->s + b->n;
    for (i = 0; i < nsp; i++) {
        int kind = 0;
        const double *xy = sp[i].xy;
        if (sp[i].n == 0)
            continue;
        *w++ = 'M';
        for (j = 0; j < sp[i].n; j++) {
            if (j == 1) {
                *w++ = 'L';
                kind = 0;
            }
            w += write_number(w, xy[2 * j], precision, &kind);
            w += write_number(w, xy[2 * j + 1], precision, &kind);
        }
        if (sp[i].closed)
            *w++ = 'Z';
    }
    *w = '\0';
    b->n = (size_t)(w - b->s);
    return 1;
}

conica_code conica_svg_format_path(const conica_svg_subpath *sp, size_t nsp, int precision,
                                   char **buf, size_t *len, conica_status *st)
{
    conica_svg__buf b = {NULL, 0, 0, 0};
    if ((!sp && nsp) || !buf || !len)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_format_path: NULL argument");
    if (!conica_svg__format_path_into(&b, sp, nsp, precision)) {
        free(b.s);
        return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory writing path data");
    }
    {
        /* give back what the worst case reserved (in place for large blocks) */
        char *t = realloc(b.s, b.n + 1);
        if (t)
            b.s = t;
    }
    *buf = b.s;
    *len = b.n;
    return CONICA_OK;
}

/* ------------------------------------------------------------ arcs */

/* Angle from u to v, signed (SVG 2, F.6.5.4). */
static double vec_angle(double ux, double uy, double vx, double vy)
{
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

int conica_svg__arc_to_centre(conica_svg_seg *seg, double rx, double ry, double phi_deg)
{
    double x1 = seg->x0, y1 = seg->y0, x2 = seg->x1, y2 = seg->y1;
    double phi, cphi, sphi, dx2, dy2, xp, yp, lambda, num, den, coef, cxp, cyp, ux, uy, vx, vy;
    double dtheta;

    if (x1 == x2 && y1 == y2)
        return 0; /* F.6.2: coincident end points, the arc is omitted */
    rx = fabs(rx);
    ry = fabs(ry);
    if (rx == 0.0 || ry == 0.0) {
        seg->type = CONICA_SVG_SEG_LINE; /* F.6.2: zero radius, a straight line */
        return 1;
    }
    phi = fmod(phi_deg, 360.0) * (M_PI / 180.0);
    cphi = cos(phi);
    sphi = sin(phi);
    /* F.6.5 step 1, in coordinates relative to the chord midpoint so the
     * result does not depend on where the arc sits. */
    dx2 = 0.5 * (x1 - x2);
    dy2 = 0.5 * (y1 - y2);
    xp = cphi * dx2 + sphi * dy2;
    yp = -sphi * dx2 + cphi * dy2;
    /* F.6.6: scale radii up when no ellipse reaches both end points. */
    lambda = (xp * xp) / (rx * rx) + (yp * yp) / (ry * ry);
    if (lambda > 1.0) {
        double s = sqrt(lambda);
        rx *= s;
        ry *= s;
    }
    /* F.6.5 step 2 (radicand clamped at 0: after scaling it is 0 up to rounding). */
    num = rx * rx * ry * ry - rx * rx * yp * yp - ry * ry * xp * xp;
    den = rx * rx * yp * yp + ry * ry * xp * xp;
    coef = (num > 0.0 && den > 0.0) ? sqrt(num / den) : 0.0;
    if (seg->large_arc == seg->sweep)
        coef = -coef;
    cxp = coef * rx * yp / ry;
    cyp = -coef * ry * xp / rx;
    /* step 3 */
    seg->cx = cphi * cxp - sphi * cyp + 0.5 * (x1 + x2);
    seg->cy = sphi * cxp + cphi * cyp + 0.5 * (y1 + y2);
    /* step 4 */
    ux = (xp - cxp) / rx;
    uy = (yp - cyp) / ry;
    vx = (-xp - cxp) / rx;
    vy = (-yp - cyp) / ry;
    seg->theta1 = vec_angle(1.0, 0.0, ux, uy);
    dtheta = vec_angle(ux, uy, vx, vy);
    if (!seg->sweep && dtheta > 0.0)
        dtheta -= 2.0 * M_PI;
    else if (seg->sweep && dtheta < 0.0)
        dtheta += 2.0 * M_PI;
    if (!isfinite(seg->cx) || !isfinite(seg->cy) || !isfinite(rx) || !isfinite(ry) ||
        !isfinite(seg->theta1) || !isfinite(dtheta)) {
        /* Overflow near DBL_MAX: no usable centre; draw the chord. */
        seg->type = CONICA_SVG_SEG_LINE;
        return 1;
    }
    seg->dtheta = dtheta;
    seg->rx = rx;
    seg->ry = ry;
    seg->phi = phi;
    seg->type = CONICA_SVG_SEG_ARC;
    return 1;
}

/* ------------------------------------------------------------ path parser */

typedef struct scanner {
    const char *s;
    size_t len, pos;
    const char *err; /* first error message, NULL while fine */
    size_t err_pos;
} scanner;

static int is_wsp(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f';
}

static void skip_wsp(scanner *sc)
{
    while (sc->pos < sc->len && is_wsp(sc->s[sc->pos]))
        sc->pos++;
}

/* comma-wsp between numbers: wsp* (',' wsp*)? */
static void skip_comma_wsp(scanner *sc)
{
    skip_wsp(sc);
    if (sc->pos < sc->len && sc->s[sc->pos] == ',') {
        sc->pos++;
        skip_wsp(sc);
    }
}

static int set_err(scanner *sc, size_t pos, const char *msg)
{
    if (!sc->err) {
        sc->err = msg;
        sc->err_pos = pos;
    }
    return 0;
}

static int read_number(scanner *sc, double *v)
{
    size_t used = 0;
    int r;
    if (sc->pos >= sc->len)
        return set_err(sc, sc->pos, "expected a number, found the end of the data");
    r = conica__parse_double(sc->s + sc->pos, sc->len - sc->pos, v, &used);
    if (r == CONICA__NUM_NONFINITE)
        return set_err(sc, sc->pos, "number is not finite");
    if (r != CONICA__NUM_OK)
        return set_err(sc, sc->pos, "expected a number");
    sc->pos += used;
    return 1;
}

static int read_flag(scanner *sc, int *f)
{
    char c;
    if (sc->pos >= sc->len)
        return set_err(sc, sc->pos, "expected an arc flag (0 or 1), found the end of the data");
    c = sc->s[sc->pos];
    if (c != '0' && c != '1')
        return set_err(sc, sc->pos, "expected an arc flag (0 or 1)");
    *f = c == '1';
    sc->pos++;
    return 1;
}

/* Could a number start here? (the test for an implicit repeated command) */
static int number_starts(const scanner *sc)
{
    char c;
    if (sc->pos >= sc->len)
        return 0;
    c = sc->s[sc->pos];
    return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+';
}

static int nparams(char up)
{
    switch (up) {
    case 'M': case 'L': case 'T': return 2;
    case 'H': case 'V': return 1;
    case 'S': case 'Q': return 4;
    case 'C': return 6;
    case 'A': return 7;
    default: return 0;
    }
}

static int push(conica_svg_path *p, const conica_svg_seg *g, size_t max_segments, int *limit)
{
    if (max_segments && p->n >= max_segments) {
        *limit = 1;
        return 0;
    }
    return conica_svg__path_push(p, g);
}

int conica_svg__path_push(conica_svg_path *p, const conica_svg_seg *g)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 16;
        conica_svg_seg *s = realloc(p->seg, cap * sizeof *s);
        if (!s)
            return 0;
        p->seg = s;
        p->cap = cap;
    }
    p->seg[p->n++] = *g;
    return 1;
}

void conica_svg_path_init(conica_svg_path *p)
{
    if (p)
        memset(p, 0, sizeof *p);
}

void conica_svg_path_free(conica_svg_path *p)
{
    if (!p)
        return;
    free(p->seg);
    memset(p, 0, sizeof *p);
}

conica_code conica_svg_path_parse(const char *d, size_t len, size_t max_segments,
                                  conica_svg_path *out, conica_status *st)
{
    conica_svg_path p;
    conica_code rc;
    if ((!d && len) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_path_parse: NULL argument");
    conica_svg_path_init(&p);
    rc = conica_svg__path_parse_into(d, len, max_segments, &p, st);
    if (rc != CONICA_OK) {
        conica_svg_path_free(&p);
        return rc;
    }
    conica_svg_path_free(out);
    *out = p;
    return CONICA_OK;
}

conica_code conica_svg__path_parse_into(const char *d, size_t len, size_t max_segments,
                                        conica_svg_path *out, conica_status *st)
{
    conica_svg_path p;
    scanner sc;
    double cx = 0, cy = 0;    /* current point */
    double sx = 0, sy = 0;    /* start of the current subpath */
    double rcx = 0, rcy = 0;  /* last control point, for S/T reflection */
    char prev = 0;            /* previous command (upper case) */
    int limit = 0, oom = 0;

    if ((!d && len) || !out)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_path_parse: NULL argument");
    /* the caller's array, emptied: parsing many attributes allocates once */
    p = *out;
    p.n = 0;
    p.has_error = 0;
    p.error_offset = 0;
    p.error[0] = '\0';
    sc.s = d;
    sc.len = len;
    sc.pos = 0;
    sc.err = NULL;
    sc.err_pos = 0;

    skip_wsp(&sc);
    while (sc.pos < sc.len && !sc.err && !oom && !limit) {
        char cmd = sc.s[sc.pos], up = (char)(cmd & ~0x20);
        int rel = cmd >= 'a', first = 1, np;
        size_t cmd_pos = sc.pos;

        if (!strchr("MLHVCSQTAZ", up) || !((cmd >= 'A' && cmd <= 'Z') || (cmd >= 'a' && cmd <= 'z'))) {
            set_err(&sc, sc.pos, "expected a path command letter");
            break;
        }
        if (p.n == 0 && up != 'M') {
            set_err(&sc, sc.pos, "path data must begin with a moveto (M or m)");
            break;
        }
        sc.pos++;
        if (up == 'Z') {
            conica_svg_seg g;
            memset(&g, 0, sizeof g);
            g.type = CONICA_SVG_SEG_CLOSE;
            g.cmd = cmd;
            g.offset = cmd_pos;
            g.x0 = cx;
            g.y0 = cy;
            g.x1 = sx;
            g.y1 = sy;
            if (!push(&p, &g, max_segments, &limit)) {
                oom = !limit;
                break;
            }
            cx = sx;
            cy = sy;
            prev = 'Z';
            skip_wsp(&sc);
            continue;
        }
        np = nparams(up);
        skip_wsp(&sc);
        /* One argument set per iteration; further sets are implicit repeats
         * (after a moveto they are linetos, SVG 2 9.3.3). */
        for (;;) {
            double a[7];
            int flags[2] = {0, 0};
            int i, ok = 1;
            size_t set_pos = sc.pos;
            conica_svg_seg g;
            char eff = up;

            if (!first) {
                size_t before = sc.pos;
                int comma;
                skip_wsp(&sc);
                comma = sc.pos < sc.len && sc.s[sc.pos] == ',';
                skip_comma_wsp(&sc);
                if (!number_starts(&sc)) {
                    if (comma)
                        set_err(&sc, sc.pos, "a comma must be followed by another argument set");
                    else
                        sc.pos = before;
                    break;
                }
                set_pos = sc.pos;
                if (up == 'M')
                    eff = 'L';
            }
            for (i = 0; i < np && ok; i++) {
                if (i > 0)
                    skip_comma_wsp(&sc);
                if (up == 'A' && (i == 3 || i == 4))
                    ok = read_flag(&sc, &flags[i - 3]);
                else
                    ok = read_number(&sc, &a[i]);
            }
            if (!ok)
                break;
            memset(&g, 0, sizeof g);
            g.cmd = first ? cmd : (up == 'M' ? (rel ? 'l' : 'L') : cmd);
            g.offset = first ? cmd_pos : set_pos;
            g.x0 = cx;
            g.y0 = cy;
            switch (eff) {
            case 'M':
                g.type = CONICA_SVG_SEG_MOVE;
                g.x1 = rel ? cx + a[0] : a[0];
                g.y1 = rel ? cy + a[1] : a[1];
                sx = g.x1;
                sy = g.y1;
                break;
            case 'L':
                g.type = CONICA_SVG_SEG_LINE;
                g.x1 = rel ? cx + a[0] : a[0];
                g.y1 = rel ? cy + a[1] : a[1];
                break;
            case 'H':
                g.type = CONICA_SVG_SEG_LINE;
                g.x1 = rel ? cx + a[0] : a[0];
                g.y1 = cy;
                break;
            case 'V':
                g.type = CONICA_SVG_SEG_LINE;
                g.x1 = cx;
                g.y1 = rel ? cy + a[0] : a[0];
                break;
            case 'C':
                g.type = CONICA_SVG_SEG_CUBIC;
                for (i = 0; i < 4; i += 2) {
                    g.c[i] = rel ? cx + a[i] : a[i];
                    g.c[i + 1] = rel ? cy + a[i + 1] : a[i + 1];
                }
                g.x1 = rel ? cx + a[4] : a[4];
                g.y1 = rel ? cy + a[5] : a[5];
                break;
            case 'S':
                g.type = CONICA_SVG_SEG_CUBIC;
                /* first control: reflection of the previous cubic's second
                 * control, else the current point (SVG 2, 9.3.6) */
                g.c[0] = (prev == 'C' || prev == 'S') ? 2.0 * cx - rcx : cx;
                g.c[1] = (prev == 'C' || prev == 'S') ? 2.0 * cy - rcy : cy;
                g.c[2] = rel ? cx + a[0] : a[0];
                g.c[3] = rel ? cy + a[1] : a[1];
                g.x1 = rel ? cx + a[2] : a[2];
                g.y1 = rel ? cy + a[3] : a[3];
                break;
            case 'Q':
                g.type = CONICA_SVG_SEG_QUAD;
                g.c[0] = rel ? cx + a[0] : a[0];
                g.c[1] = rel ? cy + a[1] : a[1];
                g.x1 = rel ? cx + a[2] : a[2];
                g.y1 = rel ? cy + a[3] : a[3];
                break;
            case 'T':
                g.type = CONICA_SVG_SEG_QUAD;
                g.c[0] = (prev == 'Q' || prev == 'T') ? 2.0 * cx - rcx : cx;
                g.c[1] = (prev == 'Q' || prev == 'T') ? 2.0 * cy - rcy : cy;
                g.x1 = rel ? cx + a[0] : a[0];
                g.y1 = rel ? cy + a[1] : a[1];
                break;
            case 'A':
                g.x1 = rel ? cx + a[5] : a[5];
                g.y1 = rel ? cy + a[6] : a[6];
                g.large_arc = flags[0];
                g.sweep = flags[1];
                break;
            default:
                break;
            }
            if (!isfinite(g.x1) || !isfinite(g.y1) || !isfinite(g.c[0]) || !isfinite(g.c[1]) ||
                !isfinite(g.c[2]) || !isfinite(g.c[3])) {
                set_err(&sc, set_pos, "coordinate overflows a double");
                break;
            }
            if (eff == 'A') {
                int keep = conica_svg__arc_to_centre(&g, a[0], a[1], a[2]);
                if (keep && !push(&p, &g, max_segments, &limit)) {
                    oom = !limit;
                    break;
                }
            } else if (!push(&p, &g, max_segments, &limit)) {
                oom = !limit;
                break;
            }
            if (g.type == CONICA_SVG_SEG_CUBIC) {
                rcx = g.c[2];
                rcy = g.c[3];
            } else if (g.type == CONICA_SVG_SEG_QUAD) {
                rcx = g.c[0];
                rcy = g.c[1];
            }
            cx = g.x1;
            cy = g.y1;
            prev = eff;
            first = 0;
        }
        skip_wsp(&sc);
    }
    if (oom || limit) {
        p.n = 0;
        *out = p;
        if (oom)
            return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory parsing path data");
        return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                "path data has more than %zu segments", max_segments);
    }
    if (sc.err) {
        p.has_error = 1;
        p.error_offset = sc.err_pos;
        snprintf(p.error, sizeof p.error, "%s", sc.err);
    }
    *out = p;
    return CONICA_OK;
}

conica_code conica_svg_points_parse(const char *s, size_t len, size_t max_points, double **xy,
                                    size_t *n, size_t *error_offset, conica_status *st)
{
    scanner sc;
    double *v = NULL;
    size_t cnt = 0, cap = 0;
    if ((!s && len) || !xy || !n || !error_offset)
        return conica__fail(st, CONICA_ERR_ARG, 0, 0, "conica_svg_points_parse: NULL argument");
    sc.s = s;
    sc.len = len;
    sc.pos = 0;
    sc.err = NULL;
    sc.err_pos = 0;
    skip_wsp(&sc);
    while (sc.pos < sc.len) {
        double a, b;
        if (cnt > 0) {
            skip_comma_wsp(&sc);
            if (sc.pos >= sc.len)
                break;
        }
        if (!read_number(&sc, &a))
            break;
        skip_comma_wsp(&sc);
        if (!read_number(&sc, &b))
            break;
        if (max_points && cnt >= max_points) {
            free(v);
            return conica__fail(st, CONICA_ERR_LIMIT, 0, 0,
                                    "points list has more than %zu points", max_points);
        }
        if (cnt == cap) {
            size_t nc = cap ? 2 * cap : 16;
            double *t = realloc(v, 2 * nc * sizeof *t);
            if (!t) {
                free(v);
                return conica__fail(st, CONICA_ERR_NOMEM, 0, 0, "out of memory");
            }
            v = t;
            cap = nc;
        }
        v[2 * cnt] = a;
        v[2 * cnt + 1] = b;
        cnt++;
        skip_wsp(&sc);
    }
    if (cnt == 0) {
        free(v);
        v = NULL;
    }
    *xy = v;
    *n = cnt;
    *error_offset = sc.err ? sc.err_pos : (size_t)-1;
    return CONICA_OK;
}
