#!/usr/bin/python3
"""Rewrites the generated regions of README.md and docs/*.md from the recorded results.

    docs_render.py [--check]

A generated region is a block

    <!-- generated: NAME -->
    ...
    <!-- end generated -->

or, inside a sentence or a table cell, a span <!-- gen: NAME -->...<!-- /gen -->; NAME is one of
the functions below (REGIONS, SPANS), each built from docs/results/*.json alone (written by
docs_record.py), so that the same results always give the same text; the one exception,
out-name-index (docs/output-format.md), is built from the output schema's table lib/io/schema.c
(read through the C preprocessor, $CC or cc) and touchdown/result.h; and the hand-written tables
of the run file in docs/output-format.md (datasets, scales, /events fields, root attributes) are
checked against that table (a name, type, shape or unit that differs fails). --check writes nothing and
fails (exit 1, with a diff) if a file differs from what the results give: a number edited by
hand, or results regenerated without the docs. Only Debian's python3 modules are used.
"""
import difflib
import json
import math
import os
import re
import statistics
import sys
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, "docs", "results")
FILES = ["README.md"] + ["docs/" + f for f in sorted(os.listdir(os.path.join(ROOT, "docs")))
                         if f.endswith(".md")]
BLOCK = re.compile(r"(<!-- generated: ([a-z0-9-]+)[^>]*-->\n)(.*?)(<!-- end generated -->)", re.S)
SPAN = re.compile(r"(<!-- gen: ([a-z0-9-]+) -->)(.*?)(<!-- /gen -->)", re.S)
CASES = [("A", "paper-a"), ("B", "paper-b"), ("C", "paper-c"), ("D", "paper-d-kc1.25e12"),
         ("D10", "paper-d-kc1.25e10")]
LABEL = {"paper-a": "A (constraint, 90 rad/s)", "paper-b": "B (constraint, 190 rad/s)",
         "paper-c": "C (penalty 1.25e12, 90 rad/s)", "paper-d-kc1.25e12": "D (penalty 1.25e12, 190 rad/s)",
         "paper-d-kc1.25e10": "D10 (penalty 1.25e10, 190 rad/s)"}

_cache = {}


def res(source):
    """docs/results/SOURCE.json, loaded once."""
    if source not in _cache:
        with open(os.path.join(RESULTS, source + ".json")) as f:
            _cache[source] = json.load(f)
    return _cache[source]


def summary(source, key):
    return res(source)["runs"][key]["summary"]


def cpu(source, key):
    """The CPU time of a recorded run (user + system, s)."""
    return res(source)["runs"][key].get("cpu_time")


def cpu_per_rev(source, key):
    """CPU s per revolution after the first contact (the paper's figure of merit, in CPU time)."""
    s = summary(source, key)
    w, wr, c = num(s, "wall_time"), num(s, "wall_time_per_revolution"), cpu(source, key)
    return None if not w or wr is None or c is None else wr * c / w


def num(d, *keys):
    """A number from nested JSON, None where missing or null (a failed value)."""
    for k in keys:
        if d is None:
            return None
        d = d.get(k) if isinstance(d, dict) else (d[k] if isinstance(d, list) and k < len(d) else None)
    return d if isinstance(d, (int, float)) and not isinstance(d, bool) else None


def cite(*sources):
    """Where the numbers of a region come from: the results files with their stamps."""
    parts = []
    for s in sources:
        st = res(s)
        parts.append("[`docs/results/%s.json`](%sresults/%s.json) (%s at %s, %s)" % (
            s, "{DOCS}", s, st["tool_version"].replace("touchdown ", ""), st["revision"], st["date"][:10]))
    return "; ".join(parts)


# Number formats: one place, so that every region writes a number the same way.
def g(x, digits=3):
    """x to DIGITS significant digits, '-' for a missing value."""
    if x is None or not math.isfinite(x):
        return "-"
    if x == 0:
        return "0"
    e = int(math.floor(math.log10(abs(x))))
    if -4 <= e < 6:
        return "%.*f" % (max(digits - 1 - e, 0), x)
    return "%.*e" % (digits - 1, x)


def e(x, digits=2):
    """x in exponent form (1.0e-13), '-' for a missing value."""
    if x is None or not math.isfinite(x):
        return "-"
    mantissa, exponent = ("%.*e" % (digits - 1, x)).split("e")
    return "%se%d" % (mantissa, int(exponent))


def n(x):
    """A count or a large number with thousands separators."""
    return "-" if x is None else "{:,}".format(int(round(x)))


def f(x, decimals):
    return "-" if x is None or not math.isfinite(x) else "%.*f" % (decimals, x)


def pct(x, decimals=1):
    return "-" if x is None else "%.*f %%" % (decimals, 100.0 * x)


def rel(a, b):
    return None if a is None or b is None or b == 0 else abs(a - b) / abs(b)


# Arithmetic that lets a missing value (null in the JSON: a failed or undefined quantity) through
# as None, printed '-', instead of failing the whole page.
def mx(values):
    v = [x for x in values if x is not None]
    return max(v) if v else None


def mn(values):
    v = [x for x in values if x is not None]
    return min(v) if v else None


def sub(a, b):
    return None if a is None or b is None else a - b


def div(a, b):
    return None if a is None or not b else a / b


def kn(x):
    return div(x, 1e3)


def mag(x):
    return None if x is None else abs(x)


def lt(a, b):
    return a is not None and a < b


def span_range(values, fmt, unit=""):
    """'lo-hi UNIT' (or one value) of the values that are numbers."""
    v = [x for x in values if x is not None]
    if not v:
        return "-"
    lo, hi = fmt(min(v)), fmt(max(v))
    return (lo if lo == hi else "%s-%s" % (lo, hi)) + unit


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(r) + " |" for r in rows]
    return "\n".join(line.replace("|  |", "| |").replace("|  |", "| |") for line in out) + "\n"


# --- the sources, read ---------------------------------------------------------------------------
def bench_case(which, case, key):
    for m in res("bench")["bench"][which]["result"]["medians"]:
        if m["case"] == case:
            return num(m, key)
    return None


def bench_ratio(which, name, key="cpu_median"):
    for r in res("bench")["bench"][which]["result"]["ratios"]:
        if r["name"] == name:
            return num(r, key)
    return None


def bench_machine(which):
    return res("bench")["bench"][which]["result"]["machine"]


def bench_cpu_per_rev(which, case):
    w, wr = bench_case(which, case, "wall_time"), bench_case(which, case, "wall_time_per_revolution")
    c = bench_case(which, case, "cpu_time")
    return None if not w or wr is None or c is None else wr * c / w


def rtf_cpu(which, case):
    """Simulated seconds per CPU second (2 s simulated by every paper case)."""
    cpu = bench_case(which, case, "cpu_time")
    return None if not cpu else 2.0 / cpu


class Missing(dict):
    """A parsed test output: a line the test no longer prints reads as missing values ('-')."""

    def __missing__(self, key):
        return (None, None, "-")


def first_contact_test():
    """test_first_contact's printed measurements: exact time and velocity; per method the error
    of the time, the relative error of the radial velocity, and the steps."""
    msgs = res("validation")["tests"]["test_first_contact"]["messages"]
    out = Missing()
    for line in msgs:
        m = re.match(r"exact first contact t = ([0-9.]+) s, radial velocity ([0-9.eE+-]+)", line)
        if m:
            out["exact"] = (float(m.group(1)), float(m.group(2)))
        m = re.match(r"(.*?): t = [0-9.]+ s \(error ([0-9.eE+-]+) s\), v_r = [0-9.eE+-]+ "
                     r"\(rel\. error ([0-9.eE+-]+)\), (.*)", line)
        if m:
            out[m.group(1)] = (float(m.group(2)), float(m.group(3)), m.group(4))
    return out


def rig_modal_test():
    msgs = res("validation")["tests"]["test_rig_modal"]["messages"]
    worst_w = worst_z = 0.0
    crit = []
    for line in msgs:
        m = re.match(r"ross, .*max rel diff omega_d ([0-9.eE+-]+), zeta ([0-9.eE+-]+)", line)
        if m:
            worst_w, worst_z = max(worst_w, float(m.group(1))), max(worst_z, float(m.group(2)))
        m = re.match(r"critical speed \(lag\): ([0-9.]+) rad/s (\w+) branch \d+ zeta ([0-9.]+)", line)
        if m:
            crit.append((float(m.group(1)), m.group(2), float(m.group(3))))
    return worst_w, worst_z, crit


def exact_first_contact():
    return first_contact_test()["exact"][0]


# --- README.md -----------------------------------------------------------------------------------
def readme_glance():
    a = summary("runs", "paper-a")
    drift = [num(summary("runs", c), "stats", "worst_drift") for c in ["paper-a", "paper-b"]]
    fc = first_contact_test()
    flight = fc["free flight in closed form, defaults"][0]
    ida_def = fc["IDA, defaults (rtol 1e-6, atol 1e-9)"][0]
    tight = fc["tight (rtol 1e-12, atol 1e-16)"][0]
    ratios = [bench_ratio("shipped", r) for r in ["C/A", "D/B"]]
    if all(r is not None and r < 1 for r in ratios):
        penalty = "%s times faster (CPU time; the closed-form flight carries a penalty run between its microsecond contacts)" % span_range(
            [1 / r for r in ratios], lambda x: "%.1f" % x)
    else:
        penalty = "%s times slower (CPU time)" % span_range(ratios, lambda x: "%.1f" % x)
    mesh = [num(summary("mesh", "paper-a/%d" % k), "peak_normal_force") for k in [2, 4, 8]]
    w, _, _ = rig_modal_test()
    rows = [
        ["constrained model, computing per revolution after first contact (case B, as shipped)",
         "13.3 s", "%s s (CPU, `touchdown bench`, median of %d)" % (
             g(bench_cpu_per_rev("shipped", "B"), 2), res("bench")["bench"]["shipped"]["result"]["repeats"])],
        ["penalty Kc = 1.25e12 N/m against constrained, same case", "54 times slower", penalty],
        ["first contact of case A against the exact linear solution", "-",
         "%s s (closed-form flight, any tolerance); IDA alone: %s s (rtol 1e-12), %s s (defaults)" % (
             e(mag(flight)), e(mag(tight)), e(mag(ida_def)))],
        ["worst drift off the clearance circle in contact (cases A, B)", "-", "%s m" % e(mx(drift))],
        ["rig eigenvalues against ross-rotordynamics", "-", "%s relative" % e(w)],
        ["peak contact force, constrained, case A", "1.8 kN",
         "%s N, %s N into the housing (a reconstructed rig; %s kN as the shaft mesh is refined: not mesh-converged, see validation.md)" % (
             n(num(a, "peak_normal_force")), n(num(a, "peak_housing_force")),
             span_range([x / 1e3 for x in mesh if x], lambda x: "%.0f" % x))],
        ["does the constrained model bound the penalty force from above?", "yes (claimed)",
         "no: a stiff penalty impact peaks at v0 sqrt(m_eff Kc), far above it"],
    ]
    return ("Measured on this project's 2-core machine (%s); details, commands and every other check in\n"
            "[docs/validation.md](docs/validation.md) and [docs/performance.md](docs/performance.md).\n\n"
            % cite("runs", "bench", "validation", "mesh")) + table(["", "the paper", "touchdown"], rows)


def readme_realtime():
    return ("Not met: case B at 10x real time. As shipped (rtol 1e-9, BDF order <= 5, the settings at which its\n"
            "contact statistics match a converged run) it runs at %sx real time, at the library defaults at\n"
            "%sx (simulated time over CPU time, `touchdown bench`, %s); docs/performance.md explains\n"
            "why (the undamped rig's highest shaft modes ring after every impact and hold the step at a few\n"
            "microseconds) and what would change it: the reduced rotor (`reduction.cutoff`) shortens case B's\n"
            "run, but the AMB journals' ringing modes stay with the nodes it keeps physical; the rest needs a\n"
            "decision on the rig or the model.\n" % (
                g(rtf_cpu("shipped", "B"), 2), g(rtf_cpu("defaults", "B"), 2), cite("bench")))


