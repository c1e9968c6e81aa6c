/* SPDX-License-Identifier: MIT */
/*
 * conica_test.c - the Catch2-compatible runner behind conica_test.h.
 *
 * Behaviour follows Catch2 3.7.1 (src/catch2/catch_session.cpp,
 * internal/catch_test_spec_parser.cpp, catch_test_spec.cpp,
 * reporters/catch_reporter_helpers.cpp, internal/catch_test_case_tracker.cpp):
 * the test-spec grammar, hidden tests, section discovery, the console
 * summary rows and the exit codes. Unlike the library, the runner keeps its
 * state in one static struct: a test binary is one process running one
 * session, and TEST_CASE registration by constructor needs somewhere to go.
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* sigaltstack */
#endif
#include "conica_test.h"

#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Catch2's exit codes (catch_session.cpp). */
enum {
    EXIT_OK = 0,
    EXIT_ERROR = 1,
    EXIT_NO_TESTS = 2,
    EXIT_UNMATCHED = 3,
    EXIT_ALL_SKIPPED = 4,
    EXIT_INVALID_SPEC = 5,
    EXIT_FAILED = 42
};

#define CONSOLE_WIDTH 80 /* CATCH_CONFIG_CONSOLE_WIDTH */
/* Events kept per run for the junit/xml reporters; more are counted only. */
#define MAX_STORED_EVENTS 1000
/* A case whose section tree never completes is a runner bug, not a test. */
#define MAX_RUNS_PER_CASE 1000000L

/* ================================================================ utils */

static void *xmalloc(size_t n) {
    void *p = malloc(n ? n : 1);
    if (!p) {
        fputs("conica_test: out of memory\n", stderr);
        exit(EXIT_ERROR);
    }
    return p;
}

static void *xrealloc(void *p, size_t n) {
    void *q = realloc(p, n ? n : 1);
    if (!q) {
        fputs("conica_test: out of memory\n", stderr);
        exit(EXIT_ERROR);
    }
    return q;
}

static char *xstrndup(const char *s, size_t n) {
    char *p = (char *)xmalloc(n + 1);
    memcpy(p, s, n);
    p[n] = '\0';
    return p;
}

static char *xstrdup(const char *s) { return xstrndup(s, strlen(s)); }

/* Growable string. */
typedef struct sb {
    char *p;
    size_t n, cap;
} sb;

static void sb_putn(sb *b, const char *s, size_t n) {
    if (b->n + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 64;
        while (cap < b->n + n + 1) cap *= 2;
        b->p = (char *)xrealloc(b->p, cap);
        b->cap = cap;
    }
    memcpy(b->p + b->n, s, n);
    b->n += n;
    b->p[b->n] = '\0';
}

static void sb_puts(sb *b, const char *s) { sb_putn(b, s, strlen(s)); }
static void sb_putc(sb *b, char c) { sb_putn(b, &c, 1); }

static void sb_vprintf(sb *b, const char *fmt, va_list ap) {
    char small[256];
    va_list ap2;
    va_copy(ap2, ap);
    int n = vsnprintf(small, sizeof small, fmt, ap2);
    va_end(ap2);
    if (n < 0) return;
    if ((size_t)n < sizeof small) {
        sb_putn(b, small, (size_t)n);
        return;
    }
    char *big = (char *)xmalloc((size_t)n + 1);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    sb_putn(b, big, (size_t)n);
    free(big);
}

static void sb_printf(sb *b, const char *fmt, ...) CT_PRINTF(2, 3);
static void sb_printf(sb *b, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sb_vprintf(b, fmt, ap);
    va_end(ap);
}

/* Takes the string out of the builder (never NULL). */
static char *sb_take(sb *b) {
    char *p = b->p ? b->p : xstrdup("");
    b->p = NULL;
    b->n = b->cap = 0;
    return p;
}

static char *vformat(const char *fmt, va_list ap) {
    sb b = {0};
    sb_vprintf(&b, fmt, ap);
    return sb_take(&b);
}

static char lower(char c) { return (c >= 'A' && c <= 'Z') ? (char)(c - 'A' + 'a') : c; }

static int streq_nocase(const char *a, const char *b) {
    for (; *a && *b; a++, b++)
        if (lower(*a) != lower(*b)) return 0;
    return *a == *b;
}

/* Lower-cased copy without leading/trailing blanks (Catch2 normaliseString). */
static char *normalise(const char *s, size_t n) {
    while (n && (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')) s++, n--;
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\n' ||
                 s[n - 1] == '\r'))
        n--;
    char *p = xstrndup(s, n);
    for (size_t i = 0; i < n; i++) p[i] = lower(p[i]);
    return p;
}

/* Locale-free unsigned decimal; 1 on success. */
static int parse_uint(const char *s, unsigned long long max, unsigned long long *out) {
    unsigned long long v = 0;
    if (!*s) return 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9') return 0;
        unsigned d = (unsigned)(*s - '0');
        if (v > (max - d) / 10) return 0;
        v = v * 10 + d;
    }
    *out = v;
    return 1;
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* ================================================================ tags */

/* Tags of a test as lower-cased strings; "[.foo]" gives "." and "foo" and
 * "[!hide]" gives "." as in Catch2's TestCaseInfo. */
typedef struct taglist {
    char **v;
    size_t n;
} taglist;

static void taglist_add(taglist *t, const char *s, size_t n) {
    char *tag = normalise(s, n);
    for (size_t i = 0; i < t->n; i++)
        if (strcmp(t->v[i], tag) == 0) {
            free(tag);
            return;
        }
    t->v = (char **)xrealloc(t->v, (t->n + 1) * sizeof *t->v);
    t->v[t->n++] = tag;
}

static void taglist_parse(taglist *t, const char *tags) {
    t->v = NULL;
    t->n = 0;
    if (!tags) return;
    const char *p = tags;
    while ((p = strchr(p, '[')) != NULL) {
        const char *e = strchr(p + 1, ']');
        if (!e) break;
        const char *s = p + 1;
        size_t n = (size_t)(e - s);
        if (n > 0 && s[0] == '.') {
            taglist_add(t, ".", 1);
            if (n > 1) taglist_add(t, s + 1, n - 1);
        } else if (n == 5 && strncmp(s, "!hide", 5) == 0) {
            taglist_add(t, ".", 1);
            taglist_add(t, s, n);
        } else if (n > 0) {
            taglist_add(t, s, n);
        }
        p = e + 1;
    }
}

static void taglist_free(taglist *t) {
    for (size_t i = 0; i < t->n; i++) free(t->v[i]);
    free(t->v);
    t->v = NULL;
    t->n = 0;
}

static int taglist_has(const taglist *t, const char *tag) {
    for (size_t i = 0; i < t->n; i++)
        if (streq_nocase(t->v[i], tag)) return 1;
    return 0;
}

int ct_tags_hidden(const char *tags) {
    taglist t;
    taglist_parse(&t, tags);
    int h = taglist_has(&t, ".");
    taglist_free(&t);
    return h;
}

/* ================================================================ test spec */

typedef struct pattern {
    int is_tag;
    int exclude;
    char *text; /* normalised; for names without the '*' ends */
    int wild_start, wild_end;
    char *orig; /* as written, for "No test cases matched '...'" */
} pattern;

typedef struct filter {
    pattern *v;
    size_t n;
    size_t matched; /* test cases this filter selected */
} filter;

typedef struct spec {
    filter *v;
    size_t n;
    filter cur;
    int invalid;
    /* parser state, reset per argument like TestSpecParser::parse */
    int mode, exclusion;
    sb pat;  /* pattern characters */
    sb orig; /* characters as written */
} spec;

enum { M_NONE, M_NAME, M_QUOTED, M_TAG };

static void filter_add(filter *f, pattern p) {
    f->v = (pattern *)xrealloc(f->v, (f->n + 1) * sizeof *f->v);
    f->v[f->n++] = p;
}

static void spec_add_pattern(spec *s, int is_tag, const char *text, const char *orig,
                             int exclude) {
    pattern p;
    memset(&p, 0, sizeof p);
    p.is_tag = is_tag;
    p.exclude = exclude;
    p.text = normalise(text, strlen(text));
    p.orig = xstrdup(orig);
    if (!is_tag) {
        size_t n = strlen(p.text);
        if (n && p.text[0] == '*') {
            memmove(p.text, p.text + 1, n--);
            p.wild_start = 1;
        }
        if (n && p.text[n - 1] == '*') {
            p.text[--n] = '\0';
            p.wild_end = 1;
        }
    }
    filter_add(&s->cur, p);
}

/* TestSpecParser::endMode: turn the pending characters into a pattern. */
static void spec_end_mode(spec *s) {
    if (s->mode == M_NONE) return;
    const char *tok = s->pat.p ? s->pat.p : "";
    const char *orig = s->orig.p ? s->orig.p : "";
    int excl = s->exclusion;
    if (strncmp(tok, "exclude:", 8) == 0) {
        excl = 1;
        tok += 8;
    }
    if (*tok) {
        if (s->mode == M_TAG) {
            /* "[.foo]" is the hide-and-tag shorthand: also require ".". */
            if (tok[0] == '.' && tok[1]) {
                spec_add_pattern(s, 1, ".", orig, excl);
                tok++;
            }
            spec_add_pattern(s, 1, tok, orig, excl);
        } else {
            spec_add_pattern(s, 0, tok, orig, excl);
        }
    }
    s->pat.n = s->orig.n = 0;
    if (s->pat.p) s->pat.p[0] = '\0';
    if (s->orig.p) s->orig.p[0] = '\0';
    s->exclusion = 0;
    s->mode = M_NONE;
}

