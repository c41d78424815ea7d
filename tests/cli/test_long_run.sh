#!/usr/bin/env bash
# A long run's keys through the tool (tests/test_long_run.c checks them through the library):
#   - end_at_rest: rub-damped.cfg's rotor, nothing pushing it, spinning down freely from 100 rad/s
#     under a constant drag torque 0.7 N m on J = 0.01 kg m^2, ends complete at the first 1 ms grid
#     sample at rest (after 0.99 J Omega0 / T = 1.4142857 s: at 1.415 s), says so in the text and the
#     JSON, and its files end there;
#   - output.window and output.events = false: the window file has one row per window and its flag,
#     /windows is in the HDF5 file, and the samples are the grid's alone (the same run with its events
#     has both); the events are not recorded, so there is no events file (a stale one is removed, no
#     temporary one is left) and no /events table, which would say "no events, complete" of a run that
#     had them: the JSON names no events file and still counts the events;
#   - a window shorter than a sample interval, or not a whole number of them, is refused with one
#     line (exit 2, no file);
#   - end_at_rest tests the last sample too (a run at rest at end_time ended at rest), tests the
#     speed only after the last schedule entry (a drop still to come), and is refused (exit 2, one
#     line naming it) on a rotor already at rest, held at speed or ramped to a speed it holds;
#   - a free spin whose drive outruns its drag under end_at_rest runs to end_time at the closed-form
#     speed and says it did not come to rest (a warning, ended_at_rest false, the text's line).
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
rub=$src/cases/rub-damped.cfg
work=$(mktemp -d "${PWD}/long-run.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
need h5ls hdf5-tools

spin=(--set 'unbalances=()' --set 'schedule=()' --set speed=100
    --set 'spin={free=true; inertia=0.01; drag_torque=0.7; drag_viscous=0.0;}' --set end_time=3
    --set output.sample_rate=1000 --set end_at_rest=true)

t "$work/rest" run "${spin[@]}" "$rub" -o r
check "end_at_rest: exit 0 (got $rc: $(head -c 300 "$work/rest/.err"))" test "$rc" = 0
check "end_at_rest: the text says when ($(grep '^ended at rest' "$work/rest/.out"))" \
    grep -q '^ended at rest  *at 1.4150000000 s' "$work/rest/.out"
t "$work/rest-json" run -q --json --csv '' --hdf5 '' "${spin[@]}" "$rub"
check "end_at_rest: JSON ended_at_rest true, t_reached 1.415 ($(jf "$work/rest-json/.out" ended_at_rest), \
$(jf "$work/rest-json/.out" t_reached))" \
    test "$(jf "$work/rest-json/.out" ended_at_rest)" = true -a "$(jf "$work/rest-json/.out" t_reached)" = 1.415
check "end_at_rest: complete ($(jf "$work/rest-json/.out" complete))" \
    test "$(jf "$work/rest-json/.out" complete)" = true
t "$work/plain" run -q --json --csv '' --hdf5 '' --set end_time=0.01 "$rub"
check "a run without end_at_rest has no ended_at_rest member" test -z "$(jf "$work/plain/.out" ended_at_rest)"
# the last sample is tested like the others: the same spin-down with end_time = 1.4145 s, where its
# speed is 100 - 70 x 1.4145 = 0.985 rad/s (at rest: below 1 rad/s), ends there at rest, no warning
t "$work/rest-end" run --json --csv '' --hdf5 '' "${spin[@]}" --set end_time=1.4145 --set output.section_after=0 "$rub"
check "end_at_rest, at rest at end_time: JSON ended_at_rest true at 1.4145 s, no warning ($(jf "$work/rest-end/.out" \
ended_at_rest), $(jf "$work/rest-end/.out" t_reached), $(cat "$work/rest-end/.err"))" \
    test "$rc" = 0 -a "$(jf "$work/rest-end/.out" ended_at_rest)" = true -a ! -s "$work/rest-end/.err"
check "end_at_rest, at rest at end_time: t_reached 1.4145 s ($(jf "$work/rest-end/.out" t_reached))" \
    awk -v a="$(jf "$work/rest-end/.out" t_reached)" 'BEGIN { exit !(a != "" && a - 1.4145 < 1e-9 && 1.4145 - a < 1e-9) }'
check "end_at_rest: the CSV file's last sample is at 1.415 s ($(grep -v '^#' "$work/rest/r.csv" | tail -n 1 | cut -d, -f1))" \
    test "$(grep -v '^#' "$work/rest/r.csv" | tail -n 1 | cut -d, -f1)" = 1.415

# end_at_rest waits for the last prescribed change: the same rotor under a viscous drag only
# (J dOmega/dt = -c Omega, Omega = 100 exp(-c t / J), c / J = 5 /s) is below 1 % of its start speed
# from ln(100) / 5 = 0.921 s, but an AMB is scheduled to fail at 1.2 s: the run ends at the first
# grid sample after the failure, 1.201 s, and its ending is judged over the whole run it reached
visc=(--set 'unbalances=()' --set 'schedule=({time=1.2; amb_off=0;})' --set speed=100
    --set 'spin={free=true; inertia=0.01; drag_torque=0.0; drag_viscous=0.05;}' --set end_time=3
    --set output.sample_rate=1000 --set end_at_rest=true)
near() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a - b < 1e-9 && b - a < 1e-9) }'; }
t "$work/sched" run -q --json --csv '' --hdf5 '' "${visc[@]}" "$rub"
check "end_at_rest after the schedule's last entry: exit 0, ended at rest ($rc, $(jf "$work/sched/.out" ended_at_rest))" \
    test "$rc" = 0 -a "$(jf "$work/sched/.out" ended_at_rest)" = true
