#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite for the SVG render (conica_svg_render, docs/svg-rendering.md):
# every hand-written case of tests/data/render/ and every vendored icon of
# tests/data/icons/ is rendered by rsvg-convert (librsvg) as it is and as
# the flat scene svgscene writes for it (each painted item one <path> under
# its matrix, in its clip); the painted pixels must agree outside a 1-px
# band to 0.1 % (tests/support/pixdiff.py). Plus the warnings the render
# must give and the errors of its caps.
# usage (from the repository root): sh tests/cli/svg_render.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
scene=$build/tests/svgscene
pixdiff=tests/support/pixdiff.py
data=tests/data/render

if [ ! -x "$scene" ]; then
    begin_case "svg render suite"
    skip_case "$scene is not built (make $scene)"
    finish
fi
have_rsvg=1
command -v rsvg-convert >/dev/null 2>&1 || have_rsvg=0

# same_pixels FILE [UNIT]: the scene of FILE paints what FILE paints
same_pixels() {
    f=$1 unit=${2:-px} b=$tmp/$(basename "$1" .svg).$unit
    check "$f: scene ($unit)" "$scene" --unit "$unit" "$f" "$b.svg"
    if [ "$have_rsvg" -eq 0 ]; then
        skip_case "rsvg-convert not installed (scripts/deps.sh test)"
        return
    fi
    # one size for both (the scene's root size in mm may round to another
    # pixel count than the document's)
    check "$f: rsvg-convert renders it" rsvg-convert -w 480 -h 480 -o "$b.orig.png" "$f"
    check "$f: rsvg-convert renders the scene" rsvg-convert -w 480 -h 480 -o "$b.png" "$b.svg"
    check "$f: same painted pixels outside a 1-px band (0.1 %)" \
        python3 "$pixdiff" "$b.orig.png" "$b.png"
}

for f in "$data"/*.svg; do
    begin_case "render agrees with librsvg: $(basename "$f")"
    same_pixels "$f"
    # librsvg 2.54 ignores vector-effect; the scene keeps it (SVG 2, as
    # browsers draw it), so only in px do both draw the same
    case $f in */nonscaling.svg) ;; *) same_pixels "$f" mm ;; esac
done

