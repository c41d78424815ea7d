#!/usr/bin/env bash
# Formats every C source with the checked-in .clang-format (apt-get install clang-format), except
# third_party/: the FMI standard's headers stay byte for byte as published.
#   scripts/format.sh          reformat in place
#   scripts/format.sh --check  list files that differ, exit 1 if any
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
files=$(git ls-files '*.c' '*.h' ':!:third_party/*')
if [ "${1:-}" = "--check" ]; then
    bad=0
    for f in $files; do
        clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || { echo "$f"; bad=1; }
    done
    exit $bad
fi
clang-format -i $files
