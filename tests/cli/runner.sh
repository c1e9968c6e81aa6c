# SPDX-License-Identifier: MIT
# The test runner's own suite: runs the deliberately failing binary
# (tests/runner_selftest/failing.c, hidden cases) with Catch2 command lines
# and checks output, reporters and exit codes.
#     sh tests/cli/runner.sh [BUILD_DIR]
. "$(dirname "$0")/harness.sh"

B=$build/tests/runner_failing
X=$build/tests/runner_cxx

valid_xml() { # file: well-formed XML?
    if command -v xmllint >/dev/null 2>&1; then
        xmllint --noout "$1"
    else
        python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$1"
    fi
}

begin_case "self-test binaries are built"
check_true "runner_failing exists" test -x "$B"
check_true "runner_cxx exists" test -x "$X"
if [ ! -x "$B" ] || [ ! -x "$X" ]; then
    finish
fi

begin_case "no arguments: only visible cases run"
check_exit 0 "plain run passes" "$B"
check_grep '^All tests passed \(1 assertion in 1 test case\)$' "$out" "singular summary"
check_grep '^={79}$' "$out" "a line of 79 '=' before the summary"
check_no_grep 'marker:' "$out" "hidden cases did not run"

begin_case "a passing hidden case selected by tag"
check_exit 0 "[pass] passes" "$B" '[pass]'
check_grep '^All tests passed \(4 assertions in 1 test case\)$' "$out"
check_grep '^Filters: \[pass\]$' "$out"

begin_case "all self-test cases: summary rows"
check_exit 42 "[.selftest] fails with 42" "$B" '[.selftest]'
check_grep '^test cases: 11 \|  2 passed \|  8 failed \| 1 skipped$' "$out" "test case row, padded like Catch2"
check_grep '^assertions: 29 \| 11 passed \| 18 failed$' "$out" "assertion row, no skipped column"
check_grep '^tests/runner_selftest/failing\.c:[0-9]+: FAILED:$' "$out" "file:line: FAILED:"

begin_case "CHECK continues, REQUIRE stops"
check_exit 42 "[check] fails" "$B" '[check]'
check_grep '^marker: after-check$' "$out" "code after a failed CHECK ran"
check_grep '^  CHECK_EQ\( 2 \+ 2, 5 \)$' "$out" "expression as written"
check_grep '^  4 == 5$' "$out" "expansion with both operands"
check_grep '^test cases: 1 \| 1 failed$' "$out"
check_grep '^assertions: 3 \| 1 passed \| 2 failed$' "$out"
check_exit 42 "[require] fails" "$B" '[require]'
check_no_grep 'after-require' "$out" "code after a failed REQUIRE did not run"
check_grep '^assertions: 1 \| 1 failed$' "$out"

begin_case "sections: one run per leaf"
check_exit 0 "[sections] passes" "$B" '[sections]'
check_count 3 '^marker: body-run$' "$out" "body ran three times"
check_grep '^All tests passed \(3 assertions in 1 test case\)$' "$out"
h_leaves=$(grep '^marker: leaf' "$out" | tr '\n' ';')
check_true "leaves in order A/A1, A/A2, B" test "$h_leaves" = "marker: leaf A/A1;marker: leaf A/A2;marker: leaf B;"
check_exit 42 "[secfail] fails" "$B" '[secfail]'
check_grep '^marker: ran-Y$' "$out" "sibling of a failed section ran"
check_no_grep 'after-require-in-X' "$out"
check_grep '^  X$' "$out" "failure header names the section"

begin_case "-c runs one section path"
check_exit 0 "-c A -c A2" "$B" '[sections]' -c A -c A2
check_count 1 '^marker: body-run$' "$out"
check_grep '^marker: leaf A/A2$' "$out"
check_no_grep 'leaf (A/A1|B)' "$out"
check_exit 0 "--section B" "$B" '[sections]' --section B
check_grep '^marker: leaf B$' "$out"
check_count 1 '^marker: body-run$' "$out"

begin_case "SKIP"
check_exit 4 "all cases skipped exits 4" "$B" '[skip]'
check_grep '^test cases: 1 \| 1 skipped$' "$out"
check_grep '^assertions: - none -$' "$out"
check_grep 'SKIPPED:$' "$out"
check_grep '^  not today 7$' "$out" "skip message formatted"
check_no_grep 'after-skip' "$out"
check_exit 0 "a skip next to a pass exits 0" "$B" '[pass],[skip]'
check_grep '^test cases: 2 \| 1 passed \| 1 skipped$' "$out" "comma is OR"

