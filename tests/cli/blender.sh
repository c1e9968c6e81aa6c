#!/bin/sh
# SPDX-License-Identifier: MIT
# Conica add-on in real, headless Blender. Installs BUILD/conica-blender.zip
# (with bpy.ops.preferences.addon_install, as a user would) into a temporary
# BLENDER_USER_SCRIPTS and runs tests/blender/test_addon.py in ONE Blender run
# (each start costs seconds). The script prints `PASS name` or
# `FAIL name: why` per check; each becomes a test case of this suite.
# Usage (from the repo root): sh tests/cli/blender.sh BUILD_DIR
. "$(dirname "$0")/harness.sh"

zip=$build/conica-blender.zip
blender=${BLENDER:-blender}
log=$tmp/blender.log

so=$build/blender/conica/_conica.abi3.so
abi=tests/blender/stable_abi.txt

# The stable ABI is what lets one binary load in every Python from 3.11 on:
# the module is compiled with -DPy_LIMITED_API=0x030B0000, and here every
# Py* symbol it imports must be in CPython 3.11's stable ABI list. A symbol
# outside it (a non-limited call, a private helper) would load in one
# CPython and fail with "undefined symbol" in the next.
# abi_outside LIST: the Py* symbols the .so imports that LIST lacks.
abi_outside() {
    nm -D --undefined-only "$so" | awk '{print $NF}' | sed 's/@.*//' |
        grep -E '^_?Py' | sort -u >"$tmp/imports"
    grep -v '^#' "$1" | sort -u >"$tmp/abi"
    comm -23 "$tmp/imports" "$tmp/abi"
}
begin_case "blender: _conica.abi3.so imports only stable-ABI symbols"
if ! command -v nm >/dev/null 2>&1; then
    skip_case "nm (binutils) is not installed"
else
    check_true "$so exists (make BUILD=$build blender-addon)" test -f "$so"
    abi_outside "$abi" >"$tmp/outside"
    check_true "symbols outside the stable ABI: $(tr '\n' ' ' <"$tmp/outside")" \
        test ! -s "$tmp/outside"
    check_true "it imports Py* symbols at all ($(wc -l <"$tmp/imports") of them)" \
        test -s "$tmp/imports"
    check_true "it uses the buffer protocol, the 3.11 part of the stable ABI" \
        grep -qx PyObject_GetBuffer "$tmp/imports"
    # the check can fail: without PyObject_GetBuffer in the list it says so
    grep -vx PyObject_GetBuffer "$abi" >"$tmp/abi-3.10"
    check_true "a list without PyObject_GetBuffer is caught" \
        sh -c 'test "$1" = PyObject_GetBuffer' sh "$(abi_outside "$tmp/abi-3.10")"
fi

# The zip is a Blender 4.2+ extension and a 3.x legacy add-on at once:
# tests/blender/check_manifest.py reads it against the extension rules
# (no Blender needed); each rule is a case. A zip with a broken manifest
# must fail those rules.
begin_case "blender: the manifest checker runs to its end"
python=${CONICA_PYTHON:-/usr/bin/python3}
"$python" tests/blender/check_manifest.py "$zip" >"$tmp/manifest.log" 2>&1
check_grep '^SUMMARY ' "$tmp/manifest.log" "check_manifest.py ran to its end"
grep -E '^(PASS|FAIL) ' "$tmp/manifest.log" | while IFS= read -r line; do
    printf '%s\n' "$line"
done >"$tmp/manifest.results"
while IFS= read -r line; do
    rest=${line#* }
    name=${rest%%:*}
    begin_case "blender: manifest: $name"
    check_true "$rest" test "${line%% *}" = PASS
done <"$tmp/manifest.results"
begin_case "blender: manifest: a broken manifest is refused"
mkdir -p "$tmp/bad/conica"
(cd "$tmp/bad" && "$python" -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1]); z.extractall("."); z.close()' "$(cd "$OLDPWD" && pwd)/$zip")
sed -e 's/^tagline = .*/tagline = "Subdivides curves so that circles stay round, and much more besides."/' \
    -e '/^maintainer/d' -e 's/^tags = .*/tags = ["Curves"]/' \
    "$tmp/bad/conica/blender_manifest.toml" >"$tmp/bad/m" && mv "$tmp/bad/m" "$tmp/bad/conica/blender_manifest.toml"
