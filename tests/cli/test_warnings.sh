#!/usr/bin/env bash
# A suspect result says so (docs/output-format.md, "Warnings"): one stderr line each
# ("touchdown: CASE: warning: ..."), the same text in the JSON summary's `warnings` list and in
# the files (HDF5 attribute `warnings`, CSV `# warnings` line), for each rule: an AMB past its
# force capacity with saturation off; a schedule entry at or after the end time; a clearance
# larger than the shaft radius that no AMB air gap bounds; a section from fewer than 8 crossings; a
# rotor past an AMB's air gap at its sensor.
# Each rule is also shown silent on a case just on the other side of it. A sweep carries its
# points' warnings in a `warnings` column and says how many on stderr; the bifurcation diagram
# says when its points crossed their section too few times.
# Cheap: tests/data/case/amb-jeffcott.cfg (a rigid rotor on two AMBs, 0.01 s), paper case A
# for 0.1 s and cases/shock.cfg (about 1 s each).
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
export LC_ALL=C
work=$(mktemp -d "${PWD}/warnings.XXXXXX")
trap 'rm -rf "$work"' EXIT
amb=$src/tests/data/case/amb-jeffcott.cfg
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
has() { grep -qF -- "$2" "$1"; }
# The JSON summary's warnings list, one a line.
warnings() { "$py" -c 'import json, sys; print("\n".join(json.load(open(sys.argv[1])).get("warnings", [])))' "$1"; }
py=$(h5py_python)
[ -n "$py" ] || py=python3

# rule TAG NEEDLE ARGS...: a run that must warn with NEEDLE on stderr and in its JSON
rule() {
    local tag=$1 needle=$2
    shift 2
    t "$work/$tag" run --json --csv '' --hdf5 '' "$@"
    check "$tag: a 'warning:' stderr line and the JSON's warnings hold '$needle' (rc $rc: $(grep warning "$work/$tag/.err"))" \
        test "$rc" = 0 -a -n "$(grep -F 'warning: ' "$work/$tag/.err" | grep -F -- "$needle")" -a \
        -n "$(warnings "$work/$tag/.out" | grep -F -- "$needle")"
}
# quiet TAG NEEDLE ARGS...: a run that must not warn with NEEDLE
quiet() {
    local tag=$1 needle=$2
    shift 2
    t "$work/$tag" run --json --csv '' --hdf5 '' "$@"
    check "$tag: no warning '$needle' (rc $rc: $(grep warning "$work/$tag/.err"))" \
        test "$rc" = 0 -a -z "$(grep -F -- "$needle" "$work/$tag/.err")" -a -z "$(warnings "$work/$tag/.out" | grep -F -- "$needle")"
}

# a clean case: no warning at all, an empty list
t "$work/clean" run --json --csv '' --hdf5 '' "$amb"
check "clean case: exit 0, nothing on stderr, \"warnings\":[]" \
    test "$rc" = 0 -a ! -s "$work/clean/.err" -a -n "$(grep -F '"warnings":[]' "$work/clean/.out")"

# an AMB past its capacity: the peak force is about 1 mN, twice a 0.5 mN capacity
rule amb-over "AMB 0 reached" --set 'ambs[0].force_capacity=5e-4' "$amb"
check "amb-over: the warning gives the load (200.2 %) and names the key that clips" \
    has "$work/amb-over/.err" "200.2 % of its force capacity 0.0005 N, at t = 0 s with saturation off"
quiet amb-saturated "AMB 0 reached" --set 'ambs[0].force_capacity=5e-4' --set 'ambs[0].saturation=true' "$amb"
quiet amb-within "AMB 0 reached" --set 'ambs[0].force_capacity=2e-3' "$amb"

# schedule entries at or after the end time (paper A: t = 0.1 s and 1.1 s)
rule schedule-at "schedule[0] at t = 0.1 s is at or after the end time 0.1 s: it never happens" \
    --set end_time=0.1 "$case_a"
check "schedule-at: the later entry warned too" has "$work/schedule-at/.err" "schedule[1] at t = 1.1 s"
quiet schedule-before "schedule[0]" --set end_time=0.1000001 "$case_a"
# entries written out of time order are named as written, not by their rank in time
rule schedule-order "schedule[0] at t = 1.1 s is at or after the end time 0.5 s" \
    --set end_time=0.5 --set 'schedule[0].time=1.1' --set 'schedule[1].time=0.1' "$case_a"
check "schedule-order: the entry at 0.1 s, schedule[1], is not warned" \
    test -z "$(grep -F 'schedule[1]' "$work/schedule-order/.err")"

# a clearance larger than the shaft radius (0.05 m), unless an AMB air gap bounds it
rule clearance "retainers[1].clearance 0.08 m is larger than the shaft radius there (0.05 m)" \
    --set 'retainers[1].clearance=0.08' "$amb"
