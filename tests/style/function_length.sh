#!/usr/bin/env bash
# Every function in lib/ is at most MAX lines, signature to closing brace (the style rule "small
# functions with one job"). The code is formatted by .clang-format (Linux braces): a function body
# opens with "{" alone at column 0 and closes with "}" alone at column 0, and its signature starts on
# the first line after the previous top-level declaration, comment or blank line.
# Usage: function_length.sh SOURCE_DIR [MAX]   (exit 1 and one line per long function)
set -euo pipefail
src=${1:?usage: function_length.sh SOURCE_DIR [MAX]}
max=${2:-80}
status=0
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
done < <(find "$src/lib" -name '*.c' -print0 | sort -z)
exit $status
