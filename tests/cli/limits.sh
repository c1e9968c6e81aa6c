#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/limits.sh BUILD_DIR - every input-controlled size of the tools
# has a default, a flag and a clear error: each cap is hit on purpose and
# the run must exit 1, name the cap in its message, and write nothing (the
# -o file is never created, stdout stays empty). Levels past the hard
# maximum are usage errors (exit 2). See README.md for the table.
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica
svgsmooth=$build/bin/svgsmooth
scad=$build/bin/scadprofile
ex=examples

# refused EXIT PATTERN OUTFILE CMD...: exit status, an stderr line matching
# PATTERN, no OUTFILE and no stdout.
refused() {
    r_want=$1 r_pat=$2 r_outf=$3
    shift 3
    rm -f "$r_outf"
    check_exit "$r_want" "exit $r_want: $*" "$@"
    check_grep "$r_pat" "$err" "message /$r_pat/"
    check_true "nothing written to $(basename "$r_outf")" test ! -e "$r_outf"
    check_true "nothing on stdout" test ! -s "$out"
}

printf 'v 0 0\nv 4 0\nv 4 3\nv 0 3\n' >"$tmp/square.txt"
printf 'degree 2\nknots 0 0 0 1 2 3 3 3\nc 0 0\nc 4 0\nc 6 3\nc 3 6\nc 0 3\n' >"$tmp/open.spl"

begin_case "subdivision levels: 0..30, more is a usage error"
refused 2 '-k needs an integer in 0\.\.30' "$tmp/o.txt" \
    "$conica" subdivide -k 31 -o "$tmp/o.txt" "$ex/ellipse.txt"
refused 2 '0\.\.30' "$tmp/o.svg" "$conica" combs -k 31 -o "$tmp/o.svg" "$ex/ellipse.txt"
refused 2 '0\.\.20' "$tmp/o.txt" "$conica" errors -k 21 "$ex/ellipse.txt"
refused 2 '--levels needs a whole number in 0\.\.30' "$tmp/o.svg" \
    "$svgsmooth" --levels 31 -o "$tmp/o.svg" "$ex/letter-R.svg"
refused 2 '--levels needs an integer in 0\.\.30' "$tmp/o.scad" \
    "$scad" --levels 31 -o "$tmp/o.scad" "$ex/ellipse.txt"

begin_case "output points: default budget refuses a huge level before allocating"
refused 1 'would make more than the 67108864 points allowed \(max_points\)' "$tmp/o.txt" \
    "$conica" subdivide -k 30 -o "$tmp/o.txt" "$ex/ellipse.txt"
refused 1 'more than the 67108864 points allowed' "$tmp/o.svg" \
    "$conica" combs -k 25 -o "$tmp/o.svg" "$ex/ellipse.txt"
refused 1 'exceed the limit of 67108864 points \(--max-points\)' "$tmp/o.svg" \
    "$svgsmooth" --levels 30 -o "$tmp/o.svg" "$ex/letter-R.svg"
refused 1 'more than the 4194304 points allowed' "$tmp/o.scad" \
    "$scad" --levels 30 -o "$tmp/o.scad" "$ex/ellipse.txt"

begin_case "output points: --max-points lowers the budget"
refused 1 'more than the 1000 points allowed \(max_points\)' "$tmp/o.txt" \
    "$conica" subdivide -k 10 --max-points 1000 -o "$tmp/o.txt" "$ex/ellipse.txt"
refused 1 'exceed the limit of 50 points \(--max-points\)' "$tmp/o.svg" \
    "$svgsmooth" --max-points 50 -o "$tmp/o.svg" "$ex/letter-R.svg"
refused 1 'more than the 100 points allowed' "$tmp/o.scad" \
    "$scad" --max-points 100 --levels 10 -o "$tmp/o.scad" "$ex/ellipse.txt"
refused 1 'needs more than 100 dense points.*raise the cap or the tolerance' "$tmp/o.scad" \
    "$scad" --max-points 100 --tolerance 1e-9 -o "$tmp/o.scad" "$ex/ellipse.txt"
refused 2 '--max-points needs an integer in 16\.\.' "$tmp/o.scad" \
    "$scad" --max-points 10 -o "$tmp/o.scad" "$ex/ellipse.txt"

