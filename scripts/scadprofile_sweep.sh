#!/bin/sh
# SPDX-License-Identifier: MIT
# scadprofile on a sample of an icon package beside rsvg-convert's pixels
# (docs/benchmarks.md, "scadprofile: the painted region").
#   sh scripts/scadprofile_sweep.sh DIR N FIT [BIN]
# takes N files spread evenly over DIR/*.svg (every (count/N)-th), writes each
# with --units px --fit FIT, and compares its pixels with tests/support/
# scad_pixels.py (lost, added <= 0.1 % outside a 1 px band at 600 px).
# Prints one line per refused or disagreeing file and a summary line.
set -u
dir=$1; n=$2; fit=$3; bin=${4:-build/bin/scadprofile}
py=/usr/bin/python3; [ -x "$py" ] || py=python3
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
total=$(ls "$dir"/*.svg | wc -l)
step=$(( (total + n - 1) / n ))
acc=0; ref=0; ok=0; bad=0
for f in $(ls "$dir"/*.svg | awk -v s="$step" 'NR % s == 1' | head -n "$n"); do
    b=$(basename "$f" .svg)
    if "$bin" --units px --fit "$fit" --module m -o "$out/$b.scad" "$f" 2>"$out/$b.err"; then
        acc=$((acc + 1))
        if "$py" tests/support/scad_pixels.py "$out/$b.scad" "$f" >"$out/$b.pix" 2>&1; then
            ok=$((ok + 1))
        else
            bad=$((bad + 1)); echo "pixels $b: $(cat "$out/$b.pix")"
        fi
    else
        ref=$((ref + 1)); echo "refused $b: $(tail -1 "$out/$b.err")"
    fi
done
echo "$dir --fit $fit: accepted $acc, refused $ref; pixels agree $ok, disagree $bad"
