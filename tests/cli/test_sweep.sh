#!/usr/bin/env bash
# `touchdown sweep`: the table does not depend on -j (wall time aside); each row is what an
# independent `touchdown run` of the same point says; a failing point, or one whose worker is
# killed or outlives --point-timeout, is a row and the others run; bad --vary specs, keys and values are one line and exit 2
# before anything runs; SIGINT half way leaves the table marked incomplete (or nothing), never a
# table that looks finished; a sweep killed half way (SIGKILL) and run again resumes from its
# journal and writes the table of an uninterrupted run (a zero-filled tail of the journal, what a
# crash leaves, is dropped with a notice), and a journal of another sweep or a file that is not a
# journal is refused, one of another build (its row layout) as such.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/sweep.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_r=$src/cases/rub-damped.cfg
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
need h5dump hdf5-tools
need h5diff hdf5-tools
has() { grep -qF -- "$2" "$1"; }
# The table without its last column (wall time) on the data lines.
no_wall() { sed '/^#/!s/,[^,]*$//' "$1"; }
# Numbers equal as doubles (awk reads 17 significant digits exactly).
# (both undefined: "nan" in the table, null in JSON, is the same answer)
same_number() {
    case "$1:$2" in nan:null | null:nan | nan:nan) return 0 ;; nan:* | *:nan | null:* | *:null) return 1 ;; esac
    awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 == b + 0) }'
}

# 12 points of rub-damped (4 speeds x 3 unbalance steps), 0.2 s each: free, rubbing, bouncing
grid=(--set end_time=0.2 --vary speed=60:150:4 --vary 'schedule[0].magnitude=0.05,0.1,0.2')

# ---- (a) -j 1 and -j 2 ------------------------------------------------------------------------
t "$work/j1" sweep -j 1 "${grid[@]}" -o s "$case_r"
rc1=$rc
t "$work/j2" sweep -j 2 "${grid[@]}" -o s "$case_r"
check "sweep -j 1 and -j 2: exit 0 (got $rc1, $rc: $(head -c 300 "$work/j2/.err"))" test "$rc1" = 0 -a "$rc" = 0
check "sweep: 12 data rows and the flag '# complete' last" \
    test "$(grep -vc '^#' "$work/j2/s.csv")" = 13 -a "$(tail -n 1 "$work/j2/s.csv")" = "# complete"
check "sweep: the header names the swept keys and the units" \
    test "$(head -n 1 "$work/j2/s.csv" | cut -d, -f1-6)" = \
    "point [-],speed,schedule[0].magnitude,status,message,peak_housing_force [N]"
check "sweep: the first key varies slowest (row 4 is speed 90, magnitude 0.1)" \
    test "$(sed -n 6p "$work/j2/s.csv" | cut -d, -f1-4)" = "4,90,0.1,success"
check "sweep -j 1 and -j 2: identical CSV tables apart from wall time" \
    cmp -s <(no_wall "$work/j1/s.csv") <(no_wall "$work/j2/s.csv")
# /point is left out too: its list of the datasets that use it as their axis leads h5diff into /wall_time
check "sweep -j 1 and -j 2: identical HDF5 tables apart from wall time (h5diff)" \
    h5diff -q --exclude-path /wall_time --exclude-path /point "$work/j1/s.h5" "$work/j2/s.h5"
check "sweep: the HDF5 table is flagged complete" \
    test -n "$(h5dump -a /complete "$work/j2/s.h5" | grep -E '^ *\(0\): 1$')"

