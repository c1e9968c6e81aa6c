#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite for `conica subdivide` (README.md).
# usage (from the repository root): sh tests/cli/subdivide.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica

count_v() { grep -c '^v ' "$1"; }
# A closed circle of n points, radius r, centre (cx, cy), exact unit normals.
circle() { # n r cx cy > file
    awk -v n="$1" -v r="$2" -v cx="$3" -v cy="$4" 'BEGIN {
        pi = atan2(0, -1)
        for (i = 0; i < n; i++) { t = 2*pi*i/n; printf "v %.17g %.17g\n", cx + r*cos(t), cy + r*sin(t) }
        for (i = 0; i < n; i++) { t = 2*pi*i/n; printf "vn %.17g %.17g\n", cos(t), sin(t) } }'
}
# max_radial FILE R CX CY: largest |distance to (cx,cy) - r| / r over the v lines.
max_radial() { awk -v r="$2" -v cx="$3" -v cy="$4" '
    /^v / { d = sqrt(($2-cx)^2 + ($3-cy)^2) - r; if (d < 0) d = -d; if (d/r > m) m = d/r }
    END { printf "%.3g\n", m + 0 }' "$1"; }
# max_unit FILE: largest | |normal| - 1 | over the vn lines.
max_unit() { awk '/^vn / { d = sqrt($2*$2 + $3*$3) - 1; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "%.3g\n", m + 0 }' "$1"; }
# le A B: is the number A <= B?
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 <= b + 0) }'; }
# eq_count FILE N: the file has N v lines.
eq_count() { [ "$(count_v "$1")" -eq "$2" ]; }

circle 8 5 0 0 >"$tmp/circle.txt"
circle 6 5 10000 10000 >"$tmp/far.txt"
head -n 5 "$tmp/circle.txt" >"$tmp/arc.txt"
awk '!/^vn/' "$tmp/circle.txt" >"$tmp/nonormals.txt"
printf '# comment\nv 0 0\nv 1 0 7\nv 0 1\n' >"$tmp/bad.txt"

begin_case "conica is built"
check_true "$conica exists" test -x "$conica"

begin_case "--help exits 0 and describes every option"
check "--help" "$conica" subdivide --help
check_grep '^Usage: conica subdivide' "$out"
for opt in -k --open --closed --precise --estimate-normals --reference-compatible --time -o \
    --max-points --normals --threads --noise; do
    check_grep "(^| )$opt( |,|=|$)" "$out" "--help mentions $opt"
done

begin_case "circle round trip: -k 3 gives 8*2^3 points on the circle with unit normals"
check "-k 3" "$conica" subdivide -k 3 "$tmp/circle.txt"
check_count 64 '^v ' "$out"
check_count 64 '^vn ' "$out"
e=$(max_radial "$out" 5 0 0)
check_true "radial error $e <= 1e-13" le "$e" 1e-13
u=$(max_unit "$out")
check_true "normal length error $u <= 1e-15" le "$u" 1e-15

begin_case "a circle far from the origin stays a circle (default and --precise)"
for mode in --closed --precise; do
    check "$mode -k 6" "$conica" subdivide -k 6 $mode "$tmp/far.txt"
    check_count 384 '^v ' "$out"
    # awk reads the output as double: the coordinates themselves round at
    # 1e4 * 1.1e-16, i.e. 2.2e-13 of the radius.
    e=$(max_radial "$out" 5 10000 10000)
    check_true "$mode: relative radial error $e <= 1e-11" le "$e" 1e-11
done

begin_case "--reference-compatible fits in absolute coordinates, as the reference does"
# Same scheme, other frame: at the origin it reproduces the circle too; at
# (1e4, 1e4) the absolute-coordinate fit loses digits like the reference
# (REFERENCE.md section 1), while the default local frame does not.
check "--reference-compatible at the origin" "$conica" subdivide -k 3 --reference-compatible "$tmp/circle.txt"
check_count 64 '^v ' "$out"
e=$(max_radial "$out" 5 0 0)
check_true "origin: relative radial error $e <= 1e-13" le "$e" 1e-13
check "--reference-compatible far away" "$conica" subdivide -k 8 --reference-compatible "$tmp/far.txt"
check_count 1536 '^v ' "$out"
e=$(max_radial "$out" 5 10000 10000)
check_true "far: relative radial error $e >= 1e-8 (the absolute fit drifts)" le 1e-8 "$e"
check "default far away" "$conica" subdivide -k 8 "$tmp/far.txt"
e=$(max_radial "$out" 5 10000 10000)
check_true "far, default: relative radial error $e <= 1e-11" le "$e" 1e-11

