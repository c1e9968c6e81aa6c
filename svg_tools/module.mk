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