static void spec_add_filter(spec *s) {
    if (s->cur.n == 0) return;
    s->v = (filter *)xrealloc(s->v, (s->n + 1) * sizeof *s->v);
    s->v[s->n++] = s->cur;
    memset(&s->cur, 0, sizeof s->cur);
}

/* One command-line argument. Patterns continue the current filter (Catch2
 * ANDs arguments); ',' starts a new filter (OR). Returns 0 if invalid. */
static int spec_parse(spec *s, const char *arg) {
    s->mode = M_NONE;
    s->exclusion = 0;
    s->pat.n = s->orig.n = 0;
    if (s->pat.p) s->pat.p[0] = '\0';
    if (s->orig.p) s->orig.p[0] = '\0';
    int escaped = 0;
    for (const char *c = arg; *c; c++) {
        if (escaped) {
            if (s->mode == M_NONE) s->mode = M_NAME;
            sb_putc(&s->pat, *c);
            sb_putc(&s->orig, *c);
            escaped = 0;
            continue;
        }
        if (*c == '\\') {
            escaped = 1;
            sb_putc(&s->orig, *c);
            continue;
        }
        if (*c == ',') {
            if (s->mode == M_TAG || s->mode == M_QUOTED) {
                s->invalid = 1;
                s->mode = M_NONE;
                s->pat.n = s->orig.n = 0;
                if (s->pat.p) s->pat.p[0] = '\0';
                if (s->orig.p) s->orig.p[0] = '\0';
                return 0;
            }
            spec_end_mode(s);
            spec_add_filter(s);
            continue;
        }
        switch (s->mode) {
        case M_NONE:
            if (*c == ' ') continue;
            sb_putc(&s->orig, *c);
            if (*c == '~') {
                s->exclusion = 1;
            } else if (*c == '[') {
                s->mode = M_TAG;
            } else if (*c == '"') {
                s->mode = M_QUOTED;
            } else {
                s->mode = M_NAME;
                sb_putc(&s->pat, *c);
            }
            break;
        case M_NAME:
            if (*c == '[') {
                if (s->pat.p && strcmp(s->pat.p, "exclude:") == 0) {
                    s->pat.n = 0;
                    s->pat.p[0] = '\0';
                    s->exclusion = 1;
                } else {
                    spec_end_mode(s);
                }
                sb_putc(&s->orig, *c);
                s->mode = M_TAG;
            } else {
                sb_putc(&s->pat, *c);
                sb_putc(&s->orig, *c);
            }
            break;
        case M_QUOTED:
            sb_putc(&s->orig, *c);
            if (*c == '"')
                spec_end_mode(s);
            else
                sb_putc(&s->pat, *c);
            break;
        case M_TAG:
            sb_putc(&s->orig, *c);
            if (*c == ']' || *c == '[')
                spec_end_mode(s);
            else
                sb_putc(&s->pat, *c);
            break;
        default:
            break;
        }
    }
    spec_end_mode(s);
    return 1;
}

/* After the last argument. */
static void spec_finish(spec *s) { spec_add_filter(s); }

static void spec_free(spec *s) {
    for (size_t i = 0; i <= s->n; i++) {
        filter *f = i < s->n ? &s->v[i] : &s->cur;
        for (size_t j = 0; j < f->n; j++) {
            free(f->v[j].text);
            free(f->v[j].orig);
        }
        free(f->v);
    }
    free(s->v);
    free(s->pat.p);
    free(s->orig.p);
    memset(s, 0, sizeof *s);
}

static int name_matches(const pattern *p, const char *name) {
    char *n = normalise(name, strlen(name));
    size_t ln = strlen(n), lp = strlen(p->text);
    int m;
    if (p->wild_start && p->wild_end)
        m = strstr(n, p->text) != NULL;
    else if (p->wild_start)
        m = ln >= lp && strcmp(n + ln - lp, p->text) == 0;
    else if (p->wild_end)
        m = strncmp(n, p->text, lp) == 0;
    else
        m = strcmp(n, p->text) == 0;
    free(n);
    return m;
}

static int pattern_matches(const pattern *p, const char *name, const taglist *tags) {
    return p->is_tag ? taglist_has(tags, p->text) : name_matches(p, name);
}

/* TestSpec::Filter::matches. */
static int filter_matches(const filter *f, const char *name, const taglist *tags) {
    int use = !taglist_has(tags, ".");
    for (size_t i = 0; i < f->n; i++) {
        if (f->v[i].exclude) continue;
        use = 1;
        if (!pattern_matches(&f->v[i], name, tags)) return 0;
    }
    for (size_t i = 0; i < f->n; i++)
        if (f->v[i].exclude && pattern_matches(&f->v[i], name, tags)) return 0;
    return use;
}

static int spec_matches(const spec *s, const char *name, const char *tags) {
    taglist t;
    taglist_parse(&t, tags);
    int m = 0;
    if (s->n == 0) {
        m = !taglist_has(&t, ".");
    } else {
        for (size_t i = 0; i < s->n && !m; i++) m = filter_matches(&s->v[i], name, &t);
    }
    taglist_free(&t);
    return m;
}

int ct_spec_matches_argv(int argc, const char *const *argv, const char *name,
                         const char *tags) {
    spec s;
    memset(&s, 0, sizeof s);
    int ok = 1;
    for (int i = 0; i < argc && ok; i++) ok = spec_parse(&s, argv[i]);
    spec_finish(&s);
    int r = ok ? spec_matches(&s, name, tags) : -1;
    spec_free(&s);
    return r;
}

int ct_spec_matches(const char *spec_text, const char *name, const char *tags) {
    return ct_spec_matches_argv(1, &spec_text, name, tags);
}

static char *filter_describe(const filter *f) {
    sb b = {0};
    for (size_t i = 0; i < f->n; i++) {
        /* "[.foo]" made two patterns with the same text: name it once. */
        if (i && strcmp(f->v[i].orig, f->v[i - 1].orig) == 0) continue;
        if (b.n) sb_putc(&b, ' ');
        if (f->v[i].is_tag || f->v[i].orig[0] == '"')
            sb_puts(&b, f->v[i].orig);
        else
            sb_printf(&b, "\"%s\"", f->v[i].orig);
    }
    return sb_take(&b);
}

/* ================================================================ sections */

/* TrackerBase run states (catch_test_case_tracker.cpp). */
enum { T_NOT_STARTED, T_EXECUTING, T_EXEC_CHILDREN, T_NEEDS_RUN, T_DONE, T_FAILED };

typedef struct node {
    char *name;
    const char *file;
    int line;
    int state;
    int depth;
    struct node *parent, *child, *last_child, *sibling;
} node;

struct ct_tracker {
    node root;
    node *cur;
    int cycle_done; /* a section closed in this run: enter no more */
    char **filters;
    size_t nfilters;
};

static int node_complete(const node *n) { return n->state == T_DONE || n->state == T_FAILED; }

static void node_free_children(node *n) {
    node *c = n->child;
    while (c) {
        node *next = c->sibling;
        node_free_children(c);
        free(c->name);
        free(c);
        c = next;
    }
    n->child = n->last_child = NULL;
}

ct_tracker *ct_tracker_new(void) {
    ct_tracker *t = (ct_tracker *)xmalloc(sizeof *t);
    memset(t, 0, sizeof *t);
    t->cur = &t->root;
    return t;
}

void ct_tracker_free(ct_tracker *t) {
    if (!t) return;
    node_free_children(&t->root);
    for (size_t i = 0; i < t->nfilters; i++) free(t->filters[i]);
    free(t->filters);
    free(t);
}

int ct_tracker_add_filter(ct_tracker *t, const char *name) {
    t->filters = (char **)xrealloc(t->filters, (t->nfilters + 1) * sizeof *t->filters);
    t->filters[t->nfilters++] = normalise(name, strlen(name));
    return 1;
}

void ct_tracker_start_run(ct_tracker *t) {
    t->cur = &t->root;
    t->cycle_done = 0;
    t->root.state = T_EXECUTING;
}

static void node_open(node *n) {
    n->state = T_EXECUTING;
    for (node *p = n->parent; p && p->state != T_EXEC_CHILDREN; p = p->parent)
        p->state = T_EXEC_CHILDREN;
}

/* TrackerBase::close for the current node, then move to its parent. */
static void tracker_close_current(ct_tracker *t) {
    node *n = t->cur;
    switch (n->state) {
    case T_EXECUTING:
        n->state = T_DONE;
        break;
    case T_EXEC_CHILDREN: {
        int all = 1;
        for (node *c = n->child; c; c = c->sibling) all &= node_complete(c);
        if (all) n->state = T_DONE;
        break;
    }
    default: /* T_NEEDS_RUN stays; finished states stay */
        break;
    }
    if (n->parent) t->cur = n->parent;
    t->cycle_done = 1;
}

static node *tracker_enter_at(ct_tracker *t, const char *name, const char *file, int line) {
    node *c;
    for (c = t->cur->child; c; c = c->sibling)
        if (strcmp(c->name, name) == 0) break;
    if (!c) {
        c = (node *)xmalloc(sizeof *c);
        memset(c, 0, sizeof *c);
        c->name = xstrdup(name);
        c->file = file;
        c->line = line;
        c->parent = t->cur;
        c->depth = t->cur->depth + 1;
        if (t->cur->last_child)
            t->cur->last_child->sibling = c;
        else
            t->cur->child = c;
        t->cur->last_child = c;
        /* -c NAME: a section off the requested path counts as complete. */
        if ((size_t)c->depth <= t->nfilters) {
            char *nn = normalise(name, strlen(name));
            if (strcmp(nn, t->filters[c->depth - 1]) != 0) c->state = T_DONE;
            free(nn);
        }
    }
    if (t->cycle_done || node_complete(c)) return NULL;
    node_open(c);
    t->cur = c;
    return c;
}

