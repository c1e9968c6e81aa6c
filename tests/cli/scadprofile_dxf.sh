#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite of scadprofile's DXF input (conica/dxf.h):
#   sh tests/cli/scadprofile_dxf.sh BUILD_DIR      (from the repository root)
# The drawings are made at run time by ezdxf (python3-ezdxf, an independent
# DXF writer: tests/dxf/make_cases.py); tests/dxf/check.py evaluates their
# exact geometry itself (de Boor, ezdxf's construction tools) and checks
# the two-sided deviation, the fit sign and the contours of each module.
# OpenSCAD's example drawings (Debian's openscad package) are read too.
set -u
. "$(dirname "$0")/harness.sh"
bin=$build/bin/scadprofile
conica=$build/bin/conica
cases=$tmp/cases
T=0.01

begin_case "scadprofile is built; ezdxf is present"
check_true "$bin exists" test -x "$bin"
if ! py 'import ezdxf, numpy' 2>/dev/null; then
    skip_case "python3-ezdxf or python3-numpy not installed (scripts/deps.sh test)"
    finish
fi
check "the drawings are made" "$PY" tests/dxf/make_cases.py "$cases"

# run NAME FIT [scadprofile options]: $cases/NAME.dxf -> $cases/NAME.FIT.scad
# (module m; each fit of a drawing its own file, so nothing is run twice)
run() {
    n=$1
    f=$2
    shift 2
    "$bin" --module m --tolerance $T --fit "$f" "$@" -o "$cases/$n.$f.scad" "$cases/$n.dxf"
}
# The geometry checks (tests/dxf/check.py against the drawing's exact
# geometry) are queued and run in one process at the end, each drawing's
# exact geometry evaluated once for all its fits; each is one assertion of
# its own, in a case named after the one that queued it.
tab=$(printf '\t')
jobs=$tmp/jobs
meta=$tmp/jobs.meta
: >"$jobs"
: >"$meta"
njobs=0
# deviation DESC DXF SCAD FIT [check.py options]
deviation() {
    njobs=$((njobs + 1))
    d=$1
    shift
    printf 'j%d\t%s %s m %s %s\n' "$njobs" "$1" "$2" "$T" "$(shift 2; echo "$*")" >>"$jobs"
    printf 'j%d\t%s\t%s\n' "$njobs" "$h_case" "$d" >>"$meta"
}
# fit DESC NAME FIT [check.py options]: the module run NAME FIT wrote
fit() {
    d=$1
    n=$2
    f=$3
    shift 3
    deviation "$d" "$cases/$n.dxf" "$cases/$n.$f.scad" "$f" "$@"
}
# result LABEL: that check's lines; status 0 when it passed
result() {
    sed -n "/^=== $1\$/,/^RESULT $1 /p" "$tmp/verify.out"
    grep -q "^RESULT $1 ok\$" "$tmp/verify.out"
}
verify_queued() {
    "$PY" tests/dxf/check.py --batch "$jobs" >"$tmp/verify.out" 2>&1
    last=""
    while IFS="$tab" read -r label c d; do
        if [ "$c" != "$last" ]; then
            begin_case "$c: against the exact geometry"
            last=$c
        fi
        check "$d" result "$label"
    done <"$meta"
}

begin_case "issue 35, reproduction 1: the bulged LWPOLYLINE edge is an arc"
check "reads" run repro_bulge inside
check "the arc is there: points beyond x = 40, up to the arc's top x = 45" py '
import re
t = open("'"$cases"'/repro_bulge.inside.scad").read()
xs = [float(x) for x in re.findall(r"\[([-0-9.e+]+),[-0-9.e+]+\]", t.split("function m_points")[1].split("function m_paths")[0])]
assert max(xs) > 44.99 and max(xs) <= 45.0 + 1e-5, max(xs)
assert sum(1 for x in xs if x > 40.001) >= 10
'
fit "within T of the drawn edge, both ways; inside it" repro_bulge inside --contours 1

begin_case "issue 35, reproduction 2: the SPLINE is there"
check "reads" run repro_spline inside
fit "within T of the spline (de Boor), both ways; inside it" repro_spline inside --contours 1
check "a lone open spline is an error naming where it stops" fails_with 1 \
    "spline_open.dxf:[0-9]*: an outline does not close: it stops at (50, 0), an end of SPLINE handle" \
    "$bin" -o "$cases/spline_open.scad" "$cases/spline_open.dxf"
