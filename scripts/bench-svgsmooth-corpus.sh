#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth on real icon sets, every file in each mode, measured by the
# independent checker build/tests/svgcheck (tests/svgcheck/svgcheck.c: no
# svgsmooth or libcore code): files over the tolerance, the worst ratio,
# closed-subpath starts moved, corners lost, new crossings, output points,
# and (with rsvg-convert) pixels that differ from the original at 96 px.
#
#   scripts/bench-svgsmooth-corpus.sh BUILD SET=DIR... [-n N] [-m MODES] [-P]
#
# SET=DIR: a name and a directory of *.svg (e.g. from `npm pack
# @tabler/icons` unpacked in /tmp); -n: at most N files per set, in name
# order (default all); MODES: comma list of smooth, levels3, levels8,
# flatten (--tolerance 0.01), simplify (--simplify 0.05) (default all);
# -P: no pictures (the pixels column shows -).
# Prints one row per set and mode: set mode files over worst starts
# corners-lost/corners crossings points pixels. Benchmark only (never
# asserts); the icon sets are no dependency of Conica.
set -u
build=${1:?build directory}
shift
max=0
pixels=1
modes=smooth,levels3,levels8,flatten,simplify
sets=
while [ $# -gt 0 ]; do
    case $1 in
    -n) max=$2; shift 2 ;;
    -m) modes=$2; shift 2 ;;
    -P) pixels=0; shift ;;
    *) sets="$sets $1"; shift ;;
    esac
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
have_rsvg=0
[ $pixels = 1 ] && command -v rsvg-convert >/dev/null 2>&1 && command -v python3 >/dev/null 2>&1 &&
    have_rsvg=1
printf '%-14s %-9s %6s %5s %8s %6s %12s %5s %9s %9s\n' set mode files over worst starts corners cross points pixels
for spec in $sets; do
    name=${spec%%=*}
    dir=${spec#*=}
    rm -f "$tmp"/orig*.png
    find "$dir" -name '*.svg' | LC_ALL=C sort > "$tmp/list"
    [ "$max" -gt 0 ] && head -n "$max" "$tmp/list" > "$tmp/l2" && mv "$tmp/l2" "$tmp/list"
    for mode in $(echo "$modes" | tr ',' ' '); do
        case $mode in
        smooth) opt= ; chk= ;;
        levels3) opt='--levels 3' ; chk= ;;
        levels8) opt='--levels 8' ; chk= ;;
        flatten) opt='--flatten --tolerance 0.01' ; chk='--tol 0.01 --samples-too' ;;
        simplify) opt="--simplify 0.05" ; chk="--lines-tol 0.05" ;;
        *) echo "unknown mode $mode" >&2; exit 2 ;;
        esac
        : > "$tmp/rows"
        px=0
        k=0
        while read -r f; do
            k=$((k + 1))
            # shellcheck disable=SC2086
            if ! "$build/bin/svgsmooth" $opt -o "$tmp/out.svg" "$f" 2>/dev/null; then
                echo "ratio=fail" >> "$tmp/rows"
                continue
            fi
            # shellcheck disable=SC2086
            "$build/tests/svgcheck" $chk "$f" "$tmp/out.svg" >> "$tmp/rows" 2>/dev/null ||
                echo "ratio=unpaired" >> "$tmp/rows"
            if [ $have_rsvg = 1 ]; then
                # the original's picture once per file
                [ -f "$tmp/orig$k.png" ] || rsvg-convert -w 96 -h 96 -o "$tmp/orig$k.png" "$f" 2>/dev/null
                [ -f "$tmp/orig$k.png" ] &&
                    rsvg-convert -w 96 -h 96 -o "$tmp/b.png" "$tmp/out.svg" 2>/dev/null &&
                    px=$((px + $(python3 "$(dirname "$0")/pngdiff.py" "$tmp/orig$k.png" "$tmp/b.png")))
            fi
        done < "$tmp/list"
        [ $have_rsvg = 1 ] || px=-
        awk -v set="$name" -v mode="$mode" -v px="$px" '
            { n++; split($0, kv, " "); for (i in kv) { split(kv[i], p, "="); v[p[1]] = p[2] }
              if (v["ratio"] == "fail" || v["ratio"] == "unpaired") { bad++; next }
              if (v["over"] > 0) over++; if (v["ratio"] > worst) worst = v["ratio"]
              if (v["starts"] > 0) starts++; split(v["corners"], c, "/"); lost += c[1]; corners += c[2]
              cross += v["crossings"]; pts += v["points"] }
            END { printf "%-14s %-9s %6d %5d %8.3f %6d %12s %5d %9d %9s%s\n", set, mode, n, over, worst,
                  starts, lost "/" corners, cross, pts, px, bad ? " (" bad " failed or unpaired)" : "" }' "$tmp/rows"
    done
done
