#!/usr/bin/env bash
# The cost of a digital controller: the CPU time of case A (cases/paper-a.cfg, its AMBs' PD in the
# DAE) and of the same case with the PD run as a 10 kHz sampled controller with one sample of delay
# (cases/paper-a-digital.cfg), and their ratio. A benchmark, not a test: it asserts no limit.
#
#   bench/digital.sh [-n REPEATS] [BUILD_DIR]
#
# Each case runs REPEATS times (default 3), the runs alternating, with no output files; the CPU time
# (user + system, of the tool's process) printed is the median. Where the time goes: a third run,
# case A with the closed-form flight off (solver.free_flight = false), separates what the digital
# case loses by integrating the free flight with IDA (the flight does not carry sampled controllers
# yet) from what its samples cost (each one a stop and a restart of the integrator); beside each
# run, the integrator's steps and restarts, the flight's share of the simulated time, the
# controller's samples, and the time in contact. BUILD_DIR defaults to ./build of the source tree.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$here/build
repeats=3
while [ $# -gt 0 ]; do
    case $1 in
    -n) repeats=$2; shift ;;
    -h | --help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) build=$1 ;;
    esac
    shift
done
tool=$build/touchdown
[ -x "$tool" ] || { echo "digital.sh: no tool at $tool (scripts/setup.sh $build builds it)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# one NAME CASE [OVERRIDE...]: run CASE once, its CPU seconds into $work/NAME.cpu (a line per run),
# its JSON summary into $work/NAME.json
one() {
    local name=$1 case=$2 t0 t1
    shift 2
    t0=$(awk '{ print $14 + $15 + $16 + $17 }' /proc/$$/stat)
    "$tool" run -q --json --hdf5 '' --csv '' "$@" "$here/cases/$case" >"$work/$name.json" 2>"$work/$name.err" || {
        echo "digital.sh: $case failed:" >&2
        cat "$work/$name.err" >&2
        exit 1
    }
    t1=$(awk '{ print $14 + $15 + $16 + $17 }' /proc/$$/stat)
    echo "$t0 $t1" | awk -v hz="$(getconf CLK_TCK)" '{ printf "%.2f\n", ($2 - $1) / hz }' >>"$work/$name.cpu"
}

for ((i = 0; i < repeats; i++)); do
    one continuous paper-a.cfg
    one digital paper-a-digital.cfg
    one noflight paper-a.cfg --set solver.free_flight=false
done

/usr/bin/python3 - "$work" <<'PY'
import json, os, statistics, sys
work = sys.argv[1]
rows = {}
for name in ("continuous", "digital", "noflight"):
    cpu = [float(x) for x in open(os.path.join(work, name + ".cpu")).read().split()]
    d = json.load(open(os.path.join(work, name + ".json")))
    rows[name] = (statistics.median(cpu), d)
print("%-40s %8s %10s %9s %8s %9s %9s" % ("case", "CPU s", "steps", "restarts", "samples", "flight s", "contact s"))
for name, case in (("continuous", "paper-a.cfg"), ("digital", "paper-a-digital.cfg"),
                   ("noflight", "paper-a.cfg, solver.free_flight=false")):
    cpu, d = rows[name]
    st = d["stats"]
    print("%-40s %8.2f %10d %9d %8d %9.3f %9.3f" % (case, cpu, st["steps"], st["restarts"],
          st.get("controller_samples", 0), st["flight_time"], d["contact_time"]))
a, b, c = rows["continuous"][0], rows["digital"][0], rows["noflight"][0]
ratio = lambda x, y: x / y if y > 0 else float("nan")
print("CPU ratio digital / continuous: %.2f" % ratio(b, a))
print("  of which: continuous without the flight / with it %.2f, digital / continuous without the flight %.2f"
      % (ratio(c, a), ratio(b, c)))
PY