begin_case "-k 0 writes the input back"
check "-k 0" "$conica" subdivide -k 0 -o "$tmp/k0.txt" "$tmp/circle.txt"
grep '^v ' "$tmp/circle.txt" >"$tmp/a"
grep '^v ' "$tmp/k0.txt" >"$tmp/b"
check_true "v lines identical" cmp -s "$tmp/a" "$tmp/b"
check_true "vn lines within 1e-15" sh -c "paste -d ' ' '$tmp/circle.txt' '$tmp/k0.txt' |
    awk '\$1 == \"vn\" { d = (\$2 - \$5)^2 + (\$3 - \$6)^2; if (d > 1e-30) bad++; n++ }
         END { exit bad > 0 || n != 8 }'"

begin_case "--open: n points -> 2n-1 per level, end points kept"
check "--open -k 1" "$conica" subdivide --open -k 1 "$tmp/arc.txt"
check_count 9 '^v ' "$out"
check "--open -k 3" "$conica" subdivide --open -k 3 "$tmp/arc.txt"
check_count 33 '^v ' "$out"
check_true "first point kept" test "$(grep '^v ' "$out" | head -n 1)" = "$(sed -n 1p "$tmp/arc.txt")"
check_true "last point kept" test "$(grep '^v ' "$out" | tail -n 1)" = "$(sed -n 5p "$tmp/arc.txt")"
check "--open --closed: the last wins" "$conica" subdivide --open --closed -k 1 "$tmp/arc.txt"
check_count 10 '^v ' "$out"

begin_case "stdin and stdout: '-', no IN, -o -"
check "file to stdout" "$conica" subdivide -k 2 "$tmp/circle.txt"
cp "$out" "$tmp/ref.txt"
check "'-' reads stdin" sh -c "'$conica' subdivide -k 2 - < '$tmp/circle.txt'"
check_true "same output from stdin" cmp -s "$out" "$tmp/ref.txt"
check "no IN reads stdin, -o - writes stdout" sh -c "'$conica' subdivide -k2 -o - < '$tmp/circle.txt'"
check_true "same output" cmp -s "$out" "$tmp/ref.txt"

begin_case "-o writes the file and leaves no temporary behind"
mkdir "$tmp/outdir"
check "-o" "$conica" subdivide -k 2 -o "$tmp/outdir/c.txt" "$tmp/circle.txt"
check_true "stdout empty with -o" test ! -s "$out"
check_true "-o output equals stdout output" cmp -s "$tmp/outdir/c.txt" "$tmp/ref.txt"
check_true "no other file in the directory" test "$(ls "$tmp/outdir" | wc -l)" -eq 1

begin_case "-o to a FIFO or device writes in place (never renames over it)"
# Renaming a temporary over /dev/null as root replaces the device with a
# regular file; a FIFO shows the same without risking the machine.
if mkfifo "$tmp/fifo" 2>/dev/null; then
    cat "$tmp/fifo" >"$tmp/fifo.out" &
    reader=$!
    check "-o FIFO" "$conica" subdivide -k 2 -o "$tmp/fifo" "$tmp/circle.txt"
    # A conica that never opened the FIFO leaves the reader blocked: stop it.
    i=0
    while kill -0 "$reader" 2>/dev/null && [ "$i" -lt 30 ]; do sleep 0.1; i=$((i + 1)); done
    kill "$reader" 2>/dev/null
    wait "$reader" 2>/dev/null
    check_true "still a FIFO" test -p "$tmp/fifo"
    check_true "the reader got the curve" cmp -s "$tmp/fifo.out" "$tmp/ref.txt"
else
    skip_case "mkfifo not available"
fi
check_exit 1 "-o a directory" "$conica" subdivide -k 1 -o "$tmp" "$tmp/circle.txt"
check_grep "is a directory" "$err"

begin_case "--time prints exactly one line on stderr in the documented format"
check "--time" "$conica" subdivide -k 4 --time "$tmp/circle.txt"
check_true "one stderr line" test "$(wc -l <"$err")" -eq 1
check_grep '^subdivide: [0-9]+ edge points in [0-9.]+(e[-+][0-9]+)? s \([0-9.]+(e[-+][0-9]+)? us/point\)$' "$err"
check_grep '^subdivide: 120 edge points ' "$err" "N counts the edge points of all levels (8+16+32+64)"
check_count 128 '^v ' "$out"