begin_case "plotter: a tolerance too fine for the point budget is refused (flatten, spline)"
refused 1 'exceed the limit of 100 points \(--max-points\)' "$tmp/o.svg" \
    "$svgsmooth" --flatten --tolerance 0.00001 --max-points 100 -o "$tmp/o.svg" "$ex/icon-arcs.svg"
refused 1 'scadprofile: error: .*open\.spl' "$tmp/o.scad" \
    "$scad" --max-points 16 --tolerance 1e-12 -o "$tmp/o.scad" "$tmp/open.spl"

begin_case "conica plot: output points, knot budget, --points within --max-points"
if ! "$conica" plot --help >/dev/null 2>&1; then
    skip_case "this conica has no plot command"
else
    refused 1 'open\.spl: .*max_points' "$tmp/o.txt" \
        "$conica" plot --abs-tolerance 1e-12 --max-points 100 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--knot-budget 2000000 exceeds --max-knots 1000000' "$tmp/o.txt" \
        "$conica" plot --method adaptive --stop budget --knot-budget 2000000 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--points 5000000 exceeds --max-points 4000000' "$tmp/o.txt" \
        "$conica" plot --method chaikin --points 5000000 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 1 'corner cutting exceeds 1000 points \(max_points\)' "$tmp/o.txt" \
        "$conica" plot --method chaikin --points 1000 --max-points 1000 -o "$tmp/o.txt" "$tmp/open.spl"
    # --points is an input-controlled size too: it must not lift the output
    # cap (cmd_plot.c raised max_points to --points, so `--points 100000000`
    # allocated gigabytes). Either a usage error or a limit error is right.
    for m in uniform mathematica; do
        rm -f "$tmp/o.txt"
        h_run "$conica" plot --method "$m" --points 100000 --max-points 1000 -o "$tmp/o.txt" "$tmp/open.spl"
        st=$?
        check_true "--method $m --points 100000 --max-points 1000 is refused (exit $st)" \
            test "$st" -eq 1 -o "$st" -eq 2
        check_true "--method $m: nothing written" test ! -e "$tmp/o.txt"
    done
fi

begin_case "conica plot: knots inserted (--max-knots) and iterations (--max-iterations)"
if ! "$conica" plot --help >/dev/null 2>&1; then
    skip_case "this conica has no plot command"
else
    check "--help documents --max-knots and --max-iterations" "$conica" plot --help
    check_grep '--max-knots=N +limit: refuse to insert more than N knots' "$out"
    check_grep '--max-iterations=N +limit: refuse to run more than N plotter' "$out"
    check_grep 'trial steps \(default 20000000\)' "$out"
    # pre-phase 5 + loop budget 5 = 10 knots under a cap of 5: the loop hits it
    refused 1 'open\.spl: more than 5 knots inserted \(max_knots\); raise the cap with --max-knots N' \
        "$tmp/o.txt" "$conica" plot --method adaptive --stop budget --prephase 5 --knot-budget 5 \
        --max-knots 5 -o "$tmp/o.txt" "$tmp/open.spl"
    check "the same run passes with --max-knots 10" "$conica" plot --method adaptive --stop budget \
        --prephase 5 --knot-budget 5 --max-knots 10 -o "$tmp/o.txt" "$tmp/open.spl"
    check_true "... and writes the plot" test -s "$tmp/o.txt"
    check "--stats: between 6 and 10 knots inserted" "$conica" plot --method adaptive --stop budget \
        --prephase 5 --knot-budget 5 --max-knots 10 --stats -o "$tmp/o.txt" "$tmp/open.spl"
    check_grep '^plot: [0-9]+ points, ([6-9]|10) knots inserted' "$err"
    refused 2 '--knot-budget 50 exceeds --max-knots 5' "$tmp/o.txt" \
        "$conica" plot --method adaptive --knot-budget 50 --max-knots 5 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--prephase 6 exceeds --max-knots 5' "$tmp/o.txt" \
        "$conica" plot --method adaptive --prephase 6 --max-knots 5 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--max-knots needs an integer >= 0' "$tmp/o.txt" \
        "$conica" plot --max-knots -1 -o "$tmp/o.txt" "$tmp/open.spl"
    check "a lower --max-knots lowers the default knot budget (500) instead of refusing" \
        "$conica" plot --method adaptive --max-knots 3 --stats -o "$tmp/o.txt" "$tmp/open.spl"
    check_grep '^plot: [0-9]+ points, [0-3] knots inserted' "$err"
    refused 1 'open\.spl: guaranteed plot needs more than 5 trial steps \(max_iterations\); raise the cap with --max-iterations N' \
        "$tmp/o.txt" "$conica" plot --abs-tolerance 1e-9 --max-iterations 5 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 1 'adaptive loop exceeds 3 iterations \(max_iterations\); raise the cap with --max-iterations N' \
        "$tmp/o.txt" "$conica" plot --method adaptive --max-iterations 3 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--max-iterations needs an integer >= 1' "$tmp/o.txt" \
        "$conica" plot --max-iterations 0 -o "$tmp/o.txt" "$tmp/open.spl"
    check "the default caps let the guaranteed plot of 1e-9 through" \
        "$conica" plot --abs-tolerance 1e-9 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 1 'raise the cap with --max-points N' "$tmp/o.txt" \
        "$conica" plot --abs-tolerance 1e-9 --max-points 10 -o "$tmp/o.txt" "$tmp/open.spl"
