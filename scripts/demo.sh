#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo`: run the main jobs on the bundled examples/ and say where the
# results are. BUILD is $1. Each module's scripts/demo-*.sh adds its part.
set -eu
build=${1:-build}
out=$build/demo
mkdir -p "$out"
echo "demo: conic subdivision of the bundled curves (5 levels)"
for f in examples/*.txt; do
    [ -f "$f" ] || continue
    name=$(basename "$f" .txt)
    case "$name" in *open*) mode=--open ;; *) mode=--closed ;; esac
    "$build/bin/conica" subdivide -k 5 $mode -o "$out/$name.k5.txt" "$f"
    echo "  $f -> $out/$name.k5.txt ($(grep -c '^v ' "$out/$name.k5.txt") points)"
done
for s in scripts/demo-*.sh; do
    [ -f "$s" ] || continue
    echo "demo: $(basename "$s" .sh | sed 's/^demo-//')"
    sh "$s" "$build"
done
echo "demo: all outputs are in $out/"
