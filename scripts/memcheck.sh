#!/bin/sh
# SPDX-License-Identifier: MIT
# scripts/memcheck.sh [BUILD] [SUITE...] - valgrind memcheck over the
# command-line tools (make memcheck). Two parts:
#
# 1. A representative set of invocations -- conica subdivide/combs/errors/
#    plot, svgsmooth and scadprofile on examples/ and generated inputs,
#    success and error paths -- each run under
#        valgrind -q --error-exitcode=99 --leak-check=full
#                 --errors-for-leak-kinds=definite,possible
#    Valgrind's exit status 99 is kept apart from the tools' own 1 (error)
#    and 2 (usage), so a leak or an invalid access on an error path cannot
#    hide behind an expected exit 1. A run passes when the status is the
#    expected one (never 99) and the log has no error report.
# 2. CLI test suites (tests/cli/SUITE.sh; default: MEMCHECK_SUITES below)
#    with CONICA_WRAP set, so the harness runs every invocation of a tool
#    in BUILD/bin under the same valgrind command (see tests/cli/harness.sh):
#    each such run must end without valgrind errors, and the suite's own
#    assertions must pass as they do without valgrind.
#
# Not part of `make test` (valgrind makes the tools 20-50x slower); CI can
# run a subset: `sh scripts/memcheck.sh build limits` runs part 1 and one
# suite. MEMCHECK_SUITES=none skips part 2. Logs: BUILD/memcheck/.
set -u
build=${1:-build}
[ $# -gt 0 ] && shift
# Suites of part 2: every suite of our own binaries that runs in minutes
# under valgrind (fuzz_smoke runs sanitizer builds; blender, install,
# runner, cgal_broken test other programs).
suites=${*:-${MEMCHECK_SUITES:-subdivide combs plot svgsmooth scadprofile limits no_data_lost hostile_xml reliability_table}}
[ "$suites" = none ] && suites=
VG="valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,possible"
# Assertions that fail under valgrind for a documented valgrind limitation,
# not a memory error: valgrind computes x87 long double in 64-bit double
# precision (valgrind manual, "Limitations"), so accuracy bounds that rely
# on the long double steps of the subdivision are looser under it (combs.sh
# on a circle about (100,-50): E_max 5.2e-14 natively, 1.3e-13 under
# valgrind). Such a failure is listed, not counted; every other failed
# assertion of a suite fails memcheck. One description per line.
VG_NUMERIC="E_max below 1e-13 at every level"
bin=$build/bin
logs=$build/memcheck
mkdir -p "$logs"
rm -f "$logs"/*.log
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-memcheck.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
if ! command -v valgrind >/dev/null 2>&1; then
    echo "memcheck: valgrind is not installed (scripts/deps.sh test installs it)"
    exit 1
fi
pass=0 fail=0 i=0

# run EXPECTED_EXIT NAME CMD...
run() {
    want=$1 name=$2
    shift 2
    i=$((i + 1))
    log=$logs/$(printf '%02d' "$i")-$name.log
    $VG --log-file="$log" "$@" >"$tmp/out" 2>"$tmp/err" </dev/null
    st=$?
    # -q logs nothing but errors: any report (Invalid read/write/free,
    # uninitialised value, a definitely/possibly lost record, ...) fails.
    if [ "$st" -eq "$want" ] && [ "$st" -ne 99 ] && ! grep -q -E \
        'ERROR SUMMARY: [1-9]|(definitely|possibly) lost|Invalid (read|write|free)|uninitialised|Mismatched free|overlap|[Ff]ishy|Syscall param|Conditional jump' \
        "$log"; then
        pass=$((pass + 1))
        printf 'ok    %-28s exit %s\n' "$name" "$st"
    else
        fail=$((fail + 1))
        printf 'FAIL  %-28s exit %s (expected %s), log %s\n' "$name" "$st" "$want" "$log"
        sed 's/^/      /' "$log" | head -n 30
        sed 's/^/      stderr: /' "$tmp/err" | head -n 5
    fi
}

ex=examples
# generated inputs
awk 'BEGIN { for (i = 0; i < 12; i++) { a = 6.283185307179586 * i / 12;
      printf "v %.17g %.17g\n", 3 * cos(a), 2 * sin(a) } }' >"$tmp/ellipse12.txt"
printf 'v 0 0\nv 1 nan\nv 2 0\n' >"$tmp/nan.txt"
printf 'v 0 0\n' >"$tmp/one.txt"
printf 'v 0 0\nv 0 0\nv 0 0\nv 0 0\n' >"$tmp/dup.txt"
printf 'hello world\n' >"$tmp/garbage.txt"
: >"$tmp/empty.txt"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L10 0 L 10 x"/></svg>\n' >"$tmp/badpath.svg"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n<svg xmlns="http://www.w3.org/2000/svg"><text>&x;</text></svg>\n' >"$tmp/xxe.svg"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0' >"$tmp/truncated.svg"
printf 'degree 2\nknots 0 0 0 1 2 3 3 3\nc 0 0\nc 4 0\nc 6 3\nc 3 6\nc 0 3\n' >"$tmp/open.spl"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 nan\n' >"$tmp/bad.spl"

c=$bin/conica
run 0 subdivide-ellipse "$c" subdivide -k 4 -o "$tmp/o.txt" "$ex/ellipse.txt"
run 0 subdivide-precise "$c" subdivide -k 3 --precise "$ex/flower.txt"
run 0 subdivide-open "$c" subdivide -k 3 --open "$ex/parabola_open.txt"
run 0 subdivide-estimate "$c" subdivide -k 3 --estimate-normals --normals circle "$tmp/ellipse12.txt"
run 0 subdivide-threads "$c" subdivide -k 4 --threads 2 "$ex/flower.txt"
run 0 subdivide-refcompat "$c" subdivide -k 2 --reference-compatible "$tmp/ellipse12.txt"
run 1 subdivide-nan "$c" subdivide -k 2 "$tmp/nan.txt"
run 1 subdivide-one-point "$c" subdivide -k 2 "$tmp/one.txt"
run 1 subdivide-duplicates "$c" subdivide -k 2 "$tmp/dup.txt"
run 1 subdivide-garbage "$c" subdivide "$tmp/garbage.txt"
run 1 subdivide-empty "$c" subdivide "$tmp/empty.txt"
run 1 subdivide-max-points "$c" subdivide -k 10 --max-points 100 "$ex/ellipse.txt"
run 1 subdivide-missing "$c" subdivide "$tmp/does-not-exist.txt"
run 1 subdivide-unwritable "$c" subdivide -k 1 -o "$tmp/no/such/dir/o.txt" "$ex/ellipse.txt"
run 2 subdivide-usage "$c" subdivide --levels 99 "$ex/ellipse.txt"
run 0 combs "$c" combs -k 3 -o "$tmp/c.svg" "$ex/flower.txt"
run 1 combs-nan "$c" combs -k 3 "$tmp/nan.txt"
run 0 errors "$c" errors -k 4 --conic 1,1,0,0,0,-25 --plot "$tmp/e.svg" "$ex/ellipse.txt"
run 1 errors-garbage "$c" errors "$tmp/garbage.txt"
if "$c" plot --help >/dev/null 2>&1; then
    run 0 plot-spline "$c" plot -o "$tmp/p.txt" "$tmp/open.spl"
    run 1 plot-bad-spline "$c" plot "$tmp/bad.spl"
fi

s=$bin/svgsmooth
run 0 svgsmooth-leaf "$s" --levels 3 -o "$tmp/leaf.svg" "$ex/traced-leaf.svg"
run 0 svgsmooth-flatten "$s" --flatten --tolerance 0.1 --convert-shapes "$ex/icon-arcs.svg"
run 0 svgsmooth-tolerance "$s" --tolerance 0.05 "$ex/letter-R.svg"
cp "$ex/rect-star.svg" "$tmp/inplace.svg"
run 0 svgsmooth-in-place "$s" --levels 2 --in-place "$tmp/inplace.svg"
run 0 svgsmooth-badpath "$s" "$tmp/badpath.svg"
run 1 svgsmooth-xxe "$s" "$tmp/xxe.svg"
run 1 svgsmooth-truncated "$s" "$tmp/truncated.svg"
run 1 svgsmooth-not-svg "$s" "$tmp/garbage.txt"
run 1 svgsmooth-max-points "$s" --levels 8 --max-points 100 "$ex/traced-leaf.svg"
run 1 svgsmooth-unwritable "$s" -o "$tmp/no/such/dir/o.svg" "$ex/traced-leaf.svg"

p=$bin/scadprofile
run 0 scadprofile-svg "$p" --extrude 5 -o "$tmp/b.scad" "$ex/bracket.svg"
run 0 scadprofile-points "$p" --tolerance 0.01 "$ex/ellipse.txt"
run 0 scadprofile-levels-force "$p" --levels 3 --force --rotate-extrude "$ex/flower.txt"
run 0 scadprofile-spline "$p" --tolerance 0.01 "$tmp/open.spl"
run 1 scadprofile-nan "$p" "$tmp/nan.txt"
run 1 scadprofile-xxe "$p" "$tmp/xxe.svg"
run 1 scadprofile-bad-spline "$p" "$tmp/bad.spl"
run 1 scadprofile-empty "$p" "$tmp/empty.txt"
run 1 scadprofile-unwritable "$p" -o "$tmp/no/such/dir/o.scad" "$ex/ellipse.txt"

echo "memcheck: $pass passed, $fail failed (valgrind logs in $logs)"

# Part 2: CLI suites, every tool invocation under valgrind.
s_runs=0 s_errs=0 s_fail=0 s_n=0
for suite in $suites; do
    s_n=$((s_n + 1))
    slog=$logs/suite-$suite.log
    CONICA_WRAP="$VG --log-file=@LOG@" sh "tests/cli/$suite.sh" "$build" >"$slog" 2>&1
    sst=$?
    w=$(sed -n 's/^wrapped: \([0-9]*\) runs, \([0-9]*\) with errors$/\1 \2/p' "$slog" | tail -n 1)
    r=${w% *} e=${w#* }
    summary=$(grep -E '^(All tests passed|test cases:|assertions:)' "$slog" | tr '\n' ' ')
    if [ -z "$w" ]; then r=0 e=0; fi
    s_runs=$((s_runs + r))
    s_errs=$((s_errs + e))
    # descriptions of the failed assertions: the line after each FAILED:
    awk '/: FAILED:$/ { getline; sub(/^  /, ""); print }' "$slog" >"$tmp/failed"
    grep -v -x -F "$VG_NUMERIC" "$tmp/failed" >"$tmp/real" || :
    nreal=$(grep -c . "$tmp/real")
    nnum=$(($(grep -c . "$tmp/failed") - nreal))
    if [ "$e" -ne 0 ] || [ -z "$w" ] || [ "$nreal" -ne 0 ] ||
        { [ "$sst" -ne 0 ] && [ "$nnum" -eq 0 ]; }; then
        s_fail=$((s_fail + 1))
        printf 'FAIL  suite %-20s %s runs under valgrind, %s with errors, exit %s: %s(log %s)\n' \
            "$suite" "$r" "$e" "$sst" "$summary" "$slog"
        grep -A 12 'FAILED:' "$slog" | head -n 60 | sed 's/^/      /'
    else
        printf 'ok    suite %-20s %s runs under valgrind, 0 with errors: %s\n' "$suite" "$r" "$summary"
        if [ "$nnum" -ne 0 ]; then
            printf '      (%s assertion(s) looser under valgrind'"'"'s 64-bit long double, not counted: %s)\n' \
                "$nnum" "$(tr '\n' ';' <"$tmp/failed")"
        fi
    fi
done
if [ "$s_n" -gt 0 ]; then
    echo "memcheck suites: $s_n suites, $s_runs tool runs under valgrind, $s_errs with valgrind errors, $s_fail suites failed"
fi
[ "$fail" -eq 0 ] && [ "$s_fail" -eq 0 ]
