#!/bin/sh
# Conica add-on in real, headless Blender: installs BUILD/conica-blender.zip
# into a temporary BLENDER_USER_SCRIPTS and runs tests/blender/test_addon.py
# in ONE Blender run (each start costs seconds). The script prints
# `PASS name` / `FAIL name: why` per check; this suite reports each as a test
# case and ends with Catch2's summary line (what scripts/run-tests.sh sums).
# Usage (from the repo root): sh tests/cli/blender.sh BUILD_DIR
set -u
build=${1:-build}
zip=$build/conica-blender.zip
blender=${BLENDER:-blender}

skip() {
    echo "SKIPPED: $1"
    echo "==============================================================================="
    echo "test cases: 1 | 0 passed | 0 failed | 1 skipped"
    exit 0
}
command -v "$blender" >/dev/null 2>&1 || skip "blender not installed (scripts/deps.sh test installs it)"
[ -f "$zip" ] || { echo "error: $zip missing: run make BUILD=$build blender-addon" >&2
    echo "test cases: 1 | 0 passed | 1 failed"; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-blender-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$tmp/scripts/addons" "$tmp/config"
log=$tmp/blender.log
BLENDER_USER_SCRIPTS=$tmp/scripts BLENDER_USER_CONFIG=$tmp/config CONICA_ZIP=$zip \
    "$blender" -b --factory-startup --python-exit-code 1 \
    --python tests/blender/test_addon.py >"$log" 2>&1
rc=$?

pass=$(grep -c '^PASS ' "$log")
fail=$(grep -c '^FAIL ' "$log")
grep -E '^(PASS|FAIL) ' "$log" | sed -n 's/^PASS /  ok   /p; s/^FAIL /  FAIL /p'
if ! grep -q '^SUMMARY ' "$log"; then
    # Blender crashed or the script died before its end: one more failure.
    echo "FAIL blender_run: Blender exited $rc before the end of the script; log tail:"
    tail -n 40 "$log"
    fail=$((fail + 1))
elif [ "$fail" -ne 0 ]; then
    echo "---- failures (full log: rerun by hand) ----"
    grep -A 12 '^FAIL ' "$log" | head -n 200
fi
total=$((pass + fail))
echo "==============================================================================="
if [ "$fail" -eq 0 ] && [ "$total" -gt 0 ]; then
    echo "All tests passed ($total assertions in $total test cases)"
    exit 0
fi
echo "test cases: $total | $pass passed | $fail failed"
exit 1
