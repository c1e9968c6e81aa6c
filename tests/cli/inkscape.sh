#!/bin/sh
# SPDX-License-Identifier: MIT
# The Inkscape extension (svg_tools/inkscape/) with Debian's inkscape and its
# own inkex: the script run the way Inkscape runs it (the document as a file,
# the selection as --id, the result on stdout), and, when xvfb-run is there,
# real Inkscape running the installed extension by its action. On a document
# with three shapes and one selected, only that one changes, and exactly as
# `svgsmooth --select` changes it.
# Usage (from the repo root): sh tests/cli/inkscape.sh BUILD_DIR
. "$(dirname "$0")/harness.sh"

# absolute: Inkscape runs the script in another directory
bin=$(cd "$build/bin" 2>/dev/null && pwd) || bin=$build/bin
svgsmooth=$bin/svgsmooth
zip=$build/conica-inkscape.zip
inkex_dir=${INKEX_DIR:-/usr/share/inkscape/extensions}
# Inkscape runs extensions with the system Python (its inkex needs lxml)
py=/usr/bin/python3
[ -x "$py" ] || py=python3
script=$tmp/ext/conica/conica_smooth.py

cat >"$tmp/doc.svg" <<'SVG'
<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100" viewBox="0 0 300 100">
  <path id="path1" d="M10 10C30 0 70 0 90 10L90 90L10 90Z" fill="none" stroke="#000"/>
  <path id="path2" d="M110 50A40 40 0 0 1 190 50A40 40 0 0 1 110 50Z" fill="none" stroke="#000"/>
  <path id="path3" d="M210 10Q290 10 290 50T210 90Z" fill="none" stroke="#000"/>
</svg>
SVG

# inkex ends an aborted extension with status 251 (inkex.base.ABORT_STATUS);
# Inkscape then shows the message on stderr in a dialog.
# ink NAME ARGS...: the extension as Inkscape runs it, stdout to $tmp/NAME.svg
ink() {
    i_name=$1
    shift
    PYTHONPATH=$inkex_dir PATH=$bin:$PATH "$py" "$script" "$@" "$tmp/doc.svg" >"$tmp/$i_name.svg" 2>"$tmp/$i_name.err"
}

# dval FILE ID: the d attribute of element ID (whatever the XML layout)
dval() {
    "$py" -c 'import sys; from lxml import etree
t = etree.parse(sys.argv[1])
e = t.xpath("//*[@id=$i]", i=sys.argv[2])
print(e[0].get("d") if e else "MISSING")' "$1" "$2"
}

begin_case "inkscape: the extension unpacks from the zip"
if [ ! -d "$inkex_dir/inkex" ]; then
    skip_case "Inkscape's inkex is not installed in $inkex_dir (scripts/deps.sh test installs inkscape)"
    finish
fi
# inkex imports lxml, cssselect and numpy: without one of them every run of
# the extension fails, and real Inkscape waits on its error dialog
inkex_ok=1
PYTHONPATH=$inkex_dir "$py" -c 'import inkex' >"$tmp/inkex.err" 2>&1 || inkex_ok=0
check_true "Inkscape's inkex imports with $py (it needs lxml, cssselect, numpy: scripts/deps.sh test)" \
    test "$inkex_ok" -eq 1
[ "$inkex_ok" -eq 1 ] || cat "$tmp/inkex.err"
mkdir -p "$tmp/ext"
case "$build" in
    */san)
        # the sanitizer pass builds the binaries only (make test-san): the
        # extension comes from the source tree, svgsmooth from the build
        cp -r svg_tools/inkscape "$tmp/ext/conica" ;;
    *)
        check_true "$zip exists (make BUILD=$build inkscape-extension)" test -f "$zip"
        check "unzip" "$py" -m zipfile -e "$zip" "$tmp/ext" ;;
esac
for f in conica_smooth.inx conica_flatten.inx conica_smooth.py; do
    check_true "conica/$f in the zip" test -f "$tmp/ext/conica/$f"