begin_case "INFO, CAPTURE and comparison output"
check_exit 42 "[info] fails" "$B" '[info]'
check_grep '^with messages:$' "$out"
check_grep '^  alpha=5$' "$out"
check_grep '^  x := 0.5$' "$out" "CAPTURE_D"
check_grep '^  pass 2$' "$out" "INFO in a loop shows the current pass"
check_no_grep '^  pass [01]$' "$out" "earlier passes replaced"
check_grep '^  0.5 == 0.25 \+/- 0.001 \(\|difference\| 0.25\)$' "$out" "CHECK_NEAR expansion"
check_exit 42 "[cmp] fails" "$B" '[cmp]'
check_grep '^  123456789012 == 7$' "$out"
check_grep '^  "left" == "right"$' "$out"
check_grep '^  1 == 1.5 within relative 1e-09' "$out"
check_grep '^  CHECK_FALSE\( 2 > 1 \)$' "$out"
check_grep '^  3 < 2$' "$out"
check_exit 42 "FAIL ends the case" "$B" '[explicit]'
check_grep '^explicitly with message:$' "$out"
check_grep '^  boom now$' "$out"
check_no_grep 'after-fail' "$out"

begin_case "test specs: names, wildcards, negation"
check_exit 0 "hidden case by name wildcard" "$B" 'selftest: p*'
check_grep '^All tests passed \(4 assertions in 1 test case\)$' "$out"
check_exit 42 "leading wildcard" "$B" '*stops'
check_grep '^test cases: 1 \| 1 failed$' "$out"
check_exit 0 "arguments AND, ~ negates" "$B" '[.selftest]' '~[fail]'
check_grep '^test cases: 3 \| 2 passed \| 1 skipped$' "$out"
check_exit 0 "exact name with spaces" "$B" 'visible: one assertion'
check_grep '^All tests passed \(1 assertion in 1 test case\)$' "$out"
check_exit 2 "[a][b] is AND: nothing has both" "$B" '[pass][skip]'

begin_case "no match, unmatched and invalid specs"
check_exit 2 "nothing matched: exit 2" "$B" 'no such test'
check_grep "^No test cases matched '\"no such test\"'$" "$out"
check_grep '^No tests ran$' "$out"
check_exit 3 "-w UnmatchedTestSpec: exit 3" "$B" -w UnmatchedTestSpec 'no such test'
check_exit 3 "one of two filters unmatched" "$B" --warn UnmatchedTestSpec '[pass],[nothing]'
check_grep "^No test cases matched '\[nothing\]'$" "$out"
check_exit 0 "--allow-running-no-tests" "$B" --allow-running-no-tests 'no such test'
check_exit 5 "comma inside a tag is invalid" "$B" '[a,b]'
check_grep '^Invalid Filter: \[a,b\]$' "$out"
check_exit 5 "comma inside quotes is invalid" "$B" '"x,y"'

begin_case "command-line errors"
check_exit 1 "unknown option" "$B" --frobnicate
check_grep 'Unrecognised token: --frobnicate' "$err"
check_exit 1 "-x needs a number" "$B" -x many
check_exit 1 "unknown reporter" "$B" -r tap
check_exit 1 "unknown order" "$B" --order sideways
check_exit 1 "shard index out of range" "$B" --shard-count 2 --shard-index 2
check_exit 0 "--help" "$B" --help
check_grep '^usage:$' "$out"
check_exit 0 "-?" "$B" '-?'

begin_case "listing"
check_exit 0 "--list-tests" "$B" --list-tests
check_grep '^All available test cases:$' "$out"
check_grep '^  visible: one assertion$' "$out"
check_grep '^      \[visible\]$' "$out"
check_grep '^1 test case$' "$out"
check_exit 0 "--list-tests with a filter" "$B" --list-tests '[.order]'
check_grep '^Matching test cases:$' "$out"
check_grep '^3 matching test cases$' "$out"
check_exit 0 "--list-tags" "$B" --list-tags '[.selftest]'
check_grep '^   8  \[fail\]$' "$out"
check_grep '^  11  \[selftest\]$' "$out"
check_exit 0 "--list-reporters" "$B" --list-reporters
check_grep '^  junit:' "$out"

begin_case "junit reporter"
check_exit 42 "junit to a file" "$B" '[.selftest]' -r junit -o "$tmp/j.xml"
check_true "junit output is well-formed XML" valid_xml "$tmp/j.xml"
check_grep '<testsuite name="runner_failing" errors="0" failures="8" skipped="1" tests="14"' "$tmp/j.xml"
check_grep '<testcase classname="runner_failing.global" name="selftest: sections/A/A2"' "$tmp/j.xml"
check_grep '<failure message="2 \+ 2, 5" type="CHECK_EQ">' "$tmp/j.xml"
check_grep 'name="selftest: xml &lt;escaping&gt; &amp; &quot;quotes&quot;"' "$tmp/j.xml"
check_grep '<skipped message="not today 7" type="SKIP">' "$tmp/j.xml"
check_exit 0 "console and junit::out= together" "$B" '[pass]' -r console -r "junit::out=$tmp/k.xml"
check_grep '^All tests passed \(4 assertions in 1 test case\)$' "$out"
check_true "junit::out file is well-formed" valid_xml "$tmp/k.xml"
check_grep 'failures="0" skipped="0" tests="1"' "$tmp/k.xml"
check_exit 1 "two reporters on the default output" "$B" -r console -r junit