check "end_at_rest after the schedule's last entry: t_reached 1.201 s ($(jf "$work/sched/.out" t_reached))" \
    near "$(jf "$work/sched/.out" t_reached)" 1.201
check "end_at_rest: ending_window is the time reached, 1.201 s ($(jf "$work/sched/.out" ending_window))" \
    near "$(jf "$work/sched/.out" ending_window)" 1.201
# a drive that outruns the drag (1.0 against 0.7 N m on J = 0.01 kg m^2: J dOmega/dt = 0.3 N m, so
# Omega = 100 + 30 t, 115 rad/s at 0.5 s): the run reaches end_time at speed, says so in a warning
# naming end_at_rest and the drive, and in the summary (ended_at_rest false, the text's line)
drive=(--set 'unbalances=()' --set 'schedule=()' --set speed=100 --set end_time=0.5 --set output.section_after=0
    --set 'spin={free=true; inertia=0.01; drive_torque=1.0; drag_torque=0.7;}' --set output.sample_rate=1000
    --set end_at_rest=true)
t "$work/drive" run --json --csv '' --hdf5 '' "${drive[@]}" "$rub"
check "end_at_rest, drive > drag: exit 0, complete at 0.5 s ($rc, $(jf "$work/drive/.out" t_reached))" \
    test "$rc" = 0 -a "$(jf "$work/drive/.out" complete)" = true -a "$(jf "$work/drive/.out" t_reached)" = 0.5
check "end_at_rest, drive > drag: JSON ended_at_rest false ($(jf "$work/drive/.out" ended_at_rest))" \
    test "$(jf "$work/drive/.out" ended_at_rest)" = false
check "end_at_rest, drive > drag: final speed 115 rad/s, the closed form ($(jf "$work/drive/.out" final_speed))" \
    near "$(jf "$work/drive/.out" final_speed)" 115
check "end_at_rest, drive > drag: one warning line naming end_at_rest and the drive ($(cat "$work/drive/.err"))" \
    test "$(grep -c 'warning: end_at_rest: the rotor did not come to rest by end_time 0.5 s.*spin.drive_torque 1 N m exceeds' \
        "$work/drive/.err")" = 1
t "$work/drive-text" run --csv '' --hdf5 '' "${drive[@]}" "$rub"
check "end_at_rest, drive > drag: the text says it did not ($(grep '^ended at rest' "$work/drive-text/.out"))" \
    grep -q '^ended at rest  *no: at speed at end_time 0.5 s' "$work/drive-text/.out"
# a rotor that cannot come to rest is refused, naming end_at_rest: one already at rest, one held at speed
t "$work/still" run -q --set speed=0 --set end_time=0.5 "$src/cases/drop-to-rest.cfg" -o s
check "end_at_rest at a start speed of 0: exit 2, one line naming end_at_rest ($(cat "$work/still/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/still/.err")" = 1 -a -n "$(grep -F 'drop-to-rest.cfg:' "$work/still/.err" | grep -F 'end_at_rest: the start speed 0 rad/s')"
t "$work/held" run -q --set end_at_rest=true "$rub" -o h
check "end_at_rest at a held speed: exit 2, one line naming end_at_rest ($(cat "$work/held/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/held/.err")" = 1 -a -n "$(grep -F 'end_at_rest: the speed is held at 90 rad/s' "$work/held/.err")"
# a speed_ramp ending at 50 rad/s holds that speed for ever: refused too (not a run to end_time)
t "$work/ramp" run -q --set end_at_rest=true --set 'schedule=()' \
    --set 'speed_ramp=({time=0.0; speed=90.0;}, {time=0.2; speed=50.0;})' "$rub" -o p
