#!/bin/sh
# SPDX-License-Identifier: MIT
# CLI suite for the documentation (README.md, docs/*.md, docs/man/*.1,
# docs/examples/*.c); docs/development.md ("The documentation test")
# describes it.
# usage (from the repository root): sh tests/cli/docs.sh BUILD_DIR
#
#  - manual pages: groff -ww -z -man (and mandoc -T lint -W warning when
#    mandoc is installed) print nothing;
#  - the --flags of each page equal those of the tool's option table
#    (--dump-options; conica: per subcommand, the page's `.SS "conica
#    NAME"` section);
#  - every relative link of README.md and docs/*.md names an existing file
#    (and a #fragment a heading of it);
#  - README.md has fewer than 350 lines;
#  - no file outside tests/ refers to the sibling shared-data directory;
#  - `make install` installs the manual pages;
#  - every ```sh runnable block of README.md and docs/*.md runs (sh -e) from
#    a scratch copy of the repository root (symbolic links, `build` pointing
#    at BUILD_DIR), each document's blocks in order in one directory; a
#    following ```text block (blank lines or up to two `...:` lines
#    between) is its expected stdout+stderr (`...` matches any text
#    within a line);
#  - every .nf block of each manual page's EXAMPLES section runs the same
#    way (OpenSCAD source there is rendered by openscad when installed);
#  - the pictures docs/ shows are the ones make demo makes now
#    (scripts/docs-pictures.sh; at most 1 pixel in 1000 differs);
#  - every docs/examples/*.c compiles against BUILD_DIR/lib/libconica.a and
#    runs; a ```c docs/examples/NAME.c block equals the file and a following
#    ```text block (required) its output;
#  - the comparison fails on a changed output (a document made here, and
#    library.md with one digit changed).
# In the sanitizer pass (BUILD_DIR ending in /san) only the examples run,
# with `cc` wrapped to add the sanitizer flags, and no output is compared:
# clang's build rounds some results differently in the last digits.
set -u
. "$(dirname "$0")/harness.sh"
root=$(pwd)
case "$build" in
/*) buildabs=$build ;;
*) buildabs=$root/$build ;;
esac
case "$build" in */san) san=1 ;; *) san=0 ;; esac
docs="README.md $(ls docs/*.md 2>/dev/null | tr '\n' ' ')"

# ---------------------------------------------------------------- helpers
# docs.py: links, blocks, comparison.
cat >"$tmp/docs.py" <<'EOF'
import os, re, sys, unicodedata

FENCE = re.compile(r'^(\s*)(`{3,}|~{3,})(.*)$')

def fenced(lines):
    """Yield (start_line, info, body_lines, end_line) of every fenced block
    and mark which lines are inside one."""
    out, i, n = [], 0, len(lines)
    while i < n:
        m = FENCE.match(lines[i])
        if m:
            fence, info = m.group(2), m.group(3).strip()
            j = i + 1
            while j < n and not lines[j].strip().startswith(fence):
                j += 1
            out.append((i + 1, info, lines[i + 1:j], j + 1))
            i = j + 1
        else:
            i += 1
    return out

def prose(lines):
    """Lines outside fenced blocks, with their numbers."""
    inside = set()
    for start, _, _, end in fenced(lines):
        inside.update(range(start, end + 1))
    return [(k + 1, l) for k, l in enumerate(lines) if k + 1 not in inside]

def slug(text):
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', text)  # link text only
    s = ''
    for ch in text.strip().lower():
        if ch.isalnum() or ch in ' -_' or unicodedata.category(ch).startswith('M'):
            s += ch
    return s.replace(' ', '-')

def anchors(path):
    lines = open(path, encoding='utf-8').read().split('\n')
    seen, out = {}, set()
    for _, l in prose(lines):
        m = re.match(r'^#{1,6}\s+(.*?)\s*#*\s*$', l)
        if m:
            a = slug(m.group(1))
            k = seen.get(a, 0)
            seen[a] = k + 1
            out.add(a if k == 0 else '%s-%d' % (a, k))
    return out

