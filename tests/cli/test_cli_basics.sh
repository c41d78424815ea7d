#!/usr/bin/env bash
# The tool's basic contract: help and version, exit codes, where `touchdown run` writes its files
# (default names, -o, --hdf5/--csv, '' for none), -q, --json, --set, no progress line when stderr
# is not a terminal, `info` on every shipped case, `modal` on the Jeffcott case.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/cli-basics.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

files_in() { (cd "$1" && ls | tr '\n' ' ' | sed 's/ $//'); }

# ---- help and version ----------------------------------------------------------------------
for h in --help -h help; do
    t "$work/help$h" "$h"
    check "touchdown $h: exit 0, usage on stdout, nothing on stderr" \
        test "$rc" = 0 -a ! -s "$work/help$h/.err" -a -n "$(grep '^usage: touchdown COMMAND' "$work/help$h/.out")"
done
t "$work/noargs"
check "touchdown (no arguments): exit 2, usage on stderr" \
    test "$rc" = 2 -a ! -s "$work/noargs/.out" -a -n "$(grep '^usage:' "$work/noargs/.err")"
t "$work/version" --version
check "touchdown --version: exit 0, 'touchdown X.Y.Z' ($(cat "$work/version/.out"))" \
    test "$rc" = 0 -a -n "$(grep -E '^touchdown [0-9]+\.[0-9]+\.[0-9]+' "$work/version/.out")"
check "touchdown --version: the second line says whether MPI is built in ($(sed -n 2p "$work/version/.out"))" \
    test -n "$(sed -n 2p "$work/version/.out" | grep -E '^built (with|without) MPI')"
for cmd in run info modal plot; do
    t "$work/help-$cmd" "$cmd" --help
    check "touchdown $cmd --help: exit 0, its usage on stdout" \
        test "$rc" = 0 -a ! -s "$work/help-$cmd/.err" -a -n "$(grep "^usage: touchdown $cmd" "$work/help-$cmd/.out")"
done
check "touchdown --help documents the exit codes" grep -q "exit codes: 0 success, 1 .*, 2 bad input" "$work/help--help/.out"

# ---- run: default names, summary, no progress line off a terminal -------------------------
d=$work/default
t "$d" run --set end_time=0.02 "$case_a"
check "run: exit 0 (stderr: $(head -c 200 "$d/.err"))" test "$rc" = 0
check "run: default outputs CASENAME.h5, .csv, .events.csv in the current directory ($(files_in "$d"))" \
    test "$(files_in "$d")" = "paper-a.csv paper-a.events.csv paper-a.h5"
# (its schedule entries at 0.1 s and 1.1 s never happen in 0.02 s: two warning lines, nothing else)
check "run: nothing on stderr but the warnings when it is not a terminal (no progress line)" \
    test "$(grep -c ': warning: schedule\[[01]\] ' "$d/.err")" = 2 -a -z "$(grep -v ': warning: ' "$d/.err")"
check "run: the summary says complete" grep -qE "^status +complete" "$d/.out"
for field in "first contact" "contact onsets" "peak normal force" "time in contact" "returned to free orbit" \
    "wall time per revolution"; do
    check "run: the summary gives '$field'" grep -q "$field" "$d/.out"
done
check "run: the CSV has a header and 201 samples at 10 kHz" \
    test "$(grep -vc '^#' "$d/paper-a.csv")" = 202 -a -n "$(head -n 1 "$d/paper-a.csv" | grep '^t \[s\],')"

# ---- -o PREFIX, --hdf5 / --csv, '' for none ------------------------------------------------
d=$work/prefix
t "$d" run -q -o sub-result --set end_time=0.01 "$case_a"
check "run -o PREFIX -q: exit 0, PREFIX.* written, nothing printed but the warnings ($(files_in "$d"))" \
    test "$rc" = 0 -a "$(files_in "$d")" = "sub-result.csv sub-result.events.csv sub-result.h5" \
    -a ! -s "$d/.out" -a -z "$(grep -v ': warning: ' "$d/.err")"
