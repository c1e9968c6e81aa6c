#!/bin/sh
# SPDX-License-Identifier: MIT
# The _conica extension in plain CPython (/usr/bin/python3, the 3.11 it is
# built for), outside Blender, under PYTHONMALLOC=debug so a use after free
# or a buffer overrun in the module shows up as a crash of that case. Runs
# tests/python/test_conica_ext.py against BUILD/blender/conica (make tests
# builds it as part of the add-on zip); each case the script reports
# (`PASS name` / `FAIL name: why`) becomes a test case of this suite.
# Usage (from the repo root): sh tests/cli/python_ext.sh BUILD_DIR
. "$(dirname "$0")/harness.sh"

python=${CONICA_PYTHON:-/usr/bin/python3}
ext=$build/blender/conica
log=$tmp/python.log

begin_case "python: the extension suite runs to its end"
check_true "$ext holds the built _conica (make BUILD=$build blender-addon)" \
    sh -c 'ls "$1"/_conica*.so >/dev/null 2>&1' sh "$ext"
PYTHONMALLOC=debug "$python" tests/python/test_conica_ext.py "$ext" >"$log" 2>&1
rc=$?
check_grep '^SUMMARY ' "$log" "the script (exit $rc) ran to its end"
if ! grep -q '^SUMMARY ' "$log"; then
    tail -n 40 "$log"
fi

grep -E '^(PASS|FAIL) ' "$log" >"$tmp/results"
while IFS= read -r line; do
    status=${line%% *}
    rest=${line#* }
    name=${rest%%:*}
    begin_case "python: $name"
    if [ "$status" = PASS ]; then
        check_true "$name" true
    else
        check_true "$rest" false
        awk -v n="FAIL $name:" 'index($0, n) == 1 {p = 1; next}
            /^(PASS|FAIL|SUMMARY) / {p = 0} p' "$log" | head -n 15
    fi
done <"$tmp/results"
finish
