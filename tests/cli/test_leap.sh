#!/usr/bin/env bash
# The projective leap through the tool (tests/test_leap.c checks it through the library), end to end
# from the case file to the summary and the files:
#   - rub-damped.cfg's rotor, levitated with its unbalance and nothing scheduled, spinning down
#     freely from 100 rad/s under a drag torque 0.7 N m on J = 0.01 kg m^2, with leaps (bursts of
#     0.1 s, leaps of 4 bursts after 0.05 s of healing, from 0.1 s), ends at rest and says how much
#     it leapt (text and JSON);
#   - the energy account closes over the whole run, leaps included, to 2e-5 of the 50.1 J the machine
#     held, as the integration's own does (5.4e-4 J for this run integrated throughout; a leap at the
#     burst's dOmega/dt left the lateral energy's change over each burst, times the factor, in it:
#     0.088 J);
#   - leap.burst = 0 turns the leaps off (the summary of a run without the group);
#   - the windows (CSV and HDF5) and the samples have no row inside a leap: the gaps between them
#     add up to the time leapt; the files list the leaps (the CSV's `#` lines: the count, each
#     leap's start and length, the lengths adding up to the time leapt) and that the run ended at
#     rest; touchdown plot's data, and touchdown report's, has a blank line (a break in gnuplot's
#     line) at each leap; a sweep's table has the leaps and the end at rest as the run's JSON has
#     them (a point that does not leap: none, NaN);
#   - a rub held through the leaps: the summary's contact time and the stats' time in contact are the
#     retainers' (the contact held up to a burst's ends and the leaps counted), within 10 % of the run
#     integrated throughout, and the ending is that run's kind (no leap crosses the ending's stretch);
#     a bouncing rub's stats count the leaps' onsets and events as the summary does; one leap's
#     spread of dOmega/dt is null;
#   - a leap key written wrong (a misspelt key in the file, a factor below 1, a group on a held
#     speed, a start at or after end_time, a start before a housing shock's end, housing motion held for ever, more retainers than
#     a leap holds) is refused with one line naming the file, the line or the override and the key,
#     exit 2, and no file.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
rub=$src/cases/rub-damped.cfg
work=$(mktemp -d "${PWD}/leap.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
need h5dump hdf5-tools

spin=(--set 'schedule=()' --set speed=100
    --set 'spin={free=true; inertia=0.01; drag_torque=0.7; drag_viscous=0.0;}' --set end_time=2
    --set end_at_rest=true --set energy=true --set output.sample_rate=1000 --set output.window=0.05
    --set output.events=false)
leap='leap={burst=0.1; factor=4.0; heal=0.05; start=0.1;}'
# a <= b, numerically
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 <= b + 0) }'; }

t "$work/run" run --json "${spin[@]}" --set "$leap" "$rub" -o l
out=$work/run/.out
check "leap: exit 0 (got $rc: $(head -c 300 "$work/run/.err"))" test "$rc" = 0
leaps=$(jf "$out" leaps)
leapt=$(jf "$out" leapt_time)
check "leap: ended at rest, with leaps and time leapt in the JSON ($(jf "$out" ended_at_rest), $leaps, $leapt)" \
    test "$(jf "$out" ended_at_rest)" = true -a "${leaps:-0}" -ge 2
check "leap: at least 0.5 s of the run leapt ($leapt)" le 0.5 "$leapt"
residual=$(jf "$out" residual)
initial=$(jf "$out" initial)
abs=$(awk -v r="$residual" 'BEGIN { print r < 0 ? -r : r }')
check "leap: the energy account closes over the run to 2e-5 of $initial J (residual $residual J)" \
    le "$abs" "$(awk -v e="$initial" 'BEGIN { print 2e-5 * e }')"
check "leap: the two rates are given ($(jf "$out" leap_decel_power), $(jf "$out" leap_decel_speed))" \
    test -n "$(jf "$out" leap_decel_power)" -a "$(jf "$out" leap_decel_power)" != null
t "$work/text" run "${spin[@]}" --set "$leap" --csv '' --hdf5 '' "$rub"
check "leap: the text summary says it ($(grep '^leapt' "$work/text/.out"))" \
    grep -q "^leapt (not integrated) .* in $leaps leaps" "$work/text/.out"

