#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo` part: curvature combs, an error-vs-level plot and the
# numerics ablation of the CONIS paper (Figure 6), as SVG rendered to PNG.
# BUILD is $1; everything goes to $BUILD/demo/.
set -eu
build=${1:-build}
out=$build/demo
conica=$build/bin/conica
mkdir -p "$out"

render() { # svg -> png next to it (rsvg-convert, from librsvg2-bin)
    if command -v rsvg-convert >/dev/null 2>&1; then
        rsvg-convert -b white -o "${1%.svg}.png" "$1"
        echo "  $1 -> ${1%.svg}.png"
    else
        echo "  $1 (rsvg-convert not installed: no PNG)"
    fi
}

# The comb of a smooth subdivided shape, and of a non-convex one (teeth flip
# at inflections with --signed).
"$conica" combs -k 5 -o "$out/comb-ellipse.svg" examples/ellipse.txt
echo "  examples/ellipse.txt -> $out/comb-ellipse.svg (curvature comb, k = 5)"
render "$out/comb-ellipse.svg"
"$conica" combs -k 5 --signed -o "$out/comb-flower.svg" examples/flower.txt
echo "  examples/flower.txt -> $out/comb-flower.svg (signed curvature comb, k = 5)"
render "$out/comb-flower.svg"

# Conic and normal errors per level on the ellipse 4x^2 + 9y^2 = 36 (its
# samples are exact), as Figures 3-4 of the CONIS paper.
"$conica" errors -k 12 --conic 4,9,0,0,0,-36 --plot "$out/errors-ellipse.svg" \
    examples/ellipse.txt >"$out/errors-ellipse.txt"
echo "  examples/ellipse.txt -> $out/errors-ellipse.txt (conic error per level, table)," \
    "$out/errors-ellipse.svg (chart)"
render "$out/errors-ellipse.svg"

# The ablation: E, E_max at k = 4, 8, 12 per variant, and the combs at k = 10
# side by side, on the reference's example9 from the shared data
# ($CONICA_SHARED_DATA, else ../shared/data, as the tests find it), else on
# the bundled flower (with a notice: the README's pictures use example9).
example=${CONICA_SHARED_DATA:-../shared/data}/conis/input/example9.txt
if [ ! -f "$example" ]; then
    echo "demo-diagnostics: notice: $example absent (set CONICA_SHARED_DATA);" \
        "the ablation uses examples/flower.txt instead" >&2
    example=examples/flower.txt
fi
"$build/bench/bench_ablation" --example "$example" --svg "$out/ablation-combs.svg" \
    >"$out/ablation.md"
echo "  $example -> $out/ablation.md (numerics ablation, tables), $out/ablation-combs.svg (combs)"
render "$out/ablation-combs.svg"
