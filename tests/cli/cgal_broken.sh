# SPDX-License-Identifier: MIT
# tests/cli/cgal_broken.sh: the CGAL checks of issue 4 can fail. The hidden
# test [.broken] of tests/cgal/test_cgal.cpp runs the inflection checks with
# insert_inflections = 0 (a deliberately broken scheme); it must FAIL with
# Catch2's test-failure exit code 42, naming the missing inflection points.
. "$(dirname "$0")/harness.sh"

bin=$build/tests/cgal_test

begin_case "CGAL suite fails on a scheme without inflection insertion"
if [ ! -x "$bin" ]; then
    skip_case "$bin not built (make tests builds it)"
fi
check_exit 42 "[.broken] fails" "$bin" "[.broken]"
check_grep 'inflection edges by CGAL, 0 inserted' "$out" "failure names the missing inflection points"
check_grep 'test cases: 1 \| 1 failed' "$out" "exactly the one hidden case ran and failed"

begin_case "the hidden broken test is not run by default"
if [ ! -x "$bin" ]; then
    skip_case "$bin not built"
fi
check_exit 0 "listing works" "$bin" --list-tests
check_no_grep 'broken variant' "$out" "hidden test not listed"
check_exit 0 "listing hidden tests" "$bin" --list-tests "[.broken]"
check_grep 'broken variant' "$out" "hidden test listed when named"

finish
