#!/usr/bin/python3
"""The shock study of docs/shock-study.md: cases/shock.cfg, and the map of its outcome over the
shock's amplitude and duration (cases/shock-sweep.cfg's grid) beside the linear prediction.

    shock_study.py BUILD_DIR     rerun the study: docs/results/shock.json and docs/figures/shock-*.png
                                 (two runs at a time; the wall time in the record), then render the docs
    shock_study.py --check TOOL  rerun the record's `case` row (cases/shock.cfg as shipped, about 1 s) and
                                 compare its outcome and margins with the record (tests/cli/test_docs.sh)

scripts/make-docs.sh --full --only shock does the same (docs_record.py's source "shock");
docs_render.py renders the regions of docs/shock-study.md from the record with REGIONS below.

The linear prediction is computed here, not by the tool: BUILD_DIR/tests/plant_probe writes the
case's plant (M, K, C, G per unit speed, AMB axes and gains, node positions, retainers, unbalance,
gravity) through the public API, and tests/validation/base_motion/rig_reference.py's functions close
the PID loops and step the forced response exactly (scipy.linalg.expm): the static sag under gravity
and the steady unbalance orbit (both in closed form) plus the shock's response, sampled every
PREDICT_STEP; the predicted margin of a retainer is its clearance less the largest radius of that
sum. It leaves out what is not linear: contact, and the amplifiers' saturation. The tool's margin is
its `min_clearance_margin` where the tool gives it; otherwise (a tool without that output) the
clearance less the largest sampled radius of the run's CSV, which the record says.
Recording needs Debian's python3-numpy and python3-scipy (the test dependencies; imported only
there, so that rendering the docs needs neither) and gnuplot for the figures.
"""
import concurrent.futures
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

CASE = "cases/shock.cfg"
SWEEP = "cases/shock-sweep.cfg"
G0 = 9.80665             # m/s^2 per g (ISO 80000-3 standard gravity)
PREDICT_STEP = 1.0e-4    # s: the linear response's grid (its fastest content, ~200 Hz, 50 points a period)
AMPLITUDE_KEY, DURATION_KEY = "housing.shocks[0].amplitude", "housing.shocks[0].duration"


def sweep_values():
    """The amplitudes and durations of cases/shock-sweep.cfg's grid (its one source)."""
    with open(os.path.join(ROOT, SWEEP)) as f:
        text = f.read()
    out = []
    for key in (AMPLITUDE_KEY, DURATION_KEY):
        m = re.search(r'key = "%s";\s*values = \[([^]]*)\]' % re.escape(key), text)
        out.append([float(v) for v in m.group(1).split(",")])
    return out


def shock_of_case():
    """cases/shock.cfg's pulse, read from its housing group (its one source): amplitude (m/s^2),
    duration (s), start (s) and the unit direction."""
    with open(os.path.join(ROOT, CASE)) as f:
        text = f.read()
    group = text[text.index("housing = {"):]
    value = lambda key: float(re.search(r"\b%s = ([0-9.eE+-]+);" % key, group).group(1))
    d = [float(v) for v in re.search(r"direction = \[([^]]*)\];", group).group(1).split(",")]
    norm = math.hypot(*d)
    return value("amplitude"), value("duration"), value("start"), [d[0] / norm, d[1] / norm]


def numerics():
    """numpy and the reference's functions, for the recording only."""
    for sub in ("base_motion", "control"):
        path = os.path.join(ROOT, "tests", "validation", sub)
        if path not in sys.path:
            sys.path.insert(0, path)
    import numpy
    import rig_reference
    return numpy, rig_reference