begin_case "xml reporter"
check_exit 42 "xml to a file" "$B" '[.selftest]' -r xml -o "$tmp/x.xml"
cp "$tmp/x.xml" "$out"
check_true "xml output is well-formed" valid_xml "$out"
check_grep '^<Catch2TestRun name="runner_failing"' "$out"
check_grep '<Expression success="false" type="CHECK_EQ" filename="tests/runner_selftest/failing.c"' "$out"
check_grep '<Section name="A2"' "$out"
check_grep '<OverallResultsCases successes="2" failures="8" expectedFailures="0" skips="1"/>' "$out"

begin_case "-a, -x and -s"
check_exit 42 "-a stops at the first failure" "$B" '[.selftest]' -a
check_grep '^test cases: 2 \| 1 passed \| 1 failed$' "$out"
check_grep '^assertions: 5 \| 4 passed \| 1 failed$' "$out"
check_no_grep 'after-check' "$out" "the failing case stopped too"
check_exit 42 "-x 3" "$B" '[abort]' -x 3
check_count 3 'FAILED:$' "$out"
check_exit 42 "--abortx=2" "$B" '[abort]' --abortx=2
check_count 2 'FAILED:$' "$out"
check_exit 0 "-s shows passing assertions" "$B" '[pass]' -s
check_count 4 'PASSED:$' "$out"

begin_case "--order, --rng-seed and sharding"
check_exit 0 "declaration order" "$B" '[.order]'
check_true "decl: c a b" test "$(grep '^marker: order' "$out" | tr -d '\n')" = "marker: order cmarker: order amarker: order b"
check_exit 0 "lexical order" "$B" '[.order]' --order lex
check_true "lex: a b c" test "$(grep '^marker: order' "$out" | tr -d '\n')" = "marker: order amarker: order bmarker: order c"
check_exit 0 "random order, seed 7" "$B" '[.order]' --order rand --rng-seed 7
grep '^marker: order' "$out" >"$tmp/rand1"
check_grep '^Randomness seeded to: 7$' "$out"
check_exit 0 "random order, seed 7 again" "$B" '[.order]' --order rand --rng-seed 7
grep '^marker: order' "$out" >"$tmp/rand2"
check_true "same seed, same order" cmp -s "$tmp/rand1" "$tmp/rand2"
check_count 3 '^marker: order' "$tmp/rand1" "random order runs every case once"
check_exit 0 "shard 1 of 3" "$B" '[.order]' --shard-count 3 --shard-index 1
check_true "shard 1 of 3 is the second case" test "$(grep '^marker: order' "$out")" = "marker: order a"
check_exit 0 "-d yes prints durations" "$B" '[pass]' -d yes
check_grep '^[0-9]+\.[0-9]{3} s: selftest: passes$' "$out"

begin_case "a crashing case is reported"
case $build in
    */san) skip_case "AddressSanitizer reports crashes itself" ;;
esac
check_exit 139 "dies of SIGSEGV (128 + 11)" "$B" '[.crash]'
check_grep '^due to a fatal error condition:$' "$out"
check_grep '^  SIGSEGV - Segmentation violation signal$' "$out"
check_grep '^test cases: 1 \| 1 failed$' "$out" "totals printed before dying"
check_grep '^-{79}$' "$out" "header names the case"
check_grep '^selftest: crash$' "$out"

begin_case "the shell harness itself"
h_lib=$(cd "$(dirname "$0")" && pwd)/harness.sh
cat >"$tmp/mixed.sh" <<SUITE
. "$h_lib"
begin_case "passes"
check "true passes" true
begin_case "fails"
check "true passes" true
check_exit 3 "exit status 3 expected" sh -c 'echo oops >&2; exit 4'
begin_case "skipped"
skip_case "not here"
check "ignored after skip" false
finish
SUITE
check_exit 42 "a failing suite exits 42" sh "$tmp/mixed.sh"
check_grep '^test cases: 3 \| 1 passed \| 1 failed \| 1 skipped$' "$out"
check_grep '^assertions: 3 \| 2 passed \| 1 failed$' "$out"
check_grep '^  exit status 4 \(expected 3\)$' "$out" "the failure says what was expected"
check_grep '^  oops$' "$out" "the failure shows the command's stderr"
check_grep '^  not here$' "$out" "skip reason printed"
printf '. "%s"\nbegin_case one\ncheck a true\ncheck_grep x "%s"\nfinish\n' "$h_lib" "$tmp/mixed.sh" >"$tmp/pass.sh"
check_exit 0 "a passing suite exits 0" sh "$tmp/pass.sh"
check_grep '^All tests passed \(2 assertions in 1 test case\)$' "$out"
printf '. "%s"\nbegin_case one\nskip_case why\nfinish\n' "$h_lib" >"$tmp/skip.sh"
check_exit 4 "an all-skipped suite exits 4" sh "$tmp/skip.sh"
check_grep '^test cases: 1 \| 1 skipped$' "$out"
check_grep '^assertions: - none -$' "$out"
printf '. "%s"\nfinish\n' "$h_lib" >"$tmp/none.sh"
check_exit 2 "a suite without cases exits 2" sh "$tmp/none.sh"
check_grep '^No tests ran$' "$out"

begin_case "C++17 compatibility"
check_exit 0 "the header works from C++" "$X"
check_grep '^All tests passed \(17 assertions in 3 test cases\)$' "$out"

finish
