#!/bin/sh
# SPDX-License-Identifier: MIT
# scripts/completions.sh BIN_DIR OUT_DIR - bash and zsh completions for
# conica, svgsmooth and scadprofile, made from their option tables
# (`TOOL --dump-options`, libcore/tools/cli_opt.h): OUT_DIR/bash/TOOL and
# OUT_DIR/zsh/_TOOL. Run by `make completions` (and so by `make install`,
# which puts them where bash-completion and zsh look under PREFIX).
# Options, their values (file names, the words an option takes) and the
# operands (SVG files, any file, conica's commands) are completed.
set -eu
bin=$1
outdir=$2
mkdir -p "$outdir/bash" "$outdir/zsh"

for tool in conica svgsmooth scadprofile; do
    [ -x "$bin/$tool" ] || continue
    "$bin/$tool" --dump-options >"$outdir/$tool.table"

    # ------------------------------------------------------------ bash
    awk -F '\t' -v tool="$tool" '
    function key(prog) { k = prog; sub("^" tool " ?", "", k); return k }
    function files(kind) {
        if (kind == "svg")
            return "COMPREPLY=($(compgen -f -X \"!*.[sS][vV][gG]\" -- \"$cur\") $(compgen -d -- \"$cur\"))"
        if (kind == "file")
            return "COMPREPLY=($(compgen -f -- \"$cur\"))"
        w = kind; gsub(/\|/, " ", w)
        return "COMPREPLY=($(compgen -W \"" w "\" -- \"$cur\"))"
    }
    $1 == "tool" { k = key($2); keys[++nk] = k; operands[k] = $3; next }
    $1 == "cmd" { cmds = cmds (cmds == "" ? "" : " ") $2; next }
    $1 == "opt" {
        if ($3 != "-") words[k] = words[k] " --" $3
        if ($2 != "-") words[k] = words[k] " -" $2
        if ($4 == "required") {
            act = $6 == "-" ? "return 0" : files($6) "; return 0"
            if ($3 != "-") values = values "    \"" k "|--" $3 "\") " act " ;;\n"
            if ($2 != "-") values = values "    \"" k "|-" $2 "\") " act " ;;\n"
        }
    }
    END {
        f = "_conica_complete_" tool
        print "# bash completion for " tool " (made by scripts/completions.sh from its option table)"
        print f "() {"
        print "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD-1]} cmd= i"
        print "    COMPREPLY=()"
        print "    # --opt=VALUE: bash splits at the ="
        print "    if [[ $prev == = ]]; then prev=${COMP_WORDS[COMP_CWORD-2]}; fi"
        print "    if [[ $cur == = ]]; then prev=${COMP_WORDS[COMP_CWORD-1]}; cur=; fi"
        if (cmds != "") {
            print "    for ((i = 1; i < COMP_CWORD; i++)); do"
            print "        case ${COMP_WORDS[i]} in -*) ;; *) cmd=${COMP_WORDS[i]}; break ;; esac"
            print "    done"
        }
        print "    case \"$cmd|$prev\" in"
        printf "%s", values
        print "    esac"
        print "    case \"$cmd|$cur\" in"
        for (i = 1; i <= nk; i++) {
            k = keys[i]
            print "    \"" k "|\"-*) COMPREPLY=($(compgen -W \"" substr(words[k], 2) "\" -- \"$cur\")); return 0 ;;"
        }
        print "    esac"
        print "    case $cmd in"
        for (i = 1; i <= nk; i++) {
            k = keys[i]
            if (k == "" && cmds != "")
                print "    \"\") COMPREPLY=($(compgen -W \"" cmds "\" -- \"$cur\")) ;;"
            else if (operands[k] != "-")
                print "    \"" k "\") " files(operands[k]) " ;;"
        }
        print "    esac"
        print "}"
        print "complete -o filenames -F " f " " tool
    }' "$outdir/$tool.table" >"$outdir/bash/$tool"

    # ------------------------------------------------------------- zsh
    awk -F '\t' -v tool="$tool" '
    function key(prog) { k = prog; sub("^" tool " ?", "", k); return k }
    function clean(s,    out, i, c) { # without the characters zsh specs give a meaning
        out = ""
        for (i = 1; i <= length(s); i++) {
            c = substr(s, i, 1)
            if (index("[]:\047\\`$", c) == 0) out = out c
        }
        return out
    }
    function value(kind, meta) {
        if (kind == "svg") return ":" meta ":_files -g \"*.(svg|SVG)\""
        if (kind == "file") return ":" meta ":_files"
        if (kind == "-") return ":" meta ": "
        w = kind; gsub(/\|/, " ", w)
        return ":" meta ":(" w ")"
    }
    function operand(kind) {
        if (kind == "-") return ""
        if (kind == "svg") return " \\\n    \047*:SVG file:_files -g \"*.(svg|SVG)\"\047"
        if (kind == "file") return " \\\n    \047*:file:_files\047"
        w = kind; gsub(/\|/, " ", w)
        return " \\\n    \0471:word:(" w ")\047"
    }
    $1 == "tool" { k = key($2); keys[++nk] = k; specs[k] = ""; operands[k] = $3; next }
    $1 == "cmd" { cmds = cmds " \\\n      \047" $2 "[" clean($3) "]\047"; next }
    $1 == "opt" {
        h = "[" clean($7) "]"
        v = $4 == "none" ? "" : value($6, $5 == "-" ? "value" : clean($5))
        if ($4 == "optional") v = ":" v
        lng = $3 == "-" ? "" : "--" $3 ($4 == "required" ? "=" : $4 == "optional" ? "=-" : "")
        sht = $2 == "-" ? "" : "-" $2 ($4 == "none" ? "" : "+")
        if (lng != "" && sht != "")
            s = "\047(-" $2 " --" $3 ")\047{" sht "," lng "}\047" h v "\047"
        else
            s = "\047" lng sht h v "\047"
        specs[k] = specs[k] " \\\n    " s
    }
    END {
        print "#compdef " tool
        print "# zsh completion for " tool " (made by scripts/completions.sh from its option table)"
        print "_conica_complete_" tool "() {"
        if (cmds == "") {
            print "  _arguments -s -S" specs[""] operand(operands[""])
        } else {
            print "  local curcontext=$curcontext state line"
            print "  _arguments -C -s -S" specs[""] " \\\n    \0471:command:->command\047 \\\n    \047*::argument:->argument\047"
            print "  case $state in"
            print "  command) _values command" cmds " ;;"
            print "  argument)"
            print "    case $line[1] in"
            for (i = 1; i <= nk; i++) {
                k = keys[i]
                if (k == "") continue
                print "    " k ") _arguments -s -S" specs[k] operand(operands[k]) " ;;"
            }
            print "    esac ;;"
            print "  esac"
        }
        print "}"
        print "_conica_complete_" tool " \"$@\""
    }' "$outdir/$tool.table" >"$outdir/zsh/_$tool"
    rm -f "$outdir/$tool.table"
done