class Linear:
    """The case's contact-free, unsaturated response: static sag + unbalance orbit + shock."""

    def __init__(self, build):
        np, ref = numerics()
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "plant.txt")
            subprocess.run([os.path.join(build, "tests", "plant_probe"), os.path.join(ROOT, CASE), path],
                           check=True)
            self.p = p = ref.read_plant(path)
        self.ndof = n = p["ndof"]
        self.A = ref.closed(n, p["omega"], p["axes"], p["gains"], p["mats"])
        self.M = p["mats"][0]
        R, _ = ref.rigid_fields(n, p["z"], 0.0)
        self.R = R
        N = self.A.shape[0]
        # gravity: the load M a_g (touchdown's gravity_load), static under the PID loops
        bg = np.zeros(N)
        bg[n:2 * n] = p["gravity"][0] * R[0] + p["gravity"][1] * R[1]
        self.static = np.linalg.solve(self.A, -bg)
        # unbalance U at node k: the force U W^2 (cos(W t + phase), sin(W t + phase)) (docs/theory.md)
        bu = np.zeros(N, dtype=complex)
        W = p["omega"]
        for node, mag, phase in p["unbalances"]:
            f = np.zeros(n, dtype=complex)
            f[4 * node] = mag * W * W * np.exp(1j * phase)
            f[4 * node + 1] = -1j * mag * W * W * np.exp(1j * phase)
            bu[n:2 * n] += np.linalg.solve(self.M, f)
        self.orbit = np.linalg.solve(1j * W * np.eye(N) - self.A, bu)

    def response(self, times, amplitude, duration, start, direction):
        """Displacements q (ndof columns) at `times`."""
        np, ref = numerics()
        W = self.p["omega"]
        base = self.static[None, :] + np.real(self.orbit[None, :] * np.exp(1j * W * np.asarray(times))[:, None])
        ls = -self.M @ (amplitude * (direction[0] * self.R[0] + direction[1] * self.R[1]))
        pulse = {"start": start, "duration": duration}
        shock = ref.forced(self.A, self.ndof, (self.M, ls, np.zeros(self.ndof)), pulse, np.asarray(times))
        return (base + shock)[:, :self.ndof]

    def margins(self, q):
        """Each retainer's clearance less its largest radius over the rows of q."""
        np, _ = numerics()
        return [c - float(np.max(np.hypot(q[:, 4 * node], q[:, 4 * node + 1]))) for node, c in self.p["retainers"]]