(cd "$tmp/bad" && "$python" -c 'import sys, zipfile, os
z = zipfile.ZipFile("bad.zip", "w")
[z.write(os.path.join("conica", f)) for f in sorted(os.listdir("conica"))]
z.close()')
"$python" tests/blender/check_manifest.py "$tmp/bad/bad.zip" >"$tmp/bad.log" 2>&1
check_grep '^FAIL manifest_tagline: .*characters, at most 64' "$tmp/bad.log" "a long tagline ending in '.' fails"
check_grep '^FAIL manifest_required_fields: missing: maintainer' "$tmp/bad.log" "a missing maintainer fails"
check_grep "^FAIL manifest_tags: unknown tags \['Curves'\]" "$tmp/bad.log" "an unknown tag fails"

# The Windows x64 zip (make blender-extension-windows, cross-compiled with
# MinGW-w64): its _conica.pyd may import python3.dll (the stable ABI) and
# Windows' own DLLs only, never python311.dll, a MinGW runtime DLL
# (libgfortran, libwinpthread, libgcc_s) or LAPACK, and export
# PyInit__conica only; its manifest passes the same rules for windows-x64.
winzip=$build/conica-blender-windows-x64.zip
# pe_foreign DLLS: the DLL names of the list that are not allowed
pe_foreign() {
    grep -viE '^(python3|kernel32|msvcrt|ucrtbase|advapi32|api-ms-win-[a-z0-9-]+)\.dll$' "$1"
}
begin_case "blender: windows: the .pyd imports python3.dll and Windows' DLLs only"
objdump_w=x86_64-w64-mingw32-objdump
if [ ! -f "$winzip" ]; then
    skip_case "$winzip not built (make blender-extension-windows; scripts/deps.sh windows)"
elif ! command -v "$objdump_w" >/dev/null 2>&1; then
    skip_case "$objdump_w (binutils-mingw-w64-x86-64) is not installed"
else
    mkdir -p "$tmp/win"
    "$python" -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1]); open(sys.argv[2], "wb").write(z.read("conica/_conica.pyd"))' \
        "$winzip" "$tmp/win/_conica.pyd"
    "$objdump_w" -p "$tmp/win/_conica.pyd" >"$tmp/win/pe"
    awk '/DLL Name:/ {print $3}' "$tmp/win/pe" >"$tmp/win/dlls"
    check_true "it imports python3.dll ($(tr '\n' ' ' <"$tmp/win/dlls"))" \
        grep -qx python3.dll "$tmp/win/dlls"
    check_true "DLLs beyond python3.dll and Windows': $(pe_foreign "$tmp/win/dlls" | tr '\n' ' ')" \
        sh -c '! grep -viqE "^(python3|kernel32|msvcrt|ucrtbase|advapi32|api-ms-win-[a-z0-9-]+)\.dll$" "$1"' \
        sh "$tmp/win/dlls"
    # the export name table: "[   0] PyInit__conica"
    sed -n '/Export Name Pointer\|\[Ordinal\/Name Pointer\] Table/,/^$/p' "$tmp/win/pe" |
        awk '/^\t\[ *[0-9]+\]/ {print $NF}' >"$tmp/win/exports"
    check_true "exports: $(tr '\n' ' ' <"$tmp/win/exports")" \
        test "$(cat "$tmp/win/exports")" = PyInit__conica
    # the check can fail: a runtime DLL in the list is caught
    { cat "$tmp/win/dlls"; echo libgfortran-5.dll; } >"$tmp/win/dlls-bad"
    check_true "a libgfortran-5.dll import is caught" \
        test "$(pe_foreign "$tmp/win/dlls-bad")" = libgfortran-5.dll