# --- docs/performance.md -------------------------------------------------------------------------
def perf_summary():
    b_cpu = bench_case("shipped", "B", "cpu_time")
    iv = intervals_errors()
    drift_s = [num(summary("runs", c), "stats", "worst_drift") for c in ["paper-a", "paper-b"]]
    drift_d = [num(summary("references", c + "/defaults"), "stats", "worst_drift") for c in ["paper-a", "paper-b"]]
    exact = exact_first_contact()
    fa = num(summary("runs", "paper-a"), "first_contact_time")
    fa_d = num(summary("references", "paper-a/defaults"), "first_contact_time")
    ratios_s = {r: bench_ratio("shipped", r) for r in ["C/A", "D/B", "D10/B"]}
    ratios_d = {r: bench_ratio("defaults", r) for r in ["C/A", "D/B", "D10/B"]}
    rtf = rtf_cpu("shipped", "B")
    ok_iv = iv["shipped"][0] is not None and iv["shipped"][0] <= 1e-7 and iv["shipped"][2] <= 1e-2
    rows = [
        ["case B, constrained, >= 10x faster than real time (2.0 s in <= 0.2 s) with its first ten contact "
         "intervals within 1e-7 s and 1 % of a converged run",
         "as shipped (rtol 1e-9, BDF order <= 5, [settings that converge](#the-papers-cases-settings-that-converge)): "
         "%s s CPU (`touchdown bench`, %sx real time); first contact exact (closed-form flight); first ten "
         "intervals (0.3 s, `bench/intervals.sh`) %s s and %s %s. At the library defaults %s s CPU, intervals %s s off" % (
             g(b_cpu, 3), g(rtf, 2), e(mx(iv["shipped"][:2]), 2), e(iv["shipped"][2], 2),
             "in the peaks" if ok_iv else "in the peaks (not met)",
             g(bench_case("defaults", "B", "cpu_time"), 3), e(mx(iv["defaults"][:2]))),
         ("**no**, about %.0fx short" % (10 / rtf) if rtf < 10 else "yes") if rtf else "-"],
        ["penalty (Kc = 1.25e12 N/m) within 5x the constrained model's time on the same case",
         "as shipped C/A %s, D/B %s, D10/B %s (CPU, same invocation); at the defaults %s, %s, %s (the paper: 54)" % (
             tuple(g(ratios_s[r], 2) for r in ratios_s) + tuple(g(ratios_d[r], 2) for r in ratios_d)),
         "yes" if all(x is not None and x <= 5 for x in ratios_s.values()) else "no"],
        ["worst constraint drift < 1e-9 m (cases A, B)",
         "%s m as shipped, %s m at the defaults" % (e(mx(drift_s)), e(mx(drift_d))),
         "yes" if lt(mx(drift_s + drift_d), 1e-9) and None not in drift_s + drift_d else "no"],
        ["first contact of case A within 1e-7 s of the exact %s s" % f(exact, 12),
         "%s s as shipped, %s s at the defaults (closed-form flight, [0.5.0](#050-free-flight-in-closed-form))" % (
             e(sub(fa, exact)), e(sub(fa_d, exact))),
         "yes" if None not in (fa, fa_d, exact) and max(abs(fa - exact), abs(fa_d - exact)) <= 1e-7 else "no"],
    ]
    return ("From %s.\n\n" % cite("bench", "runs", "references", "intervals", "validation")
            + table(["target", "measured (2.0 s simulated)", "met?"], rows))


def perf_digital():
    """bench/digital.sh: case A against its PD as a 10 kHz sampled law, the flight on and off."""
    d = res("digital")["digital"]
    rows = []
    for name in ["continuous", "digital", "noflight", "digital_noflight"]:
        r = d["runs"][name]
        rows.append(["`%s`" % r["case"], f(r["cpu_median"], 2), n(r["steps"]), n(r["restarts"]),
                     n(r["controller_samples"]), f(r["flight_time"], 3), f(r["contact_time"], 3)])
    ra = d["ratios"]
    target = 1.3  # the controller workbench's: a sampled law costs at most 30 % more than the continuous one
    met = "met" if ra["digital_over_continuous"] <= target else "not met"
    return ("From %s (medians of %d runs each, CPU seconds of the tool's process).\n\n" % (cite("digital"), d["repeats"])
            + table(["case", "CPU s", "steps", "restarts", "samples", "flight s", "contact s"], rows)
            + "\nDigital / continuous: **%s** (the target: %s at most, %s). Without the flight / with it: %s for the "
              "continuous case, %s for the digital one.\n" % (
                  g(ra["digital_over_continuous"], 3), g(target, 2), met, g(ra["continuous_noflight_over_flight"], 3),
                  g(ra["digital_noflight_over_flight"], 3)))


def flight_sampled(group):
    """tests/test_flight_sampled.c's sensor error at the samples: the flight's (group 1) or IDA's at the
    case's tolerances (group 2), both against IDA at a thousandth of them."""
    return search("test_flight_sampled", r"sensor values " + FLOAT + r" m, .*the integrator at the case's "
                  r"tolerances: " + FLOAT + r" m", group)


def span_flight_sampled_flight():
    return e(flight_sampled(1), 1)


def span_flight_sampled_ida():
    return e(flight_sampled(2), 1)


def intervals_errors():
    """Largest error of the first ten contact intervals' starts, ends (s) and peaks (relative)
    against the reference, per setting: bench/intervals.sh's measure."""
    runs = res("intervals")["runs"]
    ref = runs["ref"]["intervals"]
    out = {}
    for name in ["shipped", "defaults"]:
        run = runs[name]["intervals"]
        m = min(10, len(ref), len(run))
        ds = max((abs(a[0] - b[0]) for a, b in zip(ref[:m], run[:m])), default=None)
        closed = [(a, b) for a, b in zip(ref[:m], run[:m]) if a[1] and b[1]]
        de = max((abs(a[1] - b[1]) for a, b in closed), default=None)
        dp = max((abs(a[2] - b[2]) / a[2] for a, b in closed if a[2] > 0), default=None)
        out[name] = (ds, de, dp)
    return out


def paper_row(s):
    return [n(num(s, "contacts")), g(num(s, "contact_time"), 3), f(num(s, "total_impulse"), 2),
            f(num(s, "friction_work"), 2), n(num(s, "peak_housing_force"))]


def perf_paper_settings():
    rows = []
    for key, case in CASES:
        shipped = summary("runs", case)
        r12, r11 = summary("references", case + "/ref12"), summary("references", case + "/ref11")
        d = summary("references", case + "/defaults")
        label = key + (" (penalty)" if key in ("C", "D", "D10") else "")
        c12, c11, cd = (cpu("references", case + r) for r in ["/ref12", "/ref11", "/defaults"])
        rows.append([label, "shipped (1e-9, <= 5)" if key == "A" else "shipped"] + paper_row(shipped)
                    + [f(cpu("runs", case), 1)])
        both = [" / ".join(p) for p in zip(paper_row(r12), paper_row(r11))]
        rows.append(["", "1e-12 / 1e-11"] + both + ["%s / %s" % (f(c12, 1), f(c11, 1))])
        rows.append(["", "defaults (1e-6, <= 2)" if key == "A" else "defaults"] + paper_row(d) + [f(cd, 1)])
    return ("Every paper case, 2 s, as shipped against two converged references (rtol 1e-12 / atol 1e-15 and\n"
            "rtol 1e-11 / 1e-14, both order <= 5) and against the library defaults (`touchdown run --json --hdf5\n"
            "'' --csv '' [--set solver.rtol=R --set solver.atol=A --set solver.max_order=O] cases/paper-X.cfg`,\n"
            "one run each; CPU s of the run on the shared 2-core machine, load average %s and %s at the starts; %s):\n\n" % (
                g(res("runs")["machine"]["loadavg_start"], 2), g(res("references")["machine"]["loadavg_start"], 2),
                cite("runs", "references"))
            + table(["case", "run", "onsets", "time in contact s", "total impulse N s", "friction work J",
                     "peak housing force N", "CPU s"], rows))


def perf_paper_findings():
    imp_s, fw_s, imp_d, fw_d, on_sp, ct_sp, inside, outside = [], [], [], [], [], [], 0, []
    for key, case in CASES:
        s = summary("runs", case)
        refs = [summary("references", case + "/ref12"), summary("references", case + "/ref11")]
        d = summary("references", case + "/defaults")
        for k, acc_s, acc_d in [("total_impulse", imp_s, imp_d), ("friction_work", fw_s, fw_d)]:
            v = [num(x, k) for x in refs + [s]]
            acc_s.append(mx(rel(a, b) for a in v for b in v))
            acc_d.append(mx(rel(num(d, k), num(r, k)) for r in refs))
        on = [num(r, "contacts") for r in refs]
        ct = [num(r, "contact_time") for r in refs]
        on_sp.append(rel(mx(on), mn(on)))
        ct_sp.append(rel(mx(ct), mn(ct)))
        if None not in on + ct + [num(s, "contacts"), num(s, "contact_time")] and \
                min(on) <= num(s, "contacts") <= max(on) and min(ct) <= num(s, "contact_time") <= max(ct):
            inside += 1
        else:
            outside.append("%s: %s onsets and %s s against %s and %s s" % (
                key, n(num(s, "contacts")), g(num(s, "contact_time"), 3),
                " / ".join(n(x) for x in on), " / ".join(g(x, 3) for x in ct)))
    pen = []
    for key, case in CASES[2:]:
        d = summary("references", case + "/defaults")
        ct = [num(summary("references", case + "/" + r), "contact_time") for r in ["ref12", "ref11"]]
        factor = div(num(d, "contact_time"), mx(ct))
        pen.append("%s %s s against %s s%s" % (key, g(num(d, "contact_time"), 3), span_range(ct, lambda x: g(x, 2)),
                                               " (%.0f times)" % factor if factor and factor >= 2 else " (within %s)" % pct(
                                                   rel(num(d, "contact_time"), mx(ct)), 0)))
    dpk = [num(summary("references", "paper-d-kc1.25e12/" + r), "peak_housing_force") for r in ["ref12", "ref11"]]
    firsts = {}
    for key, case in CASES:
        for src, k in [("runs", case)] + [("references", case + "/" + r) for r in ["ref12", "ref11", "defaults"]]:
            firsts.setdefault("A" if key in ("A", "C") else "B", []).append(num(summary(src, k), "first_contact_time"))
    firsts = {r: [x for x in v if x is not None] or [float("nan")] for r, v in firsts.items()}
    first_txt = "; ".join("%s's rotor (%s) %s s, %s s between the %d runs" % (
        rotor, "A, C" if rotor == "A" else "B, D, D10", f(statistics.median(v), 12), e(max(v) - min(v), 1), len(v))
        for rotor, v in sorted(firsts.items()))
    cpu = {k: bench_case("shipped", k, "cpu_time") for k, _ in CASES}
    dcpu = {k: bench_case("defaults", k, "cpu_time") for k, _ in CASES}
    m = bench_machine("shipped")
    return (
        "- **The total impulse and the friction work converge**, and the summary leads with them: the\n"
        "  references and the shipped run of a case agree within %s (impulse) and %s (friction work),\n"
        "  the defaults within %s and %s of the references.\n" % (
            pct(mx(imp_s)), pct(mx(fw_s)), pct(mx(imp_d)), pct(mx(fw_d)))
        + "- **The onset count and the time in contact are not converged quantities** over 2 s of bouncing:\n"
        "  the two references differ by %s in onsets and %s in time in contact (the sequence depends\n"
        "  on rounding after a few dozen bounces). As shipped %d of the 5 cases fall inside that spread%s.\n"
        "  At the defaults, time in contact of the penalty cases against the references: %s. Where it is\n"
        "  many times too long, BDF2 has damped the contact ringing (56 kHz at Kc = 1.25e12 N/m), and the\n"
        "  rotor lost its rebound and rested on the retainer.\n" % (
            span_range(on_sp, lambda x: "%.0f" % (100 * x), " %"), span_range(ct_sp, lambda x: "%.0f" % (100 * x), " %"),
            inside, (" (outside: " + "; ".join(outside) + ")") if outside else "", ", ".join(pen))
        + "- **The peak forces are not converged** (the constraint's is an instantaneous impulse-like peak,\n"
        "  the summary says so; a stiff penalty peak is v0 sqrt(m_eff Kc) of the hardest of two thousand\n"
        "  chaotic impacts: D's references differ by %s).\n" % pct(rel(mx(dpk), mn(dpk)), 0)
        + "- **First contacts** are the closed-form flight's at every setting: %s.\n" % first_txt
        + "- **Cost** (`touchdown bench -n 3`, cases as shipped, CPU s, median of 3, load average %s to %s):\n"
        "  A %s, B %s, C %s, D %s, D10 %s; penalty against constraint in the same invocation\n"
        "  C/A %s, D/B %s, D10/B %s. The constraint cases take %s and %s times their CPU time at the\n"
        "  defaults (A %s, B %s s). Case B runs at %s times real time: the real-time targets are not met\n"
        "  on the full model (%s).\n" % (
            g(m["loadavg_start"], 2), g(m["loadavg_end"], 2),
            *(g(cpu[k], 3) for k, _ in CASES),
            *(g(bench_ratio("shipped", r), 2) for r in ["C/A", "D/B", "D10/B"]),
            g(div(cpu["A"], dcpu["A"]), 2), g(div(cpu["B"], dcpu["B"]), 2), g(dcpu["A"], 3), g(dcpu["B"], 3),
            g(rtf_cpu("shipped", "B"), 2), cite("bench")))


