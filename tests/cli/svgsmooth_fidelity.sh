#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth within its stated tolerance, measured by build/tests/svgcheck
# (tests/svgcheck/svgcheck.c: path data read and distances measured with
# no svgsmooth or libcore code, dense samples both ways refined by golden
# section): the six reproductions of issue 32 and the icons vendored under
# tests/data/icons/ (from npm, each set with its licence), in every mode.
# usage (from the repository root): sh tests/cli/svgsmooth_fidelity.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth
svgcheck=$build/tests/svgcheck
# the sanitizer pass (BUILD/san) measures its svgsmooth with the normal
# build's checker: the checker is not what is under test
[ -x "$svgcheck" ] || svgcheck=${build%/san}/tests/svgcheck

# within MODE-ARGS -- CHECK-ARGS -- IN: svgsmooth IN with MODE-ARGS, then
# svgcheck: every subpath within the tolerance both ways, closed subpaths
# start (and open ones start and end) where drawn, every corner a vertex,
# no new crossing between subpaths.
within() {
    w_opt=
    while [ "$1" != -- ]; do w_opt="$w_opt $1"; shift; done
    shift
    w_chk=
    while [ "$1" != -- ]; do w_chk="$w_chk $1"; shift; done
    shift
    # shellcheck disable=SC2086
    check "svgsmooth$w_opt $(basename "$1")" "$svgsmooth" $w_opt -o "$tmp/w.svg" "$1"
    # shellcheck disable=SC2086
    check "svgcheck$w_chk" "$svgcheck" $w_chk "$1" "$tmp/w.svg"
    check_grep '^ratio=(0\.[0-9]+|1\.0000) over=0 subpaths=[0-9]+ starts=0 corners=0/[0-9]+ crossings=0 ' \
        "$out" "$(basename "$1")$w_opt: $(cat "$out")"
}

svg() { printf '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><path d="%s"/></svg>\n' "$1" >"$2"; }

begin_case "the checker sees what the old output got wrong (it can fail)"
[ -x "$svgcheck" ] || skip_case "$svgcheck not built (make tests)"
svg 'M6.588 6.603c-2.178 .547 -3.588 1.417 -3.588 2.397c0 1.657 4.03 3 9 3' "$tmp/r1.svg"
# the 4.69x output of before, as written then
svg 'M6.588 6.603L6.318356 6.673435 6.050166 6.74922 5.78367 6.830777 5.519174 6.918607 5.256968 7.013345 4.997635 7.115684 4.741796 7.226519 4.490324 7.346936 4.236447 7.482814 3.99033 7.632287 3.754592 7.797904 3.533585 7.982721 3.330127 8.195205 3.160747 8.435737 3.042994 8.70722 3 9 3.201792 9.631678 3.650589 10.11986 4.18504 10.48795 4.762847 10.78336 5.344795 11.01957 5.94062 11.2182 6.545586 11.38629 7.157117 11.52865 7.75518 11.64536 8.356622 11.74319 8.960597 11.82375 9.566497 11.88825 10.17372 11.93759 10.78195 11.9724 11.39082 11.99312 12 12' "$tmp/r1.old.svg"
check "svgcheck on the old output" "$svgcheck" "$tmp/r1.svg" "$tmp/r1.old.svg"
check_grep '^ratio=4\.[0-9]+ over=1 ' "$out" "4.7 times the tolerance: $(cat "$out")"

begin_case "1. smoothing: the chords written stay within the tolerance at every level"
for lev in 1 2 3 4 5 6 8; do
    within --levels $lev -- -- "$tmp/r1.svg"
done
within --tolerance 0.05 -- -- "$tmp/r1.svg"

begin_case "2. flattening: a hook's tip beyond the chord end counts"
svg 'M0 0Q4 0 5 0.05Q6 0.1 5 0.15Q4 0.2 0 0.2L20 5' "$tmp/r2.svg"
within --flatten --tolerance 0.1 -- --tol 0.1 -- "$tmp/r2.svg"
within --flatten --tolerance 0.02 -- --tol 0.02 -- "$tmp/r2.svg"
within -- -- "$tmp/r2.svg"