for set in tabler bootstrap mdi simple; do
    [ -d tests/data/icons/$set ] || continue
    begin_case "render agrees with librsvg on $set icons"
    for f in tests/data/icons/$set/*.svg; do
        same_pixels "$f"
    done
done

begin_case "the tabler frame path paints nothing; the icon is its strokes"
check "count" "$scene" --count "$data/tabler.svg"
check_grep '^2$' "$out"
check "count with --unpainted" "$scene" --count --unpainted "$data/tabler.svg"
check_grep '^3$' "$out"

begin_case "what is not drawn is named, once per element and kind"
cat >"$tmp/warn.svg" <<'SVG'
<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
  <defs><clipPath id="c"><rect width="5" height="5"/></clipPath><mask id="m"/><filter id="f"/>
    <marker id="mk"><path d="M0 0h2v2z"/></marker></defs>
  <text id="t" x="5" y="5">hello<tspan>x</tspan></text>
  <image id="i" href="x.png" width="10" height="10"/>
  <rect id="cp" width="10" height="10" clip-path="url(#c)" style="clip-path:url(#c)"/>
  <rect id="mk2" width="10" height="10" mask="url(#m)"/>
  <rect id="fl" width="10" height="10" filter="url(#f)"/>
  <rect id="fm" width="10" height="10" filter="url(#nothing)"/>
  <path id="pm" d="M0 0 L10 10 L20 0" stroke="black" marker-mid="url(#mk)"/>
  <rect id="sg" width="10" height="10" transform="scale(0 1)"/>
  <rect id="bt" width="10" height="10" transform="scale(a)"/>
  <path id="bd" d="M0 0 L10 10 Lx"/>
  <path id="lj" d="M0 0 L10 10" stroke="black" stroke-linejoin="arcs"/>
  <path id="ns" d="M0 0 L10 10" stroke="black" vector-effect="non-scaling-stroke"/>
  <foreignObject id="fo" width="10" height="10"/>
</svg>
SVG
check "render" "$scene" "$tmp/warn.svg" "$tmp/warn.out.svg"
check_grep "text 't'.*text is not drawn" "$err"
check_grep "image 'i'.*images are not drawn" "$err"
check_grep "rect 'cp'.*clip-path is not applied: drawn unclipped" "$err"
check_grep "rect 'mk2'.*mask is not applied" "$err"
check_grep "rect 'fl'.*filter is not applied" "$err"
check_grep "rect 'fm'.*no filter element: not drawn" "$err"
check_grep "path 'pm'.*markers" "$err"
check_grep "rect 'sg'.*not invertible: not drawn" "$err"
check_grep "rect 'bt'.*not valid: ignored" "$err"
check_grep "path 'bd'.*bad path data" "$err"
check_grep "path 'lj'.*drawn as miter" "$err"
check_grep "foreignObject 'fo'" "$err"
check_grep "path 'ns'.*librsvg 2.54 scales" "$err"
cp "$err" "$tmp/warn.err"
check "one warning for clip-path although set twice" \
    sh -c "[ \$(grep -c \"rect 'cp'\" '$tmp/warn.err') -eq 1 ]"
check "the not-drawn elements are not in the scene" "$scene" --count "$tmp/warn.svg"
check_grep '^8$' "$out"

begin_case "caps: use cycles, use depth, instances are errors naming the line"
cat >"$tmp/cycle.svg" <<'SVG'
<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10">
<g id="a">
<use href="#a" x="1"/>
</g>
</svg>
SVG
check_exit 1 "a use inside its target" "$scene" "$tmp/cycle.svg" "$tmp/x.svg"
check_grep "cycle.svg:3:.*reference cycle" "$err"
python3 - "$tmp/deep.svg" "$tmp/wide.svg" <<'PY'
import sys
# 40 uses each of the one before: deeper than the default cap of 32
s = ['<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><defs><path id="u0" d="M0 0h1v1z"/>']
s += ['<use id="u%d" href="#u%d"/>' % (i, i - 1) for i in range(1, 41)]
s.append('</defs><use href="#u40"/></svg>')
open(sys.argv[1], 'w').write('\n'.join(s))
# billion laughs by use: 10 copies of 10 copies ... 8 levels = 10^8 instances
s = ['<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><defs><path id="l0" d="M0 0h1v1z"/>']
for i in range(1, 9):
    s.append('<g id="l%d">' % i + ''.join('<use href="#l%d"/>' % (i - 1) for _ in range(10)) + '</g>')
s.append('</defs>\n<use href="#l8"/></svg>')
open(sys.argv[2], 'w').write('\n'.join(s))
PY
check_exit 1 "use nested 41 deep" "$scene" "$tmp/deep.svg" "$tmp/x.svg"
check_grep "nested more than 32 deep" "$err"
check_exit 1 "10^8 instances" "$scene" "$tmp/wide.svg" "$tmp/x.svg"
check_grep "more than 1048576 elements drawn" "$err"
python3 - "$tmp/css.svg" <<'PY'
import sys
# 4000 selectors that each walk 250 ancestors for every one of 5000 rects
s = ['<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10"><style>']
s += ['a ' + ' '.join(['g'] * 30) + ' rect {fill:none}' for i in range(4000)]
s.append('</style>' + '<g>' * 250 + '<rect width="1" height="1"/>' * 5000 + '</g>' * 250 + '</svg>')
open(sys.argv[1], 'w').write('\n'.join(s))
PY
check_exit 1 "selector matching beyond 2^30 steps" "$scene" "$tmp/css.svg" "$tmp/x.svg"
check_grep "CSS selector matching takes more than 1073741824 steps" "$err"
check "no output was written" sh -c "[ ! -s '$tmp/x.svg' ]"

finish
