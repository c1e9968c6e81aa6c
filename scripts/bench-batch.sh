#!/bin/sh
# SPDX-License-Identifier: MIT
# Many small files: svgsmooth on N copies of the example SVGs (0.4-1.5 kB
# each, default N = 10000) in one call (-r, -j 2 and -j 1), against a shell
# loop of one svgsmooth per file and against xargs -P 2 (two at a time).
# Wall and CPU (user + system, children included) seconds; every method
# must write the same N files. Figures only, no assertions.
# Usage: sh scripts/bench-batch.sh BUILD_DIR
#   BATCH_FILES=N   another N; BATCH_LOOPS=0 leaves out the shell loop and
#   xargs (a process start per file: about 0.03 s CPU and, on a busy
#   machine, 0.25 s wall each, i.e. most of an hour for 10 000 files)
[ -n "${BASH_VERSION:-}" ] || exec bash "$0" "$@"
set -u
build=${1:-build}
svgsmooth=$(cd "$build/bin" && pwd)/svgsmooth
n=${BATCH_FILES:-10000}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-bench-batch.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/in"
# one awk process writes the N copies (a cp per file would take minutes)
awk -v n="$n" -v dir="$tmp/in" '
    FNR == 1 { k++ } { doc[k] = doc[k] $0 "\n" }
    END { for (i = 0; i < n; i++) { f = dir "/f" i ".svg"; printf "%s", doc[i % k + 1] >f; close(f) } }
' examples/*.svg
opts="--levels 3"
TIMEFORMAT='%R %U %S'

# run NAME COMMAND...: one row (the command's outputs go to $tmp/NAME/)
run() {
    name=$1
    shift
    rm -rf "${tmp:?}/out"
    mkdir -p "$tmp/out"
    t=$( { time "$@" >/dev/null 2>"$tmp/err"; } 2>&1 )
    set -- $t
    written=$(ls "$tmp/out" | wc -l)
    awk -v name="$name" -v w="$1" -v u="$2" -v s="$3" -v n="$n" -v k="$written" 'BEGIN {
        printf "| %-34s | %7.2f | %7.2f | %8.0f | %6d |\n", name, w, u + s, n / w, k }'
    [ -z "$keep" ] && cp -r "$tmp/out" "$tmp/ref" && keep=1
    diff -rq "$tmp/ref" "$tmp/out" >/dev/null || echo "| ($name: outputs differ from the first method's) |"
}
keep=

loop() {
    for f in "$tmp"/in/*.svg; do
        "$svgsmooth" $opts -o "$tmp/out/${f##*/}" "$f"
    done
}
xargs2() {
    (cd "$tmp/in" && ls | xargs -P 2 -I{} "$svgsmooth" $opts -o "$tmp/out/{}" "$tmp/in/{}")
}

echo "svgsmooth $opts on $n small SVG files ($(nproc) processors online)"
echo
echo "| method                             |  wall s |   CPU s |  files/s | written |"
echo "| ---------------------------------- | ------: | ------: | -------: | ------: |"
# shellcheck disable=SC2086
run "one call: svgsmooth -r -j 2" "$svgsmooth" $opts -r -j 2 "$tmp/in" -o "$tmp/out/"
# shellcheck disable=SC2086
run "one call: svgsmooth -r -j 1" "$svgsmooth" $opts -r -j 1 "$tmp/in" -o "$tmp/out/"
if [ "${BATCH_LOOPS:-1}" != 0 ]; then
    run "shell loop, one svgsmooth per file" loop
    run "xargs -P 2, one svgsmooth per file" xargs2
fi
