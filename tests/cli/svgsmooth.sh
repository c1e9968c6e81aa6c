#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite for svgsmooth (README.md).
# usage (from the repository root): sh tests/cli/svgsmooth.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth

# ---------------------------------------------------------------- helpers
# geom.py: numbers of every d/points attribute, radial errors, PNG masks.
cat >"$tmp/geom.py" <<'EOF'
import re, sys, struct, zlib, math

NUM = re.compile(r'[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?')

def paths(fname, attr='d'):
    text = open(fname, encoding='utf-8').read()
    return re.findall(r'\s%s="([^"]*)"' % attr, text)

def points(d):
    v = [float(x) for x in NUM.findall(d)]
    return list(zip(v[0::2], v[1::2]))

def png_alpha(fname):
    """Alpha channel of an 8-bit RGBA (or RGB) non-interlaced PNG."""
    data = open(fname, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n'
    pos, idat, w = 8, b'', 0
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            w, h, depth, ctype, _, _, inter = struct.unpack('>IIBBBBB', body)
            assert depth == 8 and ctype in (2, 6) and inter == 0
            bpp = 4 if ctype == 6 else 3
        elif kind == b'IDAT':
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f = raw[i]; line = bytearray(raw[i + 1:i + 1 + stride]); i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]; c = prev[x - bpp] if x >= bpp else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line); prev = line
    if bpp == 3:
        return w, h, [[255 if any(r[3*x:3*x+3] != b'\xff\xff\xff') else 0 for x in range(w)] for r in rows]
    return w, h, [[r[4 * x + 3] for x in range(w)] for r in rows]

def cmd_radial(fname, cx, cy, r):
    worst = 0.0
    for d in paths(fname):
        for x, y in points(d):
            worst = max(worst, abs(math.hypot(x - cx, y - cy) - r) / r)
    print('%.3g' % worst)

def cmd_count(fname, attr='d'):
    print(sum(len(points(d)) for d in paths(fname, attr)))

def cmd_shape(a, b, px):
    """Every pixel covered in one rendering lies within px pixels of a
    pixel covered in the other (coverage: alpha >= 128)."""
    w, h, A = png_alpha(a)
    w2, h2, B = png_alpha(b)
    assert (w, h) == (w2, h2)
    px = int(px)
    def far(M, N):
        bad = 0
        for y in range(h):
            for x in range(w):
                if M[y][x] >= 128 and N[y][x] < 128:
                    if not any(N[yy][xx] >= 128 for yy in range(max(0, y - px), min(h, y + px + 1))
                               for xx in range(max(0, x - px), min(w, x + px + 1))):
                        bad += 1
        return bad
    covered = sum(1 for row in A for v in row if v >= 128)
    print(far(A, B) + far(B, A), covered)

getattr(sys.modules[__name__], 'cmd_' + sys.argv[1])(*[
    float(a) if re.fullmatch(r'[-+0-9.e]+', a) else a for a in sys.argv[2:]])
EOF
geom() { python3 "$tmp/geom.py" "$@"; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 <= b + 0) }'; }

svg_doc() { # body > stdout
    printf '<?xml version="1.0"?>\n<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 400 400">\n%s\n</svg>\n' "$1"
}
# four arcs of radius r about (cx, cy)
circle_d() {
    awk -v cx="$1" -v cy="$2" -v r="$3" 'BEGIN {
        printf "M%.17g %.17gA%.17g %.17g 0 0 1 %.17g %.17g", cx + r, cy, r, r, cx, cy + r
        printf "A%.17g %.17g 0 0 1 %.17g %.17g", r, r, cx - r, cy
        printf "A%.17g %.17g 0 0 1 %.17g %.17g", r, r, cx, cy - r
        printf "A%.17g %.17g 0 0 1 %.17g %.17gZ", r, r, cx + r, cy }'
}