int ct_tracker_enter(ct_tracker *t, const char *name) {
    return tracker_enter_at(t, name, NULL, 0) != NULL;
}

void ct_tracker_leave(ct_tracker *t) {
    if (t->cur != &t->root) tracker_close_current(t);
}

/* RunContext::sectionEndedEarly: the innermost open section fails and its
 * parent needs another run. A failure in the case body outside any section
 * fails nothing: Catch2 closes the case's tracker as usual, so sections not
 * yet visited still get their runs. */
void ct_tracker_fail(ct_tracker *t) {
    node *n = t->cur;
    if (n->parent) {
        n->state = T_FAILED;
        n->parent->state = T_NEEDS_RUN;
        t->cur = n->parent;
    }
    t->cycle_done = 1;
}

int ct_tracker_end_run(ct_tracker *t) {
    while (t->cur != &t->root) tracker_close_current(t);
    tracker_close_current(t);
    return node_complete(&t->root);
}

/* ================================================================ results */

enum { EV_PASS, EV_FAIL, EV_SKIP, EV_WARN };

typedef struct event {
    int kind;
    const char *file;
    int line;
    char *macro;     /* "CHECK_EQ", or NULL for FAIL/SKIP/WARN/SUCCEED */
    char *expr;      /* operands as written */
    char *expansion; /* operands' values, may be NULL */
    char *messages;  /* INFO messages and the explicit message, '\n'-joined */
    int nmessages;
    struct event *next;
} event;

typedef struct secinfo {
    char *name;
    const char *file;
    int line;
} secinfo;

typedef struct run {
    secinfo *path; /* the deepest section chain entered in this run */
    size_t depth;
    double secs;
    long passed, failed, skipped;
    event *first, *last;
    size_t nevents;
    struct run *next;
} run;

typedef struct caserec {
    ct_case *tc;
    run *runs, *last_run;
    double secs;
    long passed, failed, skipped; /* assertions */
    int result;                   /* 0 passed, 1 failed, 2 skipped */
} caserec;

typedef struct info {
    const char *file;
    int line;
    int depth; /* section depth it was issued in */
    char *text;
} info;

typedef struct reporter {
    int kind; /* R_CONSOLE, R_JUNIT, R_XML */
    char *out;  /* NULL: the default output */
    FILE *fp;
    int own_fp;
} reporter;

enum { R_CONSOLE, R_JUNIT, R_XML };
enum { ORDER_DECL, ORDER_LEX, ORDER_RAND };

static struct state {
    /* registration */
    ct_case *first, *last;
    size_t ncases;
    /* configuration */
    const char *exe;
    char *run_name;
    int success, list_tests, list_tags, list_reporters, help;
    int order, durations, allow_no_tests, verbosity;
    int warn_no_assertions, warn_unmatched;
    long abort_after;
    uint32_t seed;
    unsigned long long shard_count, shard_index;
    reporter *reps;
    size_t nreps;
    char *default_out;
    char **sections;
    size_t nsections;
    /* the session */
    FILE *con; /* console reporter stream or NULL */
    int store_passes;
    int run_info_printed;
    long total_pass, total_fail, total_skip; /* assertions */
    long cases_pass, cases_fail, cases_skip;
    int aborting;
    /* the case being run */
    caserec *rec;
    run *cur_run;
    ct_tracker *tracker;
    int in_case;
    int header_printed;
    info *infos;
    size_t ninfos, capinfos;
    jmp_buf jump;
    const char *last_file; /* last assertion, for fatal signals */
    int last_line;
    char data_dir[4096];
    int data_dir_done;
} S;

void ct_register(ct_case *tc) {
    tc->next = NULL;
    if (S.last)
        S.last->next = tc;
    else
        S.first = tc;
    S.last = tc;
    S.ncases++;
}

uint32_t ct_run_seed(void) { return S.seed; }

const char *ct_current_case(void) { return S.in_case ? S.rec->tc->name : NULL; }

/* ---------------------------------------------------------------- console */

static void line_of(FILE *fp, char c) {
    for (int i = 0; i < CONSOLE_WIDTH - 1; i++) fputc(c, fp);
    fputc('\n', fp);
}

static void print_indented(FILE *fp, const char *text, const char *indent) {
    const char *p = text;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - p) : strlen(p);
        fprintf(fp, "%s%.*s\n", indent, (int)n, p);
        p += n;
        if (*p == '\n') p++;
    }
}

static void console_run_info(void) {
    if (!S.con || S.run_info_printed) return;
    fputc('\n', S.con);
    line_of(S.con, '~');
    fprintf(S.con, "%s is a Catch2-compatible Conica test runner (conica_test).\n"
                   "Run with -? for options\n\n",
            S.run_name);
    S.run_info_printed = 1;
}

/* printTestCaseAndSectionHeader: case name, open sections, innermost place. */
static void console_header(void) {
    if (!S.con || S.header_printed) return;
    console_run_info();
    line_of(S.con, '-');
    fprintf(S.con, "%s\n", S.rec->tc->name);
    node *chain[256];
    size_t n = 0;
    for (node *c = S.tracker->cur; c && c->parent && n < 256; c = c->parent) chain[n++] = c;
    const char *file = S.rec->tc->file;
    int line = S.rec->tc->line;
    for (size_t i = n; i-- > 0;) {
        fprintf(S.con, "  %s\n", chain[i]->name);
        file = chain[i]->file;
        line = chain[i]->line;
    }
    line_of(S.con, '-');
    fprintf(S.con, "%s:%d\n", file, line);
    line_of(S.con, '.');
    fputc('\n', S.con);
    S.header_printed = 1;
}

static void console_event(const event *e) {
    if (!S.con) return;
    console_header();
    FILE *fp = S.con;
    fprintf(fp, "%s:%d: ", e->file, e->line);
    const char *label = NULL;
    switch (e->kind) {
    case EV_PASS:
        fputs("PASSED:\n", fp);
        label = e->macro ? "with message" : "explicitly with message";
        break;
    case EV_FAIL:
        fputs("FAILED:\n", fp);
        label = e->macro ? "with message" : "explicitly with message";
        break;
    case EV_SKIP:
        fputs("SKIPPED:\n", fp);
        label = "explicitly with message";
        break;
    default:
        fputs("warning:\n", fp);
        break;
    }
    if (e->macro) {
        fprintf(fp, "  %s( %s )\n", e->macro, e->expr);
        if (e->expansion) {
            fputs("with expansion:\n", fp);
            print_indented(fp, e->expansion, "  ");
        }
    }
    if (e->nmessages > 0) {
        if (label) fprintf(fp, "%s%s:\n", label, e->nmessages > 1 ? "s" : "");
        print_indented(fp, e->messages, "  ");
    }
    fputc('\n', fp);
    fflush(fp);
}

/* SummaryColumn/printSummaryRow from catch_reporter_helpers.cpp: values of a
 * column share a width; zero cells of captioned columns are left out. */
static void summary_rows(FILE *fp, long tc[5], long as[5]) {
    static const char *const caption[5] = {"", "passed", "failed", "skipped",
                                           "failed as expected"};
    const char *label[2] = {"test cases", "assertions"};
    for (int row = 0; row < 2; row++) {
        for (int col = 0; col < 5; col++) {
            char a[32], b[32], cell[32];
            snprintf(a, sizeof a, "%ld", tc[col]);
            snprintf(b, sizeof b, "%ld", as[col]);
            size_t w = strlen(a) > strlen(b) ? strlen(a) : strlen(b);
            const char *v = row == 0 ? a : b;
            snprintf(cell, sizeof cell, "%*s", (int)w, v);
            if (col == 0) {
                if (strcmp(cell, "0") != 0)
                    fprintf(fp, "%s: %s", label[row], cell);
                else
                    fprintf(fp, "%s: - none -", label[row]);
            } else if (strcmp(cell, "0") != 0) {
                fprintf(fp, " | %s %s", cell, caption[col]);
            }
        }
        fputc('\n', fp);
    }
}

static void console_totals(FILE *fp) {
    long ncases = S.cases_pass + S.cases_fail + S.cases_skip;
    line_of(fp, '=');
    if (ncases == 0) {
        fputs("No tests ran\n", fp);
    } else if (S.total_pass + S.total_fail > 0 && S.cases_fail == 0 && S.cases_skip == 0) {
        fprintf(fp, "All tests passed (%ld assertion%s in %ld test case%s)\n", S.total_pass,
                S.total_pass == 1 ? "" : "s", S.cases_pass, S.cases_pass == 1 ? "" : "s");
    } else {
        long tc[5] = {ncases, S.cases_pass, S.cases_fail, S.cases_skip, 0};
        long as[5] = {S.total_pass + S.total_fail, S.total_pass, S.total_fail, 0, 0};
        summary_rows(fp, tc, as);
    }
    fputc('\n', fp);
    fflush(fp);
}

/* ---------------------------------------------------------------- xml */

static void xml_text(FILE *fp, const char *s) {
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        case '\'': fputs("&apos;", fp); break;
        default:
            if (*p < 0x20 && *p != '\n' && *p != '\t' && *p != '\r')
                fprintf(fp, "\\x%02x", *p); /* not representable in XML 1.0 */
            else
                fputc(*p, fp);
        }
    }
}

static void xml_attr(FILE *fp, const char *name, const char *value) {
    fprintf(fp, " %s=\"", name);
    xml_text(fp, value ? value : "");
    fputc('"', fp);
}