check "end_at_rest on a ramp ending at speed: exit 2, one line naming end_at_rest ($(cat "$work/ramp/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/ramp/.err")" = 1 -a -n "$(grep -F 'end_at_rest: the speed_ramp ends at 50 rad/s (at 0.2 s) and holds that speed' "$work/ramp/.err")"
check "end_at_rest refused: no file" test -z "$(ls "$work/still")$(ls "$work/held")$(ls "$work/ramp")"

mkdir -p "$work/win" && echo "stale" >"$work/win/w.events.csv"
t "$work/win" run -q --json --set end_time=0.3 --set output.window=0.05 --set output.events=false "$rub" -o w
check "windows: exit 0 (got $rc: $(head -c 300 "$work/win/.err"))" test "$rc" = 0
check "windows: 6 rows and the flag in w.windows.csv ($(grep -vc '^#' "$work/win/w.windows.csv") lines)" \
    test "$(grep -vc '^#' "$work/win/w.windows.csv")" = 7 -a "$(tail -n 1 "$work/win/w.windows.csv")" = "# complete"
check "windows: its header starts with t_start, t_end, speed ($(head -c 40 "$work/win/w.windows.csv"))" \
    grep -q '^t_start \[s\],t_end \[s\],speed \[rad/s\],' "$work/win/w.windows.csv"
check "events = false: no events file, not even a stale one, and no temporary file ($(ls "$work/win" | tr '\n' ' '))" \
    test ! -e "$work/win/w.events.csv" -a -z "$(ls "$work/win" | grep -F partial)"
check "events = false: no /events or /event in w.h5 ($(h5ls "$work/win/w.h5" | grep -cE '^event'))" \
    test -z "$(h5ls "$work/win/w.h5" | grep -E '^events? ')"
check "events = false: the JSON names no events file and counts the events ($(jf "$work/win/.out" events_path), \
$(jf "$work/win/.out" events))" \
    test "$(jf "$work/win/.out" events_path)" = null -a "$(jf "$work/win/.out" events)" -gt 0
check "events = false: the samples file still ends with its flag ($(tail -n 1 "$work/win/w.csv"))" \
    test "$(tail -n 1 "$work/win/w.csv")" = "# complete"
check "events = false: the 3001 grid samples and nothing else in w.csv ($(grep -vc '^#' "$work/win/w.csv") lines)" \
    test "$(grep -vc '^#' "$work/win/w.csv")" = 3002
t "$work/ev" run -q --set end_time=0.3 "$rub" -o e
check "events = true: the same run's events file has rows, w.csv as many more ($(grep -vc '^#' "$work/ev/e.events.csv"), \
$(grep -vc '^#' "$work/ev/e.csv"))" \
    test "$(grep -vc '^#' "$work/ev/e.events.csv")" -gt 1 -a "$(grep -vc '^#' "$work/ev/e.csv")" -gt 3002
check "windows: /windows/contact_fraction in w.h5 is 6 x 2" \
    test -n "$(h5ls "$work/win/w.h5/windows/contact_fraction" | grep -F '{6/Inf, 2}')"

t "$work/short" run -q --set output.window=1e-5 "$rub" -o s
check "window shorter than a sample interval: exit 2, one line naming output.window ($(cat "$work/short/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/short/.err")" = 1 -a -n "$(grep -F 'output.window' "$work/short/.err")"
check "window shorter than a sample interval: no file" test -z "$(ls "$work/short")"
# rub-damped.cfg samples at 10 kHz: 0.15 ms is one and a half sample intervals, which a window
# closed at grid samples would silently make 0.2 ms
t "$work/half" run -q --set output.window=1.5e-4 "$rub" -o h
check "window not a whole number of sample intervals: exit 2, one line naming output.window ($(cat "$work/half/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/half/.err")" = 1 -a -n "$(grep -F 'output.window: 0.00015 s is not a whole number of sample intervals' "$work/half/.err")"
check "window not a whole number of sample intervals: no file" test -z "$(ls "$work/half")"

finish
