#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# LAPACK(E) for the Windows build of the Blender add-on, from Debian's own
# lapack source package, cross-compiled with Debian's MinGW-w64 toolchain
# (gcc-mingw-w64-x86-64, gfortran-mingw-w64-x86-64) into one static archive.
#
#   blender_addon/tools/windows-lapack.sh SRC OUT
#
# SRC: the unpacked source package (blender_addon/tools/debian-source.sh
# fetches it); OUT: a directory that receives liblapacke.a and the LAPACKE
# headers (include/, with the lapacke_mangling.h a LAPACK build makes). Only what libconica calls is compiled: the LAPACKE
# entry points libcore uses (grep LAPACKE_ libcore/src: LAPACKE_dgesvd_work)
# and, file by file, every LAPACK and BLAS routine they reach (the
# undefined symbols of what is compiled so far, until none is left but the
# Fortran runtime's, which comes from libgfortran.a at link time). That is
# some 60 files of the 2000, a minute instead of a quarter of an hour.
set -eu
src=$1
out=$2
cross=${MINGW_PREFIX:-x86_64-w64-mingw32}
cc="$cross-gcc-win32"
fc="$cross-gfortran-win32"
nm="$cross-nm"
ar="$cross-ar"
mkdir -p "$out/obj" "$out/include"
cp "$src"/LAPACKE/include/*.h "$out/include/"
cp "$src/LAPACKE/include/lapacke_mangling_with_flags.h.in" "$out/include/lapacke_mangling.h"

entries=$(grep -oh 'LAPACKE_[a-z0-9_]*' libcore/src/*.c | sort -u)
[ -n "$entries" ] || { echo "windows-lapack: libcore calls no LAPACKE_ function" >&2; exit 1; }

# where: the source file that defines symbol $1 (C for LAPACKE_*, Fortran
# for name_), or nothing (the Fortran runtime, the C library)
where() {
    case $1 in
        LAPACKE_*)
            for d in src utils; do
                f=$src/LAPACKE/$d/$(echo "$1" | tr 'A-Z' 'a-z').c
                [ -f "$f" ] && { echo "$f"; return; }
            done ;;
        *_)
            name=${1%_}
            for d in SRC BLAS/SRC INSTALL; do
                for f in "$src/$d/$name.f" "$src/$d/$name.f90"; do
                    [ -f "$f" ] && { echo "$f"; return; }
                done
            done ;;
    esac
    return 0
}

compile() {
    o=$out/obj/$(basename "$1").o
    [ -f "$o" ] && return 0
    case $1 in
        *.c) $cc -O2 -I"$out/include" -DHAVE_LAPACK_CONFIG_H -c "$1" -o "$o" ;;
        *.f|*.f90|*.F90) $fc -O2 -frecursive -J"$out/mod" -c "$1" -o "$o" ;;
    esac
}

# the Fortran 90 modules that LAPACK 3.10+'s .f90 routines use, first
mkdir -p "$out/mod"
compile "$src/SRC/la_constants.f90"
compile "$src/SRC/la_xisnan.F90"

todo=$entries
while [ -n "$todo" ]; do
    for sym in $todo; do
        f=$(where "$sym")
        [ -n "$f" ] && compile "$f"
    done
    # every symbol the objects need that none of them defines yet
    $nm "$out"/obj/*.o | awk '$1 == "U" {print $2}' | sort -u >"$out/undef"
    $nm "$out"/obj/*.o | awk 'NF == 3 && $2 ~ /[TDRB]/ {print $3}' | sort -u >"$out/def"
    todo=""
    for sym in $(comm -23 "$out/undef" "$out/def"); do
        f=$(where "$sym")
        [ -n "$f" ] && [ ! -f "$out/obj/$(basename "$f").o" ] && todo="$todo $sym"
    done
done
rm -f "$out/liblapacke.a"
$ar rcs "$out/liblapacke.a" "$out"/obj/*.o
echo "windows-lapack: $(ls "$out"/obj | wc -l) files compiled into $out/liblapacke.a"
