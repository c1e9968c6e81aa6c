#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/signals.sh BUILD_DIR - a tool stopped by a signal while it
# writes its output leaves no temporary file and the old output as it was,
# and says so: exit 128 + signo and `TOOL: error: FILE: stopped by SIG...`.
# SIGXFSZ comes from `ulimit -f` (deterministic: the write that crosses the
# limit raises it), for every tool that writes files. SIGTERM, SIGINT and
# SIGHUP are sent by kill to conica subdivide while it writes a 64 MB
# output: the tool is frozen with SIGSTOP as soon as its temporary shows
# up, the signal is queued, the tool continued. SIGKILL cannot be caught:
# it leaves the target as it was and at most one hidden
# .NAME.conica-tmp.XXXXXX, nothing a plain `ls` or a glob shows. The
# per-signal details (SIGPIPE, a signal ignored at start) are unit tests
# in tests/test_cli.c.
set -u
. "$(dirname "$0")/harness.sh"
case $build in /*) b=$build ;; *) b=$(pwd)/$build ;; esac
conica=$b/bin/conica
svgsmooth=$b/bin/svgsmooth
scad=$b/bin/scadprofile
ex=$(pwd)/examples

# fresh NAME: a directory holding result.out with known bytes; sets $d, $f.
fresh() {
    d=$tmp/$1
    rm -rf "$d"
    mkdir -p "$d"
    f=$d/result.out
    printf 'precious data\n' >"$f"
    ls -A "$d" >"$tmp/before"
}

# intact NAME: $f has its old bytes and $d holds nothing else.
intact() {
    check_true "$1: the old output is byte-identical" \
        sh -c 'test "$(cat "$1")" = "precious data"' sh "$f"
    ls -A "$d" >"$tmp/after"
    check_true "$1: no temporary left ($(tr '\n' ' ' <"$tmp/after"))" cmp -s "$tmp/before" "$tmp/after"
}

# xfsz NAME CMD-WITH-@OUT@...: under `ulimit -f 2` (1 KiB) the run exits
# 153 (128 + SIGXFSZ) with the message, and nothing changes.
xfsz() {
    x_name=$1
    shift
    fresh "xfsz-$x_name"
    x_i=0
    for x_a in "$@"; do
        [ "$x_a" = @OUT@ ] && x_a=$f
        if [ $x_i -eq 0 ]; then set --; fi
        set -- "$@" "$x_a"
        x_i=1
    done
    check_exit 153 "$x_name: stopped by the file size limit, exit 128 + SIGXFSZ" \
        sh -c 'ulimit -f 2 && exec "$@"' sh "$@"
    check_grep "^[a-z]+: error: $f: stopped by SIGXFSZ \(file size limit exceeded\); output not written" \
        "$err" "$x_name: the message names the output and the signal"
    intact "$x_name"
}

begin_case "SIGXFSZ (ulimit -f) while writing: every tool"
xfsz subdivide "$conica" subdivide -k 6 -o @OUT@ "$ex/ellipse.txt"
xfsz combs "$conica" combs -k 4 -o @OUT@ "$ex/ellipse.txt"
xfsz errors-plot "$conica" errors -k 3 --plot @OUT@ "$ex/ellipse.txt"
xfsz plot "$conica" plot --tolerance 1e-6 -o @OUT@ "$ex/helix.spl"
xfsz svgsmooth "$svgsmooth" -o @OUT@ "$ex/letter-R.svg"
xfsz scadprofile "$scad" -o @OUT@ "$ex/ellipse.txt"
# --in-place: the input is the output
fresh xfsz-inplace
cp "$ex/letter-R.svg" "$d/in.svg"
ls -A "$d" >"$tmp/before"
check_exit 153 "svgsmooth --in-place: exit 153" \
    sh -c 'ulimit -f 2 && exec "$@"' sh "$svgsmooth" --in-place "$d/in.svg"
check_true "svgsmooth --in-place: the input is byte-identical" cmp -s "$ex/letter-R.svg" "$d/in.svg"
ls -A "$d" >"$tmp/after"
check_true "svgsmooth --in-place: no temporary left" cmp -s "$tmp/before" "$tmp/after"

# Start conica subdivide writing 64 MB (16 levels on 12 points) into $f in
# the background, freeze it with SIGSTOP once its temporary exists (sets
# $pid; returns 1 when the run ended first: writing 64 MB takes about a
# second, the poll looks every 10 ms). A
# background job of a non-interactive shell starts with SIGINT ignored
# (and the tools keep an ignored signal ignored): env resets it.
start_and_freeze() {
    env --default-signal=INT "$conica" subdivide -k 16 -o "$f" "$ex/ellipse.txt" \
        >"$out" 2>"$err" </dev/null &
    pid=$!
    s_i=0
    while [ $s_i -lt 3000 ]; do
        set -- "$d"/.result.out.conica-tmp.*
        if [ -e "$1" ]; then
            kill -STOP "$pid" 2>/dev/null
            set -- "$d"/.result.out.conica-tmp.*
            [ -e "$1" ] && return 0
            break
        fi
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.01
        s_i=$((s_i + 1))
    done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    return 1
}

for sig in TERM INT HUP; do
    case $sig in TERM) n=15 ;; INT) n=2 ;; HUP) n=1 ;; esac
    begin_case "SIG$sig while writing: temporary removed, exit $((128 + n))"
    fresh "sig-$sig"
    if ! start_and_freeze; then
        check_true "the hidden temporary .result.out.conica-tmp.* shows up while 64 MB are written" false
        continue
    fi
    kill -"$sig" "$pid"
    kill -CONT "$pid"
    wait "$pid" 2>/dev/null
    st=$?
    h_cmd="conica subdivide -k 16 ... (sent SIG$sig)"
    check_true "exit status $st is 128 + $n" test "$st" -eq $((128 + n))
    check_grep "^conica: error: $f: stopped by SIG$sig; output not written \(the temporary file was removed\)" "$err"
    intact "SIG$sig"
done

begin_case "SIGKILL while writing: the target intact, only a hidden temporary"
fresh sig-KILL
if start_and_freeze; then
    kill -KILL "$pid"
    kill -CONT "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    st=$?
    check_true "exit status $st is 137" test "$st" -eq 137
    check_true "the old output is byte-identical" \
        sh -c 'test "$(cat "$1")" = "precious data"' sh "$f"
    check_true "a plain listing shows only the target" test "$(ls "$d")" = result.out
    check_count 1 '^\.result\.out\.conica-tmp\.[A-Za-z0-9]{6}$' "$(ls -A "$d" >"$tmp/all"; echo "$tmp/all")" \
        "at most one hidden .result.out.conica-tmp.XXXXXX"
else
    check_true "the hidden temporary .result.out.conica-tmp.* shows up while 64 MB are written" false
fi

finish