def touchdown_run(tool, sets, csv_path):
    args = ["run", "--json", "-q", "--hdf5", "", "--csv", csv_path]
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    proc = subprocess.run([tool] + args + [CASE], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    try:
        summary = json.loads(proc.stdout)
    except ValueError:
        sys.exit("shock_study: touchdown %s printed no JSON: %s" % (" ".join(args), proc.stderr[:300]))
    for key in ("hdf5_path", "csv_path", "events_path"):
        if summary.get(key):
            summary[key] = os.path.basename(summary[key])
    shown = ["''" if a == "" else (os.path.basename(a) if a == csv_path else a) for a in args]
    return {"command": "touchdown " + " ".join(shown + [CASE]), "summary": summary}


def read_columns(path, names):
    np, _ = numerics()
    with open(path) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        head = [h.split(" ")[0] for h in next(rows)]
        idx = [head.index(c) for c in names]
        return np.array([[float(r[i]) for i in idx] for r in rows if r])


def sampled_margins(path, clearances):
    """Each retainer's clearance less its largest sampled radius (r_retK columns of the CSV)."""
    np, _ = numerics()
    r = read_columns(path, ["r_ret%d" % k for k in range(len(clearances))])
    return [c - float(np.max(r[:, k])) for k, c in enumerate(clearances)]


def point(tool, lin, tmp, amplitude, duration):
    """One grid point: the tool's run and the linear prediction on the same shock."""
    np, _ = numerics()
    csv_path = os.path.join(tmp, "p-%g-%g.csv" % (amplitude, duration))
    out = touchdown_run(tool, [(AMPLITUDE_KEY, repr(amplitude)), (DURATION_KEY, repr(duration))], csv_path)
    s = out["summary"]
    clearances = [c for _, c in lin.p["retainers"]]
    out["sampled_margin"] = min(sampled_margins(csv_path, clearances)) if s.get("complete") else None
    _, _, start, direction = shock_of_case()
    times = np.arange(0.0, s.get("t_end") or 0.5, PREDICT_STEP)
    out["linear_margin"] = min(lin.margins(lin.response(times, amplitude, duration, start, direction)))
    out["tool_margin"] = s.get("min_clearance_margin", out["sampled_margin"])
    out["margin_source"] = "min_clearance_margin" if "min_clearance_margin" in s else "sampled"
    gaps = [g for _, g in lin.p["air_gaps"]]
    peaks = s.get("sensor_peak_displacement") or []
    out["past_air_gap"] = any(g > 0 and x is not None and x > g for x, g in zip(peaks, gaps))
    out["outcome"] = s.get("shock_outcome") or (None if not s.get("complete") else
                                                ("none" if not s.get("contacts") else "contact"))
    os.remove(csv_path)
    return out


def case_run(tool, lin, tmp):
    """cases/shock.cfg as shipped; its retainer radii against the linear prediction before contact."""
    np, _ = numerics()
    csv_path = os.path.join(tmp, "case.csv")
    out = touchdown_run(tool, [], csv_path)
    s = out["summary"]
    cols = read_columns(csv_path, ["t", "r_ret0", "r_ret1"])
    amplitude, duration, start, direction = shock_of_case()
    q = lin.response(cols[:, 0], amplitude, duration, start, direction)
    r_lin = np.stack([np.hypot(q[:, 4 * node], q[:, 4 * node + 1]) for node, _ in lin.p["retainers"]], axis=1)
    first = s.get("first_contact_time")
    before = cols[:, 0] < (first if first is not None else cols[-1, 0] + 1.0)
    out["shock"] = {"amplitude": amplitude, "duration": duration, "start": start, "direction": list(direction)}
    out["linear_error_before_contact"] = float(np.max(np.abs(cols[before, 1:] - r_lin[before])))
    out["peak_radius_before_contact"] = float(np.max(cols[before, 1:]))
    out["linear_margin"] = min(lin.margins(lin.response(np.arange(0.0, s["t_end"], PREDICT_STEP), amplitude,
                                                        duration, start, direction)))
    step = max(1, len(cols) // 2500)
    out["series"] = {"t": cols[::step, 0].tolist(), "r_ret0": cols[::step, 1].tolist(),
                     "r_ret1": cols[::step, 2].tolist(), "r_lin0": r_lin[::step, 0].tolist(),
                     "r_lin1": r_lin[::step, 1].tolist()}
    return out


def references(tool):
    """The two base-motion tests (tests/validation/base_motion/), run as ctest runs them; their printed
    comparisons."""
    build = os.path.dirname(tool)
    here = os.path.join(ROOT, "tests", "validation", "base_motion")
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, args in (("jeffcott", [tool]),
                           ("rig", [tool, os.path.join(build, "tests", "plant_probe"), os.path.join(ROOT, "cases")])):
            script = os.path.join(here, "%s_reference.py" % name)
            proc = subprocess.run(["/usr/bin/python3", script] + args, cwd=tmp, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, universal_newlines=True)
            if proc.returncode != 0:
                sys.exit("shock_study: %s failed:\n%s" % (script, proc.stdout[-2000:]))
            out[name] = {"command": "python3 tests/validation/base_motion/%s_reference.py %s" % (
                name, " ".join(["build/touchdown"] + (["build/tests/plant_probe", "cases"] if name == "rig" else []))),
                "messages": proc.stdout.splitlines()}
    return out


def record(tool, stamp):
    """Every run of the study; returns the record (docs/results/shock.json)."""
    build = os.path.dirname(tool)
    data = stamp(tool, "shock", "scripts/shock_study.py: touchdown run --json of cases/shock.cfg, and of it "
                 "with --set %s=A --set %s=D over cases/shock-sweep.cfg's grid, two at a time; the linear "
                 "prediction from tests/plant_probe's plant in scipy" % (AMPLITUDE_KEY, DURATION_KEY))
    data["references"] = references(tool)
    lin = Linear(build)
    amplitudes, durations = sweep_values()
    data["grid"] = {"amplitudes": amplitudes, "durations": durations, "g": G0, "predict_step": PREDICT_STEP,
                    "clearances": [c for _, c in lin.p["retainers"]], "air_gaps": [g for _, g in lin.p["air_gaps"]]}
    with tempfile.TemporaryDirectory() as tmp:
        data["case"] = case_run(tool, lin, tmp)
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            futures = {"%g %g" % (a, d): pool.submit(point, tool, lin, tmp, a, d)
                       for a in amplitudes for d in durations}
            data["map"] = {k: f.result() for k, f in futures.items()}
    figures(data)
    return data


# --- the figures (gnuplot) ------------------------------------------------------------------------
def figures(data):
    with tempfile.TemporaryDirectory() as tmp:
        series = data["case"]["series"]
        dat = os.path.join(tmp, "case.dat")
        with open(dat, "w") as f:
            for row in zip(series["t"], series["r_ret0"], series["r_ret1"], series["r_lin0"], series["r_lin1"]):
                f.write("%.6g %.6g %.6g %.6g %.6g\n" % (row[0], *(1e3 * v for v in row[1:])))
        c = data["grid"]["clearances"][0] * 1e3
        sh = data["case"]["shock"]
        script = """set terminal pngcairo size 900,480 font ",10"
set output "%(out)s"
set grid
set xlabel "t [s]"
set ylabel "retainer radius [mm]"
set key top right
set arrow from graph 0, first %(c)g to graph 1, first %(c)g nohead dt 2
set label "clearance" at graph 0.01, first %(c)g offset 0,0.6
set object 1 rect from first %(t0)g, graph 0 to first %(t1)g, graph 1 behind fillcolor rgb "#dddddd" fillstyle solid 1.0 noborder
plot "%(dat)s" using 1:2 with lines lw 1.5 title "NDE retainer (touchdown)", \\
     "%(dat)s" using 1:3 with lines lw 1.5 title "DE retainer (touchdown)", \\
     "%(dat)s" using 1:4 with lines dt 2 lw 1 title "NDE, linear (no contact, no saturation)", \\
     "%(dat)s" using 1:5 with lines dt 2 lw 1 title "DE, linear"
""" % {"out": os.path.join(ROOT, "docs", "figures", "shock-radius.png"), "dat": dat, "c": c,
       "t0": sh["start"], "t1": sh["start"] + sh["duration"]}
        subprocess.run(["gnuplot"], input=script, universal_newlines=True, check=True)
        map_figure(data, tmp)


OUTCOME_COLOUR = {"none": "#2ca02c", "touch": "#1f77b4", "rub": "#ff7f0e", "drop": "#d62728",
                  "unsettled": "#9467bd", "contact": "#ff7f0e", None: "#7f7f7f"}


def map_figure(data, tmp):
    blocks = {}
    for key, p in data["map"].items():
        a, d = (float(v) for v in key.split())
        blocks.setdefault(p["outcome"], []).append((d * 1e3, a / G0))
    plots = []
    for k, (outcome, pts) in enumerate(sorted(blocks.items(), key=lambda kv: str(kv[0]))):
        path = os.path.join(tmp, "map-%d.dat" % k)
        with open(path, "w") as f:
            f.write("".join("%g %g\n" % xy for xy in pts))
        plots.append('"%s" using 1:2 with points pt 7 ps 2.2 lc rgb "%s" title "%s"'
                     % (path, OUTCOME_COLOUR.get(outcome, "#000000"), outcome or "failed"))
    past = os.path.join(tmp, "past.dat")
    with open(past, "w") as f:
        for key, p in data["map"].items():
            if p["past_air_gap"]:
                a, d = (float(v) for v in key.split())
                f.write("%g %g\n" % (d * 1e3, a / G0))
    if os.path.getsize(past):
        plots.append('"%s" using 1:2 with points pt 6 ps 3 lw 1.5 lc rgb "black" '
                     'title "past an AMB air gap at its sensor"' % past)
    # the linear prediction's boundary: where its margin crosses zero, per duration
    edge = os.path.join(tmp, "edge.dat")
    with open(edge, "w") as f:
        for d in data["grid"]["durations"]:
            a = boundary(data, d)
            if a is not None:
                f.write("%g %g\n" % (d * 1e3, a / G0))
    plots.append('"%s" using 1:2 with linespoints lw 2 dt 2 lc rgb "black" title "linear prediction: margin 0"'
                 % edge)
    script = """set terminal pngcairo size 640,600 font ",10"
set output "%s"
set grid
set logscale xy
set xrange [2:150]
set yrange [0.15:40]
set xlabel "half-sine duration [ms]"
set ylabel "peak acceleration of the housing [g]"
set key outside below
plot %s
""" % (os.path.join(ROOT, "docs", "figures", "shock-map.png"), ", \\\n     ".join(plots))
    subprocess.run(["gnuplot"], input=script, universal_newlines=True, check=True)


def boundary(data, d):
    """The amplitude at which the linear margin reaches zero at duration d: the margin is affine in
    the amplitude (superposition) between two grid amplitudes, so interpolated linearly."""
    pts = [(a, data["map"]["%g %g" % (a, d)]["linear_margin"]) for a in data["grid"]["amplitudes"]]
    for (a0, m0), (a1, m1) in zip(pts, pts[1:]):
        if m0 > 0 >= m1:
            return a0 + (a1 - a0) * m0 / (m0 - m1)
    return None


# --- the docs (render) ------------------------------------------------------------------------------
def _res():
    with open(os.path.join(ROOT, "docs", "results", "shock.json")) as f:
        return json.load(f)


def _g(x, digits=3):
    return "-" if x is None else "%.*g" % (digits, x)


def _um(x):
    """In um, to the um; below 0.5 um one significant digit, so that a small negative margin keeps its sign
    ("-0.4", not "-0")."""
    if x is None:
        return "-"
    v = x * 1e6
    return "%.0f" % v if abs(v) >= 0.5 or v == 0.0 else "%.1g" % v


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows]) + "\n"


