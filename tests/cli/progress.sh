#!/bin/sh
# SPDX-License-Identifier: MIT
# The progress line of one long job (issue 37): svgsmooth on one document
# and conica subdivide draw it on stderr with --progress (kB of path data,
# edge points), never when stderr is not a terminal by default or with -q,
# and the output is the same bytes either way.
# usage (from the repository root): sh tests/cli/progress.sh BUILD_DIR
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth
conica=$build/bin/conica

begin_case "svgsmooth --progress on one document"
check "svgsmooth --progress" "$svgsmooth" --progress -o "$tmp/p.svg" examples/traced-leaf.svg
tr '\r' '\n' <"$err" >"$tmp/p.err"
check_grep '^svgsmooth: [0-9]*/[0-9]* kB' "$tmp/p.err"
check "svgsmooth -q" "$svgsmooth" -q -o "$tmp/q.svg" examples/traced-leaf.svg
check_true "-q writes nothing on stderr" test ! -s "$err"
check "svgsmooth (stderr not a terminal)" "$svgsmooth" -o "$tmp/d.svg" examples/traced-leaf.svg
check_true "no progress line when stderr is not a terminal" test ! -s "$err"
check_true "the same output with and without progress" cmp "$tmp/p.svg" "$tmp/q.svg"
check_true "... and by default" cmp "$tmp/p.svg" "$tmp/d.svg"
check "a batch keeps its own line (files)" "$svgsmooth" --progress --levels 2 \
    examples/traced-leaf.svg examples/icon-arcs.svg -o "$tmp/batch/"
tr '\r' '\n' <"$err" >"$tmp/b.err"
check_grep '^svgsmooth: [0-9]*/2 files' "$tmp/b.err"
check_true "no per-document kB line in a batch" sh -c "! grep -q ' kB' '$tmp/b.err'"

begin_case "conica subdivide --progress"
check "conica subdivide --progress -k 10" "$conica" subdivide --progress -k 10 -o "$tmp/p.txt" examples/ellipse.txt
tr '\r' '\n' <"$err" >"$tmp/s.err"
check_grep '^conica subdivide: [0-9]*/[0-9]* edge points' "$tmp/s.err"
check "conica subdivide -q -k 10" "$conica" subdivide -q -k 10 -o "$tmp/q.txt" examples/ellipse.txt
check_true "-q writes nothing on stderr" test ! -s "$err"
check "conica subdivide -k 10 (stderr not a terminal)" "$conica" subdivide -k 10 -o "$tmp/d.txt" examples/ellipse.txt
check_true "no progress line when stderr is not a terminal" test ! -s "$err"
check_true "the same points with and without progress" cmp "$tmp/p.txt" "$tmp/q.txt"
check "--progress with threads" "$conica" subdivide --progress --threads 2 -k 10 -o "$tmp/t.txt" examples/ellipse.txt
check_true "the same points with threads" cmp "$tmp/p.txt" "$tmp/t.txt"

finish
