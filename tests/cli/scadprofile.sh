#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite of scadprofile, with the real OpenSCAD (headless) where present.
#   sh tests/cli/scadprofile.sh BUILD_DIR      (from the repository root)
# Prints a Catch2-style summary. OpenSCAD runs are few (about 1 s each).
set -u
. "$(dirname "$0")/harness.sh"
bin=$build/bin/scadprofile
has_openscad() { command -v openscad >/dev/null 2>&1; }
# OpenSCAD must exit 0 and print no WARNING: line.
openscad_ok() { # out in
    openscad -o "$1" "$2" >"$tmp/openscad.log" 2>&1 || { cat "$tmp/openscad.log"; return 1; }
    if grep -q 'WARNING:' "$tmp/openscad.log"; then cat "$tmp/openscad.log"; return 1; fi
    [ -s "$1" ]
}
openscad_binstl() { # out in
    openscad --export-format binstl -o "$1" "$2" >"$tmp/openscad.log" 2>&1 || { cat "$tmp/openscad.log"; return 1; }
    if grep -q 'WARNING:' "$tmp/openscad.log"; then cat "$tmp/openscad.log"; return 1; fi
    [ -s "$1" ]
}
# pyenv shims cost about a second per start: prefer the system interpreter.

begin_case "scadprofile is built"
check_true "$bin exists" test -x "$bin"

