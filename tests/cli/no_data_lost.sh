#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/no_data_lost.sh BUILD_DIR - no CLI loses data when it fails.
# For every tool (conica subdivide / combs / plot when present, svgsmooth
# incl. --in-place, scadprofile):
#   - a failed run leaves an existing output file byte-identical;
#   - no temporary file is left in the target directory, also when the
#     final rename fails (the target is a directory);
#   - an unwritable output location (read-only /proc, a path under a
#     regular file, a missing directory, chmod 555 when not root) is exit 1;
#   - a write error (-o /dev/full) is exit 1, not a silent success;
#   - a successful run that replaces an output keeps its mode and a
#     symbolic link stays a link whose target is updated (attrs below).
set -u
. "$(dirname "$0")/harness.sh"
conica=$build/bin/conica
svgsmooth=$build/bin/svgsmooth
scad=$build/bin/scadprofile
ex=examples

printf 'v 0 0\nv 1 nan\nv 2 0\n' >"$tmp/nan.txt"
printf 'degree 2\nknots 0 0 0 1 1 1\nc 0 0\nc 1 nan\nc 2 0\n' >"$tmp/nan.spl"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0' >"$tmp/truncated.svg"
# a bowtie: valid SVG, but its profile crosses itself (svgsmooth's tests)
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 10L10 0L0 10Z"/></svg>\n' \
    >"$tmp/bowtie.svg"
# valid SVG that scadprofile refuses: a point beyond OpenSCAD's range (a
# bowtie is no longer refused: the fill rule says what it paints)
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L1e15 0L0 10Z"/></svg>\n' \
    >"$tmp/far.svg"
printf 'degree 2\nknots 0 0 0 1 2 3 3 3\nc 0 0\nc 4 0\nc 6 3\nc 3 6\nc 0 3\n' >"$tmp/open.spl"

has_plot=0
"$conica" plot --help >/dev/null 2>&1 && has_plot=1

# keeps NAME EXT CMD-WITH-@OUT@...: run CMD (which must fail) with @OUT@ as
# an existing file in a fresh directory; the file keeps its bytes and the
# directory gains nothing.
keeps() {
    k_name=$1 k_ext=$2
    shift 2
    k_dir=$tmp/keep-$k_name
    mkdir -p "$k_dir"
    k_file=$k_dir/result.$k_ext
    printf 'precious data\nline 2\n' >"$k_file"
    cp "$k_file" "$tmp/expected"
    ls -A "$k_dir" >"$tmp/before"
    k_i=0
    for k_a in "$@"; do
        [ "$k_a" = @OUT@ ] && k_a=$k_file
        if [ $k_i -eq 0 ]; then set --; fi
        set -- "$@" "$k_a"
        k_i=1
    done
    check_exit 1 "$k_name: the failing run exits 1" "$@"
    check_true "$k_name: the existing output is byte-identical" cmp -s "$k_file" "$tmp/expected"
    ls -A "$k_dir" >"$tmp/after"
    check_true "$k_name: no temporary file left beside it" cmp -s "$tmp/before" "$tmp/after"
}

# unwritable NAME EXT CMD-WITH-@OUT@...: every unwritable location is exit 1
# with an error naming it.
unwritable() {
    u_name=$1 u_ext=$2
    shift 2
    : >"$tmp/plainfile"
    mkdir -p "$tmp/ro"
    chmod 555 "$tmp/ro"
    for u_out in "/proc/conica-test.$u_ext" "$tmp/plainfile/out.$u_ext" \
        "$tmp/missing/dir/out.$u_ext" "$tmp/ro/out.$u_ext"; do
        if [ "$u_out" = "$tmp/ro/out.$u_ext" ] && [ "$(id -u)" -eq 0 ]; then
            continue # root writes into a 555 directory
        fi
        u_i=0
        for u_a in "$@"; do
            [ "$u_a" = @OUT@ ] && u_a=$u_out
            if [ $u_i -eq 0 ]; then set --; fi
            set -- "$@" "$u_a"
            u_i=1
        done
        check_exit 1 "$u_name: unwritable $u_out is exit 1" "$@"
        check_grep "error: .*$(basename "$u_out")|error: .*$(dirname "$u_out")" "$err" \
            "$u_name: the message names $u_out"
        check_true "$u_name: nothing created" test ! -e "$u_out"
        set -- # restore the template for the next location
        for u_a in $u_template; do set -- "$@" "$u_a"; done
    done
    chmod 755 "$tmp/ro"
}