begin_case "--precise: long double digits, the same curve"
check "--precise" "$conica" subdivide -k 3 --precise "$tmp/circle.txt"
check_count 64 '^v ' "$out"
e=$(max_radial "$out" 5 0 0)
check_true "radial error $e <= 1e-15" le "$e" 1e-15
check_true "numbers carry more than 17 digits" \
    awk '/^v / && length($2) > 20 { found = 1 } END { exit !found }' "$out"

begin_case "--estimate-normals and --normals area|circle"
for m in area circle; do
    check "input without vn, --normals $m" "$conica" subdivide -k 2 --normals $m "$tmp/nonormals.txt"
    check_count 32 '^vn ' "$out"
    check "--estimate-normals --normals=$m" \
        "$conica" subdivide -k 2 --estimate-normals --normals=$m "$tmp/circle.txt"
    # a regular polygon's estimated normals are the circle's normals
    e=$(max_radial "$out" 5 0 0)
    check_true "$m: radial error $e <= 1e-13" le "$e" 1e-13
done

begin_case "error: missing input file"
check_exit 1 "missing file" "$conica" subdivide "$tmp/missing.txt"
check_grep "^conica: error: $tmp/missing.txt: " "$err"
check_true "nothing on stdout" test ! -s "$out"

begin_case "error: a malformed line is named as FILE:LINE, exit 1, nothing written"
check_exit 1 "three numbers" "$conica" subdivide -o "$tmp/never.txt" "$tmp/bad.txt"
check_grep "^conica: error: $tmp/bad.txt:3: " "$err"
check_true "no output file" test ! -e "$tmp/never.txt"
printf 'v 0 0\nv 1 zero\nv 0 1\n' >"$tmp/bad2.txt"
check_exit 1 "a word" "$conica" subdivide "$tmp/bad2.txt"
check_grep "bad2.txt:2: 'zero' is not a number" "$err"
check_true "nothing on stdout" test ! -s "$out"
printf 'v 0 0\nv 1 0\nv 0 1\nvn 1 0\n' >"$tmp/bad3.txt"
check_exit 1 "vn count" "$conica" subdivide "$tmp/bad3.txt"
check_grep "bad3.txt:4: 1 'vn' lines for 3 'v' lines" "$err"
printf 'v 0 0\n1 0\n' >"$tmp/bad4.txt"
check_exit 1 "unknown line" "$conica" subdivide "$tmp/bad4.txt"
check_grep "bad4.txt:2: unknown line" "$err"
check_exit 1 "malformed stdin" sh -c "'$conica' subdivide < '$tmp/bad.txt'"
check_grep "^conica: error: <stdin>:3: " "$err"

begin_case "error: NaN and Inf"
printf 'v 0 0\nv 1 0\nv NaN 1\n' >"$tmp/nan.txt"
check_exit 1 "NaN" "$conica" subdivide "$tmp/nan.txt"
check_grep "nan.txt:3: 'NaN' is not a finite number" "$err"
printf 'v 0 0\nv 1 0\nv 0 1\nvn 1 0\nvn 0 inf\nvn 1 1\n' >"$tmp/inf.txt"
check_exit 1 "inf" "$conica" subdivide "$tmp/inf.txt"
check_grep "inf.txt:5: " "$err"
printf 'v 0 0\nv 1 0\nv 1e999 1\n' >"$tmp/huge.txt"
check_exit 1 "overflow" "$conica" subdivide "$tmp/huge.txt"
check_grep "huge.txt:3: " "$err"

begin_case "error: degenerate curve (all points equal)"
printf 'v 1 1\nv 1 1\nv 1 1\n' >"$tmp/same.txt"
check_exit 1 "coincident points" "$conica" subdivide -k 1 "$tmp/same.txt"
check_grep "^conica: error: $tmp/same.txt" "$err"
check_true "nothing on stdout" test ! -s "$out"

begin_case "error: duplicate consecutive points are named by line"
printf '# square\nv 0 0\nv 1 0\nv 1 1\nv 1 1\nv 0 1\n' >"$tmp/dup.txt"
check_exit 1 "zero-length edge" "$conica" subdivide -k 1 "$tmp/dup.txt"
check_grep "^conica: error: $tmp/dup.txt:[45]: " "$err"

begin_case "usage errors exit 2"
for args in "-k 31" "-k -1" "-k x" "-k" "--bogus" "--normals foo" "--threads 0" \
    "--max-points 0" "a.txt b.txt" "-o"; do
    check_exit 2 "'$args'" "$conica" subdivide $args
    check_grep 'usage error' "$err"
done

