#!/bin/sh
# scripts/memcheck.sh [BUILD] - valgrind memcheck over the command-line tools
# (make memcheck). A representative set of invocations -- conica
# subdivide/combs/errors (and plot when the tool has it), svgsmooth and
# scadprofile on examples/ and generated inputs, success and error paths --
# each run under
#     valgrind --error-exitcode=1 --leak-check=full
# A run passes when the tool's own exit status is the expected one and
# valgrind's log reports `ERROR SUMMARY: 0 errors` (invalid reads/writes,
# uninitialised values, definite/possible leaks). Logs: BUILD/memcheck/.
set -u
build=${1:-build}
bin=$build/bin
logs=$build/memcheck
mkdir -p "$logs"
rm -f "$logs"/*.log
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-memcheck.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
if ! command -v valgrind >/dev/null 2>&1; then
    echo "memcheck: valgrind is not installed (scripts/deps.sh test installs it)"
    exit 1
fi
pass=0 fail=0 i=0

# run EXPECTED_EXIT NAME CMD...
run() {
    want=$1 name=$2
    shift 2
    i=$((i + 1))
    log=$logs/$(printf '%02d' "$i")-$name.log
    valgrind -q --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,possible \
        --log-file="$log" "$@" >"$tmp/out" 2>"$tmp/err" </dev/null
    st=$?
    if [ "$st" -eq "$want" ] && ! grep -q -E 'ERROR SUMMARY: [1-9]|definitely lost: [1-9]|Invalid (read|write)|uninitialised' "$log"; then
        pass=$((pass + 1))
        printf 'ok    %-28s exit %s\n' "$name" "$st"
    else
        fail=$((fail + 1))
        printf 'FAIL  %-28s exit %s (expected %s), log %s\n' "$name" "$st" "$want" "$log"
        sed 's/^/      /' "$log" | head -n 30
        sed 's/^/      stderr: /' "$tmp/err" | head -n 5
    fi
}

ex=examples
# generated inputs
awk 'BEGIN { for (i = 0; i < 12; i++) { a = 6.283185307179586 * i / 12;
      printf "v %.17g %.17g\n", 3 * cos(a), 2 * sin(a) } }' >"$tmp/ellipse12.txt"
printf 'v 0 0\nv 1 nan\nv 2 0\n' >"$tmp/nan.txt"
printf 'v 0 0\n' >"$tmp/one.txt"
printf 'v 0 0\nv 0 0\nv 0 0\nv 0 0\n' >"$tmp/dup.txt"
printf 'hello world\n' >"$tmp/garbage.txt"
: >"$tmp/empty.txt"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 L10 0 L 10 x"/></svg>\n' >"$tmp/badpath.svg"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n<svg xmlns="http://www.w3.org/2000/svg"><text>&x;</text></svg>\n' >"$tmp/xxe.svg"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0' >"$tmp/truncated.svg"
printf 'degree 2\nknots 0 0 0 1 2 3 3 3\nc 0 0\nc 4 0\nc 6 3\nc 3 6\nc 0 3\n' >"$tmp/open.spl"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 nan\n' >"$tmp/bad.spl"

c=$bin/conica
run 0 subdivide-ellipse "$c" subdivide -k 4 -o "$tmp/o.txt" "$ex/ellipse.txt"
run 0 subdivide-precise "$c" subdivide -k 3 --precise "$ex/flower.txt"
run 0 subdivide-open "$c" subdivide -k 3 --open "$ex/parabola_open.txt"
run 0 subdivide-estimate "$c" subdivide -k 3 --estimate-normals --normals circle "$tmp/ellipse12.txt"
run 0 subdivide-threads "$c" subdivide -k 4 --threads 2 "$ex/flower.txt"
run 0 subdivide-refcompat "$c" subdivide -k 2 --reference-compatible "$tmp/ellipse12.txt"
run 1 subdivide-nan "$c" subdivide -k 2 "$tmp/nan.txt"
run 1 subdivide-one-point "$c" subdivide -k 2 "$tmp/one.txt"
run 1 subdivide-duplicates "$c" subdivide -k 2 "$tmp/dup.txt"
run 1 subdivide-garbage "$c" subdivide "$tmp/garbage.txt"
run 1 subdivide-empty "$c" subdivide "$tmp/empty.txt"
run 1 subdivide-max-points "$c" subdivide -k 10 --max-points 100 "$ex/ellipse.txt"
run 1 subdivide-missing "$c" subdivide "$tmp/does-not-exist.txt"
run 1 subdivide-unwritable "$c" subdivide -k 1 -o "$tmp/no/such/dir/o.txt" "$ex/ellipse.txt"
run 2 subdivide-usage "$c" subdivide --levels 99 "$ex/ellipse.txt"
run 0 combs "$c" combs -k 3 -o "$tmp/c.svg" "$ex/flower.txt"
run 1 combs-nan "$c" combs -k 3 "$tmp/nan.txt"
run 0 errors "$c" errors -k 4 --conic 1,1,0,0,0,-25 --plot "$tmp/e.svg" "$ex/ellipse.txt"
run 1 errors-garbage "$c" errors "$tmp/garbage.txt"
if "$c" plot --help >/dev/null 2>&1; then
    run 0 plot-spline "$c" plot -o "$tmp/p.txt" "$tmp/open.spl"
    run 1 plot-bad-spline "$c" plot "$tmp/bad.spl"
fi

s=$bin/svgsmooth
run 0 svgsmooth-leaf "$s" --levels 3 -o "$tmp/leaf.svg" "$ex/traced-leaf.svg"
run 0 svgsmooth-flatten "$s" --flatten --tolerance 0.1 --convert-shapes "$ex/icon-arcs.svg"
run 0 svgsmooth-tolerance "$s" --tolerance 0.05 "$ex/letter-R.svg"
cp "$ex/rect-star.svg" "$tmp/inplace.svg"
run 0 svgsmooth-in-place "$s" --levels 2 --in-place "$tmp/inplace.svg"
run 0 svgsmooth-badpath "$s" "$tmp/badpath.svg"
run 1 svgsmooth-xxe "$s" "$tmp/xxe.svg"
run 1 svgsmooth-truncated "$s" "$tmp/truncated.svg"
run 1 svgsmooth-not-svg "$s" "$tmp/garbage.txt"
run 1 svgsmooth-max-points "$s" --levels 8 --max-points 100 "$ex/traced-leaf.svg"
run 1 svgsmooth-unwritable "$s" -o "$tmp/no/such/dir/o.svg" "$ex/traced-leaf.svg"

p=$bin/scadprofile
run 0 scadprofile-svg "$p" --extrude 5 -o "$tmp/b.scad" "$ex/bracket.svg"
run 0 scadprofile-points "$p" --tolerance 0.01 "$ex/ellipse.txt"
run 0 scadprofile-levels-force "$p" --levels 3 --force --rotate-extrude "$ex/flower.txt"
run 0 scadprofile-spline "$p" --tolerance 0.01 "$tmp/open.spl"
run 1 scadprofile-nan "$p" "$tmp/nan.txt"
run 1 scadprofile-xxe "$p" "$tmp/xxe.svg"
run 1 scadprofile-bad-spline "$p" "$tmp/bad.spl"
run 1 scadprofile-empty "$p" "$tmp/empty.txt"
run 1 scadprofile-unwritable "$p" -o "$tmp/no/such/dir/o.scad" "$ex/ellipse.txt"

echo "memcheck: $pass passed, $fail failed (valgrind logs in $logs)"
[ "$fail" -eq 0 ]
