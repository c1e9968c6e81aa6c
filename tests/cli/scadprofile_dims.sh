#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite of scadprofile, issue 15 "dimension-true parts": include-safe
# modules (NAME(center), NAME_points/paths/bbox, --demo-call), coordinates
# with the fewest digits within tolerance/1000 and the input's own numbers
# exact, --module from the file name, --fit, refusals (out of range) and
# skipped zero-area subpaths named as the SVG numbers them.
#   sh tests/cli/scadprofile_dims.sh BUILD_DIR      (from the repository root)
set -u
. "$(dirname "$0")/harness.sh"
bin=$build/bin/scadprofile
has_openscad() { command -v openscad >/dev/null 2>&1; }
# OpenSCAD must exit 0 and print neither WARNING nor ERROR.
openscad_clean() { # out in
    openscad -o "$1" "$2" >"$tmp/openscad.log" 2>&1 || { cat "$tmp/openscad.log"; return 1; }
    if grep -q -E 'WARNING|ERROR' "$tmp/openscad.log"; then cat "$tmp/openscad.log"; return 1; fi
    [ -s "$1" ]
}
# The points of NAME_points() in a written file, as "x y" lines (the text
# read back as numbers).
points() { # file
    "$PY" - "$1" <<'EOF'
import re, sys
t = open(sys.argv[1]).read()
m = re.search(r"function \w+_points\(\) = \[(.*?)\];", t, re.S)
for x, y in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1)):
    print(x, y)
EOF
}

cp examples/bracket.svg "$tmp/bracket.svg"
cp examples/bracket.svg "$tmp/my-bracket v2.svg"
# A disc r = 20 with a bore r = 8 (evenodd), 1 user unit = 1 mm.
cat >"$tmp/disc.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
  <path id="disc" fill-rule="evenodd"
        d="M70,50 A20,20 0 1 0 30,50 A20,20 0 1 0 70,50 Z
           M58,50 A8,8 0 1 0 42,50 A8,8 0 1 0 58,50 Z"/>
</svg>
EOF
cat >"$tmp/circle.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
  <circle id="c" cx="50" cy="50" r="20"/>
</svg>
EOF

# --------------------------------------------------------------- digits
begin_case "bracket: bounding box exactly 0..80 x 0..50 in the written numbers"
check "scadprofile --tolerance 0.01 bracket.svg" "$bin" --tolerance 0.01 -o "$tmp/b.scad" "$tmp/bracket.svg"
points "$tmp/b.scad" >"$tmp/b.pts"
check "the numbers read back: min/max exactly 0, 80, 0, 50" py '
import sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/b.pts")]
xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
box = (min(xs), max(xs), min(ys), max(ys))
print(len(pts), "points, box", box)
sys.exit(0 if box == (0, 80, 0, 50) else 1)
'
check_grep '^function bracket_bbox\(\) = \[\[0,0\],\[80,50\]\];$' "$tmp/b.scad" "NAME_bbox() says the same"
check_grep '^  \[6,0\],$' "$tmp/b.scad" "a corner of a straight edge is written as drawn (6, 0)"
check "no number has more than 9 significant digits (before: 16-17)" py '
import sys
def sig(s):
    d = s.lstrip("-").split("e")[0].replace(".", "").lstrip("0").rstrip("0")
    return len(d)
w = max(sig(t) for l in open("'"$tmp"'/b.pts") for t in l.split())
print("most significant digits:", w)
sys.exit(0 if w <= 9 else 1)
'
# --fit inside keeps the polygon within the painted region: the bore (a
# hole) is drawn larger, by tangent lines, its vertices in [8, 8 + T]
# (before issue 31 its vertices were on the circle: the hole smaller than
# drawn, material added)
check "bore vertices (r 8 about (40, 30)) in [8, 8 + 0.01]" py '
import math, sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/b.pts")]
bore = [math.hypot(p[0] - 40, p[1] - 30) - 8 for p in pts if math.hypot(p[0] - 40, p[1] - 30) < 12]
print(len(bore), "bore points, range", min(bore), max(bore))
sys.exit(0 if len(bore) > 20 and min(bore) >= -0.01 / 1000 and max(bore) <= 0.01 else 1)
'
check_grep '^// tolerance: 0\.01 mm ' "$tmp/b.scad" "the header states the tolerance"
check_grep '^// coordinates: fewest digits within 1e-05 mm \(tolerance/1000\)' "$tmp/b.scad" \
    "the header states the digits' share of it"