static void event_body(sb *b, const event *e) {
    sb_puts(b, e->kind == EV_SKIP ? "SKIPPED:\n" : e->kind == EV_PASS ? "PASSED:\n" : "FAILED:\n");
    if (e->macro) {
        sb_printf(b, "  %s( %s )\n", e->macro, e->expr);
        if (e->expansion) sb_printf(b, "with expansion:\n  %s\n", e->expansion);
    }
    if (e->nmessages > 0) {
        sb_printf(b, "%s%s:\n", e->macro ? "with message" : "explicitly with message",
                  e->nmessages > 1 ? "s" : "");
        const char *p = e->messages;
        while (*p) {
            const char *nl = strchr(p, '\n');
            size_t n = nl ? (size_t)(nl - p) : strlen(p);
            sb_puts(b, "  ");
            sb_putn(b, p, n);
            sb_putc(b, '\n');
            p += n;
            if (*p) p++;
        }
    }
    sb_printf(b, "at %s:%d\n", e->file, e->line);
}

static char *run_name_of(const caserec *c, const run *r) {
    sb b = {0};
    sb_puts(&b, c->tc->name);
    for (size_t i = 0; i < r->depth; i++) sb_printf(&b, "/%s", r->path[i].name);
    return sb_take(&b);
}

static void junit_write(FILE *fp, caserec *recs, size_t n, double total_secs) {
    long tests = 0, failures = 0, skipped = 0;
    for (size_t i = 0; i < n; i++)
        for (run *r = recs[i].runs; r; r = r->next) {
            tests++;
            if (r->failed)
                failures++;
            else if (r->skipped)
                skipped++;
        }
    char stamp[64];
    time_t t = time(NULL);
    struct tm tmv;
    gmtime_r(&t, &tmv);
    strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n  <testsuite", fp);
    xml_attr(fp, "name", S.run_name);
    fprintf(fp, " errors=\"0\" failures=\"%ld\" skipped=\"%ld\" tests=\"%ld\" hostname=\"tbd\""
                " time=\"%.3f\" timestamp=\"%s\">\n",
            failures, skipped, tests, total_secs, stamp);
    fprintf(fp, "    <properties>\n      <property name=\"random-seed\" value=\"%lu\"/>\n"
                "    </properties>\n",
            (unsigned long)S.seed);
    char *classname = (char *)xmalloc(strlen(S.run_name) + 8);
    sprintf(classname, "%s.global", S.run_name);
    for (size_t i = 0; i < n; i++) {
        for (run *r = recs[i].runs; r; r = r->next) {
            char *name = run_name_of(&recs[i], r);
            fputs("    <testcase", fp);
            xml_attr(fp, "classname", classname);
            xml_attr(fp, "name", name);
            fprintf(fp, " time=\"%.3f\" status=\"run\">\n", r->secs);
            free(name);
            for (event *e = r->first; e; e = e->next) {
                if (e->kind != EV_FAIL && e->kind != EV_SKIP) continue;
                const char *tag = e->kind == EV_FAIL ? "failure" : "skipped";
                fprintf(fp, "      <%s", tag);
                if (e->macro) {
                    xml_attr(fp, "message", e->expr);
                    xml_attr(fp, "type", e->macro);
                } else {
                    const char *m = e->messages ? strrchr(e->messages, '\n') : NULL;
                    xml_attr(fp, "message", m ? m + 1 : (e->messages ? e->messages : ""));
                    xml_attr(fp, "type", e->kind == EV_FAIL ? "FAIL" : "SKIP");
                }
                fputs(">\n", fp);
                sb b = {0};
                event_body(&b, e);
                xml_text(fp, b.p);
                free(b.p);
                fprintf(fp, "      </%s>\n", tag);
            }
            fputs("    </testcase>\n", fp);
        }
    }
    free(classname);
    fputs("    <system-out/>\n    <system-err/>\n  </testsuite>\n</testsuites>\n", fp);
    fflush(fp);
}

static void xml_results(FILE *fp, const char *ind, const char *el, long s, long f, long k) {
    fprintf(fp, "%s<%s successes=\"%ld\" failures=\"%ld\" expectedFailures=\"0\" skips=\"%ld\"/>\n",
            ind, el, s, f, k);
}

static void xml_write(FILE *fp, caserec *recs, size_t n) {
    fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Catch2TestRun", fp);
    xml_attr(fp, "name", S.run_name);
    fprintf(fp, " rng-seed=\"%lu\" xml-format-version=\"3\" catch2-version=\"3.7.1\">\n",
            (unsigned long)S.seed);
    for (size_t i = 0; i < n; i++) {
        caserec *c = &recs[i];
        fputs("  <TestCase", fp);
        xml_attr(fp, "name", c->tc->name);
        xml_attr(fp, "tags", c->tc->tags);
        xml_attr(fp, "filename", c->tc->file);
        fprintf(fp, " line=\"%d\">\n", c->tc->line);
        for (run *r = c->runs; r; r = r->next) {
            sb ind = {0};
            sb_puts(&ind, "    ");
            for (size_t d = 0; d < r->depth; d++) {
                fputs(ind.p, fp);
                fputs("<Section", fp);
                xml_attr(fp, "name", r->path[d].name);
                xml_attr(fp, "filename", r->path[d].file);
                fprintf(fp, " line=\"%d\">\n", r->path[d].line);
                sb_puts(&ind, "  ");
            }
            for (event *e = r->first; e; e = e->next) {
                if (e->macro) {
                    if (e->messages) {
                        const char *p = e->messages;
                        while (*p) {
                            const char *nl = strchr(p, '\n');
                            size_t len = nl ? (size_t)(nl - p) : strlen(p);
                            char *m = xstrndup(p, len);
                            fprintf(fp, "%s<Info>", ind.p);
                            xml_text(fp, m);
                            fputs("</Info>\n", fp);
                            free(m);
                            p += len;
                            if (*p) p++;
                        }
                    }
                    fprintf(fp, "%s<Expression success=\"%s\"", ind.p,
                            e->kind == EV_PASS ? "true" : "false");
                    xml_attr(fp, "type", e->macro);
                    xml_attr(fp, "filename", e->file);
                    fprintf(fp, " line=\"%d\">\n%s  <Original>", e->line, ind.p);
                    xml_text(fp, e->expr);
                    fprintf(fp, "</Original>\n%s  <Expanded>", ind.p);
                    xml_text(fp, e->expansion ? e->expansion : e->expr);
                    fprintf(fp, "</Expanded>\n%s</Expression>\n", ind.p);
                } else {
                    const char *el = e->kind == EV_FAIL ? "Failure"
                                     : e->kind == EV_SKIP ? "Skip"
                                     : e->kind == EV_WARN ? "Warning" : "Success";
                    fprintf(fp, "%s<%s", ind.p, el);
                    xml_attr(fp, "filename", e->file);
                    fprintf(fp, " line=\"%d\">", e->line);
                    xml_text(fp, e->messages ? e->messages : "");
                    fprintf(fp, "</%s>\n", el);
                }
            }
            for (size_t d = r->depth; d-- > 0;) {
                ind.n -= 2;
                ind.p[ind.n] = '\0';
                fprintf(fp, "%s  <OverallResults successes=\"%ld\" failures=\"%ld\" "
                            "expectedFailures=\"0\" skipped=\"%s\"/>\n%s</Section>\n",
                        ind.p, r->passed, r->failed, r->skipped ? "true" : "false", ind.p);
            }
            free(ind.p);
        }
        fprintf(fp, "    <OverallResult success=\"%s\" skips=\"%ld\"", c->failed ? "false" : "true",
                c->skipped);
        if (S.durations) fprintf(fp, " durationInSeconds=\"%.6f\"", c->secs);
        fputs("/>\n  </TestCase>\n", fp);
    }
    xml_results(fp, "  ", "OverallResults", S.total_pass, S.total_fail, S.total_skip);
    xml_results(fp, "  ", "OverallResultsCases", S.cases_pass, S.cases_fail, S.cases_skip);
    fputs("</Catch2TestRun>\n", fp);
    fflush(fp);
}

/* ---------------------------------------------------------------- events */

static char *info_messages(int *count, const char *extra) {
    sb b = {0};
    int n = 0;
    for (size_t i = 0; i < S.ninfos; i++) {
        if (n++) sb_putc(&b, '\n');
        sb_puts(&b, S.infos[i].text);
    }
    if (extra) {
        if (n++) sb_putc(&b, '\n');
        sb_puts(&b, extra);
    }
    *count = n;
    if (!n) return NULL;
    return sb_take(&b);
}

static void run_store(event *e) {
    run *r = S.cur_run;
    if (r->nevents >= MAX_STORED_EVENTS) {
        free(e->macro);
        free(e->expr);
        free(e->expansion);
        free(e->messages);
        free(e);
        return;
    }
    r->nevents++;
    if (r->last)
        r->last->next = e;
    else
        r->first = e;
    r->last = e;
}

/* Record one result. `extra` is an explicit message; strings are copied. */
static void report(int kind, const char *file, int line, const char *macro, char *expr,
                   char *expansion, const char *extra) {
    if (!S.in_case) {
        fprintf(stderr, "%s:%d: assertion outside a test case\n", file, line);
        free(expr);
        free(expansion);
        return;
    }
    S.last_file = file;
    S.last_line = line;
    if (kind == EV_PASS) {
        S.total_pass++;
        S.cur_run->passed++;
        S.rec->passed++;
    } else if (kind == EV_FAIL) {
        S.total_fail++;
        S.cur_run->failed++;
        S.rec->failed++;
    } else if (kind == EV_SKIP) {
        S.total_skip++;
        S.cur_run->skipped++;
        S.rec->skipped++;
    }
    int shown = kind != EV_PASS || S.success;
    int stored = kind != EV_PASS || S.store_passes;
    if (!shown && !stored) {
        free(expr);
        free(expansion);
        return;
    }
    event *e = (event *)xmalloc(sizeof *e);
    memset(e, 0, sizeof *e);
    e->kind = kind;
    e->file = file;
    e->line = line;
    e->macro = macro ? xstrdup(macro) : NULL;
    e->expr = expr;
    e->expansion = expansion;
    /* A warning shows no INFO context (ConsoleAssertionPrinter::printMessage). */
    if (kind == EV_WARN) {
        e->messages = extra ? xstrdup(extra) : NULL;
        e->nmessages = extra ? 1 : 0;
    } else {
        e->messages = info_messages(&e->nmessages, extra);
    }
    if (shown) console_event(e);
    if (stored)
        run_store(e);
    else {
        free(e->macro);
        free(e->expr);
        free(e->expansion);
        free(e->messages);
        free(e);
    }
}

