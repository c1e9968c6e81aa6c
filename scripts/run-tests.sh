#!/bin/sh
# SPDX-License-Identifier: MIT
# Run every test suite against the build in $1 (default: build) and end with
# one line `N passed, M failed` summed over all suites (test cases).
#
# Suites: each test binary in BUILD/tests (Catch2-compatible runner), each
# CLI suite tests/cli/*.sh (shell harness, same summary format), then the
# unit and CLI suites again from the sanitizer build in BUILD/san when it
# exists (make test builds it). Logs go to BUILD/test-logs/.
#
# The suites are independent (each works in its own mktemp directory), so
# they run CONICA_TEST_JOBS at a time (default: the processor count),
# longest first: the order comes from the times the previous run left in
# BUILD/test-logs/*.time, and on a fresh build directory from the list of
# slow suites below. Each suite's line is printed when it ends, with its wall
# time; at the end come the failed suites again (where their logs first say
# FAILED, and their tails), the time of all suites and, when
# CONICA_TEST_START holds the epoch seconds at which `make test` began (the
# Makefile sets it), the time of the whole run including the builds.
set -u

# Wall-clock seconds with fractions (GNU date's %N; whole seconds elsewhere).
now() {
    t=$(date +%s.%N 2>/dev/null)
    case "$t" in *N*|'') date +%s ;; *) printf '%s\n' "$t" ;; esac
}
# seconds FROM TO: the difference, one decimal.
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }
logname() { printf '%s' "$1" | tr '/ ' '__'; }

# Count one suite's closing lines: Catch2's "All tests passed (A assertions
# in T test cases)" or its "test cases: T | P passed | F failed | S skipped"
# row. Prints "P F S".
count() { # log status
    summary=$(grep -E '^(All tests passed|test cases:|No tests ran)' "$1" | tail -n 1)
    p=0 f=0 s=0
    case "$summary" in
        "All tests passed"*)
            p=$(printf '%s\n' "$summary" | sed -n 's/.* in \([0-9]*\) test case.*/\1/p') ;;
        "test cases:"*)
            p=$(printf '%s\n' "$summary" | sed -n 's/.*| *\([0-9]*\) passed.*/\1/p')
            f=$(printf '%s\n' "$summary" | sed -n 's/.*| *\([0-9]*\) failed.*/\1/p')
            s=$(printf '%s\n' "$summary" | sed -n 's/.*| *\([0-9]*\) skipped.*/\1/p')
            if [ -z "$p$f$s" ]; then  # "test cases: T | T skipped" style rows
                s=$(printf '%s\n' "$summary" | sed -n 's/^test cases: *\([0-9]*\).*/\1/p')
            fi ;;
    esac
    p=${p:-0} f=${f:-0} s=${s:-0}
    # A suite that failed without saying how many cases failed still fails.
    if [ "$2" -ne 0 ] && [ "$2" -ne 4 ] && [ "$f" -eq 0 ]; then f=1; fi
    echo "$p $f $s"
}

