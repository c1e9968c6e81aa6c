#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth on many files in one call: FILE... -o DIR/, --in-place FILE...,
# -r (directories mirrored), -j N; one broken file among 200 fails alone
# (named, exit 1, the 199 others written); every output is byte for byte
# what a single-file run writes.
# Usage (from the repo root): sh tests/cli/svgsmooth_batch.sh BUILD_DIR
. "$(dirname "$0")/harness.sh"

svgsmooth=$build/bin/svgsmooth

# icon I: a small document, different for each I (a circle of arcs, a
# polygon, a cubic)
icon() {
    awk -v i="$1" 'BEGIN {
        r = 10 + i % 17; cx = 50 + i % 7; cy = 40 + i % 5
        printf "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 120 120\">\n"
        printf "  <path id=\"c\" d=\"M%d %dA%d %d 0 0 1 %d %dA%d %d 0 0 1 %d %dZ\"/>\n", cx - r, cy, r, r, cx + r, cy, r, r, cx - r, cy
        printf "  <polygon id=\"p\" points=\"10,10 %d,12 30,%d\"/>\n", 40 + i % 9, 30 + i % 11
        printf "  <path id=\"b\" d=\"M5 100C20 %d 60 %d 100 100\"/>\n</svg>\n", 60 + i % 13, 70 + i % 3 }'
}

mkdir -p "$tmp/in"
i=0
while [ $i -lt 200 ]; do
    icon $i >"$tmp/in/icon-$(printf %03d $i).svg"
    i=$((i + 1))
done
# one broken document among them
printf '<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M0 0L1 1"/>\n<g>\n' >"$tmp/in/icon-137.svg"

begin_case "200 files in one call, one broken: 199 written, the broken one named, exit 1"
check_exit 1 "svgsmooth FILE... -o DIR/" "$svgsmooth" --levels 3 -j 2 "$tmp"/in/*.svg -o "$tmp/out/"
check_grep "^svgsmooth: error: $tmp/in/icon-137.svg:[0-9]+: " "$err" "the broken file is named with its line"
check_count 1 '^svgsmooth: error:' "$err" "one error line"
check_grep '^svgsmooth: 199 files written, 1 failed$' "$err" "one summary line"
check_true "199 outputs" test "$(ls "$tmp/out" | wc -l)" -eq 199
check_true "no output for the broken file" test ! -e "$tmp/out/icon-137.svg"
check_true "no temporary left" test -z "$(ls -A "$tmp/out" | grep conica-tmp)"

begin_case "each output is what a single-file run writes"
bad=0
for n in 000 001 042 136 138 199; do
    "$svgsmooth" --levels 3 -o "$tmp/single.svg" "$tmp/in/icon-$n.svg" 2>/dev/null
    cmp -s "$tmp/single.svg" "$tmp/out/icon-$n.svg" || bad="$bad $n"
done
check_true "identical to single-file runs (differing:$bad)" test "$bad" = 0
check "-j 1 gives the same files" "$svgsmooth" --levels 3 -j 1 "$tmp/in/icon-00"?.svg -o "$tmp/out1/"
check_true "-j 1 and -j 2 agree" sh -c "for f in '$tmp'/out1/*.svg; do cmp -s \"\$f\" '$tmp'/out/\${f##*/} || exit 1; done"
check_grep '^svgsmooth: 10 files written, 0 failed$' "$err" "summary"
check "default -j (processor count)" "$svgsmooth" --flatten --tolerance 0.1 "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg" -o "$tmp/flat"/
"$svgsmooth" --flatten --tolerance 0.1 "$tmp/in/icon-001.svg" >"$tmp/flat1.svg"
check_true "flatten batch output = single run" cmp -s "$tmp/flat1.svg" "$tmp/flat/icon-001.svg"

begin_case "--in-place FILE...: each replaced, a broken one left as it was"
mkdir -p "$tmp/ip"
cp "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg" "$tmp/in/icon-137.svg" "$tmp/ip/"
chmod 640 "$tmp/ip/icon-001.svg"
check_exit 1 "--in-place three files, one broken" "$svgsmooth" --levels 3 --in-place "$tmp/ip/icon-000.svg" "$tmp/ip/icon-001.svg" "$tmp/ip/icon-137.svg"
check_grep '^svgsmooth: 2 files written, 1 failed$' "$err" "summary"
check_true "icon-000 replaced as a single run writes it" cmp -s "$tmp/ip/icon-000.svg" "$tmp/out/icon-000.svg"
check_true "icon-001 replaced" cmp -s "$tmp/ip/icon-001.svg" "$tmp/out/icon-001.svg"
check_true "icon-001 keeps its mode 640" test "$(ls -ln "$tmp/ip/icon-001.svg" | cut -c1-10)" = "-rw-r-----"
check_true "the broken one untouched" cmp -s "$tmp/ip/icon-137.svg" "$tmp/in/icon-137.svg"
check_true "no temporary left" test -z "$(ls -A "$tmp/ip" | grep conica-tmp)"