check "nothing written" test ! -e "$cases/spline_open.scad"
check "--open closes it by a straight edge, with a warning" fails_with 0 \
    "warning: .*closed by a straight edge of length 50" run spline_open inside --open
deviation "the spline and the closing edge are there (the drawing of reproduction 2)" \
    "$cases/repro_spline.dxf" "$cases/spline_open.inside.scad" inside --contours 1

begin_case "issue 35, reproduction 3: CIRCLE r = 3 within T"
for f in inside outside middle; do
    check "--fit $f reads" run repro_circle $f
    fit "--fit $f: within T both ways (inside, outside: on that side)" repro_circle $f --contours 1
done

begin_case "every entity type within T of its exact geometry, in every fit"
# name, contours
for c in slot_chain:3 mixed_chain:1 ellipses:2 nurbs_knots:1 periodic:1 r12_polyline:2 \
         mirrored_ocs:1 blocks:26 corner_plate:2; do
    n=${c%%:*}
    k=${c##*:}
    for f in inside outside middle; do
        check "$n --fit $f reads" run $n $f
        side=", $f the drawn region"
        [ $f = middle ] && side=""
        fit "$n --fit $f: $k contours within T both ways$side" $n $f --contours $k
    done
done
# two CIRCLEs that cross: even-odd, as import() reads them, two crescents
# meeting where the circles cross (each copy of such a point moved T/100
# into its own crescent: --touch)
for f in inside outside middle; do
    check "overlap --fit $f reads" run overlap $f
    fit "overlap --fit $f: the lens is not material, 2 crescents within T" overlap $f --contours 2 --touch
done
check "HATCH boundaries read when nothing else is drawn" run hatch_only inside
fit "hatch: 2 contours within T, inside" hatch_only inside --hatch --contours 2
check "LINE/ARC chain: a slot with 2 holes (outer and holes by containment)" \
    grep -q '^// 1 outer contour, 2 holes' "$cases/slot_chain.inside.scad"
check "blocks: 13 outlines and their 13 holes" grep -q '^// 13 outer contours, 13 holes' "$cases/blocks.inside.scad"
check "--fit clearance reads" run slot_chain clearance
check "--fit clearance is the inside polygon (its holes are drawn at least as large)" py '
import re
a, b = (re.search(r"function m_points\(\) = \[(.*?)\];", open("'"$cases"'/slot_chain.%s.scad" % f).read(), re.S).group(1) for f in ("inside", "clearance"))
assert a == b and len(a) > 100
'

begin_case "curves meeting straight edges at corners keep their lines, in every fit"
# issue 35: the path model's old fit moved a corner where a curve meets a
# line (mixed_chain was 1.75 T off under --fit outside, and chords of
# concave stretches added material under --fit inside); the region fit
# keeps corners and straight edges as drawn, checked above by
# tests/dxf/check.py; here the corners' own numbers
for f in inside outside middle; do
    check "corner_plate --fit $f: the corners and straight edges exactly as drawn" py '
import re
t = open("'"$cases"'/corner_plate.'$f'.scad").read()
P = [(float(a), float(b)) for a, b in re.findall(r"\[([-0-9.e+]+),([-0-9.e+]+)\]", t.split("function m_points")[1].split("function m_paths")[0])]
for c in [(0, 0), (15, 0), (25, 0), (40, 0), (40, 10), (0, 10), (30, 6), (30, 14)]:
    assert c in P, c
xs, ys = [p[0] for p in P], [p[1] for p in P]
# the sides and the bottom: no vertex beyond their lines
assert min(xs) == 0 and max(xs) == 40 and min(ys) == 0, (min(xs), max(xs), min(ys))
# the hole: no vertex beyond its straight edge, into the material
assert all(x >= 30 for x, y in P if 6 < y < 14 and 29 < x < 35), "the hole keeps its straight edge"
'
done

begin_case "units: \$INSUNITS inches and metres to millimetres, --units in"
check "inch drawing" run inch inside
check "inch: 2 x 1 in = 50.8 x 25.4 mm" grep -q '^function m_bbox() = \[\[0,0\],\[50.8,25.4\]\];' "$cases/inch.inside.scad"
fit "inch: within T of the drawing in mm" inch inside --contours 2
check "the header names the drawing's units" grep -q '^// DXF: .*drawing units in;' "$cases/inch.inside.scad"
# (the units alone: at 1 mm, not the 0.01 of a circle of r = 250 mm)
check "metre drawing" "$bin" --module m --tolerance 1 -o "$cases/metre.scad" "$cases/metre.dxf"
check "metre: 2 x 1 m = 2000 x 1000 mm" grep -q '^function m_bbox() = \[\[0,0\],\[2000,1000\]\];' "$cases/metre.scad"
check "--units in on the inch drawing keeps its numbers" \
    "$bin" --module m --tolerance $T --units in -o "$cases/inch_in.scad" "$cases/inch.dxf"
check "bbox in inches" grep -q '^function m_bbox() = \[\[0,0\],\[2,1\]\];' "$cases/inch_in.scad"
deviation "within T in inches" "$cases/inch.dxf" "$cases/inch_in.scad" inside --unit-mm 25.4 --contours 2

begin_case "layers: frozen and off layers skipped, --layer selects, the header lists them"
check "every visible layer, one warning per skipped kind" fails_with 0 \
    "warning: .*2 CIRCLE entities skipped: on a frozen or switched-off layer" run layers inside
check_grep "2 TEXT entities skipped: not profile geometry" "$tmp/fw.err" "TEXT counted once"
check_grep "1 MTEXT entity skipped" "$tmp/fw.err"
fit "A and B read: 2 contours within T" layers inside --layers A,B --contours 2
check "header lists the layers read" grep -q '^// layers read: A, B$' "$cases/layers.inside.scad"
check "--layer B alone" run layers middle --layer B
fit "only B: 1 contour" layers middle --layers B --contours 1
check "header lists B" grep -q '^// layers read: B$' "$cases/layers.middle.scad"
check "--layer C reads a frozen layer on request" run layers outside --layer C
check "header lists C" grep -q '^// layers read: C$' "$cases/layers.outside.scad"
check "--layer X: nothing to read is an error" fails_with 1 "no profile geometry" \
    "$bin" --layer X -o "$cases/none.scad" "$cases/layers.dxf"

begin_case "chaining: a gap is an error with where it stops; --gap joins it"
check "0.5 gap refused" fails_with 1 \
    "open_outline.dxf:[0-9]*: an outline does not close: it stops at (0.5, 0)" \
    "$bin" -o "$cases/open_outline.scad" "$cases/open_outline.dxf"
check_grep "note: --gap D joins" "$tmp/fw.err" "the way out is named"
check "nothing written" test ! -e "$cases/open_outline.scad"
check "--gap 0.6 joins it" run open_outline inside --gap 0.6
check "a triangle of 3 points" py '
import re
t = open("'"$cases"'/open_outline.inside.scad").read()
assert len(re.findall(r"^  \[", t.split("function m_points")[1].split("function m_paths")[0], re.M)) == 3
'
check "--gap 0.4 does not" fails_with 1 "does not close" \
    "$bin" --gap 0.4 -o "$cases/open_outline.scad" "$cases/open_outline.dxf"

begin_case "the modules render in OpenSCAD without a warning"
if command -v openscad >/dev/null 2>&1; then
    # the modules written above, each fit a drawing's own file
    for m in repro_bulge.inside repro_spline.inside repro_circle.outside slot_chain.inside \
             blocks.outside nurbs_knots.middle corner_plate.outside; do
        printf 'include <%s.scad>\nlinear_extrude(2) m();\n' "$m" >"$cases/r_$m.scad"
        check "$m renders" sh -c "openscad -o '$cases/r_$m.stl' '$cases/r_$m.scad' >'$cases/r_$m.log' 2>&1 && ! grep -q WARNING '$cases/r_$m.log' && test -s '$cases/r_$m.stl'"
    done
else
    skip_case "openscad not installed"
fi

begin_case "hostile DXF: a clear error with file:line, nothing written"
# hostile NAME 'python writing $f' 'expected message'
hostile() {
    py "f = open('$cases/$1.dxf', 'w'); $2; f.close()"
    check "$1: refused" fails_with 1 "$3" "$bin" -o "$cases/$1.scad" "$cases/$1.dxf"
    check "$1: nothing written" test ! -e "$cases/$1.scad"
}
hostile truncated "f.write('0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n')" \
    "truncated.dxf:7: truncated: group code 10 has no value line"
hostile odd_pairs "f.write('0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n1\n20\n')" \
    "odd_pairs.dxf:9: truncated: group code 20 has no value"
hostile bad_code "f.write('0\nSECTION\n2\nENTITIES\n0\nLINE\nten\n1\n')" \
    "bad_code.dxf:7: expected a group code"
hostile nan "f.write('0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\nnan\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n')" \
    "nan.dxf:8: group 10: 'nan' is not a finite number"
hostile huge "f.write('0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n10\n1e300\n20\n0\n40\n1\n0\nENDSEC\n0\nEOF\n')" \
    "huge.dxf:5: a coordinate (1e+300) is beyond +-1e+15"
hostile overflow "f.write('0\nSECTION\n2\nENTITIES\n0\nLINE\n10\n1e400\n0\nENDSEC\n0\nEOF\n')" \
    "overflow.dxf:8: group 10: '1e400' is not a finite number"
hostile recursive "f.write('0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nA\n10\n0\n20\n0\n0\nINSERT\n2\nA\n10\n1\n20\n0\n0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nA\n10\n0\n20\n0\n0\nENDSEC\n0\nEOF\n')" \
    "recursive.dxf:13: block 'A' inserts itself (recursive blocks)"
hostile million "f.write('0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n90\n1000000\n70\n1\n'); f.write(''.join('10\n%d\n20\n%d\n' % (i, i % 2) for i in range(1000)) * 1000); f.write('0\nENDSEC\n0\nEOF\n')" \
    "million.dxf:5: LWPOLYLINE has more than 524288 vertices (max_vertices)"
hostile deep "f.write('0\nSECTION\n2\nBLOCKS\n' + ''.join('0\nBLOCK\n2\nB%d\n0\nINSERT\n2\nB%d\n0\nENDBLK\n' % (i, i + 1) for i in range(20)) + '0\nBLOCK\n2\nB20\n0\nCIRCLE\n40\n1\n0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nB0\n0\nENDSEC\n0\nEOF\n')" \
    "deep.dxf:[0-9]*: INSERTs nested deeper than 16 (max_depth)"
hostile bomb "f.write('0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nB\n0\nCIRCLE\n10\n0\n20\n0\n40\n1\n0\nENDBLK\n0\nBLOCK\n2\nA\n0\nINSERT\n2\nB\n70\n1000\n71\n1000\n44\n3\n45\n3\n0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nA\n70\n2000\n71\n2000\n44\n3000\n45\n3000\n0\nENDSEC\n0\nEOF\n')" \
    "bomb.dxf:[0-9]*: INSERT array of 2000 x 2000 copies exceeds max_entities (1048576)"
hostile bomb2 "f.write('0\nSECTION\n2\nBLOCKS\n0\nBLOCK\n2\nB\n0\nCIRCLE\n10\n0\n20\n0\n40\n1\n0\nENDBLK\n0\nBLOCK\n2\nA\n0\nINSERT\n2\nB\n70\n1000\n71\n1000\n44\n3\n45\n3\n0\nENDBLK\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n0\nINSERT\n2\nA\n70\n1000\n71\n1000\n44\n3000\n45\n3000\n0\nENDSEC\n0\nEOF\n')" \
    "bomb2.dxf:[0-9]*: the drawing has more than 4194304 control points (max_points)"
hostile binary "f.write('AutoCAD Binary DXF\r\n\x1a\x00')" \
    "binary.dxf:1: binary DXF is not supported: save the drawing as ASCII DXF"
hostile fitonly "f.write('0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\nAB12\n71\n3\n74\n3\n11\n0\n21\n0\n11\n1\n21\n1\n11\n2\n21\n0\n0\nENDSEC\n0\nEOF\n')" \
    "fitonly.dxf:5: SPLINE (handle AB12) has fit points only"
hostile knots "f.write('0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\n7\n71\n3\n40\n0\n40\n1\n10\n0\n20\n0\n10\n1\n20\n1\n0\nENDSEC\n0\nEOF\n')" \
    "knots.dxf:5: SPLINE (handle 7): degree 3, 2 control points, 2 knots"
hostile nosection "f.write('0\nLINE\n10\n0\n')" "nosection.dxf:1: expected '0 SECTION'"

begin_case "CRLF line ends and a comment read as LF"
check "CRLF copy" py '
t = open("'"$cases"'/repro_circle.dxf", newline="").read().replace("\r\n", "\n")
open("'"$cases"'/crlf.dxf", "w", newline="").write("999\r\nmade by a test\r\n" + t.replace("\n", "\r\n"))
'
check "CRLF reads" run crlf inside
check "same points as the LF original" py '
import re
a = re.findall(r"^  \[.*", open("'"$cases"'/repro_circle.inside.scad").read(), re.M)
b = re.findall(r"^  \[.*", open("'"$cases"'/crlf.inside.scad").read(), re.M)
assert a == b and len(a) > 10
'
check "a DXF on stdin is recognised by its content" sh -c "'$bin' --module m - < '$cases/repro_circle.dxf' | grep -q '^// source: - (DXF)'"
check "--layer on SVG input is a usage error" fails_with 2 "apply to DXF input only" \
    "$bin" --layer A examples/bracket.svg

begin_case "conica plot takes a DXF SPLINE"
check "the only SPLINE of a drawing" sh -c "'$conica' plot --abs-tolerance 0.001 '$cases/spline_open.dxf' > '$tmp/plot.txt'"
check "the polyline runs from (0, 0) to (50, 0), within 0.001 of the spline (de Boor)" py '
import ezdxf, numpy as np, sys
sys.path.insert(0, "tests/dxf")
pts = np.loadtxt("'"$tmp"'/plot.txt")
sp = [e for e in ezdxf.readfile("'"$cases"'/spline_open.dxf").modelspace() if e.dxftype() == "SPLINE"][0]
exec(open("tests/dxf/check.py").read().split("def main")[0])
ex = np.array(spline_samples(3, list(sp.knots), [tuple(v)[:2] for v in sp.control_points], [1.0] * 6, 20000))
assert np.allclose(pts[0], [0, 0]) and np.allclose(pts[-1], [50, 0])
d = seg_dist(ex, pts[:-1], pts[1:], 0.01).max()
print(len(pts), "points, deviation", d)
assert d <= 0.001
'
check "two SPLINEs: the handles are named" fails_with 1 "2 SPLINE entities (handles" \
    "$conica" plot "$cases/nurbs_two.dxf"
check "--entity picks one" sh -c "'$conica' plot --entity 2F '$cases/nurbs_two.dxf' | grep -q '^0 0$'"
check "--entity of no SPLINE" fails_with 1 "no SPLINE with handle 'ZZ'" "$conica" plot --entity ZZ "$cases/nurbs_two.dxf"
check "--entity on a .spl is a usage error" fails_with 2 "names a SPLINE of a DXF input" \
    "$conica" plot --entity 2F examples/nurbs-circle.spl

# OpenSCAD's own example drawings, as Debian's openscad package installs
# them (scripts/deps.sh test): no file fetched from elsewhere is kept here.
samples=${CONICA_DXF_SAMPLES:-/usr/share/openscad/examples/Old}
begin_case "public DXF files (OpenSCAD's examples, $samples)"
# file: what the module header says of it
expected="example008.dxf: 4 outer contours, 2 holes
example013.dxf: 1 outer contour, 0 holes"
if [ ! -f "$samples/example008.dxf" ]; then
    skip_case "$samples has no DXF examples (Debian: openscad)"
else
    for b in example008 example013; do
        f=$samples/$b.dxf
        expect=$(printf '%s\n' "$expected" | sed -n "s/^$b\.dxf: *//p")
        check "$b reads: $expect" "$bin" --module m -o "$tmp/pub_$b.scad" "$f"
        check_grep "^// $expect" "$tmp/pub_$b.scad" "$b: $expect"
        deviation "$b within T of its geometry" "$f" "$tmp/pub_$b.scad" inside
    done
fi

verify_queued
finish
