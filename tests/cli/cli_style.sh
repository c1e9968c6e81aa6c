#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/cli_style.sh BUILD_DIR - one command-line style for every tool
# and subcommand (docs/development.md): the same --version line with the
# library's version, usage errors as `TOOL [SUBCOMMAND]: usage error: ...`
# pointing at that command's own --help, errors as `TOOL: error: FILE:LINE:
# what`, `-` for standard input wherever a command reads a file, a
# one-line description of every subcommand in `conica --help`, and help
# texts that speak of the papers, not of internal names.
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica
subcommands="combs errors plot subdivide"

begin_case "--version: one format, the library's version"
# the library's version, from the header the tools are built against
libver=$(sed -n 's/^#define CONICA_VERSION_STRING "\(.*\)"$/\1/p' libcore/include/conica/common.h)
[ -n "$libver" ] || libver=$(sed -n 's/^Version: //p' "$build/conica.pc")
for t in conica svgsmooth scadprofile; do
    "$build/bin/$t" --version >"$tmp/$t.ver" 2>&1
    check_count 1 "^$t \\(Conica\\) $libver\$" "$tmp/$t.ver" "$t --version prints '$t (Conica) $libver'"
    check_count 1 "." "$tmp/$t.ver" "$t --version prints one line"
done

begin_case "conica --help: one line describing each subcommand"
"$conica" --help >"$tmp/help" 2>&1
for c in $subcommands; do
    check_grep "^  $c +[a-zA-Z].{10,}" "$tmp/help" "conica --help describes $c"
done

begin_case "usage errors name the subcommand and point at its own --help"
for c in $subcommands; do
    "$conica" "$c" --no-such-flag >/dev/null 2>"$tmp/$c.err"
    check_grep "^conica $c: usage error: " "$tmp/$c.err" "conica $c: the usage error names 'conica $c'"
    check_grep "'conica $c --help'" "$tmp/$c.err" "conica $c: it points at 'conica $c --help'"
    check_exit 2 "conica $c: a usage error exits 2" "$conica" "$c" --no-such-flag
done
for t in svgsmooth scadprofile; do
    "$build/bin/$t" --no-such-flag >/dev/null 2>"$tmp/$t.err"
    check_grep "^$t: usage error: " "$tmp/$t.err" "$t: the usage error names $t"
    check_grep "'$t --help'" "$tmp/$t.err" "$t: it points at '$t --help'"
done
"$conica" no-such-command >/dev/null 2>"$tmp/top.err"
check_grep "^conica: usage error: unknown command" "$tmp/top.err" "conica: an unknown command is a usage error of conica"

begin_case "every subcommand that reads a file reads - as standard input"
check "conica subdivide -" sh -c "'$conica' subdivide -k 1 - <examples/ellipse.txt >'$tmp/s.txt'"
check_true "subdivide wrote points" test -s "$tmp/s.txt"
check "conica combs -" sh -c "'$conica' combs -k 2 - <examples/ellipse.txt >'$tmp/c.svg'"
check_grep "<svg" "$tmp/c.svg" "combs wrote an SVG from stdin"
check "conica errors -" sh -c "'$conica' errors -k 2 - <examples/ellipse.txt >'$tmp/e.txt'"
check_grep "^ *2 " "$tmp/e.txt" "errors printed level 2 from stdin"
check "conica plot -" sh -c "'$conica' plot - <examples/nurbs-circle.spl >'$tmp/p.txt'"
check_true "plot wrote points" test -s "$tmp/p.txt"
check "svgsmooth -" sh -c "'$build/bin/svgsmooth' - <examples/rect-star.svg >'$tmp/r.svg'"
check_grep "<svg" "$tmp/r.svg" "svgsmooth wrote an SVG from stdin"
check "scadprofile -" sh -c "'$build/bin/scadprofile' - <examples/bracket.svg >'$tmp/b.scad'"
check_grep "module " "$tmp/b.scad" "scadprofile wrote a module from stdin"

begin_case "errors name the tool, the file and the line"
printf 'v 0 0\nv 1 zero\nv 1 1\n' >"$tmp/bad.txt"
for c in subdivide combs errors; do
    "$conica" "$c" "$tmp/bad.txt" >/dev/null 2>"$tmp/$c.bad"
    check_grep "^conica: error: $tmp/bad.txt:2: " "$tmp/$c.bad" "conica $c: 'conica: error: FILE:2: ...'"
done
printf 'degree 2\nknots 0 0 0 1 1 x\n' >"$tmp/bad.spl"
"$conica" plot "$tmp/bad.spl" >/dev/null 2>"$tmp/plot.bad"
check_grep "^conica: error: $tmp/bad.spl:2: " "$tmp/plot.bad" "conica plot: 'conica: error: FILE:2: ...'"
printf '<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M 0 0 L"/>\n</svg>\n' >"$tmp/bad.svg"
printf '<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M 0 0 L 1 1" <\n</svg>\n' >"$tmp/badxml.svg"
"$build/bin/svgsmooth" "$tmp/badxml.svg" >/dev/null 2>"$tmp/svg.bad"
check_grep "^svgsmooth: error: $tmp/badxml.svg:2: " "$tmp/svg.bad" "svgsmooth: 'svgsmooth: error: FILE:2: ...'"
"$build/bin/scadprofile" "$tmp/bad.svg" >/dev/null 2>"$tmp/scad.bad"
check_grep "^scadprofile: error: $tmp/bad.svg:2: " "$tmp/scad.bad" "scadprofile: 'scadprofile: error: FILE:2: ...'"

begin_case "help texts cite the papers, not internal names"
for c in $subcommands; do
    "$conica" "$c" --help >"$tmp/$c.help" 2>&1
    check_no_grep "[Ss]eed|REFERENCE\\.md|\\.\\./shared" "$tmp/$c.help" "conica $c --help has no internal names"
done
for t in svgsmooth scadprofile; do
    "$build/bin/$t" --help >"$tmp/$t.help" 2>&1
    check_no_grep "[Ss]eed|REFERENCE\\.md|\\.\\./shared" "$tmp/$t.help" "$t --help has no internal names"
done

finish
