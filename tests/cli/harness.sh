# SPDX-License-Identifier: MIT
# tests/cli/harness.sh - a small POSIX sh library for CLI test suites.
#
# A suite is run from the repository root as `sh tests/cli/NAME.sh BUILD_DIR`:
#
#     . "$(dirname "$0")/harness.sh"      # sets $build (from $1) and $tmp
#     begin_case "subdivide a circle"
#     check "conica runs" "$build/bin/conica" subdivide "$tmp/in.txt"
#     check_grep '^x ' "$out"              # $out/$err: the last command's output
#     check_exit 1 "bad input is an error" "$build/bin/conica" subdivide /nonexistent
#     skip_case "openscad not installed"   # the rest of this case is ignored
#     finish                               # summary in Catch2's words, exit code
#
# Every check is one assertion; every begin_case one test case. finish prints
# the same summary as the C runner (`All tests passed (N assertions in M test
# cases)`, or the `test cases:` / `assertions:` rows) and exits like Catch2:
# 0 passed, 42 something failed, 4 every case skipped, 2 no case ran.
# A failing check prints the suite, the case, what was expected, the command
# and the tails of its stdout and stderr.
#
# CONICA_WRAP (for `make memcheck`, scripts/memcheck.sh): a command prefix,
# split into words, put before every command the checks run whose program
# lies in $build/bin (not before sh, env, cmp, ...). `@LOG@` in it becomes
# a log file per command. Exit status 99 of a wrapped command means the
# wrapper found errors (memcheck.sh uses valgrind --error-exitcode=99): that
# is one more failed assertion, with the log's tail, whatever the check
# expected. finish then prints `wrapped: N runs, E with errors` before the
# summary.

build=${1:-build}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-cli.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
trap 'rm -rf "$tmp"; exit 130' INT TERM
out=$tmp/.out
err=$tmp/.err
: >"$out"
: >"$err"

