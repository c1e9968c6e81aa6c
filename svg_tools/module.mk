# SPDX-License-Identifier: MIT
# svg_tools: the SVG layer (libconica_svg.a) and the svgsmooth tool.
SVG_SRCS := $(filter-out svg_tools/svgsmooth.c,$(sort $(wildcard svg_tools/*.c)))
SVG_OBJS := $(SVG_SRCS:%.c=$(BUILD)/obj/%.o)
SVG_A    := $(BUILD)/lib/libconica_svg.a
MODULE_LIBS := $(SVG_A) $(MODULE_LIBS)

# The layer reuses libcore's internal locale-free number reader (numparse.h).
$(BUILD)/obj/svg_tools/%.o: CPPFLAGS += -Isvg_tools -Ilibcore/src -Ilibcore/tools $(XML_CFLAGS)
$(BUILD)/obj/tests/test_svg%.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)
# test_progress checks the progress reports of every layer, this one's too.
$(BUILD)/obj/tests/test_progress.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)

$(SVG_A): $(SVG_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

SVGSMOOTH_OBJS := $(BUILD)/obj/svg_tools/svgsmooth.o
$(BUILD)/bin/svgsmooth: $(SVGSMOOTH_OBJS) $(SVG_A) $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $(SVGSMOOTH_OBJS) $(SVG_A) $(CLI_A) $(CORE_A) $(ALL_LDLIBS)

BINS += $(BUILD)/bin/svgsmooth

# The Inkscape 1.x extension (svg_tools/inkscape/).
#   make install-inkscape   for the user: INKSCAPE_USER_DIR (the directory
#                           `inkscape --user-data-directory` names, made when
#                           missing: a fresh profile works), no root needed
#   make install            system-wide: INKSCAPE_DIR, for PREFIX /usr or
#                           /usr/local the extensions directory of the
#                           installed Inkscape (its --system-data-directory;
#                           Debian's 1.2 searches /usr/share/inkscape only,
#                           not /usr/local), else DATADIR/inkscape
#   make inkscape-extension a zip to unpack by hand
# Both installs write svgsmooth.path (BINDIR/svgsmooth) beside the script,
# so the extension finds the installed svgsmooth without PATH.
INKSCAPE_EXT := svg_tools/inkscape/conica_smooth.inx svg_tools/inkscape/conica_flatten.inx \
                svg_tools/inkscape/conica_smooth.py
INKSCAPE_ZIP := $(BUILD)/conica-inkscape.zip

$(INKSCAPE_ZIP): $(INKSCAPE_EXT)
	@mkdir -p $(BUILD)/inkscape/conica
	cp $(INKSCAPE_EXT) $(BUILD)/inkscape/conica/
	rm -f $@ && cd $(BUILD)/inkscape && python3 -m zipfile -c $(abspath $@) conica

inkscape-extension: $(INKSCAPE_ZIP)
TEST_EXTRA += $(INKSCAPE_ZIP)

INKSCAPE ?= inkscape
# (a system prefix: Inkscape's own directory; another prefix, such as
# ~/.local, keeps to DATADIR: use install-inkscape for the user there)
INKSCAPE_DIR ?= $(if $(filter /usr /usr/local,$(PREFIX)),$(or $(shell $(INKSCAPE) --system-data-directory 2>/dev/null),$(DATADIR)/inkscape),$(DATADIR)/inkscape)/extensions/conica
INKSCAPE_USER_DIR ?= $(or $(shell $(INKSCAPE) --user-data-directory 2>/dev/null),$(or $(XDG_CONFIG_HOME),$(HOME)/.config)/inkscape)/extensions/conica
INKSCAPE_FILES := $(notdir $(INKSCAPE_EXT)) svgsmooth.path
INSTALLED += $(INKSCAPE_FILES:%=$(INKSCAPE_DIR)/%)
INSTALLED_DIRS += $(INKSCAPE_DIR)

# install-inkscape-to DIR: the extension and svgsmooth.path into DIR (made)
define install-inkscape-to
	install -d $(1)
	install -m 644 svg_tools/inkscape/*.inx $(1)/
	install -m 755 svg_tools/inkscape/conica_smooth.py $(1)/
	printf '%s\n' '$(BINDIR)/svgsmooth' >$(1)/svgsmooth.path
endef

install-inkscape-system: $(INKSCAPE_EXT)
	$(call install-inkscape-to,$(DESTDIR)$(INKSCAPE_DIR))

install-inkscape: $(INKSCAPE_EXT)
	$(call install-inkscape-to,$(INKSCAPE_USER_DIR))
	@echo "Conica's extension is in $(INKSCAPE_USER_DIR): restart Inkscape, then Extensions > Modify Path"

uninstall-inkscape:
	rm -f $(INKSCAPE_FILES:%=$(INKSCAPE_USER_DIR)/%)
	rmdir $(INKSCAPE_USER_DIR) 2>/dev/null || true

install: install-inkscape-system
.PHONY: inkscape-extension install-inkscape install-inkscape-system uninstall-inkscape

# svgcheck (issue 32): svgsmooth's output measured against its input by the
# independent checker of tests/support (no svg_tools or libcore code), for
# tests/cli/svgsmooth_fidelity.sh and scripts/bench-svgsmooth-corpus.sh.
SVGCHECK := $(BUILD)/tests/svgcheck
$(SVGCHECK): $(BUILD)/obj/tests/svgcheck/svgcheck.o $(BUILD)/lib/libconica_testsupport.a
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a -lm
TEST_EXTRA += $(SVGCHECK)

# svgscene (tests/tools/svgscene.c): a document's rendered scene as a flat
# SVG, for tests/cli/svg_render.sh's pixel comparisons with rsvg-convert.
SVGSCENE := $(BUILD)/tests/svgscene
$(BUILD)/obj/tests/tools/svgscene.o: CPPFLAGS += -Isvg_tools
$(SVGSCENE): $(BUILD)/obj/tests/tools/svgscene.o $(SVG_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(SVG_A) $(CORE_A) $(ALL_LDLIBS)
TEST_EXTRA += $(SVGSCENE)
SAN_EXTRA += $(SVGSCENE)

# glyphset (tests/tools/glyphset.c): DejaVu glyphs as SVG files, the glyph
# part of scripts/bench-svgsmooth-corpus.sh's corpus (issue 32).
GLYPHSET := $(BUILD)/tests/glyphset
$(GLYPHSET): $(BUILD)/obj/tests/tools/glyphset.o $(BUILD)/lib/libconica_testsupport.a
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(FT_LIBS) -lm
TEST_EXTRA += $(GLYPHSET)