done
for f in "$tmp"/ext/conica/*.inx; do
    check "$(basename "$f") is well-formed XML" "$py" -c 'import sys; from lxml import etree; etree.parse(sys.argv[1])' "$f"
done
check_grep 'needs-live-preview="true"' "$tmp/ext/conica/conica_smooth.inx" "Conic Smooth has live preview"
check_grep '<submenu name="Modify Path"/>' "$tmp/ext/conica/conica_flatten.inx" "Flatten to Tolerance is under Modify Path"

begin_case "inkscape: Conic Smooth on one selected path of three changes only it, as svgsmooth --select"
check "extension, path2 selected" ink sel --mode=smooth --method=levels --levels=4 --corner_angle=40 --id=path2
check "svgsmooth --select path2" "$svgsmooth" --levels 4 --corner-angle 40.0 --select path2 -o "$tmp/ref.svg" "$tmp/doc.svg"
check_true "the extension's document is svgsmooth's, byte for byte" cmp -s "$tmp/sel.svg" "$tmp/ref.svg"
for id in path1 path3; do
    check_true "$id unchanged" test "$(dval "$tmp/sel.svg" $id)" = "$(dval "$tmp/doc.svg" $id)"
done
check_true "path2 changed" test "$(dval "$tmp/sel.svg" path2)" != "$(dval "$tmp/doc.svg" path2)"
check_true "path2 is now a polyline (arcs smoothed into points)" sh -c "! printf '%s' '$(dval "$tmp/sel.svg" path2)' | grep -q A"

begin_case "inkscape: nothing selected smooths the whole document; tolerance mode"
check "extension, no selection" ink all --method=tolerance --tolerance=0.05 --corner_angle=30
check "svgsmooth on the document" "$svgsmooth" --tolerance 0.05 --corner-angle 30.0 -o "$tmp/ref-all.svg" "$tmp/doc.svg"
check_true "the same document" cmp -s "$tmp/all.svg" "$tmp/ref-all.svg"
for id in path1 path2 path3; do
    check_true "$id changed" test "$(dval "$tmp/all.svg" $id)" != "$(dval "$tmp/doc.svg" $id)"
done

begin_case "inkscape: Flatten to Tolerance on the selection"
check "extension, flatten path1 and path3" ink flat --mode=flatten --tolerance=0.5 --id=path1 --id=path3
check "svgsmooth --flatten" "$svgsmooth" --flatten --tolerance 0.5 --select path1,path3 -o "$tmp/ref-flat.svg" "$tmp/doc.svg"
check_true "the same document" cmp -s "$tmp/flat.svg" "$tmp/ref-flat.svg"
check_true "path2 unchanged" test "$(dval "$tmp/flat.svg" path2)" = "$(dval "$tmp/doc.svg" path2)"

begin_case "inkscape: simplify is passed only when > 0, and refused clearly by an svgsmooth without it"
# an svgsmooth from before --simplify: refuses it, does the rest
cat >"$tmp/old-svgsmooth" <<OLD
#!/bin/sh
[ "\$1" = --help ] && { "$svgsmooth" --help | grep -v -- --simplify; exit 0; }
for a in "\$@"; do
    [ "\$a" = --simplify ] && { echo "svgsmooth: usage error: unknown option '--simplify'" >&2; exit 2; }
done
exec "$svgsmooth" "\$@"
OLD
chmod +x "$tmp/old-svgsmooth"
check_exit 251 "Simplify 0.5 with an svgsmooth lacking --simplify fails" ink old --simplify=0.5 --svgsmooth="$tmp/old-svgsmooth" --id=path2
check_grep 'has no --simplify option' "$tmp/old.err" "the message says why"
check_true "no document written" test ! -s "$tmp/old.svg"
if "$svgsmooth" --help | grep -q '^ *--simplify '; then
    check "Simplify 0.5 with this svgsmooth" ink simp --simplify=0.5 --id=path2
    check "svgsmooth --simplify" "$svgsmooth" --levels 4 --corner-angle 40.0 --simplify 0.5 --select path2 -o "$tmp/ref-simp.svg" "$tmp/doc.svg"
    check_true "the same document" cmp -s "$tmp/simp.svg" "$tmp/ref-simp.svg"
else
    check "Simplify 0 never asks for --simplify" ink simp0 --simplify=0 --svgsmooth="$tmp/old-svgsmooth" --id=path2
    check_true "and smooths as before" cmp -s "$tmp/simp0.svg" "$tmp/ref.svg"
fi

begin_case "inkscape: a missing svgsmooth is named, never a traceback"
check_exit 251 "an svgsmooth path that does not exist" ink miss --svgsmooth="$tmp/nowhere/svgsmooth" --id=path2
check_grep 'svgsmooth not found at .*nowhere' "$tmp/miss.err" "the message names the path"
check_no_grep 'Traceback' "$tmp/miss.err" "no Python traceback"
mkdir -p "$tmp/emptybin"
PYTHONPATH=$inkex_dir PATH=$tmp/emptybin "$py" "$script" --id=path2 "$tmp/doc.svg" >"$tmp/nopath.svg" 2>"$tmp/nopath.err"
check_true "not on PATH: exit 251" test $? -eq 251
check_grep 'cannot find the svgsmooth program' "$tmp/nopath.err" "the message says how to fix it"
check_exit 251 "tolerance 0 is refused" ink tol0 --method=tolerance --tolerance=0
check_no_grep 'Traceback' "$tmp/tol0.err" "no Python traceback"

begin_case "inkscape: installed under PREFIX, the extension finds PREFIX/bin/svgsmooth"
mkdir -p "$tmp/prefix/bin" "$tmp/prefix/share/inkscape/extensions"
cp "$svgsmooth" "$tmp/prefix/bin/"
cp -r "$tmp/ext/conica" "$tmp/prefix/share/inkscape/extensions/"
PYTHONPATH=$inkex_dir PATH=$tmp/emptybin "$py" "$tmp/prefix/share/inkscape/extensions/conica/conica_smooth.py" \
    --levels=4 --id=path2 "$tmp/doc.svg" >"$tmp/prefixed.svg" 2>"$tmp/prefixed.err"
check_true "runs without svgsmooth on PATH" test $? -eq 0
check_true "the same result" cmp -s "$tmp/prefixed.svg" "$tmp/ref.svg"

begin_case "inkscape: real Inkscape runs the extension by its action (select-by-id, org.conica.smooth.noprefs)"
if [ "$inkex_ok" -eq 0 ]; then
    check_true "inkex imports (see the first case); not starting Inkscape to wait on its error dialog" false
elif ! command -v inkscape >/dev/null 2>&1 || ! command -v xvfb-run >/dev/null 2>&1; then
    skip_case "inkscape or xvfb-run not installed (Inkscape 1.2 offers extension actions only with its GUI; scripts/deps.sh test installs both)"
else
    # a fresh profile and the documented step: make install-inkscape
    mkdir -p "$tmp/home"
    check "make install-inkscape into a fresh HOME" env HOME="$tmp/home" XDG_CONFIG_HOME= \
        make --no-print-directory BUILD="$build" BINDIR="$bin" install-inkscape
    check_true "the extension is in ~/.config/inkscape/extensions/conica" \
        test -f "$tmp/home/.config/inkscape/extensions/conica/conica_smooth.py"
    check_grep "^$bin/svgsmooth\$" "$tmp/home/.config/inkscape/extensions/conica/svgsmooth.path" \
        "svgsmooth.path names the installed svgsmooth"
    # Inkscape runs the script with the first python3 on PATH: the system
    # one, which has lxml and cssselect; svgsmooth is not on that PATH (the
    # extension finds it through svgsmooth.path); a timeout in case a dialog waits
    HOME=$tmp/home XDG_CONFIG_HOME= PATH=/usr/bin:/bin \
        timeout 120 xvfb-run -a inkscape --with-gui --batch-process \
        --actions="select-by-id:path2;org.conica.smooth.noprefs;export-filename:$tmp/gui.svg;export-plain-svg;export-do" \
        "$tmp/doc.svg" >"$tmp/gui.log" 2>&1
    check_true "Inkscape wrote the document" test -s "$tmp/gui.svg"
    check_no_grep 'could not find action' "$tmp/gui.log" "Inkscape knows the extension's action"
    for id in path1 path3; do
        check_true "$id unchanged" test "$(dval "$tmp/gui.svg" $id)" = "$(dval "$tmp/doc.svg" $id)"
    done
    check_true "path2 as svgsmooth --select path2 (the .inx defaults: levels 4 as svgsmooth's, corner 40)" \
        test "$(dval "$tmp/gui.svg" path2)" = "$(dval "$tmp/ref.svg" path2)"

    # svgsmooth missing: the message goes to Inkscape's log, no dialog waits
    printf '%s\n' "$tmp/nowhere/svgsmooth" >"$tmp/home/.config/inkscape/extensions/conica/svgsmooth.path"
    HOME=$tmp/home XDG_CONFIG_HOME= PATH=/usr/bin:/bin \
        timeout 120 xvfb-run -a inkscape --with-gui --batch-process \
        --actions="select-by-id:path2;org.conica.smooth.noprefs;export-filename:$tmp/gui2.svg;export-plain-svg;export-do" \
        "$tmp/doc.svg" >"$tmp/gui2.log" 2>&1
    st=$?
    check_true "svgsmooth missing: Inkscape ends by itself (status $st; 124: killed by the timeout)" test "$st" -ne 124
    check_grep 'Conica: .*svgsmooth' "$tmp/gui2.log" "the message is in Inkscape's output"
    check_true "the document is written unchanged" test "$(dval "$tmp/gui2.svg" path2)" = "$(dval "$tmp/doc.svg" path2)"
fi
finish