# --------------------------------------------------------------- inputs
# Ellipse a = 30, b = 20 from 8 exact samples with exact unit normals; the
# quarter points are written with exact zeros.
py '
import math
a, b = 30.0, 20.0
pts = []
for k in range(8):
    t = k * math.pi / 4
    c, s = math.cos(t), math.sin(t)
    if k % 2 == 0:
        c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][k // 2]
    x, y = a * c, b * s
    nx, ny = x / a**2, y / b**2
    l = math.hypot(nx, ny)
    pts.append((x, y, nx / l, ny / l))
with open("'"$tmp"'/ellipse.txt", "w") as f:
    for p in pts: f.write("v %r %r\n" % (p[0], p[1]))
    for p in pts: f.write("vn %r %r\n" % (p[2], p[3]))
r = 50.0
with open("'"$tmp"'/circle.txt", "w") as f:
    for k in range(8):
        t = k * math.pi / 4
        f.write("v %r %r\n" % (1000 + r * math.cos(t), -300 + r * math.sin(t)))
    for k in range(8):
        t = k * math.pi / 4
        f.write("vn %r %r\n" % (math.cos(t), math.sin(t)))
'
printf 'v 0 0\nv 2 2\nv 2 0\nv 0 2\n' >"$tmp/bowtie.txt"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0\nc 1\nc 0\n' >"$tmp/fn.spl"
# A plate 60 x 40 mm with a round hole (r 8) and a slot with round ends
# (evenodd), drawn in px on a 120 x 80 viewBox spanning 60 x 40 mm.
cat >"$tmp/plate.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 120 80">
  <path id="plate" fill-rule="evenodd"
        d="M0,0 H120 V80 H0 Z
           M46,40 A16,16 0 1 0 14,40 A16,16 0 1 0 46,40 Z
           M70,30 H100 A10,10 0 0 1 100,50 H70 A10,10 0 0 1 70,30 Z"/>
</svg>
EOF

# --------------------------------------------------------------- cases
begin_case "help, version and usage errors"
check "--help exits 0" "$bin" --help
check "--version names the tool" sh -c "'$bin' --version | grep -q '^scadprofile '"
check "--levels with --tolerance is a usage error" fails_with 2 "exclude" "$bin" --levels 3 --tolerance 1 "$tmp/ellipse.txt"
check "unknown option" fails_with 2 "unknown option" "$bin" --frobnicate "$tmp/ellipse.txt"
check "bad module name" fails_with 2 "identifier" "$bin" --module 9lives "$tmp/ellipse.txt"
# OpenSCAD keywords would make a file OpenSCAD cannot parse; the built-ins the
# file calls would be replaced by the module itself
for word in for module function if else let each true false undef include use assert echo; do
    check "--module $word is a usage error" fails_with 2 "'$word' is an OpenSCAD reserved word" \
        "$bin" --module "$word" -o "$tmp/kw.scad" "$tmp/ellipse.txt"
done
check "nothing written for a reserved word" test ! -e "$tmp/kw.scad"
check "--module polygon is a usage error" fails_with 2 "built-in module" "$bin" --module polygon "$tmp/ellipse.txt"
check "a name containing a keyword is fine" "$bin" --levels 1 --module for_each -o "$tmp/kw.scad" "$tmp/ellipse.txt"

begin_case "stdin is identified by its content"
check "a spline file on stdin (comment line first) is read as a spline" \
    sh -c "'$bin' --tolerance 0.01 - < examples/nurbs-circle.spl > '$tmp/stdin-spl.scad'"
check_grep '^// source: - \(spline\)$' "$tmp/stdin-spl.scad" "header names the spline reader"
check "the same from the named file" "$bin" --tolerance 0.01 -o "$tmp/file-spl.scad" examples/nurbs-circle.spl
check_true "same points either way" test "$(grep -c '^  \[' "$tmp/stdin-spl.scad")" -eq "$(grep -c '^  \[' "$tmp/file-spl.scad")"
check "an SVG on stdin" sh -c "'$bin' --flatten-only - < '$tmp/plate.svg' > '$tmp/stdin-svg.scad'"
check_grep '^// source: - \(SVG\)$' "$tmp/stdin-svg.scad"
check "a point file on stdin" sh -c "'$bin' --levels 2 - < '$tmp/ellipse.txt' > '$tmp/stdin-pts.scad'"
check_grep '^// source: - \(point-normal\)$' "$tmp/stdin-pts.scad"

begin_case "errors name the file and line; nothing is written"
printf 'v 0 0\nv 1 0\nv 1 x\n' >"$tmp/bad.txt"
check "parse error as FILE:LINE" fails_with 1 "scadprofile: error: $tmp/bad.txt:3:" "$bin" "$tmp/bad.txt"
echo keep >"$tmp/keep.scad"
check "bowtie refused with its segment pair" fails_with 1 "segment 1 (points 1-2) and segment 3 (points 3-4)" \
    "$bin" --flatten-only -o "$tmp/keep.scad" "$tmp/bowtie.txt"
check "target untouched" sh -c "[ \"\$(cat '$tmp/keep.scad')\" = keep ]"
check "no temporary left behind" sh -c "[ \$(ls '$tmp' | grep -c keep) -eq 1 ]"
check "profile crossing the axis refused for rotate_extrude" fails_with 1 "x < 0" \
    "$bin" --levels 2 --rotate-extrude -o "$tmp/axis.scad" "$tmp/ellipse.txt"
check "nothing written" test ! -e "$tmp/axis.scad"
check "--force writes it with a warning" fails_with 0 "warning:.*x < 0" \
    "$bin" --levels 2 --rotate-extrude --force -o "$tmp/axis.scad" "$tmp/ellipse.txt"
check "forced file exists" test -s "$tmp/axis.scad"
printf 'v 0 0\nv 1 1\nv 3 3\n' >"$tmp/collinear.txt"
check "collinear points: zero area, not a self-intersection" fails_with 1 \
    "collinear.txt: the contour has zero area .*; nothing to write" "$bin" --flatten-only "$tmp/collinear.txt"
check_no_grep 'intersects' "$tmp/fw.err" "no self-intersection claimed"
printf '# a square with a repeated corner\nv 0 0\nv 1 0\n\nv 1 0\nv 0 1\n' >"$tmp/dup.txt"
check "duplicate point names its line (subdivision)" fails_with 1 "$tmp/dup.txt:3: points 1 and 2 coincide" \
    "$bin" --levels 2 "$tmp/dup.txt"
check "duplicate point names its line (validation)" fails_with 1 "$tmp/dup.txt:3: .*points 2 and 3 are equal" \
    "$bin" --flatten-only "$tmp/dup.txt"

begin_case "tolerance: near-minimal points for a circle r=50"
for tol in 0.1 0.01 0.001; do
    "$bin" --tolerance $tol --module profile -o "$tmp/c.scad" "$tmp/circle.txt" 2>"$tmp/c.err"
    check "tolerance $tol: circle points within tol/1000 (the digits), within 1.1x of the minimum, polygon within tol" py '
import math, re, sys
tol = '$tol'
text = open("'"$tmp"'/c.scad").read()
m = re.search(r"function profile_points\(\) = \[(.*?)\];", text, re.S)
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1))]
n = len(pts); r = 50.0
minimum = math.ceil(math.pi / math.acos(1 - tol / r))
on = max(abs(math.hypot(x - 1000, y + 300) - r) for x, y in pts)
chord = max(r - math.sqrt(r*r - (math.dist(pts[i], pts[(i+1) % n]) / 2) ** 2) for i in range(n))
print("points", n, "minimum", minimum, "on-circle", on, "chord error", chord)
sys.exit(0 if (minimum <= n <= 1.1 * minimum and on <= tol / 1000 and chord + on <= tol) else 1)
'
done

