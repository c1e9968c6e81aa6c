#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/cli_conventions.sh BUILD_DIR - every tool and every conica
# subcommand parses its command line the way getopt_long tools do, checked
# for all of them the same way (docs/development.md, "Command lines"):
#   --opt=VALUE and --opt VALUE, an unambiguous abbreviation, -kVALUE and
#   -k VALUE, combined flags (-qk2), options after operands, `--` ending
#   the options, `-` for standard input, --help (Usage: ..., every option of
#   the table, 80 columns), --version, an unknown option or a missing value
#   exiting 2 with "Try 'PROG --help' for more information.", and a
#   progress line on a terminal only (-q / --progress force it).
# The option tables come from `TOOL --dump-options` (the source of --help,
# the completions and the manual-page check in docs.sh).
set -u
. "$(dirname "$0")/harness.sh"
ex=$PWD/examples
bindir=$(cd "$build/bin" && pwd) # absolute: some runs change directory
ver=$(sed -n 's/^#define CONICA_VERSION_STRING "\(.*\)"$/\1/p' libcore/include/conica/common.h)
[ -n "$ver" ] || ver=$(sed -n "s/^Version: //p" "$build/conica.pc")

# One line per command: NAME|INPUT|LONG VALUE|SHORT VALUE|FLAG (- for
# none)|an option every run gets (- for none). VALUE @OUT@ is a file the
# command writes (compared as well as stdout).
commands="conica subdivide|$ex/ellipse.txt|levels 2|k 2|q|-
conica plot|$ex/nurbs-circle.spl|tolerance 2|o @OUT@|-|-
conica combs|$ex/ellipse.txt|width 400|k 2|-|-
conica errors|$ex/ellipse.txt|levels 2|k 2|-|-
svgsmooth|$ex/rect-star.svg|levels 2|k 2|q|-
scadprofile|$ex/bracket.svg|tolerance 0.1|t 0.1|q|--module=m"

# bin_of NAME: the program and the subcommand, as words.
bin_of() {
    case $1 in
    conica\ *) printf "%s %s" "$bindir/conica" "${1#conica }" ;;
    *) printf "%s" "$bindir/$1" ;;
    esac
}

n_run=0
# run TAG CMD...: run CMD with every @OUT@ replaced by a file of its own;
# $tmp/TAG.all holds stdout then that file (the lines that repeat the
# command line or the input's name left out: scadprofile's `// command:`
# and `// source:`, the title line of conica errors), TAG.err stderr,
# TAG.rc the exit status.
run() {
    r_tag=$1
    shift
    r_file=$tmp/$r_tag.file
    rm -f "$r_file"
    r_n=$#
    while [ "$r_n" -gt 0 ]; do
        r_a=$1
        shift
        case $r_a in *@OUT@*) r_a=$(printf '%s' "$r_a" | sed "s|@OUT@|$r_file|") ;; esac
        set -- "$@" "$r_a"
        r_n=$((r_n - 1))
    done
    "$@" >"$tmp/$r_tag.out" 2>"$tmp/$r_tag.err" <"${r_stdin:-/dev/null}"
    echo $? >"$tmp/$r_tag.rc"
    { cat "$tmp/$r_tag.out"; [ -f "$r_file" ] && cat "$r_file"; } | grep -v -e '^// command:' -e '^// source:' -e '^# conica errors ' >"$tmp/$r_tag.all"
    n_run=$((n_run + 1))
}

# same DESC TAG1 TAG2: both ran with status 0, wrote something, the same.
same() {
    check_true "$1: exit 0 ($(cat "$tmp/$2.err" | head -n 2))" test "$(cat "$tmp/$2.rc")" = 0
    check_true "$1: the other spelling exits 0 ($(cat "$tmp/$3.err" | head -n 2))" test "$(cat "$tmp/$3.rc")" = 0
    check_true "$1: output written" test -s "$tmp/$2.all"
    check_true "$1: the same output" cmp -s "$tmp/$2.all" "$tmp/$3.all"
}

# shortest_prefix NAME TABLE: the shortest abbreviation of --NAME no other
# long option of the table starts with.
shortest_prefix() {
    awk -F '\t' -v want="$1" '$1 == "opt" && $3 != "-" { names[++n] = $3 }
        END { for (len = 1; len <= length(want); len++) {
                  p = substr(want, 1, len); hits = 0
                  for (i = 1; i <= n; i++) if (substr(names[i], 1, len) == p) hits++
                  if (hits == 1) { print p; exit } } }' "$2"
}