d=$work/only-h5
t "$d" run -q --csv '' --hdf5 only.h5 --set end_time=0.01 "$case_a"
check "run --csv '' --hdf5 only.h5: only only.h5 ($(files_in "$d"))" test "$rc" = 0 -a "$(files_in "$d")" = "only.h5"
d=$work/only-csv
t "$d" run -q --hdf5 '' --csv only.csv --set end_time=0.01 "$case_a"
check "run --hdf5 '' --csv only.csv: only the CSV and its events ($(files_in "$d"))" \
    test "$rc" = 0 -a "$(files_in "$d")" = "only.csv only.events.csv"
d=$work/none
t "$d" run --hdf5 '' --csv '' --set end_time=0.01 "$case_a"
check "run --hdf5 '' --csv '': no file, still a summary ($(files_in "$d"))" \
    test "$rc" = 0 -a -z "$(files_in "$d")" -a -n "$(grep -E '^status +complete' "$d/.out")"

# ---- --json and --set ----------------------------------------------------------------------
d=$work/json
t "$d" run --json --hdf5 '' --csv '' --set end_time=0.0123 --set speed=95 "$case_a"
check "run --json: exit 0, one line holding one JSON object" \
    test "$rc" = 0 -a "$(wc -l <"$d/.out")" = 1 -a -n "$(grep -E '^\{.*\}$' "$d/.out")"
check "run --json: complete true, status success" \
    test "$(jf "$d/.out" complete)" = true -a "$(jf "$d/.out" status)" = '"success"'
check "run --set end_time=0.0123: t_reached $(jf "$d/.out" t_reached)" \
    awk -v t="$(jf "$d/.out" t_reached)" 'BEGIN { exit !(t == 0.0123) }'
check "run --set speed=95: speed $(jf "$d/.out" speed)" test "$(jf "$d/.out" speed)" = 95
check "run --json: library_version is the tool's ($(jf "$d/.out" library_version))" \
    test "touchdown $(jf "$d/.out" library_version | tr -d '"')" = "$(head -n 1 "$work/version/.out")"

# ---- info on every shipped case; the rig alone is not a case --------------------------------
for c in "$src"/cases/*.cfg; do
    name=$(basename "$c" .cfg)
    t "$work/info-$name" info "$c"
    if [ "$name" = rig ]; then
        check "info cases/rig.cfg: exit 2 (a machine, not a run: $(head -c 120 "$work/info-$name/.err"))" test "$rc" = 2
        continue
    fi
    check "info cases/$name.cfg: exit 0, names the case, lists modes" \
        test "$rc" = 0 -a -n "$(grep "^case *$name " "$work/info-$name/.out")" \
        -a -n "$(grep '^first modes' "$work/info-$name/.out")" -a -z "$(files_in "$work/info-$name")"
done
check "info paper-a: 13 nodes, 2 AMBs, 2 retainers, 52 DOFs" \
    test -n "$(grep -E '^shaft +12 elements, 13 nodes' "$work/info-paper-a/.out")" \
    -a "$(grep -c '^amb ' "$work/info-paper-a/.out")" = 2 -a "$(grep -c '^retainer ' "$work/info-paper-a/.out")" = 2 \
    -a -n "$(grep -E '^DOFs +52 mechanical' "$work/info-paper-a/.out")"

# ---- modal ---------------------------------------------------------------------------------
d=$work/modal
t "$d" modal "$src/cases/jeffcott.cfg"
check "modal jeffcott: exit 0, writes jeffcott-modal.csv and .h5 ($(files_in "$d"))" \
    test "$rc" = 0 -a "$(files_in "$d")" = "jeffcott-modal.csv jeffcott-modal.h5"
check "modal jeffcott: lists critical speeds" grep -q "critical speeds" "$d/.out"

finish