h_suite=${0##*/}
h_cases=0 h_cases_failed=0 h_cases_skipped=0
h_pass=0 h_fail=0
h_case="" h_case_failed=0 h_case_skipped=0 h_header=0
h_cmd=""
h_wrapped=0 h_wrap_errors=0
h_wrap_log=$tmp/.wrap.log

h_line() { # character
    printf '%s\n' "$(printf '%79s' '' | tr ' ' "$1")"
}

h_end_case() {
    [ -n "$h_case" ] || return 0
    h_cases=$((h_cases + 1))
    if [ "$h_case_failed" -ne 0 ]; then
        h_cases_failed=$((h_cases_failed + 1))
    elif [ "$h_case_skipped" -ne 0 ]; then
        h_cases_skipped=$((h_cases_skipped + 1))
    fi
    h_case=""
}

# begin_case NAME: start a test case (ends the previous one).
begin_case() {
    h_end_case
    h_case=$1 h_case_failed=0 h_case_skipped=0 h_header=0
}

h_header() {
    [ "$h_header" -eq 0 ] || return 0
    h_line -
    printf '%s\n' "${h_case:-(no case)}"
    h_line -
    printf '%s\n' "tests/cli/$h_suite"
    h_line .
    echo
    h_header=1
}

h_tail() { # label file
    if [ -s "$2" ]; then
        printf '%s (last 20 lines):\n' "$1"
        tail -n 20 "$2" | sed 's/^/  /'
    fi
}

h_pass() {
    h_pass=$((h_pass + 1))
    if [ -n "${CLI_VERBOSE:-}" ]; then
        printf '%s: PASSED: %s\n' "$h_suite" "$1"
    fi
}

h_fail() { # description detail [show-output]
    h_fail=$((h_fail + 1))
    h_case_failed=1
    h_header
    printf '%s: FAILED:\n  %s\n' "tests/cli/$h_suite" "$1"
    [ -n "$2" ] && printf '%s\n' "$2" | sed 's/^/  /'
    if [ -n "$h_cmd" ]; then
        printf 'command:\n  %s\n' "$h_cmd"
        h_tail stdout "$out"
        h_tail stderr "$err"
    fi
    echo
}

h_skipping() { [ "$h_case_skipped" -ne 0 ]; }

# Runs a command with stdin closed; its output lands in $out and $err.
# Returns the command's exit status.
h_run() {
    h_cmd=$(printf '%s ' "$@")
    case "${CONICA_WRAP:-}:$1" in
        :*) "$@" >"$out" 2>"$err" </dev/null ;;
        *:"$build"/bin/*) h_run_wrapped "$@" ;;
        *) "$@" >"$out" 2>"$err" </dev/null ;;
    esac
}

h_run_wrapped() {
    h_wrapped=$((h_wrapped + 1))
    : >"$h_wrap_log"
    # shellcheck disable=SC2046 # the prefix is words on purpose
    set -- $(printf '%s\n' "$CONICA_WRAP" | sed "s|@LOG@|$h_wrap_log|g") "$@"
    "$@" >"$out" 2>"$err" </dev/null
    h_wst=$?
    if [ "$h_wst" -eq 99 ]; then
        h_wrap_errors=$((h_wrap_errors + 1))
        h_fail "the wrapper (${CONICA_WRAP%% *}) found errors: exit 99" \
            "$(tail -n 40 "$h_wrap_log" 2>/dev/null)"
    fi
    return "$h_wst"
}

# Python for checks written inline (Debian's, when a pyenv one shadows it).
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
# py SCRIPT [ARGS]: run an inline Python check.
py() { "$PY" -c "$@"; }
# fails_with STATUS PATTERN CMD...: CMD exits with STATUS and its stderr has
# a line with PATTERN (use as: check "..." fails_with 1 'error' cmd ...).
fails_with() {
    want=$1 pat=$2
    shift 2
    "$@" >"$tmp/fw.out" 2>"$tmp/fw.err"
    got=$?
    [ "$got" -eq "$want" ] || { echo "exit $got, wanted $want"; cat "$tmp/fw.err"; return 1; }
    grep -q -- "$pat" "$tmp/fw.err" || { echo "stderr lacks '$pat':"; cat "$tmp/fw.err"; return 1; }
}

# check DESC CMD...: passes when CMD exits 0.
check() {
    h_skipping && return 0
    h_desc=$1
    shift
    h_run "$@"
    h_st=$?
    if [ "$h_st" -eq 0 ]; then
        h_pass "$h_desc"
    else
        h_fail "$h_desc" "exit status $h_st (expected 0)"
    fi
}

# check_exit N DESC CMD...: passes when CMD exits with status N.
check_exit() {
    h_skipping && return 0
    h_want=$1 h_desc=$2
    shift 2
    h_run "$@"
    h_st=$?
    if [ "$h_st" -eq "$h_want" ]; then
        h_pass "$h_desc"
    else
        h_fail "$h_desc" "exit status $h_st (expected $h_want)"
    fi
}

# check_grep PATTERN FILE [DESC]: FILE has a line matching the extended regex.
check_grep() {
    h_skipping && return 0
    if grep -E -q -e "$1" "$2" 2>/dev/null; then
        h_pass "${3:-$2 matches /$1/}"
    else
        h_fail "${3:-$2 matches /$1/}" "no line matches /$1/ in $2"
    fi
}

# check_no_grep PATTERN FILE [DESC]: no line of FILE matches.
check_no_grep() {
    h_skipping && return 0
    if grep -E -q -e "$1" "$2" 2>/dev/null; then
        h_fail "${3:-$2 should not match /$1/}" \
            "unexpected: $(grep -E -n -e "$1" "$2" | head -n 3)"
    else
        h_pass "${3:-$2 has no line matching /$1/}"
    fi
}

# check_count N PATTERN FILE [DESC]: exactly N lines of FILE match.
check_count() {
    h_skipping && return 0
    h_n=$(grep -E -c -e "$2" "$3" 2>/dev/null)
    if [ "${h_n:-0}" -eq "$1" ]; then
        h_pass "${4:-$3: $1 lines match /$2/}"
    else
        h_fail "${4:-$3: $1 lines should match /$2/}" "found ${h_n:-0}"
    fi
}

# check_true DESC TEST...: a shell test without output capture, e.g.
#     check_true "output written" test -s "$tmp/o.svg"
check_true() {
    h_skipping && return 0
    h_desc=$1
    shift
    if "$@"; then
        h_pass "$h_desc"
    else
        h_cmd=""
        h_fail "$h_desc" "failed: $*"
    fi
}

# skip_case REASON: the current case is skipped; its later checks are ignored.
skip_case() {
    h_case_skipped=1
    h_header
    printf '%s: SKIPPED:\nexplicitly with message:\n  %s\n\n' "tests/cli/$h_suite" "$1"
}

# finish: summary in Catch2's words; exits 0, 42, 4 or 2.
finish() {
    h_end_case
    if [ -n "${CONICA_WRAP:-}" ]; then
        echo "wrapped: $h_wrapped runs, $h_wrap_errors with errors"
    fi
    h_asserts=$((h_pass + h_fail))
    h_cpass=$((h_cases - h_cases_failed - h_cases_skipped))
    h_line =
    if [ "$h_cases" -eq 0 ]; then
        echo "No tests ran"
        echo
        exit 2
    fi
    if [ "$h_asserts" -gt 0 ] && [ "$h_cases_failed" -eq 0 ] && [ "$h_cases_skipped" -eq 0 ]; then
        h_a=assertions h_c="test cases"
        [ "$h_pass" -eq 1 ] && h_a=assertion
        [ "$h_cpass" -eq 1 ] && h_c="test case"
        echo "All tests passed ($h_pass $h_a in $h_cpass $h_c)"
        echo
        exit 0
    fi
    # Catch2's SummaryColumn: a column's cells share a width; captioned
    # cells that are exactly "0" are left out; a zero total is "- none -".
    set -- "$h_cases" "$h_asserts" "$h_cpass" "$h_pass" "$h_cases_failed" "$h_fail" \
        "$h_cases_skipped" 0
    h_r1="test cases:" h_r2="assertions:"
    for h_caption in "" passed failed skipped; do
        h_v1=$1 h_v2=$2
        shift 2
        h_w=${#h_v1}
        [ ${#h_v2} -gt "$h_w" ] && h_w=${#h_v2}
        h_c1=$(printf '%*s' "$h_w" "$h_v1")
        h_c2=$(printf '%*s' "$h_w" "$h_v2")
        if [ -z "$h_caption" ]; then
            if [ "$h_c1" = 0 ]; then h_r1="$h_r1 - none -"; else h_r1="$h_r1 $h_c1"; fi
            if [ "$h_c2" = 0 ]; then h_r2="$h_r2 - none -"; else h_r2="$h_r2 $h_c2"; fi
        else
            [ "$h_c1" = 0 ] || h_r1="$h_r1 | $h_c1 $h_caption"
            [ "$h_c2" = 0 ] || h_r2="$h_r2 | $h_c2 $h_caption"
        fi
    done
    printf '%s\n%s\n\n' "$h_r1" "$h_r2"
    if [ "$h_fail" -ne 0 ]; then exit 42; fi
    if [ "$h_cases_skipped" -eq "$h_cases" ]; then exit 4; fi
    exit 0
}
