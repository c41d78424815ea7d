#!/usr/bin/env bash
# Faults during `touchdown run`, and the completeness rule of docs/output-format.md:
#   1. while a run goes on only PATH.XXXXXX.partial exists (the directory is listed while it runs), a
#      stale result at PATH is removed, and a file at a final path is always complete; a finished
#      run leaves its three files at their final paths, complete (HDF5 complete = 1, CSV and event
#      CSV end with "# complete"), and no .partial;
#   2. SIGINT and SIGTERM, sent about 1 s into cases/paper-a.cfg (end_time raised to 100 s so that
#      the run is still going on however fast the machine): exit 1, an error line with the
#      reason and the simulated time, the files at their final paths with complete = 0, the
#      incomplete_reason and the CSV's "# incomplete: ..." line giving the same time, t_reached
#      in the HDF5 file equal to that time, no .partial left;
#   3. a solver failure (solver.atol = 1e-300, accepted by the case reader; IDA fails at the
#      first impact): exit 1, the message, incomplete files;
#   4. SIGKILL (cannot be caught): only .partial files remain, nothing at a final path;
#   5. an output path that cannot be created: exit 2 (bad input, refused before the run), one error line, no file left;
#   6. SIGINT while the solver is slow inside one step (solver.max_step = 1e-12 s over end_time =
#      5e-5 s, 5e7 steps, within the step bound of touchdown/limits.h; free flight off, which would
#      carry the contact-free run in closed form, without steps): the run must still stop
#      (the 10 s limit catches a hang only: it stops 0.12 s after the signal under ASan on a
#      loaded machine) with exit 1 and incomplete files;
#   7. a full disk, simulated by the file size limit (ulimit -f, SIGXFSZ ignored, so writes fail
#      with EFBIG): exit 1 (no crash in HDF5's exit handler), one error line naming the cause, no
#      temporary file left and nothing at a final path that does not say incomplete; the test
#      fails (it does not skip) when the limit cannot be put in force;
#   8. two runs writing the same output paths at once (HDF5 file locking off): each file at a
#      final path holds the rows of the one run its case text names (its last time is that run's
#      end_time), never a mixture;
#   9. output paths refused before the run with exit 2, one error line, no file written and the
#      inputs unchanged: two outputs that are one file (also through the events file, a hard link
#      or a symbolic link), an output that is the case file or an @include file, an output named
#      *.partial, an output that is a device node or a directory, an output directory that does
#      not exist or is not writable, a path longer than 1023 characters (also for modal and
#      bench).
# HDF5 attributes are read with h5dump (Debian package hdf5-tools); without it the test fails.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
case_a=$src/cases/paper-a.cfg
work=$(mktemp -d "${PWD}/run-faults.XXXXXX")
pids=()
cleanup() {
    local p
    for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
    rm -rf "$work"
}
trap cleanup EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

need h5dump hdf5-tools

# h5attr FILE NAME: the value of a root attribute (strings without quotes); fails if absent.
h5attr() {
    h5dump -m '%.17g' -a "/$2" "$1" 2>/dev/null | sed -nE 's/^[[:space:]]*\(0\): "?([^"]*)"?[[:space:]]*$/\1/p' | head -n 1 | grep .
}
last_line() { tail -n 1 "$1" 2>/dev/null; }
same_time() { awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= 1e-9) }'; }

# partial_of FILE: the temporary file(s) of the output FILE (FILE.XXXXXX.partial), one a line.
partial_of() {
    local p
    for p in "$1".*.partial; do [ -e "$p" ] && echo "$p"; done
    return 0
}
# wait_for_data DIR: wait (at most 60 s) until DIR's temporary paper-a.csv holds data.
wait_for_data() {
    local i p
    for ((i = 0; i < 1200; i++)); do
        p=$(partial_of "$1/paper-a.csv")
        [ -n "$p" ] && [ -s "$p" ] && return 0
        sleep 0.05
    done
    return 1
}
# wait_exit PID SECONDS: wait for the process; kill it (and fail) if it outlives SECONDS.
wait_exit() {
    local pid=$1 limit=$2 i
    for ((i = 0; i < limit * 20; i++)); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.05
    done
    if kill -0 "$pid" 2>/dev/null; then
        kill -9 "$pid" 2>/dev/null
        wait "$pid" 2>/dev/null
        rc=timeout
        return 1
    fi
    wait "$pid"
    rc=$?
    return 0
}

