#!/bin/sh
# SPDX-License-Identifier: MIT
# Install the Debian packages a make target needs, and nothing else.
#   scripts/deps.sh build   compiler, LAPACKE, libxml2, Python headers
#   scripts/deps.sh test    build + CGAL, GMP, OpenSCAD, Blender, rsvg, clang,
#                           FreeType and the DejaVu fonts (glyph outlines),
#                           Inkscape with the Python modules its inkex needs
#                           and Xvfb (the extension test)
#   scripts/deps.sh demo    build + OpenSCAD, Blender, rsvg
#   scripts/deps.sh windows build + MinGW-w64 C and Fortran cross compilers
#                           (make blender-extension-windows; test has them too)
# Prints what it installs; does nothing when everything is present.
set -eu

build="gcc g++ make pkg-config liblapacke-dev libxml2-dev python3-dev"
test="libcgal-dev libgmp-dev openscad blender librsvg2-bin libxml2-utils clang libclang-rt-14-dev valgrind libfreetype-dev fonts-dejavu-core groff-base mandoc inkscape python3-lxml python3-cssselect python3-numpy xvfb xauth"
demo="openscad blender librsvg2-bin"
windows="gcc-mingw-w64-x86-64 gfortran-mingw-w64-x86-64 binutils-mingw-w64-x86-64 dpkg-dev"

case "${1:-build}" in
    build) want="$build" ;;
    test) want="$build $test $windows" ;;
    demo) want="$build $demo" ;;
    windows) want="$build $windows" ;;
    *) echo "deps.sh: error: unknown target '$1' (build, test, demo or windows)" >&2; exit 2 ;;
esac

missing=""
for p in $want; do
    if command -v dpkg-query >/dev/null 2>&1 &&
       dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        continue
    fi
    case " $missing " in *" $p "*) ;; *) missing="$missing $p" ;; esac
done
[ -z "$missing" ] && exit 0

if ! command -v apt-get >/dev/null 2>&1; then
    echo "deps.sh: error: apt-get not found; install these packages by hand:$missing" >&2
    exit 1
fi
if [ "$(id -u)" -eq 0 ]; then sudo=""
elif command -v sudo >/dev/null 2>&1; then sudo="sudo"
else
    echo "deps.sh: error: not root and no sudo; install as root:$missing" >&2
    exit 1
fi
echo "deps.sh: installing:$missing"
$sudo apt-get update -qq
# shellcheck disable=SC2086
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $missing