def region_case():
    r = _res()
    c = r["case"]
    s = c["summary"]
    rows = [["shock", "%s m/s^2 (%s g), %s ms half-sine from %s s, direction (%s, %s)" % (
                _g(c["shock"]["amplitude"], 5), _g(c["shock"]["amplitude"] / G0, 3), _g(c["shock"]["duration"] * 1e3),
                _g(c["shock"]["start"]), _g(c["shock"]["direction"][0]), _g(c["shock"]["direction"][1]))],
            ["outcome", str(s.get("shock_outcome", "-"))],
            ["smallest clearance margin (touchdown)", "%s um" % _um(s.get("min_clearance_margin"))],
            ["smallest margin, linear prediction", "%s um" % _um(c["linear_margin"])],
            ["first contact", "%s s" % _g(s.get("first_contact_time"), 4)],
            ["sustained contacts (retainer 0, 1)", ", ".join(str(v) for v in s.get("retainer_contacts", []))],
            ["brief contacts (touch-and-go)", ", ".join(str(v) for v in s.get("retainer_touch_and_go", []))],
            ["peak normal force", "%s N" % _g(s.get("peak_normal_force"), 4)],
            ["peak AMB force", "%s N (AMB %s)" % (_g(s.get("peak_amb_force"), 4), s.get("peak_amb"))],
            ["ending", str(s.get("ending"))],
            ["retainer radius, touchdown against linear, before the first contact",
             "largest difference %s um (largest radius %s um)" % (_g(c["linear_error_before_contact"] * 1e6, 3),
                                                                 _um(c["peak_radius_before_contact"]))]]
    return _table(["", "cases/shock.cfg"], rows) + "\nCommand: `%s`.\n" % c["command"]