# ---- (b) each row against an independent touchdown run ----------------------------------------
# Under the sanitizers (TD_TEST_SANITIZED=1) the rows 0, 4 and 8 only (a speed and an unbalance
# step each, from 60 rad/s with 0.05 kg m to 120 rad/s with 0.2 kg m): the run and the JSON
# summary the comparison reads are the same code for every row; every row is the plain pass's.
bad=""
compared=""
while IFS= read -r line; do
    IFS=, read -r p speed mag status _ phf imp fw ct nc fct _ <<<"$line"
    sanitized && [ $((p % 4)) != 0 ] && continue
    compared="$compared $p"
    # from the end (the warnings column may hold quoted commas): wall_time, warnings, shock_outcome,
    # contact_happened, min_clearance_margin, t_reached, peak_amb_load, final_speed
    final=$(sed -E 's/"[^"]*"/x/g' <<<"$line" | awk -F, '{ print $(NF - 7) }')
    margin=$(sed -E 's/"[^"]*"/x/g' <<<"$line" | awk -F, '{ print $(NF - 4) }')
    outcome=$(sed -E 's/"[^"]*"/x/g' <<<"$line" | awk -F, '{ print $(NF - 2) }')
    t "$work/run$p" run --json -q --csv '' --hdf5 '' --set end_time=0.2 --set "speed=$speed" \
        --set "schedule[0].magnitude=$mag" "$case_r"
    o=$work/run$p/.out
    jfct=$(jf "$o" first_contact_time)
    for pair in "$phf:$(jf "$o" peak_housing_force)" "$imp:$(jf "$o" total_impulse)" "$fw:$(jf "$o" friction_work)" \
        "$ct:$(jf "$o" contact_time)" "$nc:$(jf "$o" contacts)" "$fct:$jfct" "$final:$(jf "$o" final_speed)" \
        "$margin:$(jf "$o" min_clearance_margin)"; do
        same_number "${pair%%:*}" "${pair#*:}" || bad="$bad point $p (${pair})"
    done
    [ "$status" = success ] && has "$work/j2/s.csv" "$p,$speed,$mag,success,,$phf," || bad="$bad point $p status"
    has "$work/j2/s.csv" "$(jf "$o" ending | tr -d '"')" || bad="$bad point $p ending"
    [ "\"$outcome\"" = "$(jf "$o" shock_outcome)" ] || bad="$bad point $p shock_outcome $outcome"
done < <(grep -v '^#' "$work/j2/s.csv" | tail -n +2)
check "sweep rows${compared} equal independent 'touchdown run --json' of their points${bad:+:$bad}" \
    test -n "$compared" -a -z "$bad"

# ---- (c) a failing point ----------------------------------------------------------------------
t "$work/fail" sweep -j 2 --set end_time=0.03 --set start=orbit --vary speed=60,90,190 -o f "$case_a"
check "sweep with a failing point: exit 1 (got $rc)" test "$rc" = 1
check "sweep with a failing point: its row says why, the others ran" \
    test "$(grep -c ',success,,' "$work/fail/f.csv")" = 2 -a \
    -n "$(grep '^2,190,invalid argument,"the start state is outside the clearance' "$work/fail/f.csv")"
check "sweep with a failing point: stderr names it, the table is complete" \
    test -n "$(grep 'point 2 (speed=190)' "$work/fail/.err")" -a "$(tail -n 1 "$work/fail/f.csv")" = "# complete"
t "$work/json" sweep -j 2 --json --set end_time=0.03 --set start=orbit --vary speed=60,90,190 -o f "$case_a"
check "sweep --json: one object with the counts and files" \
    test "$(jf "$work/json/.out" done)" = 2 -a "$(jf "$work/json/.out" failed)" = 1 \
    -a "$(jf "$work/json/.out" csv_path)" = '"f.csv"' -a "$(jf "$work/json/.out" hdf5_path)" = '"f.h5"'

# ---- (c) a worker that dies (SIGKILL) is a failed row, the others run ----------------------------
if command -v pgrep >/dev/null; then
    mkdir -p "$work/kill"
    (cd "$work/kill" && exec "$tool" sweep -j 2 --set end_time=1.0 --vary speed=90,120 -o k "$case_r" \
        >"$work/kill/.out" 2>"$work/kill/.err" </dev/null) &
    pid=$!
    kid=""
    for _ in $(seq 1 100); do # the first worker, as soon as it exists (at most 5 s)
        kid=$(pgrep -P "$pid" | head -n 1)
        [ -n "$kid" ] && break
        sleep 0.05
    done
    [ -n "$kid" ] && kill -s KILL "$kid"
    wait "$pid"
    rc=$?
    check "sweep with a killed worker: exit 1, one 'worker died' row naming the signal, the other ran (rc $rc)" \
        test "$rc" = 1 -a "$(grep -c ',worker died,the worker was killed by signal 9' "$work/kill/k.csv")" = 1 \
        -a "$(grep -c ',success,,' "$work/kill/k.csv")" = 1 -a "$(tail -n 1 "$work/kill/k.csv")" = "# complete"
fi