# check_final DIR WANT(complete|incomplete) [REASON_WORD]: the three files at final paths, no
# .partial, and their flags. Sets reason_time to the time named in the CSV's incomplete line.
check_final() {
    local d=$1 want=$2 word=${3:-} f last reason h5c h5r tr
    reason_time=""
    for f in paper-a.h5 paper-a.csv paper-a.events.csv; do
        check "$want: $f at its final path" test -s "$d/$f"
        check "$want: no temporary $f left" test -z "$(partial_of "$d/$f")"
    done
    for f in paper-a.csv paper-a.events.csv; do
        last=$(last_line "$d/$f")
        if [ "$want" = complete ]; then
            check "$want: $f ends with '# complete' (got '$last')" test "$last" = "# complete"
        else
            case "$last" in
            "# incomplete: "*"$word"*) pass "$want: $f ends with '$last'" ;;
            *) fail "$want: $f ends with '$last', expected '# incomplete: ...$word...'" ;;
            esac
        fi
    done
    reason=$(last_line "$d/paper-a.csv")
    reason_time=$(printf '%s\n' "$reason" | grep -oE 't = [0-9.eE+-]+ s' | head -n 1 | sed -E 's/t = (.*) s/\1/')
    h5c=$(h5attr "$d/paper-a.h5" complete)
    if [ "$want" = complete ]; then
        check "HDF5 complete = 1 (got '$h5c')" test "$h5c" = 1
        check "HDF5 has no incomplete_reason" test -z "$(h5attr "$d/paper-a.h5" incomplete_reason)"
    else
        check "HDF5 complete = 0 (got '$h5c')" test "$h5c" = 0
        h5r=$(h5attr "$d/paper-a.h5" incomplete_reason)
        case "$h5r" in
        *"$word"*) pass "HDF5 incomplete_reason '$h5r'" ;;
        *) fail "HDF5 incomplete_reason '$h5r' lacks '$word'" ;;
        esac
        check "HDF5 incomplete_reason equals the CSV's ('$h5r')" test "# incomplete: $h5r" = "$reason"
        tr=$(h5attr "$d/paper-a.h5" t_reached)
        check "HDF5 t_reached ($tr) is the time in the reason ($reason_time)" same_time "$tr" "$reason_time"
    fi
}

# The finished runs of 1 and 8 end at 0.3 s (0.29 s for 8's twin); under the sanitizers
# (TD_TEST_SANITIZED=1) at 0.15 s (0.14 s), past case A's first contact (0.105 s) and its events:
# the writers, their temporary files, locks and renames are the same code for a shorter run, and
# these runs were most of the test's time under ASan.
run_end=0.3
twin_ends="0.3 0.29"
if sanitized; then
    run_end=0.15
    twin_ends="0.15 0.14"
fi

# ---- 1. during a run: only .partial; after it: complete files at final paths -----------------
d=$work/listing
mkdir -p "$d"
echo "stale" >"$d/paper-a.csv"
echo "stale" >"$d/paper-a.h5"
(cd "$d" && exec "$tool" run -q --set end_time=$run_end "$case_a" >"$work/l.out" 2>"$work/l.err") &
pid=$!
pids+=("$pid")
polls=0
partial_only=0
stale_gone=0
bad_final=""
while kill -0 "$pid" 2>/dev/null; do
    polls=$((polls + 1))
    have_partial=0
    [ -n "$(partial_of "$d/paper-a.csv")" ] && have_partial=1
    for f in paper-a.csv paper-a.events.csv; do
        if [ -e "$d/$f" ] && [ "$(cat "$d/$f" 2>/dev/null | head -c 5)" != "stale" ] &&
            [ "$(last_line "$d/$f")" != "# complete" ] && [ -e "$d/$f" ]; then
            bad_final="$bad_final $f(poll $polls: last line '$(last_line "$d/$f")')"
        fi
    done
    if [ $have_partial = 1 ] && [ ! -e "$d/paper-a.csv" ] && [ ! -e "$d/paper-a.h5" ] &&
        [ ! -e "$d/paper-a.events.csv" ]; then
        partial_only=$((partial_only + 1))
        stale_gone=1
    fi
    sleep 0.05
done
wait "$pid"
rc=$?
check "complete run: exit 0 (got $rc; $(head -c 200 "$work/l.err"))" test "$rc" = 0
# (but its warnings: case A's second unbalance step, at 1.1 s, never happens in 0.3 s)
check "complete run: nothing on stderr but warnings" test -z "$(grep -v ': warning: ' "$work/l.err")"
check "while running: $partial_only of $polls listings showed only .partial files (stale results removed)" \
    test "$partial_only" -ge 1 -a "$stale_gone" = 1
