#!/bin/sh
# SPDX-License-Identifier: MIT
# The pictures in docs/ and where each comes from, in one place.
#
#   scripts/docs-pictures.sh list            picture, kind and source, a line each
#   scripts/docs-pictures.sh make BUILD DIR  make every checkable picture into DIR
#                                            (as docs/ names them), from BUILD's tools
#   scripts/docs-pictures.sh update BUILD    the same into docs/ (`make docs-pictures`)
#
# Kinds: `demo NAME` is BUILD/demo/NAME as `make demo` makes it (the demo
# runs in a scratch view of BUILD, so BUILD/demo is left alone); `shared
# FILE` is `conica combs -k 5 --signed` of FILE under the reference's test
# data (the directory CONICA_SHARED_DATA names), rendered 600 px wide as
# docs/subdivide.md shows, skipped with a notice without that data; `fixed`
# pictures show an earlier state (output before a fix, the reference
# implementation's own output) and are never remade. tests/cli/docs.sh
# compares `make`'s pictures with docs/ (scripts/pngdiff.py).
set -eu

list() {
    cat <<'LIST'
docs/blender-before-after.png demo blender-before-after.png
docs/blender-mesh-to-curve.png demo blender-mesh-to-curve.png
docs/scadprofile-bracket.png demo model-view.png
docs/svgsmooth-icon.png demo svg-icon-arcs.compare.png
docs/svgsmooth-leaf-clean.png demo svg-traced-leaf.clean.png
docs/svgsmooth-leaf-zoom.png demo svg-traced-leaf.zoom.png
docs/svgsmooth-letter-R.png demo svg-letter-R.compare.png
docs/img/diag-ablation-combs.png demo ablation-combs.png
docs/img/diag-comb-ellipse.png demo comb-ellipse.png
docs/img/diag-comb-flower.png demo comb-flower.png
docs/img/diag-errors-ellipse.png demo errors-ellipse.png
docs/img/fair-example9-local.png shared conis/input/example9.txt
docs/img/fair-lG2-local.png shared conis/input/lG2.txt
docs/img/fair-example9-before.png fixed -
docs/img/fair-example9-reference.png fixed -
docs/img/fair-lG2-before.png fixed -
docs/img/fair-lG2-reference.png fixed -
LIST
}

make_into() { # build dir
    build=$1 dest=$2
    view=$(mktemp -d "${TMPDIR:-/tmp}/conica-pictures.XXXXXX")
    trap 'rm -rf "$view"' EXIT INT TERM
    case "$build" in /*) babs=$build ;; *) babs=$(pwd)/$build ;; esac
    for e in "$babs"/*; do
        [ "${e##*/}" = demo ] || ln -s "$e" "$view/${e##*/}"
    done
    mkdir -p "$view/demo"
    sh scripts/demo.sh "$view" >"$view/demo.log" 2>&1 || {
        tail -n 30 "$view/demo.log" >&2
        echo "docs-pictures.sh: make demo's scripts failed" >&2
        exit 1
    }
    shared=${CONICA_SHARED_DATA:-}
    list | while read -r pic kind src; do
        mkdir -p "$dest/$(dirname "$pic")"
        case $kind in
        demo)
            if [ -f "$view/demo/$src" ]; then
                cp "$view/demo/$src" "$dest/$pic"
            else
                echo "note: $pic: make demo made no $src here (its tool is not installed)"
            fi ;;
        shared)
            if [ -n "$shared" ] && [ -f "$shared/$src" ]; then
                "$build/bin/conica" combs -k 5 --signed -o "$view/comb.svg" "$shared/$src"
                rsvg-convert -w 600 -b white -o "$dest/$pic" "$view/comb.svg"
            else
                echo "note: $pic: not made (CONICA_SHARED_DATA names no directory with $src)"
            fi ;;
        esac
    done
}

case "${1:-}" in
list) list ;;
make) make_into "$2" "$3" ;;
update) make_into "$2" . ;;
*) echo "usage: scripts/docs-pictures.sh list | make BUILD DIR | update BUILD" >&2; exit 2 ;;
esac
