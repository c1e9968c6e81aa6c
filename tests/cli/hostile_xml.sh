#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/hostile_xml.sh BUILD_DIR - hostile XML through both SVG-reading
# tools (svgsmooth and scadprofile): entity expansion (billion laughs),
# external entities (XXE, general and parameter), an external DTD, XInclude,
# huge attribute values and deep nesting. Each is refused (exit 1, clear
# message, nothing written) or neutralised (the file is never read: no line
# of /etc/passwd reaches the output). svgsmooth.sh already checks the
# simple XXE / 3-level laughs cases for svgsmooth; here both tools see the
# full-size attacks.
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth
scad=$build/bin/scadprofile
svgns='xmlns="http://www.w3.org/2000/svg"'
tri='<path id="t" d="M0 0L10 0L10 10Z"/>'

# both_refuse FILE PATTERN: each tool exits 1 with PATTERN, writes nothing.
both_refuse() {
    for tool in "$svgsmooth" "$scad"; do
        name=$(basename "$tool")
        rm -f "$tmp/o.out"
        check_exit 1 "$name refuses $(basename "$1")" "$tool" -o "$tmp/o.out" "$1"
        check_grep "^$name: error: .*$2" "$err" "$name names the problem: /$2/"
        check_true "$name wrote nothing" test ! -e "$tmp/o.out"
    done
}

# both_neutralise FILE: each tool succeeds and nothing of /etc/passwd leaks.
both_neutralise() {
    for tool in "$svgsmooth" "$scad"; do
        name=$(basename "$tool")
        rm -f "$tmp/o.out"
        check "$name accepts $(basename "$1") without reading the external file" \
            "$tool" -o "$tmp/o.out" "$1"
        check_true "$name wrote its output" test -s "$tmp/o.out"
        check_no_grep 'root:|/bin/(ba)?sh|nologin' "$tmp/o.out" "no /etc/passwd content in the output"
        check_no_grep 'root:|nologin' "$err" "no /etc/passwd content in the messages"
    done
}

begin_case "billion laughs: 10 entities of 10 references each"
{
    printf '<?xml version="1.0"?>\n<!DOCTYPE svg [\n<!ENTITY lol "lol">\n'
    prev=lol
    for i in 1 2 3 4 5 6 7 8 9; do
        printf '<!ENTITY lol%d "' "$i"
        for j in 1 2 3 4 5 6 7 8 9 10; do printf '&%s;' "$prev"; done
        printf '">\n'
        prev=lol$i
    done
    printf ']>\n<svg %s>%s<text>&lol9;</text></svg>\n' "$svgns" "$tri"
} >"$tmp/laughs.svg"
both_refuse "$tmp/laughs.svg" "entity 'lol1' refused: .*entity expansion"

begin_case "quadratic blowup: one big entity referenced many times"
{
    printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY big "'
    head -c 100000 /dev/zero | tr '\0' 'x'
    printf '">]>\n<svg %s>%s<text>' "$svgns" "$tri"
    i=0
    while [ $i -lt 2000 ]; do printf '&big;'; i=$((i + 1)); done
    printf '</text></svg>\n'
} >"$tmp/quadratic.svg"
both_refuse "$tmp/quadratic.svg" "entity 'big' refused"

begin_case "XXE: external general entity"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>\n<svg %s><path id="&x;" d="M0 0L10 0L10 10Z"/><text>&x;</text></svg>\n' \
    "$svgns" >"$tmp/xxe.svg"
both_refuse "$tmp/xxe.svg" "entity 'x' refused: external or parameter entity \(XXE\)"

begin_case "XXE: external parameter entity"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY %% p SYSTEM "file:///etc/passwd"> %%p;]>\n<svg %s>%s</svg>\n' \
    "$svgns" "$tri" >"$tmp/xxe-param.svg"
both_refuse "$tmp/xxe-param.svg" "entity 'p' refused: external or parameter entity \(XXE\)"

begin_case "XXE: entity fetched over the network"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY x SYSTEM "http://127.0.0.1:9/x">]>\n<svg %s>%s<text>&x;</text></svg>\n' \
    "$svgns" "$tri" >"$tmp/xxe-http.svg"
both_refuse "$tmp/xxe-http.svg" "entity 'x' refused"

begin_case "external DTD: not loaded (neutralised)"
printf '<?xml version="1.0"?>\n<!DOCTYPE svg SYSTEM "file:///etc/passwd">\n<svg %s>%s</svg>\n' \
    "$svgns" "$tri" >"$tmp/dtd.svg"
both_neutralise "$tmp/dtd.svg"

begin_case "XInclude: not processed (neutralised)"
printf '<svg %s xmlns:xi="http://www.w3.org/2001/XInclude"><xi:include href="file:///etc/passwd" parse="text"/>%s</svg>\n' \
    "$svgns" "$tri" >"$tmp/xinclude.svg"
both_neutralise "$tmp/xinclude.svg"
check "svgsmooth again" "$svgsmooth" -o "$tmp/x.svg" "$tmp/xinclude.svg"
check_grep 'xi:include href="file:///etc/passwd"' "$tmp/x.svg" "svgsmooth keeps the xi:include element as it was"

