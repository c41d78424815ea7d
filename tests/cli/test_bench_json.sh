#!/usr/bin/env bash
# `touchdown bench --json` stays valid JSON whatever the user's strings hold: the cases are read
# from a directory whose name has a double quote, a backslash and a tab, and a --set override
# with the same characters is echoed in the report's "sets" list. Python's json module (an
# independent parser) must read the report and give the override back byte for byte.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/bench-json.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf

dir="$work/q\"b\\s"$'\t'"c"
mkdir -p "$dir" && cp -R "$src"/cases/. "$dir"/ # with cases/include
set_arg='output.csv="x\"y\\z'$'\t''w.csv"'
t "$work/run" bench --quick --json --cases A --dir "$dir" --set "$set_arg"
check "bench --json with a quote, a backslash and a tab in --dir and --set: exit 0" test "$rc" = 0
check "the report is valid JSON and gives the --set back unchanged" \
    python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(d["sets"] != [sys.argv[2]] or d["runs"][0]["case"] != "A")' \
    "$work/run/.out" "$set_arg"

echo "$((checks - fails)) passed, $fails failed"
[ "$fails" = 0 ]