quiet clearance-gap "clearance" --set 'retainers[1].clearance=0.08' --set 'ambs[0].air_gap=0.1' "$amb"
quiet clearance-radius "clearance" --set 'retainers[1].clearance=0.05' "$amb"

# a section from 3 crossings (2000 rad/s for 0.01 s after the transient), and from 16
rule section "section has only 3 crossings after the transient" --set speed=2000 --set end_time=0.02 "$amb"
quiet section-enough "crossings" --set speed=2000 --set end_time=0.1 "$amb"

# the rotor past an AMB's air gap (1.2 mm) at its sensor: cases/shock.cfg with a 20 g, 30 ms pulse drives it
# to about 3.7 mm at the sensors (no stator contact in the model); the shipped 50 g, 3 ms pulse keeps it
# within (about 0.73 mm)
rule air-gap "AMB 0's sensor saw the rotor 0.003" \
    --set 'housing.shocks.[0].amplitude=196.133' --set 'housing.shocks.[0].duration=0.03' "$src/cases/shock.cfg"
check "air-gap: both AMBs warned, naming the key" \
    test -n "$(grep -F "past the AMB's air gap 0.0012 m (ambs[1].air_gap)" "$work/air-gap/.err")"
quiet air-gap-within "air gap" "$src/cases/shock.cfg"

# ---- in the files --------------------------------------------------------------------------------
t "$work/files" run -o f --set 'ambs[0].force_capacity=5e-4' --set 'retainers[1].clearance=0.08' "$amb"
check "files: the CSV holds both warnings as '# warnings:' lines" \
    test "$rc" = 0 -a -n "$(sed -n '/^# warnings:$/,/^# [^|]/p' "$work/files/f.csv" | grep -F '#| AMB 0 reached')" -a \
    -n "$(sed -n '/^# warnings:$/,/^# [^|]/p' "$work/files/f.csv" | grep -F '#| retainers[1].clearance')"
if "$py" -c 'import h5py' 2>/dev/null; then
    check "files: the HDF5 attribute 'warnings' holds both, one a line" "$py" - "$work/files/f.h5" <<'EOF'
import sys, h5py
w = h5py.File(sys.argv[1], "r").attrs["warnings"]
w = (w.decode() if isinstance(w, bytes) else w).splitlines()
sys.exit(0 if len(w) == 2 and w[0].startswith("AMB 0 reached") and w[1].startswith("retainers[1].clearance") else 1)
EOF
fi
t "$work/nofiles" run -o f "$amb"
check "files of a clean run: no warnings attribute" test "$rc" = 0 -a -z "$(grep -F '# warnings' "$work/nofiles/f.csv")"

# ---- the per-retainer line: sustained and brief contacts, and the time in contact -----------------
t "$work/ret" run --set end_time=0.1 --csv '' --hdf5 '' "$case_a"
check "retainer lines: 'sustained contacts N, brief contacts (touch-and-go) M, in contact P % of the run'" \
    test "$rc" = 0 -a "$(grep -cE '^retainer [01] .*; sustained contacts [0-9]+, brief contacts \(touch-and-go\) [0-9]+, in contact [0-9.e+-]+ % of the run; race' "$work/ret/.out")" = 2

# ---- a sweep: the warnings column, one stderr line; the bifurcation diagram from few crossings ----
t "$work/s" sweep -j 2 --set end_time=0.02 --vary speed=1000,2000 --vary 'ambs[0].force_capacity=5e-4,1e4' -o s "$amb"
check "sweep: exit 0, one stderr line '4 of 4 points have warnings' ($(head -c 300 "$work/s/.err"))" \
    test "$rc" = 0 -a "$(grep -c 'warning' "$work/s/.err")" = 1 -a \
    -n "$(grep -F 'touchdown sweep: warning: 4 of 4 points have warnings' "$work/s/.err")"
check "sweep: the table's warnings column (before wall_time) holds each point's, the AMB's at capacity 5e-4 only" \
    test "$(head -n 1 "$work/s/s.csv" | grep -o 'warnings,wall_time \[s\]$')" = "warnings,wall_time [s]" -a \
    "$(grep -c 'AMB 0 reached' "$work/s/s.csv")" = 2 -a "$(grep -c '^[0-9],[0-9]*,5e-4,.*AMB 0 reached' "$work/s/s.csv")" = 2
t "$work/s" plot --no-run -d p s.h5
check "plot: the bifurcation diagram says its points crossed the section fewer than 8 times ($(cat "$work/s/.err"))" \
    test "$rc" = 0 -a -n "$(grep -F 's.h5: bifurcation diagram: 4 of the 4 points that ran crossed the section fewer than 8 times' "$work/s/.err")"

finish
