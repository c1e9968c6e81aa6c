// SPDX-License-Identifier: MIT
// conica_test.h from C++17: the CGAL tests include it this way. Every case
// here passes; tests/cli/runner.sh runs the binary and checks its summary.
#include "conica_test.h"

#include <string>
#include <vector>

TEST_CASE("C++: assertions on standard types", "[cxx]") {
    std::vector<int> v{1, 2, 3};
    REQUIRE(v.size() == 3u);
    CHECK_EQ(v.size(), 3);
    CHECK(std::vector<int>{1, 2}.size() == 2u);
    CHECK_FALSE(v.empty());
    std::string s = "conic";
    CHECK_STR_EQ(s.c_str(), "conic");
    CHECK_NEAR(0.1 + 0.2, 0.3, 1e-15);
    CHECK_REL(1e300 * 1.0000000000000002, 1e300, 1e-15);
    CHECK_LE(1.0, 2.0);
}

TEST_CASE("C++: sections and context", "[cxx]") {
    static int runs = 0;
    ++runs;
    int depth = 0;
    SECTION("a") {
        depth = 1;
        SECTION("a1") { CHECK_EQ(depth, 1); }
        SECTION("a2") { DYNAMIC_SECTION("a2-%d", 7) { CHECK_EQ(depth, 1); } }
    }
    SECTION("b") {
        INFO("runs so far: %d", runs);
        CAPTURE_I(depth);
        CHECK_EQ(depth, 0);
    }
    CHECK_LE(runs, 3);
}

TEST_CASE("C++: helpers", "[cxx]") {
    ct_rng r;
    ct_rng_init(&r, 42);
    double u = ct_rng_uniform(&r);
    CHECK_GE(u, 0.0);
    CHECK_LT(u, 1.0);
    CHECK(ct_spec_matches("[cxx]", "x", "[cxx]") == 1);
}