def perf_remains():
    full, red = summary("runs", "paper-b/0.5"), summary("runs", "paper-b/0.5/reduced")
    rub, rubr = summary("runs", "rub-damped"), summary("runs", "rub-damped/reduced")
    rub_c, rubr_c = cpu("runs", "rub-damped"), cpu("runs", "rub-damped/reduced")
    return (
        "- The 10x real-time target for case B at accurate tolerances: not met. As shipped (rtol 1e-9, BDF\n"
        "  order <= 5) case B runs at %sx real time ([summary](#summary)); the cost is IDA in contact, held\n"
        "  to microsecond steps by the undamped rig's 11-13 kHz modes. The reduced rotor removes only part\n"
        "  of them: the local rotations of the AMB journals live on nodes that carry parts and stay\n"
        "  physical. Case B to 0.5 s as shipped: %s s of CPU and %s steps full, %s s and %s steps\n"
        "  with a 2 kHz cut-off (total impulse %s against %s N s; onsets %s against %s, the micro-bounces\n"
        "  the dropped modes drove; `touchdown run --set end_time=0.5 [--set reduction.cutoff=2000]\n"
        "  cases/paper-b.cfg`, %s). What would reach it needs a decision on the model or the rig\n"
        "  ([above](#what-would-reach-10x-decisions-outside-this-code)).\n"
        "- `rub-damped` at 30x real time (full model) and 100x (reduced): %s; %sx and %sx\n"
        "  (%s and %s s of CPU for 2 s, one run each). It is %s IDA steps and\n"
        "  no free flight: the flight does not carry retainers with a race body or their own contact law\n"
        "  even while they are free, and half of the 2 s is free. Carrying those phases (the race on its\n"
        "  mount is linear; its spin-down under Coulomb drag is piecewise) is the next step for speed.\n" % (
            g(rtf_cpu("shipped", "B"), 2),
            g(cpu("runs", "paper-b/0.5"), 3), n(num(full, "stats", "steps")), g(cpu("runs", "paper-b/0.5/reduced"), 3),
            n(num(red, "stats", "steps")), f(num(full, "total_impulse"), 2), f(num(red, "total_impulse"), 2),
            n(num(full, "contacts")), n(num(red, "contacts")), cite("runs"),
            "met" if lt(rub_c, 2 / 30) and lt(rubr_c, 2 / 100) else "not met",
            g(div(2, rub_c), 2), g(div(2, rubr_c), 2), g(rub_c, 2), g(rubr_c, 2), n(num(rub, "stats", "steps"))))


# --- docs/validation.md --------------------------------------------------------------------------
def val_paper_cases():
    rows = []
    for key, case in CASES:
        s = summary("runs", case)
        drift = num(s, "stats", "worst_drift") if key in ("A", "B") else None
        free = s.get("returned_to_free_orbit")
        rows.append([LABEL[case], f(num(s, "first_contact_time"), 8), n(num(s, "contacts")),
                     n(num(s, "peak_normal_force")), n(num(s, "peak_housing_force")),
                     pct(num(s, "contact_fraction"), 2 if key not in ("A", "B") else 1),
                     "-" if free is None else ("yes" if free else "no"), f(cpu("runs", case), 2),
                     f(cpu_per_rev("runs", case), 3), e(drift)])
    d = [summary("references", c + "/defaults") for _, c in CASES]
    return (table(["case", "first contact, s", "contact onsets", "peak normal force, N", "peak housing force, N",
                   "time in contact", "returned to free orbit", "CPU time, s", "CPU s / rev after 1st contact",
                   "worst drift, m"], rows)
            + "\n(Every case to its 2 s, one run each as shipped, `touchdown run --json --hdf5 '' --csv ''\n"
            "cases/paper-X.cfg`, %s; the CPU times on the shared 2-core machine, load average %s at the\n"
            "start.) At the library defaults (rtol 1e-6, atol 1e-9 m, order <= 2) the same cases make\n"
            "%s onsets and spend %s in contact (%s; the converged\n"
            "references: [performance](performance.md#the-papers-cases-settings-that-converge)).\n" % (
                cite("runs"), g(res("runs")["machine"]["loadavg_start"], 2), " / ".join(n(num(x, "contacts")) for x in d),
                " / ".join(pct(num(x, "contact_fraction"), 1) for x in d), cite("references")))


def val_paper_vs_here():
    a, b = summary("runs", "paper-a"), summary("runs", "paper-b")
    tol = [num(summary("tolerances", "paper-a/" + r), "peak_normal_force") for r in ["1e-6", "1e-7", "1e-8"]]
    tol.append(num(a, "peak_normal_force"))
    d, d10 = summary("runs", "paper-d-kc1.25e12"), summary("runs", "paper-d-kc1.25e10")
    rows = [
        ["A: peak contact force", "1.8 kN, settling to peaks of ~700 N",
         "%s kN (%s kN across rtol 1e-6..1e-9)" % (g(kn(num(a, "peak_normal_force")), 2),
                                                  span_range([kn(x) for x in tol], lambda x: g(x, 2)))],
        ["A: after the unbalance is reduced", "returns to the non-contacting orbit",
         "%s (last contact ends at %s s)" % ("yes" if a.get("returned_to_free_orbit") else "no",
                                             f(num(a, "last_contact_time"), 2))],
        ["B: motion, peak force", "bouncing, up to 2.2 kN",
         "%s contact onsets, peak %s kN" % (n(num(b, "contacts")), g(kn(num(b, "peak_normal_force")), 3))],
        ["constrained model, s per revolution", "13.3", "%s (A), %s (B)" % (
            g(bench_cpu_per_rev("shipped", "A"), 2), g(bench_cpu_per_rev("shipped", "B"), 2))],
        ["penalty 1.25e12 (190 rad/s): s per revolution, peak", "716 s, 0.9 kN", "%s s, %s kN" % (
            g(bench_cpu_per_rev("shipped", "D"), 2), g(kn(num(d, "peak_normal_force")), 3))],
        ["penalty 1.25e10 (190 rad/s): s per revolution, peak", "331 s, 85 N", "%s s, %s kN" % (
            g(bench_cpu_per_rev("shipped", "D10"), 2), g(kn(num(d10, "peak_normal_force")), 3))],
    ]
    return (table(["", "paper (its own rig and computer, 2000s)", "here"], rows)
            + "\n(s per revolution: CPU time per revolution after the first contact, `touchdown bench -n 3`\n"
            "median; %s.)\n" % cite("bench", "runs", "tolerances"))


def val_tolerances():
    rows = []
    peaks, ons = [], []
    for rtol in ["1e-6", "1e-7", "1e-8", "1e-9"]:
        if rtol == "1e-9":
            a, b = summary("runs", "paper-a"), summary("runs", "paper-b")
            a_cpu = cpu("runs", "paper-a")
        else:
            a, b = summary("tolerances", "paper-a/" + rtol), summary("tolerances", "paper-b/" + rtol)
            a_cpu = cpu("tolerances", "paper-a/" + rtol)
        peaks += [num(a, "peak_normal_force"), num(b, "peak_normal_force")]
        ons += [num(a, "contacts"), num(b, "contacts")]
        rows.append([rtol + (" (shipped)" if rtol == "1e-9" else ""), f(num(a, "first_contact_time"), 12),
                     n(num(a, "contacts")), n(num(a, "peak_normal_force")), pct(num(a, "contact_fraction")),
                     n(num(b, "contacts")), n(num(b, "peak_normal_force")), pct(num(b, "contact_fraction")),
                     f(a_cpu, 1)])
    return (table(["rtol (atol = 1e-3 rtol m)", "A: first contact, s", "onsets", "peak, N", "in contact",
                   "B: onsets", "peak, N", "in contact", "A CPU s"], rows)
            + "\n(BDF order <= 5 as shipped; exact first contact %s s; %s.)\n" % (
                f(exact_first_contact(), 12), cite("tolerances", "runs", "validation")))


def val_mesh():
    rows = []
    fcs = {}
    for k in [1, 2, 4, 8, 16]:
        fc = num(summary("mesh", "first-contact/%d" % k), "first_contact_time")
        fcs[k] = fc
        if k == 16:
            rows.append(["16 (193)", "", "", "", "", "", "", f(fc, 10)])
            continue
        if k == 1:
            a, b = summary("references", "paper-a/defaults"), summary("references", "paper-b/defaults")
        else:
            a, b = summary("mesh", "paper-a/%d" % k), summary("mesh", "paper-b/%d" % k)
        rows.append(["%d (%d)" % (k, 12 * k + 1), n(num(a, "contacts")), n(num(a, "peak_normal_force")),
                     pct(num(a, "contact_fraction")), n(num(b, "contacts")), n(num(b, "peak_normal_force")),
                     pct(num(b, "contact_fraction")), f(fc, 10)])
    return (table(["k (nodes)", "A: onsets", "peak, N", "in contact", "B: onsets", "peak, N", "in contact",
                   "A: first contact (rtol 1e-10, atol 1e-13), s"], rows)
            + "\n(%s.) The first contact converges (to %s s; the 13-node rig's is %s s early).\n" % (
                cite("mesh", "references"), f(fcs[16], 8), e(sub(fcs[16], fcs[1]))))


def val_first_contact():
    fc = first_contact_test()
    t, v = fc["exact"][:2]
    rows = []
    for label, key in [("closed-form flight, defaults", "free flight in closed form, defaults"),
                       ("IDA alone, defaults (rtol 1e-6, atol 1e-9)", "IDA, defaults (rtol 1e-6, atol 1e-9)"),
                       ("IDA alone, rtol 1e-12, atol 1e-16", "tight (rtol 1e-12, atol 1e-16)")]:
        err, verr, steps = fc[key]
        rows.append([label, "%s s" % e(err), e(verr), steps])
    return ("Exact: t = %s s, radial velocity %s m/s (%s).\n\n" % (f(t, 12), f(v, 9), cite("validation"))
            + table(["method", "contact time error", "impact velocity error", "steps"], rows))


def val_rig_modal():
    w, z, crit = rig_modal_test()
    pairs = ", ".join("%.1f" % c[0] for c in crit)
    return ("16 modes at 0, 90 and 190 rad/s, largest relative difference %s in omega_d and %s in zeta; with\n"
            "the 100 Hz force lag the rig's critical speeds are %s rad/s (zeta %s; %s).\n" % (
                e(w), e(z), pairs, ", ".join("%.2f" % c[2] for c in crit), cite("validation")))


def conv_table(case, extra=False):
    rows = []
    for rtol in ["1e-6", "1e-7"]:
        for k in [1, 2, 4, 8]:
            s = summary("convergence", "%s/%s/%d" % (case, rtol, k))
            row = [rtol, str(12 * k), f(cpu("convergence", "%s/%s/%d" % (case, rtol, k)), 2),
                   f(num(s, "peak_housing_force"), 1),
                   f(num(s, "total_impulse"), 2), g(num(s, "friction_work"), 6), f(num(s, "contact_time"), 5),
                   f(num(s, "peak_normal_force"), 1)]
            if extra:
                row += [f(num(s, "final_speed"), 3), s.get("ending") or "-"]
            rows.append(row)
    head = ["rtol", "elements", "CPU s", "peak housing force (N)", "total impulse (N s)", "friction work (J)",
            "time in contact (s)", "peak normal force (N)"]
    if extra:
        head += ["final speed (rad/s)", "ending"]
    changes = []
    keys = [("housing force", "peak_housing_force"), ("impulse", "total_impulse"),
            ("friction work", "friction_work"), ("time in contact", "contact_time")]
    if extra:
        keys.append(("final speed", "final_speed"))
    for rtol in ["1e-6", "1e-7"]:
        s4, s8 = (summary("convergence", "%s/%s/%d" % (case, rtol, k)) for k in (4, 8))
        changes.append("rtol %s: %s" % (rtol, ", ".join(
            "%s %s %%" % (label, g(div(rel(num(s8, k), num(s4, k)), 0.01), 2)) for label, k in keys)))
    return (table(head, rows) + "\n48 -> 96 elements, relative change: %s (%s).\n" % (
        "; ".join(changes), cite("convergence")))


def val_conv_rub_damped():
    return conv_table("rub-damped")


def val_conv_paper_a():
    return conv_table("paper-a")


def val_conv_drop():
    return conv_table("drop", extra=True)


# The answers of the spread table: JSON name, column head, number format.
SPREAD_COLUMNS = [("peak_housing_force", "peak housing force (N)", n), ("contacts", "contacts", n),
                  ("contact_time", "time in contact (s)", lambda x: g(x, 3)),
                  ("total_impulse", "total impulse (N s)", lambda x: f(x, 1)),
                  ("friction_work", "friction work (J)", lambda x: g(x, 4)),
                  ("final_speed", "final speed (rad/s)", lambda x: g(x, 5))]
SPREAD_NAMES = {"peak_housing_force": "peak housing force", "total_impulse": "impulse",
                "friction_work": "friction work", "final_speed": "final speed", "contacts": "contacts",
                "contact_time": "time in contact", "first_contact_time": "first contact",
                "peak_normal_force": "peak normal force", "peak_amb_force": "peak AMB force"}