def region_map():
    r = _res()
    rows = []
    for a in r["grid"]["amplitudes"]:
        row = ["%s (%s g)" % (_g(a, 4), _g(a / G0, 3))]
        for d in r["grid"]["durations"]:
            p = r["map"]["%g %g" % (a, d)]
            t = p["summary"].get("contact_time")
            row.append("%s%s: %s / %s%s" % (p["outcome"] or "failed", " %s ms" % _g(t * 1e3, 2) if t else "",
                                            _um(p["tool_margin"]), _um(p["linear_margin"]),
                                            " (!)" if p["past_air_gap"] else ""))
        rows.append(row)
    src = {p["margin_source"] for p in r["map"].values()}
    return _table(["peak [m/s^2] \\ duration [ms]"] + [_g(d * 1e3) for d in r["grid"]["durations"]], rows) + \
        "\nEach cell: the outcome (with the run's time in contact), then the smallest clearance margin in um, " \
        "touchdown's (%s; negative: the compliant contact's deepest penetration) / the linear prediction's " \
        "(negative: the linear rotor would pass the clearance by that much). (!): the rotor at an AMB's sensor " \
        "went further than the AMB's air gap.\n" % (
            "its `min_clearance_margin`" if src == {"min_clearance_margin"} else
            "the clearance less the largest sampled retainer radius")


