#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth writes documents back byte for byte: outside the rewritten d and
# points values every byte of the output is the input's (attribute layout,
# quoting, entity references, comments, CDATA, DOCTYPE, CRLF, BOM, a
# missing final newline), and with --select matching nothing the output is
# the input. Checked on every examples/*.svg and on real-world-like files.
# usage (from the repository root): sh tests/cli/svg_bytes.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth

# skeleton.py A B: A and B are equal once every d/points attribute value
# (either quote) is cut out; prints how many values differ, exits 1 when the
# skeletons differ (and shows the first differing bytes).
cat >"$tmp/skeleton.py" <<'EOF'
import re, sys
VAL = re.compile(rb'''(\s(?:d|points)\s*=\s*)("[^"]*"|'[^']*')''')
def cut(b):
    return VAL.sub(rb'\1@', b), [m.group(2) for m in VAL.finditer(b)]
a = open(sys.argv[1], 'rb').read()
b = open(sys.argv[2], 'rb').read()
(sa, va), (sb, vb) = cut(a), cut(b)
if sa != sb:
    i = next((k for k in range(min(len(sa), len(sb))) if sa[k] != sb[k]), min(len(sa), len(sb)))
    print('skeletons differ at byte %d: %r vs %r' % (i, sa[max(0, i - 40):i + 40], sb[max(0, i - 40):i + 40]))
    sys.exit(1)
