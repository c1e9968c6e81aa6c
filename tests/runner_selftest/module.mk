# SPDX-License-Identifier: MIT
# The runner's self-test binaries (run by tests/cli/runner.sh, not by the
# unit-test loop): runner_failing holds hidden cases that fail, pass, skip
# and use sections; runner_cxx proves conica_test.h compiles as C++17.
RUNNER_FAILING := $(BUILD)/tests/runner_failing
RUNNER_CXX     := $(BUILD)/tests/runner_cxx
# The top Makefile defines RUNNER_A after including the fragments, so name
# the runner library directly in prerequisites (expanded immediately).
RUNNER_LIB     := $(BUILD)/lib/libconica_test.a

$(RUNNER_FAILING): $(BUILD)/obj/tests/runner_selftest/failing.o $(RUNNER_LIB)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(RUNNER_LIB) -lm

$(BUILD)/obj/tests/runner_selftest/cxx_check.o: CXXFLAGS += -Wpedantic -Wconversion
$(RUNNER_CXX): $(BUILD)/obj/tests/runner_selftest/cxx_check.o $(RUNNER_LIB)
	@mkdir -p $(@D)
	$(CXX) $(LDFLAGS) -o $@ $< $(RUNNER_LIB) -lm

TEST_EXTRA += $(RUNNER_FAILING) $(RUNNER_CXX)
