#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite for `conica plot` (README.md).
# usage (from the repository root): sh tests/cli/plot.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica
data=../shared/data/splines

# le A B: is the number A <= B?
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 <= b + 0) }'; }
lines() { grep -c . "$1"; }

# y = (2t - 1)^2 on [0, 1] as a quadratic spline function.
printf '# parabola\ndegree 2\nknots 0 0 0 1 1 1\nc 1\nc -1\nc 1\n' >"$tmp/parabola.spl"
# Two quadratic pieces that do not meet (knot of multiplicity p+1 = 3).
printf 'degree 2\nknots 0 0 0 1 1 1 2 2 2\nc 0 0\nc 1 1\nc 2 0\nc 3 0\nc 4 1\nc 5 0\n' \
    >"$tmp/jump.spl"
# A 3-D helix-like cubic.
printf 'degree 3\nknots 0 0 0 0 1 2 2 2 2\nc 1 0 0\nc 0 1 1\nc -1 0 2\nc 0 -1 3\nc 1 0 4\n' \
    >"$tmp/space.spl"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 1x\nc 2 0\n' >"$tmp/badnum.spl"
printf 'degree 2\nknots 0 0 0 1 1\nc 0 0\nc 1 1\nc 2 0\n' >"$tmp/badcount.spl"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 1\nc 2 0\nw 1 -1 1\n' >"$tmp/badweight.spl"

begin_case "conica plot is built and documented"
check_true "$conica exists" test -x "$conica"
check "--help" "$conica" plot --help
check_grep '^Usage: conica plot' "$out"
for opt in --method --criterion --rule --stop --knot-budget --curve-points --abs-tolerance \
    --tolerance --viewport --points --max-points --stats -o --prephase --local-weight --angle \
    --max-recursion; do
    check_grep " $opt" "$out" "help mentions $opt"
done

begin_case "guaranteed mode: vertices on the curve, every chord within the tolerance"
check "plot the parabola" "$conica" plot --method guaranteed --abs-tolerance 1e-3 "$tmp/parabola.spl"
cp "$out" "$tmp/par.txt"
# vertices on y = (2x-1)^2; the distance of the curve to each chord is the
# vertical gap (x1-x0)^2 over sqrt(1 + slope^2) (the tangent parallel to the
# chord touches at the middle); both directions of the Hausdorff distance.
worst=$(awk 'NF == 2 { y = (2*$1 - 1)^2; e = $2 - y; if (e < 0) e = -e; if (e > on) on = e
    if (n++) { h = $1 - x0; m = ($2 - y0) / h; d = h*h / sqrt(1 + m*m); if (d > w) w = d }
    x0 = $1; y0 = $2 }
    END { printf "%.17g %.17g %d\n", on, w, n }' "$tmp/par.txt")
set -- $worst
check_true "vertices on the curve ($1)" le "$1" 1e-12
check_true "chord deviation $2 <= 1e-3" le "$2" 1e-3
check_true "chords close to the tolerance (not wasteful: $2)" le 0.5e-3 "$2"
check_true "end points are the ends" test "$(head -n 1 "$tmp/par.txt")" = "0 1"
check_true "last point" test "$(tail -n 1 "$tmp/par.txt")" = "1 1"

begin_case "--stats prints the documented line"
check "stats" "$conica" plot --stats --abs-tolerance 1e-3 "$tmp/parabola.spl"
check_grep '^plot: [0-9]+ points, [0-9]+ knots inserted, [0-9]+ flops, [0-9.e+-]+ s$' "$err"
check "adaptive stats" "$conica" plot --method adaptive --stats "$tmp/parabola.spl"
check_grep '^plot: [0-9]+ points, [1-9][0-9]* knots inserted' "$err"

begin_case "pixel tolerance (eq. (3.26)) and viewport"
check "3 px default" "$conica" plot "$tmp/parabola.spl"
n3=$(lines "$out")
check "0.5 px on 1000x1000" "$conica" plot --tolerance 0.5 --viewport 1000x1000 "$tmp/parabola.spl"
n05=$(lines "$out")
check_true "tighter tolerance, more points ($n3 -> $n05)" test "$n05" -gt "$n3"
check "bigger viewport" "$conica" plot --tolerance 0.5 --viewport 4000x4000 "$tmp/parabola.spl"
check_true "bigger viewport, more points" test "$(lines "$out")" -gt "$n05"

