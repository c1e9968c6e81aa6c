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
# The mirror is DEBIAN_MIRROR (default http://deb.debian.org/debian), the
# suite VERSION_CODENAME of /etc/os-release (bookworm on Debian 12).
set -eu
pkg=$1
dir=$2
shift 2
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
suite=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
[ -n "$suite" ] || { echo "debian-source: no VERSION_CODENAME in /etc/os-release" >&2; exit 1; }
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
