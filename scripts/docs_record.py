#!/usr/bin/python3
"""Reruns every number the documentation quotes from the tool and records it in docs/results/.

    docs_record.py BUILD_DIR fast|slow [SOURCE ...]
    docs_record.py --check TOOL SOURCE KEY ...
    docs_record.py --check-keys TOOL

The second form reruns recorded runs (docs/results/SOURCE.json, runs KEY) with their recorded
arguments and fails if a number differs from the record by more than RTOL relative (below), or a
text, a count or a null differs; the wall-clock quantities are not compared, nor keys the record
lacks (a newer tool's additions). The third compares the tool's case keys (touchdown info --keys)
with docs/results/keys.json, exactly.

One JSON file per source (docs/results/SOURCE.json), each stamped with the tool's version, the
source revision, the date, the machine and the exact commands (paths relative to the repository
root, where every command runs). The fast sources take seconds each; the slow ones (benchmarks,
tolerance and mesh studies) minutes. scripts/make-docs.sh runs this and then docs_render.py.
Only Debian's python3 modules are used.
"""
import datetime
import json
import os
import re
import resource
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
from contact_intervals import contact_intervals  # noqa: E402  (bench/intervals.sh reads them the same way)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, "docs", "results")

PAPER = ["paper-a", "paper-b", "paper-c", "paper-d-kc1.25e12", "paper-d-kc1.25e10"]
NO_FILES = ["--json", "-q", "--hdf5", "", "--csv", ""]
# The converged references of docs/performance.md, "The paper's cases: settings that converge".
REF12 = {"solver.rtol": "1e-12", "solver.atol": "1e-15", "solver.max_order": "5"}
REF11 = {"solver.rtol": "1e-11", "solver.atol": "1e-14", "solver.max_order": "5"}
# Sources that fit in seconds: what README.md, docs/validation.md and docs/reference-rig.md quote
# from the shipped cases as they are.
FAST_CASES = PAPER + ["rub-damped", "drop", "run-up"]


def library_defaults(tool):
    """The library's defaults (lib/util/options.c) of the solver keys the studies compare against,
    as the case reader's tables give them (touchdown info --keys)."""
    out, _ = tool_output(tool, ["info", "--keys"])
    keys = {k["key"]: k["default"] for k in json.loads(out)}
    return {k: keys[k] for k in ("solver.rtol", "solver.atol", "solver.max_order")}


def run_args(case, sets=None):
    """The argument list of `touchdown run` without output files for CASE with --set SETS."""
    args = ["run"] + NO_FILES
    for key, value in (sets or {}).items():
        args += ["--set", "%s=%s" % (key, value)]
    return args + ["cases/%s.cfg" % case]


