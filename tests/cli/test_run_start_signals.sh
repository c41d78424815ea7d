#!/usr/bin/env bash
# `touchdown run` start states, summary and signals: start = "auto" falls back to rest where the
# orbit lies outside a clearance (and says so), "orbit" stays strict, an unstable closed loop is
# refused an orbit start and called unstable; --json prints with -q and for runs that fail before
# their first step; SIGHUP ends run, modal and bench like SIGINT/SIGTERM (exit 1, what was written
# kept and marked), also during the set-up.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/run-start.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
has() { grep -qF -- "$2" "$1"; }
# bg DIR SIGNAL DELAY ARGS...: start the tool in DIR, send SIGNAL after DELAY s; rc as t.
bg() {
    local d=$1 sig=$2 delay=$3 pid
    shift 3
    mkdir -p "$d"
    (cd "$d" && exec "$tool" "$@" >"$d/.out" 2>"$d/.err" </dev/null) &
    pid=$!
    sleep "$delay"
    kill -s "$sig" "$pid" 2>/dev/null
    wait "$pid"
    rc=$?
}

# ---- -q and --json ------------------------------------------------------------------------------
t "$work/jq" run --json -q --set end_time=0.01 -o r "$case_a"
check "run --json -q: exit 0, one JSON object on stdout (got rc $rc, $(wc -l <"$work/jq/.out") lines)" \
    test "$rc" = 0 -a "$(wc -l <"$work/jq/.out")" = 1 -a "$(jf "$work/jq/.out" complete)" = true
check "run --json: the summary names every file ($(jf "$work/jq/.out" events_path))" \
    test "$(jf "$work/jq/.out" hdf5_path)" = '"r.h5"' -a "$(jf "$work/jq/.out" csv_path)" = '"r.csv"' \
    -a "$(jf "$work/jq/.out" events_path)" = '"r.events.csv"'
check "run --json: start \"auto\" used the orbit of paper case A, stable" \
    test "$(jf "$work/jq/.out" start)" = '"orbit"' -a "$(jf "$work/jq/.out" stability)" = '"stable"'
t "$work/q" run -q --set end_time=0.01 -o r "$case_a"
check "run -q alone: exit 0, nothing on stdout" test "$rc" = 0 -a ! -s "$work/q/.out"

# ---- start = "auto" and "orbit" outside the clearance ---------------------------------------------
t "$work/s190" run --set speed=190 --set end_time=0.02 -o r "$case_a"
check "run --set speed=190: exit 0 (got $rc: $(head -c 200 "$work/s190/.err"))" test "$rc" = 0
check "run --set speed=190: the summary says rest, and why" \
    has "$work/s190/.out" 'start                       rest (start = "auto": the steady orbit lies outside the clearance of retainer'
t "$work/s190o" run --json --set speed=190 --set start='"orbit"' -o r "$case_a"
check "start = \"orbit\" at 190 rad/s: exit 2, the reason on stderr (got $rc)" \
    test "$rc" = 2 -a "$(grep -c 'outside the clearance' "$work/s190o/.err")" = 1
check "start = \"orbit\" at 190 rad/s: --json still prints status, message and time reached" \
    test "$(jf "$work/s190o/.out" complete)" = false -a "$(jf "$work/s190o/.out" status)" = '"invalid argument"' \
    -a "$(jf "$work/s190o/.out" t_reached)" = 0 -a -n "$(jf "$work/s190o/.out" message | grep 'outside the clearance')"
check "start = \"orbit\" at 190 rad/s: no file left behind ($(ls "$work/s190o"))" test -z "$(ls "$work/s190o")"

# ---- an unstable closed loop (the rig with kp = 1e3 A/m) -------------------------------------------
t "$work/uo" run --set 'ambs[0].kp=1e3' --set start='"orbit"' -o r "$case_a"
check "unstable, start = \"orbit\": exit 2, refused with a way out ($(head -c 300 "$work/uo/.err"))" \
    test "$rc" = 2 -a -n "$(grep 'unstable' "$work/uo/.err" | grep 'start = "rest"')"
t "$work/ua" run --json --set 'ambs[0].kp=1e3' --set end_time=0.02 -o r "$case_a"
check "unstable, start = \"auto\": runs from rest and the summary says unstable (rc $rc, start $(jf "$work/ua/.out" start), stability $(jf "$work/ua/.out" stability))" \
    test "$(jf "$work/ua/.out" start)" = '"rest"' -a "$(jf "$work/ua/.out" stability)" = '"unstable"' \
    -a -n "$(jf "$work/ua/.out" start_reason | grep unstable)"
t "$work/ut" run --set 'ambs[0].kp=1e3' --set end_time=0.02 -o r "$case_a"
check "unstable: the text summary says so" has "$work/ut/.out" 'contact-free system         unstable'

# ---- signals -------------------------------------------------------------------------------------
# SIGHUP in the middle of a run: exit 1, the files kept and marked incomplete
bg "$work/hup" HUP 1.5 run --set end_time=60 -o r "$case_a"
check "run, SIGHUP: exit 1 (got $rc), 'interrupted' on stderr" \
    test "$rc" = 1 -a -n "$(grep -i interrupted "$work/hup/.err")"
check "run, SIGHUP: r.h5, r.csv and r.events.csv kept ($(ls "$work/hup" | tr '\n' ' '))" \
    test -s "$work/hup/r.h5" -a -s "$work/hup/r.csv" -a -s "$work/hup/r.events.csv"
check "run, SIGHUP: the CSV is marked incomplete" has "$work/hup/r.csv" 'incomplete'
# SIGINT during the set-up (a dense orbit solve of some seconds on a refined mesh): exit 1
bg "$work/int" INT 1 run --json --set shaft.refine=25 --set start='"orbit"' -o r "$case_a"
check "run, SIGINT during the set-up: exit 1 (got $rc), said so: $(head -c 200 "$work/int/.err")" \
    test "$rc" = 1 -a -n "$(grep 'interrupted while setting up' "$work/int/.err")"
check "run, SIGINT during the set-up: --json says interrupted" \
    test "$(jf "$work/int/.out" status)" = '"interrupted"'
# shaft.refine = 4 keeps the plain build's modal running past 1 s; the sanitized tool (TD_TEST_SANITIZED=1)
# takes some 5 s on the case's own mesh and, refined, went on 13 s past the signal to its next
# check: there the case's mesh, the same signal handling, message and files
mesh=(--set shaft.refine=4)
sanitized && mesh=()
bg "$work/mhup" HUP 1 modal "${mesh[@]}" -o m "$case_a"
check "modal, SIGHUP: exit 1 (got $rc), 'interrupted' on stderr, no file ($(ls "$work/mhup" | tr '\n' ' '))" \
    test "$rc" = 1 -a -n "$(grep -i interrupted "$work/mhup/.err")" -a -z "$(ls "$work/mhup")"
bg "$work/bhup" HUP 1.5 bench --quick --repeats 99 --dir "$src/cases" -o b.json
check "bench, SIGHUP: exit 1 (got $rc), 'interrupted' on stderr, no JSON file" \
    test "$rc" = 1 -a -n "$(grep -i interrupted "$work/bhup/.err")" -a ! -e "$work/bhup/b.json"

finish