begin_case "bracket under --fit outside, middle, clearance: straight edges stay on their lines"
for fit in outside middle clearance; do
    check "scadprofile --fit $fit" "$bin" --tolerance 0.01 --fit "$fit" -o "$tmp/b-$fit.scad" "$tmp/bracket.svg"
    points "$tmp/b-$fit.scad" >"$tmp/b-$fit.pts"
    # The plate's sides x = 0, x = 80 and y = 0 are straight edges: no vertex
    # may leave them outward. The top (y = 50) is the lug's arc: outside
    # and middle may put its vertex up to the tolerance beyond it.
    check "--fit $fit: x in 0..80, y in 0..50.01" py '
import sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/b-'"$fit"'.pts")]
xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
box = (min(xs), max(xs), min(ys), max(ys))
print(len(pts), "points, box", box)
sys.exit(0 if box[0] == 0 and box[1] == 80 and box[2] == 0 and 50 <= box[3] <= 50.01 else 1)
'
done

begin_case "rounding that would make points meet: written exactly, with a warning"
# (10, 0) and (10, 3.14e-6) are one point at 1e-5 (tolerance 0.01 / 1000);
# 1e-6 would stay (a short number of the input), 3.1415926535e-6 is not
printf 'v 0 0\nv 10 0\nv 10 0.0000031415926535\nv 10 10\nv 0 10\n' >"$tmp/close.txt"
check "accepted with a warning" fails_with 0 "would make the profile invalid .*written exactly instead" \
    "$bin" --flatten-only --tolerance 0.01 -o "$tmp/close.scad" "$tmp/close.txt"
check_grep '^  \[10,3\.1415926535e-06\],$' "$tmp/close.scad" "the close point keeps its value"
printf 'v 0 0\nv 10 0\nv 10 0.000001\nv 10 10\nv 0 10\n' >"$tmp/short.txt"
check "a short number of the input is kept" "$bin" --flatten-only --tolerance 0.01 -o "$tmp/short.scad" "$tmp/short.txt"
check_grep '^  \[10,1e-06\],$' "$tmp/short.scad" "(10, 1e-06) as written"
check_true "no warning" test ! -s "$err"
check_grep '^// coordinates: exact' "$tmp/close.scad" "the header says so"
check "--levels writes exact round-trip numbers" "$bin" --levels 2 -o "$tmp/lv.scad" "$tmp/close.txt"
check_grep '^// coordinates: exact' "$tmp/lv.scad"

# --------------------------------------------------------------- modules
begin_case "no top-level geometry: include, then linear_extrude(3) NAME()"
check "the default file" "$bin" --tolerance 0.01 -o "$tmp/gen.scad" "$tmp/bracket.svg"
check "no top-level statement but definitions" py '
import re, sys
bad = []
depth = 0
for line in open("'"$tmp"'/gen.scad"):
    s = line.split("//")[0].rstrip()
    if depth == 0 and s and not s.startswith((" ", "function ", "module ")):
        bad.append(line)
    depth += s.count("[") - s.count("]")
print(bad)
sys.exit(0 if not bad and depth == 0 else 1)
'
check_grep '^module bracket\(center=false\)$' "$tmp/gen.scad" "module NAME(center=false)"
check_grep '^function bracket_points\(\) = \[$' "$tmp/gen.scad"
check_grep '^function bracket_paths\(\) = \[$' "$tmp/gen.scad"
if has_openscad; then
    printf 'include <gen.scad>\nlinear_extrude(3) bracket();\n' >"$tmp/inc.scad"
    check "include <gen.scad> + linear_extrude(3) bracket(): OpenSCAD renders it, no WARNING or ERROR" \
        openscad_clean "$tmp/inc.stl" "$tmp/inc.scad"
    printf 'use <gen.scad>\nlinear_extrude(3) bracket();\n' >"$tmp/use.scad"
    check "use <gen.scad> the same" openscad_clean "$tmp/use.stl" "$tmp/use.scad"
    printf 'include <gen.scad>\nbracket(center=true);\necho(bracket_bbox());\n' >"$tmp/ctr.scad"
    check "bracket(center=true) exports to SVG" openscad_clean "$tmp/ctr.svg" "$tmp/ctr.scad"
    check_grep '^ECHO: \[\[0, 0\], \[80, 50\]\]$' "$tmp/openscad.log" "bracket_bbox() evaluates to the box"
    check "center=true: the exported box is -40..40 x -25..25" py '
