#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo`, SVG part (called by scripts/demo.sh with the build directory):
# smooth and flatten every examples/*.svg with svgsmooth into BUILD/demo/,
# render input and outputs with rsvg-convert and put them side by side
# (BUILD/demo/svg-NAME.compare.png: input | smoothed | flattened).
set -eu
build=${1:-build}
out=$build/demo
svgsmooth=$build/bin/svgsmooth
mkdir -p "$out"
have_rsvg=1
command -v rsvg-convert >/dev/null 2>&1 || have_rsvg=0
for f in examples/*.svg; do
    [ -f "$f" ] || continue
    name=svg-$(basename "$f" .svg)
    cp "$f" "$out/$name.in.svg"
    "$svgsmooth" --stats -o "$out/$name.smooth.svg" "$f" 2>"$out/$name.smooth.stats"
    "$svgsmooth" --stats --flatten --tolerance 0.5 -o "$out/$name.flat.svg" "$f" 2>"$out/$name.flat.stats"
    echo "  $f -> $out/$name.smooth.svg ($(sed -n 's/.*, \([0-9]*\) output points.*/\1/p' "$out/$name.smooth.stats") points)," \
         "$out/$name.flat.svg ($(sed -n 's/.*, \([0-9]*\) output points.*/\1/p' "$out/$name.flat.stats") points)"
    [ "$have_rsvg" -eq 1 ] || continue
    for v in in smooth flat; do
        rsvg-convert -w 360 -b white -o "$out/$name.$v.png" "$out/$name.$v.svg"
    done
    h=$(python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print(struct.unpack('>I', d[20:24])[0])" "$out/$name.in.png")
    cat >"$out/$name.compare.svg" <<EOF
<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="1120" height="$((h + 30))">
  <rect width="1120" height="$((h + 30))" fill="#fff"/>
  <g font-family="sans-serif" font-size="16" text-anchor="middle">
    <text x="180" y="20">input</text><text x="560" y="20">svgsmooth (4 levels)</text>
    <text x="940" y="20">svgsmooth --flatten --tolerance 0.5</text>
  </g>
  <image x="0" y="30" width="360" height="$h" xlink:href="$name.in.png"/>
  <image x="380" y="30" width="360" height="$h" xlink:href="$name.smooth.png"/>
  <image x="760" y="30" width="360" height="$h" xlink:href="$name.flat.png"/>
</svg>
EOF
    (cd "$out" && rsvg-convert -o "$name.compare.png" "$name.compare.svg")
    echo "  before/after: $out/$name.compare.png"
    # A close-up when the example names a box (data-demo-zoom="x y w h").
    zoom=$(sed -n 's/.*data-demo-zoom="\([^"]*\)".*/\1/p' "$f" | head -n 1)
    [ -n "$zoom" ] || continue
    for v in in smooth flat; do
        sed -e "/<svg /s/ viewBox=\"[^\"]*\"/ viewBox=\"$zoom\"/" \
            -e '/<svg /s/ width="[^"]*"//' -e '/<svg /s/ height="[^"]*"//' \
            "$out/$name.$v.svg" >"$out/$name.$v.zoom.svg"
        rsvg-convert -w 360 -h 360 -b white -o "$out/$name.$v.zoom.png" "$out/$name.$v.zoom.svg"
    done
    sed -e "s/$name\.\(in\|smooth\|flat\)\.png/$name.\1.zoom.png/g" -e "s/height=\"$h\"/height=\"360\"/g" \
        -e "s/height=\"$((h + 30))\"/height=\"390\"/g" "$out/$name.compare.svg" >"$out/$name.zoom.svg"
    (cd "$out" && rsvg-convert -o "$name.zoom.png" "$name.zoom.svg")
    echo "  close-up ($zoom): $out/$name.zoom.png"
done
[ "$have_rsvg" -eq 1 ] || echo "  (rsvg-convert not installed: no PNGs; scripts/deps.sh demo installs it)"

# The traced leaf cleaned: every traced point interpolated (--lines-as-samples)
# beside --simplify 1 (the fewest vertices whose smoothed curve stays within
# 1 unit of every traced point), and the curvature combs of the right side
# (base to tip, between the two corners) through the vertices each keeps.
leaf=examples/traced-leaf.svg
[ -f "$leaf" ] || exit 0
"$svgsmooth" --lines-as-samples --precision 12 -o "$out/svg-traced-leaf.all.svg" "$leaf"
"$svgsmooth" --simplify 1 --lines-as-samples --precision 12 -o "$out/svg-traced-leaf.simplify.svg" "$leaf"
conica=$build/bin/conica
for v in all simplify; do
    # the kept vertices are the output points equal to a traced one (the
    # subdivision keeps its control points bit for bit)
    python3 - "$leaf" "$out/svg-traced-leaf.$v.svg" >"$out/svg-traced-leaf.$v.right.txt" <<'PY'
import re, sys
num = re.compile(r'[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?')
def pts(f):
    d = re.search(r'id="leaf" d="([^"]*)"', open(f).read()).group(1)
    v = [float(x) for x in num.findall(d)]
    return list(zip(v[0::2], v[1::2]))
traced = pts(sys.argv[1])
kept = [p for p in pts(sys.argv[2]) if p in set(traced)]
tip = kept.index((100.0, 30.0))
for x, y in kept[:tip + 1]:
    print('v %r %r' % (x, y))
PY
    "$conica" combs --open --signed -o "$out/svg-traced-leaf.$v.comb.svg" \
        "$out/svg-traced-leaf.$v.right.txt"
done
echo "  traced leaf, --simplify 1: $(grep -c '^v' "$out/svg-traced-leaf.simplify.right.txt") vertices on the right side" \
     "instead of $(grep -c '^v' "$out/svg-traced-leaf.all.right.txt") (combs: $out/svg-traced-leaf.*.comb.svg)"
[ "$have_rsvg" -eq 1 ] || exit 0
for v in all simplify; do
    rsvg-convert -w 360 -b white -o "$out/svg-traced-leaf.$v.png" "$out/svg-traced-leaf.$v.svg"
    rsvg-convert -w 360 -b white -o "$out/svg-traced-leaf.$v.comb.png" "$out/svg-traced-leaf.$v.comb.svg"
done
cat >"$out/svg-traced-leaf.simplify.cmp.svg" <<EOF2
<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="740" height="780">
  <rect width="740" height="780" fill="#fff"/>
  <g font-family="sans-serif" font-size="16" text-anchor="middle">
    <text x="180" y="20">every traced point interpolated</text><text x="560" y="20">svgsmooth --simplify 1</text>
    <text x="180" y="410">signed curvature comb, right side</text><text x="560" y="410">signed curvature comb, right side</text>
  </g>
  <image x="0" y="30" width="360" height="360" xlink:href="svg-traced-leaf.all.png"/>
  <image x="380" y="30" width="360" height="360" xlink:href="svg-traced-leaf.simplify.png"/>
  <image x="0" y="420" width="360" height="360" preserveAspectRatio="xMidYMid meet" xlink:href="svg-traced-leaf.all.comb.png"/>
  <image x="380" y="420" width="360" height="360" preserveAspectRatio="xMidYMid meet" xlink:href="svg-traced-leaf.simplify.comb.png"/>
</svg>
EOF2
(cd "$out" && rsvg-convert -o svg-traced-leaf.clean.png svg-traced-leaf.simplify.cmp.svg)
echo "  traced leaf cleaned: $out/svg-traced-leaf.clean.png"