def spread_cell(a, fmt):
    """'least-greatest (spread)', the spread bold when it does not settle; '-' without values."""
    if not a or not a.get("count"):
        return "-"
    lo, hi = fmt(a["least"]), fmt(a["greatest"])
    spread = "-" if a["spread"] is None else g(100.0 * a["spread"], 2) + " %"
    if a.get("settles") is False:
        spread = "**%s**" % spread
    return "%s (%s)" % (lo if lo == hi else "%s-%s" % (lo, hi), spread)


def val_spread():
    runs = res("spread")["runs"]
    rows, settle = [], []
    # the paper's cases in their order, then the others as recorded
    order = [c for _, c in CASES if c in runs] + sorted(c for c in runs if c not in dict(CASES).values())
    for case in order:
        sp = runs[case]["summary"].get("spread") or {}
        answers = sp.get("answers", {})
        label = next((k for k, c in CASES if c == case), case)
        rows.append([label, "%s of %s" % (sp.get("completed", "-"), sp.get("members", "-")),
                     "%s (%s)" % (sp.get("same_ending", "-"), sp.get("ending") or "-")]
                    + [spread_cell(answers.get(k), fmt) for k, _, fmt in SPREAD_COLUMNS]
                    + [f(cpu("spread", case), 1)])
        ok = [SPREAD_NAMES[k] for k in SPREAD_NAMES if (answers.get(k) or {}).get("settles") is True]
        settle.append("%s: %s" % (label, ", ".join(ok) if ok else "none"))
    members = next(iter(runs.values()))["summary"]["spread"]["members"]
    return (table(["case", "runs that reached their end", "ended as the run did"] + [h for _, h, _ in SPREAD_COLUMNS]
                  + ["CPU s"], rows)
            + "\n(`touchdown run --json --spread %d --hdf5 '' --csv '' cases/CASE.cfg`: each case as shipped and %d "
            "more runs with\nsolver.atol x 0.99 .. 1.01; least-greatest over the %d runs, and in brackets the spread, "
            "(greatest - least) /\n|median|, **bold** where it is above 2 %%, the range of atol: the answer does not "
            "settle. CPU s: the\n%d runs together on the shared 2-core machine; %s.)\n\nSettles (spread at most "
            "2 %%), of all nine answers of the summary:\n\n%s\n" % (
                members, members - 1, members, members, cite("spread"),
                "\n".join("- " + line for line in settle)))


def span_readme_spread_a():
    """Which of case A's answers in the spread table settle and which do not."""
    answers = summary("spread", "paper-a")["spread"]["answers"]
    words = {True: [], False: []}
    for k, _, _ in SPREAD_COLUMNS:
        if answers[k].get("settles") is not None:
            words[answers[k]["settles"]].append("the " + SPREAD_NAMES[k])

    def listing(w):
        return w[0] if len(w) == 1 else ", ".join(w[:-1]) + " and " + w[-1]
    parts = []
    if words[False]:
        parts.append("%s do%s not settle" % (listing(words[False]), "es" if len(words[False]) == 1 else ""))
    if words[True]:
        parts.append("%s do%s" % (listing(words[True]), "es" if len(words[True]) == 1 else ""))
    return "; ".join(parts) or "no answer has a spread"


def test_messages(test):
    return res("validation")["tests"][test]["messages"]


def beam_blocks():
    """test_beams' convergence tables: {title: {elements: [(error, order) of modes 1-3]}}."""
    blocks, title = {}, None
    for line in test_messages("test_beams"):
        if re.match(r"(Pinned|Free)", line):
            title = line
            blocks[title] = {}
        elif title and re.match(r"\s+\d+\s+-?[0-9.]+e", line):
            fields = line.replace("(", " ").replace(")", " ").split()
            k, rest = int(fields[0]), [float(x) for x in fields[1:]]
            # "K  e1  e2  e3" on the first row, "K  e1 (o1)  e2 (o2)  e3 (o3)" after it
            errs, orders = (rest, [None] * 3) if len(rest) == 3 else (rest[0::2], rest[1::2])
            blocks[title][k] = list(zip(errs, orders))
        elif not line.strip() or line.startswith(("Timoshenko", "EB vs")):
            title = None
    return blocks


BEAMS = [("pinned-pinned, L/d = 1000, EB consistent vs Rayleigh", "EB element, consistent mass, vs Rayleigh", "L/d = 1000"),
         ("free-free, L/d = 10000, EB consistent vs EB", "Free-free, EB element", "L/d = 10000"),
         ("pinned-pinned, L/d = 10, EB lumped vs Rayleigh", "LUMPED", "L/d = 10)"),
         ("pinned-pinned, L/d = 10, Timoshenko vs Timoshenko", "Timoshenko element", "L/d = 10)"),
         ("pinned-pinned, L/d = 4, Timoshenko vs Timoshenko", "Timoshenko element", "L/d = 4)")]


def beam_block(part, ld):
    for title, rows in beam_blocks().items():
        if part in title and ld in title:
            return rows
    return {}


def val_beams():
    rows = []
    for label, part, ld in BEAMS:
        b = beam_block(part, ld)
        cells = [", ".join(e(x[0]) for x in b.get(k, [])) or "-" for k in (4, 16, 64)]
        cells.append(", ".join(f(x[1], 1) for x in b.get(32, [])) or "-")
        rows.append([label] + cells)
    timo = [l for l in test_messages("test_beams") if re.match(r"\s+(5|100)\s+-?[0-9.]+e", l)]
    t = {int(l.split()[0]): float(l.split()[1]) for l in timo}
    return (table(["beam, element", "4 el.", "16 el.", "64 el.", "order (16 -> 32 el.)"], rows)
            + "\nConsistent mass converges from above, lumped mass from below; Timoshenko minus EB scales as\n"
            "(d/L)^2 (%s at L/d = 100, %s at L/d = 5 for mode 1; %s).\n" % (e(t.get(100)), e(t.get(5)),
                                                                           cite("validation")))


def jeffcott():
    out = {}
    for line in test_messages("test_jeffcott"):
        m = re.match(r"Jeffcott omega_n = ([0-9.]+) rad/s, modes ([0-9.]+) / ([0-9.]+) \(rel err ([0-9.eE+-]+)\)", line)
        if m:
            out["wn"], out["modes"], out["err"] = m.group(1), (m.group(2), m.group(3)), float(m.group(4))
        m = re.match(r"Jeffcott critical speed \((\w+)\).*rel err ([0-9.eE+-]+)", line)
        if m:
            out[m.group(1)] = float(m.group(2))
    return out


def overhung_errors():
    return [float(x) for line in test_messages("test_overhung_disc")
            for x in re.findall(r"\(closed [0-9.]+, ([0-9.eE+-]+)\)", line)]


def harmonic_worst():
    return mx(float(x) for line in test_messages("test_harmonic") for x in re.findall(r"rel err ([0-9.eE+-]+)", line))


def critical_root_finder():
    for line in test_messages("test_modal"):
        m = re.search(r"root finder: .*\(rel diff ([0-9.eE+-]+)\)", line)
        if m:
            return float(m.group(1))
    return None


def val_rotor_models():
    j = jeffcott()
    o = overhung_errors()
    return ("**Rotor models.** Jeffcott (`test_jeffcott`, disc on a massless shaft and bearings):\n"
            "omega_n = %s rad/s, modes %s / %s (%s), critical speeds\n"
            "%s and %s. Overhung disc (`test_overhung_disc`): forward and backward whirl frequencies of\n"
            "both modes at 0, 500, 1000, 3000 rad/s within %s .. %s of the quartic's roots. Unbalance\n"
            "response (`test_harmonic`): amplitude and phase at W/wn = 0.3 .. 3 to %s (%s).\n" % (
                j.get("wn", "-"), *j.get("modes", ("-", "-")), e(j.get("err")), e(j.get("backward")),
                e(j.get("forward")), e(mn(o)), e(mx(o)), e(harmonic_worst()), cite("validation")))


# --- touchdown bench --scaling (docs/performance.md, "Scaling with the number of DOFs") ------------
def scaling(which):
    """One recorded `touchdown bench --scaling`: its command, its JSON and, per size, what the table
    quotes (costs are CPU s per simulated s, medians; us/step are CPU microseconds per IDA step)."""
    rec = res("scaling")["scaling"][which]
    r = rec["result"]
    span_c = r["t_contact"] - r["t0"]
    rows = []
    for x in r["scaling"]:
        us = div(1e6 * x["contact_klu_cpu_cost"] * span_c, x["contact_steps"])
        rows.append(dict(x, us_step=us, us_step_dof=div(us, x["dofs"]),
                         dense_over_klu=div(x["free_dense_cpu_cost"], x["free_klu_cpu_cost"])))
    return rec, r, rows


def slopes(rows, key):
    """The exponents p of cost ~ DOFs^p between successive sizes."""
    return [math.log(b[key] / a[key]) / math.log(b["dofs"] / a["dofs"]) for a, b in zip(rows, rows[1:])
            if a[key] and b[key]]


def wrap(text, indent=""):
    """A paragraph or a list item (INDENT on its continuation lines) wrapped at the page's width."""
    return textwrap.fill(" ".join(text.split()), 105, subsequent_indent=indent, break_long_words=False,
                         break_on_hyphens=False) + "\n"


def perf_scaling():
    rec, r, rows = scaling("defaults")
    srec, sr, srows = scaling("shipped")
    sets = re.findall(r"--set (\S+)", rec["command"])
    first, last = rows[0], rows[-1]
    per_dof = [x["us_step_dof"] for x in rows]
    free = sorted({x["free_steps"] for x in rows} | {x["free_steps_dense"] for x in rows})
    dense = slopes(rows, "free_dense_cpu_cost")
    grow = div(last["contact_klu_cpu_cost"], first["contact_klu_cpu_cost"])
    m = r["machine"]
    out = wrap(
        "`touchdown bench --scaling`: case A's machine with every shaft element split into k = 1, 4, 8, 16 "
        "equal ones (%s nodes; node i becomes node k i, so discs, AMBs, retainers and the unbalance keep their "
        "axial positions), from t = %s s; free flight to %s s with KLU and with the dense solver (SUNDIALS's "
        "`SUNLinSol_Dense`), and through the first contact to %s s with KLU. Cost: CPU s of the run (set-up "
        "aside) per simulated s, median of %d; us/step: CPU microseconds per IDA step in contact. At the "
        "library's solver defaults, with IDA through the free flight too (`%s`; %s; load average %s to %s):" % (
            ", ".join(str(x["nodes"]) for x in rows), f(r["t0"], 2), f(r["t_free"], 2), f(r["t_contact"], 2),
            r["repeats"], "`, `".join(sets), cite("scaling"), f(m["loadavg_start"], 2), f(m["loadavg_end"], 2)))
    out += "\n" + table(["nodes", "DOFs", "free: steps", "KLU cost", "dense cost", "dense / KLU", "contact: steps",
                         "onsets", "KLU cost", "us/step", "us/step/DOF"],
                        [[n(x["nodes"]), n(x["dofs"]), n(x["free_steps"]), g(x["free_klu_cpu_cost"]),
                          g(x["free_dense_cpu_cost"]), g(x["dense_over_klu"], 2), n(x["contact_steps"]),
                          n(x["contact_onsets"]), g(x["contact_klu_cpu_cost"]), g(x["us_step"], 2),
                          g(x["us_step_dof"], 2)] for x in rows]) + "\n"
    out += wrap(
        "- The cost of a step in contact %s the DOF count (%s to %s us per step per DOF, %s to %s DOFs)%s." % (
            "grows in proportion to" if mx(per_dof) / mn(per_dof) < 1.5 else "grows faster than",
            g(mn(per_dof), 2), g(mx(per_dof), 2), n(first["dofs"]), n(last["dofs"]),
            ", as it does when KLU's fill of the banded shaft stays proportional to its size"
            if mx(per_dof) / mn(per_dof) < 1.5 else ""), "  ")
    fewer = last["contact_steps"] < first["contact_steps"]
    out += wrap(
        "- The cost per simulated second of contact grows %sx for %sx the DOFs%s. The free flight is %s IDA "
        "steps at every size, with KLU and dense alike." % (
            g(grow, 2), g(div(last["dofs"], first["dofs"]), 2),
            (", less than linearly, because the refined rigs take fewer steps (%s at %s nodes against %s at %s): "
             "their highest modes are far above 1/h and BDF2 damps them in a step (see above)" % (
                 n(last["contact_steps"]), n(last["nodes"]), n(first["contact_steps"]), n(first["nodes"])))
            if fewer and grow < div(last["dofs"], first["dofs"]) else "",
            " or ".join(n(x) for x in free)), "  ")
    if all(lt(1, x["dense_over_klu"]) for x in rows):
        out += wrap(
            "- KLU is faster than the dense solver at every size tried, %sx already at %s DOFs; the dense cost "
            "grows like DOFs^%s to DOFs^%s between successive sizes (the dense LU of this SUNDIALS build, not "
            "an optimised one)." % (g(first["dense_over_klu"], 2), n(first["dofs"]), f(mn(dense), 1), f(mx(dense), 1)),
            "  ")
    else:
        out += wrap("- The dense solver is faster than KLU at some size tried (dense / KLU in the table).", "  ")
    up = all(b["contact_steps"] > a["contact_steps"] for a, b in zip(srows, srows[1:]))
    out += wrap(
        "- Without the `--set`s, `touchdown bench --scaling` runs case A's settings as shipped (the paper's "
        "rtol 1e-9, BDF order <= 5 and the closed-form free flight, [above](#the-papers-cases-settings-that-converge)), "
        "and the step counts in contact %s with the refinement: %s at %s nodes, %sx the defaults' steps. One "
        "repeat (`%s`: %s s of CPU; the table above took %s s):" % (
            "grow" if up else "do not fall", n(srows[-1]["contact_steps"]), n(srows[-1]["nodes"]),
            g(div(srows[-1]["contact_steps"], last["contact_steps"]), 2), srec["command"], g(srec["cpu_time"], 3),
            g(rec["cpu_time"], 2)), "  ")
    out += "\n" + table(["nodes", "free: IDA steps", "free: cost", "contact: steps", "onsets", "KLU cost",
                         "us/step", "steps / defaults' steps"],
                        [[n(x["nodes"]), n(x["free_steps"]), g(x["free_klu_cpu_cost"]), n(x["contact_steps"]),
                          n(x["contact_onsets"]), g(x["contact_klu_cpu_cost"]), g(x["us_step"], 2),
                          g(div(x["contact_steps"], d["contact_steps"]), 2)] for x, d in zip(srows, rows)])
    closed = [(x, d) for x, d in zip(srows, rows) if x["free_steps"] == 0]
    if closed:
        x, d = closed[-1]
        out += "\n" + wrap(
            "Where the free window takes 0 IDA steps (%s nodes) the closed-form flight carries it; at %s nodes "
            "it costs %s CPU s per simulated s against %s for IDA's %s steps at the defaults%s." % (
                ", ".join(str(c["nodes"]) for c, _ in closed), n(x["nodes"]), g(x["free_klu_cpu_cost"]),
                g(d["free_klu_cpu_cost"]), n(d["free_steps"]),
                "; at %s nodes IDA takes %s steps in it" % (n(srows[-1]["nodes"]), n(srows[-1]["free_steps"]))
                if srows[-1]["free_steps"] else ""))
    return out