svg_doc "<!-- keep me --><g id=\"g\" fill-rule=\"evenodd\"><path id=\"c\" d=\"$(circle_d 200 200 80)\" fill=\"#00f\"/></g><path id=\"sq\" d=\"M10 10H60V60H10Z\"/>" >"$tmp/circle.svg"
svg_doc "<path id=\"far\" d=\"$(circle_d 5000 3000 37.5)\"/>" >"$tmp/far.svg"
svg_doc '<path id="bad" d="M10 10L50 10L50 50Z L5"/>
<path id="ok" d="M0 0L1 1"/>' >"$tmp/warn.svg"
printf '<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M0 0"/>\n<g>\n</svg>\n' >"$tmp/broken.svg"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY xxe SYSTEM "file:///etc/passwd">]>\n<svg xmlns="http://www.w3.org/2000/svg"><text>&xxe;</text></svg>\n' >"$tmp/xxe.svg"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [\n<!ENTITY a "aaaaaaaaaa">\n<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">\n<!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">\n]>\n<svg xmlns="http://www.w3.org/2000/svg"><text>&c;</text></svg>\n' >"$tmp/laughs.svg"

# ---------------------------------------------------------------- cases
begin_case "svgsmooth is built"
check_true "$svgsmooth exists" test -x "$svgsmooth"

begin_case "--help describes every flag, --version answers"
check "--help" "$svgsmooth" --help
for opt in --levels --tolerance --corner-angle --flatten --precision --select \
           --convert-shapes --stats --in-place -o --max-input-bytes --max-depth \
           --max-elements --max-path-bytes --max-points --version; do
    check_grep "^ +(-[a-z], )?$opt" "$out" "--help mentions $opt"
done
check "--version" "$svgsmooth" --version
check_grep '^svgsmooth \(Conica\) [0-9]' "$out"

begin_case "a circle of four arcs lands on the circle (17 digits), also at (5000,3000)"
check "smooth" "$svgsmooth" --precision 17 --levels 5 -o "$tmp/c.out.svg" "$tmp/circle.svg"
# the square shares the file: measure the circle alone
grep -o 'id="c" d="[^"]*"' "$tmp/c.out.svg" | sed 's/id="c"//' >"$tmp/c.only"
printf '<x %s/>\n' "$(cat "$tmp/c.only")" >"$tmp/c.only.svg"
err_c=$(geom radial "$tmp/c.only.svg" 200 200 80)
check_true "radial error $err_c <= 1e-9" le "$err_c" 1e-9
check_true "128 points" test "$(geom count "$tmp/c.only.svg")" -eq 128
check "far away" "$svgsmooth" --precision 17 --levels 5 -o "$tmp/far.out.svg" "$tmp/far.svg"
err_f=$(geom radial "$tmp/far.out.svg" 5000 3000 37.5)
check_true "radial error at (5000,3000) $err_f <= 1e-9" le "$err_f" 1e-9

begin_case "everything but geometry survives; the square stays a square"
check "smooth" "$svgsmooth" "$tmp/circle.svg"
check_grep '<!-- keep me -->' "$out"
check_grep '<g id="g" fill-rule="evenodd">' "$out"
check_grep 'fill="#00f"' "$out"
check_grep '<path id="sq" d="M10 10L60 10 60 60 10 60Z"/>' "$out"
check_grep '^<\?xml version="1.0"\?>$' "$out"

begin_case "stdin to stdout, -o, --in-place"
check "stdin" sh -c "\"$svgsmooth\" - < \"$tmp/circle.svg\""
check_grep 'id="sq"' "$out"
cp "$tmp/circle.svg" "$tmp/inplace.svg"
check "--in-place" "$svgsmooth" --levels 2 --in-place "$tmp/inplace.svg"
check_true "stdout empty with --in-place" test ! -s "$out"
check_grep 'd="M280 200L' "$tmp/inplace.svg"
check_exit 2 "--in-place with stdin is a usage error" "$svgsmooth" --in-place -
check_exit 2 "--in-place with -o is a usage error" "$svgsmooth" --in-place -o "$tmp/x.svg" "$tmp/circle.svg"

