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
finish