check "while running: no incomplete file at a final path${bad_final:+ (saw$bad_final)}" test -z "$bad_final"
check_final "$d" complete

# ---- 2. SIGINT and SIGTERM about 1 s into the run ------------------------------------------
for sig in INT TERM; do
    d=$work/sig$sig
    mkdir -p "$d"
    (cd "$d" && exec "$tool" run --set end_time=100 "$case_a" >"$work/s.out" 2>"$work/s.err") &
    pid=$!
    pids+=("$pid")
    if ! wait_for_data "$d"; then
        fail "SIG$sig: no data written within 60 s"
        continue
    fi
    sleep 1
    kill -"$sig" "$pid"
    if ! wait_exit "$pid" 30; then
        fail "SIG$sig: the run did not stop within 30 s"
        continue
    fi
    err=$(cat "$work/s.err")
    check "SIG$sig: exit 1 (got $rc)" test "$rc" = 1
    check "SIG$sig: one error line on stderr (got $(wc -l <"$work/s.err"))" test "$(wc -l <"$work/s.err")" = 1
    msg_time=$(printf '%s\n' "$err" | sed -nE 's/.*interrupted at t = ([0-9.eE+-]+) s.*/\1/p')
    check "SIG$sig: the message gives the reason and the simulated time: $err" test -n "$msg_time"
    check "SIG$sig: the message names the case" grep -qF "$case_a" "$work/s.err"
    check "SIG$sig: stopped inside the run (0 < t = $msg_time < 100)" \
        awk -v t="$msg_time" 'BEGIN { exit !(t > 0 && t < 100) }'
    check "SIG$sig: the summary on stdout says INCOMPLETE" grep -q "INCOMPLETE (interrupted)" "$work/s.out"
    check_final "$d" incomplete interrupted
    check "SIG$sig: the CSV's reason gives the same time ($reason_time)" same_time "$reason_time" "$msg_time"
    last_t=$(grep -v '^#' "$d/paper-a.csv" | tail -n 1 | cut -d, -f1)
    check "SIG$sig: the last CSV row ($last_t s) is at that time" same_time "$last_t" "$msg_time"
done

# ---- 3. a solver failure: an impossible tolerance that the case reader accepts ---------------
d=$work/solver
mkdir -p "$d"
(cd "$d" && timeout -s KILL 120 "$tool" run --set end_time=0.3 --set solver.atol=1e-300 "$case_a" \
    >"$work/f.out" 2>"$work/f.err")
rc=$?
err=$(cat "$work/f.err")
check "solver failure: exit 1 (got $rc)" test "$rc" = 1
check "solver failure: one error line besides the warnings (got $(grep -vc ': warning: ' "$work/f.err"))" \
    test "$(grep -vc ': warning: ' "$work/f.err")" = 1
check "solver failure: the message says what failed and when: $err" \
    grep -qE "fail.*t = [0-9]" "$work/f.err"
check "solver failure: the summary on stdout says INCOMPLETE" grep -q "INCOMPLETE (solver failure)" "$work/f.out"
check_final "$d" incomplete fail
st=$(h5attr "$d/paper-a.h5" status)
check "solver failure: HDF5 status '$st'" test "$st" = "solver failure"

# leftovers_check DIR: DIR holds the leftovers of a run killed with SIGKILL (its writer gone). A new
# run on the same paths removes them when it opens its outputs, never a live run's temporary files
# (each writer holds a lock on its own, lib/io/writer.c): a run started beside a live one writes
# its own temporary files, finishes, and leaves the live run's alone.
leftovers_check() {
    local d=$1 dead live p i gone=0
    dead=$(ls "$d" | grep '\.partial$' | tr '\n' ' ')
    (cd "$d" && exec "$tool" run -q --set end_time=100 "$case_a" >/dev/null 2>&1) &
    live_pid=$!
    pids+=("$live_pid")
    for ((i = 0; i < 1200 && gone == 0; i++)); do # until the live run's writer has swept the dead one's
        gone=1
        for p in $dead; do [ -e "$d/$p" ] && gone=0; done
        sleep 0.05
    done
    check "SIGKILL leftovers ($dead) removed by the next run on the same paths" test "$gone" = 1
    if ! wait_for_data "$d"; then
        fail "leftovers: the live run wrote no data within 60 s"
    fi
    live=$(ls "$d" | grep '\.partial$' | tr '\n' ' ')
    check "leftovers: the live run has its three temporary files ($live)" test "$(echo $live | wc -w)" = 3
    (cd "$d" && "$tool" run -q --set end_time=0.01 "$case_a" >"$work/beside.out" 2>&1)
    rc=$?
    check "a run beside a live one on the same paths: exit 0 (got $rc: $(head -c 300 "$work/beside.out"))" test "$rc" = 0
    check "a run beside a live one: its results at the final paths" \
        test -s "$d/paper-a.csv" -a -s "$d/paper-a.h5" -a -s "$d/paper-a.events.csv"
    for p in $live; do
        check "a run beside a live one leaves the live run's $p" test -e "$d/$p"
    done
    check "the live run still runs" kill -0 "$live_pid"
    kill -9 "$live_pid" 2>/dev/null
    wait "$live_pid" 2>/dev/null
}