LINK = re.compile(r'\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')

def cmd_links(files):
    bad = 0
    for f in files:
        lines = open(f, encoding='utf-8').read().split('\n')
        for no, l in prose(lines):
            l = re.sub(r'`[^`]*`', '', l)  # inline code is no link
            for m in LINK.finditer(l):
                target = m.group(1)
                if re.match(r'^[a-z][a-z0-9+.-]*:', target):
                    continue  # http:, https:, mailto:
                path, _, frag = target.partition('#')
                full = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
                if not os.path.exists(full):
                    print('%s:%d: link to a missing file: %s' % (f, no, target))
                    bad += 1
                elif frag and full.endswith('.md') and frag not in anchors(full):
                    print('%s:%d: link to a missing heading: %s' % (f, no, target))
                    bad += 1
    sys.exit(1 if bad else 0)

def following_text(blocks, k, lines):
    """The ```text block right after block k: only blank lines between, or
    at most two lines that introduce it (ending in ':', as `Output:`)."""
    if k + 1 >= len(blocks):
        return None
    end = blocks[k][3]
    start, info, body, _ = blocks[k + 1]
    if info.split()[:1] != ['text']:
        return None
    between = [lines[i].strip() for i in range(end, start - 1) if lines[i].strip()]
    if len(between) > 2 or any(not b.endswith(':') for b in between):
        return None
    return body

def cmd_blocks(doc, outdir):
    """Write NNN.sh (+ NNN.expected) for every `sh runnable` block and
    print `NNN LINE` per block."""
    lines = open(doc, encoding='utf-8').read().split('\n')
    blocks = fenced(lines)
    n = 0
    for k, (start, info, body, _) in enumerate(blocks):
        if info.split()[:2] != ['sh', 'runnable']:
            continue
        n += 1
        base = os.path.join(outdir, '%03d' % n)
        open(base + '.sh', 'w').write('\n'.join(body) + '\n')
        exp = following_text(blocks, k, lines)
        if exp is not None:
            open(base + '.expected', 'w').write('\n'.join(exp) + '\n')
        print('%03d %d' % (n, start))

def cmd_cblocks(doc, outdir):
    """For every ```c docs/examples/NAME.c block: NAME.block (its body) and
    NAME.expected (a following text block); print `NAME LINE FILE`."""
    lines = open(doc, encoding='utf-8').read().split('\n')
    blocks = fenced(lines)
    for k, (start, info, body, _) in enumerate(blocks):
        words = info.split()
        if len(words) < 2 or words[0] != 'c':
            continue
        name = os.path.basename(words[1])[:-2]
        open(os.path.join(outdir, name + '.block'), 'w').write('\n'.join(body) + '\n')
        exp = following_text(blocks, k, lines)
        if exp is not None:
            open(os.path.join(outdir, name + '.expected'), 'w').write('\n'.join(exp) + '\n')
        print('%s %d %s' % (name, start, words[1]))

def match(want, got):
    parts = want.split('...')
    if len(parts) == 1:
        return want == got
    if not got.startswith(parts[0]) or not got.endswith(parts[-1]):
        return False
    pos, end = len(parts[0]), len(got) - len(parts[-1])
    for p in parts[1:-1]:
        i = got.find(p, pos, end)
        if i < 0:
            return False
        pos = i + len(p)
    return pos <= end

def cmd_compare(expected, actual):
    want = open(expected, encoding='utf-8').read().rstrip('\n').split('\n')
    got = open(actual, encoding='utf-8', errors='replace').read().rstrip('\n').split('\n')
    ok = len(want) == len(got) and all(match(w, g) for w, g in zip(want, got))
    if not ok:
        print('expected (%d lines):' % len(want))
        for w in want:
            print('  | ' + w)
        print('got (%d lines):' % len(got))
        for g in got:
            print('  | ' + g)
    sys.exit(0 if ok else 1)