def span_val_beams_cell():
    eb = beam_block("EB element, consistent mass, vs Rayleigh", "L/d = 1000").get(16)
    ti = beam_block("Timoshenko element", "L/d = 10)").get(16)
    return "%s (EB mode 1), %s (Timoshenko mode 1)" % (e(eb[0][0]) if eb else "-", e(ti[0][0]) if ti else "-")


def span_val_jeffcott_cell():
    j = jeffcott()
    return "%s (mode), %s / %s (critical speeds)" % (e(j.get("err")), e(j.get("backward")), e(j.get("forward")))


def span_val_overhung_cell():
    return "<= %s" % e(mx(overhung_errors()))


def span_val_harmonic_cell():
    return "<= %s" % e(harmonic_worst())


def span_val_root_finder_cell():
    return e(critical_root_finder())


FLOAT = r"(-?[0-9.]+(?:e[+-]?[0-9]+)?)"


def search(test, pattern, group=1):
    """The first match of PATTERN in TEST's messages, as a float (None if none)."""
    for line in test_messages(test):
        m = re.search(pattern, line)
        if m:
            return float(m.group(group))
    return None


def val_annular_rub():
    rows = []
    for line in test_messages("test_annular_rub"):
        m = re.match(r"(defaults.*?|rtol 1e-10.*?|W \d+, U [0-9.]+, mu [0-9.]+)(?: \(N [0-9.]+\))?:\s+N = [0-9.]+ N "
                     r"\(rel\. error " + FLOAT + r"\), phase [0-9.]+ rad \(error " + FLOAT + r"\), whirl rate / W - 1 = "
                     + FLOAT + r", (\d+) steps", line)
        if m:
            label = m.group(1) + (" (order 5, rtol 1e-10)" if m.group(1).startswith("W 150") else "")
            rows.append([label, e(float(m.group(2))), e(float(m.group(3))), e(float(m.group(4))), n(int(m.group(5)))])
    return (table(["solver", "N rel. error", "phase error, rad", "whirl rate / W - 1", "steps"], rows)
            + "\n(%s.)\n" % cite("validation"))


def val_annular_mount():
    rows = []
    for line in test_messages("test_annular_rub"):
        m = re.match(r"mount, (constraint|Kc 1e10) .*N rel\. error " + FLOAT + r", phase error " + FLOAT +
                     r" rad, .*\(rel\. error " + FLOAT + r"\), lead error " + FLOAT + r" rad, radius - expected "
                     + FLOAT + r" m, .*, (\d+) steps", line)
        if m:
            rows.append(["constraint" if m.group(1) == "constraint" else "Kc = 1e10 N/m"]
                        + [e(float(m.group(i))) for i in range(2, 7)] + [n(int(m.group(7)))])
    miss = search("test_annular_rub", r"compliant run against the constraint's closed form: N " + FLOAT)
    return (table(["contact", "N rel. error", "phase error, rad", "\\|z_r\\| rel. error", "its angle error, rad",
                   "r - rho, m", "steps"], rows)
            + "\nThe compliant run's N misses the constraint's closed form by %s, far outside the tolerance (%s).\n"
            % (e(miss), cite("validation")))


def ge(x):
    """An error: plain between 0.01 and 10, else in exponent form."""
    return g(x, 2) if x is not None and 0.01 <= abs(x) < 10 else e(x)


def val_penalty():
    rows = []
    names = {"rigid": "constraint", "HC": "Hunt-Crossley", "undamped": "undamped"}
    for line in test_messages("test_penalty_convergence"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 10 or cells[0] not in names:
            continue
        law, kc = names[cells[0]], float(cells[1])
        v = [float(c) for c in cells[2:10]]
        rigid = law == "constraint"
        rows.append([law, "-" if rigid else cells[1].replace(".00e+", "e").replace("e+", "e"),
                     f(v[0], 6), "-" if rigid else ge(v[1]), f(v[2], 6), "-" if rigid else ge(v[3]),
                     f(v[4], 4), "-" if rigid else ge(v[5]), "%.0f (lambda)" % v[6] if rigid else e(v[6], 3), e(v[7])])
    return (table(["law", "Kc, N/m", "I_20, N s", "error", "I_r, N s", "error", "1st contact, ms", "error", "peak, N",
                   "max penetration, m"], rows) + "\n(%s.)\n" % cite("validation"))


def val_scenarios():
    t = "test_sim_scenarios"
    en = [l for l in test_messages(t) if l.startswith("energy drift inside contact phases")]
    m = re.match(r"energy drift inside contact phases: " + FLOAT + r" \(rtol 1e-8\), " + FLOAT + r" \(rtol 1e-10\); "
                 r"onsets (\d+), (\d+); largest relative change across an onset " + FLOAT + ", " + FLOAT, en[0]) if en else None
    two = [l for l in test_messages(t) if l.startswith("two contacts:")]
    m2 = re.match(r"two contacts: (\d+) samples with both retainers in contact, \d+ contact samples, (\d+) onsets, "
                  r"worst drift " + FLOAT, two[0]) if two else None
    rest = [l for l in test_messages(t) if l.startswith("retainer 0 at rest")]
    m3 = re.match(r"retainer 0 at rest: angle " + FLOAT + r" deg \(expected " + FLOAT + r"\), N = " + FLOAT
                  + r" N \(expected " + FLOAT + r"\)", rest[0]) if rest else None
    grp = (lambda mm, i: mm.group(i) if mm else "-")
    return (
        "- *Energy.* Rig with AMBs replaced by undamped springs, frictionless retainers, gravity, start at\n"
        "  rest: the rotor falls and chatters on both retainers (%s onsets in 30 ms). Between onset and\n"
        "  release the constraint does no work, so the mechanical energy must stay constant: largest relative\n"
        "  change inside a contact phase %s at rtol 1e-8 and %s at rtol 1e-10 (asserted < 2e-6 and\n"
        "  a 10x drop: it is solver error, BDF2 damping the undamped high modes the impacts excite). Every\n"
        "  plastic impact loses energy (largest change across an onset %s and %s).\n"
        "- *Two contacts at once* (unbalances at both end discs, 1 rad apart): %s samples with both\n"
        "  retainers in contact, %s onsets, worst drift %s m, friction = -sgn(v_s) mu N to 1e-12.\n"
        "- *Rotor drop* (AMBs fail, gravity, structural damping): at rest on both retainers at the whirl\n"
        "  angle %s deg (expected -90 - atan(mu) = %s deg) with N = %s N each (expected\n"
        "  m g / (2 sqrt(1 + mu^2)) = %s N; %s).\n" % (
            grp(m, 3) if grp(m, 3) == grp(m, 4) else grp(m, 3) + "-" + grp(m, 4), e(float(grp(m, 1))) if m else "-", e(float(grp(m, 2))) if m else "-",
            e(float(grp(m, 5))) if m else "-", e(float(grp(m, 6))) if m else "-",
            grp(m2, 1), grp(m2, 2), e(float(grp(m2, 3))) if m2 else "-",
            grp(m3, 1), grp(m3, 2), grp(m3, 3), grp(m3, 4), cite("validation")))


def span_val_energy_cell():
    a = search("test_sim_scenarios", r"energy drift inside contact phases: " + FLOAT)
    b = search("test_sim_scenarios", r"\(rtol 1e-8\), " + FLOAT + r" \(rtol 1e-10\)")
    return "%s (rtol 1e-8), %s (rtol 1e-10)" % (e(a), e(b))


def span_val_two_cell():
    return "drift %s m" % e(search("test_sim_scenarios", r"two contacts: .*worst drift " + FLOAT))


def span_val_drop_rest_cell():
    ang = search("test_sim_scenarios", r"retainer 0 at rest: angle " + FLOAT)
    exp = search("test_sim_scenarios", r"retainer 0 at rest: angle \S+ deg \(expected " + FLOAT)
    nn = search("test_sim_scenarios", r"retainer 0 at rest: .*N = " + FLOAT)
    ne = search("test_sim_scenarios", r"retainer 0 at rest: .*N = \S+ N \(expected " + FLOAT)
    return "angle %s rad, N %s rel." % (e(abs(math.radians(sub(ang, exp)))) if None not in (ang, exp) else "-",
                                        e(rel(nn, ne)))


def span_val_annular_cell():
    def err(label):
        return search("test_annular_rub", re.escape(label) + r":\s+N = \S+ N \(rel\. error " + FLOAT + r"\), phase \S+ rad"
                      r" \(error " + FLOAT + r"\)"), search("test_annular_rub", re.escape(label) + r":\s+N = \S+ N "
                                                            r"\(rel\. error \S+\), phase \S+ rad \(error " + FLOAT)
    tight, dflt = err("rtol 1e-10, BDF2"), err("defaults (rtol 1e-6, BDF2)")
    return "N %s, phase %s rad (rtol 1e-10); %s (defaults)" % (e(tight[0]), e(tight[1]), e(dflt[0]))


def span_val_race_energy_cell():
    a = search("test_race", r"solver\.rtol = 1e-6 .*= " + FLOAT + r" of the largest term")
    b = search("test_race", r"solver\.rtol = 1e-8 .*= " + FLOAT + r" of the largest term")
    return "%s of the largest term (defaults), %s (rtol 1e-8, atol 1e-11)" % (e(a), e(b))


def span_val_spin_up_cell():
    x = search("test_speed", r"spin-up from rest: journal centre against the closed form within " + FLOAT)
    u = search("test_speed", r"\(U/m = " + FLOAT)
    return "%s m = %s of U/m (rtol 1e-12)" % (e(x), e(div(x, u)))


def span_val_run_up_cell():
    out = []
    for line in test_messages("test_speed"):
        m = re.match(r"run-up at (\d+) rad/s: .*\(([+-][0-9.]+) %\)", line)
        if m:
            out.append((m.group(1), "%+.2f" % float(m.group(2))))
    return "%s rad/s: %s %%" % (", ".join(s for s, _ in out), ", ".join(v for _, v in out))


def span_val_tolerance_cell():
    a = search("test_tolerance", r"error against the reference: " + FLOAT + r" \(defaults\)")
    b = search("test_tolerance", r"error against the reference: .*\(defaults\), " + FLOAT)
    return "%s (defaults), %s (rtol 1e-7, atol 1e-10)" % (pct(a, 2), pct(b, 2))


# The summary's rows whose measured errors were typed by hand before: each from its test's printed
# measurement (docs_record.py, source validation).
def span_val_mount_cell():
    def err(label):
        pre = re.escape(label) + r" \(order 5, rtol 1e-10\): "
        return (search("test_annular_rub", pre + r"N rel\. error " + FLOAT),
                search("test_annular_rub", pre + r".*phase error " + FLOAT),
                search("test_annular_rub", pre + r".*\|z_r\| \S+ m \(rel\. error " + FLOAT))
    a, b = err("mount, constraint"), err("mount, Kc 1e10")
    return "N %s / %s, phase %s / %s rad, race radius %s / %s" % (
        e(a[0]), e(b[0]), e(mag(a[1])), e(mag(b[1])), e(a[2]), e(b[2]))


def penalty_row(law, kc):
    """test_penalty_convergence's table row of LAW at KC: (I_20 error, I_r error)."""
    for line in test_messages("test_penalty_convergence"):
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) > 5 and cells[0] == law and cells[1] == kc:
            return float(cells[3]), float(cells[5])
    return None, None