def region_agreement():
    r = _res()
    free = [p for p in r["map"].values() if p["outcome"] == "none"]
    diffs = [p["tool_margin"] - p["linear_margin"] for p in free]
    rel = [abs(p["tool_margin"] - p["linear_margin"]) / (r["grid"]["clearances"][0] - p["linear_margin"])
           for p in free]
    same = sum(1 for p in r["map"].values() if (p["outcome"] == "none") == (p["linear_margin"] > 0))
    worst = max(range(len(free)), key=lambda i: abs(diffs[i])) if free else None
    lines = ["- points without contact: %d of %d; there the margins differ by %s to %s um, at most %s of the "
             "retainer's travel (clearance less the margin)" % (len(free), len(r["map"]), _g(min(diffs) * 1e6, 3),
                                                                 _g(max(diffs) * 1e6, 3), _g(max(rel), 2))
             if free else "- no point without contact",
             "- contact or not, as the linear prediction's sign says it: %d of %d points" % (same, len(r["map"]))]
    if worst is not None:
        p = free[worst]
        lines.append("- the largest difference, %s um, at `%s`" % (_g(diffs[worst] * 1e6, 3), p["command"]))
    bound = ["%s ms: %s g" % (_g(d * 1e3), _g(boundary(r, d) / G0, 3) if boundary(r, d) else "-")
             for d in r["grid"]["durations"]]
    lines.append("- the linear prediction's contact boundary (margin 0, interpolated): " + "; ".join(bound))
    if free:
        top = max(free, key=lambda p: p["summary"].get("peak_amb_load") or 0.0)
        lines.append("- the largest AMB force at a point without contact: %s N, %s of the AMB's capacity (`%s`)" % (
            _g(top["summary"].get("peak_amb_force"), 4), _g(top["summary"].get("peak_amb_load"), 3), top["command"]))
    past = [p for p in r["map"].values() if p["past_air_gap"]]
    lines.append("- points where the rotor at an AMB's sensor went past the AMB's air gap (%s mm): %d of %d, "
                 "the weakest %s" % (", ".join(_g(g * 1e3) for g in r["grid"]["air_gaps"]), len(past), len(r["map"]),
                                     _weakest(r, past)))
    return "\n".join(lines) + "\n"


