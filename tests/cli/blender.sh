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
begin_case "blender: warnings reach Blender's reports"
check_grep '^Warning: mixed, spline 3: spline is not planar' "$log" \
    "the non-planar spline of 'mixed' is reported as a warning"
check_grep '^Warning: twisted, spline 0: spline is not planar' "$log" \
    "the lone non-planar spline is reported as a warning"
check_grep '^Warning: keyed: has shape keys' "$log" \
    "a curve with shape keys is reported as a warning"

# One case per check the script reported.
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