def tool_output(tool, args, check=True):
    """Run the tool from the repository root; its stdout and the wall time it took."""
    start = time.monotonic()
    proc = subprocess.run([tool] + args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    wall = time.monotonic() - start
    if check and proc.returncode != 0:
        sys.exit("docs_record: touchdown %s: exit %d: %s" % (" ".join(args), proc.returncode,
                                                             proc.stderr.strip()[:500]))
    return proc.stdout, wall


def record_run(tool, args):
    """One `touchdown run --json`: the command as written from the repository root and the
    summary as printed (a failed run is recorded too: its JSON says so)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out, wall = tool_output(tool, args, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        summary = json.loads(out)
    except ValueError:
        sys.exit("docs_record: touchdown %s printed no JSON" % " ".join(args))
    # CPU time of the process (user + system): on a shared machine it scatters far less than the
    # wall time the summary gives
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    print("  %-60s %6.1f s wall %6.1f s CPU" % (" ".join(a if a else "''" for a in args[len(NO_FILES) + 1:]),
                                                wall, cpu), flush=True)
    return {"command": "touchdown " + " ".join(a if a else "''" for a in args), "args": args,
            "cpu_time": round(cpu, 3), "summary": summary}


def git_revision():
    def git(*args):
        proc = subprocess.run(["git", "-C", ROOT] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, universal_newlines=True)
        return proc.stdout.strip() if proc.returncode == 0 else ""
    rev = git("describe", "--always", "--tags")
    if not rev:
        return "unknown"
    # "-modified": the sources the numbers come from (library, tool, cases, build, the scripts
    # that run them) differ from the commit; the docs and their results do not count
    dirty = git("status", "--porcelain", "--untracked-files=no", "--", "lib", "include", "tools", "cases",
                "cmake", "CMakeLists.txt", "bench", "scripts/make-figures.sh", "scripts/docs_record.py",
                "scripts/recovery_study.py", "scripts/shock_study.py", "scripts/sweep_study.py", "scripts/sweep_study_page.py",
                "tests/validation/base_motion")
    return rev + ("-modified" if dirty else "")


def stamp(tool, source, commands_note):
    version, _ = tool_output(tool, ["--version"])
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]
    cpu = ""
    if os.path.exists("/proc/cpuinfo"):
        with open("/proc/cpuinfo") as f:
            m = re.search(r"^model name\s*:\s*(.*)$", f.read(), re.M)
            cpu = m.group(1) if m else ""
    return {"source": source, "tool_version": version.splitlines()[0],
            "revision": git_revision(),
            "date": datetime.datetime.utcnow().strftime("%Y-%m-%dT%H:%M:%SZ"),
            "machine": {"nproc": os.cpu_count(), "cpu": cpu, "loadavg_start": float(load)},
            "made_by": "scripts/make-docs.sh", "how": commands_note}


def save(name, data):
    os.makedirs(RESULTS, exist_ok=True)
    path = os.path.join(RESULTS, name + ".json")
    with open(path + ".tmp", "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(path + ".tmp", path)
    print("docs_record: wrote docs/results/%s.json" % name, flush=True)


def src_runs(tool, build):
    """The shipped cases as they are, without output files."""
    data = stamp(tool, "runs", "touchdown run --json, one run per case as shipped")
    data["runs"] = {case: record_run(tool, run_args(case)) for case in FAST_CASES}
    # docs/performance.md, "What remains": what the reduced rotor gives on case B and rub-damped
    for case, sets in [("paper-b/0.5", {"end_time": "0.5"}),
                       ("paper-b/0.5/reduced", {"end_time": "0.5", "reduction.cutoff": "2000"}),
                       ("rub-damped/reduced", {"reduction.cutoff": "2000"}),
                       # docs/validation.md, "The drop": the energy account at 12 elements
                       ("drop/energy-12", {"energy": "true", "shaft.refine": "1"})]:
        data["runs"][case] = record_run(tool, run_args(case.split("/")[0], sets))
    return data


def parse_criticals(text):
    rows = re.findall(r"^\s+(forward|backward)\s+([0-9.eE+-]+) rad/s.*zeta ([0-9.eE+-]+)", text, re.M)
    return [{"whirl": w, "speed": float(s), "zeta": float(z)} for w, s, z in rows]


def src_modal(tool, build):
    """Critical speeds and the rig's mass (touchdown modal and info, their text output)."""
    data = stamp(tool, "modal", "touchdown modal and touchdown info, text output parsed")
    data["modal"] = {}
    for case in ["run-up", "paper-a"]:
        args = ["modal", "--csv", "", "--hdf5", "", "cases/%s.cfg" % case]
        out, _ = tool_output(tool, args)
        data["modal"][case] = {"command": "touchdown " + " ".join(a or "''" for a in args),
                               "critical_speeds": parse_criticals(out)}
    out, _ = tool_output(tool, ["info", "cases/paper-a.cfg"])
    m = re.search(r"^mass\s+([0-9.]+) kg", out, re.M)
    j = re.search(r"^polar\s+J = ([0-9.eE+-]+) kg m\^2", out, re.M)
    data["info"] = {"command": "touchdown info cases/paper-a.cfg",
                    "mass": float(m.group(1)) if m else None,
                    "polar_inertia": float(j.group(1)) if j else None}
    return data


def src_validation(tool, build):
    """The messages of the validation tests the docs quote (cmocka print_message lines)."""
    data = stamp(tool, "validation", "tests/validation executables, their printed measurements")
    data["tests"] = {}
    for test in ["test_first_contact", "test_rig_modal", "test_beams", "test_jeffcott", "test_overhung_disc",
                 "test_harmonic", "test_modal", "test_annular_rub", "test_penalty_convergence",
                 "test_sim_scenarios", "test_race", "test_speed", "test_flight_sampled",
                 # issue 31, tolerances: the first impact's convergence (docs/validation.md)
                 "test_tolerance",
                 # issue 31, trust: the summary's rows typed by hand before (about 20 s of CPU)
                 "test_sim", "test_amb_pid", "test_tight_tolerances"]:
        exe = os.path.join(build, "tests", test)
        proc = subprocess.run([exe], cwd=os.path.dirname(exe), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, universal_newlines=True,
                              env=dict(os.environ, CMOCKA_MESSAGE_OUTPUT="stdout"))
        if proc.returncode != 0:
            sys.exit("docs_record: %s failed:\n%s" % (test, proc.stdout[-2000:]))
        lines = [l for l in proc.stdout.splitlines() if l and not l.startswith("[")]
        data["tests"][test] = {"command": "build/tests/" + test, "messages": lines}
    return data


def src_keys(tool, build):
    """The case reader's schema (touchdown info --keys): the key tables of docs/case-format.md."""
    data = stamp(tool, "keys", "touchdown info --keys, its JSON as printed")
    out, _ = tool_output(tool, ["info", "--keys"])
    data["command"] = "touchdown info --keys"
    data["keys"] = json.loads(out)
    return data


def src_bench(tool, build):
    """touchdown bench, as shipped and at the library defaults (3 repeats, medians)."""
    data = stamp(tool, "bench", "touchdown bench -n 3 --json, as shipped and at the defaults")
    data["bench"] = {}
    for name, sets in [("shipped", {}), ("defaults", library_defaults(tool))]:
        args = ["bench", "-n", "3", "--json", "--dir", "cases"]
        for key, value in sets.items():
            args += ["--set", "%s=%s" % (key, value)]
        out, wall = tool_output(tool, args)
        print("  bench %-10s %6.1f s" % (name, wall), flush=True)
        data["bench"][name] = {"command": "touchdown " + " ".join(args), "result": json.loads(out)}
    return data


def src_digital(tool, build):
    """bench/digital.sh (docs/performance.md, "Digital controllers"): case A against its PD as a
    10 kHz sampled controller, each with the closed-form flight on and off (3 repeats, medians)."""
    data = stamp(tool, "digital", "bench/digital.sh -n 3 --json")
    start = time.monotonic()
    proc = subprocess.run([os.path.join(ROOT, "bench", "digital.sh"), "-n", "3", "--json", build],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if proc.returncode != 0:
        sys.exit("docs_record: bench/digital.sh failed:\n%s" % proc.stderr[-2000:])
    print("  bench/digital.sh %6.1f s" % (time.monotonic() - start), flush=True)
    data["command"] = "bench/digital.sh -n 3 --json"
    data["digital"] = json.loads(proc.stdout)
    return data


def src_fmu(tool, build):
    """The FMU through fmpy (docs/fmu.md, docs/performance.md "The FMU loop"): tests/fmu/test_loop.py's
    closed loop against the built-in run, and bench/fmu.sh (3 repeats, medians); both with the fmpy
    of the build's test environment (BUILD_DIR/fmpy-venv, tests/fmu/make_venv.sh)."""
    import tempfile
    data = stamp(tool, "fmu", "tests/fmu/test_loop.py --json, bench/fmu.sh -n 3 --json")
    venv = os.path.join(build, "fmpy-venv")
    subprocess.run(["bash", os.path.join(ROOT, "tests", "fmu", "make_venv.sh"), venv,
                    os.path.join(ROOT, "tests", "fmu", "requirements.txt")], check=True, stdout=subprocess.DEVNULL)
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "loop.json")
        proc = subprocess.run([os.path.join(venv, "bin", "python"), os.path.join(ROOT, "tests", "fmu", "test_loop.py"),
                               tool, ROOT, build, os.path.join(build, "touchdown-fmu.so"), "--json", out],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        if not os.path.exists(out):
            sys.exit("docs_record: tests/fmu/test_loop.py failed:\n%s" % proc.stdout[-2000:])
        with open(out) as f:
            data["loop"] = json.load(f)
    # a check that fails is recorded as such (the docs say so), never left out
    data["loop"]["failed_checks"] = [l[len("FAIL: "):] for l in proc.stdout.splitlines() if l.startswith("FAIL: ")]
    data["loop"]["command"] = "build/fmpy-venv/bin/python tests/fmu/test_loop.py build/touchdown . build build/touchdown-fmu.so --json FILE"
    print("  tests/fmu/test_loop.py %6.1f s" % (time.monotonic() - start), flush=True)
    start = time.monotonic()
    proc = subprocess.run([os.path.join(ROOT, "bench", "fmu.sh"), "-n", "3", "--json", build],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if proc.returncode != 0:
        sys.exit("docs_record: bench/fmu.sh failed:\n%s" % proc.stderr[-2000:])
    print("  bench/fmu.sh %6.1f s" % (time.monotonic() - start), flush=True)
    data["bench"] = json.loads(proc.stdout)
    data["bench"]["command"] = "bench/fmu.sh -n 3 --json"
    return data


def src_scaling(tool, build):
    """touchdown bench --scaling (docs/performance.md, "Scaling with the number of DOFs"): at the
    library's solver defaults with IDA through the free flight too (the cost of a step against the
    DOF count, KLU against dense; 3 repeats, medians), and once with case A's settings as shipped
    (the paper's rtol 1e-9, BDF order <= 5, closed-form free flight: the step counts they give on
    the refined rigs; one repeat, its cost is most of this source's)."""
    data = stamp(tool, "scaling", "touchdown bench --scaling --json, at the library defaults and as shipped")
    data["scaling"] = {}
    sets = dict(library_defaults(tool), **{"solver.free_flight": "false"})
    for name, repeats, sets in [("defaults", "3", sets), ("shipped", "1", {})]:
        args = ["bench", "--scaling", "-n", repeats, "--json", "--dir", "cases"]
        for key, value in sets.items():
            args += ["--set", "%s=%s" % (key, value)]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        out, wall = tool_output(tool, args)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        print("  bench --scaling %-10s %6.1f s wall %6.1f s CPU" % (name, wall, cpu), flush=True)
        data["scaling"][name] = {"command": "touchdown " + " ".join(args), "cpu_time": round(cpu, 1),
                                 "result": json.loads(out)}
    return data


def src_references(tool, build):
    """The paper's cases at two converged settings and at the library defaults."""
    data = stamp(tool, "references", "touchdown run --json at the reference settings and defaults")
    data["runs"] = {}
    for case in PAPER:
        for name, sets in [("ref12", REF12), ("ref11", REF11), ("defaults", library_defaults(tool))]:
            data["runs"]["%s/%s" % (case, name)] = record_run(tool, run_args(case, sets))
    return data


def src_tolerances(tool, build):
    """Cases A and B at rtol 1e-6..1e-8 (atol 1e-3 rtol m, order <= 5; 1e-9 is the shipped run)."""
    data = stamp(tool, "tolerances", "touchdown run --json, cases A and B at looser tolerances")
    data["runs"] = {}
    for case in ["paper-a", "paper-b"]:
        for rtol in ["1e-6", "1e-7", "1e-8"]:
            atol = "%.0e" % (float(rtol) * 1e-3)
            sets = {"solver.rtol": rtol, "solver.atol": atol.replace("e-0", "e-")}
            data["runs"]["%s/%s" % (case, rtol)] = record_run(tool, run_args(case, sets))
    return data


def src_mesh(tool, build):
    """Cases A and B with the shaft refined (defaults), and case A's first contact converging."""
    data = stamp(tool, "mesh", "touchdown run --json with shaft.refine, library defaults")
    data["runs"] = {}
    for case in ["paper-a", "paper-b"]:
        for k in [2, 4, 8]:
            sets = dict(library_defaults(tool), **{"shaft.refine": str(k)})
            data["runs"]["%s/%d" % (case, k)] = record_run(tool, run_args(case, sets))
    for k in [1, 2, 4, 8, 16]:
        sets = {"solver.rtol": "1e-10", "solver.atol": "1e-13", "end_time": "0.11",
                "shaft.refine": str(k)}
        data["runs"]["first-contact/%d" % k] = record_run(tool, run_args("paper-a", sets))
    return data


def src_convergence(tool, build):
    """bench/convergence.sh's runs: shaft.refine 1, 2, 4, 8 at two tolerances, three cases."""
    data = stamp(tool, "convergence", "the runs of bench/convergence.sh CASE, touchdown run --json")
    data["runs"] = {}
    # Case A at the library's BDF order <= 2 (bench/convergence.sh cases/paper-a.cfg
    # solver.max_order=2): at its shipped order <= 5 a refined undamped shaft takes minutes a run.
    for case, extra in [("rub-damped", {}), ("paper-a", {"solver.max_order": "2"}), ("drop", {})]:
        for rtol, atol in [("1e-6", "1e-9"), ("1e-7", "1e-10")]:
            for k in [1, 2, 4, 8]:
                sets = dict(extra, **{"shaft.refine": str(k), "solver.rtol": rtol, "solver.atol": atol})
                data["runs"]["%s/%s/%d" % (case, rtol, k)] = record_run(tool, run_args(case, sets))
    return data


def src_intervals(tool, build):
    """bench/intervals.sh's measure for case B to 0.3 s: the first ten contact intervals as shipped
    and at the defaults against a converged run (rtol 1e-11, atol 1e-14 m, order <= 5)."""
    import tempfile
    data = stamp(tool, "intervals", "bench/intervals.sh's runs: touchdown run --csv, events compared")
    data["runs"] = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, sets in [("ref", REF11), ("shipped", {}), ("defaults", library_defaults(tool))]:
            sets = dict(sets, **{"end_time": "0.3", "output.sample_rate": "1000"})
            args = run_args("paper-b", sets)[:]
            args[args.index("--csv") + 1] = os.path.join(tmp, name + ".csv")
            args.remove("--json")
            before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
            tool_output(tool, args)
            cpu = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before
            shown = [a if not a.startswith(tmp) else "OUT.csv" for a in args]
            data["runs"][name] = {"command": "touchdown " + " ".join(a or "''" for a in shown),
                                  "cpu_time": cpu,
                                  "intervals": contact_intervals(os.path.join(tmp, name + ".events.csv"))}
            print("  intervals %-10s %6.1f s CPU" % (name, cpu), flush=True)
    return data


# The cases of docs/validation.md, "Does this run's answer settle?": the paper's cases, the drop, and
# the damped steady rub beside them.
SPREAD_CASES = PAPER + ["drop", "rub-damped"]
SPREAD_MEMBERS = 5


def src_spread(tool, build):
    """touchdown run --spread 5 of each case as shipped: the run and four more with solver.atol
    within +-1 %, each leading answer's least, median, greatest and spread over the five."""
    data = stamp(tool, "spread", "touchdown run --json --spread %d, one ensemble per case as shipped" % SPREAD_MEMBERS)
    data["runs"] = {}
    for case in SPREAD_CASES:
        args = run_args(case)
        data["runs"][case] = record_run(tool, args[:-1] + ["--spread", str(SPREAD_MEMBERS), args[-1]])
    return data


def src_figures(tool, build):
    """docs/figures/ by scripts/make-figures.sh (its own runs of the paper's cases; the sweep studies'
    figures come with their record, the source sweep_study)."""
    data = stamp(tool, "figures", "scripts/make-figures.sh BUILD_DIR")
    start = time.monotonic()
    subprocess.run([os.path.join(ROOT, "scripts", "make-figures.sh"), build], check=True)
    data["wall_time"] = time.monotonic() - start
    data["figures"] = sorted(f for f in os.listdir(os.path.join(ROOT, "docs", "figures"))
                             if f.endswith(".png") and not f.startswith("study-"))
    return data


def src_report(tool, build):
    """docs/report.md's example: cases/drop.cfg run as shipped, then `touchdown report` of its file,
    the text and the JSON as written (run in a temporary directory, so that the report names the
    file as drop.h5)."""
    import tempfile
    data = stamp(tool, "report", "touchdown run -q -o drop cases/drop.cfg, then touchdown report drop.h5, "
                                 "in a temporary directory")
    commands = [["run", "-q", "-o", "drop", os.path.join(ROOT, "cases", "drop.cfg")], ["report", "drop.h5"]]
    with tempfile.TemporaryDirectory() as tmp:
        for args in commands:
            proc = subprocess.run([tool] + args, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  universal_newlines=True)
            if proc.returncode != 0:
                sys.exit("docs_record: touchdown %s: exit %d: %s" % (args[0], proc.returncode, proc.stderr.strip()[:500]))
        with open(os.path.join(tmp, "drop-report.txt")) as f:
            data["text"] = f.read()
        with open(os.path.join(tmp, "drop-report.json")) as f:
            data["json"] = json.load(f)
    data["commands"] = ["touchdown run -q -o drop cases/drop.cfg", "touchdown report drop.h5"]
    return data


def src_drop_sweep(tool, build):
    """docs/theory.md's table of the drop over its speed: cases/drop-speed-sweep.cfg's points, each
    a `touchdown run --json` of that case at the point's speed (the runs `touchdown sweep` makes of
    it; about 12 s of CPU in all), and the sweep's speeds read from the case."""
    data = stamp(tool, "drop_sweep", "touchdown run --json --set speed=S cases/drop-speed-sweep.cfg, "
                                     "S the sweep's speeds")
    with open(os.path.join(ROOT, "cases", "drop-speed-sweep.cfg")) as f:
        m = re.search(r'key = "speed"; values = \[([^]]*)\]', f.read())
    speeds = [float(v) for v in m.group(1).split(",")]
    data["runs"] = {"%g" % s: record_run(tool, run_args("drop-speed-sweep", {"speed": repr(s)})) for s in speeds}
    return data


def src_recovery(tool, build):
    """docs/recovery-study.md's runs (scripts/recovery_study.py: the case with and without its
    supervisor, the laws that fail, the damper's phase and gain, the map)."""
    import recovery_study
    return recovery_study.record(tool, stamp)


def src_breakdown(tool, build):
    """bench/breakdown.sh (docs/performance.md, "Cost per step"): CPU time, steps and the cost per
    IDA step by category of drop, rub-damped and paper-b (3 repeats, medians; a perf profile each).
    The earlier version's column: with TD_BENCH_BEFORE=BUILD_DIR (a build of that version) both
    tools are measured, alternating; without it the recorded earlier column is kept as it was
    measured (its version and date stay in the record)."""
    before = os.environ.get("TD_BENCH_BEFORE")
    args = ["-n", "3", "--json"] + (["--before", os.path.abspath(before)] if before else []) + [build]
    note = "bench/breakdown.sh -n 3 --json%s BUILD_DIR" % (" --before BEFORE_BUILD_DIR" if before else "")
    data = stamp(tool, "breakdown", note)
    start = time.monotonic()
    proc = subprocess.run([os.path.join(ROOT, "bench", "breakdown.sh")] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True)
    if proc.returncode != 0:
        sys.exit("docs_record: bench/breakdown.sh failed:\n%s" % proc.stderr[-2000:])
    print("  bench/breakdown.sh %6.1f s" % (time.monotonic() - start), flush=True)
    data["command"] = note
    data["breakdown"] = json.loads(proc.stdout)
    if not before:
        path = os.path.join(RESULTS, "breakdown.json")
        old = json.load(open(path))["breakdown"] if os.path.exists(path) else None
        if old and "before" in old["versions"]:
            data["breakdown"]["versions"]["before"] = old["versions"]["before"]
            data["breakdown"]["before_measured"] = old.get("before_measured", {"date": None})
            for case, rows in old["cases"].items():
                if case in data["breakdown"]["cases"] and "before" in rows:
                    data["breakdown"]["cases"][case]["before"] = rows["before"]
    else:
        data["breakdown"]["before_measured"] = {"date": data["date"]}
    return data


def src_shock(tool, build):
    """docs/shock-study.md's runs (scripts/shock_study.py: cases/shock.cfg and the grid of
    cases/shock-sweep.cfg, with the linear prediction beside each point)."""
    import shock_study
    return shock_study.record(tool, stamp)


def src_sweep_study(tool, build):
    """docs/sweep-study.md's sweeps and runs (scripts/sweep_study.py: the two study sweeps and the phase
    sweep, their figures, and the single runs the page reads: convergence, the bounces at 20 kHz, the
    drops behind the choice of keys and end time)."""
    import sweep_study
    return sweep_study.record(tool, stamp)


# --- projective leap: the check against the full integration (bench/leap-check.sh) -----------------
def src_leap_check(tool, build):
    """bench/leap-check.sh (docs/performance.md, "Long runs: the projective leap"): cases/drop-to-rest.cfg
    to 20 s integrated throughout and with its leaps, each an ensemble of 5 (touchdown run --spread 5),
    and once at leap factor 20 (about 10 min of CPU)."""
    note = "bench/leap-check.sh -n 5 --end 20 --json BUILD_DIR"
    data = stamp(tool, "leap-check", note)
    start = time.monotonic()
    proc = subprocess.run([os.path.join(ROOT, "bench", "leap-check.sh"), "-n", "5", "--end", "20", "--json", build],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if proc.returncode != 0:
        sys.exit("docs_record: bench/leap-check.sh failed:\n%s" % proc.stderr[-2000:])
    print("  bench/leap-check.sh %6.1f s" % (time.monotonic() - start), flush=True)
    data["command"] = note
    data["check"] = json.loads(proc.stdout)
    return data


SOURCES = {"fast": [("runs", src_runs), ("modal", src_modal), ("validation", src_validation), ("keys", src_keys)],
           "slow": [("bench", src_bench), ("digital", src_digital), ("fmu", src_fmu), ("scaling", src_scaling), ("references", src_references),
                    ("intervals", src_intervals), ("tolerances", src_tolerances), ("mesh", src_mesh),
                    ("convergence", src_convergence), ("spread", src_spread), ("figures", src_figures),
                    ("recovery", src_recovery), ("report", src_report),
                    ("drop_sweep", src_drop_sweep), ("shock", src_shock), ("sweep_study", src_sweep_study),
                    # issue 31: the cost per step
                    ("breakdown", src_breakdown),
                    # projective leap
                    ("leap-check", src_leap_check)]}


# The runs are deterministic: the same build gives the same bits. The tolerance allows for another
# compiler or libm rounding a last digit differently in a run that does not amplify it; the
# chaotic bouncing of the undamped paper cases amplifies any such difference to a different,
# equally valid contact sequence, which this check then reports (rerun scripts/make-docs.sh on
# that platform).
RTOL = 1e-6
WALL_CLOCK = {"wall_time", "solver_wall_time", "wall_time_per_revolution", "realtime_factor",
              "library_version", "hdf5_path", "csv_path", "events_path"}


def is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def differences(rec, new, where=""):
    """Where NEW departs from the record REC beyond RTOL; keys REC lacks are ignored."""
    out = []
    if isinstance(rec, dict):
        if not isinstance(new, dict):
            return ["%s: %r, recorded an object" % (where, new)]
        for k, v in rec.items():
            if k in WALL_CLOCK:
                continue
            if k not in new:
                out.append("%s.%s: missing, recorded %r" % (where, k, v))
            else:
                out += differences(v, new[k], "%s.%s" % (where, k))
    elif isinstance(rec, list):
        if not isinstance(new, list) or len(new) != len(rec):
            return ["%s: %d values, recorded %d" % (where, len(new) if isinstance(new, list) else -1, len(rec))]
        for i, (a, b) in enumerate(zip(rec, new)):
            out += differences(a, b, "%s[%d]" % (where, i))
    elif is_number(rec) and is_number(new):
        # counts (below a million) must match exactly, measured values to RTOL
        if abs(new - rec) > RTOL * max(abs(rec), abs(new)):
            out.append("%s: %.17g, recorded %.17g" % (where, new, rec))
    elif rec != new:
        out.append("%s: %r, recorded %r" % (where, new, rec))
    return out


def check(tool, source, keys):
    with open(os.path.join(RESULTS, source + ".json")) as f:
        runs = json.load(f)["runs"]
    bad = 0
    for key in keys:
        if key not in runs:
            print("FAIL: %s: no recorded run %s" % (source, key))
            bad += 1
            continue
        rec = runs[key]
        out, wall = tool_output(tool, rec["args"], check=False)
        try:
            diffs = differences(rec["summary"], json.loads(out), key)
        except ValueError:
            diffs = ["%s: the tool printed no JSON" % key]
        if diffs:
            bad += 1
            print("FAIL: %s (%.1f s) differs from docs/results/%s.json (rtol %g): %s%s" % (
                key, wall, source, RTOL, "; ".join(diffs[:8]), " ..." if len(diffs) > 8 else ""))
        else:
            print("ok:   %s (%.1f s) matches docs/results/%s.json (rtol %g)" % (key, wall, source, RTOL))
    return 1 if bad else 0


def check_keys(tool):
    """The tool's case keys against docs/results/keys.json: any difference fails (rerun
    scripts/make-docs.sh, which rewrites the key tables of docs/case-format.md from them)."""
    with open(os.path.join(RESULTS, "keys.json")) as f:
        rec = json.load(f)["keys"]
    out, _ = tool_output(tool, ["info", "--keys"])
    new = json.loads(out)
    old = {k["key"]: k for k in rec}
    diffs = ["%s: new" % k["key"] for k in new if k["key"] not in old]
    diffs += ["%s: gone" % k for k in old if k not in {n["key"] for n in new}]
    for k in new:
        diffs += differences(old.get(k["key"], k), k, k["key"])
    if not diffs and [k["key"] for k in rec] != [k["key"] for k in new]:
        diffs = ["the keys are in another order"]
    if diffs:
        print("FAIL: touchdown info --keys differs from docs/results/keys.json (rerun scripts/make-docs.sh): "
              "%s%s" % ("; ".join(diffs[:8]), " ..." if len(diffs) > 8 else ""))
        return 1
    print("ok:   touchdown info --keys matches docs/results/keys.json (%d keys)" % len(rec))
    return 0


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--check-keys":
        sys.exit(check_keys(os.path.abspath(sys.argv[2])))
    if len(sys.argv) >= 4 and sys.argv[1] == "--check":
        sys.exit(check(os.path.abspath(sys.argv[2]), sys.argv[3], sys.argv[4:]))
    if len(sys.argv) < 3 or sys.argv[2] not in SOURCES:
        sys.exit("usage: docs_record.py BUILD_DIR fast|slow [SOURCE ...]")
    build = os.path.abspath(sys.argv[1])
    tool = os.path.join(build, "touchdown")
    only = set(sys.argv[3:])
    for name, fn in SOURCES[sys.argv[2]]:
        if only and name not in only:
            continue
        start = time.monotonic()
        print("docs_record: %s ..." % name, flush=True)
        data = fn(tool, build)
        after = None
        if isinstance(data, tuple):  # a record with files to install once it is saved (sweep_study)
            data, after = data
        data["record_wall_time"] = round(time.monotonic() - start, 1)
        save(name, data)
        if after:
            after()


if __name__ == "__main__":
    main()