# leap.burst = 0 turns a case's leaps off: the run is the one without a leap group, bit for bit
t "$work/off" run -q --json --csv '' --hdf5 '' "${spin[@]}" --set "$leap" --set leap.burst=0 "$rub"
t "$work/none" run -q --json --csv '' --hdf5 '' "${spin[@]}" "$rub"
strip() { sed -E 's/"(wall_time|solver_wall_time|wall_time_per_revolution|realtime_factor)":[^,}]*//g' "$1"; }
check "leap.burst = 0: no leaps member, the same summary as without the group (exit $rc)" \
    test -z "$(jf "$work/off/.out" leaps)" -a -n "$(jf "$work/off/.out" t_reached)" -a \
    "$(strip "$work/off/.out")" = "$(strip "$work/none/.out")"

# the gaps: between consecutive windows (CSV), their HDF5 copies, and the samples, each sums to leapt
gaps_csv=$(grep -v '^#' "$work/run/l.windows.csv" | awk -F, 'NR > 2 { g += $1 - e } NR > 1 { e = $2 } END { print g }')
check "leap: the windows' gaps (CSV) add up to the time leapt ($gaps_csv, $leapt)" \
    awk -v a="$gaps_csv" -v b="$leapt" 'BEGIN { d = a - b; exit !(d < 1e-9 && d > -1e-9) }'
h5col() { h5dump -d "/windows/$1" -y -w 0 "$work/run/l.h5" | awk '/DATA \{/ { getline; gsub(/[ ]/, ""); print; exit }' | tr ',' '\n'; }
gaps_h5=$(paste -d, <(h5col time_start) <(h5col time_end) | awk -F, 'NR > 1 { g += $1 - e } { e = $2 } END { print g }')
check "leap: the windows' gaps (HDF5) add up to the time leapt ($gaps_h5, $leapt)" \
    awk -v a="$gaps_h5" -v b="$leapt" 'BEGIN { d = a - b; exit !(d < 1e-9 && d > -1e-9) }'
gaps_s=$(grep -v '^#' "$work/run/l.csv" | awk -F, 'NR > 2 && $1 - p > 0.0015 { g += $1 - p } NR > 1 { p = $1 } END { print g }')
check "leap: the samples' gaps add up to the time leapt ($gaps_s, $leapt)" \
    awk -v a="$gaps_s" -v b="$leapt" 'BEGIN { d = a - b; exit !(d < 1e-9 && d > -1e-9) }'
# the files list the leaps: the CSV's count, starts and lengths (`#` lines), the lengths adding up
# to the time leapt, and the end at rest
csv_attr() { grep "^# $1 = " "$work/run/l.csv" | cut -d= -f2; }
check "leap: the CSV lists $leaps leaps ($(csv_attr summary_leaps); $(csv_attr leap_time | wc -w) starts, $(csv_attr leap_length | wc -w) lengths)" \
    test "$(csv_attr summary_leaps | tr -d ' ')" = "$leaps" -a "$(csv_attr leap_time | wc -w)" = "$leaps" -a \
    "$(csv_attr leap_length | wc -w)" = "$leaps"
lengths=$(csv_attr leap_length | tr ' ' '\n' | awk '{ s += $1 } END { printf "%.17g", s }')
check "leap: the CSV's leap lengths add up to the time leapt ($lengths, $leapt)" \
    awk -v a="$lengths" -v b="$leapt" 'BEGIN { d = a - b; exit !(d < 1e-9 && d > -1e-9) }'
check "leap: the CSV says the run ended at rest ($(csv_attr summary_ended_at_rest))" \
    test "$(csv_attr summary_ended_at_rest | tr -d ' ')" = 1
check "leap: the HDF5 file lists the leaps too ($(h5dump -a /leap_time "$work/run/l.h5" | grep -c DATASPACE))" \
    h5dump -a /leap_time -a /leap_length -a /summary_leaps -a /summary_ended_at_rest "$work/run/l.h5"