while IFS='|' read -r name input long short flag extra; do
    # shellcheck disable=SC2046
    set -- $(bin_of "$name")
    "$@" --dump-options >"$tmp/$(printf '%s' "$name" | tr ' ' _).table" 2>&1
    [ "$extra" = - ] || set -- "$@" "$extra"
    prog=$*
    ext=${input##*.}
    lname=${long% *} lval=${long#* }
    sname=${short% *} sval=${short#* }
    tag=$(printf '%s' "$name" | tr ' ' _)

    begin_case "$name: --$lname=V, --$lname V and an abbreviation"
    check_true "$name --dump-options lists --$lname" grep -q "	$lname	required	" "$tmp/$tag.table"
    run "$tag.eq" "$@" "--$lname=$lval" "$input"
    run "$tag.sep" "$@" "--$lname" "$lval" "$input"
    same "$name --$lname=$lval" "$tag.eq" "$tag.sep"
    abbr=$(shortest_prefix "$lname" "$tmp/$tag.table")
    if [ "$abbr" != "$lname" ]; then
        run "$tag.abbr" "$@" "--$abbr=$lval" "$input"
        same "$name --$abbr=$lval (abbreviated)" "$tag.abbr" "$tag.eq"
    fi
    run "$tag.after" "$@" "$input" "--$lname" "$lval"
    same "$name: an option after the operand" "$tag.after" "$tag.sep"

    begin_case "$name: -$sname$sval and -$sname $sval"
    run "$tag.att" "$@" "-$sname$sval" "$input"
    run "$tag.apart" "$@" "-$sname" "$sval" "$input"
    same "$name -$sname$sval" "$tag.att" "$tag.apart"

    begin_case "$name: combined short flags"
    if [ "$flag" = - ]; then
        # the table has no short option without a value to combine
        check_true "$name has no short flag (its table agrees)" \
            test -z "$(awk -F '\t' '$1 == "opt" && $2 != "-" && $2 != "h" && $4 == "none"' "$tmp/$tag.table")"
    else
        run "$tag.comb" "$@" "-$flag$sname$sval" "$input"
        run "$tag.split" "$@" "-$flag" "-$sname" "$sval" "$input"
        same "$name -$flag$sname$sval" "$tag.comb" "$tag.split"
    fi

    begin_case "$name: -- ends the options, - is standard input"
    mkdir -p "$tmp/$tag.dir"
    cp "$input" "$tmp/$tag.dir/-input.$ext"
    (cd "$tmp/$tag.dir" && run "$tag.dd" "$@" "--$lname=$lval" -- "-input.$ext" &&
        run "$tag.dot" "$@" "--$lname=$lval" "./-input.$ext")
    same "$name -- -input.$ext" "$tag.dd" "$tag.dot"
    r_stdin=$input run "$tag.stdin" "$@" "--$lname=$lval" -
    same "$name - <input" "$tag.stdin" "$tag.eq"

    begin_case "$name: --help and --version"
    run "$tag.help" "$@" --help
    check_true "$name --help exits 0" test "$(cat "$tmp/$tag.help.rc")" = 0
    check_true "$name --help starts 'Usage: $name '" \
        test "$(head -n 1 "$tmp/$tag.help.out" | cut -c1-$((8 + ${#name})))" = "Usage: $name "
    check_true "$name --help writes nothing on stderr" test ! -s "$tmp/$tag.help.err"
    awk -F '\t' '$1 == "opt" && $3 != "-" { print "--" $3 }' "$tmp/$tag.table" >"$tmp/$tag.longs"
    missing=$(while read -r o; do grep -q -e "$o" "$tmp/$tag.help.out" || printf '%s ' "$o"; done <"$tmp/$tag.longs")
    check_true "$name --help names every option of its table ($missing)" test -z "$missing"
    wide=$(awk 'length > 80' "$tmp/$tag.help.out" | head -n 2)
    check_true "$name --help fits 80 columns ($wide)" test -z "$wide"
    run "$tag.ver" "$@" --version
    check_true "$name --version exits 0" test "$(cat "$tmp/$tag.ver.rc")" = 0
    check_true "$name --version: '${name%% *} (Conica) $ver'" test "$(cat "$tmp/$tag.ver.out")" = "${name%% *} (Conica) $ver"

    begin_case "$name: usage errors exit 2 and point at --help"
    for bad in --no-such-option -Z "--$lname"; do
        if [ "$bad" = "--$lname" ]; then
            run "$tag.bad" "$@" "$input" "$bad" # the value is missing
        else
            run "$tag.bad" "$@" "$bad" "$input"
        fi
        check_true "$name $bad: exit 2" test "$(cat "$tmp/$tag.bad.rc")" = 2
        check_true "$name $bad: nothing on stdout" test ! -s "$tmp/$tag.bad.out"
        check_true "$name $bad: '$name: usage error: ...'" grep -q "^$name: usage error: " "$tmp/$tag.bad.err"
        check_true "$name $bad: Try '$name --help' for more information." \
            grep -qx "Try '$name --help' for more information." "$tmp/$tag.bad.err"
        case $bad in
        --no-such-option) check_true "$name $bad: named as typed" grep -q "unknown option '$bad'" "$tmp/$tag.bad.err" ;;
        --$lname) check_true "$name $bad: its value is missing" grep -q -e "$bad needs a value" "$tmp/$tag.bad.err" ;;
        esac
    done
done <<EOF
$commands
EOF

begin_case "manual pages name every short option with its long one, as the tables do"
# (docs.sh compares the long options of each page or section with the table)
for t in conica svgsmooth scadprofile; do
    "$bindir/$t" --dump-options | awk -F '\t' '$1 == "opt" && $2 != "-" && $3 != "-" { print $2, $3 }' |
        sort -u >"$tmp/$t.pairs"
    check_true "$t: its tables have short options" test -s "$tmp/$t.pairs"
    sed 's/\\-/-/g' "docs/man/$t.1" >"$tmp/$t.man"
    while read -r s l; do
        check_true "$t.1 names -$s with --$l" grep -q -e "-$s \", \" --$l\( \|\$\)" "$tmp/$t.man"
    done <"$tmp/$t.pairs"
done

begin_case "conica itself: --help, --version, unknown options and commands"
check "conica --help" "$build/bin/conica" --help
check_grep '^Usage: conica COMMAND' "$out"
for c in combs errors plot subdivide; do
    check_grep "^  $c +[A-Za-z]" "$out" "conica --help lists $c"
done
check "conica --version" "$build/bin/conica" --version
check_grep "^conica \\(Conica\\) $ver\$" "$out"
check_exit 2 "conica --no-such-option" "$build/bin/conica" --no-such-option
check_grep "^Try 'conica --help' for more information\\.\$" "$err"
check_exit 2 "conica no-such-command" "$build/bin/conica" no-such-command
check_grep "^conica: usage error: unknown command 'no-such-command'" "$err"
check_exit 2 "conica with no command" "$build/bin/conica"
check "options of a command follow it: conica subdivide --levels=1" \
    "$build/bin/conica" subdivide --levels=1 "$ex/ellipse.txt"

begin_case "an ambiguous abbreviation names the candidates"
check_exit 2 "conica subdivide --max=3" "$build/bin/conica" subdivide --max=3 "$ex/ellipse.txt"
check_grep "option '--max' is ambiguous \\(--max-points, --max-input-points\\)" "$err"
check_exit 2 "a flag given a value: conica subdivide --open=1" "$build/bin/conica" subdivide --open=1 "$ex/ellipse.txt"
check_grep "option '--open' takes no value" "$err"

begin_case "counts of one are singular"
printf '<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L10 0L10 10z"/></svg>\n' >"$tmp/one.svg"
check "svgsmooth --stats on one element" "$bindir/svgsmooth" --stats -o "$tmp/one.out.svg" "$tmp/one.svg"
check_grep "stats: 1 element, 1 subpath, 3 input vertices, 3 output points" "$err"
check "scadprofile --stats on one element" "$bindir/scadprofile" --stats -o "$tmp/one.scad" "$tmp/one.svg"
check_grep "input SVG, 1 element, 1 closed subpath;" "$err"
check "svgsmooth on one file of a batch" "$bindir/svgsmooth" -o "$tmp/onedir/" "$tmp/one.svg"
check_grep "^svgsmooth: 1 file written, 0 failed" "$err"

begin_case "a progress line on a terminal only; -q and --progress force it"
mkdir -p "$tmp/many/svgsmooth" "$tmp/many/scadprofile"
for i in 1 2 3 4 5 6; do
    cp "$ex/rect-star.svg" "$tmp/many/svgsmooth/f$i.svg"
    cp "$ex/bracket.svg" "$tmp/many/scadprofile/f$i.svg" # a part drawn to be one
done
# pty CMD...: run CMD with stderr on a pseudo-terminal; what it wrote there
pty() {
    "$PY" - "$@" <<'EOF'
import os, pty, subprocess, sys
m, s = pty.openpty()
p = subprocess.Popen(sys.argv[1:], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=s)
os.close(s)
data = b''
while True:
    try:
        d = os.read(m, 4096)
    except OSError:
        break
    if not d:
        break
    data += d
sys.stdout.write(data.decode('utf-8', 'replace'))
sys.exit(p.wait())
EOF
}
PY=${PY:-python3}
for t in svgsmooth scadprofile; do
    check "$t, several files, stderr a terminal" pty "$build/bin/$t" -o "$tmp/$t.p1/" "$tmp/many/$t"/f*.svg
    check_grep "^.?$t: [0-9]+/6 files, .* files/s, ETA [0-9]+ s" "$out" "$t: a progress line with count, rate and ETA"
    check_grep "$t: 6 files written, 0 failed" "$out" "$t: the summary after it"
    check "$t -q, stderr a terminal" pty "$build/bin/$t" -q -o "$tmp/$t.p2/" "$tmp/many/$t"/f*.svg
    check_no_grep "files/s" "$out" "$t -q: no progress line"
    check "$t, stderr a file" "$build/bin/$t" -o "$tmp/$t.p3/" "$tmp/many/$t"/f*.svg
    check_no_grep "files/s" "$err" "$t: no progress line when stderr is not a terminal"
    check "$t --progress, stderr a file" "$build/bin/$t" --progress -o "$tmp/$t.p4/" "$tmp/many/$t"/f*.svg
    check_grep "[0-9]+/6 files, .* files/s" "$err" "$t --progress: the progress line all the same"
done

finish