ROFF = [('\\-', '-'), ('\\e', '\\'), ('\\(ha', '^'), ('\\(ti', '~'),
        ('\\(dq', '"'), ('\\(aq', "'"), ('\\&', '')]
SCAD = re.compile(r'^\s*(use|include)\s*<|;\s*$')

def cmd_manblocks(page, outdir):
    """Every .nf/.fi block of a page's EXAMPLES section as NNN.sh (command
    lines) or NNN.scad (OpenSCAD source: `use <...>` or lines ending in
    ';'), roff escapes undone; print `NNN LINE KIND` per block."""
    lines = open(page, encoding='utf-8').read().split('\n')
    inside, block, start, n = False, None, 0, 0
    for i, l in enumerate(lines):
        if l.startswith('.SH'):
            inside = l.split(None, 1)[1:] == ['EXAMPLES']
            continue
        if not inside:
            continue
        if l.startswith('.nf'):
            block, start = [], i + 1
        elif l.startswith('.fi') and block is not None:
            text = '\n'.join(block)
            for a, b in ROFF:
                text = text.replace(a, b)
            kind = 'scad' if any(SCAD.search(b) for b in text.split('\n')) else 'sh'
            n += 1
            open(os.path.join(outdir, '%03d.%s' % (n, kind)), 'w').write(text + '\n')
            print('%03d %d %s' % (n, start, kind))
            block = None
        elif block is not None and not l.startswith('.'):
            block.append(l)

cmd = sys.argv[1]
if cmd == 'manblocks':
    cmd_manblocks(sys.argv[2], sys.argv[3])
elif cmd == 'links':
    cmd_links(sys.argv[2:])
elif cmd == 'blocks':
    cmd_blocks(sys.argv[2], sys.argv[3])
elif cmd == 'cblocks':
    cmd_cblocks(sys.argv[2], sys.argv[3])
elif cmd == 'compare':
    cmd_compare(sys.argv[2], sys.argv[3])
EOF

# quiet CMD...: CMD exits 0 and prints nothing (its output is shown otherwise).
quiet() {
    "$@" >"$tmp/.quiet" 2>&1
    q_st=$?
    cat "$tmp/.quiet"
    [ "$q_st" -eq 0 ] && [ ! -s "$tmp/.quiet" ]
}

# flags: the --long-flags in stdin, one a line, sorted, unique. Manual page
# source writes a hyphen as \-; comment lines are left out.
flags() {
    grep -v '^\.\\"' | sed 's/\\-/-/g' | grep -o -e '--[a-z][a-z0-9-]*' | sort -u
}

# same_flags HELP PAGE: the two flag lists are equal (the difference shown).
same_flags() {
    if cmp -s "$1" "$2"; then
        return 0
    fi
    comm -23 "$1" "$2" | sed 's/^/in --help, not in the manual page: /'
    comm -13 "$1" "$2" | sed 's/^/in the manual page, not in --help: /'
    return 1
}

