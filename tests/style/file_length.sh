#!/usr/bin/env bash
# Every C source and header under lib/, tools/ and fmu/ (in any sub-folder) is at most MAX lines (1000):
# a file longer than that holds more than one part, and its parts belong in files of their own.
# Usage: file_length.sh SOURCE_DIR [MAX]   (exit 1 and one line per long file)
#        file_length.sh --self-check        (the check itself, on a tree it writes in a temporary
#                                           folder: files of MAX and MAX + 1 lines, one without a
#                                           final newline, in sub-folders of lib/ and tools/)
set -euo pipefail

# SOURCE_DIR MAX: one line per .c/.h file of SOURCE_DIR/{lib,tools,fmu}/** longer than MAX lines;
# status 1 if any. A last line without a newline counts as a line.
long_files() {
    local src=$1 max=$2 file n status=0
    while IFS= read -r -d '' file; do
        n=$(awk 'END { print NR }' "$file")
        if ((n > max)); then
            echo "${file#"$src"/}: $n lines (at most $max)"
            status=1
        fi
    done < <(find "$src/lib" "$src/tools" $([ -d "$src/fmu" ] && echo "$src/fmu") \( -name '*.c' -o -name '*.h' \) -print0 | sort -z)
    return $status
}

if [ "${1:-}" = --self-check ]; then
    tree=$(mktemp -d)
    trap 'rm -rf "$tree"' EXIT
    mkdir -p "$tree/lib/sim/parts" "$tree/tools/plot"
    lines() { seq -f '/* line %g */' 1 "$1"; }
    lines 1000 >"$tree/lib/sim/parts/at_the_limit.c"           # allowed
    lines 1001 >"$tree/lib/sim/one_too_many.h"                   # reported
    lines 1000 >"$tree/tools/plot/no_final_newline.c"            # 1001 lines, the last one without
    printf '/* line 1001 */' >>"$tree/tools/plot/no_final_newline.c" # a newline: reported
    lines 2000 >"$tree/tools/plot/notes.txt"                     # not C: not read
    want=$'lib/sim/one_too_many.h: 1001 lines (at most 1000)\ntools/plot/no_final_newline.c: 1001 lines (at most 1000)'
    if got=$(long_files "$tree" 1000); then
        echo "FAIL: the check passed files of 1001 lines"
        exit 1
    fi
    if [ "$got" != "$want" ]; then
        printf 'FAIL: the check reported\n%s\ninstead of\n%s\n' "$got" "$want"
        exit 1
    fi
    echo "ok:   the check reports files of 1001 lines in sub-folders of lib/ and tools/ and allows 1000"
    exit 0
fi
src=${1:?usage: file_length.sh SOURCE_DIR [MAX] | --self-check}
max=${2:-1000}
if long_files "$src" "$max"; then
    echo "ok:   every .c and .h file under lib/, tools/ and fmu/ is at most $max lines"
    exit 0
fi
exit 1