/* Ends the current run of the case (REQUIRE, FAIL, SKIP, --abort). */
static CT_NORETURN void end_run_early(void) { longjmp(S.jump, 1); }

static int after_result(int ok, int req) {
    if (!ok && S.abort_after > 0 && S.total_fail >= S.abort_after) S.aborting = 1;
    if (!ok && (req || S.aborting) && S.in_case) end_run_early();
    return ok;
}

static char *fmt_alloc(const char *fmt, ...) CT_PRINTF(1, 2);
static char *fmt_alloc(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    char *s = vformat(fmt, ap);
    va_end(ap);
    return s;
}

/* A passing assertion that nobody prints (-s) or stores (-s with junit/xml)
 * is only counted: formatting its operands would dominate property tests
 * that make millions of assertions. */
static int quiet_pass(int ok, const char *file, int line) {
    if (!ok || S.success || S.store_passes || !S.in_case) return 0;
    S.last_file = file;
    S.last_line = line;
    S.total_pass++;
    S.cur_run->passed++;
    S.rec->passed++;
    return 1;
}

int ct_check_bool(const char *file, int line, const char *macro, const char *expr, int ok,
                  int req) {
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, xstrdup(expr), NULL, NULL);
    return after_result(ok, req);
}

static int cmp_ok_ll(const char *op, long long a, long long b) {
    if (strcmp(op, "==") == 0) return a == b;
    if (strcmp(op, "!=") == 0) return a != b;
    if (strcmp(op, "<") == 0) return a < b;
    if (strcmp(op, "<=") == 0) return a <= b;
    if (strcmp(op, ">") == 0) return a > b;
    return a >= b;
}

int ct_check_int(const char *file, int line, const char *macro, const char *ea, const char *eb,
                 const char *op, long long a, long long b, int req) {
    int ok = cmp_ok_ll(op, a, b);
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s", ea, eb),
           fmt_alloc("%lld %s %lld", a, op, b), NULL);
    return after_result(ok, req);
}

int ct_check_uint(const char *file, int line, const char *macro, const char *ea,
                  const char *eb, const char *op, unsigned long long a, unsigned long long b,
                  int req) {
    int ok = strcmp(op, "==") == 0 ? a == b : a != b;
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s", ea, eb),
           fmt_alloc("%llu %s %llu", a, op, b), NULL);
    return after_result(ok, req);
}

int ct_check_cmp_d(const char *file, int line, const char *macro, const char *ea,
                   const char *eb, const char *op, double a, double b, int req) {
    int ok;
    if (strcmp(op, "<") == 0)
        ok = a < b;
    else if (strcmp(op, "<=") == 0)
        ok = a <= b;
    else if (strcmp(op, ">") == 0)
        ok = a > b;
    else
        ok = a >= b;
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s", ea, eb),
           fmt_alloc("%.17g %s %.17g", a, op, b), NULL);
    return after_result(ok, req);
}

int ct_check_near(const char *file, int line, const char *macro, const char *ea,
                  const char *eb, const char *et, double a, double b, double tol, int req) {
    double d = fabs(a - b);
    int ok = d <= tol; /* false for NaN */
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s, %s", ea, eb, et),
           fmt_alloc("%.17g == %.17g +/- %.6g (|difference| %.17g)", a, b, tol, d), NULL);
    return after_result(ok, req);
}

int ct_check_rel(const char *file, int line, const char *macro, const char *ea, const char *eb,
                 const char *et, double a, double b, double rel, int req) {
    double d = fabs(a - b);
    double scale = fmax(fabs(a), fabs(b));
    int ok = d <= rel * scale; /* false for NaN */
    if (quiet_pass(ok, file, line)) return 1;
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s, %s", ea, eb, et),
           fmt_alloc("%.17g == %.17g within relative %.6g (|difference| %.17g, relative %.6g)",
                     a, b, rel, d, scale > 0 ? d / scale : d),
           NULL);
    return after_result(ok, req);
}

static char *quoted(const char *s) {
    if (!s) return xstrdup("NULL");
    sb b = {0};
    sb_putc(&b, '"');
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\')
            sb_printf(&b, "\\%c", *p);
        else if (*p == '\n')
            sb_puts(&b, "\\n");
        else if (*p < 0x20)
            sb_printf(&b, "\\x%02x", *p);
        else
            sb_putc(&b, (char)*p);
    }
    sb_putc(&b, '"');
    return sb_take(&b);
}

int ct_check_str(const char *file, int line, const char *macro, const char *ea, const char *eb,
                 const char *a, const char *b, int req) {
    int ok = (a && b) ? strcmp(a, b) == 0 : a == b;
    if (quiet_pass(ok, file, line)) return 1;
    char *qa = quoted(a), *qb = quoted(b);
    report(ok ? EV_PASS : EV_FAIL, file, line, macro, fmt_alloc("%s, %s", ea, eb),
           fmt_alloc("%s == %s", qa, qb), NULL);
    free(qa);
    free(qb);
    return after_result(ok, req);
}

/* SUCCEED, FAIL_CHECK, FAIL, SKIP, WARN: an explicit message, no expression. */
static void explicit_v(int kind, const char *file, int line, const char *fmt, va_list ap) {
    char *m = vformat(fmt, ap);
    report(kind, file, line, NULL, NULL, NULL, m);
    free(m);
}

#define EXPLICIT_EVENT(kind)                        \
    do {                                            \
        va_list ap;                                 \
        va_start(ap, fmt);                          \
        explicit_v(kind, file, line, fmt, ap);      \
        va_end(ap);                                 \
    } while (0)

void ct_succeed(const char *file, int line, const char *fmt, ...) { EXPLICIT_EVENT(EV_PASS); }

void ct_warn(const char *file, int line, const char *fmt, ...) { EXPLICIT_EVENT(EV_WARN); }

void ct_fail_check(const char *file, int line, const char *fmt, ...) {
    EXPLICIT_EVENT(EV_FAIL);
    after_result(0, 0);
}

void ct_fail(const char *file, int line, const char *fmt, ...) {
    EXPLICIT_EVENT(EV_FAIL);
    if (S.in_case) end_run_early();
    exit(EXIT_ERROR);
}

void ct_skip(const char *file, int line, const char *fmt, ...) {
    EXPLICIT_EVENT(EV_SKIP);
    if (S.in_case) end_run_early();
    exit(EXIT_ERROR);
}

void ct_info(const char *file, int line, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    char *m = vformat(fmt, ap);
    va_end(ap);
    if (!S.in_case) {
        free(m);
        return;
    }
    /* The same source line again (a loop, a helper called twice) replaces
     * its earlier message, as if Catch2's scope had ended. */
    for (size_t i = 0; i < S.ninfos; i++)
        if (S.infos[i].line == line && strcmp(S.infos[i].file, file) == 0) {
            free(S.infos[i].text);
            S.infos[i].text = m;
            return;
        }
    if (S.ninfos == S.capinfos) {
        S.capinfos = S.capinfos ? 2 * S.capinfos : 16;
        S.infos = (info *)xrealloc(S.infos, S.capinfos * sizeof *S.infos);
    }
    info *in = &S.infos[S.ninfos++];
    in->file = file;
    in->line = line;
    in->depth = S.tracker->cur->depth;
    in->text = m;
}

static void infos_trim(int depth) {
    while (S.ninfos > 0 && S.infos[S.ninfos - 1].depth > depth) free(S.infos[--S.ninfos].text);
}

int ct_section_enter(const char *file, int line, const char *name) {
    if (!S.in_case) return 0;
    node *n = tracker_enter_at(S.tracker, name, file, line);
    if (!n) return 0;
    S.header_printed = 0;
    run *r = S.cur_run;
    /* Record the chain: only one leaf path is entered per run. */
    for (size_t i = 0; i < r->depth; i++) free(r->path[i].name);
    free(r->path);
    r->depth = (size_t)n->depth;
    r->path = (secinfo *)xmalloc(r->depth * sizeof *r->path);
    for (node *c = n; c->parent; c = c->parent) {
        secinfo *si = &r->path[c->depth - 1];
        si->name = xstrdup(c->name);
        si->file = c->file;
        si->line = c->line;
    }
    return 1;
}

int ct_section_enter_fmt(const char *file, int line, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    char *name = vformat(fmt, ap);
    va_end(ap);
    int r = ct_section_enter(file, line, name);
    free(name);
    return r;
}

int ct_section_leave(void) {
    if (!S.in_case) return 0;
    int depth = S.tracker->cur->depth;
    ct_tracker_leave(S.tracker);
    infos_trim(depth - 1);
    S.header_printed = 0;
    return 0;
}

/* ================================================================ running */