changed = sum(1 for x, y in zip(va, vb) if x != y)
# a rewritten value keeps its quote
quotes = all(x[:1] == y[:1] for x, y in zip(va, vb))
print(changed)
sys.exit(0 if quotes else 1)
EOF
skeleton() { python3 "$tmp/skeleton.py" "$@"; }
wellformed() { python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" "$1"; }

# ---------------------------------------------------------------- files
# multi-line attributes, single quotes, entities, comments, CDATA, DOCTYPE
# with an internal entity, a stylesheet PI, namespaced attributes, '>' in a
# value, tabs
cat >"$tmp/real.svg" <<'EOF'
<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<?xml-stylesheet type="text/css" href="style.css"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd" [
	<!ENTITY ns_svg "http://www.w3.org/2000/svg">
]>
<!-- Created with a hand editor: keep   this   spacing -->
<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"
     xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
     width='200'   height="200"
     viewBox = "0 0 200 200" >
  <style type="text/css"><![CDATA[
    path { stroke: #000; } /* a > b & c */
  ]]></style>
  <title>Tom &amp; Jerry &#169; &ns_svg;</title>
  <g inkscape:label="Layer &quot;1&quot;" data-note='a > b'>
    <path
       id='curve'
       style="fill:none;stroke-width:2"
       d='M 10,100
          C 40,10 60,10 90,100
          S 140,190 170,100'
       inkscape:connector-curvature="0" />
    <polygon id="tri" points="20,180 60,120
	100,180" fill='#c00'/>
    <path id="line" d="M10 10 L190 10"/>
    <use xlink:href="#curve" x="5"/>
  </g>
  <text x="10" y="195">a	tab, an &lt;entity&gt;</text>
</svg>
<!-- trailing comment -->
EOF
# CRLF line ends, a UTF-8 BOM, no final newline
printf '\357\273\277<?xml version="1.0"?>\r\n<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">\r\n  <!-- crlf -->\r\n  <polyline id="zig"\r\n     points="10,50 30,35 50,30 70,35 90,50"\r\n     fill="none"/>\r\n  <path id="q" d="M10 90Q50 60 90 90"/>\r\n</svg>' >"$tmp/crlf.svg"
# a shape converted to a path keeps its other attributes where they were
printf '<svg xmlns="http://www.w3.org/2000/svg">\n  <rect id="r"\n     x="10" y="20"\n     width="30" height="40"\n     fill='"'"'red'"'"'></rect>\n</svg>\n' >"$tmp/shape.svg"

# ---------------------------------------------------------------- cases
begin_case "svgsmooth is built"
check_true "$svgsmooth exists" test -x "$svgsmooth"

begin_case "--select matching nothing: the output is the input, byte for byte"
for f in examples/*.svg "$tmp/real.svg" "$tmp/crlf.svg" "$tmp/shape.svg"; do
    [ -f "$f" ] || continue
    b=$(basename "$f" .svg)
    check "$b: --select none" "$svgsmooth" --select no-such-id -o "$tmp/$b.none.svg" "$f"
    check "$b: identical" cmp "$f" "$tmp/$b.none.svg"
done
cp "$tmp/crlf.svg" "$tmp/inplace.svg"
check "--in-place, nothing selected" "$svgsmooth" --select no-such-id --in-place "$tmp/inplace.svg"
check "--in-place: identical" cmp "$tmp/crlf.svg" "$tmp/inplace.svg"

begin_case "every example: only d/points values change, and they do"
for f in examples/*.svg; do
    [ -f "$f" ] || continue
    b=$(basename "$f" .svg)
    for mode in smooth flat simplify; do
        case $mode in
            smooth) set -- ;;
            flat) set -- --flatten --tolerance 0.5 ;;
            simplify) set -- --simplify 0.5 ;;
        esac
        check "$b $mode" "$svgsmooth" "$@" -o "$tmp/$b.$mode.svg" "$f"
        check "$b $mode: same bytes outside the values" skeleton "$f" "$tmp/$b.$mode.svg"
        check_true "$b $mode: some value rewritten ($(cat "$out"))" test "$(cat "$out")" -gt 0
        check "$b $mode: well-formed" wellformed "$tmp/$b.$mode.svg"
    done
done

begin_case "real-world-like files: layout, quotes, entities, comments, CDATA, CRLF, BOM kept"
check "real.svg" "$svgsmooth" --lines-as-samples -o "$tmp/real.out.svg" "$tmp/real.svg"
check "real.svg: same bytes outside the values" skeleton "$tmp/real.svg" "$tmp/real.out.svg"
check_true "real.svg: three values rewritten" test "$(cat "$out")" -eq 3
check "real.svg: well-formed" wellformed "$tmp/real.out.svg"
check_grep "d='M10 100L" "$tmp/real.out.svg" "the single-quoted d stays single-quoted"
check "crlf.svg" "$svgsmooth" -o "$tmp/crlf.out.svg" "$tmp/crlf.svg"
check "crlf.svg: same bytes outside the values" skeleton "$tmp/crlf.svg" "$tmp/crlf.out.svg"
check_true "crlf.svg: two values rewritten" test "$(cat "$out")" -eq 2
check_true "crlf.svg: BOM kept" test "$(head -c 3 "$tmp/crlf.out.svg" | od -An -tx1 | tr -d ' ')" = efbbbf
check_true "crlf.svg: no final newline added" test "$(tail -c 6 "$tmp/crlf.out.svg")" = "</svg>"
check "--select one element: the other stays as written" "$svgsmooth" --select q -o "$tmp/crlf.q.svg" "$tmp/crlf.svg"
check "--select: same bytes outside the values" skeleton "$tmp/crlf.svg" "$tmp/crlf.q.svg"
check_true "--select: one value rewritten" test "$(cat "$out")" -eq 1
check_grep 'points="10,50 30,35 50,30 70,35 90,50"' "$tmp/crlf.q.svg" "the unselected polyline is untouched"

begin_case "--convert-shapes: the element renamed in both tags, geometry attributes out, the rest in place"
check "shape.svg" "$svgsmooth" --convert-shapes -o "$tmp/shape.out.svg" "$tmp/shape.svg"
check "well-formed" wellformed "$tmp/shape.out.svg"
check_true "layout kept" python3 -c "
import re, sys
t = open(sys.argv[1]).read()
sys.exit(0 if re.fullmatch(r'<svg xmlns=\"http://www.w3.org/2000/svg\">\n  <path id=\"r\"\n     fill=\'red\' d=\"M[^\"]*Z\"></path>\n</svg>\n', t) else 1)" "$tmp/shape.out.svg"

finish
