# SPDX-License-Identifier: MIT
# pixel_checks PAIRS: one check per line `LABEL MODULE.scad DOC.svg` of the
# file PAIRS, all compared in one python (tests/support/scad_pixels.py
# --batch: the module's pixels beside rsvg-convert's of its document).
# Sourced by CLI suites after tests/cli/harness.sh.
pixel_checks() {
    "$PY" tests/support/scad_pixels.py --batch "$1" >"$tmp/pixels" 2>&1
    while read -r label m f; do
        check_grep "^ok $label: " "$tmp/pixels" "$label: pixels agree ($(grep -F " $label: " "$tmp/pixels"))"
    done <"$1"
}