begin_case "error: unwritable output directory"
check_exit 1 "no such directory" "$conica" subdivide -k 1 -o "$tmp/no/such/dir/out.txt" "$tmp/circle.txt"
check_grep "^conica: error: $tmp/no/such/dir/out.txt" "$err"

begin_case "a failed run leaves an existing output untouched"
printf 'precious\n' >"$tmp/keep.txt"
check_exit 1 "bad input" "$conica" subdivide -o "$tmp/keep.txt" "$tmp/bad.txt"
check_true "output untouched" test "$(cat "$tmp/keep.txt")" = precious
check_exit 1 "over the point budget" \
    "$conica" subdivide -k 20 --max-points 1000 -o "$tmp/keep.txt" "$tmp/circle.txt"
check_true "output untouched" test "$(cat "$tmp/keep.txt")" = precious
check_true "no temporary left" test "$(ls "$tmp" | grep -c 'keep.txt.tmp')" -eq 0

begin_case "--max-points: the budget is enforced"
check_exit 1 "64 points over a budget of 63" "$conica" subdivide -k 3 --max-points 63 "$tmp/circle.txt"
check_true "nothing written" test ! -s "$out"
check "64 points within a budget of 64" "$conica" subdivide -k 3 --max-points 64 "$tmp/circle.txt"
check_count 64 '^v ' "$out"

begin_case "--threads gives the same bits"
check "--threads 1" "$conica" subdivide -k 6 --threads 1 "$tmp/far.txt"
cp "$out" "$tmp/t1.txt"
check "--threads 2" "$conica" subdivide -k 6 --threads 2 "$tmp/far.txt"
check_true "identical output" cmp -s "$out" "$tmp/t1.txt"

begin_case "the bundled examples subdivide"
for f in examples/ellipse.txt examples/flower.txt examples/parabola_open.txt; do
    mode=--closed
    case "$f" in *open*) mode=--open ;; esac
    check "$f" "$conica" subdivide -k 3 $mode "$f"
    n=$(count_v "$f")
    m=$(count_v "$out")
    if [ "$mode" = --open ]; then want=$(((n - 1) * 8 + 1)); else want=$((n * 8)); fi
    # non-convex input gains inflection points before level 1
    check_true "$f: $m points, at least $want" test "$m" -ge "$want"
done
check "ellipse -k 4" "$conica" subdivide -k 4 examples/ellipse.txt
check_true "ellipse reproduced within 1e-13" awk '/^v / { e = $2*$2/9 + $3*$3/4 - 1; if (e < 0) e = -e;
    if (e > m) m = e } END { exit !(m < 1e-13) }' "$out"

begin_case "--precise reads 25-digit samples in long double: Table 1 through the CLI"
# The CONIS paper's Table 1 (Bügel, Romani, Kosinka), E and E_max of its
# eqs. (13)-(14), with the reference's samples (REFERENCE.md section 1)
# written with 25 significant digits. python3's decimal module makes the
# samples and measures the 21-digit output, far beyond long double.
if ! command -v python3 >/dev/null 2>&1; then
    skip_case "python3 is not installed (needed to measure in 60-digit decimal)"
else
    cat >"$tmp/table1.py" <<'PY'
import sys
from decimal import Decimal as D, getcontext
getcontext().prec = 60
Q = {'circle': (1, 1, 0, -25), 'ellipse': (4, 9, 0, -36),
     'hyperbola': (-4, 1, 0, -4), 'parabola': (1, 0, D('-0.5'), 0)}
# f = A x^2 + B y^2 + 2 E y + F; Table 1 at k = 4, 8, 12: E then E_max
T1 = {'circle': ('1.97e-18 4.70e-17 1.57e-14', '8.67e-18 1.35e-15 1.04e-13'),
      'ellipse': ('1.37e-18 6.54e-17 3.46e-15', '6.17e-18 1.10e-15 1.53e-13'),
      'hyperbola': ('1.14e-17 4.67e-15 4.55e-13', '5.97e-16 3.54e-13 2.31e-12'),
      'parabola': ('3.54e-16 4.05e-15 3.83e-13', '3.53e-15 1.13e-12 8.09e-12')}
def grad(q, x, y):
    return 2 * q[0] * x, 2 * (q[1] * y + q[2])
def err(q, x, y):
    gx, gy = grad(q, x, y)
    return abs(q[0] * x * x + q[1] * y * y + 2 * q[2] * y + q[3]) / (gx * gx + gy * gy).sqrt()
