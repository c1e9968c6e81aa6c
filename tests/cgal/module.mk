# SPDX-License-Identifier: MIT
# tests/cgal: CGAL checks of convexity preservation and inflection splitting
# (issue 4). One C++17 translation unit: CGAL 5.5 is header-only, needs GMP,
# and takes ~8 s to compile, so it is built once and rebuilt only when its
# dependencies change (-MMD from CPPFLAGS; the .d files are included by the
# top Makefile). The binary is found by scripts/run-tests.sh as tests/cgal_*.
CGAL_TEST     := $(BUILD)/tests/cgal_test
CGAL_TEST_OBJ := $(BUILD)/obj/tests/cgal/test_cgal.o
CGAL_LIBS     := -lgmp

# CGAL's filtered predicates switch the FPU rounding mode for interval
# arithmetic; GCC must not fold across those switches (CGAL's own CMake adds
# this flag for GCC too).
$(CGAL_TEST_OBJ): CXXFLAGS += -frounding-math
# GCC 12 at -O2 reports "may be used uninitialized" inside CGAL's own
# Polygon_2 templates (instantiated in our file, so not silenced as system
# headers): a known false positive; every other warning stays an error.
$(CGAL_TEST_OBJ): CXXFLAGS += -Wno-maybe-uninitialized

$(CGAL_TEST): $(CGAL_TEST_OBJ) $(RUNNER_A) $(BUILD)/lib/libconica_testsupport.a $$(ALL_LIBS)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) -o $@ $(CGAL_TEST_OBJ) $(RUNNER_A) $(BUILD)/lib/libconica_testsupport.a $(ALL_LIBS) $(ALL_LDLIBS) $(CGAL_LIBS)

TEST_BINS += $(CGAL_TEST)