# One suite (run by xargs below): LOGS, then one line "NAME<TAB>ARGV..."
# with the argument words separated by tabs. Writes LOGS/NAME.log, .time and
# .result ("P F S EXIT"), and prints the suite's line.
if [ "${1:-}" = --one ]; then
    logs=$2
    tab=$(printf '\t')
    old_ifs=$IFS
    IFS=$tab
    # shellcheck disable=SC2086 # the tab-separated words are the argv
    set -- $3
    IFS=$old_ifs
    name=$1
    shift
    log=$logs/$(logname "$name")
    case "$name" in
        sanitizer/*)
            ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
            UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
            export ASAN_OPTIONS UBSAN_OPTIONS ;;
    esac
    t0=$(now)
    "$@" >"$log.log" 2>&1 </dev/null
    st=$?
    secs=$(seconds "$t0" "$(now)")
    set -- $(count "$log.log" "$st")
    echo "$1 $2 $3 $st" >"$log.result"
    echo "$secs" >"$log.time"
    if [ "$2" -eq 0 ]; then word=ok; else word=FAILED; fi
    printf '%-40s %s (%s passed, %s failed, %s skipped, exit %s) %8s s\n' \
        "$name" "$word" "$1" "$2" "$3" "$st" "$secs"
    exit 0
fi

build=${1:-build}
logs=$build/test-logs
mkdir -p "$logs"
jobs=${CONICA_TEST_JOBS:-$(nproc 2>/dev/null || echo 2)}
case "$jobs" in ''|*[!0-9]*|0) echo "run-tests.sh: CONICA_TEST_JOBS must be a positive number" >&2; exit 2 ;; esac
suites_start=$(now)
tab=$(printf '\t')
queue=$logs/.queue
: >"$queue"

add() { # name argv...
    n=$1
    shift
    line=$n
    for w in "$@"; do line=$line$tab$w; done
    printf '%s\n' "$line" >>"$queue"
}

add_all() { # build-dir label
    for t in "$1"/tests/test_* "$1"/tests/cgal_*; do
        [ -x "$t" ] && [ -f "$t" ] || continue
        case "$t" in *.o|*.d|*.xml) continue ;; esac
        add "$2unit/$(basename "$t")" "$t"
    done
    for s in tests/cli/*.sh; do
        case "$(basename "$s")" in harness.sh) continue ;; esac
        if [ -n "$2" ]; then
            # The sanitizer pass repeats the suites that exercise our own
            # binaries. Left out: Blender loads its own build of the
            # extension (python_ext: the extension is built without them); the
            # fuzzers are sanitizer builds already; install
            # would relink without the sanitizer flags; the runner and
            # cgal_broken suites test the runner, not the library.
            case "$(basename "$s")" in
                blender.sh|python_ext.sh|cgal_broken.sh|runner.sh|fuzz_smoke.sh|install.sh) continue ;;
            esac
        fi
        add "$2cli/$(basename "$s" .sh)" sh "$s" "$1"
    done
}

add_all "$build" ""
[ -d "$build/san/tests" ] && add_all "$build/san" "sanitizer/"

# Longest first, so that no long suite starts last. Seconds per suite: the
# previous run's, else these (measured on 2 cores; any suite not named is
# taken as short).
slow='sanitizer/cli/scadprofile_region 110
cli/blender 74
sanitizer/cli/scadprofile_dxf 72
cli/scadprofile_dxf 69
cli/scadprofile_region 54
sanitizer/unit/test_path 52
cli/fuzz_smoke 49
sanitizer/cli/svgsmooth_fidelity 45
cli/svgsmooth_fidelity 42
sanitizer/cli/svg_render 39
cli/svg_render 27
sanitizer/cli/scadprofile_dims 24'
order=$logs/.order
while IFS= read -r line; do
    n=${line%%"$tab"*}
    tf=$logs/$(logname "$n").time
    if [ -f "$tf" ]; then
        secs=$(cat "$tf")
    else
        secs=$(printf '%s\n' "$slow" | awk -v n="$n" '$1 == n { print $2 }')
    fi
    printf '%s\t%s\n' "${secs:-1}" "$line"
done <"$queue" | sort -t "$tab" -k1,1 -g -r -s | cut -f2- >"$order"

# Stale results must not count: each suite writes its own anew.
while IFS= read -r line; do
    rm -f "$logs/$(logname "${line%%"$tab"*}").result"
done <"$order"

xargs -d '\n' -n 1 -P "$jobs" sh "$0" --one "$logs" <"$order"

total_pass=0 total_fail=0 total_skip=0
failed=""
while IFS= read -r line; do
    n=${line%%"$tab"*}
    r=$logs/$(logname "$n").result
    if [ -f "$r" ]; then
        read -r p f s st <"$r"
    else
        p=0 f=1 s=0 st=none  # the suite did not even finish
    fi
    total_pass=$((total_pass + p))
    total_fail=$((total_fail + f))
    total_skip=$((total_skip + s))
    [ "$f" -eq 0 ] || failed="$failed $n"
done <"$queue"

for n in $failed; do
    log=$logs/$(logname "$n").log
    echo "---- $n: $log ----"
    first=$(grep -n -m 1 'FAILED' "$log" 2>/dev/null | cut -d: -f1)
    if [ -n "$first" ]; then
        sed -n "${first},$((first + 30))p" "$log"
        echo "[...]"
    fi
    tail -n 15 "$log" 2>/dev/null
    echo "----"
done
[ -z "$failed" ] || echo "failed suites:$failed"

end=$(now)
echo "all suites: $(seconds "$suites_start" "$end") s ($jobs at a time)"
case "${CONICA_TEST_START:-}" in
    ''|*[!0-9]*) ;;
    *) echo "make test in all (builds and suites): $(seconds "$CONICA_TEST_START" "$end") s" ;;
esac
if [ "$total_skip" -ne 0 ]; then
    echo "$total_pass passed, $total_fail failed, $total_skip skipped"
else
    echo "$total_pass passed, $total_fail failed"
fi
[ "$total_fail" -eq 0 ]
