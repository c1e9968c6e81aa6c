#!/bin/sh
# SPDX-License-Identifier: MIT
# svgsmooth on real icon sets, every file in each mode, measured by the
# independent checker build/tests/svgcheck (tests/svgcheck/svgcheck.c: no
# svgsmooth or libcore code): files over the tolerance, the worst ratio,
# closed-subpath starts moved, corners lost, new crossings (between
# subpaths of an element and within one), failures and warnings, output
# points, and (with rsvg-convert) pixels that differ from the original at
# 96 px.
#
#   scripts/bench-svgsmooth-corpus.sh BUILD SET=DIR... [-n N] [-e K] [-m MODES] [-P] [-k KEEP]
#
# SET=DIR: a name and a directory of *.svg, searched recursively (e.g. from
# `npm pack @tabler/icons` unpacked in /tmp); SET=glyphs: DejaVu's glyphs
# written by build/tests/glyphset (567 files, fonts-dejavu-core). -n: at
# most N files per set, in name order (default all); -e K: every K-th file
# of that order (a stratified sample; default 1). MODES: comma list of
# smooth, levels3, levels8, flatten (--tolerance 0.01), simplify
# (--simplify 0.05) (default all); -P: no pictures (the pixels column shows
# -); -k KEEP: keep each mode's per-file rows as KEEP/SET.MODE.rows (the
# worst files: sort them on ratio=).
# Prints one row per set and mode: set mode files over worst starts
# corners-lost/corners crossings self-crossings failed warned points
# pixels. Each set and mode is one svgsmooth call (-j 1) and one svgcheck
# --list call. Benchmark only (never asserts); the icon sets are no
# dependency of Conica.
set -u
build=$(cd "${1:?build directory}" && pwd)
shift
max=0
every=1
pixels=1
keep=
modes=smooth,levels3,levels8,flatten,simplify
sets=
while [ $# -gt 0 ]; do
    case $1 in
    -n) max=$2; shift 2 ;;
    -e) every=$2; shift 2 ;;
    -m) modes=$2; shift 2 ;;
    -k) keep=$2; shift 2 ;;
    -P) pixels=0; shift ;;
    *) sets="$sets $1"; shift ;;
    esac
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
have_rsvg=0
[ $pixels = 1 ] && command -v rsvg-convert >/dev/null 2>&1 && command -v python3 >/dev/null 2>&1 &&
    have_rsvg=1
printf '%-12s %-9s %6s %5s %8s %6s %13s %5s %5s %5s %5s %9s %9s\n' set mode files over worst \
    starts corners cross self fail warn points pixels
for spec in $sets; do
    name=${spec%%=*}
    dir=${spec#*=}
    rm -rf "$tmp/in" "$tmp"/orig*.png
    mkdir "$tmp/in"
    if [ "$dir" = glyphs ]; then
        mkdir -p "$tmp/glyphs"
        "$build/tests/glyphset" "$tmp/glyphs" >/dev/null || echo "glyphs: build/tests/glyphset failed" >&2
        dir=$tmp/glyphs
    fi
    # the files, in name order, sampled; each linked under a name unique in
    # the set (sub/dir/x.svg -> sub_dir_x.svg) so that one svgsmooth call
    # writes them all into one directory
    find "$dir" -name '*.svg' | LC_ALL=C sort |
        awk -v e="$every" -v n="$max" '(NR - 1) % e == 0 && (n == 0 || k++ < n)' > "$tmp/list"
    while read -r f; do
        rel=${f#"$dir"/}
        ln -s "$f" "$tmp/in/$(printf '%s' "$rel" | tr '/' '_')"
    done < "$tmp/list"
    ls "$tmp/in" > "$tmp/names"
    for mode in $(echo "$modes" | tr ',' ' '); do
        case $mode in
        smooth) opt= ; chk= ;;
        levels3) opt='--levels 3' ; chk= ;;
        levels8) opt='--levels 8' ; chk= ;;
        flatten) opt='--flatten --tolerance 0.01' ; chk='--tol 0.01 --samples-too' ;;
        simplify) opt="--simplify 0.05" ; chk="--lines-tol 0.05" ;;
        *) echo "unknown mode $mode" >&2; exit 2 ;;
        esac
        rm -rf "$tmp/out"
        mkdir "$tmp/out"
        # shellcheck disable=SC2086
        (cd "$tmp/in" && xargs "$build/bin/svgsmooth" $opt -q -j 1 -o "$tmp/out/" \
            < "$tmp/names") 2> "$tmp/err"
        warned=$(grep -c 'warning' "$tmp/err")
        sed "s|.*|$tmp/in/&	$tmp/out/&|" "$tmp/names" > "$tmp/pairs"
        # shellcheck disable=SC2086
        "$build/tests/svgcheck" $chk --list "$tmp/pairs" > "$tmp/rows" 2>/dev/null
        [ -n "$keep" ] && sed "s|^$tmp/in/||" "$tmp/rows" > "$keep/$name.$mode.rows"
        px=-
        if [ $have_rsvg = 1 ]; then
            px=0
            k=0
            while read -r f; do
                k=$((k + 1))
                # the original's picture once per file
                [ -f "$tmp/orig$k.png" ] || rsvg-convert -w 96 -h 96 -o "$tmp/orig$k.png" "$tmp/in/$f" 2>/dev/null
                [ -f "$tmp/orig$k.png" ] && [ -f "$tmp/out/$f" ] &&
                    rsvg-convert -w 96 -h 96 -o "$tmp/b.png" "$tmp/out/$f" 2>/dev/null &&
                    px=$((px + $(python3 "$(dirname "$0")/pngdiff.py" "$tmp/orig$k.png" "$tmp/b.png")))
            done < "$tmp/names"
        fi
        awk -F '\t' -v set="$name" -v mode="$mode" -v px="$px" -v warned="$warned" '
            { n++; delete v; split($2, kv, " "); for (i in kv) { split(kv[i], p, "="); v[p[1]] = p[2] }
              if (!("ratio" in v)) { bad++; next }
              if (v["over"] > 0) over++; if (v["ratio"] > worst) worst = v["ratio"]
              if (v["starts"] > 0) starts++; split(v["corners"], c, "/"); lost += c[1]; corners += c[2]
              cross += v["crossings"]; self += v["self"]; pts += v["points"] }
            END { printf "%-12s %-9s %6d %5d %8.3f %6d %13s %5d %5d %5d %5d %9d %9s\n", set, mode, n,
                  over, worst, starts, lost "/" corners, cross, self, bad, warned, pts, px }' "$tmp/rows"
    done
done
