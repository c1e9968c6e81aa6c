#!/bin/sh
# SPDX-License-Identifier: MIT
# `make bench`, OpenSCAD part (called by scripts/bench.sh with BUILD as $1).
# A circle of radius 50 mm from 8 exact point-normal samples, written by
# scadprofile at tolerances 0.1 / 0.01 / 0.001 mm:
#  - points used vs the minimum ceil(pi / acos(1 - tol / r)) and vs OpenSCAD's
#    defaults ($fa = 12, $fs = 2: 30 segments) with their actual error;
#  - OpenSCAD render time (CGAL, a plate minus the extruded profile, exported
#    to STL) of our profile vs circle(r = 50, $fn = N) of equal accuracy.
# Prints figures, asserts nothing.
set -u
build=${1:-build}
bin=$build/bin/scadprofile
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bench-scad.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

"$PY" - "$tmp/circle.txt" <<'EOF'
import math, sys
with open(sys.argv[1], "w") as f:
    for k in range(8):
        t = k * math.pi / 4
        f.write("v %r %r\n" % (50 * math.cos(t), 50 * math.sin(t)))
    for k in range(8):
        t = k * math.pi / 4
        f.write("vn %r %r\n" % (math.cos(t), math.sin(t)))
EOF

# seconds of wall time for one OpenSCAD export
render_time() { # scad
    "$PY" - "$1" <<'EOF'
import subprocess, sys, time
t = time.perf_counter()
r = subprocess.run(["openscad", "-o", sys.argv[1] + ".stl", sys.argv[1]], capture_output=True, text=True)
dt = time.perf_counter() - t
print("%.2f" % dt if r.returncode == 0 and "WARNING:" not in r.stderr else "failed")
EOF
}

printf '%-9s %8s %8s %7s %12s %12s | %10s %10s\n' tol points minimum ratio "our error" "ms (ours)" "render ours" "render \$fn"
for tol in 0.1 0.01 0.001; do
    "$bin" --tolerance "$tol" --module ours --stats -o "$tmp/ours.scad" "$tmp/circle.txt" 2>"$tmp/stats" || exit 1
    ms=$(sed -n 's/.*; \([0-9.]*\) ms$/\1/p' "$tmp/stats")
    line=$("$PY" - "$tmp/ours.scad" "$tol" <<'EOF'
import math, re, sys
text = open(sys.argv[1]).read()
m = re.search(r"function ours_points\(\) = \[(.*?)\];", text, re.S)
pts = [tuple(map(float, p)) for p in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", m.group(1))]
r, tol, n = 50.0, float(sys.argv[2]), len(pts)
minimum = math.ceil(math.pi / math.acos(1 - tol / r))
# largest distance between polygon and circle: vertex radial error + chord sagitta
err = max(abs(math.hypot(*p) - r) + r - math.sqrt(r * r - (math.dist(p, pts[(i + 1) % n]) / 2) ** 2)
          for i, p in enumerate(pts))
print(n, minimum, "%.3f" % (n / minimum), "%.3g" % err)
EOF
)
    set -- $line
    n=$1 minimum=$2
    cat >"$tmp/a.scad" <<EOF
use <ours.scad>
difference() { translate([-60, -60, 0]) cube([120, 120, 5]); translate([0, 0, -1]) linear_extrude(7) ours(); }
EOF
    cat >"$tmp/b.scad" <<EOF
difference() { translate([-60, -60, 0]) cube([120, 120, 5]); translate([0, 0, -1]) linear_extrude(7) circle(r=50, \$fn=$minimum); }
EOF
    if command -v openscad >/dev/null 2>&1; then
        ta=$(render_time "$tmp/a.scad")
        tb=$(render_time "$tmp/b.scad")
    else
        ta=n/a tb=n/a
    fi
    printf '%-9s %8s %8s %7s %12s %12s | %9ss %9ss\n' "$tol" "$n" "$minimum" "$3" "$4" "$ms" "$ta" "$tb"
done
"$PY" -c '
import math
r = 50
for name, n in (("OpenSCAD defaults ($fa=12, $fs=2)", max(min(360 / 12, 2 * math.pi * r / 2), 5)), ("$fn=360", 360)):
    n = math.ceil(n)
    print("%-34s %4d segments, error %.4f mm" % (name, n, r * (1 - math.cos(math.pi / n))))
'
echo "(render: wall time of 'openscad -o x.stl' for a 120x120x5 plate minus the extruded circle;"
echo " \$fn = the minimum point count, i.e. the same accuracy as the tolerance)"
