#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo`, OpenSCAD part: the bundled SVG outline examples/bracket.svg
# becomes the OpenSCAD module file BUILD/demo/profile.scad (tolerance
# 0.01 mm), OpenSCAD renders its extrusion to BUILD/demo/profile.stl, and a
# picture of that STL is drawn (OpenSCAD's PNG export needs a display, so
# the mesh is projected and shaded here, as SVG, then rsvg-convert makes PNG).
# BUILD/demo/model.scad shows the profile used as a library (`use <...>`).
set -eu
build=${1:-build}
out=$build/demo
mkdir -p "$out"
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3

"$build/bin/scadprofile" --tolerance 0.01 --extrude 5 --module bracket --stats \
    -o "$out/profile.scad" examples/bracket.svg 2>"$out/profile.stats.txt"
echo "  examples/bracket.svg -> $out/profile.scad ($(grep -cE '^  \[[-0-9.e+]+,[-0-9.e+]+\](,|\];)$' "$out/profile.scad") points)"

# A model that uses the profile as a library, as a user would.
cat >"$out/model.scad" <<'EOF'
use <profile.scad>
// the bracket plate, with a boss around the bore
bracket_extruded(height=5);
translate([40, 30, 0]) difference() {
    cylinder(r=12, h=9, $fn=96);
    translate([0, 0, -1]) cylinder(r=8, h=11, $fn=96);
}
EOF

if ! command -v openscad >/dev/null 2>&1; then
    echo "  openscad not installed: skipping the STL and the picture"
    exit 0
fi
openscad -o "$out/profile.stl" "$out/profile.scad" >"$out/openscad.log" 2>&1
if grep -q 'WARNING:' "$out/openscad.log"; then
    cat "$out/openscad.log"
    exit 1
fi
echo "  $out/profile.scad -> $out/profile.stl (OpenSCAD $(openscad --version 2>&1 | sed 's/.* //'))"
openscad -o "$out/model.stl" "$out/model.scad" >"$out/openscad-model.log" 2>&1
if grep -q 'WARNING:' "$out/openscad-model.log"; then
    cat "$out/openscad-model.log"
    exit 1
fi
echo "  $out/model.scad (use <profile.scad> plus a boss) -> $out/model.stl"

# The `use <profile.scad>` example of README.md ("Using the profile in a
# model"), checked by OpenSCAD: it must evaluate without a warning.
cat >"$out/use-example.scad" <<'EOF'
use <profile.scad>
bracket_extruded(height=5);                    // the plate
translate([40, 30, 0]) difference() {          // a boss around the bore
    cylinder(r=12, h=9, $fn=96);
    translate([0, 0, -1]) cylinder(r=8, h=11, $fn=96);
}
linear_extrude(2, scale=0.9) bracket();        // or any 2D operation on bracket()
translate([0, 80, 0]) rotate([90, 0, 0])       // revolved about the y axis (all x >= 0);
    rotate_extrude(angle=90, $fn=90) bracket(); // $fn only sets the revolution's segments
echo(len(bracket_points()));                   // the data is there for your own code
EOF
openscad -o "$out/use-example.csg" "$out/use-example.scad" >"$out/openscad-use.log" 2>&1 || {
    cat "$out/openscad-use.log"
    exit 1
}
if grep -q 'WARNING:' "$out/openscad-use.log"; then
    cat "$out/openscad-use.log"
    exit 1
fi
echo "  $out/use-example.scad (README's use <profile.scad> example) evaluates: $(grep '^ECHO' "$out/openscad-use.log")"

# Shaded isometric view of the STL (flat shading, painter's algorithm).
"$PY" - "$out/model.stl" "$out/model-view.svg" <<'EOF'
import math, struct, sys

def read_stl(path):
    data = open(path, "rb").read()
    tris = []
    if data[:5] == b"solid" and b"facet" in data[:400]:
        cur = []
        for line in data.decode().splitlines():
            w = line.split()
            if w and w[0] == "vertex":
                cur.append(tuple(map(float, w[1:4])))
                if len(cur) == 3:
                    tris.append(cur)
                    cur = []
    else:
        n = struct.unpack_from("<I", data, 80)[0]
        for k in range(n):
            v = struct.unpack_from("<12f", data, 84 + 50 * k)
            tris.append([v[3:6], v[6:9], v[9:12]])
    return tris

tris = read_stl(sys.argv[1])
az, el = math.radians(-35), math.radians(35)
def view(p):
    x, y, z = p
    x1 = x * math.cos(az) - y * math.sin(az)
    y1 = x * math.sin(az) + y * math.cos(az)
    return (x1, y1 * math.sin(el) + z * math.cos(el), -y1 * math.cos(el) + z * math.sin(el))
light = (0.3, 0.5, 0.81)
polys = []
for t in tris:
    v = [view(p) for p in t]
    ux, uy, uz = (v[1][i] - v[0][i] for i in range(3))
    wx, wy, wz = (v[2][i] - v[0][i] for i in range(3))
    n = (uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx)
    ln = math.sqrt(sum(c * c for c in n)) or 1
    n = tuple(c / ln for c in n)
    if n[2] < 0:            # facing away (the screen looks down -z)
        continue
    shade = 0.35 + 0.65 * max(0.0, sum(a * b for a, b in zip(n, light)))
    polys.append((sum(p[2] for p in v) / 3, v, shade))
polys.sort(key=lambda q: q[0])
xs = [p[0] for _, v, _ in polys for p in v]
ys = [p[1] for _, v, _ in polys for p in v]
pad = 4
w, h = max(xs) - min(xs) + 2 * pad, max(ys) - min(ys) + 2 * pad
with open(sys.argv[2], "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="%g %g %g %g">\n'
            % (round(w * 8), round(h * 8), min(xs) - pad, -max(ys) - pad, w, h))
    f.write('<rect x="%g" y="%g" width="%g" height="%g" fill="white"/>\n' % (min(xs) - pad, -max(ys) - pad, w, h))
    for _, v, s in polys:
        c = "#%02x%02x%02x" % (int(74 * s), int(122 * s), int(181 * s))
        f.write('<path d="M%s Z" fill="%s" stroke="%s" stroke-width="0.05"/>\n'
                % (" L".join("%.4f,%.4f" % (p[0], -p[1]) for p in v), c, c))
    f.write("</svg>\n")
print("  %d triangles drawn" % len(polys))
EOF
if command -v rsvg-convert >/dev/null 2>&1; then
    rsvg-convert -w 800 "$out/model-view.svg" -o "$out/model-view.png"
    echo "  picture: $out/model-view.png (and .svg)"
else
    echo "  picture: $out/model-view.svg (rsvg-convert not installed: no PNG)"
fi
