/* SPDX-License-Identifier: MIT */
/*
 * The runner's own unit tests: Catch2's test-spec grammar and hidden tests
 * (catch_test_spec_parser.cpp / catch_test_spec.cpp), section discovery
 * (catch_test_case_tracker.cpp) and the helpers. The end-to-end behaviour
 * (output, exit codes, reporters) is checked by tests/cli/runner.sh.
 */
#include "conica_test.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ------------------------------------------------------------ test specs */

typedef struct spec_case {
    const char *spec, *name, *tags;
    int expect;
} spec_case;

static void check_specs(const spec_case *v, size_t n) {
    for (size_t i = 0; i < n; i++) {
        INFO("spec '%s' against name '%s' tags '%s'", v[i].spec, v[i].name, v[i].tags);
        CHECK_EQ(ct_spec_matches(v[i].spec, v[i].name, v[i].tags), v[i].expect);
    }
}

TEST_CASE("spec: names and wildcards", "[runner][spec]") {
    static const spec_case v[] = {
        {"circle", "circle", "", 1},
        {"circle", "circles", "", 0},
        {"CIRCLE", "Circle", "", 1},            /* case-insensitive */
        {"circ*", "circle arc", "", 1},
        {"*arc", "circle arc", "", 1},
        {"*le a*", "circle arc", "", 1},
        {"*le a*", "ellipse", "", 0},
        {"*", "anything", "", 1},
        {"circle arc", "circle arc", "", 1},      /* spaces belong to the name */
        {"\"circle arc\"", "circle arc", "", 1},  /* quoted */
        {"  circle  ", "circle", "", 1},          /* trimmed */
        {"a\\,b", "a,b", "", 1},                  /* escaped comma */
        {"", "visible", "[x]", 1},                /* no filter: every visible test */
    };
    check_specs(v, sizeof v / sizeof v[0]);
}

TEST_CASE("spec: tags, AND, OR and negation", "[runner][spec]") {
    static const spec_case v[] = {
        {"[fast]", "t", "[fast][conic]", 1},
        {"[FAST]", "t", "[fast]", 1},
        {"[slow]", "t", "[fast]", 0},
        {"[fast][conic]", "t", "[fast][conic]", 1},   /* together = AND */
        {"[fast][conic]", "t", "[fast]", 0},
        {"[fast],[conic]", "t", "[conic]", 1},        /* comma = OR */
        {"[fast],[conic]", "t", "[spline]", 0},
        {"~[slow]", "t", "[fast]", 1},
        {"~[slow]", "t", "[slow]", 0},
        {"~circle", "circle", "", 0},
        {"~circle", "ellipse", "", 1},
        {"exclude:circle", "circle", "", 0},
        {"[fast]~[conic]", "t", "[fast][conic]", 0},
        {"[fast]~[conic]", "t", "[fast]", 1},
        {"c*[fast]", "circle", "[fast]", 1},           /* name and tag AND */
        {"c*[fast]", "ellipse", "[fast]", 0},
        {"ellipse,[fast]", "circle", "[fast]", 1},
    };
    check_specs(v, sizeof v / sizeof v[0]);
}

TEST_CASE("spec: hidden tests run only when selected", "[runner][spec]") {
    static const spec_case v[] = {
        {"", "h", "[.]", 0},
        {"", "h", "[.fail]", 0},
        {"", "h", "[!hide]", 0},
        {"*", "h", "[.fail]", 1},          /* a name pattern selects it */
        {"h", "h", "[.fail]", 1},
        {"[fail]", "h", "[.fail]", 1},     /* its tag selects it */
        {"[.fail]", "h", "[.fail]", 1},
        {"[.]", "h", "[.][x]", 1},
        {"[.fail]", "v", "[fail]", 0},     /* [.fail] also requires hidden */
        {"~[slow]", "h", "[.fail]", 0},    /* negation alone does not select */
        {"[x]~[slow]", "h", "[.][x]", 1},
    };
    check_specs(v, sizeof v / sizeof v[0]);
    CHECK(ct_tags_hidden("[a][.b]"));
    CHECK_FALSE(ct_tags_hidden("[a][b]"));
}

TEST_CASE("spec: invalid specs and several arguments", "[runner][spec]") {
    CHECK_EQ(ct_spec_matches("[a,b]", "t", "[a]"), -1);     /* comma inside a tag */
    CHECK_EQ(ct_spec_matches("\"a,b\"", "a,b", ""), -1);    /* comma inside quotes */
    const char *and_args[] = {"[a]", "[b]"};
    CHECK_EQ(ct_spec_matches_argv(2, and_args, "t", "[a][b]"), 1); /* arguments AND */
    CHECK_EQ(ct_spec_matches_argv(2, and_args, "t", "[a]"), 0);
    const char *or_args[] = {"[a],", "[b]"};
    CHECK_EQ(ct_spec_matches_argv(2, or_args, "t", "[b]"), 1);
    const char *bad[] = {"[a]", "[x,y]"};
    CHECK_EQ(ct_spec_matches_argv(2, bad, "t", "[a]"), -1);
}

