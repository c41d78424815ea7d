#!/usr/bin/env bash
# The shipped cases write no path from outside the checkout into their output files. The case
# text (the case with its @include files expanded, comments and all) is stored in every output
# file: the HDF5 attributes and the CSV footer of 'touchdown run' and 'touchdown modal'. A comment
# that points at a file outside the project would be copied into every result a user shares.
# Every shipped case (cases/*.cfg but the machine-only rig.cfg) is run for a few milliseconds,
# given by its absolute path (the include annotation names $src/cases/rig.cfg, inside the
# checkout), and every absolute path in its HDF5 attributes (h5dump -A), CSV header and footer
# and events CSV must lie inside the checkout. (A path of the machine the files were written on,
# like the output directory, is no part of them: run in a scratch directory outside $src.)
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$(cd "$2" && pwd -P)
work=$(mktemp -d "${PWD}/output-paths.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# Absolute paths in the text on stdin: a '/' at the start or after a blank, quote, bracket, '=',
# ':' or ',', followed by a name ('m/s', '0.02/0.10', '1/(2 pi)' and '// comment' are not paths).
absolute_paths() {
    grep -oE "(^|[][[:space:]\"'(=:,])/[A-Za-z0-9._~+-]+(/[A-Za-z0-9._~+-]*)*" | sed -E "s#^[^/]##" | sort -u
}

# Every absolute path in the text lies inside $src. An HDF5 file's own object names (/time,
# /events: dimension-scale references and axis descriptions name them) are not file paths: the
# optional NAMES file lists them, one a line, and they are passed over.
check_text() { # WHAT TEXTFILE [NAMES]
    local what=$1 text=$2 names=${3:-/dev/null} outside
    outside=$(absolute_paths <"$text" | awk -v src="$src" 'index($0, src "/") != 1 && $0 != src' |
        grep -vxF -f "$names")
    if [ -n "$outside" ]; then
        fail "$what: absolute path(s) outside the checkout: $(echo "$outside" | head -n 5 | tr '\n' ' ')"
    else
        pass "$what: no absolute path outside the checkout"
    fi
}

need h5dump hdf5-tools
need h5ls hdf5-tools

# The CSV text a writer adds besides the numbers: the header line and the '#' lines.
csv_text() { grep -E '^#' "$1"; head -n 1 "$1"; }

check_outputs() { # NAME PREFIX CSV-HAS-CASE-TEXT (1: a run's CSV, whose footer holds the case text)
    local name=$1 prefix=$2 text=$3
    if [ -s "$prefix.csv" ] && { [ "$text" = 0 ] || grep -q '^#| ' "$prefix.csv"; }; then
        csv_text "$prefix.csv" >"$prefix.csv-text"
        check_text "$name: $(basename "$prefix").csv header and footer" "$prefix.csv-text"
    else
        fail "$name: no CSV with the case text at $prefix.csv"
    fi
    if [ -s "$prefix.events.csv" ]; then
        csv_text "$prefix.events.csv" >"$prefix.events-text"
        check_text "$name: $(basename "$prefix").events.csv header" "$prefix.events-text"
    fi
    if (cd "$(dirname "$prefix")" && h5dump -A "$(basename "$prefix").h5") >"$prefix.h5-text" 2>&1 &&
        grep -q case_text "$prefix.h5-text" &&
        h5ls -r "$prefix.h5" | awk '{ print $1 }' | grep '^/' >"$prefix.h5-names"; then
        check_text "$name: $(basename "$prefix").h5 attributes" "$prefix.h5-text" "$prefix.h5-names"
    else
        fail "$name: no HDF5 file with a case_text attribute at $prefix.h5"
    fi
}

# The check itself finds a path outside the checkout.
printf '# see /elsewhere/notes.md and m/s, 0.02/0.10, 1/(2 pi), // a comment, %s/cases/rig.cfg\n' "$src" >"$work/probe"
[ "$(absolute_paths <"$work/probe" | awk -v src="$src" 'index($0, src "/") != 1')" = /elsewhere/notes.md ] &&
    pass "the check finds /elsewhere/notes.md and nothing else in a probe line" || fail "the path finder on a probe line"

n=0
for cfg in "$src"/cases/*.cfg; do
    name=$(basename "$cfg" .cfg)
    [ "$name" = rig ] && continue # the machine only, included by the paper cases
    n=$((n + 1))
    # a leap group's start lies after 2 ms, and a start at or after end_time is refused: no leaps
    cut=()
    if grep -q '^leap *=' "$cfg"; then cut=(--set leap.burst=0); fi
    if "$tool" run -q --no-progress --set end_time=0.002 "${cut[@]}" -o "$work/$name" "$cfg" >"$work/$name.log" 2>&1; then
        check_outputs "$name" "$work/$name" 1
    else
        fail "$name: touchdown run failed: $(head -n 2 "$work/$name.log")"
    fi
done
[ "$n" -ge 5 ] && pass "$n shipped cases run" || fail "only $n shipped cases found in $src/cases"

# touchdown modal stores the case text too (in its HDF5 file)
if "$tool" modal -q -o "$work/modal-a" "$src/cases/paper-a.cfg" >"$work/modal.log" 2>&1; then
    check_outputs "paper-a (modal)" "$work/modal-a" 0
else
    fail "touchdown modal failed: $(head -n 2 "$work/modal.log")"
fi

finish