fi

begin_case "readers: input points (--max-input-points), spline size (--max-control-points, --max-degree)"
refused 1 'ellipse\.txt:8: more than 5 points \(the reader.s max_points\); raise the cap with --max-input-points N' \
    "$tmp/o.txt" "$conica" subdivide -k 1 --max-input-points 5 -o "$tmp/o.txt" "$ex/ellipse.txt"
check "--max-input-points 12 lets the 12 points of ellipse.txt through" \
    "$conica" subdivide -k 1 --max-input-points 12 -o "$tmp/o.txt" "$ex/ellipse.txt"
refused 2 '--max-input-points needs a positive integer' "$tmp/o.txt" \
    "$conica" subdivide --max-input-points 0 -o "$tmp/o.txt" "$ex/ellipse.txt"
check "conica subdivide --help documents --max-input-points" "$conica" subdivide --help
check_grep '--max-input-points=N' "$out"
check_grep '^ +refuse inputs of more than N points \(default 16777216' "$out"
if "$conica" plot --help >/dev/null 2>&1; then
    refused 1 'open\.spl:7: more than 4 control points \(max_ctrl\); raise the cap with --max-control-points N' \
        "$tmp/o.txt" "$conica" plot --max-control-points 4 -o "$tmp/o.txt" "$tmp/open.spl"
    check "--max-control-points 5 lets the 5 control points through" \
        "$conica" plot --max-control-points 5 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--max-control-points needs an integer in 1\.\.4194304' "$tmp/o.txt" \
        "$conica" plot --max-control-points 4194305 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 1 'open\.spl:1: degree 2 exceeds 1 \(max_degree\); raise the cap with --max-degree N \(at most 50\)' \
        "$tmp/o.txt" "$conica" plot --max-degree 1 -o "$tmp/o.txt" "$tmp/open.spl"
    refused 2 '--max-degree needs an integer in 1\.\.50' "$tmp/o.txt" \
        "$conica" plot --max-degree 51 -o "$tmp/o.txt" "$tmp/open.spl"
    printf 'degree 51\nknots 0 1\nc 0 0\n' >"$tmp/deg51.spl"
    refused 1 'deg51\.spl:1: degree 51 exceeds 50$' "$tmp/o.txt" \
        "$conica" plot -o "$tmp/o.txt" "$tmp/deg51.spl"
fi

begin_case "XML: document size (--max-input-bytes)"
refused 1 'input larger than the limit of 100 bytes' "$tmp/o.svg" \
    "$svgsmooth" --max-input-bytes 100 -o "$tmp/o.svg" "$ex/letter-R.svg"

begin_case "input file size: CONICA_MAX_INPUT_BYTES for conica and scadprofile"
refused 1 'input larger than the limit of 40 bytes' "$tmp/o.txt" \
    env CONICA_MAX_INPUT_BYTES=40 "$conica" subdivide -o "$tmp/o.txt" "$ex/ellipse.txt"
refused 1 'input larger than the limit of 40 bytes' "$tmp/o.txt" \
    env CONICA_MAX_INPUT_BYTES=40 "$conica" plot -o "$tmp/o.txt" "$tmp/open.spl"
refused 1 'input larger than the limit of 40 bytes' "$tmp/o.scad" \
    env CONICA_MAX_INPUT_BYTES=40 "$scad" -o "$tmp/o.scad" "$ex/ellipse.txt"
