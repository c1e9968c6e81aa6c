#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/encodings.sh BUILD_DIR - svgsmooth writes a document back in
# the encoding it was read in, with its declaration and byte-order mark,
# byte for byte outside the rewritten values: for UTF-8, UTF-16LE and
# UTF-16BE with and without a byte-order mark, ISO-8859-1 and EBCDIC
# (IBM037), smoothing and flattening, -o and --in-place. The reference is
# the same document in UTF-8: its output converted to the encoding (iconv)
# must equal the encoded document's output exactly. Caps count the
# document's characters, not its bytes: a UTF-16 document with 40 000
# attributes on one element is refused like its UTF-8 twin.
set -u
. "$(dirname "$0")/harness.sh"
svgsmooth=$build/bin/svgsmooth

if ! command -v iconv >/dev/null 2>&1; then
    echo "SKIP: iconv is not installed"
    finish
fi
xmllint_ok() {
    if command -v xmllint >/dev/null 2>&1; then xmllint --noout "$1"; else true; fi
}

# The UTF-8 original: a curve to smooth, a rectangle to convert, text
# outside ASCII (a comment, an attribute, character data: all of it in
# Latin-1, which IBM037 holds too) that must come back unchanged, CRLF
# line ends in one place.
mk_doc() { # ENCNAME (the declaration's) -> stdout, UTF-8
    printf '<?xml version="1.0" encoding="%s"?>\n' "$1"
    printf '<!-- caf\303\251 -->\n'
    printf '<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">\r\n'
    printf '  <title>Gr\303\274\303\237e</title>\n'
    printf '  <path id="c\303\251" d="M10 10C40 0 60 0 90 10S90 60 50 90Z" fill="none"/>\n'
    printf '  <rect x="5" y="5" width="20" height="10"/>\n'
    printf '</svg>\n'
}

# case NAME ICONV-NAME DECLARED BOM-HEX: BOM-HEX is printed before the
# iconv output (empty for none)
run_enc() {
    name=$1 to=$2 declared=$3 bom=$4
    begin_case "encoding $name: smoothed and flattened, written back in $name"
    mk_doc UTF-8 >"$tmp/$name.u8.svg"
    mk_doc "$declared" >"$tmp/$name.decl.svg"
    { printf "$bom"; iconv -f UTF-8 -t "$to" "$tmp/$name.decl.svg"; } >"$tmp/$name.svg"
    for mode in smooth flatten; do
        case $mode in
        smooth) flags="--levels 3" ;;
        flatten) flags="--flatten --tolerance 0.05" ;;
        esac
        # shellcheck disable=SC2086
        check "$name $mode: the UTF-8 twin" "$svgsmooth" $flags "$tmp/$name.u8.svg" -o "$tmp/$name.u8.$mode.out"
        # shellcheck disable=SC2086
        check "$name $mode: the $name document" "$svgsmooth" $flags "$tmp/$name.svg" -o "$tmp/$name.$mode.out"
        # the twin declares UTF-8 (the only encoding its bytes are in)
        { printf "$bom"; sed "1s/encoding=\"UTF-8\"/encoding=\"$declared\"/" "$tmp/$name.u8.$mode.out" |
            iconv -f UTF-8 -t "$to"; } >"$tmp/$name.$mode.want"
        check_true "$name $mode: byte for byte the UTF-8 twin's output in $name (declaration and mark kept)" \
            cmp "$tmp/$name.$mode.want" "$tmp/$name.$mode.out"
        check_true "$name $mode: well-formed for libxml2 (xmllint)" xmllint_ok "$tmp/$name.$mode.out"
        check_true "$name $mode: the path was rewritten" sh -c \
            '! cmp -s "$1" "$2"' sh "$tmp/$name.svg" "$tmp/$name.$mode.out"
        cp "$tmp/$name.svg" "$tmp/$name.ip.svg"
        # shellcheck disable=SC2086
        check "$name $mode --in-place" "$svgsmooth" $flags --in-place "$tmp/$name.ip.svg"
        check_true "$name $mode --in-place: the same bytes as -o" cmp "$tmp/$name.$mode.out" "$tmp/$name.ip.svg"
    done
}

