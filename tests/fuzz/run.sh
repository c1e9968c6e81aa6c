#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/fuzz/run.sh FUZZ_BUILD SECONDS NAME... - run each fuzzer SECONDS
# seconds (libFuzzer -max_total_time) on its seed corpus.
#
# Seeds: tests/fuzz/corpus/NAME/ and tests/fuzz/regressions/NAME/ (committed,
# read only), plus, when ../shared/data exists, its files of the right kind
# copied at run time into a scratch directory (never into the repository).
# New inputs go to FUZZ_BUILD/corpus/NAME, crashes to FUZZ_BUILD/artifacts/NAME/.
# Exit status 1 when any fuzzer found something.
set -u
fb=$1
secs=$2
shift 2
shared=../shared/data
status=0
for name in "$@"; do
    bin=$fb/bin/fuzz_$name
    work=$fb/corpus/$name
    art=$fb/artifacts/$name
    extra=$fb/shared-seeds/$name
    mkdir -p "$work" "$art" "$extra"
    if [ -d "$shared" ]; then
        case $name in
        curve_parse|subdivide|scadprofile)
            find "$shared" -type f \( -name '*.txt' -o -name '*.obj' \) -size -64k \
                -exec cp {} "$extra/" \; 2>/dev/null ;;
        esac
        case $name in
        spline_parse|plot|scadprofile)
            find "$shared" -type f -name '*.spl' -size -64k -exec cp {} "$extra/" \; 2>/dev/null ;;
        esac
    fi
    dirs="tests/fuzz/corpus/$name"
    [ -d "tests/fuzz/regressions/$name" ] && dirs="$dirs tests/fuzz/regressions/$name"
    dirs="$dirs $extra"
    echo "== fuzz_$name: $secs s (log $fb/fuzz_$name.log)"
    # shellcheck disable=SC2086
    "$bin" -max_total_time="$secs" -timeout=20 -rss_limit_mb=2048 -max_len=65536 \
        -print_final_stats=1 -artifact_prefix="$art/" "$work" $dirs \
        >"$fb/fuzz_$name.log" 2>&1
    rc=$?
    grep -E '^#[0-9]+.*(DONE|pulse|NEW)' "$fb/fuzz_$name.log" | tail -n 1
    grep -E '^stat::number_of_executed_units' "$fb/fuzz_$name.log"
    if [ "$rc" -ne 0 ]; then
        echo "fuzz_$name: FAILED (exit $rc); artifacts in $art"
        grep -E 'ERROR|SUMMARY|contract violated' "$fb/fuzz_$name.log" | head -n 5
        status=1
    fi
done
exit $status
