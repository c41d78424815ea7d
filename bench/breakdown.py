#!/usr/bin/python3
"""Where the CPU time of a run goes, per IDA step (bench/breakdown.sh runs this; see its header).

For each case: REPEATS runs of `touchdown run` without output files (CPU time of the tool's
process, user + system; with --before the two tools alternate, run by run), the medians and the
integrator's counters from the JSON summary; then one more run under `perf record --call-graph
dwarf` whose samples are sorted into the categories of CATEGORIES by the functions on their
stacks. A category's time per step is its share of the samples times the median CPU time over the
steps. Two rows are derived rather than sampled: the failed attempts (Newton and error-test
failures: IDA's work on a step that is then retried has the same stacks as a step that succeeds,
so their share of the step's work is estimated as failed attempts / all attempts), and the floor
(the residual and the linear solve per step at their measured cost, nothing else: what a step
would cost if IDA's own work, the Jacobian, the factorisation, the events and the outputs cost
nothing).
"""
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASES = ["drop", "rub-damped", "paper-b"]
NO_FILES = ["-q", "--json", "--hdf5", "", "--csv", ""]
SAMPLES = 3000  # perf samples aimed at per profile (the rate is set from the run's CPU time)

# (key, what it is, functions that put a sample in it). The first category whose functions appear
# anywhere on a sample's stack takes it, so the phases around IDA's step (the flight, an event's
# handling and restart, the outputs) come first and claim the residuals or solves they call.
CATEGORIES = [
    ("flight", "closed-form flight", {"td_sim_flight_advance", "fly"}),
    ("events", "event handling and restart (consistent state, IDAReInit)",
     {"handle_stop", "flight_stop", "restart_integrator", "td_sim_restart", "td_sim_restart_after_change",
      "td_sim_make_consistent", "td_sim_handle_roots", "td_sim_restart_between_steps"}),
    ("outputs", "outputs and per-point monitors (totals, thermal, section, peaks, interpolation)",
     {"accept_point", "monitor", "td_sim_monitor_at", "td_sim_monitor_step_ahead", "td_sim_monitor_settle",
      "td_sim_totals_point", "td_sim_section_ida", "td_sim_section_flight", "td_sim_interpolate",
      "td_sim_margin_point", "td_sim_spin_hold", "take_sample"}),
    ("location", "event location (root functions, root search)",
     {"root_cb", "td_sim_roots", "IDAGetSolution", "td_sim_modes_out_of_step"}),
    ("residual", "residual", {"res_cb"}),
    ("jacobian", "Jacobian assembly", {"jac_cb", "SUNMatZero", "SUNMatZero_Sparse"}),
    ("factor", "factorisation (KLU)", {"ls_setup"}),
    ("solve", "linear solve (KLU)", {"ls_solve"}),
    ("ida", "IDA's own work (vector operations, Newton and error tests, step control)", {"IDASolve"}),
    ("setup", "setup (model, start state)", {"td_sim_create", "td_sim_create_cancellable", "td_job_start"}),
]
OTHER = ("other", "the rest (loading, the step loop, the summary)")
STEP_PARTS = ["residual", "jacobian", "factor", "solve", "ida"]  # the work of IDA's step attempts