# ---- (d) bad input: one line, exit 2, nothing written -----------------------------------------
for args in "speed=1:2:0" "speed" "speed=1:2" "speed=1,,2" "=1,2" "nokey=1,2" "speed=abc" "speed=60,abc"; do
    t "$work/bad" sweep --set end_time=0.03 --vary "$args" -o b "$case_a"
    check "sweep --vary '$args': exit 2, one line ($(head -n 1 "$work/bad/.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$work/bad/.err")" = 1 -a ! -e "$work/bad/b.csv" -a ! -e "$work/bad/b.h5"
done
check "sweep --vary 'speed=60,abc': the error names the bad point's key and value" \
    has "$work/bad/.err" "--vary 'speed=abc': speed: expected a number"
t "$work/bad1" sweep --vary 'nokey=1,2' "$case_a"
check "sweep --vary 'nokey=1,2': the error names the key" has "$work/bad1/.err" "nokey: unknown key"
t "$work/bad2" sweep --vary speed=1:2:1000 --vary 'schedule[0].magnitude=0:1:1000' "$case_a"
check "sweep past 100000 points: exit 2, one line" test "$rc" = 2 -a "$(wc -l <"$work/bad2/.err")" = 1
t "$work/bad3" sweep -j 0 --vary speed=1,2 "$case_a"
check "sweep -j 0: exit 2" test "$rc" = 2
t "$work/bad4" sweep --point-timeout 0 --vary speed=1,2 "$case_a"
check "sweep --point-timeout 0: exit 2, naming the option" test "$rc" = 2 -a -n "$(grep -F -- '--point-timeout' "$work/bad4/.err")"

# a point far beyond its --point-timeout is stopped and recorded, the other runs: rub-damped
# simulated for 500 s takes minutes of CPU, its 0.001 s well under a second even under ASan
t "$work/tmo" sweep -j 2 --point-timeout 6 --vary end_time=0.001,500 -o t "$src/cases/rub-damped.cfg"
check "sweep --point-timeout: exit 1, the long point stopped with status timeout, the short one done" \
    test "$rc" = 1 -a "$(grep -c ',500,timeout,stopped: ran longer than --point-timeout 6 s' "$work/tmo/t.csv")" = 1 \
    -a "$(grep -c '^0,0.001,success,' "$work/tmo/t.csv")" = 1 -a "$(tail -n 1 "$work/tmo/t.csv")" = "# complete"
t "$work/help" sweep --help
check "sweep --help: exit 0, the usage" test "$rc" = 0 -a -n "$(grep 'KEY=START:STOP:N' "$work/help/.out")"

# ---- (e) SIGINT half way ----------------------------------------------------------------------
mkdir -p "$work/int"
(cd "$work/int" && exec "$tool" sweep -j 2 --set end_time=0.5 --vary speed=60:150:20 --vary 'schedule[0].magnitude=0.1,0.2' \
    -o i "$case_r" >"$work/int/.out" 2>"$work/int/.err" </dev/null) &
pid=$!
sleep 1.5
kill -s INT "$pid" 2>/dev/null
wait "$pid"
rc=$?
check "sweep interrupted: exit 1 (got $rc; $(head -c 200 "$work/int/.err"))" test "$rc" = 1
check "sweep interrupted: no temporary file left ($(ls "$work/int"))" test -z "$(ls "$work/int" | grep partial)"
if [ -e "$work/int/i.csv" ]; then
    check "sweep interrupted: the CSV says incomplete, unfinished points 'not run'" \
        test -n "$(tail -n 1 "$work/int/i.csv" | grep '^# incomplete: interrupted')" \
        -a -n "$(grep ',not run,' "$work/int/i.csv")"
fi
if [ -e "$work/int/i.h5" ]; then
    check "sweep interrupted: the HDF5 table is flagged incomplete" \
        test -n "$(h5dump -a /complete "$work/int/i.h5" | grep -E '^ *\(0\): 0$')"
fi

# ---- (f) resume after SIGKILL ----------------------------------------------------------------
# 40 points of 0.3 s; the uninterrupted table first, then the same sweep killed once its journal
# holds rows, then run again. Under the sanitizers the points end at 0.15 s (rubbing and bouncing
# points still among them): the journal, its records, the resume and the table are the same code.
rend=0.3
sanitized && rend=0.15
rgrid=(--set end_time=$rend --vary speed=60:150:20 --vary 'schedule[0].magnitude=0.05,0.2')
t "$work/res" sweep -q -j 2 "${rgrid[@]}" -o u "$case_r"
check "resume: the uninterrupted sweep, exit 0, no journal left ($(ls "$work/res"))" \
    test "$rc" = 0 -a ! -e "$work/res/u.journal"