begin_case "-r: the tree mirrored under the output directory, only *.svg, hidden entries skipped"
mkdir -p "$tmp/tree/a/b" "$tmp/tree/.hidden" "$tmp/tree/c"
cp "$tmp/in/icon-000.svg" "$tmp/tree/top.svg"
cp "$tmp/in/icon-001.svg" "$tmp/tree/a/same.svg"
cp "$tmp/in/icon-002.svg" "$tmp/tree/a/b/same.SVG"
cp "$tmp/in/icon-003.svg" "$tmp/tree/c/same.svg"
cp "$tmp/in/icon-004.svg" "$tmp/tree/.hidden/x.svg"
echo "not svg" >"$tmp/tree/a/notes.txt"
check "-r DIR -o OUT/" "$svgsmooth" -r --levels 3 "$tmp/tree" -o "$tmp/mirror/"
check_grep '^svgsmooth: 4 files written, 0 failed$' "$err" "summary"
(cd "$tmp/mirror" && find . -type f | sort) >"$tmp/list"
printf './a/b/same.SVG\n./a/same.svg\n./c/same.svg\n./top.svg\n' >"$tmp/want"
check_true "the mirrored files: $(tr '\n' ' ' <"$tmp/list")" cmp -s "$tmp/list" "$tmp/want"
check_true "a/b/same.SVG as a single run" cmp -s "$tmp/mirror/a/b/same.SVG" "$tmp/out/icon-002.svg"
check "-r into a directory inside the tree skips it" "$svgsmooth" -r --levels 3 "$tmp/tree" -o "$tmp/tree/smoothed/"
check "again: the earlier outputs are not inputs" "$svgsmooth" -r --levels 3 "$tmp/tree" -o "$tmp/tree/smoothed/"
check_grep '^svgsmooth: 4 files written, 0 failed$' "$err" "still 4 files"
cp -r "$tmp/tree/a" "$tmp/ipr"
check "-r --in-place" "$svgsmooth" -r --levels 3 --in-place "$tmp/ipr"
check_true "replaced in place" cmp -s "$tmp/ipr/b/same.SVG" "$tmp/out/icon-002.svg"

begin_case "usage errors come before anything is written"
check_exit 2 "two inputs with one base name" "$svgsmooth" "$tmp/tree/a/same.svg" "$tmp/tree/c/same.svg" -o "$tmp/dup/"
check_grep "would both be written to" "$err" "names the clash"
check_grep "same.svg" "$err" "names the inputs"
check_true "nothing created" test ! -e "$tmp/dup"
check_exit 1 "a directory without -r: an input that fails, not a usage error" "$svgsmooth" "$tmp/tree" -o "$tmp/x/"
check_grep "tree: is a directory, not written \(-r processes" "$err" "says to use -r"
check_true "nothing written" sh -c 'test -z "$(ls -A "$1" 2>/dev/null)"' sh "$tmp/x"
check_exit 2 "several inputs without -o or --in-place" "$svgsmooth" "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg"
check_exit 2 "several inputs and -o FILE" "$svgsmooth" "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg" -o "$tmp/one.svg"
check_true "-o FILE not created" test ! -e "$tmp/one.svg"
check_exit 2 "stdin among several" "$svgsmooth" - "$tmp/in/icon-000.svg" -o "$tmp/x/"
check_exit 2 "-j 0" "$svgsmooth" -j 0 "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg" -o "$tmp/x/"
check_exit 2 "-j 257" "$svgsmooth" -j 257 "$tmp/in/icon-000.svg" "$tmp/in/icon-001.svg" -o "$tmp/x/"
check_exit 2 "-j with one file to stdout" "$svgsmooth" -j 2 "$tmp/in/icon-000.svg"
check_exit 2 "-o onto an existing file with -r" "$svgsmooth" -r "$tmp/tree" -o "$tmp/in/icon-000.svg"
mkdir -p "$tmp/nosvg"
echo "not svg" >"$tmp/nosvg/notes.txt"
check_exit 2 "-r finding no .svg" "$svgsmooth" -r "$tmp/nosvg" -o "$tmp/y/"
check_grep "no .svg files found" "$err" "says so"
check "one input, -o DIR/: into the directory" "$svgsmooth" --levels 3 "$tmp/in/icon-005.svg" -o "$tmp/one/"
check_true "DIR/icon-005.svg as a single run" sh -c "'$svgsmooth' --levels 3 '$tmp/in/icon-005.svg' | cmp -s - '$tmp/one/icon-005.svg'"
check_exit 1 "one input, -o an existing directory without '/': the error it always was" "$svgsmooth" --levels 3 "$tmp/in/icon-005.svg" -o "$tmp/one"
check_grep "is a directory" "$err" "says so"

