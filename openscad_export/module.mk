# SPDX-License-Identifier: MIT
# openscad_export: the .scad writer library (libconica_scad.a) and `scadprofile`.
SCAD_LIB_SRCS := $(filter-out openscad_export/scadprofile.c,$(wildcard openscad_export/*.c))
SCAD_LIB_OBJS := $(SCAD_LIB_SRCS:%.c=$(BUILD)/obj/%.o) $(BUILD)/obj/openscad_export/scad_clip.o
SCAD_A        := $(BUILD)/lib/libconica_scad.a

# Must precede the SVG library in link order (scadprofile uses both).
MODULE_LIBS_FIRST += $(SCAD_A)

$(BUILD)/obj/openscad_export/%.o: CPPFLAGS += -Iopenscad_export -Ilibcore/src -Isvg_tools -Ilibcore/tools $(XML_CFLAGS)
$(BUILD)/obj/tests/test_scad.o: CPPFLAGS += -Iopenscad_export
# Regions (fills, strokes, the check of a fit) use Clipper through the C++
# shim scad_clip.cpp: what links it also links Clipper and the C++ runtime.
CLIP_CFLAGS := $(shell $(PKG_CONFIG) --cflags polyclipping 2>/dev/null || echo -I/usr/include/polyclipping)
CLIP_LIBS   := $(shell $(PKG_CONFIG) --libs polyclipping 2>/dev/null || echo -lpolyclipping) -lstdc++
# Sanitizer builds link with clang (the C driver): it needs telling to take
# the sanitizers' C++ runtime (UBSan's vptr checks in the shim) too.
CLIP_LIBS   += $(if $(SAN),-fsanitize-link-c++-runtime)
$(BUILD)/obj/openscad_export/scad_clip.o: CPPFLAGS += $(CLIP_CFLAGS)
$(BUILD)/tests/test_scad: ALL_LDLIBS += $(CLIP_LIBS)

$(SCAD_A): $(SCAD_LIB_OBJS)
	@mkdir -p $(@D)
	rm -f $@ && ar rcs $@ $^

# scadprofile reads SVG through svg_tools and splines through the plotter:
# it is built once both are in the tree. (svg_tools/module.mk is included
# after this file, so its library is named by path here.)
ifneq ($(and $(wildcard svg_tools/module.mk),$(wildcard libcore/src/plot.c)),)
BINS += $(BUILD)/bin/scadprofile
$(BUILD)/bin/scadprofile: $(BUILD)/obj/openscad_export/scadprofile.o $(SCAD_A) $(BUILD)/lib/libconica_svg.a $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $(BUILD)/obj/openscad_export/scadprofile.o $(ALL_LIBS) $(CLIP_LIBS) $(ALL_LDLIBS)
endif

# glyphsvg (tests/tools/glyphsvg.c): DejaVu glyphs as SVG documents, for
# tests/cli/scadprofile_glyphs.sh's pixel comparisons with rsvg-convert.
# Only the test support's FreeType loader; its library is named by path
# (the Makefile defines TS_A after including the modules).
GLYPHSVG := $(BUILD)/tests/glyphsvg
$(GLYPHSVG): $(BUILD)/obj/tests/tools/glyphsvg.o $(BUILD)/lib/libconica_testsupport.a
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(FT_LIBS) -lm
TEST_EXTRA += $(GLYPHSVG)