# rename_fails NAME EXT CMD-WITH-@OUT@...: the target is a directory, so the
# final rename fails after the whole output was written: exit 1 and the
# temporary is removed.
rename_fails() {
    r_name=$1
    shift 2
    r_dir=$tmp/rn-$r_name
    mkdir -p "$r_dir/target"
    ls -A "$r_dir" >"$tmp/before"
    r_i=0
    for r_a in "$@"; do
        [ "$r_a" = @OUT@ ] && r_a=$r_dir/target
        if [ $r_i -eq 0 ]; then set --; fi
        set -- "$@" "$r_a"
        r_i=1
    done
    check_exit 1 "$r_name: output onto a directory is exit 1" "$@"
    ls -A "$r_dir" >"$tmp/after"
    check_true "$r_name: no temporary file left after the failed rename" cmp -s "$tmp/before" "$tmp/after"
    check_true "$r_name: the directory is still a directory" test -d "$r_dir/target"
}

full() {
    f_name=$1
    shift
    check_exit 1 "$f_name: a write error (/dev/full) is exit 1" "$@"
    # the output named (not <output>) and the reason (issue 33)
    check_grep 'error: /dev/full: .*No space left on device' "$err" \
        "$f_name: the write error names /dev/full and the reason"
}

# perms_of FILE: the permission column of `ls -l` (e.g. -rw-r-----).
perms_of() { ls -ln "$1" | cut -c1-10; }

# same_output A B: equal except for scadprofile's `// command: ...` line,
# which records the output path.
same_output() {
    grep -v '^// command:' "$1" >"$tmp/so-a"
    grep -v '^// command:' "$2" >"$tmp/so-b"
    cmp -s "$tmp/so-a" "$tmp/so-b"
}

# cmd_for OUT: $a_template with @OUT@ replaced by OUT (words split on
# spaces when used unquoted, as u_template above: no path here has one).
cmd_for() { printf '%s\n' "$a_template" | sed "s|@OUT@|$1|g"; }