fi
if [ -f "$winzip" ]; then
    "$python" tests/blender/check_manifest.py "$winzip" >"$tmp/winman.log" 2>&1
    begin_case "blender: windows manifest: the checker runs to its end"
    check_grep '^SUMMARY ' "$tmp/winman.log" "check_manifest.py ran to its end"
    grep -E '^(PASS|FAIL) ' "$tmp/winman.log" >"$tmp/winman.results"
    while IFS= read -r line; do
        rest=${line#* }
        begin_case "blender: windows manifest: ${rest%%:*}"
        check_true "$rest" test "${line%% *}" = PASS
    done <"$tmp/winman.results"
    begin_case "blender: windows manifest: platforms = [\"windows-x64\"]"
    "$python" -c 'import sys, zipfile, tomllib
z = zipfile.ZipFile(sys.argv[1])
m = tomllib.loads(z.read("conica/blender_manifest.toml").decode())
sys.exit(m["platforms"] != ["windows-x64"])' "$winzip"
    check_true "the manifest lists windows-x64 only" test $? -eq 0
fi

begin_case "blender: the add-on suite runs to its end"
if ! command -v "$blender" >/dev/null 2>&1; then
    skip_case "blender is not installed (scripts/deps.sh test installs it)"
    finish
fi
check_true "$zip exists (make BUILD=$build blender-addon)" test -f "$zip"
mkdir -p "$tmp/scripts" "$tmp/config"
BLENDER_USER_SCRIPTS=$tmp/scripts BLENDER_USER_CONFIG=$tmp/config CONICA_ZIP=$zip \
    "$blender" -b --factory-startup --python-exit-code 1 \
    --python tests/blender/test_addon.py >"$log" 2>&1
rc=$?
# Without the SUMMARY line Blender crashed or the script died early.
check_grep '^SUMMARY ' "$log" "Blender (exit $rc) ran the script to its end"
if ! grep -q '^SUMMARY ' "$log"; then
    tail -n 40 "$log"
fi

# The operators' warnings go through Blender's report system (self.report),
# which prints them in background mode: the degenerate and non-planar cases
# of the script must show up there, naming object and spline.
# (Not when CONICA_CASES selects some test functions only.)
if [ -z "${CONICA_CASES:-}" ]; then
begin_case "blender: warnings reach Blender's reports"
check_grep '^Warning: mixed, spline 3: spline is not planar' "$log" \
    "the non-planar spline of 'mixed' is reported as a warning"
check_grep '^Warning: twisted, spline 0: spline is not planar' "$log" \
    "the lone non-planar spline is reported as a warning"
check_grep '^Warning: keyed: has shape keys' "$log" \
    "a curve with shape keys is reported as a warning"
fi

# Esc in a real window: the modal run of job.py under Xvfb, an Esc press
# sent through Blender's event queue (--enable-event-simulate); a second
# Blender run, since the first one has no window.
if [ -z "${CONICA_CASES:-}" ]; then
begin_case "blender: Esc in a window: the script runs to its end"
if ! command -v xvfb-run >/dev/null 2>&1; then
    skip_case "xvfb-run (xvfb) is not installed"
else
    mkdir -p "$tmp/wscripts" "$tmp/wconfig"
    BLENDER_USER_SCRIPTS=$tmp/wscripts BLENDER_USER_CONFIG=$tmp/wconfig CONICA_ZIP=$zip \
        xvfb-run -a "$blender" --factory-startup --enable-event-simulate \
        --python tests/blender/test_escape_window.py >"$tmp/window.log" 2>&1
    check_grep '^SUMMARY ' "$tmp/window.log" "Blender under Xvfb ran the script to its end"
    if ! grep -q '^SUMMARY ' "$tmp/window.log"; then
        tail -n 20 "$tmp/window.log"
    fi
    grep -E '^(PASS|FAIL) ' "$tmp/window.log" >>"$log"
fi
fi

# One case per check the scripts reported.
grep -E '^(PASS|FAIL) ' "$log" >"$tmp/results"
while IFS= read -r line; do
    status=${line%% *}
    rest=${line#* }
    name=${rest%%:*}
    begin_case "blender: $name"
    if [ "$status" = PASS ]; then
        check_true "$name" true
    else
        check_true "$rest" false
        # the traceback or detail lines that follow the FAIL line
        awk -v n="FAIL $name:" 'index($0, n) == 1 {p = 1; next}
            /^(PASS|FAIL|SUMMARY) / {p = 0} p' "$log" | head -n 15
    fi
done <"$tmp/results"
finish