begin_case "errors: FILE:LINE, exit 1, output untouched"
echo "previous content" >"$tmp/target.svg"
check_exit 1 "broken XML" "$svgsmooth" -o "$tmp/target.svg" "$tmp/broken.svg"
check_grep "^svgsmooth: error: $tmp/broken.svg:[0-9]+: XML: " "$err"
check_grep '^previous content$' "$tmp/target.svg" "target untouched"
check_exit 1 "missing file" "$svgsmooth" "$tmp/none.svg"
check_grep "^svgsmooth: error: $tmp/none.svg: " "$err"
check_exit 1 "XXE refused" "$svgsmooth" "$tmp/xxe.svg"
check_grep "^svgsmooth: error: $tmp/xxe.svg:2: entity 'xxe' refused" "$err"
check_no_grep 'root:' "$out" "no /etc/passwd content"
check_exit 1 "billion laughs refused" "$svgsmooth" "$tmp/laughs.svg"
check_grep "entity 'b' refused" "$err"
check_exit 1 "depth cap" "$svgsmooth" --max-depth 1 "$tmp/circle.svg"
check_grep 'deeper than 1 \(--max-depth\)' "$err"
check_exit 1 "output point cap" "$svgsmooth" --max-points 50 "$tmp/circle.svg"
check_grep '\(--max-points\)' "$err"
check_exit 1 "input size cap" "$svgsmooth" --max-input-bytes 100 "$tmp/circle.svg"
: >"$tmp/empty.svg"
check_exit 1 "empty document" "$svgsmooth" -o "$tmp/target.svg" "$tmp/empty.svg"
check_grep "^svgsmooth: error: $tmp/empty.svg:1: XML: empty document: no <svg> element$" "$err"
check_grep '^previous content$' "$tmp/target.svg" "target untouched"
check_exit 1 "path data cap" "$svgsmooth" --max-path-bytes 50 "$tmp/circle.svg"
check_grep "^svgsmooth: error: $tmp/circle.svg:3: path 'c': path data exceeds the limit of 50 bytes" "$err"

begin_case "usage errors exit 2"
check_exit 2 "no input" "$svgsmooth"
check_exit 2 "--flatten without --tolerance" "$svgsmooth" --flatten "$tmp/circle.svg"
check_exit 2 "--levels with --tolerance" "$svgsmooth" --levels 2 --tolerance 1 "$tmp/circle.svg"
check_exit 2 "bad --levels" "$svgsmooth" --levels 99 "$tmp/circle.svg"
check_exit 2 "bad --precision" "$svgsmooth" --precision 0 "$tmp/circle.svg"
check_exit 2 "unknown option" "$svgsmooth" --frobnicate "$tmp/circle.svg"

begin_case "bad path data: warning with id and byte offset, exit 0, valid prefix kept"
check "warn" "$svgsmooth" --levels 0 "$tmp/warn.svg"
check_grep "^svgsmooth: warning: $tmp/warn.svg:3: path 'bad': bad path data at byte 22" "$err"
check_grep 'id="bad" d="M10 10L50 10 50 50Z"' "$out"

begin_case "--stats, --select, --convert-shapes, --tolerance"
# the circle (r 80) at 3 levels would be 32 chords 0.385 off it, past the
# fidelity tolerance (1e-3 of the diagonal): the chords that stray are
# split, 64 points (issue 32; 32 before) and the square's 4
check "stats" "$svgsmooth" --stats --levels 3 "$tmp/circle.svg"
check_grep '^svgsmooth: stats: 2 elements, 2 subpaths, 8 input vertices, 68 output points, [0-9.]+ s \(XML\+path I/O [0-9.]+ s, geometry [0-9.]+ s\)$' "$err"
check "select" "$svgsmooth" --select sq,nothing "$tmp/circle.svg"
check_grep 'id="c" d="M280 200A80' "$out" "unselected element unchanged"
check_grep "^svgsmooth: warning: $tmp/circle.svg: --select: no element has id 'nothing'$" "$err" \
    "an id that names no element is warned about"
