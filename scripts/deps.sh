#!/bin/sh
# SPDX-License-Identifier: MIT
# Check that what a make target needs is there, and on Debian install the
# packages that are missing, nothing else.
#   scripts/deps.sh build   compiler, LAPACKE, libxml2, Python headers
#   scripts/deps.sh test    build + CGAL, GMP, OpenSCAD, Blender, rsvg, clang,
#                           FreeType and the DejaVu fonts (glyph outlines),
#                           Inkscape with the Python modules its inkex needs
#                           and Xvfb (the extension test), zsh (completions)
#   scripts/deps.sh demo    build + OpenSCAD, Blender, rsvg
#   scripts/deps.sh bench   build + cairo's headers (the cairo columns of
#                           bench_flatten and bench_arcs)
#   scripts/deps.sh windows build + MinGW-w64 C and Fortran cross compilers
#                           (make blender-extension-windows; test has them too)
# Prints what it installs; does nothing when everything is present.
# What is present is found by what each package provides (a command, a
# pkg-config module, a header, a Python module, a file: probe() below),
# not by asking dpkg, so a system with everything installed by other means
# passes. Where something is missing and there is no apt-get, the missing
# list is printed (with the Debian package names) and the exit status is 1.
set -eu

build="gcc g++ make pkg-config liblapacke-dev libxml2-dev python3-dev libpolyclipping-dev"
test="libcgal-dev libgmp-dev openscad blender librsvg2-bin libxml2-utils clang libclang-rt-14-dev valgrind libfreetype-dev fonts-dejavu-core groff-base mandoc inkscape python3-lxml python3-cssselect python3-numpy python3-ezdxf python3-pyclipper xvfb xauth zsh"
demo="openscad blender librsvg2-bin"
bench="libcairo2-dev"
windows="gcc-mingw-w64-x86-64 gfortran-mingw-w64-x86-64 binutils-mingw-w64-x86-64 dpkg-dev"

case "${1:-build}" in
    build) want="$build" ;;
    test) want="$build $test $windows" ;;
    demo) want="$build $demo" ;;
    bench) want="$build $bench" ;;
    windows) want="$build $windows" ;;
    *) echo "deps.sh: error: unknown target '$1' (build, test, demo, bench or windows)" >&2; exit 2 ;;
esac

# probe PKG: is what the Debian package PKG provides here? A package
# without a probe of its own is asked of dpkg (absent without dpkg).
has_cmd() { command -v "$1" >/dev/null 2>&1; }
has_pc() { has_cmd "${PKG_CONFIG:-pkg-config}" && "${PKG_CONFIG:-pkg-config}" --exists "$1" 2>/dev/null; }
has_py() { # MODULE: in the python3 on PATH or the system's (Inkscape runs that)
    for py in python3 /usr/bin/python3; do
        has_cmd "$py" && "$py" -c "import $1" >/dev/null 2>&1 && return 0
    done
    return 1
}
has_header() { # HEADER [COMPILER]: the compiler finds it
    printf '#include <%s>\n' "$1" | "${2:-${CC:-cc}}" -x "${3:-c}" -E - >/dev/null 2>&1
}
probe() {
    case $1 in
    gcc | g++ | make | pkg-config | openscad | blender | clang | valgrind | mandoc | inkscape | xauth | zsh)
        has_cmd "$1" ;;
    liblapacke-dev) has_pc lapacke || has_header lapacke.h ;;
    libxml2-dev) has_pc libxml-2.0 ;;
    python3-dev) has_pc python3 ;;
    libcgal-dev) has_header CGAL/Exact_predicates_inexact_constructions_kernel.h "${CXX:-c++}" c++ ;;
    libgmp-dev) has_header gmp.h ;;
    librsvg2-bin) has_cmd rsvg-convert ;;
    libxml2-utils) has_cmd xmllint ;;
    libclang-rt-*-dev) # the sanitizer runtimes clang links
        has_cmd clang && printf 'int main(void) { return 0; }\n' |
            clang -fsanitize=address,undefined -x c - -o /dev/null >/dev/null 2>&1 ;;
    libfreetype-dev) has_pc freetype2 ;;
    libcairo2-dev) has_pc cairo ;;
    fonts-dejavu-core) [ -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] ;;
    groff-base) has_cmd groff ;;
    python3-lxml) has_py lxml ;;
    python3-cssselect) has_py cssselect ;;
    python3-numpy) has_py numpy ;;
    python3-ezdxf) has_py ezdxf ;;
    python3-pyclipper) has_py pyclipper ;;
    libpolyclipping-dev) has_pc polyclipping || has_header polyclipping/clipper.hpp "${CXX:-c++}" c++ ;;
    xvfb) has_cmd Xvfb && has_cmd xvfb-run ;;
    *) has_cmd dpkg-query && dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed" ;;
    esac
}

missing=""
for p in $want; do
    probe "$p" && continue
    case " $missing " in *" $p "*) ;; *) missing="$missing $p" ;; esac
done
[ -z "$missing" ] && exit 0

if ! command -v apt-get >/dev/null 2>&1; then
    echo "deps.sh: error: apt-get not found; install what these Debian packages provide:$missing" >&2
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