def run(tool, case, args=()):
    """One run without output files: (CPU seconds of the process, JSON summary)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([tool, "run"] + NO_FILES + list(args) + ["cases/%s.cfg" % case], cwd=ROOT,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        sys.exit("breakdown: %s run %s failed: %s" % (tool, case, proc.stderr.strip()[:500]))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, json.loads(proc.stdout)


def stacks(data):
    """The sampled stacks of a perf.data file, each a list of function names (leaf first)."""
    proc = subprocess.run(["perf", "script", "-i", data, "-F", "ip,sym", "--no-inline"], stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, universal_newlines=True, check=True)
    out, cur = [], []
    for line in proc.stdout.splitlines():
        parts = line.split()
        if not parts:
            if cur:
                out.append(cur)
            cur = []
        elif len(parts) >= 2:
            cur.append(parts[1].split("+")[0])
    if cur:
        out.append(cur)
    return out


def classify(stack):
    names = set(stack)
    for key, _, funcs in CATEGORIES:
        if names & funcs:
            return key
    return OTHER[0]


def profile(tool, case, cpu):
    """Shares of the categories in a perf profile of one run (None without a working perf)."""
    if not shutil.which("perf"):
        return None
    freq = int(min(4000, max(50, SAMPLES / max(cpu, 1e-3))))
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "perf.data")
        proc = subprocess.run(["perf", "record", "-q", "-F", str(freq), "--call-graph", "dwarf", "-o", data, tool,
                               "run"] + NO_FILES + ["cases/%s.cfg" % case], cwd=ROOT, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, universal_newlines=True)
        if proc.returncode != 0:
            print("breakdown: perf record failed (%s): no profile" % proc.stderr.strip()[:200], file=sys.stderr)
            return None
        samples = stacks(data)
    counts = {}
    for st in samples:
        k = classify(st)
        counts[k] = counts.get(k, 0) + 1
    total = max(len(samples), 1)
    return {"frequency": freq, "samples": len(samples),
            "shares": {k: counts.get(k, 0) / total for k in [c[0] for c in CATEGORIES] + [OTHER[0]]}}


def summarise(cpus, summary, prof):
    st = summary["stats"]
    simulated = summary["t_reached"] - summary["t_start"]
    cpu = statistics.median(cpus)
    steps = st["steps"]
    attempts = steps + st["error_test_fails"] + st["nonlinear_fails"]
    row = {"cpu": cpus, "cpu_median": cpu, "simulated": simulated,
           "realtime_factor_cpu": simulated / cpu if cpu > 0 else None,
           "us_per_step": 1e6 * cpu / steps if steps else None,
           "failed_attempt_fraction": (attempts - steps) / attempts if attempts else 0.0}
    for k in ("steps", "restarts", "events", "residual_evals", "jacobian_evals", "error_test_fails", "nonlinear_fails",
              "flight_steps", "flight_time", "contact_onsets"):
        row[k] = st.get(k)
    row["profile"] = prof
    if prof and steps:
        per = {k: 1e6 * cpu * v / steps for k, v in prof["shares"].items()}
        row["us_per_step_by_category"] = per
        row["failed_attempts_us_per_step"] = row["failed_attempt_fraction"] * sum(per[k] for k in STEP_PARTS)
        row["floor_us_per_step"] = per["residual"] + per["solve"]
    return row


def main():
    args = sys.argv[1:]
    repeats, as_json, before, build, cases, do_profile = 3, False, None, os.path.join(ROOT, "build"), CASES, True
    while args:
        a = args.pop(0)
        if a == "-n":
            repeats = int(args.pop(0))
        elif a == "--json":
            as_json = True
        elif a == "--before":
            before = args.pop(0)
        elif a == "--cases":
            cases = args.pop(0).split(",")
        elif a == "--no-profile":
            do_profile = False
        else:
            build = a
    tools = [("after", os.path.join(os.path.abspath(build), "touchdown"))]
    if before:
        tools.insert(0, ("before", os.path.join(os.path.abspath(before), "touchdown")))
    for _, t in tools:
        if not os.access(t, os.X_OK):
            sys.exit("breakdown: no tool at %s (scripts/setup.sh BUILD_DIR builds it)" % t)
    out = {"repeats": repeats, "cases": {}, "categories": [[k, what] for k, what, _ in CATEGORIES] + [list(OTHER)],
           "step_parts": STEP_PARTS, "versions": {}}
    for label, tool in tools:
        out["versions"][label] = subprocess.run([tool, "--version"], stdout=subprocess.PIPE,
                                                universal_newlines=True).stdout.splitlines()[0]
    for case in cases:
        cpus, last = {label: [] for label, _ in tools}, {}
        for _ in range(repeats):
            for label, tool in tools:
                cpu, summary = run(tool, case)
                cpus[label].append(round(cpu, 3))
                last[label] = summary
        out["cases"][case] = {}
        for label, tool in tools:
            prof = profile(tool, case, statistics.median(cpus[label])) if do_profile else None
            out["cases"][case][label] = summarise(cpus[label], last[label], prof)
            print("breakdown: %-10s %-6s CPU %.2f s (median of %d)" % (case, label, statistics.median(cpus[label]),
                                                                      repeats), file=sys.stderr, flush=True)
    if as_json:
        print(json.dumps(out, indent=1, sort_keys=True))
        return
    print_table(out)


def print_table(out):
    labels = [l for l in ("before", "after") if l in out["versions"]]
    for case, rows in out["cases"].items():
        print("%s" % case)
        for label in labels:
            r = rows[label]
            print("  %-6s %s: CPU %.2f s, %.2fx real time, %d steps, %d restarts, %.2f us/step" % (
                label, out["versions"][label], r["cpu_median"], r["realtime_factor_cpu"], r["steps"], r["restarts"],
                r["us_per_step"]))
            if "us_per_step_by_category" in r:
                for key, what in out["categories"]:
                    print("    %-74s %6.2f us %5.1f %%" % (what, r["us_per_step_by_category"][key],
                                                          100 * r["profile"]["shares"][key]))
                print("    %-74s %6.2f us" % ("of the step's work: failed attempts (estimate)",
                                             r["failed_attempts_us_per_step"]))
                print("    %-74s %6.2f us" % ("floor: residual + linear solve", r["floor_us_per_step"]))


if __name__ == "__main__":
    main()
