#!/bin/sh
# SPDX-License-Identifier: MIT
# scadprofile writes what the SVG paints (issue 31): the reproductions of the
# issue, one-sided fits checked by Clipper (pyclipper) against dense exact
# regions, and the vendored icons' pixels beside rsvg-convert's.
#   sh tests/cli/scadprofile_region.sh BUILD_DIR      (from the repository root)
set -u
. "$(dirname "$0")/harness.sh"
. tests/support/pixel_checks.sh
bin=$build/bin/scadprofile
sided() { "$PY" tests/support/scad_sided.py "$@"; }
pixels() { "$PY" tests/support/scad_pixels.py "$@"; }
have_pyclipper() { "$PY" -c 'import pyclipper' >/dev/null 2>&1; }
# doc W H FILL-RULE D: a one-path document in px
doc() {
    printf '<svg xmlns="http://www.w3.org/2000/svg" width="%s" height="%s" viewBox="0 0 %s %s"><path fill-rule="%s" d="%s"/></svg>\n' \
        "$1" "$2" "$1" "$2" "$3" "$4"
}

begin_case "scadprofile is built"
check_true "$bin exists" test -x "$bin"

# --------------------------------------------------------------- fits
begin_case "one-sided fits hold against the exact region (pyclipper)"
have_pyclipper || skip_case "python3-pyclipper is not installed"
hole="M0 0H40V40H0Z M14 20A6 6 0 0 1 26 20Z"
doc 40 40 evenodd "$hole" >"$tmp/hole.svg"
for T in 0.1 0.01; do
    for f in inside outside middle clearance; do
        side=$f; [ $f = clearance ] && side=inside
        check "arc-meets-line hole, --fit $f, T $T: written" \
            "$bin" --units px --fit $f --tolerance $T -o "$tmp/h.scad" "$tmp/hole.svg"
        check "arc-meets-line hole, --fit $f, T $T: one-sided within T" \
            sided "$tmp/h.scad" --d "$hole" --fit $side --tol $T --height 40 --evenodd
    done
done
# the hole's straight edge (y = 20 in the SVG, 20 up) keeps its line: both
# its ends and nothing else on it, under clearance as under every fit
"$bin" --units px --fit clearance --tolerance 0.1 -o "$tmp/h.scad" "$tmp/hole.svg"
check_grep '^  \[14,20\],$' "$tmp/h.scad" "clearance: the hole's corner (14, 20) as drawn"
check_grep '^  \[26,20\]' "$tmp/h.scad" "clearance: the hole's corner (26, 20) as drawn"
check "clearance: no hole vertex below the hole's straight edge" py '
import re, sys
t = open("'"$tmp"'/h.scad").read()
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", t)]
hole = [p for p in pts if 10 < p[0] < 30 and 10 < p[1] < 30]
print(len(hole), min(y for x, y in hole))
sys.exit(0 if hole and min(y for x, y in hole) >= 20 else 1)
'

infl="M0 20 C 10 20 10 0 20 0 V 30 H 0 Z"
doc 20 30 nonzero "$infl" >"$tmp/infl.svg"
for f in inside outside; do
    check "the inflection, --fit $f, T 0.01: one-sided within T" sh -c \
        "'$bin' --units px --fit $f --tolerance 0.01 -o '$tmp/i.scad' '$tmp/infl.svg' &&
         '$PY' tests/support/scad_sided.py '$tmp/i.scad' --d '$infl' --fit $f --tol 0.01 --height 30"
done

edge="M0 0H20V10A12 12 0 0 1 0 10Z"
doc 20 20 nonzero "$edge" >"$tmp/edge.svg"
for f in inside outside middle; do
    check "line meets arc at a corner, --fit $f: one-sided within T" sh -c \
        "'$bin' --units px --fit $f --tolerance 0.01 -o '$tmp/e.scad' '$tmp/edge.svg' &&
         '$PY' tests/support/scad_sided.py '$tmp/e.scad' --d '$edge' --fit $f --tol 0.01 --height 20"
    check "line meets arc, --fit $f: the left edge stays on x = 0" py '
import re, sys
t = open("'"$tmp"'/e.scad").read()
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", t)]
print(min(x for x, y in pts))
sys.exit(0 if min(x for x, y in pts) == 0 else 1)
'
done

arch="M0 0 H40 V40 H30 A10 10 0 0 0 10 40 H0 Z"
doc 40 40 nonzero "$arch" >"$tmp/arch.svg"
for f in inside outside; do
    check "the concave arch, --fit $f: one-sided within T" sh -c \
        "'$bin' --units px --fit $f --tolerance 0.05 -o '$tmp/a.scad' '$tmp/arch.svg' &&
         '$PY' tests/support/scad_sided.py '$tmp/a.scad' --d '$arch' --fit $f --tol 0.05 --height 40"
done
check "the check can fail: an inside fit is not outside" sh -c \
    "'$bin' --units px --fit inside --tolerance 0.05 -o '$tmp/a.scad' '$tmp/arch.svg' &&
     ! '$PY' tests/support/scad_sided.py '$tmp/a.scad' --d '$arch' --fit outside --tol 0.05 --height 40"

