#!/usr/bin/env bash
# `touchdown sweep` under MPI: `mpirun -np 2` writes the table of `-j 1` and `-j 2` (wall time
# aside, CSV and HDF5); an MPI sweep interrupted half way (SIGINT to mpirun) keeps its rows in the
# ranks' parts, and run again resumes them, computes each other point once and writes the table of
# the uninterrupted sweep, and so does a run without MPI from the same parts; a part of another
# sweep is refused; bad input is one line and exit 2 on every rank; the progress line (forced with
# --progress into a log) counts to the end, with and without MPI, and rewrites itself with '\r' on
# a terminal.
# Skips (77) when the tool is built without MPI or mpirun is missing.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
"$tool" --version | grep -q '^built with MPI' || { echo "skip: touchdown built without MPI"; exit 77; }
command -v mpirun >/dev/null || { echo "skip: no mpirun"; exit 77; }
work=$(mktemp -d "${PWD}/sweep-mpi.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_r=$src/cases/rub-damped.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
need h5diff hdf5-tools
# The table without its last column (wall time) on the data lines.
no_wall() { sed '/^#/!s/,[^,]*$//' "$1"; }
same_h5() { h5diff -q --exclude-path /wall_time --exclude-path /point "$1" "$2"; }

# Open MPI refuses root without these, and counts cores rather than hardware threads
mpi=(mpirun -np 2)
if mpirun --version 2>&1 | grep -q 'Open MPI'; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fi
# m DIR ARGS...: as t, but the tool under `mpirun -np 2`.
m() {
    local d=$1
    shift
    mkdir -p "$d"
    (cd "$d" && "${mpi[@]}" "$tool" "$@" >"$d/.out" 2>"$d/.err" </dev/null)
    rc=$?
}

# ---- (a) one table whatever runs it --------------------------------------------------------------
grid=(--set end_time=0.2 --vary speed=60:150:4 --vary 'schedule[0].magnitude=0.05,0.1,0.2')
t "$work/j1" sweep --progress -q -j 1 "${grid[@]}" -o s "$case_r"
rc1=$rc
t "$work/j2" sweep -j 2 "${grid[@]}" -o s "$case_r"
rc2=$rc
# (its 0.2 s points warn: the line 'touchdown sweep: warning: ...' is all there is on stderr)
check "sweep without --progress, stderr not a terminal: no progress line" \
    test "$rc" = 0 -a -z "$(grep -v '^touchdown sweep: warning: ' "$work/j2/.err")"
m "$work/mpi" sweep --json --progress "${grid[@]}" -o s "$case_r"
check "sweep -j 1, -j 2, mpirun -np 2: exit 0 (got $rc1, $rc2, $rc: $(head -c 300 "$work/mpi/.err"))" \
    test "$rc1" = 0 -a "$rc2" = 0 -a "$rc" = 0
check "mpirun -np 2: one JSON object (rank 0's) with 2 ranks of 1 worker, 12 points done" \
    test "$(grep -c '^{' "$work/mpi/.out")" = 1 -a "$(jf "$work/mpi/.out" ranks)" = 2 \
    -a "$(jf "$work/mpi/.out" jobs)" = 1 -a "$(jf "$work/mpi/.out" done)" = 12
check "mpirun -np 2: the CSV table of -j 1 and of -j 2, apart from wall time" \
    cmp -s <(no_wall "$work/j1/s.csv") <(no_wall "$work/mpi/s.csv")
check "mpirun -np 2 and -j 2: the same CSV table apart from wall time" \
    cmp -s <(no_wall "$work/j2/s.csv") <(no_wall "$work/mpi/s.csv")
check "mpirun -np 2: the HDF5 table of -j 1 and -j 2 apart from wall time (h5diff)" \
    eval 'same_h5 "$work/j1/s.h5" "$work/mpi/s.h5" && same_h5 "$work/j2/s.h5" "$work/mpi/s.h5"'
check "mpirun -np 2: no part or journal left after the finished table ($(ls "$work/mpi"))" \
    test -z "$(ls "$work/mpi" | grep journal)"

# ---- (b) bad input: one line from rank 0, exit 2 --------------------------------------------------
m "$work/bad" sweep --set end_time=0.03 --vary 'nokey=1,2' -o b "$case_r"
check "mpirun -np 2 sweep --vary 'nokey=1,2': exit 2, the error once ($(grep -c 'nokey' "$work/bad/.err") lines)" \
    test "$rc" = 2 -a "$(grep -c 'nokey: unknown key' "$work/bad/.err")" = 1 -a ! -e "$work/bad/b.csv"

# ---- (c) interrupted half way, resumed ------------------------------------------------------------
# 30 points of 0.3 s; the uninterrupted table from -j 2, then the MPI sweep stopped (SIGINT to
# mpirun, which passes a SIGTERM to every rank) once its parts hold rows, then run again.
rgrid=(--set end_time=0.3 --vary speed=60:150:15 --vary 'schedule[0].magnitude=0.05,0.2')
t "$work/res" sweep -q -j 2 "${rgrid[@]}" -o u "$case_r"
parts_bytes() { cat "$work"/res/r.journal.rank-* 2>/dev/null | wc -c; }
(cd "$work/res" && exec "${mpi[@]}" "$tool" sweep -q "${rgrid[@]}" -o r "$case_r" >"$work/res/r1.out" \
    2>"$work/res/r1.err" </dev/null) &
pid=$!
for _ in $(seq 1 400); do # at most 20 s for a first row in the parts (each part's header is 32 bytes)
    [ "$(parts_bytes)" -gt 64 ] && break
    sleep 0.05
done
kill -s INT "$pid" 2>/dev/null
wait "$pid"
rc=$?
check "resume: the interrupted MPI sweep exits nonzero (rc $rc) and leaves its parts ($(ls "$work/res" | tr '\n' ' '))" \
    test "$rc" != 0 -a -e "$work/res/r.journal.rank-0" -a -e "$work/res/r.journal.rank-1"
if [ -e "$work/res/r.csv" ]; then
    check "resume: the interrupted MPI sweep's table is marked incomplete" \
        test -n "$(tail -n 1 "$work/res/r.csv" | grep '^# incomplete: interrupted')"
fi
# the same parts under another prefix (a part's header does not name it): resumed without MPI
for f in "$work"/res/r.journal.rank-*; do cp "$f" "$work/res/n${f#"$work/res/r"}"; done
t "$work/res/n" sweep --json -j 2 "${rgrid[@]}" -o ../n "$case_r"
check "resume without MPI from the parts of an MPI sweep: exit 0, resumed $(jf "$work/res/n/.out" resumed) + ran $(jf "$work/res/n/.out" ran) = 30, the uninterrupted table" \
    test "$rc" = 0 -a "$(($(jf "$work/res/n/.out" resumed) + $(jf "$work/res/n/.out" ran)))" = 30 \
    -a "$(jf "$work/res/n/.out" resumed)" -ge 1 -a -z "$(ls "$work/res" | grep '^n.journal')" \
    && cmp -s <(no_wall "$work/res/u.csv") <(no_wall "$work/res/n.csv")
m "$work/res" sweep --json "${rgrid[@]}" -o r "$case_r"
o=$work/res/.out
resumed=$(jf "$o" resumed)
ran=$(jf "$o" ran)
check "resume under MPI: exit 0, $resumed points from the parts, $ran run, 30 done (rc $rc, $(head -c 200 "$work/res/.err"))" \
    test "$rc" = 0 -a "${resumed:-0}" -ge 1 -a "${resumed:-30}" -lt 30 -a "$(jf "$o" done)" = 30
check "resume under MPI: no point computed twice (resumed $resumed + ran $ran = 30)" \
    test "$((${resumed:-0} + ${ran:-0}))" = 30
check "resume under MPI: the table equals the uninterrupted one apart from wall time" \
    cmp -s <(no_wall "$work/res/u.csv") <(no_wall "$work/res/r.csv")
check "resume under MPI: no part left after the finished table ($(ls "$work/res" | tr '\n' ' '))" \
    test -z "$(ls "$work/res" | grep journal)"
printf 'not a journal of this sweep, but longer than a header.\n' >"$work/res/x.journal.rank-5"
m "$work/res/x" sweep -q "${rgrid[@]}" -o ../x "$case_r"
check "resume: a part that is not a journal is refused under MPI, exit 2 ($(grep -c 'not a sweep journal' "$work/res/x/.err") lines)" \
    test "$rc" = 2 -a "$(grep -c 'not a sweep journal' "$work/res/x/.err")" = 1
t "$work/res/y" sweep -q -j 1 "${rgrid[@]}" -o ../x "$case_r"
check "resume: a part that is not a journal is refused without MPI, exit 2" \
    test "$rc" = 2 -a -n "$(grep 'x.journal.rank-5 is not a sweep journal' "$work/res/y/.err")"

# ---- (d) the progress line ------------------------------------------------------------------------
line_re='^sweep: [0-9]+/12 points, [0-9]+ running, [0-9]+ failed, ETA ([0-9]+[hms]([0-9]{2}[ms])?|--)$'
check "sweep --progress -q into a log: whole lines in the format, the last with the final counts ($(tail -n 1 "$work/j1/.err"))" \
    test "$rc1" = 0 -a -s "$work/j1/.err" -a -z "$(grep -vE "$line_re" "$work/j1/.err" | grep -v '^touchdown sweep: warning: ')" \
    -a "$(grep -v '^touchdown sweep: warning: ' "$work/j1/.err" | tail -n 1)" = "sweep: 12/12 points, 0 running, 0 failed, ETA 0s"
check "mpirun -np 2 sweep --progress: rank 0's line counts every rank's points ($(grep -E "$line_re" "$work/mpi/.err" | tail -n 1))" \
    test "$(grep -cE "$line_re" "$work/mpi/.err")" -ge 1 \
    -a "$(grep -E "$line_re" "$work/mpi/.err" | tail -n 1)" = "sweep: 12/12 points, 0 running, 0 failed, ETA 0s"
if command -v python3 >/dev/null; then
    # on a terminal (a pty for stderr alone): the line rewritten after '\r', ended by one newline
    mkdir -p "$work/prog"
    (cd "$work/prog" && python3 -c '
import os, pty, subprocess, sys
m, s = pty.openpty()
p = subprocess.Popen(sys.argv[1:], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=s)
os.close(s)
out = b""
while True:
    try:
        d = os.read(m, 4096)
    except OSError:  # EIO once the tool has closed the pty
        break
    if not d:
        break
    out += d
sys.stdout.buffer.write(out)
sys.exit(p.wait())' "$tool" sweep -j 2 --set end_time=0.2 --vary speed=60:150:4 -o tty "$case_r" >"$work/prog/tty.err")
    rc=$?
    check "sweep on a terminal: '\\r' before each line, the last '4/4 points, 0 running, 0 failed, ETA 0s' and a newline" \
        test "$rc" = 0 -a -n "$(grep -av 'touchdown sweep: warning: ' "$work/prog/tty.err" | tr -d '\n' | grep -E $'^\rsweep: [0-9]/4 points.*\rsweep: 4/4 points, 0 running, 0 failed, ETA 0s\r?$')"
fi

finish
