#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/reliability_table.sh BUILD_DIR - the "input -> behaviour" table
# of README.md, row by row: each tool on an empty file, a file of
# the wrong format, NaN, one point, duplicate points, bad path data and a
# point at 1e300. Exit status and message must be what the table says.
# The table's other rows are asserted by their own suites: huge level in
# limits.sh, hostile XML in hostile_xml.sh, unwritable output in
# no_data_lost.sh.
set -u
. "$(dirname "$0")/harness.sh"
case $build in /*) b=$build ;; *) b=$(pwd)/$build ;; esac
conica=$b/bin/conica
svgsmooth=$b/bin/svgsmooth
scad=$b/bin/scadprofile

cd "$tmp" || exit 1
: >empty.txt
: >empty.svg
: >empty.spl
printf 'hello world\n' >garbage.txt
cp garbage.txt garbage.svg
printf 'degree x\n' >garbage.spl
printf 'v 0 0\nv 1 nan\nv 2 0\n' >nan.txt
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 nan\nc 2 0\n' >nan.spl
printf 'v 0 0\n' >one.txt
printf 'v 0 0\nv 1 0\nv 1 0\nv 0 1\n' >dup.txt
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 10L0 10L0 5L5 5Z M 3 x"/></svg>\n' >badpath.svg
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 nan"/></svg>\n' >nanpath.svg
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L0 0L0 0Z"/></svg>\n' >dupsvg.svg
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M1 1Z"/></svg>\n' >onesvg.svg

# row STATUS PATTERN CMD...: exit status and a stderr line.
row() {
    r_want=$1 r_pat=$2
    shift 2
    check_exit "$r_want" "$*: exit $r_want" "$@"
    check_grep "$r_pat" "$err" "$*: /$r_pat/"
}

begin_case "empty file"
row 1 "conica: error: empty.txt: no 'v x y' lines: the input has no points" "$conica" subdivide empty.txt
row 1 "no 'v x y' lines" "$conica" combs empty.txt
row 1 "no 'v x y' lines" "$conica" errors empty.txt
row 1 'svgsmooth: error: empty.svg:1: XML: ' "$svgsmooth" empty.svg
row 1 "scadprofile: error: empty.txt: no 'v x y' lines" "$scad" empty.txt
row 1 "scadprofile: error: empty.spl:1: missing 'degree' line" "$scad" empty.spl
row 1 'scadprofile: error: empty.svg:1: XML: ' "$scad" empty.svg

begin_case "not the format"
row 1 "garbage.txt:1: unknown line starting with 'hello'" "$conica" subdivide garbage.txt
row 1 "garbage.txt:1: unknown line starting with 'hello'" "$conica" combs garbage.txt
row 1 "garbage.txt:1: unknown line starting with 'hello'" "$conica" errors garbage.txt
row 1 'svgsmooth: error: garbage.svg:1: XML: Document is empty' "$svgsmooth" garbage.svg
row 1 "scadprofile: error: garbage.spl:1: bad number 'x'" "$scad" garbage.spl

begin_case "NaN"
row 1 "nan.txt:2: 'nan' is not a finite number" "$conica" subdivide nan.txt
row 1 "nan.txt:2: 'nan' is not a finite number" "$conica" combs nan.txt
row 1 "nan.txt:2: 'nan' is not a finite number" "$scad" nan.txt
row 1 "nan.spl:4: non-finite number 'nan'" "$scad" nan.spl
row 0 'warning: nanpath.svg:1: .*number is not finite; the valid part before it is kept' \
    "$svgsmooth" nanpath.svg
row 1 'has 2 points' "$scad" nanpath.svg

begin_case "one point"
row 1 'one.txt: a closed curve needs at least 3 points \(got 1\)' "$conica" subdivide one.txt
row 1 'one.txt: an open curve needs at least 2 points \(got 1\)' "$conica" subdivide --open one.txt
row 1 'conica: error: one\.txt: subdivision failed: a closed curve needs at least 3 points \(got 1\)' \
    "$conica" combs one.txt
# errors subdivides level by level and names the level that failed
row 1 'conica: error: one\.txt: subdivision to level 0 failed: a closed curve needs at least 3 points \(got 1\)' \
    "$conica" errors one.txt
row 1 'one.txt: a profile needs at least 3 points, the file has 1' "$scad" one.txt
row 1 'has 1 point \(a polygon needs 3\)' "$scad" onesvg.svg
check "svgsmooth writes a one-point path back" "$svgsmooth" onesvg.svg
check_grep 'd="M1 1Z"' "$out"

begin_case "duplicate points"
row 1 'dup.txt:2: points 1 and 2 coincide \(an edge of zero length\)' "$conica" subdivide dup.txt
row 1 'conica: error: dup\.txt: subdivision failed: points 1 and 2 coincide \(an edge of zero length\)' \
    "$conica" combs dup.txt
row 1 'conica: error: dup\.txt: subdivision to level 0 failed: points 1 and 2 coincide' \
    "$conica" errors dup.txt
row 1 'scadprofile: error: dup\.txt(:2)?: points 1 and 2 coincide' "$scad" dup.txt
check "svgsmooth merges consecutive duplicates" "$svgsmooth" dupsvg.svg
check_grep 'd="M0 0Z"' "$out"

begin_case "bad path data: warning, valid prefix kept"
row 0 'warning: badpath.svg:1: path \(no id\): bad path data at byte 34: expected a number; the valid part before it is kept' \
    "$svgsmooth" badpath.svg
check_grep '<path d="M' "$out"
row 0 'bad path data at byte 34' "$scad" badpath.svg
check_grep '^module badpath\(center=false\)' "$out"

begin_case "a point at 1e300 among ordinary ones ends in bounded time"
if ! command -v timeout >/dev/null 2>&1; then
    skip_case "no timeout(1)"
else
    printf 'v 10 0\nv 7.0710678118654755 7.071067811865475\nv 0 10\nv -7.071067811865475 7.0710678118654755\nv -10 0\nv 1e300 -7.071067811865477\nv 0 -10\nv 7.071067811865474 -7.071067811865477\n' >far.txt
    # found by fuzz_subdivide: LAPACK's dgesvd never returned on the
    # non-finite patch matrix this point produced (exit 124 = timed out).
    # An answer is either finite points (exit 0) or an error naming the
    # non-finite point (exit 1, nothing written).
    for c in subdivide combs errors; do
        rm -f far.out
        if [ "$c" = errors ]; then # a table on stdout
            h_run timeout 20 "$conica" errors -k 3 far.txt
            st=$?
            [ -s "$out" ] && cp "$out" far.out
        else
            h_run timeout 20 "$conica" "$c" -k 3 -o far.out far.txt
            st=$?
        fi
        check_true "conica $c -k 3 answers within 20 s with exit 0 or 1 (got $st)" test "$st" -le 1
        if [ "$st" -eq 1 ]; then
            check_grep 'far\.txt(:[0-9]+)?: .*point [0-9]+ of the output is not finite' "$err" \
                "conica $c: the error names the non-finite point"
            check_true "conica $c: nothing written" test ! -e far.out
        elif [ "$st" -eq 0 ]; then
            check_no_grep '[nN]a[nN]|[iI]nf' far.out "conica $c: no NaN/Inf written"
        fi
    done
fi

begin_case "an empty output name is a usage error in every tool"
row 2 "^conica subdivide: usage error: -o needs a file name" "$conica" subdivide -o '' one.txt
row 2 "^conica plot: usage error: -o needs a file name" "$conica" plot -o '' nan.spl
row 2 "^conica combs: usage error: -o needs a file name" "$conica" combs -o '' one.txt
row 2 "^conica errors: usage error: --plot needs a file name" "$conica" errors --plot '' one.txt
row 2 "^svgsmooth: usage error: -o needs a file name" "$svgsmooth" -o '' badpath.svg
row 2 "^scadprofile: usage error: -o needs a file name" "$scad" -o '' one.txt

begin_case "conica errors: a conic without a gradient is an error, not inf"
printf 'v 3 0\nv 0 2\nv -3 0\nv 0 -2\n' >ell.txt
row 2 "^conica errors: usage error: --conic '0,0,0,0,0,0' is not a curve" \
    "$conica" errors --conic 0,0,0,0,0,0 ell.txt
check_true "no table on stdout" test ! -s "$out"
row 2 "is not a curve" "$conica" errors --conic 0,0,0,0,0,7 ell.txt
check "a real conic still measures" "$conica" errors -k 2 --conic 0.1111111111111111,0.25,0,0,0,-1 ell.txt
check_no_grep 'inf|nan' "$out" "finite conic errors"

begin_case "a coordinate near DBL_MAX on a v line: the line is named"
# The subdivision once failed here (the inflection point computed next to
# the far point overflowed: "coordinate 1e+308 of point 6 is too large for
# the subdivision"); the turns next to it are within its rounding, so none
# is inserted, and the subdivision keeps every input point bit for bit.
printf 'v 10 0\nv 7.0710678118654755 7.071067811865475\nv 0 10\nv -7.071067811865475 7.0710678118654755\nv -10 0\nv 1e308 -7.071067811865477\nv 0 -10\nv 7.071067811865474 -7.071067811865477\n' >far308.txt
check "conica subdivides it" "$conica" subdivide -k 3 -o far.out far308.txt
check_count 64 '^v ' far.out
check_grep '^v 1e\+308 -7\.071067811865477' far.out "the far point is kept as it was"
check_no_grep 'inf|nan' far.out "every output value finite"
row 1 "^scadprofile: error: far308\.txt:6: point 6 \(1e\+308, -7\.071067811865477\) is out of range" \
    "$scad" --levels 3 -o far.scad far308.txt

begin_case "NaN geometry attributes in shapes: not a number, not 'units'"
printf '<svg xmlns="http://www.w3.org/2000/svg"><rect id="r" width="NaN" height="5"/><circle id="c" cx="0" cy="0" r="1e999"/></svg>\n' >nanshape.svg
check "svgsmooth --convert-shapes keeps them (exit 0)" "$svgsmooth" --convert-shapes -o nanshape.out nanshape.svg
check_grep "^svgsmooth: warning: nanshape\.svg:1: rect 'r': geometry attribute 'width' is not a finite number" "$err"
check_grep "circle 'c': geometry attribute 'r' is not a finite number" "$err"
check_no_grep 'units other than user units' "$err"

begin_case "spline values near DBL_MAX: too large, not 'tolerance is zero'"
printf 'degree 2\nknots 0 0 0 1 1 1\nc -1e308 0\nc 1e308 1\nc 2 0\n' >huge.spl
row 1 "^conica: error: huge\.spl: the control point values are too large" "$conica" plot huge.spl
check_no_grep 'tolerance is zero' "$err"

begin_case "conica plot: hostile numbers give finite points or an error"
if ! "$conica" plot --help >/dev/null 2>&1; then
    skip_case "this conica has no plot command"
else
    # found by fuzz_plot: denormal weights made uniform/mathematica print
    # `-nan -nan` with exit 0; knots near 1e308 overflowed the per-piece
    # point share (plot_baselines.c share(): NaN/Inf cast to size_t, UB)
    printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 1\nc 2 0\nw 1e-320 1 1e-320\n' >tinyw.spl
    printf 'degree 2\nknots 0 0 0 1e308 1.7e308 1.7e308 1.7e308\nc 0 0\nc 1 1\nc 2 0\nc 3 1\n' >bigknots.spl
    for f in tinyw bigknots; do
        for m in guaranteed adaptive uniform local-uniform chaikin lane-riesenfeld mathematica; do
            h_run "$conica" plot --method "$m" $f.spl
            st=$?
            check_true "$f.spl --method $m: exit 0 or 1 (got $st)" test "$st" -le 1
            check_no_grep '[nN]a[nN]|inf' "$out" "$f.spl --method $m: no NaN/Inf in the points"
            check_no_grep 'runtime error' "$err" "$f.spl --method $m: no undefined behaviour"
        done
    done
fi

finish