# --------------------------------------------------------------- names
begin_case "OpenSCAD built-in names are not module names"
doc 10 10 nonzero "M0 0H10V10H0Z" >"$tmp/sq.svg"
for name in translate circle square union difference offset polygon sin len; do
    check "--module $name is a usage error" fails_with 2 "built-in" \
        "$bin" --module $name -o "$tmp/n.scad" "$tmp/sq.svg"
done
cp "$tmp/sq.svg" "$tmp/translate.svg"
check "translate.svg is written" "$bin" -o "$tmp/translate.scad" "$tmp/translate.svg"
check_grep "module is named 'translate_'" "$err" "with a warning naming the new name"
check_grep '^module translate_\(center=false\)$' "$tmp/translate.scad" "module translate_"
if command -v openscad >/dev/null 2>&1; then
    printf 'use <translate.scad>\ntranslate([1, 0]) translate_();\n' >"$tmp/use.scad"
    check "OpenSCAD renders it with its own translate()" sh -c \
        "cd '$tmp' && openscad -o use.csg use.scad >use.log 2>&1 && ! grep -q 'Recursion\|WARNING' use.log"
fi

# --------------------------------------------------------------- paint
begin_case "what is painted: tabler icons are strokes, not a square; --paint"
t=tests/data/icons/tabler
check "tabler heart: written" "$bin" --units px -o "$tmp/heart.scad" "$t/heart.svg"
check_grep '^// paint: as-drawn .*: 0 fills and 1 stroke made material' "$tmp/heart.scad" \
    "the header says what was painted"
check "--paint fill: the icon's invisible box is filled (a 24 px square)" sh -c \
    "'$bin' --units px --paint fill -o '$tmp/box.scad' '$t/heart.svg' &&
     grep -q '^function heart_bbox() = \[\[0,0\],\[24,24\]\];' '$tmp/box.scad'"
check "--paint as-drawn: not that square" sh -c \
    "! grep -q '^function heart_bbox() = \[\[0,0\],\[24,24\]\];' '$tmp/heart.scad'"
check "--paint bogus is a usage error" fails_with 2 "--paint must be" \
    "$bin" --paint bogus "$t/heart.svg"

begin_case "the vendored icons' pixels agree with librsvg's (lost, added <= 0.1 %)"
command -v rsvg-convert >/dev/null 2>&1 || skip_case "rsvg-convert is not installed"
# Refused (exit 1, nothing written: the check found the fit off by more than
# its slack, here by about T/50 where two outlines of the fill cross at a
# shallow angle), never written wrong; when one is accepted, this list is
# out of date and the test says so.
refused=" simple/debian:inside simple/redbull:inside "
# Under the sanitizers (BUILD_DIR build/san, scripts/run-tests.sh's second
# pass) the first three icons of each set and the issue's reproductions; the
# normal pass takes every one. All pixel comparisons run in one python.
case $build in
*/san) subset=3 ;;
*) subset=0 ;;
esac
: >"$tmp/pairs"
for set in tabler simple bootstrap mdi; do
    i=0
    for f in tests/data/icons/$set/*.svg; do
        b=$(basename "$f" .svg)
        i=$((i + 1))
        if [ "$subset" -gt 0 ] && [ "$i" -gt "$subset" ]; then
            case $b in
            debian | mistralai | kyocera | redbull | vector-bezier) ;;
            *) continue ;;
            esac
        fi
        for fit in inside outside; do
            m="$tmp/v-$set-$b-$fit.scad"
            case "$refused" in
            *" $set/$b:$fit "*)
                check "$set/$b --fit $fit: refused cleanly (known)" fails_with 1 "nothing written" \
                    "$bin" --units px --fit $fit --module m -o "$m" "$f"
                check_true "$set/$b --fit $fit: nothing written" test ! -e "$m" ;;
            *)
                check "$set/$b --fit $fit: written" "$bin" --units px --fit $fit --module m -o "$m" "$f"
                echo "$set/$b:$fit $m $f" >>"$tmp/pairs" ;;
            esac
        done
    done
done
pixel_checks "$tmp/pairs"
# the issue's: auth0 kept 11.22 of 18.25 mm^2 under --fit outside at 0.1 mm,
# mistralai at 0.001 mm filled two square holes
check "auth0 --fit outside at 0.1 mm" sh -c \
    "'$bin' --units px --fit outside --tolerance 0.1 --module m -o '$tmp/p.scad' tests/data/icons/simple/auth0.svg &&
     '$PY' tests/support/scad_pixels.py '$tmp/p.scad' tests/data/icons/simple/auth0.svg"
# (its squares meet corner to corner in Clipper's result: each sector of
# material at such a point gets its own copy of it)
check "mistralai --fit outside at 0.001 mm" sh -c \
    "'$bin' --units px --fit outside --tolerance 0.001 --module m -o '$tmp/p.scad' tests/data/icons/simple/mistralai.svg &&
     '$PY' tests/support/scad_pixels.py '$tmp/p.scad' tests/data/icons/simple/mistralai.svg"
check_grep '^// [0-9]+ outer contours?, 0 holes' "$tmp/p.scad" \
    "mistralai: the hole that touched its outline at a corner is a notch of it now"

finish
