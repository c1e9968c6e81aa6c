/* SPDX-License-Identifier: MIT */
/*
 * A deliberately failing test binary for the runner's own suite
 * (tests/cli/runner.sh). Everything but "visible: one assertion" is hidden
 * behind [.selftest] or [.order], so a plain run passes and the suite picks
 * cases by tag. Lines starting with "marker:" go to stdout so the suite can
 * count how often a body or a section ran.
 */
#include "conica_test.h"

#include <signal.h>
#include <stdio.h>

TEST_CASE("visible: one assertion", "[visible]") { CHECK(1 + 1 == 2); }

TEST_CASE("selftest: passes", "[.selftest][pass]") {
    CHECK(2 > 1);
    CHECK_EQ(6 * 7, 42);
    CHECK_NEAR(0.1 + 0.2, 0.3, 1e-15);
    REQUIRE_STR_EQ("abc", "abc");
}

TEST_CASE("selftest: check continues", "[.selftest][fail][check]") {
    CHECK(1 == 2);
    printf("marker: after-check\n");
    CHECK_EQ(2 + 2, 5);
    CHECK(3 == 3);
}

TEST_CASE("selftest: require stops", "[.selftest][fail][require]") {
    REQUIRE(1 == 2);
    printf("marker: after-require\n");
    CHECK(1 == 1);
}

TEST_CASE("selftest: sections", "[.selftest][sections]") {
    printf("marker: body-run\n");
    SECTION("A") {
        SECTION("A1") { printf("marker: leaf A/A1\n"); CHECK(1); }
        SECTION("A2") { printf("marker: leaf A/A2\n"); CHECK(1); }
    }
    SECTION("B") { printf("marker: leaf B\n"); CHECK(1); }
}

TEST_CASE("selftest: failed section does not stop its siblings", "[.selftest][fail][secfail]") {
    SECTION("X") {
        REQUIRE_EQ(1, 0);
        printf("marker: after-require-in-X\n");
    }
    SECTION("Y") { printf("marker: ran-Y\n"); CHECK(1); }
}

TEST_CASE("selftest: skip", "[.selftest][skip]") {
    SKIP("not today %d", 7);
    printf("marker: after-skip\n");
}

TEST_CASE("selftest: info", "[.selftest][fail][info]") {
    INFO("alpha=%d", 5);
    double x = 0.5;
    CAPTURE_D(x);
    for (int i = 0; i < 3; i++) {
        INFO("pass %d", i);
        CHECK(i < 2);
    }
    CHECK_NEAR(x, 0.25, 1e-3);
}

TEST_CASE("selftest: comparisons", "[.selftest][fail][cmp]") {
    long long big = 123456789012LL;
    CHECK_EQ(big, 7);
    CHECK_REL(1.0, 1.5, 1e-9);
    CHECK_STR_EQ("left", "right");
    CHECK_FALSE(2 > 1);
    CHECK_LT(3, 2);
}

TEST_CASE("selftest: xml <escaping> & \"quotes\"", "[.selftest][fail][xml]") {
    FAIL_CHECK("message with <tag> & \"quote\"");
}

TEST_CASE("selftest: explicit FAIL", "[.selftest][fail][explicit]") {
    FAIL("boom %s", "now");
    printf("marker: after-fail\n");
}

TEST_CASE("selftest: many failures", "[.selftest][fail][abort]") {
    for (int i = 0; i < 5; i++) CHECK_EQ(i, -1);
}

TEST_CASE("order c", "[.order]") { printf("marker: order c\n"); CHECK(1); }
TEST_CASE("order a", "[.order]") { printf("marker: order a\n"); CHECK(1); }
TEST_CASE("order b", "[.order]") { printf("marker: order b\n"); CHECK(1); }

TEST_CASE("selftest: crash", "[.crash]") {
    CHECK(1);
    fflush(stdout);
    raise(SIGSEGV);
}