# touchdown plot draws no line across a leap: a blank line in its data at each one
t "$work/plot" plot -q --no-run -d "$work/plot/p" "$work/run/l.h5"
blanks=$(grep -c '^$' "$work/plot/p/retainer0.dat")
check "leap: the plot's data breaks its line at each of the $leaps leaps ($blanks blank lines; exit $rc)" \
    test "$rc" = 0 -a "$blanks" = "$leaps"
# and so does touchdown report's figure: its data, copied by a "gnuplot" that then fails (no gnuplot
# needed: the report gives up, exit 1, and leaves nothing), has a blank line at each leap
mkdir -p "$work/report"
printf '#!/bin/sh\ncp report.dat "%s/report/report.dat"\nexit 1\n' "$work" >"$work/report/gnuplot"
chmod +x "$work/report/gnuplot"
(cd "$work/report" && TOUCHDOWN_GNUPLOT="$work/report/gnuplot" "$tool" report -o r "$work/run/l.h5" >/dev/null 2>&1)
blanks=$(grep -c '^$' "$work/report/report.dat")
check "leap: the report's figure breaks its lines at each of the $leaps leaps ($blanks blank lines)" \
    test "$blanks" = "$leaps" -a "$(grep -vc '^#' "$work/report/report.dat")" -gt "$leaps"