# ---- 4. SIGKILL: nothing can be finished, so nothing may appear at a final path ------------
d=$work/kill
mkdir -p "$d"
(cd "$d" && exec "$tool" run -q --set end_time=100 "$case_a" >/dev/null 2>&1) &
pid=$!
pids+=("$pid")
if wait_for_data "$d"; then
    sleep 0.3
    kill -9 "$pid"
    wait "$pid" 2>/dev/null
    check "SIGKILL: temporary files remain" test -n "$(partial_of "$d/paper-a.csv")" -a -n "$(partial_of "$d/paper-a.h5")"
    check "SIGKILL: nothing at the final paths ($(ls "$d" | tr '\n' ' '))" \
        test ! -e "$d/paper-a.csv" -a ! -e "$d/paper-a.h5" -a ! -e "$d/paper-a.events.csv"
    leftovers_check "$d"
else
    fail "SIGKILL: no data written within 60 s"
fi

# ---- 5. an output file that cannot be created ----------------------------------------------
d=$work/nodir
mkdir -p "$d"
(cd "$d" && "$tool" run --set end_time=0.01 --hdf5 "$d/missing-dir/x.h5" --csv "$d/x.csv" "$case_a" \
    >"$work/n.out" 2>"$work/n.err")
rc=$?
check "uncreatable output: exit 2, refused before the run (got $rc)" test "$rc" = 2
check "uncreatable output: one error line naming the path: $(cat "$work/n.err")" \
    test "$(wc -l <"$work/n.err")" = 1 -a -n "$(grep -F "missing-dir/x.h5" "$work/n.err")"
check "uncreatable output: no file left ($(ls -A "$d" | tr '\n' ' '))" test -z "$(ls -A "$d")"

# ---- 6. an interrupt while the solver crawls ---------------------------------------------------
d=$work/crawl
mkdir -p "$d"
(cd "$d" && exec "$tool" run --set solver.max_step=1e-12 --set solver.free_flight=false --set end_time=5e-5 "$case_a" >"$work/c.out" \
    2>"$work/c.err") &
pid=$!
pids+=("$pid")
sleep 1
kill -INT "$pid"
if wait_exit "$pid" 10; then
    check "SIGINT with max_step = 1e-12: exit 1 (got $rc: $(head -c 200 "$work/c.err"))" test "$rc" = 1
    check "SIGINT with max_step = 1e-12: the files are at their final paths, incomplete" \
        test "$(last_line "$d/paper-a.csv" | cut -c1-14)" = "# incomplete: "
else
    fail "SIGINT with max_step = 1e-12: still running 10 s after the signal (killed)"
fi

