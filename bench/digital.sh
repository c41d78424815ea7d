#!/usr/bin/env bash
# The cost of a digital controller: the CPU time of case A (cases/paper-a.cfg, its AMBs' PD in the
# DAE) and of the same case with the PD run as a 10 kHz sampled controller with one sample of delay
# (cases/paper-a-digital.cfg), and their ratio. A benchmark, not a test: it asserts no limit.
#
#   bench/digital.sh [-n REPEATS] [--json] [BUILD_DIR]
#
# Each case runs REPEATS times (default 3), the runs alternating, with no output files; the CPU time
# (user + system, of the tool's process) printed is the median. Where the time goes: both cases run
# again with the closed-form flight off (solver.free_flight = false), which separates what the
# flight saves (it carries the free phases, from sample to sample in the digital case) from what
# the samples cost (a stop each; in contact also a restart of the integrator); beside each run, the
# integrator's steps and restarts, the flight's share of the simulated time, the controller's
# samples, and the time in contact. --json prints the same as one JSON object (scripts/make-docs.sh
# records it for docs/performance.md). BUILD_DIR defaults to ./build of the source tree.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$here/bench/common.sh" # bench_options, bench_run
bench_options '2,15p' "$@"

for ((i = 0; i < repeats; i++)); do
    bench_run continuous "$here/cases/paper-a.cfg"
    bench_run digital "$here/cases/paper-a-digital.cfg"
    bench_run noflight --set solver.free_flight=false "$here/cases/paper-a.cfg"
    bench_run digital_noflight --set solver.free_flight=false "$here/cases/paper-a-digital.cfg"
done

/usr/bin/python3 - "$work" "$repeats" "$json" <<'PY'
import json, os, statistics, sys
work, repeats, as_json = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1"
RUNS = (("continuous", "paper-a.cfg"), ("digital", "paper-a-digital.cfg"),
        ("noflight", "paper-a.cfg, solver.free_flight=false"),
        ("digital_noflight", "paper-a-digital.cfg, solver.free_flight=false"))
rows = {}
for name, case in RUNS:
    cpu = [float(x) for x in open(os.path.join(work, name + ".cpu")).read().split()]
    d = json.load(open(os.path.join(work, name + ".json")))
    st = d["stats"]
    rows[name] = {"case": case, "cpu_median": statistics.median(cpu), "cpu": cpu, "steps": st["steps"],
                  "restarts": st["restarts"], "controller_samples": st.get("controller_samples", 0),
                  "flight_steps": st["flight_steps"], "flight_time": st["flight_time"],
                  "contact_time": d["contact_time"]}
ratio = lambda x, y: rows[x]["cpu_median"] / rows[y]["cpu_median"] if rows[y]["cpu_median"] > 0 else None
ratios = {"digital_over_continuous": ratio("digital", "continuous"),
          "continuous_noflight_over_flight": ratio("noflight", "continuous"),
          "digital_noflight_over_flight": ratio("digital_noflight", "digital")}
if as_json:
    print(json.dumps({"repeats": repeats, "runs": rows, "ratios": ratios}, indent=1, sort_keys=True))
    sys.exit(0)
print("%-48s %8s %10s %9s %8s %9s %9s" % ("case", "CPU s", "steps", "restarts", "samples", "flight s", "contact s"))
for name, case in RUNS:
    r = rows[name]
    print("%-48s %8.2f %10d %9d %8d %9.3f %9.3f" % (case, r["cpu_median"], r["steps"], r["restarts"],
          r["controller_samples"], r["flight_time"], r["contact_time"]))
fmt = lambda x: "%.2f" % x if x is not None else "n/a"
print("CPU ratio digital / continuous: %s" % fmt(ratios["digital_over_continuous"]))
print("  without the flight / with it: continuous %s, digital %s"
      % (fmt(ratios["continuous_noflight_over_flight"]), fmt(ratios["digital_noflight_over_flight"])))
PY