# attrs NAME SEED [inplace]: a successful run of $a_template that replaces
# an existing output keeps what the user set up around it. SEED is copied
# to the output first (for --in-place, pass "inplace": the output is the
# input). Checked:
#   - the result is what the same run writes over a plain copy (reference);
#   - modes 0600 and 0640 survive the replacement (not reset to 0644);
#   - a symbolic link (relative beside its target, and absolute from another
#     directory) stays a link to the same target; the target gets the new
#     content and keeps its mode; no temporary is left in either directory;
#   - a new file gets 0666 & ~umask (umask 027: -rw-r-----), not -o only;
#   - a dangling link is refused (exit 1) and left as it was.
attrs() {
    a_name=$1 a_seed=$2 a_inplace=${3:-}
    a_dir=$tmp/attrs-$a_name
    mkdir -p "$a_dir/ref" "$a_dir/mode" "$a_dir/ln" "$a_dir/real" "$a_dir/new" "$a_dir/dangle"
    cp "$a_seed" "$a_dir/ref/out"
    check_exit 0 "$a_name: reference run" $(cmd_for "$a_dir/ref/out")
    check_true "$a_name: the reference differs from the seed" sh -c "! cmp -s '$a_seed' '$a_dir/ref/out'"
    for a_mode in 600 640; do
        cp "$a_seed" "$a_dir/mode/out"
        chmod "$a_mode" "$a_dir/mode/out"
        a_before=$(perms_of "$a_dir/mode/out")
        check_exit 0 "$a_name: replacing a $a_mode file succeeds" $(cmd_for "$a_dir/mode/out")
        check_true "$a_name: mode $a_mode kept ($a_before -> $(perms_of "$a_dir/mode/out"))" \
            test "$(perms_of "$a_dir/mode/out")" = "$a_before"
        check_true "$a_name: mode $a_mode: the new content" same_output "$a_dir/mode/out" "$a_dir/ref/out"
        check_true "$a_name: mode $a_mode: no temporary left" test "$(ls -A "$a_dir/mode")" = out
        rm -f "$a_dir/mode/out"
    done
    for a_kind in relative absolute; do
        rm -f "$a_dir/real/file" "$a_dir/real/link" "$a_dir/ln/link"
        cp "$a_seed" "$a_dir/real/file"
        chmod 640 "$a_dir/real/file"
        if [ "$a_kind" = relative ]; then
            a_link=$a_dir/real/link a_target=file a_listing="file link"
            ln -s file "$a_link"
        else
            a_link=$a_dir/ln/link a_target=$a_dir/real/file a_listing=file
            ln -s "$a_target" "$a_link"
        fi
        check_exit 0 "$a_name: writing through a $a_kind symlink succeeds" $(cmd_for "$a_link")
        check_true "$a_name: the $a_kind symlink is still a symlink" test -L "$a_link"
        check_true "$a_name: the $a_kind symlink still points to $a_target" \
            test "$(ls -l "$a_link" | sed 's/.* -> //')" = "$a_target"
        check_true "$a_name: $a_kind symlink: its target got the new content" \
            same_output "$a_dir/real/file" "$a_dir/ref/out"
        check_true "$a_name: $a_kind symlink: the target kept mode 0640" \
            test "$(perms_of "$a_dir/real/file")" = "-rw-r-----"
        check_true "$a_name: $a_kind symlink: no temporary beside the target" \
            test "$(ls -A "$a_dir/real" | tr '\n' ' ')" = "$a_listing "
        check_true "$a_name: $a_kind symlink: no temporary beside the link" \
            test "$(ls -A "$(dirname "$a_link")" | grep -c tmp)" -eq 0
    done
    if [ -z "$a_inplace" ]; then
        rm -f "$a_dir/new/out"
        check_exit 0 "$a_name: a new file under umask 027" \
            sh -c 'umask 027 && exec "$@"' sh $(cmd_for "$a_dir/new/out")
        check_true "$a_name: the new file is -rw-r----- (0666 & ~027, not mkstemp's 0600)" \
            test "$(perms_of "$a_dir/new/out")" = "-rw-r-----"
    fi
    rm -f "$a_dir/dangle/out"
    ln -s "$a_dir/dangle/missing" "$a_dir/dangle/out"
    check_exit 1 "$a_name: a dangling symlink as output is refused" $(cmd_for "$a_dir/dangle/out")
    if [ -z "$a_inplace" ]; then
        check_grep 'symbolic link' "$err" "$a_name: the message says why"
    else # --in-place reads the input first, which is missing
        check_grep 'error: .*dangle/out' "$err" "$a_name: the message names the file"
    fi
    check_true "$a_name: the dangling link is left as it was, nothing created" \
        test -L "$a_dir/dangle/out" -a ! -e "$a_dir/dangle/missing" -a "$(ls -A "$a_dir/dangle")" = out
}

begin_case "conica subdivide"
keeps subdivide txt "$conica" subdivide -k 2 -o @OUT@ "$tmp/nan.txt"
u_template="$conica subdivide -k 1 -o @OUT@ $ex/ellipse.txt"
unwritable subdivide txt $u_template
rename_fails subdivide txt "$conica" subdivide -k 1 -o @OUT@ "$ex/ellipse.txt"
full subdivide "$conica" subdivide -k 6 -o /dev/full "$ex/ellipse.txt"

begin_case "conica combs"
keeps combs svg "$conica" combs -k 2 -o @OUT@ "$tmp/nan.txt"
u_template="$conica combs -k 1 -o @OUT@ $ex/ellipse.txt"
unwritable combs svg $u_template
rename_fails combs svg "$conica" combs -k 1 -o @OUT@ "$ex/ellipse.txt"
full combs "$conica" combs -k 3 -o /dev/full "$ex/ellipse.txt"

begin_case "conica errors --plot"
keeps errors svg "$conica" errors -k 2 --plot @OUT@ "$tmp/nan.txt"

begin_case "conica plot"
if [ "$has_plot" -eq 0 ]; then
    skip_case "this conica has no plot command"
else
    keeps plot txt "$conica" plot -o @OUT@ "$tmp/nan.spl"
    u_template="$conica plot -o @OUT@ $tmp/open.spl"
    unwritable plot txt $u_template
    rename_fails plot txt "$conica" plot -o @OUT@ "$tmp/open.spl"
