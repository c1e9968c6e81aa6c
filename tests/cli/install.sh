# SPDX-License-Identifier: MIT
# `make install` into a staging DESTDIR, then an outside program built only
# with `pkg-config conica` (tests/install/consumer.c), linked both against the
# shared library (run through the installed soname) and statically. The GNU
# directory variables (LIBDIR, ...) and `make uninstall` (an empty tree
# after it), the completions loading in bash and zsh, -Werror only with
# WERROR=1, `make -f` from another directory with an out-of-tree BUILD, and
# scripts/deps.sh on a system without dpkg and apt-get.
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
unset PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR

begin_case "GNU directories: LIBDIR, MANDIR, ...; make uninstall leaves an empty tree"
dest2=$tmp/stage2
dirs="PREFIX=/usr LIBDIR=/usr/lib/x86_64-linux-gnu MANDIR=/usr/man DATADIR=/usr/data"
# shellcheck disable=SC2086
check "make install $dirs" make --no-print-directory BUILD="$build" DESTDIR="$dest2" $dirs install
for f in usr/lib/x86_64-linux-gnu/libconica.so.0 usr/lib/x86_64-linux-gnu/pkgconfig/conica.pc \
         usr/man/man1/svgsmooth.1 usr/data/bash-completion/completions/svgsmooth \
         usr/data/zsh/site-functions/_conica usr/include/conica/subdiv.h usr/bin/svgsmooth; do
    check_true "installed /$f" test -e "$dest2/$f"
done
check_grep '^libdir=\$\{prefix\}/lib/x86_64-linux-gnu$' "$dest2/usr/lib/x86_64-linux-gnu/pkgconfig/conica.pc"
check_true "nothing under lib/ itself" test ! -e "$dest2/usr/lib/libconica.a"
# shellcheck disable=SC2086
check "make uninstall $dirs" make --no-print-directory BUILD="$build" DESTDIR="$dest2" $dirs uninstall
left=$(find "$dest2" ! -type d | head -n 5)
check_true "no file or link left ($left)" test -z "$left"
check_true "our own directories removed" test ! -e "$dest2/usr/include/conica"

begin_case "completions load in bash and zsh"
comp=$dest/opt/conica/share
if command -v bash >/dev/null 2>&1; then
    check "bash: complete -p svgsmooth after sourcing" bash -c \
        ". '$comp/bash-completion/completions/svgsmooth' && complete -p svgsmooth"
    check_grep "^complete .*-F _conica_complete_svgsmooth svgsmooth\$" "$out"
    check "bash: conica subdivide --norm<TAB>" bash -c ". '$comp/bash-completion/completions/conica' &&
        COMP_WORDS=(conica subdivide --norm) COMP_CWORD=2 && _conica_complete_conica && echo \"\${COMPREPLY[*]}\""
    check_grep "^--normals\$" "$out"
    check "bash: the values of --normals" bash -c ". '$comp/bash-completion/completions/conica' &&
        COMP_WORDS=(conica subdivide --normals '') COMP_CWORD=3 && _conica_complete_conica && echo \"\${COMPREPLY[*]}\""
    check_grep "^area circle\$" "$out"
    check "bash: conica's commands" bash -c ". '$comp/bash-completion/completions/conica' &&
        COMP_WORDS=(conica s) COMP_CWORD=1 && _conica_complete_conica && echo \"\${COMPREPLY[*]}\""
    check_grep "^subdivide\$" "$out"
else
    check_true "bash is installed" false
fi
if command -v zsh >/dev/null 2>&1; then
    for t in conica svgsmooth scadprofile; do
        check "zsh: _$t loads (compinit, fpath)" zsh -f -c "fpath=('$comp/zsh/site-functions' \$fpath);
            autoload -Uz compinit && compinit -u -d '$tmp/zcompdump' && autoload -Uz _$t &&
            print -r -- \${_comps[$t]}"
        check_grep "^_$t\$" "$out"
        check "zsh: _$t parses (zsh -n)" zsh -n "$comp/zsh/site-functions/_$t"
    done
else
    check_true "zsh is installed (Debian: zsh, scripts/deps.sh test)" false
fi

begin_case "-Werror only with WERROR=1 (make test, .ci/run)"
# A plain make as a user types it: not the WERROR=1 that `make WERROR=1
# test` (.ci/run) passes down to every process below it (MAKEFLAGS, and
# the environment: make exports command-line variables).
check "make -n without WERROR" env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u WERROR make --no-print-directory -B -n BUILD="$tmp/wb" "$tmp/wb/obj/libcore/src/status.o"
check_no_grep "-Werror" "$out" "no -Werror forced on a plain build"
check "make -n WERROR=1" env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u WERROR make --no-print-directory -B -n BUILD="$tmp/wb" WERROR=1 "$tmp/wb/obj/libcore/src/status.o"
check_grep "-Werror" "$out" "WERROR=1 adds -Werror"
check_grep "WERROR=1" .ci/run "CI builds with WERROR=1"

begin_case "make -f from another directory, out-of-tree BUILD"
src=$PWD
mkdir -p "$tmp/elsewhere"
check "make -f $src/Makefile BUILD=oot oot/obj/libcore/src/status.o" sh -c \
    "cd '$tmp/elsewhere' && make --no-print-directory -f '$src/Makefile' BUILD=oot oot/obj/libcore/src/status.o"
check_true "the object is under the caller's BUILD" test -s "$tmp/elsewhere/oot/obj/libcore/src/status.o"
check_true "the source tree got no oot/" test ! -e "$src/oot"

begin_case "scripts/deps.sh finds what is installed without dpkg or apt-get"
# a PATH of everything in /usr/bin and /bin but dpkg and apt
mkdir -p "$tmp/path"
for f in /usr/bin/* /bin/*; do
    case ${f##*/} in dpkg* | apt*) continue ;; esac
    [ -e "$tmp/path/${f##*/}" ] || ln -s "$f" "$tmp/path/${f##*/}"
done
check "deps.sh build: everything there, no dpkg" env PATH="$tmp/path" sh scripts/deps.sh build
rm -f "$tmp/path/make"
check_exit 1 "deps.sh build without make and without apt-get" env PATH="$tmp/path" sh scripts/deps.sh build
check_grep "install what these Debian packages provide: make\$" "$err" "deps.sh names what is missing"
finish