begin_case "spline input: a rational quadratic (NURBS) circle through the plotter"
# r = 50 about (10, 20): 9 control points, weights 1, sqrt(2)/2, ...
py '
import math
h = math.sqrt(0.5)
c = [(1,0),(1,1),(0,1),(-1,1),(-1,0),(-1,-1),(0,-1),(1,-1),(1,0)]
with open("'"$tmp"'/circle.spl", "w") as f:
    f.write("degree 2\nknots 0 0 0 0.25 0.25 0.5 0.5 0.75 0.75 1 1 1\n")
    for x, y in c: f.write("c %r %r\n" % (10 + 50 * x, 20 + 50 * y))
    f.write("w " + " ".join("1" if k % 2 == 0 else repr(h) for k in range(9)) + "\n")
'
check "scadprofile --tolerance 0.01 circle.spl" "$bin" --tolerance 0.01 --module profile -o "$tmp/spl.scad" "$tmp/circle.spl"
check "points within 0.01/1000 of the circle, polygon within 0.01, within 1.1x of the minimum 158" py '
import math, re, sys
text = open("'"$tmp"'/spl.scad").read()
m = re.search(r"function profile_points\(\) = \[(.*?)\];", text, re.S)
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1))]
n, r = len(pts), 50.0
on = max(abs(math.hypot(x - 10, y - 20) - r) for x, y in pts)
chord = max(r - math.sqrt(r*r - (math.dist(pts[i], pts[(i+1) % n]) / 2) ** 2) for i in range(n))
print(n, "points, on-circle", on, "chord", chord)
sys.exit(0 if 158 <= n <= 1.1 * 158 and on <= 0.01 / 1000 and chord + on <= 0.01 else 1)
'
check "an open 1-D spline function is refused" fails_with 1 "planar spline" "$bin" "$tmp/fn.spl"

if has_openscad; then
begin_case "ellipse level 8: exact points, OpenSCAD export on the ellipse, area"
check "scadprofile --levels 8 --demo-call" "$bin" --levels 8 --module ell --demo-call -o "$tmp/ell.scad" "$tmp/ellipse.txt"
check "every point within 1e-9 of the ellipse's size" py '
import math, re, sys
a, b = 30.0, 20.0
text = open("'"$tmp"'/ell.scad").read()
m = re.search(r"function ell_points\(\) = \[(.*?)\];", text, re.S)
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1))]
def dist(x, y):  # first-order distance to the ellipse
    f = x*x/(a*a) + y*y/(b*b) - 1
    return abs(f) / math.hypot(2*x/(a*a), 2*y/(b*b))
worst = max(dist(x, y) for x, y in pts)
print(len(pts), "points, worst distance", worst)
sys.exit(0 if len(pts) == 8 * 256 and worst <= 1e-9 * a else 1)
'
check "OpenSCAD renders it to SVG without warnings" openscad_ok "$tmp/ell.svg" "$tmp/ell.scad"
check "scadprofile --extrude for an OFF export" "$bin" --levels 4 --extrude 3 --module offtest -o "$tmp/off.scad" "$tmp/ellipse.txt"
check "OpenSCAD exports it to OFF without warnings" openscad_ok "$tmp/off.off" "$tmp/off.scad"
check_true "the OFF file starts with its header and counts" \
    sh -c "head -n 1 '$tmp/off.off' | grep -q -E '^OFF( [0-9]+){3}\$'"
check "exported vertices on the ellipse to 6 digits, area within 1e-5 of pi a b" py '
import math, re, sys
a, b = 30.0, 20.0
d = re.search(r"<path d=\"(.*?)\"", open("'"$tmp"'/ell.svg").read(), re.S).group(1)
pts = [(float(x), -float(y)) for x, y in re.findall(r"([-0-9.e+]+),([-0-9.e+]+)", d)]
# Each exported coordinate carries the snap of OpenSCAD 2021 2D geometry to a
# 2^-16 grid plus its output to 6 significant digits, which is not always
# round-to-nearest (27.455963 comes out as 27.4559): allow one unit in the
# 6th digit and one grid step per coordinate, along the unit normal n:
# |nx| ex + |ny| ey.
def unit6(v):
    return 10 ** (math.floor(math.log10(abs(v))) - 5) if v else 0.0
bad = 0
worst = 0
for x, y in pts:
    f = x*x/(a*a) + y*y/(b*b) - 1
    gx, gy = 2*x/(a*a), 2*y/(b*b)
    g = math.hypot(gx, gy)
    dist = abs(f) / g
    bound = abs(gx) / g * (unit6(x) + 2**-16) + abs(gy) / g * (unit6(y) + 2**-16)
    worst = max(worst, dist / bound)
    if dist > bound: bad += 1