# the sweep's table has the leaps and the end at rest as the run's JSON has them: a point of the
# run above (end_time 2 s), one that ends at speed before rest (end_time 1 s, after its leaps) and
# one with leap.burst = 0, which does not leap: no leaps (NaN, as its JSON has no member), not 0
t "$work/sweep" sweep -j 1 -q "${spin[@]}" --set "$leap" --vary end_time=2,1,1 --with leap.burst=0.1,0.1,0 -o s "$rub"
row() { /usr/bin/python3 -c '
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
print(" ".join(rows[int(sys.argv[2])][k] for k in ("leaps [-]", "leapt_time [s]", "ended_at_rest [-]")))' "$work/sweep/s.csv" "$1" 2>&1; }
check "sweep: the leaps and the end at rest of the run above ($(row 0); the run: $leaps $leapt 1)" \
    test "$rc" = 0 -a "$(row 0 | cut -d' ' -f1,3)" = "$leaps 1" -a \
    "$(awk -v a="$(row 0 | cut -d' ' -f2)" -v b="$leapt" 'BEGIN { print (a - b < 1e-12 && b - a < 1e-12) }')" = 1
check "sweep: a point that reached end_time at speed: ended_at_rest 0 ($(row 1))" \
    test "$(row 1 | cut -d' ' -f3)" = 0 -a "$(row 1 | cut -d' ' -f1)" -ge 1
check "sweep: a point with leap.burst = 0: leaps and leapt_time nan, ended_at_rest 0 ($(row 2))" \
    test "$(row 2)" = "nan nan 0"
check "sweep: the HDF5 table has the columns ($(h5ls "$work/sweep/s.h5" | grep -cE '^(leaps|leapt_time|ended_at_rest) '))" \
    test "$(h5ls "$work/sweep/s.h5" | grep -cE '^(leaps|leapt_time|ended_at_rest) ')" = 3

# a rub held through the leaps (rub-damped.cfg's rotor with a 0.12 kg m unbalance, spinning down freely
# from 90 rad/s on J = 0.05 kg m^2 while it rubs): the summary's contact time counts the contact held
# from the last event up to a burst's ends and the leaps (as the retainers' totals do), the stats block
# counts the leaps' shares as the summary does (below), and no leap crosses the start of the ending's stretch,
# so the run ends as the run integrated throughout does (a forward rub) and its contact time is that
# run's to 10 %
rubbing=(--set 'unbalances=({node=1; magnitude=0.12; phase=0.0;})' --set 'schedule=()'
    --set 'spin={free=true; inertia=0.05; drag_torque=0.7; drag_viscous=0.0;}' --set end_time=1.5
    --set output.sample_rate=1000 --set output.section_after=0)
held='leap={burst=0.1; factor=4; heal=0.05; start=0.2;}'
t "$work/held-leap" run -q --json --csv '' --hdf5 '' "${rubbing[@]}" --set "$held" "$rub"
t "$work/held-full" run -q --json --csv '' --hdf5 '' "${rubbing[@]}" --set "$held" --set leap.burst=0 "$rub"
hl=$work/held-leap/.out
hf=$work/held-full/.out
ret_ct=$(grep -oE '"retainer_contact_time":\[[^]]*\]' "$hl" | tr -d '[]' | cut -d: -f2 | tr ',' '\n' | awk '{ s += $1 } END { printf "%.17g", s }')
near() { awk -v a="$1" -v b="$2" -v r="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(a != "" && b != "" && d <= r * b) }'; }
check "held rub, leaps: $(jf "$hl" leaps) leaps, the summary's contact time is the retainers' ($(jf "$hl" contact_time), $ret_ct)" \
    near "$(jf "$hl" contact_time)" "$ret_ct" 1e-9
check "held rub, leaps: the stats' time in contact is the retainers' ($(jf "$hl" time_in_contact), $ret_ct)" \
    near "$(jf "$hl" time_in_contact)" "$ret_ct" 1e-9
# and a bouncing rub (an unbalance of 0.06 kg m: onsets and events inside the bursts), whose stats
# count the leaps' shares of onsets and events as the summary does
t "$work/bounce" run -q --json --csv '' --hdf5 '' "${rubbing[@]}" --set "$held" \
    --set 'unbalances=({node=1; magnitude=0.06; phase=0.0;})' "$rub"
hb=$work/bounce/.out
stats_events=$(grep -oE '"stats":\{[^}]*' "$hb" | grep -oE '"events":[0-9]+' | cut -d: -f2)
check "bouncing rub, leaps: the stats' onsets and events are the summary's ($(jf "$hb" contact_onsets) $(jf "$hb" contacts), $stats_events $(jf "$hb" events))" \
    test -n "$stats_events" -a "$(jf "$hb" contact_onsets)" = "$(jf "$hb" contacts)" -a "$stats_events" = "$(jf "$hb" events)"
check "bouncing rub, leaps: the stats' time in contact is the summary's ($(jf "$hb" time_in_contact), $(jf "$hb" contact_time))" \
    near "$(jf "$hb" time_in_contact)" "$(jf "$hb" contact_time)" 1e-9
check "held rub, leaps: the contact time is the integrated run's to 10 % ($(jf "$hl" contact_time), $(jf "$hf" contact_time))" \
    near "$(jf "$hl" contact_time)" "$(jf "$hf" contact_time)" 0.1
check "held rub, leaps: the ending is the integrated run's kind ($(jf "$hl" ending); $(jf "$hf" ending))" \
    test "$(jf "$hl" ending | cut -c1-12)" = '"forward rub' -a "$(jf "$hf" ending | cut -c1-12)" = '"forward rub'
# one leap has no spread: leap_decel_sd is null (the first leap from 0.6 s is the only one)
t "$work/one" run -q --json --csv '' --hdf5 '' "${rubbing[@]}" --set end_time=1.0 --set "$held" --set leap.start=0.6 "$rub"
check "one leap: leap_decel_sd is null ($(jf "$work/one/.out" leaps) leap, sd $(jf "$work/one/.out" leap_decel_sd))" \
    test "$(jf "$work/one/.out" leaps)" = 1 -a "$(jf "$work/one/.out" leap_decel_sd)" = null

# bad leap keys: a misspelt key in a file (its line), a factor below 1 (the override), a held speed
mkdir -p "$work/bad"
cp "$src/cases/rig.cfg" "$work/bad/"
awk '{ print } /^end_time/ { print "spin = { free = true; inertia = 0.01; drag_torque = 0.7; drag_viscous = 0.0; };\n" \
    "leap = { burst = 1.0;\n    factr = 20.0; heal = 0.75; start = 3.0; };" }' "$rub" >"$work/bad/c.cfg"
line=$(grep -n 'factr' "$work/bad/c.cfg" | cut -d: -f1)
t "$work/bad" run -q "$work/bad/c.cfg" -o b
check "a misspelt leap key: exit 2, one line naming the file, line $line and the key ($(cat "$work/bad/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/bad/.err")" = 1 -a -n "$(grep -F "c.cfg:$line: leap.factr: unknown key" "$work/bad/.err")"
t "$work/factor" run -q "${spin[@]}" --set 'leap={burst=0.1; factor=0.5; heal=0.05; start=0.1;}' "$rub" -o f
check "a leap factor below 1: exit 2, one line naming the override and leap.factor ($(cat "$work/factor/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/factor/.err")" = 1 -a -n "$(grep -F 'leap.factor: must be >= 1' "$work/factor/.err")"
t "$work/held" run -q --set "$leap" --set 'schedule=()' "$rub" -o h
check "a leap on a held speed: exit 2, one line naming leap ($(cat "$work/held/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/held/.err")" = 1 -a -n "$(grep -F 'leap: a leap needs the speed as a free state' "$work/held/.err")"
# a start at or after end_time (drop-to-rest.cfg's 3 s, end_time its cap as it ends at rest): no leap
# could happen
line=$(grep -n '^leap' "$src/cases/drop-to-rest.cfg" | cut -d: -f1)
t "$work/late" run -q --set end_time=3 "$src/cases/drop-to-rest.cfg" -o late
check "a leap start at end_time: exit 2, one line naming line $line and leap.start ($(cat "$work/late/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/late/.err")" = 1 -a -n "$(grep -F "drop-to-rest.cfg:$line: leap.start: 3 s is not before end_time = 3 s: the run ends before a leap may begin (leap.burst = 0 runs without leaps)" "$work/late/.err")"
# the advice the refusal gives holds: the same end_time with leap.burst = 0 is a case the tool takes
t "$work/unleapt" info --set end_time=3 --set leap.burst=0 "$src/cases/drop-to-rest.cfg"
check "the same end_time with leap.burst = 0: read ($(head -c 300 "$work/unleapt/.err"))" test "$rc" = 0
check "bad leap keys: no file" test -z "$(ls "$work/bad" | grep -v '^rig.cfg$\|^c.cfg$')$(ls "$work/factor")$(ls "$work/held")$(ls "$work/late")"

# a leap does not move the simulation's clock, on which the housing's motion runs as the schedule
# does: drop-to-rest.cfg (leaps from 3 s) with a shock ending at 50.011 s is refused at leap.start,
# its line in the file; a ramp rotation (held for ever) at the group; nine retainers (a leap holds 8)
drop=$src/cases/drop-to-rest.cfg
line=$(grep -n '^leap' "$drop" | cut -d: -f1)
shock='shocks=({shape="half-sine"; amplitude=490.0; duration=0.011; start=50.0; direction=[0.0,1.0];});'
t "$work/shock" run -q --set end_time=0.02 --set end_at_rest=false --set "housing={$shock}" "$drop" -o s
check "a housing shock after leap.start: exit 2, one line naming line $line and leap.start ($(cat "$work/shock/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/shock/.err")" = 1 -a -n "$(grep -F "drop-to-rest.cfg:$line: leap.start: 3 s is before the last prescribed change, at 50.011 s" "$work/shock/.err")"
t "$work/ramp" run -q --set 'housing={rotation=({shape="ramp"; rate=0.1; duration=0.01; axis=[1.0,0.0];});}' "$drop" -o r
check "a ramp housing rotation under leaps: exit 2, one line naming leap ($(cat "$work/ramp/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/ramp/.err")" = 1 -a -n "$(grep -F "drop-to-rest.cfg:$line: leap: housing.rotation[0] (a ramp) turns the housing for ever" "$work/ramp/.err")"
nine=
for n in 2 10 0 1 3 4 5 6 7; do
    nine="$nine{ node = $n; clearance = 0.75e-3; shaft_radius = 0.025; friction = 0.1; bore_speed = 0.0; restitution = 0.0; },"
done
t "$work/nine" run -q "${spin[@]}" --set "retainers = (${nine%,})" --set "$leap" "$rub" -o n
check "a leap with nine retainers: exit 2 at load, one line naming leap ($(cat "$work/nine/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/nine/.err")" = 1 -a -n "$(grep -F -e "--set '$leap': leap: a leap handles at most 8 retainers (the model has 9)" "$work/nine/.err")"
check "leaps refused by the model: no file" test -z "$(ls "$work/shock")$(ls "$work/ramp")$(ls "$work/nine")"
finish