begin_case "3. a spike (a cubic whose ends coincide) keeps its extent in every mode"
svg 'M10 10c4 -4 -4 4 0 0' "$tmp/r3.svg"
within -- -- "$tmp/r3.svg"
within --levels 2 -- -- "$tmp/r3.svg"
within --flatten --tolerance 0.01 -- --tol 0.01 -- "$tmp/r3.svg"
svg 'M0 0L5 0c4 -4 -4 4 0 0L5 5' "$tmp/r3b.svg"
within --flatten --tolerance 0.01 -- --tol 0.01 -- "$tmp/r3b.svg"

begin_case "4. written digits follow from the tolerance (coordinates of 1000 and more)"
svg 'M1000 1000Q1500 0 2000 1000' "$tmp/r4.svg"
within --flatten --tolerance 0.01 -- --tol 0.01 -- "$tmp/r4.svg"
within --flatten --tolerance 0.001 -- --tol 0.001 -- "$tmp/r4.svg"
svg 'M100000 100000Q150000 0 200000 100000' "$tmp/r4b.svg"
within -- -- "$tmp/r4b.svg"
check "--precision 7 given" "$svgsmooth" --flatten --tolerance 0.01 --precision 7 -o "$tmp/p7.svg" "$tmp/r4.svg"
check_grep 'L1006\.636 986\.8158 ' "$tmp/p7.svg" "an explicit --precision wins"

begin_case "5. closed subpaths start at their drawn vertex; corners stay vertices"
# the start is a smooth join between two cubics, the corners are elsewhere:
# flattening's runs passed over it
svg 'M10 0C15 0 20 5 20 10L20 20 0 20 0 10C0 5 5 0 10 0Z' "$tmp/r5.svg"
for m in "" "--levels 3" "--flatten --tolerance 0.01"; do
    chk=
    case $m in --flatten*) chk="--tol 0.01" ;; esac
    # shellcheck disable=SC2086
    within $m -- $chk -- "$tmp/r5.svg"
    check_grep 'd="M10 0L' "$tmp/w.svg" "starts at 10 0 ($m)"
done

begin_case "6. --simplify keeps straight outlines straight; polygons' corner angle"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M100 100L1300 100 1300 260 300 1600 1320 1600 1320 1760 80 1760 80 1600 1080 260 100 260Z"/></svg>\n' >"$tmp/z.svg"
within --simplify 0.1 -- --lines-tol 0.1 -- "$tmp/z.svg"
check_grep 'd="M100 100L1300 100 1300 260 300 1600 1320 1600 1320 1760 80 1760 80 1600 1080 260 100 260Z"' "$tmp/w.svg" "the Z as drawn"
# simple-icons googlefonts, primefaces, channel4: straight subpaths smoothed
# through by --simplify crossed their neighbours and left the drawing by
# 60-126 times the tolerance
for n in googlefonts primefaces channel4; do
    f=tests/data/icons/simple-icons/$n.svg
    [ -f "$f" ] || continue
    check "$n --simplify 0.5" "$svgsmooth" --simplify 0.5 -o "$tmp/s.svg" "$f"
    check "svgcheck" "$svgcheck" --lines-tol 0.5 "$f" "$tmp/s.svg"
    check_grep '^ratio=0\.[0-9]+ over=0 .* crossings=0 ' "$out" "$n: within 0.5, no crossing: $(cat "$out")"
done
# two near-parallel wiggly polylines 0.02 apart, the lower sagging by 0.04:
# each alone is within 0.05 of its chord, and the chords cross (the upper
# one starts at the sag's bottom and ends above the lower chord); and the
# same two joined into one subpath by a detour. Plain simplification
# crossed them (1 crossing between the subpaths, 2 within the one); the
# vertices there come back until none is left.
wiggle() { # wiggle K0 K1 LIFT: "x yL x y ...", vertices k = K0..K1 at x = k / 4
    awk -v k0="$1" -v k1="$2" -v lift="$3" 'BEGIN { for (k = k0; k <= k1; k++) {
        x = k * 0.25; y = lift - 0.04 * sin(3.141592653589793 * x / 10) + 0.004 * (k % 2 ? -1 : 1)
        printf "%s%.6g %.6g", k == k0 ? "" : k == k0 + 1 ? "L" : " ", x, y } }'
}
lower=$(wiggle 0 40 0)
upper=$(wiggle 20 38 0.02)
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M%sM%s"/></svg>\n' "$lower" "$upper" >"$tmp/x2.svg"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M%s 10 1 4.5 1 %s"/></svg>\n' "$lower" \
    "$(echo "$upper" | tr L ' ')" >"$tmp/x1.svg"