check "a larger cap lets the same file through" \
    env CONICA_MAX_INPUT_BYTES=100000 "$conica" subdivide -k 1 -o "$tmp/o.txt" "$ex/ellipse.txt"
check "a malformed value warns and keeps the default" \
    env CONICA_MAX_INPUT_BYTES=lots "$conica" subdivide -k 1 -o "$tmp/o.txt" "$ex/ellipse.txt"
check_grep "CONICA_MAX_INPUT_BYTES='lots' is not a whole number" "$err"

begin_case "XML: nesting depth (--max-depth, default 256)"
{
    printf '<svg xmlns="http://www.w3.org/2000/svg">'
    i=0
    while [ $i -lt 200 ]; do printf '<g>'; i=$((i + 1)); done
    printf '<path d="M0 0L1 0L1 1Z"/>'
    i=0
    while [ $i -lt 200 ]; do printf '</g>'; i=$((i + 1)); done
    printf '</svg>\n'
} >"$tmp/deep200.svg"
check "200 levels pass the default cap" "$svgsmooth" -o "$tmp/ok.svg" "$tmp/deep200.svg"
refused 1 'elements nested deeper than 100 \(--max-depth\)' "$tmp/o.svg" \
    "$svgsmooth" --max-depth 100 -o "$tmp/o.svg" "$tmp/deep200.svg"

begin_case "XML: number of elements (--max-elements)"
{
    printf '<svg xmlns="http://www.w3.org/2000/svg">'
    i=0
    while [ $i -lt 300 ]; do printf '<path d="M%d 0L%d 1L%d 1Z"/>' $((3 * i)) $((3 * i + 1)) $((3 * i)); i=$((i + 1)); done
    printf '</svg>\n'
} >"$tmp/many.svg"
check "300 elements pass the default cap" "$svgsmooth" --levels 1 -o "$tmp/ok.svg" "$tmp/many.svg"
refused 1 'more than 100 elements \(--max-elements\)' "$tmp/o.svg" \
    "$svgsmooth" --max-elements 100 -o "$tmp/o.svg" "$tmp/many.svg"

begin_case "XML: attributes of one element (--max-attributes, default 256)"
# libxml2's work on one start tag is quadratic in its attributes (10^5 on
# one <path> took 17 s to minutes): they are counted before it parses.
attrs_svg() { # N FILE
    awk -v n="$1" 'BEGIN {
        printf "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M0 0L1 0L1 1Z\""
        for (i = 1; i < n; i++) printf " a%d=\"1\"", i
        printf "/></svg>\n" }' >"$2"
}
attrs_svg 256 "$tmp/attrs256.svg"
attrs_svg 100000 "$tmp/attrs100k.svg"
for tool in "$svgsmooth" "$scad"; do
    name=$(basename "$tool")
    check "$name: 256 attributes pass the default cap" "$tool" -o "$tmp/ok.out" "$tmp/attrs256.svg"
    refused 1 "^$name: error: .*attrs256.svg:2: element <path> has more than 255 attributes \(--max-attributes\)" \
        "$tmp/o.out" "$tool" --max-attributes 255 -o "$tmp/o.out" "$tmp/attrs256.svg"
    refused 1 "^$name: error: .*attrs100k.svg:2: element <path> has more than 256 attributes \(--max-attributes\)" \
        "$tmp/o.out" "$tool" -o "$tmp/o.out" "$tmp/attrs100k.svg"
done

