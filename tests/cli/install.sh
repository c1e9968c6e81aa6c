# SPDX-License-Identifier: MIT
# `make install` into a staging DESTDIR, then an outside program built only
# with `pkg-config conica` (tests/install/consumer.c), linked both against the
# shared library (run through the installed soname) and statically.
. "$(dirname "$0")/harness.sh"

case "$build" in
*/san) begin_case "install"; skip_case "install is checked by the normal build"; finish ;;
esac

dest=$tmp/stage
prefix=/opt/conica
begin_case "make install stages headers, libraries, tools and conica.pc"
check "make install" make --no-print-directory BUILD="$build" PREFIX="$prefix" DESTDIR="$dest" install
for f in include/conica/common.h include/conica/curve.h include/conica/subdiv.h \
         lib/libconica.a lib/libconica.so lib/pkgconfig/conica.pc bin/conica; do
    check "installed $f" test -e "$dest$prefix/$f"
done
check_grep "^prefix=$prefix\$" "$dest$prefix/lib/pkgconfig/conica.pc"

begin_case "an outside program builds and runs against the installed library"
export PKG_CONFIG_PATH="$dest$prefix/lib/pkgconfig"
export PKG_CONFIG_SYSROOT_DIR="$dest"
check "pkg-config knows conica" pkg-config --exists conica
cflags=$(pkg-config --cflags conica)
libs=$(pkg-config --libs conica)
check "compile and link (shared)" ${CC:-cc} -std=c11 -Wall -Werror $cflags \
    tests/install/consumer.c -o "$tmp/consumer" $libs -lm
check "run (shared)" env LD_LIBRARY_PATH="$dest$prefix/lib" "$tmp/consumer"
check_grep "max radial error" "$out"
check "only the installed library is used" sh -c \
    "LD_LIBRARY_PATH='$dest$prefix/lib' ldd '$tmp/consumer' | grep -q '$dest$prefix/lib/libconica.so'"
slibs=$(pkg-config --static --libs conica)
check "compile and link (static)" ${CC:-cc} -std=c11 -Wall -Werror $cflags \
    tests/install/consumer.c -o "$tmp/consumer_static" "$dest$prefix/lib/libconica.a" $slibs -lm
check "run (static)" "$tmp/consumer_static"
finish
