# The runner's self-test binaries (run by tests/cli/runner.sh, not by the
# unit-test loop): runner_failing holds hidden cases that fail, pass, skip
# and use sections; runner_cxx proves conica_test.h compiles as C++17.
RUNNER_FAILING := $(BUILD)/tests/runner_failing
RUNNER_CXX     := $(BUILD)/tests/runner_cxx

$(RUNNER_FAILING): $(BUILD)/obj/tests/runner_selftest/failing.o $(RUNNER_A)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(RUNNER_A) -lm

$(BUILD)/obj/tests/runner_selftest/cxx_check.o: CXXFLAGS += -Wpedantic -Wconversion
$(RUNNER_CXX): $(BUILD)/obj/tests/runner_selftest/cxx_check.o $(RUNNER_A)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) -o $@ $< $(RUNNER_A) -lm

TEST_EXTRA += $(RUNNER_FAILING) $(RUNNER_CXX)