def span_val_penalty_cell():
    i20, ir = penalty_row("HC", "1.00e+12")
    ratios = []
    for line in test_messages("test_penalty_convergence"):
        m = re.search(r"peak / closed form: HC ([0-9. ]+); undamped ([0-9. ]+)", line)
        if m:  # the undamped law's softest two are no short impacts (docs/validation.md)
            ratios = [float(x) for x in m.group(1).split()] + [float(x) for x in m.group(2).split()[2:]]
    dev = [abs(r - 1.0) for r in ratios]
    return "impulse %s / %s at 1e12; peaks %s-%s %%" % (e(i20), e(ir), "%.2f" % (100 * min(dev)) if dev else "-",
                                                      "%.1f" % (100 * max(dev)) if dev else "-")


def span_val_race_spin_cell():
    c = search("test_race", r"contact constraint: .*spin-up worst relative error " + FLOAT)
    k = search("test_race", r"contact compliant: .*spin-up worst relative error " + FLOAT)
    roll = mx([search("test_race", r"contact constraint: .*rolling speed error " + FLOAT),
               search("test_race", r"contact compliant: .*rolling speed error " + FLOAT)])
    v = search("test_race", r"final v_s " + FLOAT)
    cf = search("test_race", r"final v_s \S+ m/s, creep closed form " + FLOAT)
    return "%s (constraint), %s (compliant); rolling %s; creep %s" % (e(c), e(k), e(roll), e(rel(v, cf)))


def span_val_rolling_cell():
    vs = [abs(float(m.group(1))) for m in (re.search(r"contact \w+: .*\|v_s\| <= " + FLOAT + " m/s", l)
                                           for l in test_messages("test_race")) if m]
    fr = search("test_race", r"rolling: .*friction " + FLOAT)
    need = search("test_race", r"rolling: .*\(drag needs " + FLOAT)
    # the stick runs are the second pair of spin-up messages (the first pair slides with creep)
    return "\\|v_s\\| <= %s m/s; friction %s" % (e(mx(vs[2:4]) if len(vs) >= 4 else None), e(rel(fr, need)))


def span_val_whip_cell():
    def whip(label):
        pre = r"dry whip \(" + label + r"\): .*"
        n, nc = (search("test_race", pre + r"N " + FLOAT), search("test_race", pre + r"N \S+ N \(closed form " + FLOAT))
        f, fc = (search("test_race", pre + r"\|F_t\| " + FLOAT),
                 search("test_race", pre + r"\|F_t\| \S+ N \(" + FLOAT))
        return rel(n, nc), rel(f, fc), search("test_race", pre + r"\|v_s\| <= " + FLOAT)
    a, b = whip("constraint"), whip("compliant")
    def re1(x):  # 0: equal to the digits the test prints
        return "0 (to the digits printed)" if x == 0 else e(x, 1)
    return ("N %s, F_t %s, \\|v_s\\| %s m/s (constraint); %s, %s (Kc 1e10, closed form at r = c + N/Kc not "
            "taken: within 1e-4)" % (re1(a[0]), re1(a[1]), e(a[2]), re1(b[0]), re1(b[1])))


def span_val_coast_cell():
    out = []
    for law in ("constant torque", "viscous"):
        pre = r"coast-down \(" + law + r"\): Omega\(1 s\) = "
        out.append(rel(search("test_speed", pre + FLOAT), search("test_speed", pre + r"\S+ rad/s, closed form " + FLOAT)))
    return "%s rel." % e(mx(out), 1)


def span_val_levitation_cell():
    x0 = search("test_amb_pid", r"levitated start: \|xs\| <= " + FLOAT)
    f, w = (search("test_amb_pid", r"levitated start: .*AMB force " + FLOAT),
            search("test_amb_pid", r"levitated start: .*weight " + FLOAT))
    x1 = search("test_amb_pid", r"after a failure of 8 ms: \|xs\| <= " + FLOAT)
    return "\\|xs\\| %s m at the start, %s m 4 s after an 8 ms failure; force = weight to %s" % (
        e(x0), e(x1), e(rel(f, w)) if rel(f, w) else "the digits printed (10)")


def span_val_tight_cell():
    d = search("test_tight_tolerances", r"largest difference " + FLOAT)
    nf = search("test_tight_tolerances", r"rtol 1e-12: \S+ steps, " + FLOAT + " Newton failures")
    on = search("test_tight_tolerances", r"rtol 1e-12: .* Newton failures, " + FLOAT + " onsets")
    return "%s s; %s Newton failures for %s onsets" % (e(d, 3), n(nf), n(on))


def span_val_annular_order():
    """BDF2's h^2: the steps and N errors of the rub at the defaults and at rtol 1e-10 (order 2)."""
    def run(label):
        pre = re.escape(label) + r":\s+N = \S+ N \(rel\. error "
        return search("test_annular_rub", pre + FLOAT), search("test_annular_rub", pre + r".*, (\d+) steps")
    (e6, s6), (e10, s10) = run("defaults (rtol 1e-6, BDF2)"), run("rtol 1e-10, BDF2")
    w = search("test_annular_rub", r"closed form: .* W " + FLOAT + " rad/s")
    sr, er = div(s10, s6), div(e6, e10)
    return "W h = %s here, 2 s over %s steps: it scales as h^2 (%.1fx more steps at rtol 1e-10 cut the error %.0fx, " \
           "the square of the steps' ratio, %.0f)" % ("%.2g" % (w * 2.0 / s6) if w and s6 else "-", n(s6), sr or 0,
                                                     er or 0, (sr or 0) ** 2)


def span_val_releases_cell():
    return "%s releases" % n(search("test_sim_scenarios", FLOAT + r" releases, largest interval peaks"))


def span_val_grazing_cell():
    rc = [search("test_sim", r"grazing, scale " + s + r": .*max r - c " + FLOAT) for s in ("1.000000000", "1.000000001")]
    ev = [search("test_sim", r"grazing, scale " + s + r": " + FLOAT + " events")
          for s in ("0.999999999", "1.000000000", "1.000000001")]
    return "r - c <= %s m, %s-%s events in 0.3 s" % (e(mx(rc)), n(min(ev) if None not in ev else None),
                                                   n(max(ev) if None not in ev else None))


def span_val_drift_cell():
    return "%s m" % e(search("test_sim", r"case A to 0\.25 s: .*worst drift " + FLOAT))


def span_val_drift_onsets():
    return n(search("test_sim", r"case A to 0\.25 s: " + FLOAT + " onsets"))


def span_val_jeffcott_flight_cell():
    dev = search("test_sim", r"Jeffcott orbit \S+ m: worst deviation over 0\.2 s " + FLOAT)
    amp = search("test_sim", r"Jeffcott orbit " + FLOAT)
    steps = search("test_sim", r"Jeffcott orbit .* m, " + FLOAT + " steps")
    return "%s m over 0.2 s (orbit %s m), %s integrator steps" % (e(dev), e(amp), n(steps))


# --- inline spans --------------------------------------------------------------------------------
def span_rub_mean_normal():
    s = summary("runs", "rub-damped")
    return "%s N (rms %s N)" % (n(num(s, "retainer_mean_normal_force", 0)), n(num(s, "retainer_rms_normal_force", 0)))


def span_val_first_contact_cell():
    fc = first_contact_test()
    ida, tight = fc["IDA, defaults (rtol 1e-6, atol 1e-9)"], fc["tight (rtol 1e-12, atol 1e-16)"]
    return "%s s, %s (tight); %s s, %s (defaults)" % (e(mag(tight[0])), e(tight[1]), e(mag(ida[0])), e(ida[1]))


def span_val_rig_modal_cell():
    w, z, _ = rig_modal_test()
    return "omega_d %s, zeta %s" % (e(w), e(z))


def span_rig_mass():
    return "%.2f kg" % res("modal")["info"]["mass"]


def span_rig_polar():
    return "%.4f kg m^2" % res("modal")["info"]["polar_inertia"]


def span_drop_cpu():
    return "%s s" % f(cpu("runs", "drop"), 0)


def span_run_up_criticals():
    c = sorted(x["speed"] for x in res("modal")["modal"]["run-up"]["critical_speeds"])
    pairs = ["%.0f and %.0f" % (c[i], c[i + 1]) for i in range(0, len(c) - 1, 2)]
    if len(pairs) < 2:
        return ", ".join("%.0f" % x for x in c) + " rad/s"
    return "%s rad/s, the lower pairs; %s rad/s, the upper" % (", ".join(pairs[:-1]), pairs[-1])


def span_run_up_contact():
    s = summary("runs", "run-up")
    t = num(s, "first_contact_time")
    # cases/run-up.cfg: 50 rad/s to 1 s, then 10 rad/s^2 to 250 rad/s at 21 s
    return "%.0f s (about %.0f rad/s)" % (t, 50 + 10 * (t - 1)) if t is not None else "no time (no contact)"


def span_run_up_ending():
    s = summary("runs", "run-up")
    return "%s; peak housing force %s kN; %s s of CPU time for %s s" % (
        s.get("ending") or "-", g(kn(num(s, "peak_housing_force")), 2), f(cpu("runs", "run-up"), 0), f(num(s, "t_end"), 0))


def span_conv_impulses():
    return "%s N s (rigid) and %s N s (compliant, damped)" % (
        f(num(summary("runs", "paper-a"), "total_impulse"), 0), f(num(summary("runs", "rub-damped"), "total_impulse"), 0))


def span_drop_24_vs_96():
    s2, s8 = summary("convergence", "drop/1e-7/2"), summary("convergence", "drop/1e-7/8")
    worst = mx(rel(num(s2, k), num(s8, k)) for k in ["peak_housing_force", "friction_work", "final_speed"])
    return "within %s" % pct(worst, 1)


def span_drop_energy():
    en = summary("runs", "drop/energy-12").get("energy") or {}
    held = (num(en, "kinetic") or 0) + (num(en, "elastic") or 0)
    lost = sum(num(en, k) or 0 for k in ["damping_loss", "contact_loss", "drag_loss", "impact_loss"])
    r = num(en, "residual")
    if r is None or not held or not lost:
        return "(no energy account recorded)"
    return "closes to %s J, %s of the %s J the machine holds (nearly all the spin's) and %s of the %s J lost" % (
        e(abs(r), 2), e(abs(r) / held, 1), n(held), e(abs(r) / lost, 1), n(lost))


# ---- the output schema (lib/io/schema.c): the name index of docs/output-format.md ---------------

def schema_entries():
    """The entries of lib/io/schema.c in the order of td_out_id (touchdown/result.h), each a dict,
    read through the C preprocessor (the table is written with macros)."""
    import shlex
    import subprocess
    cc = shlex.split(os.environ.get("CC") or "cc")
    out = subprocess.run(cc + ["-E", "-P", "-I" + os.path.join(ROOT, "include"), "-I" + os.path.join(ROOT, "lib"),
                               os.path.join(ROOT, "lib", "io", "schema.c")],
                         check=True, capture_output=True, text=True).stdout
    with open(os.path.join(ROOT, "include", "touchdown", "result.h")) as fh:
        header = fh.read()
    ids = re.findall(r"^\s*(TD_OUT_[A-Z0-9_]+)(?: = 0)?,", header[header.index("typedef enum td_out_id"):header.index("} td_out_id;")], re.M)
    table = {}
    for m in re.finditer(r"(?<![A-Za-z0-9_])\[(TD_OUT_[A-Z0-9_]+)\] = \{", out):
        vals, cur, depth, quoted, i = [], "", 0, False, m.end()
        while quoted or depth > 0 or out[i] != "}":  # split at the commas outside strings and parentheses
            ch = out[i]
            i += 1
            if ch == '"' and out[i - 2] != "\\":
                quoted = not quoted
            elif not quoted and ch in "()":
                depth += 1 if ch == "(" else -1
            elif not quoted and depth == 0 and ch == ",":
                vals.append(cur.strip())
                cur = ""
                continue
            cur += ch
        vals.append(cur.strip())
        vals = [None if v == "((void *)0)" else v[1:-1] if v.startswith('"') else v for v in vals]
        table[m.group(1)] = dict(zip(["name", "parent", "place", "files", "type", "units", "shape", "csv",
                                      "csv_units"], vals))
    return [(i, table[i]) for i in ids if i != "TD_OUT_ID_COUNT"], table