import re, sys
d = " ".join(re.findall(r"<path d=\"(.*?)\"", open("'"$tmp"'/ctr.svg").read(), re.S))
pts = [(float(x), -float(y)) for x, y in re.findall(r"([-0-9.e+]+),([-0-9.e+]+)", d)]
xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
box = (min(xs), max(xs), min(ys), max(ys))
print(box)
sys.exit(0 if max(abs(a - b) for a, b in zip(box, (-40, 40, -25, 25))) <= 1e-4 else 1)
'
else
    skip_case "openscad not installed"
fi

begin_case "--demo-call, --extrude and --no-demo-call"
check "--demo-call" "$bin" --demo-call -o "$tmp/demo.scad" "$tmp/bracket.svg"
check_true "the file ends with bracket();" sh -c "tail -n 1 '$tmp/demo.scad' | grep -qx 'bracket();'"
check "--extrude 5 implies the call (the file renders the solid alone)" \
    "$bin" --extrude 5 -o "$tmp/ext.scad" "$tmp/bracket.svg"
check_true "the file ends with bracket_extruded();" sh -c "tail -n 1 '$tmp/ext.scad' | grep -qx 'bracket_extruded();'"
check "--extrude 5 --no-demo-call" "$bin" --extrude 5 --no-demo-call -o "$tmp/ext2.scad" "$tmp/bracket.svg"
check_grep '^module bracket_extruded\(height=5, center=false\)$' "$tmp/ext2.scad" "the wrapper is there"
check_no_grep '^bracket' "$tmp/ext2.scad" "no top-level call"
check_true "the default file has no call" sh -c "! grep -q '^bracket' '$tmp/gen.scad'"
if has_openscad; then
    check "the --demo-call file renders alone" openscad_clean "$tmp/demo.svg" "$tmp/demo.scad"
    check "the --extrude file renders alone" openscad_clean "$tmp/ext.stl" "$tmp/ext.scad"
fi
check "--help documents --demo-call, --no-demo-call, --fit and the interface" sh -c \
    "'$bin' --help > '$tmp/help.txt' && grep -q -- '--demo-call ' '$tmp/help.txt' && grep -q -- '--no-demo-call' '$tmp/help.txt' && grep -q -- '--fit=F' '$tmp/help.txt' && grep -q 'NAME_bbox()' '$tmp/help.txt' && grep -q 'include <OUT.scad>' '$tmp/help.txt'"

begin_case "--module defaults to the file name"
check "bracket.svg: module bracket, no warning" "$bin" -o "$tmp/m1.scad" "$tmp/bracket.svg"
check_grep '^module bracket\(center=false\)$' "$tmp/m1.scad"
check_true "no warning" test ! -s "$err"
check "'my-bracket v2.svg' is made into my_bracket_v2, with a warning" fails_with 0 \
    "warning: .*my-bracket v2.svg: the module is named 'my_bracket_v2'" \
    "$bin" -o "$tmp/m2.scad" "$tmp/my-bracket v2.svg"
check_grep '^module my_bracket_v2\(center=false\)$' "$tmp/m2.scad"
cp "$tmp/bracket.svg" "$tmp/2d.svg"
cp "$tmp/bracket.svg" "$tmp/for.svg"
check "2d.svg: a leading digit gets '_'" fails_with 0 "named '_2d'" "$bin" -o "$tmp/m3.scad" "$tmp/2d.svg"
check_grep '^module _2d\(center=false\)' "$tmp/m3.scad"
check "for.svg: a reserved word gets '_' after it" fails_with 0 "named 'for_'" "$bin" -o "$tmp/m4.scad" "$tmp/for.svg"
check_grep '^module for_\(center=false\)' "$tmp/m4.scad"
check "stdin keeps profile" sh -c "'$bin' - < '$tmp/bracket.svg' > '$tmp/m5.scad' 2> '$tmp/m5.err'"
check_grep '^module profile\(center=false\)' "$tmp/m5.scad"
check_true "stdin: no warning" test ! -s "$tmp/m5.err"
check "--module overrides it without a warning" "$bin" --module plate -o "$tmp/m6.scad" "$tmp/my-bracket v2.svg"
check_grep '^module plate\(center=false\)' "$tmp/m6.scad"
check_true "no warning" test ! -s "$err"
if has_openscad; then
    printf 'include <m1.scad>\ninclude <m2.scad>\nbracket();\ntranslate([100, 0]) my_bracket_v2();\n' >"$tmp/two.scad"
    check "two generated profiles included side by side do not collide" \
        openscad_clean "$tmp/two.svg" "$tmp/two.scad"
fi

