#!/usr/bin/env bash
# `touchdown sweep` used as a hostile user would: no file the sweep writes or removes may be one of
# its inputs, whatever the names. A case file or an @include named like (or hard-linked to) any
# point's file under --point-files, like the journal or like a part of it, is refused before
# anything runs: one line naming the file, exit 2, the input unchanged and still there, and the
# advice is to choose another -o prefix, never to remove the file (it is the user's case). A file
# shorter than a journal's header at the journal's name is refused and kept. A point's file that is
# the sweep's own table or journal (by name, or by device and inode; its CSV's window file too) is
# refused. A sweep
# killed by SIGKILL takes its workers with it.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/sweep-hostile.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, finish
has() { grep -qF -- "$2" "$1"; }

# A case of the rig in DIR under the name NAME (the rig itself beside it as rig.cfg), 1 ms long;
# with a third argument INC, its end time is in the file INC that it includes.
make_case() {
    mkdir -p "$1"
    cp "$src/cases/rig.cfg" "$1/rig.cfg"
    printf '@include "rig.cfg"\nspeed = 90.0;\n' >"$1/$2"
    if [ -n "${3:-}" ]; then
        printf 'end_time = 0.001;\n' >"$1/$3" # shorter than a journal's header
        cp "$1/$3" "$1/$3.orig"
        printf '@include "%s"\n' "$3" >>"$1/$2"
    else
        printf 'end_time = 0.001;\n' >>"$1/$2"
    fi
    cp "$1/$2" "$1/$2.orig"
}
# refused DIR FILE WHAT: exit 2, one line on stderr naming FILE, FILE unchanged
refused() {
    check "$3: exit 2, one line ($(head -c 300 "$1/.err"))" test "$rc" = 2 -a "$(wc -l <"$1/.err")" = 1
    check "$3: the error names $2" has "$1/.err" "$2"
    check "$3: $2 is unchanged" cmp -s "$1/$2" "$1/$2.orig"
}

# ---- (a) inputs named like point files that are not the last point's ----------------------------
make_case "$work/pf" point-000001.h5
t "$work/pf" sweep -j 1 --point-files . --vary speed=60,90,120 -o s point-000001.h5
refused "$work/pf" point-000001.h5 "a case file named like point 1's HDF5 file (of 3)"
check "a case file named like a point file: nothing written" test ! -e "$work/pf/s.csv" -a ! -e "$work/pf/point-000000.h5"

make_case "$work/inc" main.cfg point-000000.events.csv
t "$work/inc" sweep -j 1 --point-files . --point-csv --vary speed=60,90 -o s main.cfg
refused "$work/inc" point-000000.events.csv "an @include named like point 0's CSV events file"

make_case "$work/ln" main.cfg
mkdir -p "$work/ln/out"
ln "$work/ln/main.cfg" "$work/ln/out/point-000000.h5" # the same file under a point's name
t "$work/ln" sweep -j 1 --point-files out --vary speed=60,90 -o s main.cfg
refused "$work/ln" main.cfg "a case file hard-linked as point 0's HDF5 file"

# ---- (b) inputs named like the journal or a part of it -------------------------------------------
make_case "$work/ji" main.cfg s.journal
t "$work/ji" sweep -j 1 --vary speed=60,90 -o s main.cfg
refused "$work/ji" s.journal "an @include named like the journal"
check "an @include named like the journal: the advice is another -o prefix" has "$work/ji/.err" "choose another -o prefix"

make_case "$work/jc" s.journal
t "$work/jc" sweep -j 1 --vary speed=60,90 -o s s.journal
refused "$work/jc" s.journal "a case file named like the journal"
check "a case file named like the journal: the advice is another -o prefix, not to remove it" \
    test -n "$(grep -F 'choose another -o prefix' "$work/jc/.err")" -a -z "$(grep -F 'remove it' "$work/jc/.err")"

make_case "$work/jp" main.cfg s.journal.rank-3
t "$work/jp" sweep -j 1 --vary speed=60,90 -o s main.cfg
refused "$work/jp" s.journal.rank-3 "an @include named like a part of the journal (MPI rank 3)"

make_case "$work/tc" main.cfg s.csv
t "$work/tc" sweep -j 1 --vary speed=60,90 -o s main.cfg
refused "$work/tc" s.csv "an @include named like the table"
check "an @include named like the table: the advice is another -o prefix" has "$work/tc/.err" "choose another -o prefix"