print("worst vertex distance / its rounding bound", worst)
area = 0.5 * abs(sum(pts[i][0]*pts[(i+1)%len(pts)][1] - pts[(i+1)%len(pts)][0]*pts[i][1] for i in range(len(pts))))
rel = abs(area - math.pi*a*b) / (math.pi*a*b)
print(len(pts), "vertices,", bad, "off the ellipse; area rel. error", rel)
sys.exit(0 if len(pts) == 2048 and bad == 0 and rel <= 1e-5 else 1)
'

begin_case "rotate_extrude of a half-ellipse profile: closed mesh, ellipsoid volume"
# The right half of the level-5 ellipse (its points are on the ellipse; the
# quarter points are exact (0, +-b)), closed along the axis.
"$bin" --levels 5 --module profile -o "$tmp/full.scad" "$tmp/ellipse.txt"
py '
import re
text = open("'"$tmp"'/full.scad").read()
m = re.search(r"function profile_points\(\) = \[(.*?)\];", text, re.S)
pts = [p for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1)) if float(p[0]) >= 0]
i = next(k for k, p in enumerate(pts) if float(p[0]) == 0 and float(p[1]) < 0)
pts = pts[i:] + pts[:i]   # from (0,-b) up the right side to (0,b)
with open("'"$tmp"'/half.txt", "w") as f:
    for x, y in pts: f.write("v %s %s\n" % (x, y))
'
check "scadprofile --rotate-extrude accepts the half profile" \
    "$bin" --flatten-only --rotate-extrude --module half -o "$tmp/half.scad" "$tmp/half.txt"
printf 'use <half.scad>\nhalf_revolved($fn=360);\n' >"$tmp/ellipsoid.scad"
check "OpenSCAD renders rotate_extrude(\$fn=360) to STL without warnings" openscad_binstl "$tmp/ellipsoid.stl" "$tmp/ellipsoid.scad"
check "closed mesh, volume within 1e-3 of 4/3 pi a^2 b" py '
import math, struct, sys
from collections import Counter
data = open("'"$tmp"'/ellipsoid.stl", "rb").read()
n = struct.unpack_from("<I", data, 80)[0]
vol = 0.0
edges = Counter()
for k in range(n):
    v = struct.unpack_from("<12f", data, 84 + 50 * k)
    p = [tuple(v[3:6]), tuple(v[6:9]), tuple(v[9:12])]
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = p
    vol += (ax*(by*cz - bz*cy) - ay*(bx*cz - bz*cx) + az*(bx*cy - by*cx)) / 6
    for i in range(3):
        edges[(p[i], p[(i+1) % 3])] += 1
open_edges = sum(1 for (u, w), c in edges.items() if edges.get((w, u), 0) != c)
exact = 4 / 3 * math.pi * 30.0**2 * 20.0
rel = abs(vol - exact) / exact
print(n, "triangles,", open_edges, "unmatched directed edges, volume", vol, "rel. error", rel)
sys.exit(0 if open_edges == 0 and rel <= 1e-3 else 1)
'

begin_case "SVG profile with holes renders with the holes"
check "scadprofile on the plate" "$bin" --tolerance 0.01 --extrude 5 --module plate -o "$tmp/plate.scad" "$tmp/plate.svg"
check "outer first, two holes" py '
import re, sys
t = open("'"$tmp"'/plate.scad").read()
print(t.splitlines()[4])
sys.exit(0 if "1 outer contour, 2 holes" in t else 1)
'
check "OpenSCAD renders the extrusion to STL without warnings" openscad_binstl "$tmp/plate.stl" "$tmp/plate.scad"
check "volume = (plate - holes) x 5 mm" py '
import math, struct, sys
data = open("'"$tmp"'/plate.stl", "rb").read()
n = struct.unpack_from("<I", data, 80)[0]
vol = 0.0
for k in range(n):
    v = struct.unpack_from("<12f", data, 84 + 50 * k)
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = v[3:6], v[6:9], v[9:12]
    vol += (ax*(by*cz - bz*cy) - ay*(bx*cz - bz*cx) + az*(bx*cy - by*cx)) / 6
area = 60 * 40 - math.pi * 8**2 - (15 * 10 + math.pi * 5**2)
rel = abs(vol - 5 * area) / (5 * area)
print("volume", vol, "expected", 5 * area, "rel", rel)
sys.exit(0 if rel <= 1e-3 else 1)
'
else
    begin_case "rendering with OpenSCAD"
    skip_case "openscad not installed"
fi