begin_case "pieces split at discontinuities are separated by a blank line"
check "jump" "$conica" plot --abs-tolerance 1e-2 "$tmp/jump.spl"
check_count 1 '^$' "$out" "one blank line"
check "3-D" "$conica" plot --abs-tolerance 1e-2 "$tmp/space.spl"
check_count 0 '^[^ ]+ [^ ]+$' "$out" "three columns"
check_grep '^[^ ]+ [^ ]+ [^ ]+$' "$out"

begin_case "every method, criterion and rule runs"
for m in guaranteed adaptive uniform local-uniform chaikin lane-riesenfeld mathematica; do
    check "method $m" "$conica" plot --method "$m" "$tmp/space.spl"
done
for c in simplified-length length length-ratio simplified-angle angle base-line extended-base-line; do
    for r in midpoint knot-average chaikin; do
        check "adaptive $c $r" "$conica" plot --method adaptive --criterion "$c" --rule "$r" \
            --knot-budget 50 --stats "$tmp/space.spl"
    done
done
for w in length angle both; do
    check "local-uniform $w" "$conica" plot --method local-uniform --local-weight "$w" "$tmp/space.spl"
done
check "mathematica, no recursion" "$conica" plot --method mathematica --points 12 --max-recursion 0 \
    "$tmp/parabola.spl"
check_true "12 points" test "$(lines "$out")" -eq 12
check "mathematica, 2 degrees" "$conica" plot --method mathematica --points 12 --angle 2 \
    "$tmp/parabola.spl"
check_true "refined" test "$(lines "$out")" -gt 12
check "prephase" "$conica" plot --method adaptive --prephase 20 --stop budget --knot-budget 0 \
    --stats "$tmp/parabola.spl"
check_grep '^plot: 23 points, 20 knots inserted' "$err"
check "uniform N" "$conica" plot --method uniform --points 37 "$tmp/parabola.spl"
check_true "37 points" test "$(lines "$out")" -eq 37
check "budget stop" "$conica" plot --method adaptive --stop budget --knot-budget 25 --stats \
    "$tmp/parabola.spl"
check_grep '^plot: 28 points, 25 knots inserted' "$err"

begin_case "thesis test curves"
if [ -d "$data" ]; then
    for f in sptest0 sptest1 sptest2 sptest3 sptest4; do
        check "$f" "$conica" plot --tolerance 0.5 --stats "$data/$f.spl"
        check_grep '^plot: ' "$err"
    done
    check "sptest4 is one piece (C0 joins)" "$conica" plot "$data/sptest4.spl"
    check_count 0 '^$' "$out"
else
    skip_case "../shared/data not found"
fi

begin_case "output file, stdin"
check "-o" "$conica" plot --abs-tolerance 1e-2 -o "$tmp/o.txt" "$tmp/parabola.spl"
check_true "written" test -s "$tmp/o.txt"
check "stdin" sh -c "\"$conica\" plot --abs-tolerance 1e-2 - < \"$tmp/parabola.spl\""
check_true "same output" cmp -s "$out" "$tmp/o.txt"

begin_case "errors: file:line, exit 1, nothing written"
check_exit 1 "bad number" "$conica" plot -o "$tmp/e1.txt" "$tmp/badnum.spl"
check_grep "^conica: error: $tmp/badnum.spl:4: " "$err"
check_true "no output file" test ! -e "$tmp/e1.txt"
check_exit 1 "knot count" "$conica" plot -o "$tmp/e2.txt" "$tmp/badcount.spl"
check_grep "badcount.spl:2: " "$err"
check_exit 1 "weight" "$conica" plot "$tmp/badweight.spl"
check_grep "badweight.spl:6: " "$err"
check_exit 1 "missing file" "$conica" plot "$tmp/nonexistent.spl"
check_exit 1 "output cap" "$conica" plot --abs-tolerance 1e-9 --max-points 10 -o "$tmp/e3.txt" \
    "$tmp/parabola.spl"
check_grep "max_points" "$err"
check_true "no output file" test ! -e "$tmp/e3.txt"

begin_case "usage errors exit 2"
check_exit 2 "unknown method" "$conica" plot --method nope "$tmp/parabola.spl"
check_exit 2 "both tolerances" "$conica" plot --abs-tolerance 1 --tolerance 1 "$tmp/parabola.spl"
check_exit 2 "bad viewport" "$conica" plot --viewport 100 "$tmp/parabola.spl"
check_exit 2 "bad tolerance" "$conica" plot --abs-tolerance -1 "$tmp/parabola.spl"
check_exit 2 "no input" "$conica" plot
check_exit 2 "unknown option" "$conica" plot --frobnicate "$tmp/parabola.spl"

finish
