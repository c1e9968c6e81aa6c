#!/bin/sh
# SPDX-License-Identifier: MIT
# Blender benchmark (called by scripts/bench.sh as `scripts/bench-blender.sh
# BUILD_DIR`): Conic Subdivide vs Blender's own Subdivide in one headless
# Blender run. Needs BUILD/conica-blender.zip (make bench builds it).
set -u
build=${1:-build}
zip=$build/conica-blender.zip
if ! command -v blender >/dev/null 2>&1; then
    echo "bench-blender: skipped: blender is not installed"
    exit 0
fi
if [ ! -f "$zip" ]; then
    echo "bench-blender: error: $zip missing (make BUILD=$build blender-addon)" >&2
    exit 1
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-bench-blender.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$tmp/scripts" "$tmp/config"
BLENDER_USER_SCRIPTS=$tmp/scripts BLENDER_USER_CONFIG=$tmp/config CONICA_ZIP=$zip \
    blender -b --factory-startup --python-exit-code 1 --python bench/bench_blender.py \
    >"$tmp/log" 2>&1
rc=$?
# Blender's own chatter (version banner, "Info:" lines) is left out.
grep -E '^(\||Blender|Conic Subdivide|ratio|Large curve|Surfaces)' "$tmp/log"
if [ "$rc" -ne 0 ]; then
    echo "bench-blender: error: Blender exited $rc:" >&2
    tail -n 30 "$tmp/log" >&2
fi
exit "$rc"
