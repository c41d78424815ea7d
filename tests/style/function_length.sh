#!/usr/bin/env bash
# Every function in lib/, tools/ and fmu/ is at most MAX lines, signature to closing brace (the style rule "small
# functions with one job"). The code is formatted by .clang-format (Linux braces): a function body
# opens with "{" alone at column 0 and closes with "}" alone at column 0, and its signature starts on
# the first line after the previous top-level declaration, comment or blank line.
# Usage: function_length.sh SOURCE_DIR [MAX]   (exit 1 and one line per long function)
#        function_length.sh --self-check        (the check itself, on fixtures/{lib,tools}/long.c)
set -euo pipefail

# SOURCE_DIR MAX: one line per function of SOURCE_DIR/{lib,tools}/**.c longer than MAX; status 1 if any.
long_functions() {
    local src=$1 max=$2 file status=0
    while IFS= read -r -d '' file; do
        awk -v max="$max" -v file="${file#"$src"/}" '
            /^[A-Za-z_].*\(/ && !in_body && start == 0 { start = FNR; name = $0 }
            /^[[:space:]]*$/ && !in_body { start = 0 }
            /;[[:space:]]*$/ && !in_body { start = 0 }
            /^\{[[:space:]]*$/ && start > 0 { in_body = 1 }
            /^\}/ && in_body {
                n = FNR - start + 1
                if (n > max) {
                    sub(/\(.*/, "", name); sub(/.*[ *]/, "", name)
                    printf "%s:%d: %s is %d lines (at most %d)\n", file, start, name, n, max
                    bad = 1
                }
                in_body = 0; start = 0
            }
            END { exit bad }
        ' "$file" || status=1
    done < <(find "$src/lib" "$src/tools" $([ -d "$src/fmu" ] && echo "$src/fmu") -name '*.c' -print0 | sort -z)
    return $status
}

if [ "${1:-}" = --self-check ]; then
    # lib's at_the_limit is 80 lines (allowed), one_too_many 81; tools' tool_too_long 81: the two
    # lines reported.
    fixtures=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/fixtures
    want=$(printf '%s\n%s' "lib/long.c:88: one_too_many is 81 lines (at most 80)" \
        "tools/long.c:5: tool_too_long is 81 lines (at most 80)")
    if got=$(long_functions "$fixtures" 80); then
        echo "FAIL: the check passed a function of 81 lines"
        exit 1
    fi
    if [ "$got" != "$want" ]; then
        printf 'FAIL: the check reported\n%s\ninstead of\n%s\n' "$got" "$want"
        exit 1
    fi
    echo "ok:   the check reports a function of 81 lines in lib/ and in tools/ and allows one of 80"
    exit 0
fi
long_functions "${1:?usage: function_length.sh SOURCE_DIR [MAX] | --self-check}" "${2:-80}"