fi

begin_case "svgsmooth -o"
keeps svgsmooth svg "$svgsmooth" -o @OUT@ "$tmp/truncated.svg"
keeps svgsmooth-limit svg "$svgsmooth" --max-points 10 -o @OUT@ "$ex/letter-R.svg"
u_template="$svgsmooth -o @OUT@ $ex/letter-R.svg"
unwritable svgsmooth svg $u_template
rename_fails svgsmooth svg "$svgsmooth" -o @OUT@ "$ex/letter-R.svg"
full svgsmooth "$svgsmooth" --levels 6 -o /dev/full "$ex/traced-leaf.svg"

begin_case "svgsmooth --in-place never damages the input"
for bad in truncated bowtie-limit; do
    mkdir -p "$tmp/ip-$bad"
    if [ "$bad" = truncated ]; then
        cp "$tmp/truncated.svg" "$tmp/ip-$bad/in.svg"
        set -- "$svgsmooth" --in-place "$tmp/ip-$bad/in.svg"
    else
        cp "$ex/letter-R.svg" "$tmp/ip-$bad/in.svg"
        set -- "$svgsmooth" --in-place --max-points 10 "$tmp/ip-$bad/in.svg"
    fi
    cp "$tmp/ip-$bad/in.svg" "$tmp/orig.svg"
    check_exit 1 "--in-place on a failing input ($bad) exits 1" "$@"
    check_true "--in-place ($bad): the input is byte-identical" cmp -s "$tmp/ip-$bad/in.svg" "$tmp/orig.svg"
    check_true "--in-place ($bad): no temporary left" test "$(ls -A "$tmp/ip-$bad")" = in.svg
done
mkdir -p "$tmp/ip-ok"
cp "$ex/letter-R.svg" "$tmp/ip-ok/in.svg"
check "--in-place on a good input succeeds" "$svgsmooth" --in-place --levels 2 "$tmp/ip-ok/in.svg"
check_true "--in-place replaced the file" test "$(ls -A "$tmp/ip-ok")" = in.svg
check_true "--in-place changed the content" sh -c "! cmp -s '$tmp/ip-ok/in.svg' '$ex/letter-R.svg'"

printf 'precious data\nline 2\n' >"$tmp/seed.txt"
begin_case "replacing an output keeps its mode and symlinks: conica"
a_template="$conica subdivide -k 1 -o @OUT@ $ex/ellipse.txt"
attrs subdivide "$tmp/seed.txt"
a_template="$conica combs -k 1 -o @OUT@ $ex/ellipse.txt"
attrs combs "$tmp/seed.txt"
if [ "$has_plot" -eq 1 ]; then
    a_template="$conica plot -o @OUT@ $tmp/open.spl"
    attrs plot "$tmp/seed.txt"
fi

begin_case "replacing an output keeps its mode and symlinks: svgsmooth"
a_template="$svgsmooth --levels 2 -o @OUT@ $ex/letter-R.svg"
attrs svgsmooth-o "$tmp/seed.txt"
a_template="$svgsmooth --levels 2 --in-place @OUT@"
attrs svgsmooth-in-place "$ex/letter-R.svg" inplace

begin_case "replacing an output keeps its mode and symlinks: scadprofile"
a_template="$scad -o @OUT@ $ex/ellipse.txt"
attrs scadprofile "$tmp/seed.txt"

begin_case "scadprofile"
keeps scadprofile-nan scad "$scad" -o @OUT@ "$tmp/nan.txt"
keeps scadprofile-spline scad "$scad" -o @OUT@ "$tmp/nan.spl"
keeps scadprofile-xml scad "$scad" -o @OUT@ "$tmp/truncated.svg"
keeps scadprofile-invalid scad "$scad" -o @OUT@ "$tmp/far.svg"
u_template="$scad -o @OUT@ $ex/ellipse.txt"
unwritable scadprofile scad $u_template
rename_fails scadprofile scad "$scad" -o @OUT@ "$ex/ellipse.txt"
full scadprofile "$scad" --levels 6 -o /dev/full "$ex/ellipse.txt"

finish