static void run_free(run *r) {
    while (r) {
        run *next = r->next;
        for (event *e = r->first; e;) {
            event *en = e->next;
            free(e->macro);
            free(e->expr);
            free(e->expansion);
            free(e->messages);
            free(e);
            e = en;
        }
        for (size_t i = 0; i < r->depth; i++) free(r->path[i].name);
        free(r->path);
        free(r);
        r = next;
    }
}

/* One run of the body; kept apart so no local lives across setjmp. */
static int run_once(ct_case *tc) {
    if (setjmp(S.jump) == 0) {
        tc->fn();
        return 0;
    }
    return 1;
}

static void run_case(caserec *c) {
    ct_tracker *t = ct_tracker_new();
    for (size_t i = 0; i < S.nsections; i++) ct_tracker_add_filter(t, S.sections[i]);
    S.tracker = t;
    S.rec = c;
    S.in_case = 1;
    srand(S.seed);
    double t0 = now_seconds();
    long runs = 0;
    int done = 0;
    while (!done && !S.aborting) {
        run *r = (run *)xmalloc(sizeof *r);
        memset(r, 0, sizeof *r);
        if (c->last_run)
            c->last_run->next = r;
        else
            c->runs = r;
        c->last_run = r;
        S.cur_run = r;
        S.header_printed = 0;
        ct_tracker_start_run(t);
        double r0 = now_seconds();
        if (run_once(c->tc)) ct_tracker_fail(t);
        done = ct_tracker_end_run(t);
        r->secs = now_seconds() - r0;
        infos_trim(-1);
        if (++runs >= MAX_RUNS_PER_CASE && !done) {
            fprintf(stderr, "%s: test case '%s' did not finish its sections after %ld runs\n",
                    S.run_name, c->tc->name, runs);
            report(EV_FAIL, c->tc->file, c->tc->line, NULL, NULL, NULL,
                   "section discovery did not terminate");
            break;
        }
    }
    c->secs = now_seconds() - t0;
    if (S.warn_no_assertions && c->passed + c->failed + c->skipped == 0 && S.con) {
        console_header();
        fprintf(S.con, "\nNo assertions in test case '%s'\n\n", c->tc->name);
        c->failed++;
        S.total_fail++;
    }
    S.in_case = 0;
    S.cur_run = NULL;
    ct_tracker_free(t);
    S.tracker = NULL;
    if (c->failed) {
        c->result = 1;
        S.cases_fail++;
    } else if (c->skipped) {
        c->result = 2;
        S.cases_skip++;
    } else {
        c->result = 0;
        S.cases_pass++;
    }
    if (S.durations && S.con) fprintf(S.con, "%.3f s: %s\n", c->secs, c->tc->name);
}

/* ---------------------------------------------------------------- signals */

/* Catch2's fatal condition handler: a crashing case is reported as a failed
 * assertion, the totals are printed, then the signal is re-raised so the
 * process still dies of it. Not installed under AddressSanitizer, whose own
 * report is more useful. */
#if defined(__SANITIZE_ADDRESS__)
#define CT_HAVE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CT_HAVE_ASAN 1
#endif
#endif

#ifndef CT_HAVE_ASAN
static const struct {
    int sig;
    const char *what;
} FATAL_SIGNALS[] = {
    {SIGINT, "SIGINT - Terminal interrupt signal"},
    {SIGILL, "SIGILL - Illegal instruction signal"},
    {SIGFPE, "SIGFPE - Floating point error signal"},
    {SIGSEGV, "SIGSEGV - Segmentation violation signal"},
    {SIGTERM, "SIGTERM - Termination request signal"},
    {SIGABRT, "SIGABRT - Abort (abnormal termination) signal"},
    {SIGBUS, "SIGBUS - Bus error signal"},
};
#define N_FATAL (sizeof FATAL_SIGNALS / sizeof FATAL_SIGNALS[0])

static void on_fatal_signal(int sig) {
    const char *what = "unknown signal";
    for (size_t i = 0; i < N_FATAL; i++)
        if (FATAL_SIGNALS[i].sig == sig) what = FATAL_SIGNALS[i].what;
    if (S.in_case && S.con) {
        console_header();
        fprintf(S.con, "%s:%d: FAILED:\ndue to a fatal error condition:\n  %s\n\n",
                S.last_file ? S.last_file : S.rec->tc->file,
                S.last_file ? S.last_line : S.rec->tc->line, what);
        S.total_fail++;
        S.cases_fail++;
        console_totals(S.con);
    }
    fflush(NULL);
    signal(sig, SIG_DFL);
    raise(sig);
}

static void install_fatal_handlers(void) {
    static char altstack[1 << 16]; /* room to report a stack overflow */
    stack_t ss;
    memset(&ss, 0, sizeof ss);
    ss.ss_sp = altstack;
    ss.ss_size = sizeof altstack;
    sigaltstack(&ss, NULL);
    for (size_t i = 0; i < N_FATAL; i++) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_fatal_signal;
        sa.sa_flags = (int)(SA_ONSTACK | SA_RESETHAND);
        sigemptyset(&sa.sa_mask);
        sigaction(FATAL_SIGNALS[i].sig, &sa, NULL);
    }
}
#else
static void install_fatal_handlers(void) {}
#endif

/* ================================================================ CLI */

static const char *const HELP =
    "\nusage:\n"
    "  %s [<test name|pattern|tags> ... ] options\n\n"
    "where options are:\n"
    "  -?, -h, --help                  display usage information\n"
    "  -s, --success                   include successful tests in output\n"
    "  -a, --abort                     abort at first failure\n"
    "  -x, --abortx <no. failures>     abort after x failures\n"
    "  -w, --warn <warning name>       enable warnings (NoAssertions,\n"
    "                                  UnmatchedTestSpec)\n"
    "  -d, --durations <yes|no>        show test durations\n"
    "  -c, --section <section name>    specify section to run\n"
    "  -v, --verbosity <quiet|normal|high>  set output verbosity\n"
    "  --list-tests                    list all/matching test cases\n"
    "  --list-tags                     list all/matching tags\n"
    "  --list-reporters                list all available reporters\n"
    "  -r, --reporter <name[::out=FILE]>  reporter to use: console, junit, xml\n"
    "                                  (repeatable; defaults to console)\n"
    "  -o, --out <filename>            default output filename\n"
    "  -n, --name <name>               suite name\n"
    "  --order <decl|lex|rand>         test case order (defaults to decl)\n"
    "  --rng-seed <'time'|number>      set a specific seed for random numbers\n"
    "  --shard-count <shard count>     split the tests to execute into this\n"
    "                                  many groups\n"
    "  --shard-index <shard index>     index of the group of tests to execute\n"
    "  --allow-running-no-tests        treat 'No tests run' as a success\n"
    "  --colour-mode <ansi|none|default>  accepted; output is never coloured\n\n"
    "Test specs: exact name, '*' at either end, [tag], [a][b] (AND), a,b (OR),\n"
    "~ negates, tags starting with '.' hide a test unless a spec names it.\n"
    "Exit codes: 0 pass, 42 failures, 2 no tests ran, 3 unmatched spec (with\n"
    "-w UnmatchedTestSpec), 4 all skipped, 5 invalid spec, 1 other errors.\n\n";

static int cli_error(const char *fmt, ...) CT_PRINTF(1, 2);
static int cli_error(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fputs("\nError(s) in input:\n  ", stderr);
    vfprintf(stderr, fmt, ap);
    fputs("\n\nRun with -? for usage\n\n", stderr);
    va_end(ap);
    return 0;
}

static int add_reporter(const char *specv) {
    const char *sep = strstr(specv, "::");
    size_t nlen = sep ? (size_t)(sep - specv) : strlen(specv);
    reporter r;
    memset(&r, 0, sizeof r);
    if (nlen == 7 && strncmp(specv, "console", 7) == 0)
        r.kind = R_CONSOLE;
    else if (nlen == 5 && strncmp(specv, "junit", 5) == 0)
        r.kind = R_JUNIT;
    else if (nlen == 3 && strncmp(specv, "xml", 3) == 0)
        r.kind = R_XML;
    else
        return cli_error("Unrecognized reporter, '%.*s'. Check available with --list-reporters",
                         (int)nlen, specv);
    while (sep) {
        const char *kv = sep + 2;
        sep = strstr(kv, "::");
        size_t klen = sep ? (size_t)(sep - kv) : strlen(kv);
        if (klen > 4 && strncmp(kv, "out=", 4) == 0) {
            free(r.out);
            r.out = xstrndup(kv + 4, klen - 4);
        } else if (klen > 12 && strncmp(kv, "colour-mode=", 12) == 0) {
            /* accepted, never coloured */
        } else {
            free(r.out);
            return cli_error("Unrecognized reporter option in '%s'", specv);
        }
    }
    S.reps = (reporter *)xrealloc(S.reps, (S.nreps + 1) * sizeof *S.reps);
    S.reps[S.nreps++] = r;
    return 1;
}

static int is_prefix_of(const char *value, const char *word) {
    size_t n = strlen(value);
    return n > 0 && strncmp(word, value, n) == 0;
}

/* Parse argv into S; positional specs go to specs[]. Returns 1 if ok. */
static int parse_args(int argc, char **argv, const char **specs, int *nspecs) {
    *nspecs = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || a[1] == '\0') {
            specs[(*nspecs)++] = a;
            continue;
        }
        /* split --opt=value */
        char opt[64];
        const char *val = NULL;
        const char *eq = a[1] == '-' ? strchr(a, '=') : NULL;
        size_t olen = eq ? (size_t)(eq - a) : strlen(a);
        if (olen >= sizeof opt) return cli_error("Unrecognised token: %s", a);
        memcpy(opt, a, olen);
        opt[olen] = '\0';
        if (eq) val = eq + 1;
