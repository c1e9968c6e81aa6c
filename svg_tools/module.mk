# SPDX-License-Identifier: MIT
# svg_tools: the SVG layer (libconica_svg.a) and the svgsmooth tool.
SVG_SRCS := $(filter-out svg_tools/svgsmooth.c,$(sort $(wildcard svg_tools/*.c)))
SVG_OBJS := $(SVG_SRCS:%.c=$(BUILD)/obj/%.o)
SVG_A    := $(BUILD)/lib/libconica_svg.a
MODULE_LIBS := $(SVG_A) $(MODULE_LIBS)

# The layer reuses libcore's internal locale-free number reader (numparse.h).
$(BUILD)/obj/svg_tools/%.o: CPPFLAGS += -Isvg_tools -Ilibcore/src -Ilibcore/tools $(XML_CFLAGS)
$(BUILD)/obj/tests/test_svg%.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)

$(SVG_A): $(SVG_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

SVGSMOOTH_OBJS := $(BUILD)/obj/svg_tools/svgsmooth.o
$(BUILD)/bin/svgsmooth: $(SVGSMOOTH_OBJS) $(SVG_A) $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $(SVGSMOOTH_OBJS) $(SVG_A) $(CLI_A) $(CORE_A) $(ALL_LDLIBS)

BINS += $(BUILD)/bin/svgsmooth

# The Inkscape 1.x extension (svg_tools/inkscape/): `make install` puts it
# where an Inkscape installed under the same PREFIX finds system extensions
# (PREFIX/share/inkscape/extensions/conica/); `make inkscape-extension`
# makes a zip to unpack into the user's extension directory
# (~/.config/inkscape/extensions/, Edit > Preferences > System).
INKSCAPE_EXT := svg_tools/inkscape/conica_smooth.inx svg_tools/inkscape/conica_flatten.inx \
                svg_tools/inkscape/conica_smooth.py
INKSCAPE_ZIP := $(BUILD)/conica-inkscape.zip

$(INKSCAPE_ZIP): $(INKSCAPE_EXT)
	@mkdir -p $(BUILD)/inkscape/conica
	cp $(INKSCAPE_EXT) $(BUILD)/inkscape/conica/
	rm -f $@ && cd $(BUILD)/inkscape && python3 -m zipfile -c $(abspath $@) conica

inkscape-extension: $(INKSCAPE_ZIP)
TEST_EXTRA += $(INKSCAPE_ZIP)

install-inkscape: $(INKSCAPE_EXT)
	install -d $(DESTDIR)$(PREFIX)/share/inkscape/extensions/conica
	install -m 644 svg_tools/inkscape/*.inx $(DESTDIR)$(PREFIX)/share/inkscape/extensions/conica/
	install -m 755 svg_tools/inkscape/conica_smooth.py $(DESTDIR)$(PREFIX)/share/inkscape/extensions/conica/

install: install-inkscape
.PHONY: inkscape-extension install-inkscape

# svgscene (tests/tools/svgscene.c): a document's rendered scene as a flat
# SVG, for tests/cli/svg_render.sh's pixel comparisons with rsvg-convert.
SVGSCENE := $(BUILD)/tests/svgscene
$(BUILD)/obj/tests/tools/svgscene.o: CPPFLAGS += -Isvg_tools
$(SVGSCENE): $(BUILD)/obj/tests/tools/svgscene.o $(SVG_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(SVG_A) $(CORE_A) $(ALL_LDLIBS)
TEST_EXTRA += $(SVGSCENE)
SAN_EXTRA += $(SVGSCENE)