/* ------------------------------------------------------------ sections */

typedef struct sim {
    ct_tracker *t;
    char log[512];
    int failing; /* which leaf "fails" (ends the run early), by letter */
} sim;

static void logs(sim *s, const char *text) {
    size_t n = strlen(s->log);
    snprintf(s->log + n, sizeof s->log - n, "%s", text);
}

/* Runs `body` until the tracker says the case is complete (at most 50
 * runs); each run starts with '|' in the log. Returns the number of runs. */
static int drive(sim *s, int (*body)(sim *)) {
    int runs = 0, done = 0;
    s->log[0] = '\0';
    while (!done && runs < 50) {
        logs(s, "|");
        ct_tracker_start_run(s->t);
        if (body(s)) ct_tracker_fail(s->t);
        done = ct_tracker_end_run(s->t);
        runs++;
    }
    return runs;
}

/* SECTION A { SECTION 1 {}  SECTION 2 {} }  SECTION B {} ; returns 1 when a
 * leaf named in s->failing "fails" like a REQUIRE (the run ends there). */
static int body_tree(sim *s) {
    if (s->failing == 'R') return 1; /* a REQUIRE before any section */
    if (ct_tracker_enter(s->t, "A")) {
        logs(s, "A");
        if (ct_tracker_enter(s->t, "1")) {
            logs(s, "1");
            if (s->failing == '1') return 1;
            ct_tracker_leave(s->t);
        }
        if (ct_tracker_enter(s->t, "2")) {
            logs(s, "2");
            ct_tracker_leave(s->t);
        }
        ct_tracker_leave(s->t);
    }
    if (ct_tracker_enter(s->t, "B")) {
        logs(s, "B");
        ct_tracker_leave(s->t);
    }
    if (s->failing == 'r') return 1; /* a REQUIRE outside any section */
    return 0;
}

TEST_CASE("sections: one run per leaf, in declaration order", "[runner][sections]") {
    sim s = {ct_tracker_new(), "", 0};
    int runs = drive(&s, body_tree);
    CHECK_EQ(runs, 3);
    CHECK_STR_EQ(s.log, "|A1|A2|B");
    ct_tracker_free(s.t);
}

TEST_CASE("sections: a failed leaf does not stop its siblings", "[runner][sections]") {
    sim s = {ct_tracker_new(), "", '1'};
    int runs = drive(&s, body_tree);
    CHECK_EQ(runs, 3);
    CHECK_STR_EQ(s.log, "|A1|A2|B");
    ct_tracker_free(s.t);
}

TEST_CASE("sections: a failure outside sections", "[runner][sections]") {
    /* Before any section: nothing is left to discover, one run. */
    sim s = {ct_tracker_new(), "", 'R'};
    CHECK_EQ(drive(&s, body_tree), 1);
    CHECK_STR_EQ(s.log, "|");
    ct_tracker_free(s.t);
    /* After the sections: like Catch2, the other leaves still run (and the
     * failure repeats in each run). */
    s.t = ct_tracker_new();
    s.failing = 'r';
    CHECK_EQ(drive(&s, body_tree), 3);
    CHECK_STR_EQ(s.log, "|A1|A2|B");
    ct_tracker_free(s.t);
}

TEST_CASE("sections: -c filters select one path", "[runner][sections]") {
    sim s = {ct_tracker_new(), "", 0};
    ct_tracker_add_filter(s.t, "B");
    CHECK_EQ(drive(&s, body_tree), 1);
    CHECK_STR_EQ(s.log, "|B");
    ct_tracker_free(s.t);

    s.t = ct_tracker_new();
    ct_tracker_add_filter(s.t, "A");
    ct_tracker_add_filter(s.t, "2");
    CHECK_EQ(drive(&s, body_tree), 1);
    CHECK_STR_EQ(s.log, "|A2");
    ct_tracker_free(s.t);

    s.t = ct_tracker_new();
    ct_tracker_add_filter(s.t, "A"); /* everything below A runs */
    CHECK_EQ(drive(&s, body_tree), 2);
    CHECK_STR_EQ(s.log, "|A1|A2");
    ct_tracker_free(s.t);
}

static int body_loop(sim *s) {
    /* The same section reached three times in one run is entered once. */
    for (int i = 0; i < 3; i++)
        if (ct_tracker_enter(s->t, "L")) {
            logs(s, "L");
            ct_tracker_leave(s->t);
        }
    return 0;
}