# --------------------------------------------------------------- refusals
begin_case "coordinates beyond +-1e12 are refused, naming file, element and subpath"
printf '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">\n<rect id="ok" width="10" height="10"/>\n<path id="far" d="M0 0H1 V1Z M0 0 L1e15 0 L0 1Z"/>\n</svg>\n' >"$tmp/e15.svg"
check "1e15 refused" fails_with 1 \
    "error: .*e15.svg:3: path 'far': subpath 2: point 2 (1e+15, 100) is out of range" \
    "$bin" -o "$tmp/e15.scad" "$tmp/e15.svg"
check_true "nothing written" test ! -e "$tmp/e15.scad"
check "--force does not write it either" fails_with 1 "out of range" \
    "$bin" --force -o "$tmp/e15.scad" "$tmp/e15.svg"
check_true "nothing written" test ! -e "$tmp/e15.scad"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path id="t" d="M0 0L1e200 0L0 1e200Z"/></svg>\n' >"$tmp/e200.svg"
check "a triangle at 1e200 is out of range" fails_with 1 "path 't': subpath 1: point 2 .* is out of range" \
    "$bin" -o "$tmp/e200.scad" "$tmp/e200.svg"
check_no_grep 'zero area|collinear' "$tmp/fw.err" "not 'zero area (collinear)'"
printf 'v 0 0\nv 1 0\n# far\nv 1e13 1\nv 0 1\n' >"$tmp/far.txt"
check "a point file names the line of the point" fails_with 1 "far.txt:4: point 3 (10000000000000, 1) is out of range" \
    "$bin" --tolerance 0.1 -o "$tmp/far.scad" "$tmp/far.txt"
check "the same with --levels" fails_with 1 "far.txt:4: point 3 .* is out of range" \
    "$bin" --levels 2 -o "$tmp/far.scad" "$tmp/far.txt"
printf '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100"><rect width="1e12" height="1"/></svg>\n' >"$tmp/e12.svg"
check "exactly 1e12 is accepted" "$bin" -o "$tmp/e12.scad" "$tmp/e12.svg"

begin_case "zero-area subpaths are skipped with a warning that names them; the rest is written"
cat >"$tmp/za.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
  <path id="a" d="M0 0H10V10H0Z M20 20 L30 30 M40 40 L50 50 L60 60Z M20 0 H30 V10 H20 Z"/>
  <rect x="50" y="0" width="5" height="5"/>
  <path d="M70 0 L80 0"/>
</svg>
EOF
check "written, exit 0" "$bin" -o "$tmp/za.scad" "$tmp/za.svg"
check_grep "^scadprofile: warning: .*za.svg:2: path 'a': subpath 2 has 2 points \(a polygon needs 3\); skipped$" "$err" \
    "subpath 2 of path 'a' (two points) named with its line"
check_grep "^scadprofile: warning: .*za.svg:2: path 'a': subpath 3 has zero area .*; skipped$" "$err" \
    "subpath 3 (collinear) named"
check_grep "^scadprofile: warning: .*za.svg:4: path \(no id\): subpath 1 has 2 points" "$err" \
    "an element without id by its tag and line"
check_count 3 'warning' "$err" "three warnings, nothing else"
check_grep '^// 3 outer contours, 0 holes' "$tmp/za.scad" "the three squares are written"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0 M5 5 L6 6 L7 7Z"/></svg>\n' >"$tmp/none.svg"
check "nothing left: an error, nothing written" fails_with 1 "nothing to write: none of the 2 subpaths encloses an area" \
    "$bin" -o "$tmp/none.scad" "$tmp/none.svg"
check_true "nothing written" test ! -e "$tmp/none.scad"
check_grep "warning: .*none.svg:1: path \(no id\): subpath 2 has zero area" "$tmp/fw.err" "each is named first"
# overlapping subpaths are what the fill rule makes of them (nonzero: the
# union), not an error (before issue 31: "subpath 1 and subpath 3 meet")
printf '<svg xmlns="http://www.w3.org/2000/svg"><path id="x" d="M0 0H10V10H0Z M20 20L21 21 M5 5H15V15H5Z"/></svg>\n' >"$tmp/x.svg"
check "overlapping subpaths: their union is written" "$bin" -o "$tmp/x.scad" "$tmp/x.svg"
points "$tmp/x.scad" >"$tmp/x.pts"
check "the union's outline: 8 corners, area 175 px^2 in mm^2" py '
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/x.pts")]
a = sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1] for i in range(len(pts))) / 2
print(len(pts), a)
import sys; sys.exit(0 if len(pts) == 8 and abs(a - 175 * (25.4 / 96) ** 2) < 1e-3 else 1)
'

