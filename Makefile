# SPDX-License-Identifier: MIT
# Conica — plain GNU make. All outputs go under $(BUILD).
#   make            libraries and command-line tools
#   make test       every suite (installs missing Debian packages first)
#   make demo       the main job on bundled example data
#   make bench      benchmark tables
#   make install    PREFIX=/usr/local DESTDIR= (also BINDIR, LIBDIR, INCLUDEDIR,
#                   DATADIR, MANDIR); make uninstall removes what it wrote
#   make WERROR=1   warnings are errors (make test and .ci/run set it)
# Works from any directory (make -f /src/Makefile [BUILD=DIR]): the outputs
# go to BUILD, relative to the directory make was called from.
.DEFAULT_GOAL := all
SRCDIR := $(patsubst %/,%,$(dir $(abspath $(firstword $(MAKEFILE_LIST)))))
ifneq ($(CURDIR),$(SRCDIR))
# Called from elsewhere: run again in the source tree with BUILD absolute.
BUILD ?= build
OUTER_GOAL := $(firstword $(MAKECMDGOALS) all)
# goals under BUILD (make -f /src/Makefile BUILD=b b/bin/conica) made absolute too
OUTER_GOALS := $(foreach g,$(MAKECMDGOALS),$(if $(filter $(BUILD)/%,$(g)),$(abspath $(g)),$(g)))
$(OUTER_GOAL):
	@$(MAKE) --no-print-directory -C $(SRCDIR) BUILD=$(abspath $(BUILD)) $(OUTER_GOALS)
$(filter-out $(OUTER_GOAL),$(MAKECMDGOALS)):
	@:
.PHONY: $(OUTER_GOAL) $(MAKECMDGOALS)
else
.SUFFIXES:
.DELETE_ON_ERROR:
# Fragments may list $$(ALL_LIBS) as prerequisites: expanded once every
# fragment has added its library.
.SECONDEXPANSION:

BUILD   ?= build
# GNU installation directories (DESTDIR is prepended to each when installing).
PREFIX      ?= /usr/local
EXEC_PREFIX ?= $(PREFIX)
BINDIR      ?= $(EXEC_PREFIX)/bin
LIBDIR      ?= $(EXEC_PREFIX)/lib
INCLUDEDIR  ?= $(PREFIX)/include
DATAROOTDIR ?= $(PREFIX)/share
DATADIR     ?= $(DATAROOTDIR)
MANDIR      ?= $(DATAROOTDIR)/man
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
# Where bash-completion and zsh look for completions under PREFIX.
BASHCOMPDIR ?= $(DATADIR)/bash-completion/completions
ZSHCOMPDIR  ?= $(DATADIR)/zsh/site-functions
DESTDIR ?=
CC      ?= gcc
CXX     ?= g++
ifeq ($(origin CC),default)
CC := gcc
endif
ifeq ($(origin CXX),default)
CXX := g++
endif
PKG_CONFIG ?= pkg-config

VERSION := 0.1.0

# Hardware FMA where the CPU has it (CONIS §2.3 relies on fma);
# glibc's fma() is exact either way, only slower without it.
ARCH ?= $(shell grep -qw fma /proc/cpuinfo 2>/dev/null && echo -mfma)
OPT  ?= -O2
# -Werror only where asked (WERROR=1: developers, make test, CI), never
# forced on a packager's build.
WERROR ?=
WARN := -std=c11 -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes \
        -Wmissing-prototypes -Wconversion $(if $(filter 1,$(WERROR)),-Werror)
CXXWARN := -std=c++17 -Wall -Wextra -Wshadow $(if $(filter 1,$(WERROR)),-Werror)
SAN  ?=
# CFLAGS, CXXFLAGS and LDFLAGS are the user's (`make CFLAGS=-O3` replaces the
# optimisation and debug flags); the project's own are appended with
# `override`, so no command line can drop the warning set, -fPIC,
# hidden visibility or the sanitizer flags. Extra CPPFLAGS go through the
# environment (`CPPFLAGS=-DX make`): on the command line they would replace
# the include paths.
CFLAGS   ?= $(OPT) -g $(ARCH)
# No silent contraction of a*b+c into fma: gcc in C11 mode does not
# contract, clang does, so the release (gcc) and sanitizer/fuzz (clang)
# builds rounded differently and disagreed near the overflow limits (an arc
# of radius 2e161: a warning and exit 0 against the point cap, issue 33).
# Where the numerics want fma they call fma() (Kahan's difference of
# products, CONIS §2.3).
FP_CONTRACT := -ffp-contract=off
override CFLAGS   += $(WARN) $(FP_CONTRACT) -fPIC -fvisibility=hidden $(SAN)
CXXFLAGS ?= $(OPT) -g $(ARCH)
override CXXFLAGS += $(CXXWARN) $(SAN)
CPPFLAGS += -Ilibcore/include -MMD -MP -D_POSIX_C_SOURCE=200809L
override LDFLAGS  += $(SAN)

