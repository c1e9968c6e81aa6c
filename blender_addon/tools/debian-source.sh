#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Fetch one Debian source package (the Windows build of the Blender add-on
# compiles LAPACK from Debian's lapack package and takes the CPython headers
# from Debian's python3.11 package) without touching the system's apt
# configuration: a private deb-src list for the running release, private
# package lists and cache, all under DIR.
#
#   blender_addon/tools/debian-source.sh PACKAGE DIR [--download-only]
#
# The mirror is DEBIAN_MIRROR, by default the one the system's own apt
# sources use for its release (the first `deb` entry for VERSION_CODENAME of
# /etc/os-release, bookworm on Debian 12, in sources.list or a deb822
# .sources file), so the source comes from where the binaries do.
set -eu
pkg=$1
dir=$2
shift 2
suite=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
[ -n "$suite" ] || { echo "debian-source: no VERSION_CODENAME in /etc/os-release" >&2; exit 1; }
# system_mirror: the URI of the first enabled `deb` source for $suite
system_mirror() {
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
        [ -f "$f" ] || continue
        awk -v s="$suite" '$1 == "deb" { i = 2; if ($2 ~ /^\[/) while (i <= NF && $i !~ /\]$/) i++;
            if ($2 ~ /^\[/) i++; if ($(i + 1) == s) { print $i; exit } }' "$f"
    done
    for f in /etc/apt/sources.list.d/*.sources; do
        [ -f "$f" ] || continue
        # deb822 stanzas, separated by blank lines
        awk -v s="$suite" 'function flush() { if (t ~ /(^| )deb( |$)/ && (" " su " ") ~ (" " s " ") && u != "" && en != "no") print u;
                t = su = u = en = "" }
            /^[ \t]*$/ { flush(); next }
            /^Types:/ { sub(/^Types:[ \t]*/, ""); t = $0 }
            /^Suites:/ { sub(/^Suites:[ \t]*/, ""); su = $0 }
            /^URIs:/ { sub(/^URIs:[ \t]*/, ""); split($0, a, " "); u = a[1] }
            /^Enabled:/ { sub(/^Enabled:[ \t]*/, ""); en = $0 }
            END { flush() }' "$f"
    done | head -n 1
}
mirror=${DEBIAN_MIRROR:-$(system_mirror)}
[ -n "$mirror" ] || { echo "debian-source: no apt source for $suite found; set DEBIAN_MIRROR" >&2; exit 1; }
command -v apt-get >/dev/null 2>&1 || { echo "debian-source: apt-get not found" >&2; exit 1; }
mkdir -p "$dir/apt/lists/partial" "$dir/apt/cache/archives/partial"
echo "deb-src $mirror $suite main" >"$dir/apt/sources.list"
set -- -o Dir::Etc::SourceList="$(cd "$dir" && pwd)/apt/sources.list" \
    -o Dir::Etc::SourceParts=/dev/null \
    -o Dir::State::Lists="$(cd "$dir" && pwd)/apt/lists" \
    -o Dir::Cache="$(cd "$dir" && pwd)/apt/cache" "$@"
# as root, apt would hand the download to its _apt user, who cannot write DIR
[ "$(id -u)" -ne 0 ] || set -- -o APT::Sandbox::User=root "$@"
apt-get -qq "$@" update
cd "$dir"
apt-get -qq "$@" source "$pkg"
