#!/bin/sh
# SPDX-License-Identifier: MIT
# Print every benchmark table: BUILD is $1, the benchmark programs follow;
# module scripts scripts/bench-*.sh get the build directory.
set -u
build=${1:-build}
shift
status=0
for b in "$@"; do
    echo "== $(basename "$b")"
    "$b" || status=1
    echo
done
for s in scripts/bench-*.sh; do
    [ -f "$s" ] || continue
    echo "== $(basename "$s" .sh)"
    sh "$s" "$build" || status=1
    echo
done
exit $status