if sys.argv[1] == 'make':
    name = sys.argv[2]; q = Q[name]
    h = D(3).sqrt() / 2
    cs = [D(1), D('0.5'), D('-0.5'), D(-1), D('-0.5'), D('0.5')]
    sn = [D(0), h, h, D(0), -h, -h]
    pts = []
    for i in range(6):
        if name == 'circle': x, y = 5 * cs[i], 5 * sn[i]
        elif name == 'ellipse': x, y = 3 * cs[i], 2 * sn[i]
        elif name == 'hyperbola': x = D(-4) + D(8 * i) / 5; y = 2 * (1 + x * x).sqrt()
        else: x = D(-4) + D(8 * i) / 6; y = x * x
        pts.append((x, y))
    for x, y in pts:
        print('v', format(x, '.24e'), format(y, '.24e'))
    for x, y in pts:
        gx, gy = grad(q, x, y); g = (gx * gx + gy * gy).sqrt()
        print('vn', format(gx / g, '.24e'), format(gy / g, '.24e'))
else:
    name, li, path = sys.argv[2], int(sys.argv[3]), sys.argv[4]
    e = [err(Q[name], D(w[1]), D(w[2])) for w in (l.split() for l in open(path)) if w[0] == 'v']
    E, Em = sum(e) / len(e), max(e)
    pe, pm = D(T1[name][0].split()[li]), D(T1[name][1].split()[li])
    print('%s k=%d: E %.3g (Table 1: %.3g), E_max %.3g (%.3g)' % (name, 4 * li + 4, E, pe, Em, pm))
    sys.exit(0 if E <= pe and Em <= pm else 1)
PY
    for c in circle ellipse hyperbola parabola; do
        python3 "$tmp/table1.py" make $c >"$tmp/t1_$c.txt"
        mode=--closed
        case $c in hyperbola | parabola) mode=--open ;; esac
        for li in 0 1 2; do
            k=$((4 * li + 4))
            check "$c --precise -k $k" "$conica" subdivide --precise $mode -k $k "$tmp/t1_$c.txt"
            check_true "$c k=$k: E and E_max at or below Table 1 ($(python3 "$tmp/table1.py" \
                measure $c $li "$out"))" python3 "$tmp/table1.py" measure $c $li "$out"
        done
    done
fi

begin_case "--precise output round-trips: long double in, the same 21 digits out"
# -k 0 prints the input as it was read; reading that again must give the
# same long double, so the second pass prints the same text. The first
# pass keeps more than double's 17 digits of the 25-digit samples.
if [ ! -f "$tmp/t1_circle.txt" ]; then
    skip_case "needs the samples of the previous case (python3)"
else
    check "-k 0 of 25-digit samples" "$conica" subdivide --precise -k 0 "$tmp/t1_circle.txt"
    cp "$out" "$tmp/rt1.txt"
    check "-k 0 of its output" "$conica" subdivide --precise -k 0 "$tmp/rt1.txt"
    check_true "identical text" cmp -s "$out" "$tmp/rt1.txt"
    # 4.330127018922193233818615 in: the nearest long double, 21 digits out
    check_grep '^v 2\.5 4\.330127018922193233[0-9][0-9]$' "$tmp/rt1.txt" \
        "a sample keeps long double's 19-20 digits"
    check "default mode reads double" "$conica" subdivide -k 0 "$tmp/t1_circle.txt"
    check_grep '^v 2\.5 4\.3301270189221936$' "$out" "double mode keeps 17 digits"
fi

begin_case "--noise: a side zigzagging by its rounding (3 decimals) makes no inflection points"
# a flat side of 101 points whose y alternates 0, 0.0004 (a straight edge
# written to 3 decimals and perturbed), closed by a half circle: 140 points
awk 'BEGIN { pi = atan2(0, -1)
    for (i = 0; i <= 100; i++) printf "v %.3f %.4f\n", i / 10, (i % 2) * 0.0004
    for (i = 1; i < 40; i++) { t = pi * i / 40; printf "v %.6f %.6f\n", 5 + 5 * cos(t), 5 * sin(t) } }' \
    >"$tmp/zigzag.txt"
check "--noise 0.0005 -k 1" "$conica" subdivide -k 1 --noise 0.0005 "$tmp/zigzag.txt"
check_count 280 '^v ' "$out"
check "default -k 1" "$conica" subdivide -k 1 "$tmp/zigzag.txt"
check_true "without --noise the zigzag's turns are inflections" test "$(count_v "$out")" -gt 280
check_exit 2 "--noise -1 is a usage error" "$conica" subdivide --noise -1 "$tmp/zigzag.txt"

finish