def schema_path(table, ident):
    e = table[ident]
    if ident == "TD_OUT_ROOT":
        return ""
    name = e["name"] or "I"
    return schema_path(table, e["parent"]) + "/" + name


def out_name_index():
    entries, table = schema_entries()
    kinds = {"TD_OUT_GROUP": "group", "TD_OUT_DATASET": "dataset", "TD_OUT_ATTRIBUTE": "attribute",
             "TD_OUT_FIELD": "field", "TD_OUT_CSV_ONLY": "CSV line"}
    files = [("TD_OUT_IN_RUN", "run"), ("TD_OUT_IN_RUN_CSV", "run CSV"), ("TD_OUT_IN_MODAL", "modal"),
             ("TD_OUT_IN_SWEEP", "sweep")]
    rows = ["| id | name | where (group; the object of an attribute) | kind | type | shape | units | files |",
            "|---|---|---|---|---|---|---|---|"]
    for ident, e in entries:
        place = e["place"]
        if place in ("TD_OUT_GROUP", "TD_OUT_DATASET"):
            where = schema_path(table, ident) or "/"
        elif e["parent"] == "TD_OUT_ID_COUNT":
            where = "several"
        else:
            where = schema_path(table, e["parent"]) or "/"
        where = where.replace("/vary/", "/vary/KEY/") if where.startswith("/vary/") else where
        if ident.startswith("TD_OUT_SWEEP_KEY_"):
            where = "/vary/KEY"
        units = e["units"] or ""
        name = e["name"] or ("(root)" if ident == "TD_OUT_ROOT" else "I")
        bits = re.findall(r"TD_OUT_IN_[A-Z_]+", e["files"] or "")
        csv = e["csv"] or e["name"] if "TD_OUT_IN_RUN_CSV" in bits and place in ("TD_OUT_DATASET", "TD_OUT_FIELD") else ""
        rows.append("| `%s` | `%s` | `%s` | %s | %s | %s | %s | %s |" % (
            ident, name, where, kinds[place] + (", CSV `%s`" % csv if csv and place != "TD_OUT_ATTRIBUTE" else ""),
            e["type"].replace("TD_OUT_", "").replace("NO_TYPE", "-").lower(), e["shape"] or "",
            units.replace("|", "\\|"), ", ".join(w for b, w in files if b in bits)))
    return "\n".join(rows) + "\n"


DOC_TYPES = {"f64": "TD_OUT_F64", "int8": "TD_OUT_I8", "int32": "TD_OUT_I32", "int64": "TD_OUT_I64",
             "string": "TD_OUT_TEXT", "compound": "TD_OUT_COMPOUND", "enum (int32)": "TD_OUT_ENUM"}


def doc_table(text, header):
    """The rows (lists of cells) of the markdown table under the line `header`."""
    lines = text[text.index(header + "\n"):].splitlines()[2:]
    rows = []
    for ln in lines:
        if not ln.startswith("|"):
            break
        rows.append([c.strip() for c in re.split(r"(?<!\\)\|", ln.strip()[1:-1])])
    return rows


def check_out_tables():
    """The hand-written tables of the run file in docs/output-format.md against the schema: every
    name exists, with the type, shape and units the schema gives. The list of what differs."""
    entries, table = schema_entries()
    by_path = {}
    for ident, e in entries:
        if e["place"] in ("TD_OUT_GROUP", "TD_OUT_DATASET") and "TD_OUT_IN_RUN" in re.findall(r"TD_OUT_IN_[A-Z_]+", e["files"] or ""):
            by_path[schema_path(table, ident)] = e
    fields = {e["name"]: e for _, e in entries if e["place"] == "TD_OUT_FIELD"}
    roots = {e["name"]: e for _, e in entries
             if e["place"] == "TD_OUT_ATTRIBUTE" and e["parent"] in ("TD_OUT_ROOT", "TD_OUT_ID_COUNT")}
    with open(os.path.join(ROOT, "docs", "output-format.md")) as fh:
        text = fh.read()
    bad = []

    def compare(where, e, shape, typ, units):
        if e is None:
            return bad.append("%s: not in lib/io/schema.c" % where)
        if shape is not None and shape != e["shape"]:
            bad.append("%s: shape %s, the schema says %s" % (where, shape, e["shape"]))
        if DOC_TYPES.get(typ) != e["type"]:
            bad.append("%s: type %s, the schema says %s" % (where, typ, e["type"]))
        if units is not None and units != "see below" and units != e["units"]:
            bad.append("%s: units '%s', the schema says '%s'" % (where, units, e["units"]))

    for row in doc_table(text, "| scale | shape | type | axis of |"):
        for name in re.findall(r"`(/[^`]+)`", row[0]):
            compare(name, by_path.get(name), row[1], row[2], None)
    for row in doc_table(text, "| dataset | shape | type | units | content |"):
        for name in re.findall(r"`(/[^`]+)`", row[0]):
            compare(name, by_path.get(name), row[1], row[2], row[3])
    for row in doc_table(text, "| field | type | units | meaning |"):
        for name in re.findall(r"`([^`]+)`", row[0]):
            compare("/events " + name, fields.get(name), None, row[1], row[2])
    for row in doc_table(text, "| attribute | type | meaning |"):
        for name in re.findall(r"`([a-z_]+)`", row[0]):
            if name not in roots and not name.endswith("_"):
                bad.append("root attribute %s: not in lib/io/schema.c" % name)
    return bad


def fmu_loop():
    """tests/fmu/test_loop.py: the FMU in fmpy's loop with the PD in Python, and with the case's own PD
    inside, against touchdown run of cases/paper-a-digital.cfg."""
    d = res("fmu")["loop"]
    tol = d["tolerance"]
    rows = []
    for name, label in [("native", "`touchdown run`, the PD sampled inside"),
                        ("fmpy_python_pd", "fmpy, the PD in Python (`examples/fmu_pd_loop.py`)"),
                        ("fmpy_inputs_none", "fmpy, `--inputs none` (the case's PD inside the FMU)")]:
        r = d[name]
        rows.append([label, g(r["first_contact_time"], 10), g(r["peak_normal_force"], 8), n(r["events"])])
    rows.append(["tolerance of the test", "%s s" % e(tol["first_contact_time"]), "%s relative" % e(tol["peak_normal_force"]),
                 "exact" if tol["events"] == 0 else "%d" % tol["events"]])
    lg = d["long"]
    fails = d.get("failed_checks", [])
    return ("From %s: `%s` to %s s, %s steps of %s s.\n\n" % (cite("fmu"), d["case"], g(d["end_time"], 2), n(d["steps"]),
                                                             e(d["communication_step"]))
            + table(["run", "first contact s", "peak contact force N", "events"], rows)
            + "\nThe event counts of the loop with the PD in Python and of the built-in run first part at %s s. To %s s "
              "the peak contact force of the loop is %s N, the built-in run's %s N (the test's tolerance: %s "
              "relative).\n" % ("%.4f" % lg["events_part_at"] if lg["events_part_at"] is not None else "no time",
                                g(lg["end_time"], 2), g(lg["fmpy_python_pd_peak"], 8), g(lg["native_peak"], 8),
                                e(lg["tolerance"], 1))
            + ("\n**The test failed when recorded:** %s.\n" % "; ".join(fails) if fails else
               "\nEvery check of the test passed.\n"))


def perf_fmu():
    """bench/fmu.sh: the FMU loop at a 10 kHz communication step against the native run."""
    d = res("fmu")["bench"]
    rows = []
    for name in ["native", "fmu_python_pd", "fmu_inputs_none"]:
        r = d["runs"][name]
        rows.append([r["what"], f(r["cpu_median"], 2), n(r.get("steps", r.get("controller_samples"))),
                     n(r["answers"]["events"])])
    ra = d["ratios"]
    return ("From %s (`%s` to %s s, medians of %d runs each: CPU seconds of the tool's process, or of the "
            "importer's from the FMU's instantiation to its freeing).\n\n" % (cite("fmu"), d["case"], g(d["end_time"], 2),
                                                                              d["repeats"])
            + table(["run", "CPU s", "samples or steps", "events"], rows)
            + "\nFMU loop / native: **%s** with the PD in Python, %s with the case's PD inside the FMU.\n" % (
                g(ra["fmu_python_pd_over_native"], 3), g(ra["fmu_inputs_none_over_native"], 3)))


def report_drop():
    """docs/report.md: the report of cases/drop.cfg as `touchdown report` wrote it."""
    d = res("report")
    return ("From %s:\n\n    %s\n\nwrites drop-report.txt, drop-report.json and drop-report.png; the text "
            "(also printed):\n\n" % (cite("report"), "\n    ".join(d["commands"]))
            + "".join("    " + line if line.strip() else "\n" for line in d["text"].splitlines(True)))


def theory_drop_sweep():
    """docs/theory.md, "Touchdown bearing life": cases/drop-speed-sweep.cfg's points (docs_record.py's
    drop_sweep), the first retainer to fail and the hotter race of each."""
    runs = res("drop_sweep")["runs"]
    rows = []
    for key in sorted(runs, key=float):
        s = runs[key]["summary"]
        drops = [x for x in (s.get("retainer_drops_to_failure") or []) if x is not None]
        rise = [x for x in (s.get("retainer_peak_temperature_rise") or []) if x is not None]
        rows.append([f(float(key), 0), s.get("ending") or "-", f(num(s, "peak_housing_force"), 0),
                     e(min(drops) if drops else None, 3), g(max(rise) if rise else None, 3)])
    total = sum(runs[k]["cpu_time"] for k in runs)
    return (table(["speed (rad/s)", "ending", "peak housing force (N)", "drops to failure", "peak temperature rise (K)"],
                  rows)
            + "\n%d points, %s s of CPU in all (%s).\n" % (len(runs), f(total, 1), cite("drop_sweep")))


# --- issue 31: the cost per step (bench/breakdown.sh, docs/results/breakdown.json) -------------------
BREAKDOWN_CASES = {"drop": "`drop.cfg`", "rub-damped": "`rub-damped.cfg`", "paper-b": "`paper-b.cfg`"}


def breakdown_columns():
    """The record's tools in order (the earlier version first), each with its version."""
    b = res("breakdown")["breakdown"]
    names = {"before": "before: %s", "after": "now: %%s at %s" % res("breakdown")["revision"]}
    return b, [(label, names[label] % b["versions"][label].replace("touchdown ", "")) for label in ("before", "after")
               if label in b["versions"]]


def breakdown_when(b):
    before = b.get("before_measured", {}).get("date")
    return (" The column before (%s) was measured on %s beside the other, alternating run by run." % (
        b["versions"]["before"].replace("touchdown ", ""), before[:10]) if before else "")


def perf_breakdown_cost():
    """The whole runs: CPU time, real-time factor, steps, restarts, CPU per step, before and after."""
    b, cols = breakdown_columns()
    rows = []
    for case, name in BREAKDOWN_CASES.items():
        for label, version in cols:
            r = b["cases"][case][label]
            rows.append([name, version, f(r["cpu_median"], 2), g(r["realtime_factor_cpu"], 3) + "x", n(r["steps"]),
                         n(r["restarts"]), n(r["flight_steps"]), f(r["us_per_step"], 2)])
    return ("From %s: `touchdown run -q --json --hdf5 '' --csv '' cases/CASE.cfg` as shipped, CPU seconds "
            "(user + system) of the tool's process, median of %d runs; real-time factor = simulated "
            "time / CPU time.%s\n\n" % (cite("breakdown"), b["repeats"], breakdown_when(b))
            + table(["case", "version", "CPU s", "real time", "IDA steps", "restarts", "flight steps", "CPU us / step"],
                    rows))


def breakdown_cell(r, key):
    per, prof = r.get("us_per_step_by_category"), r.get("profile")
    if not per:
        return "-"
    return "%s (%s)" % (f(per[key], 2), pct(prof["shares"][key], 0).replace(" %", "%"))


