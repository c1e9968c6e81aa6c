#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark (run by scripts/bench.sh with the build directory): CPU
# seconds of svgsmooth --simplify 1 --levels 0 on random-walk polylines (steps of up
# to one unit, fixed seed) of 10^3 .. 10^6 vertices, and the exponent k of
# t ~ n^k between neighbouring sizes (issue 33: it was 1.7). Not asserted.
# (--max-depth 257 lifts libxml2's 10 MB cap on one attribute value: the
# 10^6-vertex polyline is 19 MB.)
set -u
build=${1:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '%9s %9s %8s %6s\n' vertices kept seconds k
prev_n=0
prev_t=0
for n in 1000 10000 100000 1000000; do
    awk -v n="$n" 'BEGIN {
        srand(2); x = 0; y = 0
        printf "<svg xmlns=\"http://www.w3.org/2000/svg\"><polyline points=\""
        for (i = 0; i < n; i++) { x += rand(); y += 2 * rand() - 1; printf "%.3f,%.3f ", x, y }
        print "\"/></svg>" }' > "$tmp/w.svg"
    t=$( { /usr/bin/time -f '%U %S' "$build/bin/svgsmooth" --simplify 1 --levels 0 --max-depth 257 \
        --max-input-bytes 67108864 --max-path-bytes 67108864 -o "$tmp/o.svg" "$tmp/w.svg" ; } 2>&1 |
        awk '{ print $1 + $2 }')
    kept=$(tr ' ' '\n' < "$tmp/o.svg" | grep -c ',')
    awk -v n="$n" -v kept="$kept" -v t="$t" -v pn="$prev_n" -v pt="$prev_t" 'BEGIN {
        k = (pn > 0 && pt > 0 && t > 0) ? sprintf("%.2f", log(t / pt) / log(n / pn)) : "-"
        printf "%9d %9d %8.2f %6s\n", n, kept, t, k }'
    prev_n=$n
    prev_t=$t
done