# ---- 7. a full disk: the file size limit --------------------------------------------------
# limited_run NAME ARGS...: `touchdown run -q CASE_A ARGS` under a 256 KiB file size limit.
# Exit 97/98 (not the tool's codes) say the limit could not be put in force.
limited_run() {
    local name=$1
    shift
    (
        trap '' XFSZ
        ulimit -f 256 || exit 98
        head -c 400000 /dev/zero >"$d/probe" 2>/dev/null
        [ "$(wc -c <"$d/probe")" -le 262144 ] || exit 97
        rm -f "$d/probe"
        exec "$tool" run -q "$case_a" "$@"
    ) >"$work/$name.out" 2>"$work/$name.err"
    rc=$?
}
for outs in h5 csv both; do
    d=$work/full-$outs
    mkdir -p "$d"
    case $outs in
    h5) limited_run "full-$outs" --csv '' --hdf5 "$d/paper-a.h5" ;;
    csv) limited_run "full-$outs" --hdf5 '' --csv "$d/paper-a.csv" ;;
    both) limited_run "full-$outs" -o "$d/paper-a" ;;
    esac
    if [ "$rc" = 97 ] || [ "$rc" = 98 ]; then
        fail "full disk ($outs): the file size limit could not be set up (exit $rc)"
        continue
    fi
    check "full disk ($outs): exit 1 (got $rc: $(head -c 300 "$work/full-$outs.err"))" test "$rc" = 1
    check "full disk ($outs): one error line naming the cause" \
        test "$(wc -l <"$work/full-$outs.err")" = 1 -a -n "$(grep -F "File too large" "$work/full-$outs.err")"
    for f in paper-a.h5 paper-a.csv paper-a.events.csv; do
        check "full disk ($outs): no temporary $f left" test -z "$(partial_of "$d/$f")"
        [ -e "$d/$f" ] || continue
        case $f in
        *.csv) check "full disk ($outs): $f at its final path is marked incomplete" \
            test "$(last_line "$d/$f" | cut -c1-14)" = "# incomplete: " ;;
        *) check "full disk ($outs): $f at its final path has complete = 0" \
            test "$(h5attr "$d/$f" complete)" = 0 ;;
        esac
    done
done

# ---- 8. two runs on the same output paths at once -------------------------------------------
d=$work/twins
mkdir -p "$d"
twin_pids=()
for end in $twin_ends; do
    (cd "$d" && HDF5_USE_FILE_LOCKING=FALSE exec "$tool" run -q --set end_time=$end "$case_a" -o "$d/r" \
        >"$work/twin$end.out" 2>"$work/twin$end.err") &
    twin_pids+=($!)
    pids+=($!)
done
# The runs must overlap for the check to mean anything: two temporary CSV files at once.
overlap=0
while kill -0 "${twin_pids[0]}" 2>/dev/null || kill -0 "${twin_pids[1]}" 2>/dev/null; do
    [ "$(partial_of "$d/r.csv" | wc -l)" -ge 2 ] && overlap=1
    sleep 0.02
done
for i in 0 1; do
    wait "${twin_pids[$i]}"
    rc=$?
    check "concurrent run $i: exit 0 (got $rc: $(cat "$work"/twin*.err | head -c 300))" test "$rc" = 0
done
check "concurrent runs overlapped (two temporary files of r.csv seen at once)" test "$overlap" = 1
for f in r.csv r.events.csv r.h5; do
    check "concurrent runs: no temporary $f left" test -z "$(partial_of "$d/$f")"
done
csv_end=$(sed -nE 's/^#\| # --set end_time=([0-9.]+)$/\1/p' "$d/r.csv")
csv_last=$(grep -v '^#' "$d/r.csv" | tail -n 1 | cut -d, -f1)
check "concurrent runs: r.csv ends '# complete'" test "$(last_line "$d/r.csv")" = "# complete"
check "concurrent runs: r.csv's last row (t = $csv_last) is its own run's end_time ($csv_end)" \
    same_time "$csv_last" "$csv_end"
check "concurrent runs: r.csv's rows are in time order" \
    awk -F, '!/^#/ && NR > 1 { if ($1 + 0 < last) exit 1; last = $1 + 0 }' "$d/r.csv"
h5_end=$(h5dump -a /case_text "$d/r.h5" 2>/dev/null | grep -oE -- '--set end_time=[0-9.]+' | cut -d= -f2)
h5dump -d /time -y -w 0 -o "$work/twin-time.txt" "$d/r.h5" >/dev/null 2>&1
h5_last=$(tr ', ' '\n\n' <"$work/twin-time.txt" | grep . | tail -n 1)
check "concurrent runs: r.h5 complete = 1" test "$(h5attr "$d/r.h5" complete)" = 1
check "concurrent runs: r.h5's last time ($h5_last) is its own run's end_time ($h5_end)" \
    same_time "$h5_last" "$h5_end"

