#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark (run by scripts/bench.sh with the build directory): svgsmooth
# --simplify beside Paper.js simplify() at equal maximum deviation
# (bench/simplify_paper.js). Paper.js (npm `paper`) is installed under
# BUILD/paperjs for this benchmark only; it is no dependency of Conica.
set -u
build=${1:-build}
if ! command -v node >/dev/null 2>&1; then
    echo "skipped: node is not installed"
    exit 0
fi
if [ ! -f "$build/paperjs/node_modules/paper/package.json" ]; then
    if ! command -v npm >/dev/null 2>&1 ||
        ! npm install --silent --no-audit --no-fund --prefix "$build/paperjs" paper@0.12 >/dev/null 2>&1; then
        echo "skipped: npm could not install paper (Paper.js) under $build/paperjs"
        exit 0
    fi
fi
echo "Paper.js $(sed -n 's/.*"version": *"\([^"]*\)".*/\1/p' "$build/paperjs/node_modules/paper/package.json" | head -n 1)"
NODE_PATH=$build/paperjs/node_modules node bench/simplify_paper.js "$build"
