#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/fuzz_smoke.sh BUILD_DIR - the libFuzzer targets of tests/fuzz/
# (built by `make tests` into BUILD_DIR/fuzz/bin): each replays its
# committed seed corpus and every regression input (tests/fuzz/regressions/
# NAME/, one file per past finding), then fuzzes for a few seconds
# (FUZZ_SMOKE_SECONDS, default 3). `make fuzz FUZZ_SECONDS=N` is the long run.
. "$(dirname "$0")/harness.sh"

secs=${FUZZ_SMOKE_SECONDS:-3}
fb=$build/fuzz
case $build in
*/san) san=1 ;;
*) san=0 ;;
esac

for name in curve_parse spline_parse svg_path svgsmooth svg_render scadprofile subdivide plot dxf; do
    bin=$fb/bin/fuzz_$name
    begin_case "fuzz_$name"
    if [ "$san" -eq 1 ]; then
        skip_case "the fuzzers already run under ASan+UBSan (BUILD/fuzz); not repeated in the sanitizer pass"
        continue
    fi
    if ! command -v clang >/dev/null 2>&1 && [ ! -x "$bin" ]; then
        skip_case "clang (libFuzzer) is not installed"
        continue
    fi
    check_true "fuzz_$name is built (make tests builds BUILD/fuzz/bin)" test -x "$bin"
    [ -x "$bin" ] || continue
    # Replay: every committed input once (a crash or contract violation fails).
    set -- "tests/fuzz/corpus/$name"/*
    [ -d "tests/fuzz/regressions/$name" ] && set -- "$@" "tests/fuzz/regressions/$name"/*
    files=""
    for f in "$@"; do [ -f "$f" ] && files=1; done
    check_true "fuzz_$name has seed inputs" test -n "$files"
    check "fuzz_$name replays its corpus and regression inputs" \
        "$bin" -runs=1 -timeout=30 -rss_limit_mb=2048 "$@"
    check_grep "Executed .* in [0-9]+ ms" "$err" "fuzz_$name executed the inputs"
    # A short fuzzing session from the seeds (new inputs go to a scratch dir).
    mkdir -p "$tmp/c-$name" "$tmp/a-$name"
    check "fuzz_$name fuzzes ${secs}s without a finding" \
        "$bin" -max_total_time="$secs" -timeout=20 -rss_limit_mb=2048 -max_len=16384 \
        -artifact_prefix="$tmp/a-$name/" "$tmp/c-$name" "tests/fuzz/corpus/$name"
    check_grep "^Done [0-9]+ runs in" "$err" "fuzz_$name ran to its time limit"
done
finish
