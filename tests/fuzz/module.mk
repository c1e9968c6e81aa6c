# SPDX-License-Identifier: MIT
# tests/fuzz: libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined).
#
#   make fuzz FUZZ_SECONDS=N   build every fuzzer, run each N seconds (default 60)
#   make fuzz-build            build them only ($(BUILD)/fuzz/bin/fuzz_*)
#   make memcheck              valgrind memcheck over the CLI tools and suites
#
# The libraries are rebuilt by a recursive make in $(BUILD)/fuzz with clang
# and SAN="-fsanitize=fuzzer-no-link,address,undefined" (SAN reaches CFLAGS
# and LDFLAGS); only the final link of a target adds the fuzzer's main.
FUZZ_NAMES   := curve_parse spline_parse svg_path svgsmooth svg_render scadprofile subdivide plot dxf
FUZZ_CC      ?= clang
# scadprofile's regions are C++ (openscad_export/scad_clip.cpp): the same
# compiler family builds them, so the sanitizer flags mean the same.
FUZZ_CXX     ?= clang++
FUZZ_SAN     := -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined \
                -fno-omit-frame-pointer
FUZZ_SECONDS ?= 60

# Inside the recursive make (BUILD=.../fuzz): the rules for the targets.
$(BUILD)/obj/tests/fuzz/%.o: CPPFLAGS += -Itests/fuzz -Isvg_tools -Iopenscad_export $(XML_CFLAGS)
# (ALL_LIBS is defined after the fragments are read: name the libraries.)
$(BUILD)/bin/fuzz_%: $(BUILD)/obj/tests/fuzz/fuzz_%.o $(MODULE_LIBS_FIRST) $(MODULE_LIBS) $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -fsanitize=fuzzer -o $@ $< $(ALL_LIBS) $(CLIP_LIBS) $(ALL_LDLIBS)

# From the normal build: recurse once.
ifeq ($(filter %/fuzz,$(BUILD)),)
FUZZ_BINS := $(FUZZ_NAMES:%=$(BUILD)/fuzz/bin/fuzz_%)

fuzz-build:
	$(MAKE) --no-print-directory BUILD=$(BUILD)/fuzz CC=$(FUZZ_CC) CXX=$(FUZZ_CXX) OPT=-O1 \
	  SAN="$(FUZZ_SAN)" $(FUZZ_BINS)

fuzz: fuzz-build
	sh tests/fuzz/run.sh $(BUILD)/fuzz $(FUZZ_SECONDS) $(FUZZ_NAMES)

# valgrind over a fixed list of tool runs, then CLI suites with every tool
# run under valgrind (MEMCHECK_SUITES="limits plot" for a subset, "none" for
# the fixed list only; the default list is in scripts/memcheck.sh)
memcheck: all
	sh scripts/memcheck.sh $(BUILD) $(MEMCHECK_SUITES)

TEST_EXTRA += fuzz-build
.PHONY: fuzz fuzz-build memcheck
endif

# tests/test_reliability.c (regressions of the fuzz findings) reads SVG too.
$(BUILD)/obj/tests/test_reliability.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)
