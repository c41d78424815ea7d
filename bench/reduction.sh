#!/usr/bin/env bash
# A reduced (Craig-Bampton) rotor against the full model on one case: runs CASE once full and
# once per cut-off given (Hz, through --set reduction.cutoff=...), each with the extra settings of
# -s, and prints for each the generalized DOF count, the peak force into the housing, the peak
# normal force, the time in contact, the contact onsets, the solver and CPU times, and the
# relative differences of the contact statistics from the full model's.
#
#   bench/reduction.sh [-b TOUCHDOWN] [-n REPEATS] [-s "KEY=VALUE ..."] CASE CUTOFF ...
#
# Example, the damped rub of the reference rig at 2 and 5 kHz, then on a 4x refined shaft:
#   bench/reduction.sh cases/rub-damped.cfg 2000 5000
#   bench/reduction.sh -s "shaft.refine=4" cases/rub-damped.cfg 2000 5000
# CPU s is the user time of the whole run without output files (set-up, stability check, start
# orbit, integration, summary); solver s is the run's own solver wall time. Needs python3 to read
# the summaries. With -n each run is repeated and the smallest times are shown (the machine may be
# shared; the results do not change from one repeat to the next).
set -euo pipefail
bin=${TOUCHDOWN:-touchdown}
extra=""
repeats=1
while [ $# -gt 0 ]; do
  case $1 in
    -b) bin=$2; shift 2 ;;
    -s) extra=$2; shift 2 ;;
    -n) repeats=$2; shift 2 ;;
    *) break ;;
  esac
done
case_file=${1:?usage: bench/reduction.sh [-b TOUCHDOWN] [-s SETS] CASE CUTOFF ...}
shift
[ $# -gt 0 ] || { echo "bench/reduction.sh: no cut-off to compare" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # run NAME SETS: JSON summaries to $tmp/NAME.json.K, CPU seconds to $tmp/NAME.cpu.K, DOFs to $tmp/NAME.dofs
  local name=$1 kv k args=()
  for kv in $2; do args+=(--set "$kv"); done
  for k in $(seq "$repeats"); do
    /usr/bin/env time -f %U -o "$tmp/$name.cpu.$k" "$bin" run -q --json --hdf5 "" --csv "" "${args[@]}" \
      "$case_file" > "$tmp/$name.json.$k"
  done
  "$bin" info "${args[@]}" "$case_file" | sed -n 's/^DOFs *\([0-9]*\) .*/\1/p' > "$tmp/$name.dofs"
}
run full "$extra"
i=0
for cutoff in "$@"; do
  run "r$i" "$extra reduction.cutoff=$cutoff"
  echo "$cutoff" > "$tmp/r$i.cutoff"
  i=$((i + 1))
done
python3 - "$tmp" "$i" "$case_file" "$extra" "$repeats" <<'PY'
import json, os, sys
d, runs, case, extra, repeats = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], int(sys.argv[5])

def load(name):
    s, cpu, solver = None, [], []
    for k in range(1, repeats + 1):
        with open(os.path.join(d, "%s.json.%d" % (name, k))) as f:
            s = json.load(f)
        solver.append(s["solver_wall_time"])
        with open(os.path.join(d, "%s.cpu.%d" % (name, k))) as f:
            cpu.append(float(f.read().split()[-1]))
    s["cpu"], s["solver_wall_time"] = min(cpu), min(solver)
    with open(os.path.join(d, name + ".dofs")) as f:
        s["dofs"] = int(f.read().strip() or 0)
    return s

def rel(a, b):
    return abs(b - a) / abs(a) if a else abs(b)

full = load("full")
print("case %s%s, %g s simulated, best of %d" % (case, (" with " + extra) if extra.strip() else "", full["t_reached"],
                                                 repeats))
head = "%-12s %5s %12s %12s %10s %8s %9s %7s %10s %10s %10s"
print(head % ("model", "DOFs", "housing N", "normal N", "contact s", "onsets", "solver s", "CPU s",
              "housing", "contact", "normal"))
row = "%-12s %5d %12.6g %12.6g %10.6f %8d %9.3f %7.2f %10s %10s %10s"
print(row % ("full", full["dofs"], full["peak_housing_force"], full["peak_normal_force"], full["contact_time"],
             full["contacts"], full["solver_wall_time"], full["cpu"], "-", "-", "-"))
for i in range(runs):
    r = load("r%d" % i)
    with open(os.path.join(d, "r%d.cutoff" % i)) as f:
        cut = f.read().strip()
    print(row % ("cut-off " + cut, r["dofs"], r["peak_housing_force"], r["peak_normal_force"], r["contact_time"],
                 r["contacts"], r["solver_wall_time"], r["cpu"],
                 "%.2e" % rel(full["peak_housing_force"], r["peak_housing_force"]),
                 "%.2e" % rel(full["contact_time"], r["contact_time"]),
                 "%.2e" % rel(full["peak_normal_force"], r["peak_normal_force"])))
PY
