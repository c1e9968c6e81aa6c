# bench/: benchmark programs (print figures, never assert). Shared fragment:
# each owner appends its own rules below.

# ---- bench_subdiv (issue 3): speed and accuracy of conica_subdivide
BENCH_SUBDIV := $(BUILD)/bench/bench_subdiv
$(BENCH_SUBDIV): $(BUILD)/obj/bench/bench_subdiv.o $(CORE_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(CORE_A) $(CORE_LIBS)
BENCH_BINS += $(BENCH_SUBDIV)