#define IS(s, l) (strcmp(opt, s) == 0 || strcmp(opt, l) == 0)
#define NEED_VALUE()                                                              \
    do {                                                                          \
        if (!val) {                                                               \
            if (i + 1 >= argc) return cli_error("Expected argument following %s", opt); \
            val = argv[++i];                                                      \
        }                                                                         \
    } while (0)
#define NO_VALUE()                                                                \
    do {                                                                          \
        if (val) return cli_error("Unexpected value for flag %s", opt);           \
    } while (0)
        unsigned long long u;
        if (IS("-?", "-h") || strcmp(opt, "--help") == 0) {
            NO_VALUE();
            S.help = 1;
        } else if (IS("-s", "--success")) {
            NO_VALUE();
            S.success = 1;
        } else if (IS("-a", "--abort")) {
            NO_VALUE();
            S.abort_after = 1;
        } else if (IS("-x", "--abortx")) {
            NEED_VALUE();
            if (!parse_uint(val, 1000000000ULL, &u) || u == 0)
                return cli_error("Unable to convert '%s' to destination type", val);
            S.abort_after = (long)u;
        } else if (IS("-w", "--warn")) {
            NEED_VALUE();
            if (strcmp(val, "NoAssertions") == 0)
                S.warn_no_assertions = 1;
            else if (strcmp(val, "UnmatchedTestSpec") == 0)
                S.warn_unmatched = 1;
            else
                return cli_error("Unrecognised warning option: '%s'", val);
        } else if (IS("-d", "--durations")) {
            NEED_VALUE();
            if (!strcmp(val, "yes") || !strcmp(val, "y") || !strcmp(val, "1") ||
                !strcmp(val, "true") || !strcmp(val, "on"))
                S.durations = 1;
            else if (!strcmp(val, "no") || !strcmp(val, "n") || !strcmp(val, "0") ||
                     !strcmp(val, "false") || !strcmp(val, "off"))
                S.durations = 0;
            else
                return cli_error("Expected a boolean value but did not recognise: '%s'", val);
        } else if (IS("-c", "--section")) {
            NEED_VALUE();
            S.sections = (char **)xrealloc(S.sections, (S.nsections + 1) * sizeof *S.sections);
            S.sections[S.nsections++] = xstrdup(val);
        } else if (IS("-v", "--verbosity")) {
            NEED_VALUE();
            if (!strcmp(val, "quiet"))
                S.verbosity = 0;
            else if (!strcmp(val, "normal"))
                S.verbosity = 1;
            else if (!strcmp(val, "high"))
                S.verbosity = 2;
            else
                return cli_error("Unrecognised verbosity, '%s'", val);
        } else if (IS("-r", "--reporter")) {
            NEED_VALUE();
            if (!add_reporter(val)) return 0;
        } else if (IS("-o", "--out")) {
            NEED_VALUE();
            free(S.default_out);
            S.default_out = xstrdup(val);
        } else if (IS("-n", "--name")) {
            NEED_VALUE();
            free(S.run_name);
            S.run_name = xstrdup(val);
        } else if (strcmp(opt, "--list-tests") == 0) {
            NO_VALUE();
            S.list_tests = 1;
        } else if (strcmp(opt, "--list-tags") == 0) {
            NO_VALUE();
            S.list_tags = 1;
        } else if (strcmp(opt, "--list-reporters") == 0) {
            NO_VALUE();
            S.list_reporters = 1;
        } else if (strcmp(opt, "--order") == 0) {
            NEED_VALUE();
            if (is_prefix_of(val, "declared"))
                S.order = ORDER_DECL;
            else if (is_prefix_of(val, "lexical"))
                S.order = ORDER_LEX;
            else if (is_prefix_of(val, "random"))
                S.order = ORDER_RAND;
            else
                return cli_error("Unrecognised ordering: '%s'", val);
        } else if (strcmp(opt, "--rng-seed") == 0) {
            NEED_VALUE();
            if (strcmp(val, "time") == 0)
                S.seed = (uint32_t)time(NULL);
            else if (strcmp(val, "random-device") == 0)
                S.seed = (uint32_t)((unsigned long)time(NULL) ^ ((unsigned long)getpid() << 16));
            else if (parse_uint(val, 0xffffffffULL, &u))
                S.seed = (uint32_t)u;
            else
                return cli_error("Could not parse '%s' as seed", val);
        } else if (strcmp(opt, "--shard-count") == 0) {
            NEED_VALUE();
            if (!parse_uint(val, 1000000000ULL, &u) || u == 0)
                return cli_error("Could not parse '%s' as shard count", val);
            S.shard_count = u;
        } else if (strcmp(opt, "--shard-index") == 0) {
            NEED_VALUE();
            if (!parse_uint(val, 1000000000ULL, &u))
                return cli_error("Could not parse '%s' as shard index", val);
            S.shard_index = u;
        } else if (strcmp(opt, "--allow-running-no-tests") == 0) {
            NO_VALUE();
            S.allow_no_tests = 1;
        } else if (strcmp(opt, "--colour-mode") == 0) {
            NEED_VALUE();
            if (strcmp(val, "ansi") && strcmp(val, "none") && strcmp(val, "default") &&
                strcmp(val, "win32"))
                return cli_error("colour mode must be one of: default, ansi, win32, or none. "
                                 "'%s' is not recognised",
                                 val);
        } else {
            return cli_error("Unrecognised token: %s", a);
        }
#undef IS
#undef NEED_VALUE
#undef NO_VALUE
    }
    if (S.shard_index >= S.shard_count)
        return cli_error("The shard count (%llu) must be greater than the shard index (%llu)",
                         S.shard_count, S.shard_index);
    return 1;
}

/* ---------------------------------------------------------------- ordering */

