#!/usr/bin/env bash
# The recovery supervisor through the case table `recovery` and the tool
# (tests/data/case/recovery-run.cfg: a rotor whose orbit its unbalance steps drive past the
# thresholds and back). touchdown info prints the supervisor; a run switches to the recovery law
# and back: the events CSV and HDF5 files carry the two controller_switch events with the
# controller switched to and the sensed radius (above the detection threshold, below the release
# one), the JSON and the files' attributes the account (two switches; the time on recovery is the
# time between them; the last return is the second); `--set recovery.enabled=false` takes no
# switch; a case without a supervisor writes no such column. The switch samples and the blend are
# checked against the sensor sequence by tests/test_supervisor.c.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/recovery.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
case_file="$src/tests/data/case/recovery-run.cfg"

t "$work/info" info "$case_file"
check "info: exit 0 (got $rc: $(head -c 300 "$work/info/.err"))" test "$rc" = 0
check "info prints the pair ($(grep -A1 '^recovery' "$work/info/.out" | tr '\n' ' '))" \
    grep -q 'pair 0: controller 0 "nominal" -> controller 1 "recovery"' "$work/info/.out"
check "info: the detection rule in samples" grep -q 'sensed radius > 0.5 c = 0.0005 m for 0.01 s (10 samples' \
    "$work/info/.out"
check "info: AMB 0 is driven by the nominal law" grep -q '^amb 0 .*controller 0' "$work/info/.out"

t "$work/run" run -q --json "$case_file" -o r
check "run: exit 0 (got $rc: $(head -c 300 "$work/run/.err"))" test "$rc" = 0
ev="$work/run/r.events.csv"
check "events CSV header ends with controller and r_sensed" \
    grep -q '^t \[s\],.*,peak_N \[N\],controller \[-\],r_sensed \[m\]$' "$ev"
switches=$(grep -c ',controller_switch,' "$ev")
check "two controller_switch events (got $switches)" test "$switches" = 2
first=$(grep ',controller_switch,' "$ev" | head -n 1)
second=$(grep ',controller_switch,' "$ev" | tail -n 1)
check "the first switches to controller 1 with r > 0.5 mm ($first)" \
    awk -F, -v l="$first" 'BEGIN { split(l, f, ","); exit !(f[14] == 1 && f[15] > 0.5e-3) }'
check "the second switches back to controller 0 with r < 0.3 mm ($second)" \
    awk -F, -v l="$second" 'BEGIN { split(l, f, ","); exit !(f[14] == 0 && f[15] < 0.3e-3) }'
check "other events carry controller -1" \
    awk -F, 'NR > 1 && $1 !~ /^#/ && $3 != "controller_switch" && $14 != -1 { bad = 1 } END { exit bad }' "$ev"
t1=$(echo "$first" | cut -d, -f1)
t2=$(echo "$second" | cut -d, -f1)
out="$work/run/.out"
check "JSON: controller_switches 2 (got $(jf "$out" controller_switches))" test "$(jf "$out" controller_switches)" = 2
check "JSON: last_return_time $(jf "$out" last_return_time) = the second switch $t2" \
    awk -v a="$(jf "$out" last_return_time)" -v b="$t2" 'BEGIN { exit !(a != "" && a == b + 0) }'
check "JSON: time_on_recovery $(jf "$out" time_on_recovery) = $t2 - $t1" \
    awk -v a="$(jf "$out" time_on_recovery)" -v b="$t1" -v c="$t2" 'BEGIN { d = a - (c - b); exit !(a != "" && d < 1e-12 && d > -1e-12) }'
check "CSV attributes: controller_switches = 2" grep -q '^# controller_switches = 2$' "$work/run/r.csv"
py=$(h5py_python)
if [ -n "$py" ]; then
    h5=$("$py" - "$work/run/r.h5" <<'PY' 2>&1
import sys, h5py
f = h5py.File(sys.argv[1], "r")
e = f["events"][...]
names = f["events"].attrs["kind_names"]
sw = [r for r in e if r["kind"] == 8]
print(len(sw), [int(r["controller"]) for r in sw], int(f.attrs["controller_switches"]), "controller_switch" in str(names))
PY
)
    check "HDF5: two switch events to controllers 1, 0, attribute 2, kind named ($h5)" test "$h5" = "2 [1, 0] 2 True"
else
    fail "no python3 with h5py (scripts/setup.sh installs python3-h5py)"
fi

t "$work/off" run -q --json --set 'recovery.enabled=false' "$case_file" -o r
check "enabled = false: exit 0, no switch (got $rc, $(jf "$work/off/.out" controller_switches))" \
    test "$rc" = 0 -a "$(jf "$work/off/.out" controller_switches)" = 0 -a "$(jf "$work/off/.out" last_return_time)" = null
check "enabled = false: no switch event" test "$(grep -c ',controller_switch,' "$work/off/r.events.csv")" = 0

t "$work/plain" run -q --json --set end_time=0.01 "$src/tests/data/case/amb-jeffcott.cfg" -o r
check "a case without a supervisor: no controller column, no account" \
    test "$rc" = 0 -a -z "$(grep -l 'r_sensed' "$work/plain/r.events.csv")" -a -z "$(jf "$work/plain/.out" controller_switches)"
finish