begin_case "one directory among 200 inputs: 199 written, exit 1 (issue 33)"
mkdir -p "$tmp/many" "$tmp/many/adir"
i=0
while [ $i -lt 199 ]; do
    cp "$tmp/in/icon-000.svg" "$tmp/many/f$i.svg"
    i=$((i + 1))
done
set -- "$tmp"/many/f*.svg
check_exit 1 "199 files and a directory" "$svgsmooth" --levels 2 "$@" "$tmp/many/adir" -o "$tmp/manyout/"
check_grep "adir: is a directory, not written" "$err" "names the directory"
check_grep "199 files written, 1 failed" "$err" "the summary counts it"
check_true "199 outputs" test "$(ls "$tmp/manyout" | wc -l)" -eq 199

begin_case "scadprofile IN... -o DIR/: one module per input, a failing one alone"
scad=$build/bin/scadprofile
mkdir -p "$tmp/sp"
cp examples/ellipse.txt examples/bracket.svg "$tmp/sp/"
cp examples/ellipse.txt "$tmp/sp/ring-2.txt"
printf 'v 0 0\nv 1\n' >"$tmp/sp/broken.txt"
check_exit 1 "four inputs, one broken" "$scad" --tolerance 0.05 -j 2 "$tmp/sp/ellipse.txt" "$tmp/sp/bracket.svg" "$tmp/sp/ring-2.txt" "$tmp/sp/broken.txt" -o "$tmp/scad/"
check_grep "^scadprofile: error: $tmp/sp/broken.txt:2: " "$err" "the broken one named with its line"
check_grep '^scadprofile: 3 files written, 1 failed$' "$err" "summary"
check_true "three .scad files" test "$(ls "$tmp/scad" | tr '\n' ' ')" = "bracket.scad ellipse.scad ring-2.scad "
check_grep '^module ring_2\(' "$tmp/scad/ring-2.scad" "module named from the file name"
check_grep "^// command: scadprofile --tolerance 0.05 -j 2 -o $tmp/scad/ring-2.scad $tmp/sp/ring-2.txt\$" "$tmp/scad/ring-2.scad" "the header records the command for this file alone"
"$scad" --tolerance 0.05 -o "$tmp/ring-single.scad" "$tmp/sp/ring-2.txt" 2>/dev/null
grep -v '^// command:' "$tmp/ring-single.scad" >"$tmp/a"
grep -v '^// command:' "$tmp/scad/ring-2.scad" >"$tmp/b"
check_true "otherwise what a single run writes" cmp -s "$tmp/a" "$tmp/b"
check_exit 2 "--module with several inputs" "$scad" --module m "$tmp/sp/ellipse.txt" "$tmp/sp/ring-2.txt" -o "$tmp/scad2/"
check_exit 2 "several inputs without -o DIR/" "$scad" "$tmp/sp/ellipse.txt" "$tmp/sp/ring-2.txt"
check_exit 2 "same base name twice" "$scad" "$tmp/sp/ellipse.txt" "$tmp/in/../sp/ellipse.txt" -o "$tmp/scad3/"

begin_case "a missing input fails alone; SIGTERM stops the batch without temporaries"
check_exit 1 "a missing input among others" "$svgsmooth" --levels 2 "$tmp/in/icon-000.svg" "$tmp/nope.svg" -o "$tmp/miss/"
check_grep "nope.svg: cannot open" "$err" "named"
check_grep '^svgsmooth: 1 file written, 1 failed$' "$err" "summary"
# many slow files (about 4 s of CPU at 14 levels, so an idle machine is
# still at work after a second), TERM after a moment: the tool dies of SIGTERM, no
# temporary is left anywhere, every file present is complete
"$svgsmooth" --levels 14 -j 2 "$tmp"/in/icon-0*.svg -o "$tmp/term/" 2>"$tmp/term.err" &
pid=$!
sleep 1
kill -TERM $pid
wait $pid
rc=$?
check_true "exit status 143 (died of SIGTERM), got $rc" test $rc -eq 143
check_grep '^svgsmooth: error: stopped by SIGTERM' "$tmp/term.err" "says it was stopped"
check_true "no temporary left" test -z "$(ls -A "$tmp/term" 2>/dev/null | grep conica-tmp)"
finish