static uint64_t splitmix64(uint64_t *x) {
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static int cmp_lex(const void *pa, const void *pb) {
    const ct_case *a = *(ct_case *const *)pa, *b = *(ct_case *const *)pb;
    return strcmp(a->name, b->name);
}

static ct_case **ordered_cases(size_t *n) {
    ct_case **v = (ct_case **)xmalloc(S.ncases * sizeof *v);
    size_t k = 0;
    for (ct_case *c = S.first; c; c = c->next) v[k++] = c;
    /* Constructors run in declaration order within a file; sort a file's
     * cases by line anyway so "decl" does not hinge on the toolchain. */
    for (size_t i = 1; i < k; i++) {
        ct_case *x = v[i];
        size_t j = i;
        while (j > 0 && strcmp(v[j - 1]->file, x->file) == 0 && v[j - 1]->line > x->line) {
            v[j] = v[j - 1];
            j--;
        }
        v[j] = x;
    }
    if (S.order == ORDER_LEX) qsort(v, k, sizeof *v, cmp_lex);
    if (S.order == ORDER_RAND && k > 1) {
        qsort(v, k, sizeof *v, cmp_lex); /* independent of link order */
        uint64_t st = S.seed;
        for (size_t i = k - 1; i > 0; i--) {
            size_t j = (size_t)(splitmix64(&st) % (uint64_t)(i + 1));
            ct_case *tmp = v[i];
            v[i] = v[j];
            v[j] = tmp;
        }
    }
    *n = k;
    return v;
}

/* ---------------------------------------------------------------- listing */

static void list_tests(FILE *fp, ct_case **v, size_t n, int filtered) {
    if (S.verbosity == 0) {
        for (size_t i = 0; i < n; i++) fprintf(fp, "%s\n", v[i]->name);
        return;
    }
    fputs(filtered ? "Matching test cases:\n" : "All available test cases:\n", fp);
    for (size_t i = 0; i < n; i++) {
        fprintf(fp, "  %s\n", v[i]->name);
        if (S.verbosity >= 2) fprintf(fp, "    %s:%d\n", v[i]->file, v[i]->line);
        if (v[i]->tags && v[i]->tags[0]) {
            taglist t;
            taglist_parse(&t, v[i]->tags);
            fputs("      ", fp);
            for (size_t j = 0; j < t.n; j++) fprintf(fp, "[%s]", t.v[j]);
            fputc('\n', fp);
            taglist_free(&t);
        }
    }
    fprintf(fp, "%zu %s%s\n\n", n, filtered ? "matching test case" : "test case",
            n == 1 ? "" : "s");
}

static int cmp_str(const void *a, const void *b) {
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void list_tags(FILE *fp, ct_case **v, size_t n, int filtered) {
    char **all = NULL;
    size_t na = 0;
    for (size_t i = 0; i < n; i++) {
        taglist t;
        taglist_parse(&t, v[i]->tags);
        for (size_t j = 0; j < t.n; j++) {
            all = (char **)xrealloc(all, (na + 1) * sizeof *all);
            all[na++] = t.v[j];
        }
        free(t.v);
    }
    qsort(all, na, sizeof *all, cmp_str);
    fputs(filtered ? "Tags for matching test cases:\n" : "All available tags:\n", fp);
    size_t distinct = 0;
    for (size_t i = 0; i < na;) {
        size_t j = i;
        while (j < na && strcmp(all[j], all[i]) == 0) j++;
        fprintf(fp, "  %2zu  [%s]\n", j - i, all[i]);
        distinct++;
        i = j;
    }
    fprintf(fp, "%zu tag%s\n\n", distinct, distinct == 1 ? "" : "s");
    for (size_t i = 0; i < na; i++) free(all[i]);
    free(all);
}

/* ---------------------------------------------------------------- main */

static void cleanup(void) {
    for (size_t i = 0; i < S.nreps; i++) {
        if (S.reps[i].own_fp) fclose(S.reps[i].fp);
        free(S.reps[i].out);
    }
    free(S.reps);
    S.reps = NULL;
    S.nreps = 0;
    for (size_t i = 0; i < S.nsections; i++) free(S.sections[i]);
    free(S.sections);
    S.sections = NULL;
    S.nsections = 0;
    free(S.default_out);
    S.default_out = NULL;
    free(S.run_name);
    S.run_name = NULL;
    infos_trim(-1);
    free(S.infos);
    S.infos = NULL;
    S.capinfos = 0;
}

static int open_reporters(void) {
    if (S.nreps == 0) add_reporter("console");
    int default_used = 0;
    for (size_t i = 0; i < S.nreps; i++) {
        reporter *r = &S.reps[i];
        const char *path = r->out;
        if (!path) {
            if (default_used) {
                cli_error("Only one reporter may have unspecified output file.");
                return 0;
            }
            default_used = 1;
            path = S.default_out;
        }
        if (!path || strcmp(path, "-") == 0 || strcmp(path, "%stdout") == 0) {
            r->fp = stdout;
        } else if (strcmp(path, "%stderr") == 0) {
            r->fp = stderr;
        } else {
            r->fp = fopen(path, "w");
            if (!r->fp) {
                fprintf(stderr, "Unable to open file: '%s'\n", path);
                return 0;
            }
            r->own_fp = 1;
        }
        if (r->kind == R_CONSOLE)
            S.con = r->fp;
        else if (S.success)
            S.store_passes = 1;
    }
    return 1;
}

int main(int argc, char **argv) {
    const char **specs = (const char **)xmalloc((size_t)(argc + 1) * sizeof *specs);
    int nspecs = 0;
    const char *slash = argc > 0 ? strrchr(argv[0], '/') : NULL;
    S.exe = argc > 0 ? (slash ? slash + 1 : argv[0]) : "test";
    S.run_name = xstrdup(S.exe);
    S.verbosity = 1;
    S.shard_count = 1;
    {
        /* Catch2 3 seeds from a random device by default. */
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        uint64_t x = (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 20) ^ (uint64_t)getpid();
        S.seed = (uint32_t)splitmix64(&x);
    }
    int rc = EXIT_OK;
    spec sp;
    memset(&sp, 0, sizeof sp);
    ct_case **cases = NULL;
    caserec *recs = NULL;
    size_t nrecs = 0;

    if (!parse_args(argc, argv, specs, &nspecs)) {
        rc = EXIT_ERROR;
        goto done;
    }
    if (S.help) {
        printf(HELP, S.exe);
        goto done;
    }
    if (S.list_reporters) {
        printf("Available reporters:\n"
               "  console:  Reports test results as plain lines of text\n"
               "  junit:    Reports test results in an XML format that looks like Ant's\n"
               "            junitreport target\n"
               "  xml:      Reports test results as an XML document\n\n");
        goto done;
    }
    /* Catch2 refuses duplicate test names at start-up. */
    for (ct_case *a = S.first; a; a = a->next)
        for (ct_case *b = a->next; b; b = b->next)
            if (strcmp(a->name, b->name) == 0) {
                fprintf(stderr,
                        "error: TEST_CASE( \"%s\" ) already defined.\n"
                        "\tFirst seen at %s:%d\n\tRedefined at %s:%d\n",
                        a->name, a->file, a->line, b->file, b->line);
                rc = EXIT_ERROR;
                goto done;
            }
    if (!open_reporters()) {
        rc = EXIT_ERROR;
        goto done;
    }
    {
        FILE *msg = S.con ? S.con : stdout;
        int invalid = 0;
        for (int i = 0; i < nspecs; i++) {
            if (!spec_parse(&sp, specs[i])) {
                fprintf(msg, "Invalid Filter: %s\n", specs[i]);
                invalid = 1;
            }
        }
        spec_finish(&sp);
        if (invalid) {
            rc = EXIT_INVALID_SPEC;
            goto done;
        }
    }
    size_t ncases;
    cases = ordered_cases(&ncases);
    /* Selection: hidden cases only when a filter names them. */
    size_t nsel = 0;
    for (size_t i = 0; i < ncases; i++) {
        int keep = 0;
        if (sp.n == 0) {
            keep = !ct_tags_hidden(cases[i]->tags);
        } else {
            taglist t;
            taglist_parse(&t, cases[i]->tags);
            for (size_t f = 0; f < sp.n; f++)
                if (filter_matches(&sp.v[f], cases[i]->name, &t)) {
                    sp.v[f].matched++;
                    keep = 1;
                }
            taglist_free(&t);
        }
        if (keep) cases[nsel++] = cases[i];
    }
    if (S.list_tests || S.list_tags) {
        FILE *fp = S.con ? S.con : stdout;
        if (S.list_tests) list_tests(fp, cases, nsel, sp.n > 0);
        if (S.list_tags) list_tags(fp, cases, nsel, sp.n > 0);
        goto done;
    }
    {
        /* createShard (catch_test_case_registry_impl.cpp) */
        size_t size = nsel / (size_t)S.shard_count, left = nsel % (size_t)S.shard_count;
        size_t idx = (size_t)S.shard_index;
        size_t start = idx * size + (idx < left ? idx : left);
        size_t end = start + size + (idx < left ? 1 : 0);
        if (start > 0) memmove(cases, cases + start, (end - start) * sizeof *cases);
        nsel = end - start;
    }
    if (S.con) {
        if (nspecs > 0) {
            fputs("Filters:", S.con);
            for (int i = 0; i < nspecs; i++) fprintf(S.con, " %s", specs[i]);
            fputc('\n', S.con);
        }
        fprintf(S.con, "Randomness seeded to: %lu\n", (unsigned long)S.seed);
        fflush(S.con);
    }
    install_fatal_handlers();
    recs = (caserec *)xmalloc((nsel ? nsel : 1) * sizeof *recs);
    memset(recs, 0, (nsel ? nsel : 1) * sizeof *recs);
    double t0 = now_seconds();
    for (size_t i = 0; i < nsel && !S.aborting; i++) {
        recs[i].tc = cases[i];
        nrecs = i + 1;
        run_case(&recs[i]);
    }
    double total_secs = now_seconds() - t0;
    int unmatched = 0;
    for (size_t f = 0; f < sp.n; f++)
        if (sp.v[f].matched == 0) {
            unmatched = 1;
            if (S.con) {
                char *d = filter_describe(&sp.v[f]);
                fprintf(S.con, "No test cases matched '%s'\n", d);
                free(d);
            }
        }
    for (size_t i = 0; i < S.nreps; i++) {
        reporter *r = &S.reps[i];
        if (r->kind == R_CONSOLE)
            console_totals(r->fp);
        else if (r->kind == R_JUNIT)
            junit_write(r->fp, recs, nrecs, total_secs);
        else
            xml_write(r->fp, recs, nrecs);
    }
    long ncase_total = S.cases_pass + S.cases_fail + S.cases_skip;
    if (unmatched && S.warn_unmatched)
        rc = EXIT_UNMATCHED;
    else if (ncase_total == 0 && !S.allow_no_tests)
        rc = EXIT_NO_TESTS;
    else if (ncase_total > 0 && ncase_total == S.cases_skip && !S.allow_no_tests)
        rc = EXIT_ALL_SKIPPED;
    else if (S.total_fail)
        rc = EXIT_FAILED;
done:
    fflush(stdout);
    for (size_t i = 0; i < nrecs; i++) run_free(recs[i].runs);
    free(recs);
    free(cases);
    spec_free(&sp);
    cleanup();
    free(specs);
    return rc;
}

/* ================================================================ helpers */

const char *ct_data_dir(void) {
    if (!S.data_dir_done) {
        S.data_dir_done = 1;
        S.data_dir[0] = '\0';
        struct stat st;
        const char *env = getenv("CONICA_SHARED_DATA");
        const char *cand[2] = {env, "../shared/data"};
        for (int i = 0; i < 2; i++) {
            if (!cand[i] || !cand[i][0]) continue;
            if (stat(cand[i], &st) == 0 && S_ISDIR(st.st_mode) &&
                strlen(cand[i]) < sizeof S.data_dir) {
                strcpy(S.data_dir, cand[i]);
                break;
            }
        }
    }
    return S.data_dir[0] ? S.data_dir : NULL;
}

const char *ct_data_dir_or_skip(void) {
    const char *d = ct_data_dir();
    if (!d)
        ct_skip(__FILE__, __LINE__,
                "shared test data not found: set CONICA_SHARED_DATA or run from the repository "
                "root with ../shared/data present");
    return d;
}

int ct_data_path(char *out, size_t cap, const char *rel) {
    const char *d = ct_data_dir();
    if (!d || cap == 0) return 0;
    int n = snprintf(out, cap, "%s/%s", d, rel);
    return n >= 0 && (size_t)n < cap;
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void ct_rng_init(ct_rng *r, uint64_t seed) {
    uint64_t x = seed;
    for (int i = 0; i < 4; i++) r->s[i] = splitmix64(&x);
}

uint64_t ct_rng_next(ct_rng *r) {
    uint64_t *s = r->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double ct_rng_uniform(ct_rng *r) { return (double)(ct_rng_next(r) >> 11) * 0x1.0p-53; }

double ct_rng_range(ct_rng *r, double lo, double hi) {
    return lo + (hi - lo) * ct_rng_uniform(r);
}

uint64_t ct_rng_below(ct_rng *r, uint64_t n) {
    if (n == 0) return 0;
    uint64_t limit = UINT64_MAX - UINT64_MAX % n; /* reject the biased tail */
    uint64_t x;
    do x = ct_rng_next(r);
    while (x >= limit);
    return x % n;
}

double ct_rng_normal(ct_rng *r) {
    double u1 = 1.0 - ct_rng_uniform(r); /* (0, 1] so log is finite */
    double u2 = ct_rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}