def perf_breakdown():
    """Per case, CPU us per IDA step by category (the profile's share in brackets), before and after."""
    b, cols = breakdown_columns()
    out = []
    for case, name in BREAKDOWN_CASES.items():
        rs = [b["cases"][case][label] for label, _ in cols]
        rows = [[what] + [breakdown_cell(r, key) for r in rs] for key, what in b["categories"]]
        rows.append(["**all** (CPU us per step)"] + ["**%s**" % f(r["us_per_step"], 2) for r in rs])
        rows.append(["of the step's work (%s): failed attempts, estimated" % ", ".join(b["step_parts"])]
                    + [f(r.get("failed_attempts_us_per_step"), 2) for r in rs])
        rows.append(["**floor**: residual + linear solve"] + [f(r.get("floor_us_per_step"), 2) for r in rs])
        rows.append(["step / floor"] + [g(div(r["us_per_step"], r.get("floor_us_per_step")), 2) for r in rs])
        samples = ", ".join("%s %s samples at %s Hz" % (v, n(r["profile"]["samples"]), n(r["profile"]["frequency"]))
                            for (_, v), r in zip(cols, rs) if r.get("profile"))
        out.append("%s (%s):\n\n" % (name, samples or "no profile")
                   + table(["CPU us per IDA step (share of the samples)"] + [v for _, v in cols], rows))
    return ("From %s (`perf record --call-graph dwarf` of one run per case and version, each sample put in "
            "the first category whose functions are on its stack: bench/breakdown.py).\n\n" % cite("breakdown")
            + "\n".join(out))


def perf_breakdown_findings():
    """What the breakdown says, per case: the change in CPU per step, the largest parts, the floor."""
    b, cols = breakdown_columns()
    names = dict((k, w) for k, w in b["categories"])
    out = []
    for case, name in BREAKDOWN_CASES.items():
        rows = b["cases"][case]
        a = rows["after"]
        per = a.get("us_per_step_by_category") or {}
        top = sorted(per, key=lambda k: -per[k])[:3]
        text = "- %s: %s us per step" % (name, f(a["us_per_step"], 2))
        if "before" in rows:
            text += " against %s with %s (%s of it; %s against %s s of CPU for the run)" % (
                f(rows["before"]["us_per_step"], 2), b["versions"]["before"].replace("touchdown ", ""), g(div(a["us_per_step"], rows["before"]["us_per_step"]), 3),
                f(a["cpu_median"], 2), f(rows["before"]["cpu_median"], 2))
        if top:
            text += "; the largest parts: %s" % ", ".join("%s %s us" % (names[k], f(per[k], 2)) for k in top)
            text += "; the floor %s us, the step %s times it" % (f(a["floor_us_per_step"], 2),
                                                                 g(div(a["us_per_step"], a["floor_us_per_step"]), 2))
        out.append(text + ".")
    return "\n".join(out) + "\n"


# --- projective leap: the check against the full integration (bench/leap-check.sh) -----------------
def perf_leap_check():
    """Each answer of the leap run on the stretch against the full integration's ensemble."""
    c = res("leap-check")["check"]
    rows, inside, meet, spread = [], 0, 0, 0
    for name in sorted(c["answers"]):
        a = c["answers"][name]
        full = ("%s to %s (median %s)" % (g(a["full_least"], 5), g(a["full_greatest"], 5), g(a["full_median"], 5))
                if "full_least" in a else g(a["full_run"], 5))
        leap = ("%s to %s" % (g(a["leap_least"], 5), g(a["leap_greatest"], 5)) if a.get("leap_least") is not None
                else "-")
        if "inside" in a:
            spread += 1
            inside += a["inside"]
            meet += a["ranges_meet"]
        rows.append(["`%s`" % name, g(a["leap"], 5), leap, full, ("yes" if a["inside"] else "no") if "inside" in a
                     else "-", ("yes" if a["ranges_meet"] else "no") if "ranges_meet" in a else "-"])
    fr, lp = c["full"], c["leapt"]
    rates = ("from their speeds %s +- %s rad/s^2" % (g(lp["leap_decel_speed"], 4), g(lp["leap_decel_sd"], 2))
             if lp["leaps"] > 1 else "from its burst's speeds %s rad/s^2" % g(lp["leap_decel_speed"], 4))
    text = ("From %s: `%s` (integrated throughout) against `%s` (`%s`), %d members each "
            "(solver.atol within +-1 %%). The leap run leapt %s s of the %s s in %s leap%s; the CPU for the "
            "ensemble %s s against %s s integrated (%s IDA steps against %s for the run itself). "
            "The speed's rate over the leaps from the bursts' net power %s rad/s^2, %s. "
            "Of the %d answers with a spread, the leap run lies inside the full ensemble's range in %d, and the "
            "two ensembles' ranges meet in %d.\n\n"
            % (cite("leap-check"), fr["command"], lp["command"], c["leap"].split("#")[0].strip(), c["members"],
               g(lp["leapt_time"], 4), g(c["end_time"], 3), n(lp["leaps"]), "" if lp["leaps"] == 1 else "s",
               f(lp["cpu"], 1), f(fr["cpu"], 1), n(lp["steps"]), n(fr["steps"]), g(lp["leap_decel_power"], 4), rates,
               spread, inside, meet))
    text += table(["answer", "leap run", "leap ensemble", "full ensemble", "leap run inside", "ranges meet"], rows)
    for factor, o in sorted(c["factors"].items()):
        text += ("\nThe same stretch at `leap.factor = %s` (one run, %s s of CPU, %s s leapt in %s leap%s): final "
                 "speed %s rad/s, contacts %s, drag loss %s J, energy residual %s J.\n"
                 % (factor, f(o["cpu"], 1), g(o["leapt_time"], 4), n(o["leaps"]), "" if o["leaps"] == 1 else "s",
                    g(o["final_speed"], 6), n(o["contacts"]), g(o["answers"].get("energy.drag_loss"), 5),
                    g(o["answers"].get("energy.residual"), 3)))
    return text


REGIONS = {"readme-glance": readme_glance, "readme-realtime": readme_realtime,
           "perf-summary": perf_summary, "perf-paper-settings": perf_paper_settings,
           "perf-paper-findings": perf_paper_findings, "perf-remains": perf_remains,
           "val-paper-cases": val_paper_cases, "val-paper-vs-here": val_paper_vs_here,
           "val-tolerances": val_tolerances, "val-mesh": val_mesh, "val-first-contact": val_first_contact,
           "val-rig-modal": val_rig_modal, "val-beams": val_beams, "val-rotor-models": val_rotor_models,
           "val-annular-rub": val_annular_rub, "val-annular-mount": val_annular_mount, "val-penalty": val_penalty,
           "val-scenarios": val_scenarios, "val-conv-rub-damped": val_conv_rub_damped,
           "val-conv-paper-a": val_conv_paper_a, "val-conv-drop": val_conv_drop, "val-spread": val_spread,
           "out-name-index": out_name_index, "perf-scaling": perf_scaling, "perf-digital": perf_digital,
           "fmu-loop": fmu_loop, "perf-fmu": perf_fmu, "report-drop": report_drop,
           "theory-drop-sweep": theory_drop_sweep,
           # issue 31: the cost per step
           "perf-breakdown-cost": perf_breakdown_cost, "perf-breakdown": perf_breakdown,
           "perf-breakdown-findings": perf_breakdown_findings,
           # projective leap
           "perf-leap-check": perf_leap_check}
SPANS = {"rub-mean-normal": span_rub_mean_normal, "val-first-contact-cell": span_val_first_contact_cell,
         "val-rig-modal-cell": span_val_rig_modal_cell, "rig-mass": span_rig_mass,
         "rig-polar": span_rig_polar, "drop-cpu": span_drop_cpu, "run-up-criticals": span_run_up_criticals,
         "run-up-contact": span_run_up_contact, "run-up-ending": span_run_up_ending,
         "val-beams-cell": span_val_beams_cell, "val-jeffcott-cell": span_val_jeffcott_cell,
         "val-overhung-cell": span_val_overhung_cell, "val-harmonic-cell": span_val_harmonic_cell,
         "val-root-finder-cell": span_val_root_finder_cell, "val-energy-cell": span_val_energy_cell,
         "val-two-cell": span_val_two_cell, "val-drop-rest-cell": span_val_drop_rest_cell,
         "val-annular-cell": span_val_annular_cell, "val-race-energy-cell": span_val_race_energy_cell,
         "val-spin-up-cell": span_val_spin_up_cell, "val-run-up-cell": span_val_run_up_cell,
         "conv-impulses": span_conv_impulses, "drop-24-vs-96": span_drop_24_vs_96,
         "readme-spread-a": span_readme_spread_a, "drop-energy": span_drop_energy,
         "flight-sampled-flight": span_flight_sampled_flight, "flight-sampled-ida": span_flight_sampled_ida,
         # issue 31, tolerances
         "val-tolerance-cell": span_val_tolerance_cell,
         # issue 31, trust: the validation summary's measured errors, from the tests' messages
         "val-mount-cell": span_val_mount_cell, "val-penalty-cell": span_val_penalty_cell,
         "val-race-spin-cell": span_val_race_spin_cell, "val-rolling-cell": span_val_rolling_cell,
         "val-whip-cell": span_val_whip_cell, "val-coast-cell": span_val_coast_cell,
         "val-levitation-cell": span_val_levitation_cell, "val-tight-cell": span_val_tight_cell,
         "val-releases-cell": span_val_releases_cell, "val-grazing-cell": span_val_grazing_cell,
         "val-drift-cell": span_val_drift_cell, "val-drift-onsets": span_val_drift_onsets,
         "val-jeffcott-flight-cell": span_val_jeffcott_flight_cell, "val-annular-order": span_val_annular_order}


# --- the case keys (docs/case-format.md) ------------------------------------------------------------
# The sections of docs/results/keys.json (touchdown info --keys), each a table of its own region
# "keys-SECTION"; a section the tool names that is not here fails the rendering.
KEY_SECTIONS = ["top", "shaft", "discs", "ambs", "controllers", "recovery", "speed", "bearings", "retainers", "retainer-parts", "unbalances",
                "schedule", "gravity", "reduction", "contact", "solver", "output", "modal", "sweep", "limits",
                "housing",
                # projective leap
                "leap"]


def cell(text):
    """A table cell: '-' when empty, '|' escaped."""
    return text.replace("|", "\\|") if text else "-"


def key_table(section):
    keys = res("keys")["keys"]
    unknown = sorted({k["section"] for k in keys} - set(KEY_SECTIONS))
    if unknown:
        sys.exit("docs_render: docs/results/keys.json has sections with no table: %s" % ", ".join(unknown))
    rows = [["`%s`" % k["key"], cell(k["type"]), cell(k["range"]), cell(k["unit"]), cell(k["default"]), cell(k["doc"])]
            for k in keys if k["section"] == section]
    return table(["key", "type", "range", "unit", "default", "meaning"], rows)


def key_region(section):
    return lambda: key_table(section)


REGIONS.update({"keys-" + s: key_region(s) for s in KEY_SECTIONS})
# docs/recovery-study.md's regions, built by its study script from docs/results/recovery.json
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import recovery_study  # noqa: E402

REGIONS.update(recovery_study.REGIONS)
import shock_study  # noqa: E402
REGIONS.update(shock_study.REGIONS)
SPANS.update(shock_study.SPANS)
import sweep_study_page  # noqa: E402  (docs/sweep-study.md, from docs/results/sweep_study.json)
REGIONS.update(sweep_study_page.REGIONS)
SPANS.update(sweep_study_page.SPANS)


def render(path, text):
    docs_prefix = "" if path.startswith("docs/") else "docs/"
    used = []

    def block(m):
        name = m.group(2)
        if name not in REGIONS:
            sys.exit("docs_render: %s: unknown generated region '%s'" % (path, name))
        used.append(name)
        return m.group(1) + REGIONS[name]().replace("{DOCS}", docs_prefix) + m.group(4)

    def span(m):
        name = m.group(2)
        if name not in SPANS:
            sys.exit("docs_render: %s: unknown generated span '%s'" % (path, name))
        used.append(name)
        return m.group(1) + SPANS[name]() + m.group(4)

    return SPAN.sub(span, BLOCK.sub(block, text)), used


def main():
    check = "--check" in sys.argv[1:]
    changed, used = [], []
    for path in FILES:
        with open(os.path.join(ROOT, path)) as fh:
            old = fh.read()
        new, names = render(path, old)
        used += names
        if new != old:
            changed.append(path)
            if check:
                sys.stdout.writelines(difflib.unified_diff(old.splitlines(True), new.splitlines(True),
                                                           "a/" + path, "b/" + path, n=0))
            else:
                with open(os.path.join(ROOT, path), "w") as fh:
                    fh.write(new)
    wrong = check_out_tables()
    if wrong:
        print("docs_render: docs/output-format.md disagrees with the output schema (lib/io/schema.c):\n  " +
              "\n  ".join(wrong))
        return 1
    missing = [m for m in sorted(set(REGIONS) | set(SPANS)) if m not in used]
    if missing:
        print("docs_render: regions with no marker in README.md or docs/: %s" % ", ".join(missing))
        return 1
    if check:
        if changed:
            print("docs_render: %s differ from what docs/results/ gives (a number edited by hand, or "
                  "results not rendered): run scripts/make-docs.sh --render" % ", ".join(changed))
            return 1
        print("docs_render: %d generated regions and spans match docs/results/" % len(used))
        return 0
    print("docs_render: %s" % ("rewrote " + ", ".join(changed) if changed else "nothing changed"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
