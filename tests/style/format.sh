#!/usr/bin/env bash
# Every C source and header is laid out as the checked-in .clang-format says (scripts/format.sh
# reformats them). Exit 1 listing the files that are not; exit 77 (skipped) without clang-format
# 14, the version of Debian 12 the tree is formatted with: other versions lay out some constructs
# differently, so their verdict would not be the project's.
# Usage: format.sh SOURCE_DIR
set -euo pipefail
src=${1:?usage: format.sh SOURCE_DIR}
if ! command -v clang-format >/dev/null; then
    echo "skipped: clang-format is not installed (apt-get install clang-format)"
    exit 77
fi
version=$(clang-format --version | sed -nE 's/.*version ([0-9]+)\..*/\1/p')
if [ "$version" != 14 ]; then
    echo "skipped: clang-format ${version:-of unknown version}; the tree is formatted with clang-format 14"
    exit 77
fi
mapfile -d '' files < <(find "$src/include" "$src/lib" "$src/tools" "$src/fmu" "$src/tests" "$src/fuzz" "$src/examples" \
    \( -name '*.c' -o -name '*.h' \) -print0 | sort -z)
# one run over all files; each line a formatting violation reports starts "FILE:LINE:COLUMN:"
if report=$(clang-format --style=file --dry-run -Werror "${files[@]}" 2>&1); then
    echo "ok:   ${#files[@]} C files formatted as .clang-format says"
    exit 0
fi
bad=$(printf '%s\n' "$report" | sed -nE 's/^(.*):[0-9]+:[0-9]+: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ -z "$bad" ]; then
    printf 'FAIL: clang-format failed:\n%s\n' "$report"
    exit 1
fi
while IFS= read -r f; do
    echo "not formatted: ${f#"$src"/}"
done <<<"$bad"
echo "reformat them with scripts/format.sh"
exit 1