(cd "$work/res" && exec "$tool" sweep -q -j 2 "${rgrid[@]}" -o r "$case_r" >/dev/null 2>&1 </dev/null) &
pid=$!
for _ in $(seq 1 400); do # at most 20 s for a first row in the journal (header 32 bytes)
    [ "$(stat -c %s "$work/res/r.journal" 2>/dev/null || echo 0)" -gt 32 ] && break
    sleep 0.05
done
kill -s KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
jsize=$(stat -c %s "$work/res/r.journal" 2>/dev/null || echo 0)
check "resume: the killed sweep left its journal ($jsize bytes) and no table" \
    test "$jsize" -gt 32 -a ! -e "$work/res/r.csv"
cp "$work/res/r.journal" "$work/res/other.journal" # a journal of this sweep, for (g) below
cp "$work/res/r.journal" "$work/res/build.journal" # and one of another build, for (g)
# what a crash of the machine leaves after the last record: blocks of zeros (several records' worth)
head -c 9000 /dev/zero >>"$work/res/r.journal"
(cd "$work/res" && "$tool" sweep --json -j 2 "${rgrid[@]}" -o r "$case_r" >"$work/res/r2.json" 2>"$work/res/r2.err")
rc=$?
check "resume: the zero-filled tail is dropped with a one-line notice ($(head -c 200 "$work/res/r2.err"))" \
    test "$(grep -c 'r.journal: a torn record at byte .* is dropped: its point runs again' "$work/res/r2.err")" = 1
resumed=$(jf "$work/res/r2.json" resumed)
check "resume: the second run, exit 0, $resumed points from the journal, 40 done (rc $rc, $(head -c 200 "$work/res/r2.err"))" \
    test "$rc" = 0 -a "${resumed:-0}" -ge 1 -a "${resumed:-40}" -lt 40 -a "$(jf "$work/res/r2.json" done)" = 40
check "resume: no point computed twice: resumed $resumed + ran $(jf "$work/res/r2.json" ran) = 40" \
    test $((${resumed:-0} + $(jf "$work/res/r2.json" ran))) = 40
check "resume: each journal record is one resumed point (($jsize - 32) bytes in $resumed equal records)" \
    test "${resumed:-0}" -ge 1 -a $(((jsize - 32) % ${resumed:-1})) = 0
check "resume: the table equals the uninterrupted one apart from wall time" \
    cmp -s <(no_wall "$work/res/u.csv") <(no_wall "$work/res/r.csv")
check "resume: no journal left after the finished table" test ! -e "$work/res/r.journal"
# ---- (g) journals that are not this sweep's -----------------------------------------------------
t "$work/res/o" sweep -q -j 1 --set end_time=0.29 --vary speed=60:150:20 --vary 'schedule[0].magnitude=0.05,0.2' \
    -o ../other "$case_r"
check "resume: a journal of another sweep is refused, exit 2, one line ($(head -c 200 "$work/res/o/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/res/o/.err")" = 1 -a -n "$(grep 'journal of another sweep' "$work/res/o/.err")"
# a journal of another build: its header's row size (bytes 16-23, little-endian) one row longer
/usr/bin/python3 -c '
import struct, sys
with open(sys.argv[1], "r+b") as f:
    f.seek(16); size, = struct.unpack("<Q", f.read(8)); f.seek(16); f.write(struct.pack("<Q", size + 8))' \
    "$work/res/build.journal"
t "$work/res/b" sweep -q -j 1 "${rgrid[@]}" -o ../build "$case_r"
check "resume: a journal of another build is refused as such, exit 2, one line ($(head -c 200 "$work/res/b/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/res/b/.err")" = 1 -a \
    -n "$(grep 'build.journal is a sweep journal written by another build of touchdown (its row layout differs)' "$work/res/b/.err")"
printf 'not a journal of this sweep, but longer than a header.\n' >"$work/res/x.journal"
t "$work/res/x" sweep -q -j 1 "${rgrid[@]}" -o ../x "$case_r"
check "resume: a file that is not a journal is refused, exit 2, one line ($(head -c 200 "$work/res/x/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/res/x/.err")" = 1 -a -n "$(grep 'x.journal is not a sweep journal' "$work/res/x/.err")"

finish
