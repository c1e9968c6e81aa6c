# SPDX-License-Identifier: MIT
# bench/: benchmark programs (print figures, never assert). Shared fragment:
# each owner appends its own rules below.

# ---- bench_ablation (issue 9): the numerics ablation of CONIS §3.2
BENCH_ABLATION := $(BUILD)/bench/bench_ablation
$(BUILD)/obj/bench/bench_ablation.o: CPPFLAGS += -Ilibcore/tools
$(BENCH_ABLATION): $(BUILD)/obj/bench/bench_ablation.o $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(CLI_A) $(CORE_A) $(CORE_LIBS)
BENCH_BINS += $(BENCH_ABLATION)
# scripts/demo-diagnostics.sh draws the ablation combs with it
DEMO_DEPS += $(BENCH_ABLATION)

# ---- bench_subdiv (issue 3): speed and accuracy of conica_subdivide
BENCH_SUBDIV := $(BUILD)/bench/bench_subdiv
$(BUILD)/obj/bench/bench_subdiv.o: CPPFLAGS += -Itests/support
$(BENCH_SUBDIV): $(BUILD)/obj/bench/bench_subdiv.o $(BUILD)/lib/libconica_testsupport.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CORE_A) $(CORE_LIBS)
BENCH_BINS += $(BENCH_SUBDIV)

# ---- bench_svg (issue 6): SVG layer (XML + path I/O) against the geometry it feeds
BENCH_SVG := $(BUILD)/bench/bench_svg
$(BUILD)/obj/bench/bench_svg.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)
# (ALL_LIBS is complete only after every fragment: name the libraries by path)
$(BENCH_SVG): $(BUILD)/obj/bench/bench_svg.o $(BUILD)/lib/libconica_svg.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_svg.a $(CORE_A) $(ALL_LDLIBS)
BENCH_BINS += $(BENCH_SVG)

# ---- bench_plot (issue 5): spline plotters vs minimum, uniform, Wang; criteria table
BENCH_PLOT := $(BUILD)/bench/bench_plot
$(BENCH_PLOT): $(BUILD)/obj/bench/bench_plot.o $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(CORE_A) $(CORE_LIBS)
BENCH_BINS += $(BENCH_PLOT)

# ---- bench_flatten (issue 20): guaranteed plotter vs an independent greedy
# reference, and vs cairo's flattening when Debian's libcairo2-dev is there
# (the benchmark only; never a dependency of the library or the tools)
BENCH_FLATTEN := $(BUILD)/bench/bench_flatten
CAIRO_FOUND := $(shell $(PKG_CONFIG) --exists cairo 2>/dev/null && echo yes)
$(BUILD)/obj/bench/bench_flatten.o: CPPFLAGS += -Itests/support \
    $(if $(CAIRO_FOUND),-DCONICA_HAVE_CAIRO $(patsubst -I%,-isystem %,$(shell $(PKG_CONFIG) --cflags cairo)))
$(BENCH_FLATTEN): $(BUILD)/obj/bench/bench_flatten.o $(BUILD)/lib/libconica_testsupport.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CORE_A) $(CORE_LIBS) \
	    $(FT_LIBS) $(if $(CAIRO_FOUND),$(shell $(PKG_CONFIG) --libs cairo))
BENCH_BINS += $(BENCH_FLATTEN)

# ---- bench_fidelity (issue 14): conica/path.h on glyph outlines, independent checker
BENCH_FIDELITY := $(BUILD)/bench/bench_fidelity
$(BUILD)/obj/bench/bench_fidelity.o: CPPFLAGS += -Itests/support
$(BENCH_FIDELITY): $(BUILD)/obj/bench/bench_fidelity.o $(BUILD)/lib/libconica_testsupport.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CORE_A) $(CORE_LIBS) $(FT_LIBS)
BENCH_BINS += $(BENCH_FIDELITY)

# ---- bench_scad_import: scadprofile beside OpenSCAD's import() on glyph outlines
# (runs $(BUILD)/bin/scadprofile and openscad; CPU time and RSS per run)
BENCH_SCAD_IMPORT := $(BUILD)/bench/bench_scad_import
$(BUILD)/obj/bench/bench_scad_import.o: CPPFLAGS += -Itests/support
$(BENCH_SCAD_IMPORT): $(BUILD)/obj/bench/bench_scad_import.o $(BUILD)/lib/libconica_testsupport.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CORE_A) $(CORE_LIBS) $(FT_LIBS)
BENCH_BINS += $(BENCH_SCAD_IMPORT)

# ---- bench_fairness (issue 20): curvature total variation at inflections vs the reference
BENCH_FAIRNESS := $(BUILD)/bench/bench_fairness
$(BUILD)/obj/bench/bench_fairness.o: CPPFLAGS += -Itests/support -Ilibcore/tools
$(BENCH_FAIRNESS): $(BUILD)/obj/bench/bench_fairness.o $(BUILD)/lib/libconica_testsupport.a $(CLI_A) $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CLI_A) $(CORE_A) $(CORE_LIBS) $(FT_LIBS)
BENCH_BINS += $(BENCH_FAIRNESS)

# ---- bench_arcs (issue 38): Table A, cubic / quadratic / conic arcs / NURBS ellipses
# vs the greedy optimum and cairo in one run (cairo optional, as for bench_flatten)
BENCH_ARCS := $(BUILD)/bench/bench_arcs
$(BUILD)/obj/bench/bench_arcs.o: CPPFLAGS += -Itests/support \
    $(if $(CAIRO_FOUND),-DCONICA_HAVE_CAIRO $(patsubst -I%,-isystem %,$(shell $(PKG_CONFIG) --cflags cairo)))
$(BENCH_ARCS): $(BUILD)/obj/bench/bench_arcs.o $(BUILD)/lib/libconica_testsupport.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_testsupport.a $(CORE_A) $(CORE_LIBS) \
	    $(FT_LIBS) $(if $(CAIRO_FOUND),$(shell $(PKG_CONFIG) --libs cairo))
BENCH_BINS += $(BENCH_ARCS)

# ---- bench_corners (issue 33): conica_plot on 10^3..10^6 corner knots
BENCH_CORNERS := $(BUILD)/bench/bench_corners
$(BENCH_CORNERS): $(BUILD)/obj/bench/bench_corners.o $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(CORE_A) $(CORE_LIBS)
BENCH_BINS += $(BENCH_CORNERS)

# ---- bench_scaling (issue 38): local slopes and peak memory, 10^3..10^6, of
# plot, path flatten (vs plot_bezier), svg one-path / many-path, subdivision
BENCH_SCALING := $(BUILD)/bench/bench_scaling
$(BUILD)/obj/bench/bench_scaling.o: CPPFLAGS += -Isvg_tools $(XML_CFLAGS)
$(BENCH_SCALING): $(BUILD)/obj/bench/bench_scaling.o $(BUILD)/lib/libconica_svg.a $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(BUILD)/lib/libconica_svg.a $(CORE_A) $(ALL_LDLIBS) -lpthread
BENCH_BINS += $(BENCH_SCALING)