for f in x2 x1; do
    for m in "" --lines-as-samples; do
        # shellcheck disable=SC2086
        within --simplify 0.05 $m -- --lines-tol 0.05 -- "$tmp/$f.svg"
        check_grep ' self=0 ' "$out" "$f $m: no new crossing within the subpath: $(cat "$out")"
        # still simplified: fewer points than the 60 (63) drawn
        [ -z "$m" ] && check_grep 'points=([0-9]|[1-4][0-9])$' "$out" "$f: simplified: $(cat "$out")"
    done
done
# feather's volume: a polygon whose joins turn 38.7 degrees
pv=tests/data/icons/feather/volume.svg
if [ -f "$pv" ]; then
    check "--corner-angle 30" "$svgsmooth" --corner-angle 30 -o "$tmp/v.svg" "$pv"
    check_grep 'points="11,5 6,9 2,9 2,15 6,15 11,19"' "$tmp/v.svg" "the polygon's joins kept"
fi

begin_case "real icons from npm (tests/data/icons): every mode within the tolerance"
# one svgsmooth call per mode (-r: the sets mirrored under $tmp/MODE/) and
# one svgcheck call on all its pairs; then one assertion per icon
icons=tests/data/icons
ls "$icons"/*/*.svg >"$tmp/icons" 2>/dev/null || skip_case "no icons under $icons"
rows_ok() { # ROWS OPTIONS: every pair's row within the tolerance (see within())
    while IFS= read -r r_row; do
        printf '%s\n' "${r_row#*	}" >"$tmp/row"
        check_grep '^ratio=(0\.[0-9]+|1\.0000) over=0 subpaths=[0-9]+ starts=0 corners=0/[0-9]+ crossings=0 ' \
            "$tmp/row" "$(basename "${r_row%%	*}") $2: ${r_row#*	}"
    done <"$1"
}
batch() { # NAME MODE-ARGS -- CHECK-ARGS
    b_name=$1
    shift
    b_opt=
    while [ "$1" != -- ]; do b_opt="$b_opt $1"; shift; done
    shift
    # shellcheck disable=SC2086
    check "svgsmooth$b_opt -r $icons" "$svgsmooth" $b_opt -q -r "$icons" -o "$tmp/$b_name/"
    while read -r f; do
        printf '%s\t%s\n' "$f" "$tmp/$b_name/${f#"$icons"/}"
    done <"$tmp/icons" >"$tmp/$b_name.pairs"
}
for mode in default flatten; do
    case $mode in
    default) batch default -- ; chk= ;;
    flatten) batch flatten --flatten --tolerance 0.01 -- ; chk="--tol 0.01 --samples-too" ;;
    esac
    # shellcheck disable=SC2086
    check "svgcheck $chk --list ($mode)" "$svgcheck" $chk --list "$tmp/$mode.pairs"
    cp "$out" "$tmp/$mode.rows"
    rows_ok "$tmp/$mode.rows" "$mode"
done
# --simplify 0.05: an output byte for byte the default one was measured
# there (within the stricter tolerance, no assertion again); the others
# are measured here
batch simplify --simplify 0.05 --
: >"$tmp/simplify.changed"
while IFS='	' read -r f o; do
    cmp -s "$o" "$tmp/default/${f#"$icons"/}" || printf '%s\t%s\n' "$f" "$o" >>"$tmp/simplify.changed"
done <"$tmp/simplify.pairs"
if [ -s "$tmp/simplify.changed" ]; then
    check "svgcheck --lines-tol 0.05 --list" "$svgcheck" --lines-tol 0.05 --list "$tmp/simplify.changed"
    cp "$out" "$tmp/simplify.rows"
    rows_ok "$tmp/simplify.rows" "--simplify 0.05"
fi
# 3 levels on the first icon of each set (8 levels: the reproductions)
last=
while read -r f; do
    set_dir=${f%/*}
    [ "$set_dir" = "$last" ] || within --levels 3 -- -- "$f"
    last=$set_dir
done <"$tmp/icons"
finish