check_count 1 'warning' "$err" "only the missing id is warned about"
check "--select nosuch: exit status stays 0" "$svgsmooth" --select nosuch,other -o "$tmp/sel.svg" "$tmp/circle.svg"
check_grep "no element has id 'nosuch'" "$err"
check_grep "no element has id 'other'" "$err"
check_true "nothing selected: the document is written unchanged" cmp -s "$tmp/sel.svg" "$tmp/circle.svg"
svg_doc '<circle id="o" cx="100" cy="100" r="50" fill="red"/><rect x="1" y="1" width="5" height="5"/>' >"$tmp/shapes.svg"
check "convert shapes" "$svgsmooth" --convert-shapes --levels 1 "$tmp/shapes.svg"
check_grep '<path id="o" fill="red" d="M150 100L' "$out"
check_grep '<path d="M1 1L6 1 6 6 1 6Z"/>' "$out"
check "shapes untouched without the flag" "$svgsmooth" "$tmp/shapes.svg"
check_grep '<circle id="o" cx="100" cy="100" r="50" fill="red"/>' "$out"
check "tolerance" "$svgsmooth" --tolerance 0.001 --precision 17 -o "$tmp/tol.svg" "$tmp/circle.svg"
grep -o 'id="c" d="[^"]*"' "$tmp/tol.svg" | sed 's/^id="c"/<x/; s/$/\/>/' >"$tmp/tol.c.svg"
n_tol=$(geom count "$tmp/tol.c.svg")
# level k moves its new points by the sagitta 80(1-cos(pi/(4*2^(k-1)))) of a
# r=80 circle, 4 sample edges of 90 degrees: chords of 90/2^8 degrees bulge by
# 80 (1 - cos(pi/1024)) = 0.00038 <= 0.001, at 2^7 by 0.0015 -> 4 x 2^8 = 1024
check_true "tolerance 0.001 refines a r=80 circle to 1024 points (got $n_tol)" test "$n_tol" -eq 1024

begin_case "flattening: within tolerance, straight segments single"
svg_doc '<path id="f" d="M10 200C10 50 190 50 190 200L390 200L390 390"/>' >"$tmp/flat.svg"
check "flatten" "$svgsmooth" --flatten --tolerance 0.1 --precision 17 -o "$tmp/flat.out.svg" "$tmp/flat.svg"
check_grep 'd="M10 200L[^"]* 190 200 390 200 390 390"' "$tmp/flat.out.svg" "line segments kept single"
n1=$(geom count "$tmp/flat.out.svg")
check "flatten finer" "$svgsmooth" --flatten --tolerance 0.001 -o "$tmp/flat2.out.svg" "$tmp/flat.svg"
n2=$(geom count "$tmp/flat2.out.svg")
check_true "finer tolerance gives more points ($n1 < $n2)" test "$n1" -lt "$n2"

begin_case "rendering: output renders and stays within a few pixels of the input"
if ! command -v rsvg-convert >/dev/null 2>&1; then
    skip_case "rsvg-convert not installed (scripts/deps.sh test)"
fi
for f in examples/*.svg; do
    h_skipping && break
    [ -f "$f" ] || continue
    name=$(basename "$f" .svg)
    check "smooth $name" "$svgsmooth" -o "$tmp/$name.s.svg" "$f"
    check "flatten $name" "$svgsmooth" --flatten --tolerance 0.25 -o "$tmp/$name.f.svg" "$f"
    check "render input $name" rsvg-convert -w 300 -o "$tmp/$name.png" "$f"
    check "render smoothed $name" rsvg-convert -w 300 -o "$tmp/$name.s.png" "$tmp/$name.s.svg"
    check "render flattened $name" rsvg-convert -w 300 -o "$tmp/$name.f.png" "$tmp/$name.f.svg"
    set -- $(geom shape "$tmp/$name.png" "$tmp/$name.s.png" 3)
    check_true "$name smoothed: $1 pixels farther than 3 px from the input shape ($2 covered)" test "$1" -eq 0
    check_true "$name renders something" test "$2" -gt 1000
    set -- $(geom shape "$tmp/$name.png" "$tmp/$name.f.png" 1)
    check_true "$name flattened: $1 pixels farther than 1 px from the input shape" test "$1" -eq 0
done

finish