XML_CFLAGS := $(shell $(PKG_CONFIG) --cflags libxml-2.0 2>/dev/null)
XML_LIBS   := $(shell $(PKG_CONFIG) --libs libxml-2.0 2>/dev/null || echo -lxml2)
LAPACK_LIBS := -llapacke
CORE_LIBS  := $(LAPACK_LIBS) -lm

# ---------------------------------------------------------------- libcore
CORE_SRCS := $(wildcard libcore/src/*.c)
CORE_OBJS := $(CORE_SRCS:%.c=$(BUILD)/obj/%.o)
CORE_A    := $(BUILD)/lib/libconica.a
CORE_SO   := $(BUILD)/lib/libconica.so
CORE_SONAME := libconica.so.0

$(BUILD)/obj/libcore/src/%.o: CPPFLAGS += -Ilibcore/src -DCONICA_BUILDING

# Shared helpers of every command-line tool (not part of the public library).
CLI_SRCS := libcore/tools/cli.c libcore/tools/cli_batch.c libcore/tools/cli_opt.c libcore/tools/cli_progress.c libcore/tools/plotsvg.c
CLI_OBJS := $(CLI_SRCS:%.c=$(BUILD)/obj/%.o)
CLI_A    := $(BUILD)/lib/libconica_cli.a

# The `conica` tool: one cmd_NAME.c per subcommand, found by name.
CMD_SRCS  := $(sort $(wildcard libcore/tools/cmd_*.c))
CMD_NAMES := $(patsubst libcore/tools/cmd_%.c,%,$(CMD_SRCS))
CMD_DEF   := $(BUILD)/gen/commands.def
CMD_LIST  := $(foreach c,$(CMD_NAMES),CONICA_CMD($(c)))
$(shell mkdir -p $(BUILD)/gen && { echo '$(CMD_LIST)' | cmp -s - $(CMD_DEF) || echo '$(CMD_LIST)' > $(CMD_DEF); })
CONICA_OBJS := $(BUILD)/obj/libcore/tools/conica.o $(CMD_SRCS:%.c=$(BUILD)/obj/%.o)
$(BUILD)/obj/libcore/tools/%.o: CPPFLAGS += -Ilibcore/tools -I$(BUILD)/gen

# The Catch2-compatible runner every test binary links (modules use RUNNER_A).
RUNNER_SRCS := $(wildcard tests/runner/*.c)
RUNNER_OBJS := $(RUNNER_SRCS:%.c=$(BUILD)/obj/%.o)
RUNNER_A    := $(BUILD)/lib/libconica_test.a

# Static libraries of the other modules, in link order (modules append).
# ALL_LIBS is complete only after every fragment is read: in a fragment's
# prerequisite list write $$(ALL_LIBS) (second expansion) or name the paths.
MODULE_LIBS :=
MODULE_LIBS_FIRST :=
BINS := $(BUILD)/bin/conica

# ---------------------------------------------------------------- modules
# Each module's make fragment adds its library, tools, tests and benches.
include $(wildcard */module.mk */*/module.mk)

ALL_LIBS = $(MODULE_LIBS_FIRST) $(MODULE_LIBS) $(CLI_A) $(CORE_A)
ALL_LDLIBS = $(XML_LIBS) $(CORE_LIBS)

all: $(CORE_A) $(CORE_SO) $(BINS) $(BUILD)/conica.pc

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(BUILD)/obj/%.o: %.cpp
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

$(CORE_A): $(CORE_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(CORE_SO): $(CORE_OBJS)
	@mkdir -p $(@D)
	$(CC) -shared -Wl,-soname,$(CORE_SONAME) $(LDFLAGS) -o $@.$(VERSION) $^ $(CORE_LIBS)
	ln -sf libconica.so.$(VERSION) $(BUILD)/lib/$(CORE_SONAME)
	ln -sf libconica.so.$(VERSION) $@

$(CLI_A): $(CLI_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/bin/conica: $(CONICA_OBJS) $(ALL_LIBS)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $(CONICA_OBJS) $(ALL_LIBS) $(ALL_LDLIBS)

$(BUILD)/obj/libcore/tools/conica.o: $(CMD_DEF)

# conica.pc is rewritten whenever PREFIX, LIBDIR or INCLUDEDIR changes (and only then).
PC_TEXT := \# SPDX-License-Identifier: MIT\nprefix=$(PREFIX)\nlibdir=$(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))\nincludedir=$(patsubst $(PREFIX)/%,$${prefix}/%,$(INCLUDEDIR))\n\nName: conica\nDescription: Conic-preserving curve subdivision and adaptive spline plotting\nVersion: $(VERSION)\nLibs: -L$${libdir} -lconica\nLibs.private: $(CORE_LIBS)\nCflags: -I$${includedir}\n
$(shell mkdir -p $(BUILD) && { printf '$(PC_TEXT)' | cmp -s - $(BUILD)/conica.pc || printf '$(PC_TEXT)' > $(BUILD)/conica.pc; })

# ---------------------------------------------------------------- tests
$(BUILD)/obj/tests/%.o: CPPFLAGS += -Itests/runner -Ilibcore/src -Ilibcore/tools -Itests/support
$(RUNNER_A): $(RUNNER_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

# Test support every unit test links: glyph outlines of a Debian font through
# FreeType, and a fidelity checker independent of libcore. Without FreeType
# the glyph loaders say so and the tests that need them skip.
FT_FOUND  := $(shell $(PKG_CONFIG) --exists freetype2 2>/dev/null && echo yes)
FT_CFLAGS := $(if $(FT_FOUND),-DTS_HAVE_FREETYPE $(patsubst -I%,-isystem %,$(shell $(PKG_CONFIG) --cflags freetype2)))
FT_LIBS   := $(if $(FT_FOUND),$(shell $(PKG_CONFIG) --libs freetype2))
TS_SRCS := $(wildcard tests/support/*.c)
TS_OBJS := $(TS_SRCS:%.c=$(BUILD)/obj/%.o)
TS_A    := $(BUILD)/lib/libconica_testsupport.a
$(BUILD)/obj/tests/support/%.o: CPPFLAGS += $(FT_CFLAGS)
$(TS_A): $(TS_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

UNIT_SRCS  := $(sort $(wildcard tests/test_*.c))
UNIT_BINS  := $(UNIT_SRCS:tests/%.c=$(BUILD)/tests/%)
$(BUILD)/tests/%: $(BUILD)/obj/tests/%.o $(RUNNER_A) $(TS_A) $(ALL_LIBS)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(RUNNER_A) $(TS_A) $(ALL_LIBS) $(ALL_LDLIBS) $(FT_LIBS)

# Suites that modules add (binaries or scripts the test driver runs).
TEST_BINS += $(UNIT_BINS)
# DEMO_DEPS too: the documentation test remakes docs/ pictures with make demo's scripts.
tests: all $(TEST_BINS) $(TEST_EXTRA) $(DEMO_DEPS)

deps:
	scripts/deps.sh test

NPROC := $(shell nproc 2>/dev/null || echo 2)

test: deps
	@start=$$(date +%s); \
	$(MAKE) --no-print-directory -j$(NPROC) WERROR=1 tests && \
	echo "build: $$(( $$(date +%s) - start )) s" && \
	$(MAKE) --no-print-directory -j$(NPROC) WERROR=1 test-san && \
	echo "sanitizer build: $$(( $$(date +%s) - start )) s since the start" && \
	CONICA_TEST_START=$$start scripts/run-tests.sh $(BUILD)

# The unit and CLI suites again under AddressSanitizer + UBSan (clang);
# modules add the test tools their CLI suites run to SAN_EXTRA.
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
test-san:
	$(MAKE) --no-print-directory BUILD=$(BUILD)/san CC=clang CXX=clang++ OPT=-O1 \
	  SAN="$(SAN_FLAGS)" $(patsubst $(BUILD)/%,$(BUILD)/san/%,$(BINS) $(UNIT_BINS) $(SAN_EXTRA))

# ---------------------------------------------------------------- bench, demo
# cairo's headers first (bench_flatten / bench_arcs compare with cairo;
# CAIRO_FOUND is read when make starts, so the benches build in a second make)
bench:
	scripts/deps.sh bench
	$(MAKE) --no-print-directory bench-run

bench-run: all $(BENCH_BINS)
	scripts/bench.sh $(BUILD) $(BENCH_BINS)

demo:
	scripts/deps.sh demo
	$(MAKE) --no-print-directory all $(DEMO_DEPS)
	scripts/demo.sh $(BUILD)

# The pictures in docs/ remade from make demo (scripts/docs-pictures.sh lists
# them; tests/cli/docs.sh fails when one is not current).
docs-pictures:
	scripts/deps.sh demo
	$(MAKE) --no-print-directory all $(DEMO_DEPS)
	scripts/docs-pictures.sh update $(BUILD)

# ---------------------------------------------------------------- install
# Manual pages of the tools (docs/man/*.1) go to MANDIR/man1; bash and zsh
# completions made from the tools' option tables (scripts/completions.sh)
# to BASHCOMPDIR and ZSHCOMPDIR. INSTALLED lists every file install
# writes (modules add theirs): uninstall removes exactly those.
MAN1 := $(wildcard docs/man/*.1)
HEADERS := $(wildcard libcore/include/conica/*.h)
TOOLS := $(notdir $(BINS))
COMPLETIONS := $(TOOLS:%=$(BUILD)/completions/bash/%) $(TOOLS:%=$(BUILD)/completions/zsh/_%)

$(COMPLETIONS) &: $(BINS) scripts/completions.sh
	sh scripts/completions.sh $(BUILD)/bin $(BUILD)/completions
completions: $(COMPLETIONS)

INSTALLED += $(HEADERS:libcore/include/%=$(INCLUDEDIR)/%) \
    $(LIBDIR)/libconica.a $(LIBDIR)/libconica.so.$(VERSION) $(LIBDIR)/$(CORE_SONAME) \
    $(LIBDIR)/libconica.so $(TOOLS:%=$(BINDIR)/%) $(PKGCONFIGDIR)/conica.pc \
    $(MAN1:docs/man/%=$(MANDIR)/man1/%) $(TOOLS:%=$(BASHCOMPDIR)/%) $(TOOLS:%=$(ZSHCOMPDIR)/_%)
# Directories of our own, removed by uninstall when empty.
INSTALLED_DIRS += $(INCLUDEDIR)/conica

install: $(CORE_A) $(CORE_SO) $(BINS) $(BUILD)/conica.pc $(COMPLETIONS)
	install -d $(DESTDIR)$(PKGCONFIGDIR) $(DESTDIR)$(INCLUDEDIR)/conica $(DESTDIR)$(BINDIR) \
	  $(DESTDIR)$(LIBDIR) $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(BASHCOMPDIR) $(DESTDIR)$(ZSHCOMPDIR)
	install -m 644 $(HEADERS) $(DESTDIR)$(INCLUDEDIR)/conica/
	install -m 644 $(CORE_A) $(DESTDIR)$(LIBDIR)/
	install -m 755 $(CORE_SO).$(VERSION) $(DESTDIR)$(LIBDIR)/
	ln -sf libconica.so.$(VERSION) $(DESTDIR)$(LIBDIR)/$(CORE_SONAME)
	ln -sf libconica.so.$(VERSION) $(DESTDIR)$(LIBDIR)/libconica.so
	install -m 755 $(BINS) $(DESTDIR)$(BINDIR)/
	install -m 644 $(BUILD)/conica.pc $(DESTDIR)$(PKGCONFIGDIR)/
	install -m 644 $(MAN1) $(DESTDIR)$(MANDIR)/man1/
	install -m 644 $(TOOLS:%=$(BUILD)/completions/bash/%) $(DESTDIR)$(BASHCOMPDIR)/
	install -m 644 $(TOOLS:%=$(BUILD)/completions/zsh/_%) $(DESTDIR)$(ZSHCOMPDIR)/

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))
	rmdir $(addprefix $(DESTDIR),$(INSTALLED_DIRS)) 2>/dev/null || true

clean:
	rm -rf $(BUILD)

.PHONY: all tests test test-san deps bench bench-run demo docs-pictures install uninstall completions clean

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
endif
