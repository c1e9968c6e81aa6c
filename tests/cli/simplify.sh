#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth --simplify end to end on the traced leaf (a path of straight
# segments: smoothed through with --lines-as-samples): the smoothed outline
# passes within T of every traced vertex, keeps far fewer of them, its
# curvature changes sign less often than the curve through every traced
# point, its corners (base and tip) stay; without --lines-as-samples a
# straight-only subpath stays straight (issue 32: a glyph's long edges
# bulged by 8.8 % of its diagonal); bad values are usage errors.
# usage (from the repository root): sh tests/cli/simplify.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth
leaf=examples/traced-leaf.svg

# leaf.py TRACED OUT T: prints "kept deviation sign_changes" for the leaf
# outline of OUT against the traced one (kept: output points equal to a
# traced vertex; deviation: largest distance of a traced vertex from OUT's
# polyline; sign changes of the curvature of OUT's polyline)
cat >"$tmp/leaf.py" <<'PY'
import math, re, sys
num = re.compile(r'[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?')
def pts(f):
    d = re.search(r'id="leaf" d="([^"]*)"', open(f).read()).group(1)
    v = [float(x) for x in num.findall(d)]
    return list(zip(v[0::2], v[1::2]))
traced, out = pts(sys.argv[1]), pts(sys.argv[2])
def seg(p, a, b):
    ex, ey = b[0] - a[0], b[1] - a[1]
    l2 = ex * ex + ey * ey
    t = max(0.0, min(1.0, ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / l2)) if l2 else 0.0
    return math.hypot(p[0] - a[0] - t * ex, p[1] - a[1] - t * ey)
n = len(out)
dev = max(min(seg(p, out[i], out[(i + 1) % n]) for i in range(n)) for p in traced)
k = []
for i in range(n):
    a, b, c = out[i - 1], out[i], out[(i + 1) % n]
    k.append((b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]))
big = sorted(abs(x) for x in k)[int(0.98 * (n - 1))]
changes, last = 0, 0
for x in k:
    if abs(x) > 1e-3 * big:
        s = 1 if x > 0 else -1
        changes += last != 0 and s != last
        last = s
kept = sum(1 for p in out if p in set(traced))
corners = all(c in out for c in [(100.0, 170.0), (100.0, 30.0)])
print(kept, '%.6f' % dev, changes, int(corners))
PY
leafstat() { python3 "$tmp/leaf.py" "$leaf" "$1"; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 <= b + 0) }'; }

begin_case "svgsmooth is built"
check_true "$svgsmooth exists" test -x "$svgsmooth"

begin_case "the traced leaf cleaned with --simplify 1"
if [ ! -f "$leaf" ]; then
    skip_case "$leaf missing"
fi
check "every point interpolated" "$svgsmooth" --lines-as-samples --precision 12 -o "$tmp/all.svg" "$leaf"
check "--simplify 1" "$svgsmooth" --simplify 1 --lines-as-samples --precision 12 -o "$tmp/s1.svg" "$leaf"
set -- $(leafstat "$tmp/all.svg")
all_changes=${3:-0}
set -- $(leafstat "$tmp/s1.svg")
check_true "within 1 of every traced vertex (${2:-?})" le "${2:-9}" 1
check_true "at most 16 of 80 vertices kept (${1:-?})" test "${1:-99}" -le 16
check_true "curvature sign changes ${3:-?} < a quarter of ${all_changes} (every point)" \
    test "$((${3:-99} * 4))" -lt "$all_changes"
check_true "base and tip corners kept" test "${4:-0}" -eq 1

begin_case "a tighter T keeps more vertices and stays within it"
check "--simplify 0.5" "$svgsmooth" --simplify 0.5 --lines-as-samples --precision 12 -o "$tmp/s05.svg" "$leaf"
set -- $(leafstat "$tmp/s05.svg")
check_true "within 0.5 (${2:-?})" le "${2:-9}" 0.5
check_true "more than at T = 1, fewer than 80 (${1:-?})" test "${1:-0}" -gt 12 -a "${1:-99}" -lt 80

begin_case "straight-only subpaths stay straight: fewer vertices, every output vertex a traced one"
check "--simplify 1 alone" "$svgsmooth" --simplify 1 --precision 12 -o "$tmp/st.svg" "$leaf"
set -- $(leafstat "$tmp/st.svg")
check_true "within 1 of every traced vertex (${2:-?})" le "${2:-9}" 1
check_true "at most 30 of 80 vertices (${1:-?})" test "${1:-99}" -le 30
# every point written is a traced vertex: nothing smoothed, edges straight
check_true "all $(tr -cd 'L ' <"$tmp/st.svg" | wc -c) output points traced (${1:-?} kept)" \
    test "$(python3 -c "import re,sys; d=re.search(r'id=\"leaf\" d=\"([^\"]*)\"',open(sys.argv[1]).read()).group(1); v=re.findall(r'[-+]?(?:\d+\.?\d*|\.\d+)',d); print(len(v)//2)" "$tmp/st.svg")" -eq "${1:-0}"
# DejaVu Sans 'Z' (font units, a 39-degree join under the corner angle):
# with --lines-as-samples its long edges bulged 240 units at --simplify 0.1
printf '<svg xmlns="http://www.w3.org/2000/svg"><path id="leaf" d="M100 100L1300 100 1300 260 300 1600 1320 1600 1320 1760 80 1760 80 1600 1080 260 100 260Z"/></svg>\n' >"$tmp/z.svg"
check "Z at --simplify 0.1" "$svgsmooth" --simplify 0.1 -o "$tmp/z.out.svg" "$tmp/z.svg"
check_grep 'd="M100 100L1300 100 1300 260 300 1600 1320 1600 1320 1760 80 1760 80 1600 1080 260 100 260Z"' "$tmp/z.out.svg" "the Z as drawn, start included"

begin_case "usage errors exit 2"
check_exit 2 "--simplify 0" "$svgsmooth" --simplify 0 "$leaf"
check_exit 2 "--simplify -1" "$svgsmooth" --simplify -1 "$leaf"
check_exit 2 "--simplify abc" "$svgsmooth" --simplify abc "$leaf"
check_exit 2 "--simplify without a value" "$svgsmooth" "$leaf" --simplify
check_exit 2 "--simplify with --flatten" "$svgsmooth" --flatten --tolerance 0.5 --simplify 1 "$leaf"
check_grep "not with --flatten" "$err"

finish
