#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/signals.sh BUILD_DIR - a tool stopped by a signal while it
# writes its output leaves no temporary file and the old output as it was,
# and says so: exit 128 + signo and `TOOL: error: FILE: stopped by SIG...`.
# SIGXFSZ comes from `ulimit -f` (deterministic: the write that crosses the
# limit raises it), for every tool that writes files. Every other signal
# whose default action ends the process is sent by kill to conica
# subdivide while it writes a 32 MB output, with the O_TMPFILE temporary
# and with the named one it falls back to (CONICA_TMPFILE=named): the
# tool is frozen with SIGSTOP as soon as it has the output open, the
# signal is queued, the tool continued. SIGKILL cannot be caught: it
# leaves the target as it was and nothing (O_TMPFILE) or at most one
# hidden .NAME.conica-tmp.XXXXXX, nothing a plain `ls` or a glob shows.
# Also: the output directory renamed during the write, a 250-byte output
# name. The per-signal details (SIGPIPE, a signal ignored at start) are
# unit tests in tests/test_cli.c.
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

# Start conica subdivide writing 32 MB (15 levels on 12 points) into $f in
# the background and freeze it with SIGSTOP as soon as it has a file open
# in $d (sets $pid; returns 1 when the run ended first). Its temporary has
# no name while it is written where the file system has O_TMPFILE, so the
# poll looks at the process's open files (/proc/PID/fd), not at the
# directory. A background job of a non-interactive shell starts with
# SIGINT and SIGQUIT ignored (the tools keep an ignored signal ignored):
# env resets them. `ulimit -c 0`: the signals whose default dumps core leave no
# core file. $1 (optional): CONICA_TMPFILE for the run ("named" forces
# the named temporary the tool falls back to without O_TMPFILE).
start_and_freeze() {
    env --default-signal CONICA_TMPFILE="${1:-}" sh -c 'ulimit -c 0; exec "$@"' sh \
        "$conica" subdivide -k 15 -o "$f" "$ex/ellipse.txt" >"$out" 2>"$err" </dev/null &
    pid=$!
    s_i=0
    while [ $s_i -lt 3000 ]; do
        for s_l in /proc/"$pid"/fd/*; do
            case $(readlink "$s_l" 2>/dev/null) in
            "$d"/*)
                kill -STOP "$pid" 2>/dev/null
                return 0
                ;;
            esac
        done
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.01
        s_i=$((s_i + 1))
    done
    kill -KILL "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    return 1
}

# Every signal whose default action ends the process (Linux numbers), by
# name as the message gives it: the terminal's, kill's, the timers', the
# resource limits', the user signals, the faults sent by kill, and two
# real-time signals (the message names them by number). SIGXFSZ is the
# ulimit -f case above.
for entry in HUP:1 INT:2 QUIT:3 ILL:4 TRAP:5 ABRT:6 BUS:7 FPE:8 USR1:10 SEGV:11 USR2:12 \
    PIPE:13 ALRM:14 TERM:15 STKFLT:16 XCPU:24 VTALRM:26 PROF:27 POLL:29 PWR:30 SYS:31 \
    RT34:34 RT64:64; do
    sig=${entry%%:*} n=${entry#*:}
    case $sig in RT*) name="signal $n" ;; *) name="SIG$sig" ;; esac
    for mode in tmpfile named; do
        begin_case "$name ($n) while writing ($mode temporary): removed, exit $((128 + n))"
        fresh "sig-$sig-$mode"
        if ! start_and_freeze "$([ $mode = named ] && echo named)"; then
            check_true "conica subdivide has its output open while 32 MB are written" false
            continue
        fi
        if [ $mode = named ]; then
            set -- "$d"/.result.out.conica-tmp.*
            check_true "the named fallback: .result.out.conica-tmp.XXXXXX exists" test -e "$1"
        else
            check_true "O_TMPFILE: the temporary has no name while it is written" \
                test "$(ls -A "$d")" = result.out
        fi
        kill -"$n" "$pid"
        kill -CONT "$pid"
        wait "$pid" 2>/dev/null
        st=$?
        h_cmd="conica subdivide -k 15 ... (sent $name)"
        check_true "exit status $st is 128 + $n" test "$st" -eq $((128 + n))
        check_grep "^conica: error: $f: stopped by $name; output not written \(the temporary file was removed\)" "$err"
        intact "$name"
    done
done

begin_case "SIGKILL while writing: the target intact, nothing left (O_TMPFILE)"
fresh sig-KILL
if start_and_freeze; then
    kill -KILL "$pid"
    kill -CONT "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    st=$?
    check_true "exit status $st is 137" test "$st" -eq 137
    intact "SIGKILL"
else
    check_true "conica subdivide has its output open while 32 MB are written" false
fi

begin_case "SIGKILL while writing (named fallback): only a hidden temporary"
fresh sig-KILL-named
if start_and_freeze named; then
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
    check_true "conica subdivide has its output open while 32 MB are written" false
fi

# The output directory renamed while the tool writes: the temporary was
# made through a handle on the directory, so the commit (or the signal's
# unlink) still finds it there and nothing is stranded.
for mode in tmpfile named; do
    begin_case "the output directory renamed during the write ($mode): nothing stranded"
    fresh "moved-$mode"
    if ! start_and_freeze "$([ $mode = named ] && echo named)"; then
        check_true "conica subdivide has its output open" false
        continue
    fi
    rm -rf "$d.moved"
    mv "$d" "$d.moved"
    kill -CONT "$pid"
    wait "$pid" 2>/dev/null
    st=$?
    check_true "exit status $st is 0" test "$st" -eq 0
    check_true "the renamed directory holds the new output and nothing else" \
        test "$(ls -A "$d.moved")" = result.out
    check_true "the new output is complete (a point file of 32 MB)" \
        sh -c 'test "$(wc -c <"$1")" -gt 30000000' sh "$d.moved/result.out"
    fresh "moved-sig-$mode"
    if ! start_and_freeze "$([ $mode = named ] && echo named)"; then
        check_true "conica subdivide has its output open" false
        continue
    fi
    rm -rf "$d.moved"
    mv "$d" "$d.moved"
    kill -TERM "$pid"
    kill -CONT "$pid"
    wait "$pid" 2>/dev/null
    st=$?
    check_true "SIGTERM after the rename: exit status $st is 143" test "$st" -eq 143
    check_true "SIGTERM after the rename: the old output alone in the renamed directory" \
        test "$(ls -A "$d.moved")" = result.out
done

begin_case "a valid 250-byte output name works (the temporary's name is cut to fit)"
long=$(printf '%0250d' 0 | tr 0 a)
for mode in tmpfile named; do
    fresh "long-$mode"
    check "$mode: conica subdivide -o <250 bytes>" env CONICA_TMPFILE="$([ $mode = named ] && echo named)" \
        "$conica" subdivide -k 2 -o "$d/$long" "$ex/ellipse.txt"
    check_true "$mode: the output exists, nothing else" test "$(ls -A "$d" | sort | tr '\n' ' ')" = "$long result.out "
done

finish
