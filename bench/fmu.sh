#!/usr/bin/env bash
# The cost of the FMU loop: case A with its PD as a 10 kHz digital controller
# (cases/paper-a-digital.cfg) run natively (touchdown run, the PD sampled inside), against the same
# case as an FMU stepped by an importer (fmpy) at a 10 kHz communication step, once with the loop
# closed by the same PD in Python (examples/fmu_pd_loop.py: the FMU's inputs the AMB currents) and
# once with the case's own PD inside the FMU (no inputs: the cost of the communication points and
# of the importer's calls alone). The CPU time of each and their ratios. A benchmark, not a test:
# it asserts no limit.
#
#   bench/fmu.sh [-n REPEATS] [--end T] [--json] [BUILD_DIR]
#
# Each run REPEATS times (default 3), the runs alternating, no output files; the CPU time (user +
# system) printed is the median: of the tool's process for the native run, of the importer's process
# from the FMU's instantiation to its freeing for the FMU loops (Python's start and fmpy's import
# are left out). --end T shortens the case (default: its end_time, 2 s). fmpy comes from the test
# environment of the build (BUILD_DIR/fmpy-venv, made as tests/fmu/make_venv.sh makes it).
# --json prints the same as one JSON object (scripts/make-docs.sh records it for
# docs/performance.md). BUILD_DIR defaults to ./build of the source tree.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$here/bench/common.sh" # bench_options, bench_run
end=2.0
bench_options '2,19p' "$@"
venv=$build/fmpy-venv
bash "$here/tests/fmu/make_venv.sh" "$venv" "$here/tests/fmu/requirements.txt" >&2
case=$here/cases/paper-a-digital.cfg
"$tool" fmu -q --inputs current --set end_time="$end" -o "$work/PaperA.fmu" "$case"
"$tool" fmu -q --inputs none --set end_time="$end" -o "$work/PaperAInner.fmu" "$case"

for ((i = 0; i < repeats; i++)); do
    bench_run native --set end_time="$end" "$case"
    "$venv/bin/python" "$here/bench/fmu_loop.py" "$work/PaperA.fmu" pd "$end" 1e-4 >>"$work/pd.jsonl"
    "$venv/bin/python" "$here/bench/fmu_loop.py" "$work/PaperAInner.fmu" none "$end" 1e-4 >>"$work/none.jsonl"
done

/usr/bin/python3 - "$work" "$repeats" "$json" "$end" <<'PY'
import json, os, statistics, sys
work, repeats, as_json, end = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1", float(sys.argv[4])
st = json.load(open(os.path.join(work, "native.json")))["stats"]
cpu = [float(x) for x in open(os.path.join(work, "native.cpu")).read().split()]
rows = {"native": {"what": "touchdown run, the PD sampled inside", "cpu_median": statistics.median(cpu), "cpu": cpu,
                   "answers": {"first_contact_time": st["first_contact_time"],
                               "peak_contact_force": st["peak_normal_force"], "events": st["events"]},
                   "controller_samples": st["controller_samples"]}}
for name, what, f in [("fmu_python_pd", "fmpy, the PD in Python", "pd.jsonl"),
                      ("fmu_inputs_none", "fmpy, the case's PD inside the FMU", "none.jsonl")]:
    runs = [json.loads(l) for l in open(os.path.join(work, f))]
    rows[name] = {"what": what, "cpu_median": statistics.median(r["cpu"] for r in runs),
                  "cpu": [round(r["cpu"], 3) for r in runs], "steps": runs[0]["steps"], "answers": runs[0]["answers"]}
ratio = lambda x: rows[x]["cpu_median"] / rows["native"]["cpu_median"] if rows["native"]["cpu_median"] > 0 else None
ratios = {"fmu_python_pd_over_native": ratio("fmu_python_pd"), "fmu_inputs_none_over_native": ratio("fmu_inputs_none")}
out = {"repeats": repeats, "case": "cases/paper-a-digital.cfg", "end_time": end, "communication_step": 1e-4,
       "runs": rows, "ratios": ratios}
if as_json:
    print(json.dumps(out, indent=1, sort_keys=True))
    sys.exit(0)
print("%-40s %8s %12s %12s %8s" % ("run (%g s of case A, 10 kHz)" % end, "CPU s", "1st contact", "peak N", "events"))
for name in ["native", "fmu_python_pd", "fmu_inputs_none"]:
    r = rows[name]
    a = r["answers"]
    fct = "%.6f" % a["first_contact_time"] if a["first_contact_time"] is not None else "n/a"
    print("%-40s %8.2f %12s %12.1f %8d" % (r["what"], r["cpu_median"], fct, a["peak_contact_force"], a["events"]))
fmt = lambda x: "%.2f" % x if x is not None else "n/a"
print("CPU ratio FMU loop / native: %s with the PD in Python, %s with the case's PD inside"
      % (fmt(ratios["fmu_python_pd_over_native"]), fmt(ratios["fmu_inputs_none_over_native"])))
PY