# ---- 9. output paths refused before the run -------------------------------------------------
d=$work/refuse
mkdir -p "$d/inc" "$d/ro"
cp "$src/cases/jeffcott.cfg" "$d/CASE.cfg"
cp "$src/cases/jeffcott.cfg" "$d/inc/part.cfg"
printf '# a comment\n' >"$d/inc/more.events.csv"
printf '@include "part.cfg"\n@include "more.events.csv"\n' >"$d/inc/main.cfg"
ln "$d/CASE.cfg" "$d/hard.cfg"
ln -s CASE.cfg "$d/soft.cfg"
cp -r "$d" "$work/refuse.orig"
long=$(printf 'a%.0s' $(seq 1 1030))
# refused DESCRIPTION ARGS...: `touchdown run ARGS` in $d exits 2 with one error line, and the
# directory is exactly as before (no output, no temporary file, the inputs unchanged).
refused() {
    local what=$1
    shift
    (cd "$d" && "$tool" run -q --set end_time=0.01 "$@" >"$work/r.out" 2>"$work/r.err")
    rc=$?
    check "$what: exit 2 (got $rc: $(head -c 200 "$work/r.err"))" test "$rc" = 2
    check "$what: one error line" test "$(wc -l <"$work/r.err")" = 1
    check "$what: nothing written, inputs unchanged" diff -r "$work/refuse.orig" "$d"
}
refused "--hdf5 X --csv X" --hdf5 X --csv X CASE.cfg
refused "--hdf5 r.events.csv --csv r.csv" --hdf5 r.events.csv --csv r.csv CASE.cfg
refused "--hdf5 r.h5 --csv r.h5" --hdf5 r.h5 --csv ./r.h5 CASE.cfg
refused "--csv r.h5.partial" --csv r.h5.partial CASE.cfg
refused "--hdf5 CASE.cfg CASE.cfg" --hdf5 CASE.cfg CASE.cfg
refused "--csv ../refuse/CASE.cfg CASE.cfg" --hdf5 '' --csv ../refuse/CASE.cfg CASE.cfg
refused "output is a hard link to the case file" --hdf5 hard.cfg --csv '' CASE.cfg
refused "output is a symbolic link to the case file" --hdf5 soft.cfg --csv '' CASE.cfg
refused "output is an @include file" --hdf5 inc/part.cfg --csv '' inc/main.cfg
refused "events output is an @include file" --hdf5 '' --csv inc/more.csv inc/main.cfg
refused "output is a device node (/dev/null)" --hdf5 /dev/null --csv '' CASE.cfg
refused "output is a directory" --hdf5 inc --csv '' CASE.cfg
refused "output directory does not exist" --hdf5 no-such-dir/x.h5 --csv '' CASE.cfg
refused "-o with a 1030-character prefix" -o "$long" CASE.cfg
refused "--csv with a 1030-character path" --hdf5 '' --csv "$long.csv" CASE.cfg
# the same rules for the modal outputs, refused before the analysis
refused_modal() {
    local what="modal: $1"
    shift
    (cd "$d" && "$tool" modal -q "$@" >"$work/r.out" 2>"$work/r.err")
    rc=$?
    check "$what: exit 2, one error line (got $rc: $(head -c 200 "$work/r.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$work/r.err")" = 1
    check "$what: nothing written, inputs unchanged" diff -r "$work/refuse.orig" "$d"
}
refused_modal "--hdf5 X --csv X" --hdf5 X --csv X CASE.cfg
refused_modal "--csv CASE.cfg CASE.cfg" --hdf5 '' --csv CASE.cfg CASE.cfg
refused_modal "output is a symbolic link to the case file" --hdf5 soft.cfg --csv '' CASE.cfg
refused_modal "output is an @include file" --hdf5 inc/part.cfg --csv '' inc/main.cfg
refused_modal "--csv m.h5.partial" --hdf5 '' --csv m.h5.partial CASE.cfg
refused_modal "output directory does not exist" --hdf5 no-such-dir/x.h5 --csv '' CASE.cfg
for sub in "modal -q -o $long CASE.cfg" "modal -q --csv $long.csv CASE.cfg" "bench --quick --dir $long"; do
    (cd "$d" && "$tool" $sub >"$work/r.out" 2>"$work/r.err")
    rc=$?
    check "touchdown ${sub%% *} with a 1030-character path: exit 2, one line (got $rc: $(head -c 120 "$work/r.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$work/r.err")" = 1
    check "touchdown ${sub%% *} with a 1030-character path: nothing written" diff -r "$work/refuse.orig" "$d"
done
chmod 555 "$d/ro"
if touch "$d/ro/probe" 2>/dev/null; then
    rm -f "$d/ro/probe"
    echo "skip: an unwritable output directory (this user writes into mode 555 directories)"
else
    refused "output directory not writable" --hdf5 ro/x.h5 --csv '' CASE.cfg
fi
chmod 755 "$d/ro"

finish
