#!/bin/sh
# SPDX-License-Identifier: MIT
# `make bench`, DXF part (called by scripts/bench.sh with BUILD as $1):
# scadprofile beside OpenSCAD's import() on the drawings of
# tests/dxf/make_cases.py and OpenSCAD's own example DXFs (Debian's openscad
# package), measured against each drawing's exact geometry
# (bench/bench_dxf_import.py). Prints its table, asserts nothing; skipped
# with a notice when python3-ezdxf, python3-numpy or openscad is missing.
set -u
build=${1:-build}
PY=python3
[ -x /usr/bin/python3 ] && PY=/usr/bin/python3
if ! "$PY" -c 'import ezdxf, numpy' 2>/dev/null; then
    echo "bench-dxf-import: skipped: python3-ezdxf or python3-numpy is not installed"
    exit 0
fi
if ! command -v openscad >/dev/null 2>&1; then
    echo "bench-dxf-import: skipped: openscad is not installed (the import() column)"
    exit 0
fi
tmp=$(mktemp -d "${TMPDIR:-/tmp}/conica-bench-dxf.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM
"$PY" tests/dxf/make_cases.py "$tmp" || exit 1
set --
for n in repro_bulge repro_spline repro_circle slot_chain mixed_chain corner_plate ellipses \
         nurbs_knots periodic r12_polyline mirrored_ocs blocks; do
    set -- "$@" "$tmp/$n.dxf"
done
for f in /usr/share/openscad/examples/Old/example008.dxf \
         /usr/share/openscad/examples/Old/example013.dxf; do
    [ -f "$f" ] && set -- "$@" "$f"
done
"$PY" bench/bench_dxf_import.py "$build" "$@"