# section NAME FILE: the lines of the .SS/.SH section NAME of a page.
section() {
    awk -v want="$1" '
        /^\.S[HS][ \t]/ { cur = $0; sub(/^\.S[HS][ \t]+/, "", cur); gsub(/"/, "", cur)
                          inside = (cur == want); next }
        inside { print }' "$2"
}

# outside_sections FILE NAMES...: the lines of a page outside those sections.
outside_sections() {
    f=$1
    shift
    awk -v names="|$(printf '%s|' "$@")" '
        /^\.S[HS][ \t]/ { cur = $0; sub(/^\.S[HS][ \t]+/, "", cur); gsub(/"/, "", cur)
                          inside = (index(names, "|" cur "|") > 0); next }
        !inside { print }' "$f"
}

if [ "$san" -eq 0 ]; then
# ---------------------------------------------------------------- man pages
begin_case "manual pages: groff (and mandoc) report no warning"
pages=$(ls docs/man/*.1 2>/dev/null)
check_true "docs/man holds the three pages" test -f docs/man/conica.1 -a -f docs/man/svgsmooth.1 -a -f docs/man/scadprofile.1
if command -v groff >/dev/null 2>&1; then
    for p in $pages; do
        check "groff -ww -z -man $p" quiet groff -ww -z -man "$p"
    done
else
    check_true "groff is installed (Debian: groff-base)" false
fi
if command -v mandoc >/dev/null 2>&1; then
    for p in $pages; do
        check "mandoc -T lint $p" quiet mandoc -T lint -W warning "$p"
    done
fi

# table_flags [all]: the --long-flags of the option table in stdin (a
# tool's --dump-options, which --help is made from), --help and --version
# left out unless "all".
table_flags() {
    awk -F '\t' -v all="${1:-}" '$1 == "opt" && $3 != "-" && (all != "" || ($3 != "help" && $3 != "version")) { print "--" $3 }' | sort -u
}

begin_case "manual pages: the same --flags as each tool's option table (--help)"
for tool in svgsmooth scadprofile; do
    "$build/bin/$tool" --dump-options 2>&1 | table_flags all >"$tmp/$tool.help"
    flags <"docs/man/$tool.1" >"$tmp/$tool.page"
    check_true "$tool --help lists flags" test -s "$tmp/$tool.help"
    check "$tool(1) and $tool --help name the same flags" same_flags "$tmp/$tool.help" "$tmp/$tool.page"
done
subcommands=$("$build/bin/conica" --help 2>&1 | awk '/^Commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { on = 0 }')
check_true "conica --help lists its commands" test -n "$subcommands"
names=""
: >"$tmp/conica.allhelp"
for c in $subcommands; do
    names="$names|conica $c"
    section "conica $c" docs/man/conica.1 >"$tmp/conica-$c.sec"
    check_true "conica(1) has a section .SS \"conica $c\"" test -s "$tmp/conica-$c.sec"
    "$build/bin/conica" "$c" --dump-options 2>&1 | table_flags >"$tmp/conica-$c.help"
    cat "$tmp/conica-$c.help" >>"$tmp/conica.allhelp"
    flags <"$tmp/conica-$c.sec" >"$tmp/conica-$c.page"
    check "conica(1) section 'conica $c' and conica $c --help name the same flags" \
        same_flags "$tmp/conica-$c.help" "$tmp/conica-$c.page"
done
# The rest of the page: conica --help's own flags appear in it; any flag it
# names is one some command's --help names.
"$build/bin/conica" --dump-options 2>&1 | awk '$1 == "tool" { n++ } n == 1' | table_flags all >"$tmp/conica.tophelp"
(IFS='|'; set -f; outside_sections docs/man/conica.1 $names) | flags >"$tmp/conica.toppage"
sort -u "$tmp/conica.allhelp" "$tmp/conica.tophelp" -o "$tmp/conica.allhelp"
check_true "conica(1) names every flag of conica --help" \
    test -z "$(comm -23 "$tmp/conica.tophelp" "$tmp/conica.toppage")"
comm -12 "$tmp/conica.toppage" "$tmp/conica.allhelp" >"$tmp/conica.topok"
check "conica(1) outside the command sections names only flags of some --help" \
    same_flags "$tmp/conica.topok" "$tmp/conica.toppage"

begin_case "make install installs the manual pages"
check "make install into a staging directory" \
    make --no-print-directory BUILD="$build" PREFIX=/usr DESTDIR="$tmp/stage" install
for p in $pages; do
    check_true "installed share/man/man1/${p##*/}" cmp -s "$p" "$tmp/stage/usr/share/man/man1/${p##*/}"
done

# ---------------------------------------------------------------- licences
begin_case "every source file carries an SPDX licence line, and the licences agree"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files '*.c' '*.h' '*.cpp' '*.py' '*.sh' '*.mk' Makefile '*.1' .ci/run '*.toml' >"$tmp/sources"
    : >"$tmp/nospdx"
    while IFS= read -r f; do
        case "$f" in
            blender_addon/*|tests/blender/*|bench/bench_blender.py) want=GPL-3.0-or-later ;;
            *) want=MIT ;;
        esac
        head -n 3 "$f" | grep -Eq "SPDX-License-Identifier: $want( |\$)" || printf '%s (wants %s)\n' "$f" "$want" >>"$tmp/nospdx"
    done <"$tmp/sources"
    check_true "no source file lacks its SPDX line: $(head -n 5 "$tmp/nospdx" | tr '\n' ' ')" test ! -s "$tmp/nospdx"
fi
check_true "LICENSE is the MIT licence" grep -q '^MIT License' LICENSE
check_true "blender_addon/conica/LICENSE is the GPL version 3" grep -q 'GNU GENERAL PUBLIC LICENSE' blender_addon/conica/LICENSE
check_true "the Blender manifest says GPL-3.0-or-later" grep -q '^license = \["SPDX:GPL-3.0-or-later"\]' blender_addon/conica/blender_manifest.toml
check_true "conica.pc says MIT" grep -q 'SPDX-License-Identifier: MIT' "$build/conica.pc"
for p in docs/man/*.1; do
    check_true "${p##*/} names the MIT licence" grep -q 'under the MIT licence' "$p"
done

# ---------------------------------------------------------------- the markdown
begin_case "relative links in README.md and docs/*.md resolve"
# shellcheck disable=SC2086 # the list is words
check "every relative link names an existing file and heading" "$PY" "$tmp/docs.py" links $docs

begin_case "README.md stays short"
lines=$(wc -l <README.md)
check_true "README.md has $lines lines (fewer than 350)" test "$lines" -lt 350

begin_case "no file outside tests/ refers to the shared-data sibling directory"
# The benchmarks and the diagnostics demo measure against the reference data
# when it is there, as the tests do, and say so when it is not: they are the
# other readers of it (bench/, scripts/demo-diagnostics.sh).
pattern='../shared'
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    check_exit 1 "git grep finds no '$pattern' outside tests/ and the benchmarks" \
        git grep -n -F -e "$pattern" -- . ':!tests/' ':!bench/' ':!scripts/demo-diagnostics.sh'
else
    check_exit 1 "grep finds no '$pattern' outside tests/ (not a git checkout)" \
        grep -rn -F -e "$pattern" --exclude-dir=tests --exclude-dir=.git --exclude-dir=build \
        --exclude-dir=bench --exclude=demo-diagnostics.sh .
fi
fi

# ---------------------------------------------------------------- runnable examples
# A scratch root: the repository's top-level entries as symbolic links,
# `build` the build under test; in the sanitizer pass `cc` adds the flags.
mkroot() { # dir
    mkdir -p "$1"
    for e in "$root"/* "$root"/.[!.]*; do
        [ -e "$e" ] || continue
        case "${e##*/}" in build | .git) continue ;; esac
        ln -s "$e" "$1/${e##*/}"
    done
    ln -s "$buildabs" "$1/build"
}
wrap=$tmp/wrap
mkdir -p "$wrap"
san_flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
if [ "$san" -eq 1 ]; then
    printf '#!/bin/sh\nexec clang %s "$@"\n' "$san_flags" >"$wrap/cc"
    chmod +x "$wrap/cc"
fi
run_timeout=""
command -v timeout >/dev/null 2>&1 && run_timeout="timeout 60"

for doc in $docs; do
    bdir=$tmp/blocks/$(printf '%s' "$doc" | tr '/.' '__')
    mkdir -p "$bdir"
    "$PY" "$tmp/docs.py" blocks "$doc" "$bdir" >"$bdir/list" || {
        begin_case "runnable examples of $doc"
        check_true "$doc: its blocks can be read" false
        continue
    }
    [ -s "$bdir/list" ] || continue
    begin_case "runnable examples of $doc"
    mkroot "$bdir/root"
    while read -r n line; do
        # shellcheck disable=SC2086 # run_timeout is words
        check "$doc:$line: the sh runnable block runs" sh -c \
            'cd "$1" && PATH="$2:$3/bin:$PATH" exec $4 sh -e "$5" 2>&1' sh \
            "$bdir/root" "$wrap" "$buildabs" "$run_timeout" "$bdir/$n.sh"
        cp "$out" "$bdir/$n.out"
        if [ -f "$bdir/$n.expected" ] && [ "$san" -eq 0 ]; then
            check "$doc:$line: its output is the text block below it" \
                "$PY" "$tmp/docs.py" compare "$bdir/$n.expected" "$bdir/$n.out"
        fi
    done <"$bdir/list"
done

# ---------------------------------------------------------------- man-page examples
# Each page's EXAMPLES blocks run in order in one scratch root, as the docs'
# blocks do; an OpenSCAD source block (the page shows a model using what the
# commands before it wrote) is rendered by openscad there, when installed.
for page in docs/man/*.1; do
    bdir=$tmp/man/$(basename "$page")
    mkdir -p "$bdir"
    "$PY" "$tmp/docs.py" manblocks "$page" "$bdir" >"$bdir/list" || {
        begin_case "the EXAMPLES of $page run"
        check_true "$page: its examples can be read" false
        continue
    }
    begin_case "the EXAMPLES of $page run"
    check_true "$page has examples" test -s "$bdir/list"
    mkroot "$bdir/root"
    while read -r n line kind; do
        if [ "$kind" = scad ]; then
            if ! command -v openscad >/dev/null 2>&1; then
                echo "note: $page:$line: openscad not installed, its OpenSCAD example not rendered"
                continue
            fi
            cp "$bdir/$n.scad" "$bdir/root/example-$n.scad"
            # shellcheck disable=SC2086 # run_timeout is words
            check "$page:$line: the OpenSCAD example renders" sh -c \
                'cd "$1" && exec $2 openscad -o "example-$3.stl" "example-$3.scad" 2>&1' sh \
                "$bdir/root" "$run_timeout" "$n"
        else
            case "$(cat "$bdir/$n.sh")" in
            *openscad*)
                if ! command -v openscad >/dev/null 2>&1; then
                    echo "note: $page:$line: openscad not installed, example not run"
                    continue
                fi ;;
            esac
            # shellcheck disable=SC2086 # run_timeout is words
            check "$page:$line: the example runs" sh -c \
                'cd "$1" && PATH="$2:$3/bin:$PATH" exec $4 sh -e "$5" 2>&1' sh \
                "$bdir/root" "$wrap" "$buildabs" "$run_timeout" "$bdir/$n.sh"
        fi
    done <"$bdir/list"
done

# ---------------------------------------------------------------- pictures
# Every picture docs/ shows that make demo (or the shown command) makes is
# what the build under test makes now: at most 1 pixel in 1000 differs by
# more than 1/8 of full scale (scripts/pngdiff.py).
if [ "$san" -eq 0 ]; then
    begin_case "the pictures in docs/ are the ones make demo makes (make docs-pictures)"
    if ! command -v rsvg-convert >/dev/null 2>&1; then
        skip_case "rsvg-convert not installed"
    elif check "scripts/docs-pictures.sh makes the pictures" \
        env CONICA_SHARED_DATA="${CONICA_SHARED_DATA:-../shared/data}" \
        sh scripts/docs-pictures.sh make "$build" "$tmp/pics"; then
        grep '^note:' "$out"
        scripts/docs-pictures.sh list | while read -r pic kind src; do
            [ -f "$tmp/pics/$pic" ] || continue
            diffs=$("$PY" scripts/pngdiff.py "$pic" "$tmp/pics/$pic" 2>&1 | tail -n 1)
            size=$("$PY" -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); w,h=struct.unpack(">II",d[16:24]); print(w*h)' "$pic")
            echo "$pic $diffs $size"
        done >"$tmp/pics.txt"
        while read -r pic diffs size; do
            case "$diffs$size" in
            '' | *[!0-9]*) check_true "$pic can be compared (pngdiff: $diffs)" false ;;
            *) check_true "$pic is current ($diffs of $size pixels differ)" \
                test $((diffs * 1000)) -le "$size" ;;
            esac
        done <"$tmp/pics.txt"
    fi
fi

# ---------------------------------------------------------------- C examples
begin_case "docs/examples/*.c compile against libconica.a and run"
if [ "$san" -eq 1 ]; then
    # shellcheck disable=SC2086
    set -- clang $san_flags
else
    set -- "${CC:-cc}"
fi
for src in docs/examples/*.c; do
    [ -f "$src" ] || continue
    name=$(basename "$src" .c)
    check "compile $src" "$@" -std=c11 -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror \
        -Ilibcore/include "$src" "$build/lib/libconica.a" -llapacke -lm -o "$tmp/example-$name"
    check "run $src" "$tmp/example-$name"
    cp "$out" "$tmp/example-$name.out"
done
if [ "$san" -eq 0 ]; then
    for doc in $docs; do
        cdir=$tmp/cblocks/$(printf '%s' "$doc" | tr '/.' '__')
        mkdir -p "$cdir"
        "$PY" "$tmp/docs.py" cblocks "$doc" "$cdir" >"$cdir/list" || continue
        while read -r name line file; do
            check_true "$doc:$line: the block equals $file" cmp -s "$cdir/$name.block" "$file"
            # a C example shows its output, and the output is what it prints
            check_true "$doc:$line: an output block follows $file" test -f "$cdir/$name.expected"
            if [ -f "$cdir/$name.expected" ]; then
                check "$doc: the output below $file is what it prints" \
                    "$PY" "$tmp/docs.py" compare "$cdir/$name.expected" "$tmp/example-$name.out"
            fi
        done <"$cdir/list"
    done

    begin_case "the comparison fails on a changed output (shown here)"
    # a document whose block prints 42 under a text block that says 43
    mkdir -p "$tmp/fail/blocks"
    cat >"$tmp/fail/doc.md" <<'DOC'
The answer:

```sh runnable
echo 42
```

Output:

```text
43
```
DOC
    "$PY" "$tmp/docs.py" blocks "$tmp/fail/doc.md" "$tmp/fail/blocks" >/dev/null
    sh "$tmp/fail/blocks/001.sh" >"$tmp/fail/001.out" 2>&1
    check_true "the block's text block is found (through an 'Output:' line)" test -f "$tmp/fail/blocks/001.expected"
    check_exit 1 "echo 42 against a shown 43: the comparison fails" \
        "$PY" "$tmp/docs.py" compare "$tmp/fail/blocks/001.expected" "$tmp/fail/001.out"
    # docs/library.md's path.c output with its first digit changed
    "$PY" - docs/library.md "$tmp/fail/library.md" <<'PY'
import re, sys
text = open(sys.argv[1], encoding='utf-8').read()
at = text.index('```c docs/examples/path.c')
out = text.index('```text', text.index('\n```\n', at))
digit = re.search(r'[0-9]', text[out:])
k = out + digit.start()
changed = text[:k] + str((int(text[k]) + 1) % 10) + text[k + 1:]
open(sys.argv[2], 'w', encoding='utf-8').write(changed)
print('changed line: ' + changed[k - changed[:k][::-1].index('\n'):changed.index('\n', k)])
PY
    mkdir -p "$tmp/fail/c"
    "$PY" "$tmp/docs.py" cblocks "$tmp/fail/library.md" "$tmp/fail/c" >/dev/null
    check_exit 1 "docs/library.md with one digit of path.c's output changed: the comparison fails" \
        "$PY" "$tmp/docs.py" compare "$tmp/fail/c/path.expected" "$tmp/example-path.out"
    check_grep "^expected \(" "$out" "the failure shows the expected lines"
fi

finish