# --------------------------------------------------------------- fit
begin_case "--fit: accepted, written in the header, refused where not supported"
for f in inside outside middle clearance; do
    check "--fit $f" "$bin" --fit $f --tolerance 0.01 -o "$tmp/fit-$f.scad" "$tmp/disc.svg"
    check_grep "^// fit: $f \(" "$tmp/fit-$f.scad" "the header says fit: $f"
done
check_grep '^// fit: inside \(' "$tmp/gen.scad" "inside is the default"
check "a bad --fit is a usage error" fails_with 2 "--fit must be inside, outside, middle or clearance" \
    "$bin" --fit sideways "$tmp/disc.svg"
printf 'v 0 0\nv 1 0\nv 0 1\n' >"$tmp/tri.txt"
check "--fit outside on a point file: usage error" fails_with 2 "point-normal input supports only --fit inside" \
    "$bin" --fit outside "$tmp/tri.txt"
check "--fit middle on a spline: usage error" fails_with 2 "spline input supports only --fit inside" \
    "$bin" --fit middle examples/nurbs-circle.spl
check "--fit inside on a point file is fine" "$bin" --fit inside -o "$tmp/tri.scad" "$tmp/tri.txt"
check "--fit outside with --levels: usage error" fails_with 2 "--levels keeps every subdivision point" \
    "$bin" --fit outside --levels 2 "$tmp/disc.svg"

begin_case "--fit geometry: outside and middle circles, clearance holes"
T=0.01
for f in inside outside middle; do
    "$bin" --fit $f --tolerance $T -o "$tmp/c-$f.scad" "$tmp/circle.svg" 2>/dev/null
    points "$tmp/c-$f.scad" >"$tmp/c-$f.pts"
done
if cmp -s "$tmp/c-inside.pts" "$tmp/c-outside.pts"; then
    skip_case "conica_path_flatten does not honour the fit yet (outside = inside)"
fi
check "inside: vertices on the circle (to the digits, T/1000)" py '
import math, sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/c-inside.pts")]
d = [math.hypot(x - 50, y - 50) - 20 for x, y in pts]
print(len(pts), min(d), max(d))
sys.exit(0 if max(map(abs, d)) <= '$T' / 1000 else 1)
'
check "outside: every vertex at radius >= r and <= r + T" py '
import math, sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/c-outside.pts")]
d = [math.hypot(x - 50, y - 50) - 20 for x, y in pts]
print(len(pts), min(d), max(d))
sys.exit(0 if min(d) >= 0 and max(d) <= '$T' else 1)
'
check "outside: every chord within T/1000 (the digits) of touching or clearing the circle" py '
import math, sys
p = [(x - 50, y - 50) for x, y in (tuple(map(float, l.split())) for l in open("'"$tmp"'/c-outside.pts"))]
n = len(p)
def near(a, b):  # distance of the centre from the chord
    dx, dy = b[0] - a[0], b[1] - a[1]
    t = max(0.0, min(1.0, -(a[0] * dx + a[1] * dy) / (dx * dx + dy * dy)))
    return math.hypot(a[0] + t * dx, a[1] + t * dy)
worst = min(near(p[i], p[(i + 1) % n]) for i in range(n)) - 20
print("closest chord - r:", worst)
sys.exit(0 if worst >= -'$T' / 1000 else 1)
'
check "middle has fewer points than inside" py '
import sys
a = sum(1 for _ in open("'"$tmp"'/c-inside.pts")); b = sum(1 for _ in open("'"$tmp"'/c-middle.pts"))
print("inside", a, "middle", b)
sys.exit(0 if b < a else 1)
'
points "$tmp/fit-clearance.scad" >"$tmp/cl.pts"
points "$tmp/fit-inside.scad" >"$tmp/in.pts"
check "clearance: outline vertices on the r 20 circle, bore vertices in [8, 8 + T]" py '
import math, sys
pts = [tuple(map(float, l.split())) for l in open("'"$tmp"'/cl.pts")]
d = [math.hypot(x - 50, y - 50) for x, y in pts]
outer = [r - 20 for r in d if r > 14]; bore = [r - 8 for r in d if r < 14]
print(len(outer), min(outer), max(outer), len(bore), min(bore), max(bore))
sys.exit(0 if max(map(abs, outer)) <= '$T' / 1000 and min(bore) >= 0 and max(bore) <= '$T' else 1)
'
# inside keeps to the painted region: its holes are never smaller than
# drawn, so clearance (outlines inside, holes outside) is the same polygon
check "inside: the same polygon as clearance (holes outside their circle)" cmp "$tmp/cl.pts" "$tmp/in.pts"

finish
