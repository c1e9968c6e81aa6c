#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo` part of issue 5: plot the bundled splines (examples/*.spl)
# with the guaranteed plotter at 0.5 px of a 1000x1000 view, and with the
# thesis's adaptive loop for comparison. BUILD is $1.
set -eu
build=${1:-build}
out=$build/demo
mkdir -p "$out"
for f in examples/*.spl; do
    [ -f "$f" ] || continue
    name=$(basename "$f" .spl)
    "$build/bin/conica" plot --tolerance 0.5 --viewport 1000x1000 --stats \
        -o "$out/$name.plot.txt" "$f" 2>"$out/$name.plot.stats"
    "$build/bin/conica" plot --method adaptive --stats \
        -o "$out/$name.adaptive.txt" "$f" 2>"$out/$name.adaptive.stats"
    echo "  $f -> $out/$name.plot.txt ($(cat "$out/$name.plot.stats"))"
    echo "  $f -> $out/$name.adaptive.txt, thesis loop ($(cat "$out/$name.adaptive.stats"))"
done