def region_references():
    r = _res()["references"]
    lines = []
    for name, title in (("jeffcott", "Jeffcott rotor, rigid-body reference"), ("rig", "the rig, its plant in scipy")):
        lines.append("%s (`%s`):\n" % (title, r[name]["command"]))
        lines.append("```\n" + "\n".join(r[name]["messages"]) + "\n```\n")
    return "\n".join(lines)


def _weakest(r, points):
    """The smallest amplitude among points, with its durations."""
    if not points:
        return "none"
    keys = [k for k, p in r["map"].items() if p in points]
    a = min(float(k.split()[0]) for k in keys)
    ds = sorted(float(k.split()[1]) for k in keys if float(k.split()[0]) == a)
    return "%s g at %s ms" % (_g(a / G0, 3), ", ".join(_g(d * 1e3) for d in ds))


def _largest(name, prefix=""):
    """The largest error/peak a reference printed (on its lines starting with prefix)."""
    vals = [float(l.split("error/peak")[1].split()[0]) for l in _res()["references"][name]["messages"]
            if "error/peak" in l and "largest" not in l and l.startswith(prefix)]
    return ("%.1e" % max(vals)).replace("e-0", "e-")


def span_val_base_jeffcott_cell():
    return "%s of the peak" % _largest("jeffcott")


def span_val_base_rig_cell():
    return "%s (shock), %s (rotation) of the peak" % (_largest("rig", "shock"), _largest("rig", "rotation"))


def span_shock_record_time():
    """The study's cost, as its record measured it."""
    t = _res()["record_wall_time"]
    return "about %.0f min" % (t / 60.0) if t >= 90.0 else "about %.0f s" % t


SPANS = {"val-base-jeffcott-cell": span_val_base_jeffcott_cell, "val-base-rig-cell": span_val_base_rig_cell,
         "shock-record-time": span_shock_record_time}
REGIONS = {"shock-references": region_references, "shock-case": region_case, "shock-map": region_map, "shock-agreement": region_agreement}


CHECKED = ("shock_outcome", "contact_happened", "min_clearance_margin", "retainer_min_clearance_margin",
           "first_contact_time")


def check_case(tool):
    """The record's `case` row against the tool: cases/shock.cfg rerun, its outcome and margins (and the
    first contact's time) to docs_record's RTOL; 0 when they agree."""
    import docs_record  # noqa: E402  (its comparison and tolerance)
    rec = _res()["case"]["summary"]
    with tempfile.TemporaryDirectory() as tmp:
        new = touchdown_run(tool, [], os.path.join(tmp, "case.csv"))["summary"]
    diffs = docs_record.differences({k: rec[k] for k in CHECKED if k in rec}, new, "case")
    missing = [k for k in CHECKED if k not in rec]
    if diffs or missing:
        print("FAIL: shock study: cases/shock.cfg differs from docs/results/shock.json's case (rtol %g; rerun "
              "scripts/make-docs.sh --full --only shock): %s" % (docs_record.RTOL, "; ".join(
                  diffs[:8] + ["%s: not recorded" % k for k in missing])))
        return 1
    print("ok:   shock study: cases/shock.cfg's %s match docs/results/shock.json's case (outcome %s, margin %.6g m)"
          % (", ".join(CHECKED), new["shock_outcome"], new["min_clearance_margin"]))
    return 0


def main(argv):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    if len(argv) == 2 and argv[0] == "--check":
        return check_case(os.path.abspath(argv[1]))
    if len(argv) != 1:
        sys.exit(__doc__)
    import docs_record  # noqa: E402  (its stamp and save)
    tool = os.path.join(os.path.abspath(argv[0]), "touchdown")
    docs_record.save("shock", record(tool, docs_record.stamp))
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "docs_render.py")]).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