run_enc UTF-8 UTF-8 UTF-8 ''
run_enc UTF-8-BOM UTF-8 UTF-8 '\357\273\277'
run_enc UTF-16LE UTF-16LE UTF-16LE ''
run_enc UTF-16BE UTF-16BE UTF-16BE ''
run_enc UTF-16LE-BOM UTF-16LE UTF-16 '\377\376'
run_enc UTF-16BE-BOM UTF-16BE UTF-16 '\376\377'
run_enc ISO-8859-1 ISO-8859-1 ISO-8859-1 ''
run_enc IBM037 IBM037 IBM037 ''

begin_case "encodings: the reproduction of the issue (UTF-16LE, no BOM, --in-place)"
printf '<?xml version="1.0" encoding="UTF-16LE"?>\n<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 10Z"/></svg>\n' |
    iconv -f UTF-8 -t UTF-16LE >"$tmp/u.svg"
check "svgsmooth --in-place u.svg" "$svgsmooth" --in-place "$tmp/u.svg"
check_true "still readable by libxml2" xmllint_ok "$tmp/u.svg"
check_true "an even byte count (whole UTF-16 code units)" sh -c 'test $(( $(wc -c <"$1") % 2 )) -eq 0' sh "$tmp/u.svg"
check_true "still UTF-16LE with its declaration" sh -c \
    'iconv -f UTF-16LE -t UTF-8 "$1" | head -n 1 | grep -q "encoding=\"UTF-16LE\""' sh "$tmp/u.svg"

begin_case "encodings: an encoding iconv cannot convert is refused before anything is written"
printf '<?xml version="1.0" encoding="X-NO-SUCH-ENCODING"?>\n<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 10Z"/></svg>\n' >"$tmp/bad.svg"
cp "$tmp/bad.svg" "$tmp/bad.orig"
check_exit 1 "unknown encoding, --in-place" "$svgsmooth" --in-place "$tmp/bad.svg"
check_grep "bad.svg: the document's encoding 'X-NO-SUCH-ENCODING' is not supported" "$err"
check_true "the input is untouched" cmp "$tmp/bad.orig" "$tmp/bad.svg"
check_true "no temporary left" sh -c 'test -z "$(ls -A "$1" | grep conica-tmp)"' sh "$tmp"
printf '<?xml version="1.0" encoding="ISO-8859-1"?>\n<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 10Z"/></svg>\n' |
    iconv -f UTF-8 -t UTF-16LE | head -c 101 >"$tmp/odd.svg"
check_exit 1 "a UTF-16 document cut inside a character" "$svgsmooth" "$tmp/odd.svg" -o "$tmp/odd.out"
check_true "nothing written" test ! -e "$tmp/odd.out"

begin_case "encodings: the attribute cap counts a UTF-16 document's attributes"
python3 - "$tmp" <<'EOF'
import sys
d = sys.argv[1]
attrs = " ".join('a%d="1"' % i for i in range(40000))
doc = '<?xml version="1.0" encoding="UTF-16"?>\n<svg xmlns="http://www.w3.org/2000/svg"><path %s d="M0 0L1 1"/></svg>\n' % attrs
open(d + "/many16.svg", "wb").write(doc.encode("utf-16"))
open(d + "/many8.svg", "wb").write(doc.replace("UTF-16", "UTF-8").encode("utf-8"))
EOF
for w in 8 16; do
    check_exit 1 "UTF-$w, 40 000 attributes: refused" timeout 20 "$svgsmooth" "$tmp/many$w.svg" -o "$tmp/many$w.out"
    check_grep "many$w.svg:2: element <path> has more than 256 attributes \(--max-attributes\)" "$err"
    check_true "UTF-$w: nothing written" test ! -e "$tmp/many$w.out"
done

finish