static int body_deep(sim *s) {
    /* three levels, two leaves at the bottom, one leaf at level two */
    if (ct_tracker_enter(s->t, "a")) {
        if (ct_tracker_enter(s->t, "b")) {
            if (ct_tracker_enter(s->t, "c")) {
                logs(s, "abc");
                ct_tracker_leave(s->t);
            }
            if (ct_tracker_enter(s->t, "d")) {
                logs(s, "abd");
                ct_tracker_leave(s->t);
            }
            ct_tracker_leave(s->t);
        }
        if (ct_tracker_enter(s->t, "e")) {
            logs(s, "ae");
            ct_tracker_leave(s->t);
        }
        ct_tracker_leave(s->t);
    }
    return 0;
}

TEST_CASE("sections: loops and deeper nesting", "[runner][sections]") {
    sim s = {ct_tracker_new(), "", 0};
    CHECK_EQ(drive(&s, body_loop), 1);
    CHECK_STR_EQ(s.log, "|L");
    ct_tracker_free(s.t);

    s.t = ct_tracker_new();
    CHECK_EQ(drive(&s, body_deep), 3);
    CHECK_STR_EQ(s.log, "|abc|abd|ae");
    ct_tracker_free(s.t);
}

/* The real SECTION macros: the body runs once per leaf. */
static int g_runs, g_leaf_a, g_leaf_b, g_shared;

TEST_CASE("sections: SECTION macros re-run the body", "[runner][sections]") {
    g_runs++;
    int local = 10;
    SECTION("first") {
        local += 1;
        g_leaf_a++;
        CHECK_EQ(local, 11);
    }
    SECTION("second") {
        g_leaf_b++;
        CHECK_EQ(local, 10); /* the body restarted: "first" did not run */
    }
    g_shared++;
    /* On the last run both leaves have been visited exactly once. */
    if (g_leaf_b == 1) {
        CHECK_EQ(g_runs, 2);
        CHECK_EQ(g_leaf_a, 1);
        CHECK_EQ(g_shared, 2);
    }
}

/* ------------------------------------------------------------ helpers */

TEST_CASE("rng: deterministic and in range", "[runner][rng]") {
    ct_rng a, b;
    ct_rng_init(&a, 12345);
    ct_rng_init(&b, 12345);
    for (int i = 0; i < 100; i++) REQUIRE(ct_rng_next(&a) == ct_rng_next(&b));
    ct_rng_init(&b, 12346);
    CHECK(ct_rng_next(&a) != ct_rng_next(&b));

    ct_rng_init(&a, 7);
    double sum = 0, lo = 1, hi = 0;
    int counts[6] = {0};
    for (int i = 0; i < 60000; i++) {
        double u = ct_rng_uniform(&a);
        sum += u;
        lo = u < lo ? u : lo;
        hi = u > hi ? u : hi;
        counts[ct_rng_below(&a, 6)]++;
    }
    CHECK_GE(lo, 0.0);
    CHECK_LT(hi, 1.0);
    CHECK_NEAR(sum / 60000.0, 0.5, 0.01);
    for (int k = 0; k < 6; k++) {
        INFO("bucket %d", k);
        CHECK_NEAR(counts[k], 10000, 400);
    }
    double r = ct_rng_range(&a, -2.0, -1.0);
    CHECK_GE(r, -2.0);
    CHECK_LT(r, -1.0);
    CHECK_EQ_U(ct_rng_below(&a, 0), 0);

    double m = 0, v = 0;
    for (int i = 0; i < 20000; i++) {
        double z = ct_rng_normal(&a);
        m += z;
        v += z * z;
    }
    CHECK_NEAR(m / 20000.0, 0.0, 0.05);
    CHECK_NEAR(v / 20000.0, 1.0, 0.05);
}

TEST_CASE("rng: xoshiro256** reference values", "[runner][rng]") {
    /* xoshiro256** with state {1, 2, 3, 4}: the first outputs from the
     * reference implementation (prng.di.unimi.it). */
    ct_rng r = {{1, 2, 3, 4}};
    CHECK_EQ_U(ct_rng_next(&r), 11520ULL);
    CHECK_EQ_U(ct_rng_next(&r), 0ULL);
    CHECK_EQ_U(ct_rng_next(&r), 1509978240ULL);
    CHECK_EQ_U(ct_rng_next(&r), 1215971899390074240ULL);
}

TEST_CASE("data dir: found or reported absent", "[runner][data]") {
    const char *d = ct_data_dir();
    char path[64];
    if (!d) {
        CHECK_FALSE(ct_data_path(path, sizeof path, "x"));
        SKIP("shared test data not found (../shared/data or $CONICA_SHARED_DATA)");
    }
    char buf[4200];
    REQUIRE(ct_data_path(buf, sizeof buf, "README.md"));
    CHECK(strncmp(buf, d, strlen(d)) == 0);
    CHECK_STR_EQ(buf + strlen(d), "/README.md");
    CHECK_FALSE(ct_data_path(path, 2, "README.md")); /* does not fit */
}

TEST_CASE("current case name is known", "[runner]") {
    CHECK_STR_EQ(ct_current_case(), "current case name is known");
}