begin_case "SVG units, y flip and selection"
check "mm from the viewBox: the plate spans 0..60 x 0..40, hole centre y flipped" py '
import re, subprocess, sys
out = subprocess.run(["'"$bin"'", "--flatten-only", "--tolerance", "0.01", "'"$tmp"'/plate.svg"],
                     capture_output=True, text=True, check=True).stdout
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", out)]
xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
print(min(xs), max(xs), min(ys), max(ys))
sys.exit(0 if (min(xs), max(xs), min(ys), max(ys)) == (0, 60, 0, 40) else 1)
'
check "inches: 96 px per inch" py '
import re, subprocess, sys
out = subprocess.run(["'"$bin"'", "--units", "in", "--levels", "0", "'"$tmp"'/plate.svg"],
                     capture_output=True, text=True, check=True).stdout
xs = [float(p) for p in re.findall(r"\[([-0-9.e+]+),[-0-9.e+]+\]", out)]
print(max(xs), 60 / 25.4)
sys.exit(0 if abs(max(xs) - 60 / 25.4) <= 1e-12 else 1)
'

# (the painted region's message: nothing of the selection is painted)
check "unknown id selects nothing" fails_with 1 "nothing is painted" "$bin" --select nope "$tmp/plate.svg"
check_grep "warning: $tmp/plate.svg: .*no element has id 'nope'" "$tmp/fw.err" "the unknown id is named"

begin_case "--units px on a px document keeps the numbers exactly"
cat >"$tmp/px.svg" <<'EOF'
<svg xmlns="http://www.w3.org/2000/svg" width="100px" height="60px" viewBox="0 0 100 60">
  <path id="r" d="M0 0H100V60H0Z"/>
</svg>
EOF
printf '<svg xmlns="http://www.w3.org/2000/svg" width="100" height="60"><path d="M0 0H100V60H0Z"/></svg>\n' >"$tmp/px-noviewbox.svg"
for f in px px-noviewbox; do
    check "$f: --units px --levels 0" "$bin" --units px --levels 0 -o "$tmp/$f.scad" "$tmp/$f.svg"
    check_grep '^  \[100,60\]' "$tmp/$f.scad" "$f: corner (100, 60) exactly"
    check_no_grep '0000000' "$tmp/$f.scad" "$f: no rounding residue in the numbers"
done
check "--units in: 96 px = 1 in exactly" "$bin" --units in --levels 0 -o "$tmp/px-in.scad" "$tmp/px-noviewbox.svg"
check_grep '^  \[0,0\.625\]' "$tmp/px-in.scad" "60 px = 0.625 in"

begin_case "XML limits: --max-depth, --max-elements, --max-path-bytes, --max-input-bytes"
check "the plate passes the defaults" "$bin" --flatten-only -o "$tmp/lim.scad" "$tmp/plate.svg"
rm -f "$tmp/lim.scad"
check "--max-depth 1" fails_with 1 "plate.svg:2: elements nested deeper than 1 (--max-depth)" \
    "$bin" --max-depth 1 -o "$tmp/lim.scad" "$tmp/plate.svg"
check "--max-elements 1" fails_with 1 "plate.svg:2: more than 1 elements (--max-elements)" \
    "$bin" --max-elements 1 -o "$tmp/lim.scad" "$tmp/plate.svg"
check "--max-path-bytes 20" fails_with 1 "path 'plate': path data exceeds the limit of 20 bytes (--max-path-bytes)" \
    "$bin" --max-path-bytes 20 -o "$tmp/lim.scad" "$tmp/plate.svg"
check "--max-input-bytes 100 (SVG)" fails_with 1 "input larger than the limit of 100 bytes" \
    "$bin" --max-input-bytes 100 -o "$tmp/lim.scad" "$tmp/plate.svg"
check "--max-input-bytes 100 (point file)" fails_with 1 "input larger than the limit of 100 bytes" \
    "$bin" --max-input-bytes 100 -o "$tmp/lim.scad" "$tmp/ellipse.txt"
check "--max-input-bytes overrides CONICA_MAX_INPUT_BYTES" \
    env CONICA_MAX_INPUT_BYTES=10 "$bin" --max-input-bytes 100000 --levels 1 -o "$tmp/lim2.scad" "$tmp/ellipse.txt"
check "nothing written by the refused runs" test ! -e "$tmp/lim.scad"
check "a bad value is a usage error" fails_with 2 "--max-depth needs a whole number" "$bin" --max-depth 0 "$tmp/plate.svg"
check "--help lists the limit flags" sh -c "'$bin' --help | grep -c -E '^ +--max-(depth|elements|path-bytes|input-bytes)=N( |$)' | grep -qx 4"

finish