begin_case "huge attribute value (12 MB id): read under Conica's own caps, not libxml2's 10 MB"
{
    printf '<svg %s><path id="' "$svgns"
    head -c 12000000 /dev/zero | tr '\0' 'a'
    printf '" d="M0 0L10 0L10 10Z"/></svg>\n'
} >"$tmp/hugeattr.svg"
for tool in "$svgsmooth" "$scad"; do
    name=$(basename "$tool")
    check "$name reads the 12 MB attribute" "$tool" -o "$tmp/o.out" "$tmp/hugeattr.svg"
    check_true "$name wrote its output" test -s "$tmp/o.out"
done
rm -f "$tmp/hugeattr.svg"

begin_case "huge text node (10000100 bytes): read whole, nothing after it lost"
# libxml2 stopped at a node over its own 10 MB cap with wellFormed still 1;
# the tools once went on with the partial tree (svgsmooth --in-place exit 0,
# everything after the node gone). Under XML_PARSE_HUGE the node is read:
# the document size cap (--max-input-bytes) bounds it.
{
    printf '<svg %s>%s<text>' "$svgns" "$tri"
    head -c 10000100 /dev/zero | tr '\0' 'a'
    printf '</text><path id="after" d="M30 30L50 30L50 50Z"/></svg>\n'
} >"$tmp/hugetext.svg"
check "svgsmooth reads the huge text node" "$svgsmooth" -o "$tmp/o.out" "$tmp/hugetext.svg"
check_grep '<path id="after"' "$tmp/o.out" "the path after the node is kept"
check_true "the text node is kept whole" test "$(wc -c <"$tmp/o.out")" -gt 10000100
check "scadprofile reads it" "$scad" -o "$tmp/o.scad" "$tmp/hugetext.svg"
check_exit 1 "over --max-input-bytes it is refused" \
    "$svgsmooth" --max-input-bytes 10000000 -o "$tmp/o2.out" "$tmp/hugetext.svg"
check_true "nothing written" test ! -e "$tmp/o2.out"
rm -f "$tmp/hugetext.svg" "$tmp/o.out" "$tmp/o.scad"

begin_case "an error libxml2 does not count as fatal (unbound prefix): refused"
printf '<svg %s>\n<path xlink:href="#t" d="M0 0L10 0L10 10Z"/></svg>\n' "$svgns" >"$tmp/unbound.svg"
both_refuse "$tmp/unbound.svg" "unbound.svg:2: XML: namespace error \(libxml2: Namespace prefix xlink for href on path is not defined\)"

begin_case "huge path data (34 MB d, over the 32 MiB --max-path-bytes default): refused"
{
    printf '<svg %s><path d="M0 0' "$svgns"
    head -c 6800000 /dev/zero | tr '\0' 'L' | sed 's/L/ L1 1/g'
    printf 'Z"/></svg>\n'
} >"$tmp/hugepath.svg"
both_refuse "$tmp/hugepath.svg" "path data exceeds the limit of 33554432 bytes"
rm -f "$tmp/hugepath.svg"

begin_case "deep nesting: 300 and 100000 levels"
for depth in 300 100000; do
    awk -v d="$depth" -v ns="$svgns" -v tri="$tri" 'BEGIN {
        printf "<svg %s>", ns
        for (i = 0; i < d; i++) printf "<g>"
        printf "%s", tri
        for (i = 0; i < d; i++) printf "</g>"
        printf "</svg>\n" }' >"$tmp/deep$depth.svg"
    both_refuse "$tmp/deep$depth.svg" "deep$depth.svg:1: elements nested deeper than 256 \(--max-depth\)"
done
# A cap above libxml2's 256 is honoured (XML_PARSE_HUGE), and ours still holds.
for tool in "$svgsmooth" "$scad"; do
    name=$(basename "$tool")
    check "$name --max-depth 1000 reads 300 levels" "$tool" --max-depth 1000 -o "$tmp/o.out" "$tmp/deep300.svg"
    check_true "$name wrote its output" test -s "$tmp/o.out"
    rm -f "$tmp/o.out"
    check_exit 1 "$name --max-depth 50000 still refuses 100000 levels" \
        "$tool" --max-depth 50000 -o "$tmp/o.out" "$tmp/deep100000.svg"
    check_grep "^$name: error: .*deep100000.svg:1: elements nested deeper than 50000 \(--max-depth\)" "$err"
    check_true "$name wrote nothing" test ! -e "$tmp/o.out"
done

begin_case "unterminated document and binary garbage"
printf '<svg %s><path d="M0 0L10 0' "$svgns" >"$tmp/truncated.svg"
both_refuse "$tmp/truncated.svg" "XML: "
head -c 4096 /dev/urandom | tr -d '<' >"$tmp/garbage.svg"
both_refuse "$tmp/garbage.svg" "XML: |garbage\.svg"

begin_case "messages say what is wrong, not which libxml2 function saw it (issue 33)"
printf '<svg xmlns="http://www.w3.org/2000/svg"><text>&#0;</text></svg>\n' >"$tmp/charref0.svg"
both_refuse "$tmp/charref0.svg" "charref0\.svg:1: XML: a character reference to code point 0, which XML does not allow"
check_false_grep() { ! grep -q "$1" "$2"; }
check_true "no libxml2 function name (xmlParseCharRef) in the message" check_false_grep xmlParse "$err"

finish