# ---- (b2) a short file of the user's at the journal's name ------------------------------------
# shorter than the journal's 32-byte header and not a prefix of it: not a journal cut before its
# header was whole, so refused and kept, never truncated to start a journal
make_case "$work/js" main.cfg
printf 'my notes\n\n' >"$work/js/s.journal" # 10 bytes
cp "$work/js/s.journal" "$work/js/s.journal.orig"
t "$work/js" sweep -j 1 --vary speed=60,90 -o s main.cfg
refused "$work/js" s.journal "a 10-byte text file at the journal's name"
check "a 10-byte text file at the journal's name: no table written" test ! -e "$work/js/s.csv" -a ! -e "$work/js/s.h5"

# ---- (b3) a point's file that is the sweep's own table or journal -------------------------------
# -o DIR/point-000001 --point-files DIR: the table DIR/point-000001.h5 is also point 1's file, and
# written last it would replace it; and a point's file hard-linked to the journal of an earlier
# run (a file there: compared by device and inode)
make_case "$work/pt" main.cfg
mkdir -p "$work/pt/out"
t "$work/pt" sweep -j 1 --point-files out --vary speed=60,90,120 -o out/point-000001 main.cfg
check "-o out/point-000001 --point-files out: exit 2, one line naming point 1's HDF5 file and the table ($(head -c 300 "$work/pt/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/pt/.err")" = 1 -a -n "$(grep -F 'out/point-000001.h5' "$work/pt/.err" | grep -F 'table')"
check "-o out/point-000001 --point-files out: nothing written" test -z "$(ls -A "$work/pt/out")"
# -o out/point-000000.windows --point-csv with windows on: the table's CSV is point 0's window file
t "$work/pt" sweep -j 1 --point-files out --point-csv --set output.window=0.0005 --vary speed=60,90 \
    -o out/point-000000.windows main.cfg
check "-o out/point-000000.windows --point-csv: exit 2, one line naming point 0's window file and the table ($(head -c 300 "$work/pt/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/pt/.err")" = 1 -a \
    -n "$(grep -F 'out/point-000000.windows.csv, a file of point 0' "$work/pt/.err" | grep -F 'table')"
check "-o out/point-000000.windows --point-csv: nothing written" test -z "$(ls -A "$work/pt/out")"
printf 'TDSWJ02' >"$work/pt/s.journal" # a journal cut in its header, of this sweep
ln "$work/pt/s.journal" "$work/pt/out/point-000001.h5"
t "$work/pt" sweep -j 1 --point-files out --vary speed=60,90 -o s main.cfg
check "point 1's HDF5 file hard-linked to the journal: exit 2, one line naming both ($(head -c 300 "$work/pt/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/pt/.err")" = 1 -a -n "$(grep -F 'point-000001.h5' "$work/pt/.err" | grep -F 's.journal')"
check "point 1's HDF5 file hard-linked to the journal: both left as they were" \
    test "$(cat "$work/pt/s.journal")" = TDSWJ02 -a ! -e "$work/pt/s.csv" -a ! -e "$work/pt/out/point-000000.h5"

# ---- (c) the workers die with their sweep ------------------------------------------------------
# Two points of the rig simulated for 500 s (minutes of CPU each), -j 2: once both workers run,
# the sweep is killed with SIGKILL, which no handler sees; its workers must end with it. Poll for
# them at most 30 s (a hang catcher: without the fix they run for minutes).
alive() { # PID: a process that is neither gone nor a zombie
    local st
    st=$(ps -o stat= -p "$1" 2>/dev/null) || return 1
    [ -n "$st" ] && [ "${st#Z}" = "$st" ]
}
if command -v pgrep >/dev/null && command -v ps >/dev/null; then
    make_case "$work/kill" main.cfg
    (cd "$work/kill" && exec "$tool" sweep -j 2 --no-progress --vary end_time=500,501 -o k main.cfg \
        >"$work/kill/.out" 2>"$work/kill/.err" </dev/null) &
    pid=$!
    kids=""
    for _ in $(seq 1 600); do # both workers, as soon as they exist (at most 30 s)
        kids=$(pgrep -P "$pid" | tr '\n' ' ')
        [ "$(wc -w <<<"$kids")" = 2 ] && break
        sleep 0.05
    done
    trap 'for k in $kids; do kill -s KILL "$k" 2>/dev/null; done; rm -rf "$work"' EXIT
    kill -s KILL "$pid"
    wait "$pid" 2>/dev/null
    left=$kids
    for _ in $(seq 1 300); do # at most 30 s
        left=""
        for k in $kids; do alive "$k" && left="$left $k"; done
        [ -z "$left" ] && break
        sleep 0.1
    done
    check "sweep killed by SIGKILL with 2 workers running (pids: $kids): no worker outlives it${left:+ (alive:$left)}" \
        test "$(wc -w <<<"$kids")" = 2 -a -z "$left"
fi

finish