begin_case "XML: namespace declarations in scope (--max-namespaces, default 64)"
ns_svg() { # N-ON-ROOT N-ON-G FILE
    awk -v r="$1" -v g="$2" 'BEGIN {
        printf "<svg xmlns=\"http://www.w3.org/2000/svg\""
        for (i = 1; i < r; i++) printf " xmlns:r%d=\"urn:r%d\"", i, i
        printf ">\n<g"
        for (i = 0; i < g; i++) printf " xmlns:g%d=\"urn:g%d\"", i, i
        printf "><path d=\"M0 0L1 0L1 1Z\"/></g>\n<g xmlns:h=\"urn:h\"/></svg>\n" }' >"$3"
}
ns_svg 32 32 "$tmp/ns64.svg"       # 64 in scope at the <g>
ns_svg 32 33 "$tmp/ns65.svg"       # 65
ns_svg 50000 0 "$tmp/ns50k.svg"    # the issue's 50 000 declarations on one element
for tool in "$svgsmooth" "$scad"; do
    name=$(basename "$tool")
    check "$name: 64 declarations in scope pass" "$tool" -o "$tmp/ok.out" "$tmp/ns64.svg"
    refused 1 "^$name: error: .*ns65.svg:2: element <g> has more than 64 namespace declarations in scope \(--max-namespaces\)" \
        "$tmp/o.out" "$tool" -o "$tmp/o.out" "$tmp/ns65.svg"
    check "$name --max-namespaces 65 reads it" "$tool" --max-namespaces 65 -o "$tmp/ok.out" "$tmp/ns65.svg"
    refused 1 "^$name: error: .*ns50k.svg:1: element <svg> has more than 64 namespace declarations in scope" \
        "$tmp/o.out" "$tool" -o "$tmp/o.out" "$tmp/ns50k.svg"
done
refused 2 "^svgsmooth: usage error: --max-attributes needs a whole number in 1\.\.2147483647, not '0'" \
    "$tmp/o.out" "$svgsmooth" --max-attributes 0 -o "$tmp/o.out" "$tmp/ns64.svg"

begin_case "path data length (--max-path-bytes, default 32 MiB)"
refused 1 "path 'R': path data exceeds the limit of 10 bytes \(--max-path-bytes\)" "$tmp/o.svg" \
    "$svgsmooth" --max-path-bytes 10 -o "$tmp/o.svg" "$ex/letter-R.svg"
{
    printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0'
    # 12 000 000 bytes of path data: over libxml2's own 10 MB (which no
    # longer applies), under the 32 MiB default
    head -c 2400000 /dev/zero | tr '\0' 'L' | sed 's/L/ L1 1/g'
    printf 'Z"/></svg>\n'
} >"$tmp/path12m.svg"
check "a 12 MB d under the default" "$svgsmooth" --flatten --tolerance 0.1 -o "$tmp/o.svg" "$tmp/path12m.svg"
refused 1 'path data exceeds the limit of 8388608 bytes \(--max-path-bytes\)' "$tmp/o2.svg" \
    "$svgsmooth" --max-path-bytes 8388608 -o "$tmp/o2.svg" "$tmp/path12m.svg"
rm -f "$tmp/path12m.svg" "$tmp/o.svg"

begin_case "svgsmooth writes each element as it goes: a later failure leaves the output as it was"
# The first paths are written into the temporary before the budget runs out
# on the last one: the run fails naming it, the existing output keeps its
# bytes and no temporary is left beside it.
mkdir -p "$tmp/stream"
{
    printf '<svg xmlns="http://www.w3.org/2000/svg">\n'
    for i in 1 2 3; do
        printf '<path id="p%s" d="M0 0C1 2 3 4 5 5S9 1 10 0"/>\n' "$i"
    done
    printf '<path id="big" d="M0 0C1 2 3 4 5 5S9 1 10 0S19 1 20 0S29 1 30 0S39 1 40 0S49 1 50 0"/>\n</svg>\n'
} >"$tmp/stream/in.svg"
printf 'keep me\n' >"$tmp/stream/out.svg"
check_exit 0 "without a budget the document is written (3 x 73 + 201 points)" \
    "$svgsmooth" --levels 3 --stats -o "$tmp/stream/ok.svg" "$tmp/stream/in.svg"
check_grep ' 4 elements, .* 420 output points' "$err" "four paths, 420 points"
check_exit 1 "exit 1 with a budget the last path exceeds" \
    "$svgsmooth" --levels 3 --max-points 350 -o "$tmp/stream/out.svg" "$tmp/stream/in.svg"
check_grep "in\.svg:5: .*path 'big'.*--max-points" "$err" "the message names the file, line and path"
check_true "the output keeps its bytes" sh -c "test \"\$(cat '$tmp/stream/out.svg')\" = 'keep me'"
check_true "no temporary left" sh -c "test \$(ls -A '$tmp/stream' | wc -l) -eq 3"

begin_case "stdin: the size cap applies to a pipe too"
check_exit 1 "svgsmooth refuses a large stdin" \
    sh -c "cat '$ex/traced-leaf.svg' | '$svgsmooth' --max-input-bytes 200 -"
check_grep 'input larger than the limit of 200 bytes' "$err"

finish
