#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/scaling.sh BUILD_DIR - work that grows with a user-given size
# stays near-linear (issue 17, docs/reliability.md). Each run is bounded
# by a CPU-time limit (ulimit -t, not wall time) set far above what it
# takes now and far below what the quadratic code took, and its result is
# checked as well:
#   conica plot --method adaptive --stop budget --knot-budget 300000:
#     about 1 s now (3 s under the sanitizers); the arrays of before took
#     an estimated 57 s (9.1 s at 120 000 knots, growing as the square);
#   scadprofile --force on 80 000 small overlapping triangles: about 1 s
#     now; the pairwise arrangement took 40.7 s.
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica
scad=$build/bin/scadprofile

# capped SECONDS CMD...: run CMD under `ulimit -t SECONDS`.
capped() {
    c_s=$1
    shift
    sh -c 'ulimit -t "$1" && shift && exec "$@"' sh "$c_s" "$@"
}

begin_case "adaptive plotter: 300 000 knots by budget within 30 CPU seconds"
check "the run ends (a CPU limit kills it with SIGXCPU otherwise)" \
    capped 30 "$conica" plot --method adaptive --stop budget --knot-budget 300000 \
    -o "$tmp/p.txt" examples/s-curve.spl
# 10 control points + 300 000 knots = 300 010 vertices of the control polygon
check_true "300010 points written" test "$(wc -l <"$tmp/p.txt")" -eq 300010
check_no_grep 'nan|inf' "$tmp/p.txt" "finite points"
rm -f "$tmp/p.txt"

begin_case "scadprofile --force: 80 000 overlapping paths within 20 CPU seconds"
awk 'BEGIN {
    srand(1)
    print "<svg xmlns=\"http://www.w3.org/2000/svg\">"
    for (i = 0; i < 80000; i++) {
        x = rand() * 100; y = rand() * 100
        printf "<path d=\"M%.3f %.3fL%.3f %.3fL%.3f %.3fZ\"/>\n", x, y, x + 2, y, x + 1, y + 2
    }
    print "</svg>" }' >"$tmp/many.svg"
check "the run ends" capped 20 "$scad" --force --levels 0 -o "$tmp/many.scad" "$tmp/many.svg"
check_grep '^module many\(' "$tmp/many.scad" "the module (named after the file) is written"
check_exit 1 "exit 1 (contours meet)" capped 20 "$scad" --levels 0 -o "$tmp/x.scad" "$tmp/many.svg"
check_grep 'meet' "$err" "the crossing is named"

# issue 33: every interior knot a corner (multiplicity = degree) was
# quadratic: 100 000 control points of degree 1 took 64.5 s with --method
# uniform and 2.8 s by default; a 40 000-piece cubic Bezier chain 1.5 s
# (plot) and 2.9 s (scadprofile). Linear now: well under a second each.
begin_case "100 000 corner knots (degree 1) and a 40 000-piece Bezier chain within 10 CPU seconds"
awk 'BEGIN { n = 100000
    print "degree 1"; printf "knots 0 0"
    for (i = 1; i < n - 1; i++) printf " %d", i
    printf " %d %d\n", n - 1, n - 1
    for (i = 0; i < n; i++) printf "c %d %d\n", i, i % 2 }' >"$tmp/corners.spl"
check "--method uniform: the run ends" capped 10 "$conica" plot --method uniform --points 200000 \
    -o "$tmp/c.txt" "$tmp/corners.spl"
check "default method: the run ends" capped 10 "$conica" plot -o "$tmp/c.txt" "$tmp/corners.spl"
check_true "every control point is a plotted point" test "$(wc -l <"$tmp/c.txt")" -ge 100000
awk 'BEGIN { n = 40000; pi = 3.14159265358979
    print "degree 3"; printf "knots 0 0 0 0"
    for (i = 1; i < n; i++) printf " %d %d %d", i, i, i
    printf " %d %d %d %d\n", n, n, n, n
    for (i = 0; i <= 3 * n; i++) { a = 2 * pi * i / (3 * n); r = 1 + 0.1 * sin(7 * a)
        printf "c %.17g %.17g\n", r * cos(a), r * sin(a) } }' >"$tmp/chain.spl"
check "cubic chain: conica plot ends" capped 10 "$conica" plot -o "$tmp/c.txt" "$tmp/chain.spl"
check "cubic chain: scadprofile ends" capped 10 "$scad" -o "$tmp/chain.scad" "$tmp/chain.spl"
rm -f "$tmp/c.txt" "$tmp/corners.spl" "$tmp/chain.spl"
finish
