#!/bin/sh
# SPDX-License-Identifier: MIT
# `make demo` part for the Blender add-on (called by scripts/demo.sh as
# `scripts/demo-blender.sh BUILD_DIR`): in headless Blender, refine an
# octagon, a flower and a Bezier circle with Blender's Subdivide and with
# Conic Subdivide, and a mesh circle converted to a curve; draw the curve
# data as SVG, convert it to PNG.
# Outputs: BUILD/demo/blender-{mesh-to-curve,before-after}.{svg,png},
# BUILD/demo/conica-demo.blend
set -eu
build=${1:-build}
zip=$build/conica-blender.zip
out=$build/demo
if ! command -v blender >/dev/null 2>&1; then
    echo "  demo-blender: skipped: blender is not installed"
    exit 0
fi
[ -f "$zip" ] || { echo "demo-blender: error: $zip missing (make BUILD=$build blender-addon)" >&2; exit 1; }
mkdir -p "$out"
rm -f "$out/conica-demo.blend" "$out/conica-demo.blend1"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-demo-blender.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
mkdir -p "$tmp/scripts" "$tmp/config"
if ! BLENDER_USER_SCRIPTS=$tmp/scripts BLENDER_USER_CONFIG=$tmp/config CONICA_ZIP=$zip \
    CONICA_DEMO_OUT=$out blender -b --factory-startup --python-exit-code 1 \
    --python blender_addon/tools/demo_blender.py >"$tmp/log" 2>&1; then
    echo "demo-blender: error: Blender failed:" >&2
    tail -n 30 "$tmp/log" >&2
    exit 1
fi
sed -n 's/^DEMO /  /p' "$tmp/log"
for pic in blender-mesh-to-curve blender-before-after; do
    if command -v rsvg-convert >/dev/null 2>&1; then
        rsvg-convert -o "$out/$pic.png" "$out/$pic.svg"
        echo "  $out/$pic.png (and .svg)"
    else
        echo "  $out/$pic.svg (no rsvg-convert for PNG)"
    fi
done
echo "  $out/conica-demo.blend"
