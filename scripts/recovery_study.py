#!/usr/bin/python3
"""The recovery study of docs/recovery-study.md: cases/recovery.cfg with and without its supervisor,
why the recovery law is a synchronous damper, how robust it is, and where it succeeds.

    recovery_study.py --law SPEED [PHASE_DEG]   print the recovery law's tf block at SPEED rad/s
                                                (cases/recovery.cfg's pd-sync is --law 320)
    recovery_study.py BUILD_DIR                 rerun the study: docs/results/recovery.json and
                                                docs/figures/recovery-*.png (about 12 min of CPU,
                                                two runs at a time), then render the docs

scripts/make-docs.sh --full --only recovery does the same (docs_record.py's source "recovery");
docs_render.py renders the regions of docs/recovery-study.md from the record with REGIONS below.
Every number the study quotes is in the record, with the command that gave it.
Only Debian's python3 modules are used (gnuplot draws the figures).
"""
import concurrent.futures
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = "cases/recovery.cfg"
NO_FILES = ["--json", "-q", "--hdf5", "", "--csv", ""]

# The nominal law (cases/recovery.cfg's "pd"): the rig's PD with a 2 kHz derivative filter.
KP, KD, DERIVATIVE_FILTER = 1.0e4, 40.0, 2000.0
# The AMBs' amplifier: 100 Hz bandwidth, tau = 1 / (2 pi 100) s (cases/rig.cfg).
TAU = 1.0 / (2.0 * math.pi * 100.0)
# The synchronous damper added in parallel: damping ratio of its poles and its gain at the speed.
ZETA = 0.02
GAIN_AT_SPEED = 5.0e4  # A/m, |R(j W)| = g / (2 zeta W)
CLEARANCE = 0.75e-3    # m, the rig's retainers (cases/rig.cfg)


def damper_phase(speed):
    """The phase (deg) that puts the damper's force against the whirl velocity at the speed: a force
    -c v needs the current to lead the displacement error by 90 deg at the AMB, and the amplifier
    lags it by atan(W tau); R(jW) = |R| e^{-j phi}, so phi = 270 deg - atan(W tau)."""
    return 270.0 - math.degrees(math.atan(speed * TAU))


def polymul(a, b):
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def polyadd(a, b):
    n = max(len(a), len(b))
    a = [0.0] * (n - len(a)) + list(a)
    b = [0.0] * (n - len(b)) + list(b)
    return [x + y for x, y in zip(a, b)]


def law(speed, phase=None, gain=GAIN_AT_SPEED, zeta=ZETA, notch=0.0):
    """num, den (descending powers of s) of PD + R(s), R = g (s cos phi + W sin phi) /
    (s^2 + 2 zeta W s + W^2) with g = 2 zeta W gain (zeta = 0: g = gain, the undamped internal
    model whose gain at W is infinite). notch > 0: the PD through a notch at W of that pole damping
    first (the PD blind to the synchronous motion)."""
    phase = damper_phase(speed) if phase is None else phase
    wf = 2.0 * math.pi * DERIVATIVE_FILTER
    ph = math.radians(phase)
    g = gain * 2.0 * zeta * speed if zeta > 0 else gain
    pd_num, pd_den = [KP / wf + KD, KP], [1.0 / wf, 1.0]
    if notch > 0:
        pd_num = polymul(pd_num, [1.0, 0.0, speed * speed])
        pd_den = polymul(pd_den, [1.0, 2.0 * notch * speed, speed * speed])
    r_num = [g * math.cos(ph), g * speed * math.sin(ph)]
    r_den = [1.0, 2.0 * zeta * speed, speed * speed]
    if gain == 0:
        return pd_num, pd_den
    return polyadd(polymul(pd_num, r_den), polymul(r_num, pd_den)), polymul(pd_den, r_den)


def tf_block(speed, **kw):
    num, den = law(speed, **kw)
    fmt = lambda a: "[" + ", ".join(repr(float(x)) for x in a) + "]"
    return "({ tf = { num = %s; den = %s; }; })" % (fmt(num), fmt(den))


def touchdown_json(tool, args):
    """The JSON that `touchdown ARGS CASE` prints (run from the repository's root); a run that prints
    none stops the study with its message."""
    args = args + [CASE]
    proc = subprocess.run([tool] + args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    try:
        return json.loads(proc.stdout)
    except ValueError:
        sys.exit("recovery_study: touchdown %s printed no JSON: %s" % (" ".join(args), proc.stderr[:300]))


def answered(summary, command):
    """The summary of COMMAND, or the study stopped: a run that failed has no answers. Its partial
    files would be read as a steady state and its summary classified (a failed run is not free, so
    it would read as "stays in contact"; with no contacts counted, as "no free orbit")."""
    if summary.get("status") != "success":
        sys.exit("recovery_study: %s: status %s: %s; the record is not written" % (
            command, summary.get("status"), (summary.get("message") or "")[:400]))
    return summary


def run(tool, sets, files=None):
    """touchdown run --json of the case with --set SETS (a list of (key, value)); files: an output
    prefix for the CSV (no HDF5), else none. The command as written and the summary."""
    args = ["run", "--json", "-q"]
    args += ["--hdf5", "", "-o", files] if files else NO_FILES[2:]
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    summary = touchdown_json(tool, args)
    # the output prefix is a temporary directory's: shown as its base name alone
    shown = [os.path.basename(a) if files and a == files else ("'%s'" % a if (" " in a or not a) else a)
             for a in args + [CASE]]
    command = "touchdown " + " ".join(shown)
    answered(summary, command)
    for key in ("hdf5_path", "csv_path", "events_path"):
        if summary.get(key):
            summary[key] = os.path.basename(summary[key])
    return {"command": command, "summary": summary}


def modal(tool, sets):
    """touchdown modal --json of the case with --set SETS: the contact-free loop's stability and, per
    axis, its sampled sensitivity peak and zone (docs/theory.md, "Sensitivity")."""
    args = ["modal", "--json"]
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    return touchdown_json(tool, args)


def point_sets(speed, u2, law_index=1, **kw):
    """The --set list of the case at SPEED with the final unbalance U2 and its recovery law (or,
    law_index 0, the law driving the AMBs directly, without the supervisor)."""
    sets = [("speed", repr(float(speed))), ("unbalances[0].magnitude", repr(u2)),
            ("schedule[1].magnitude", repr(u2))]
    if law_index == 0:
        sets += [("recovery.enabled", "false")]
    return sets + [("controllers[%d].law" % law_index, tf_block(speed, **kw))]


def free(summary):
    return summary.get("ending") in ("recovered", "free (no contact)")


def parallel(jobs):
    """Run the (key, function, args) jobs two at a time; {key: result}."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {key: pool.submit(fn, *args) for key, fn, args in jobs}
        return {key: f.result() for key, f in futures.items()}


def tail_means(path, t0):
    """Means over t >= t0 of the CSV's NDE retainer radius and normal force, of the radius at the
    NDE AMB's sensor node 3, and of the AMB forces' magnitudes."""
    sums, n = {}, 0
    with open(path) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        head = [h.split(" ")[0] for h in next(rows)]
        col = {h: i for i, h in enumerate(head)}
        for row in rows:
            if float(row[0]) < t0:
                continue
            v = lambda k: float(row[col[k]])
            vals = {"r_ret0": v("r_ret0"), "N_ret0": v("N_ret0"), "r_amb0": math.hypot(v("x_n3"), v("y_n3")),
                    "F_amb0": math.hypot(v("Fx_amb0"), v("Fy_amb0")), "F_amb1": math.hypot(v("Fx_amb1"), v("Fy_amb1"))}
            for k, x in vals.items():
                sums[k] = sums.get(k, 0.0) + x
            n += 1
    return {k: s / n for k, s in sums.items()}


# --- the study (record) -----------------------------------------------------------------------------
SPEEDS = [240.0, 280.0, 320.0, 360.0, 400.0]           # rad/s, the map's speeds
FINAL_U = [0.005, 0.0075, 0.01, 0.0125]                # kg m, the unbalance after the step back
ROBUST_PHASES = [213.0, 228.0, 243.0, 258.0, 273.0]    # deg, around damper_phase(320) = 243
ROBUST_GAINS = [2.0e4, 3.0e4, 5.0e4, 1.0e5]            # A/m, |R(jW)|
TAIL = 3.5                                             # s, the steady state's window: 3.5 s to the end


def exists(tool, speed, u2):
    """Whether the rig with its continuous shorthand PD has a contact-free steady orbit at the final
    unbalance (cases/rub-damped.cfg from that orbit, start = "orbit" found and no contact in 0.3 s)."""
    args = ["run"] + NO_FILES + ["--set", "speed=%r" % speed]
    for k in ("unbalances[0].magnitude", "schedule[0].magnitude", "schedule[1].magnitude"):
        args += ["--set", "%s=%r" % (k, u2)]
    args += ["--set", "end_time=0.3", "cases/rub-damped.cfg"]
    proc = subprocess.run([tool] + args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)
    command = "touchdown " + " ".join(a or "''" for a in args)
    s = answered(json.loads(proc.stdout), command)
    return {"command": command, "start": s.get("start"), "start_reason": s.get("start_reason"),
            "exists": s.get("start") == "orbit" and s.get("contacts") == 0}


def run_with_tail(tool, sets, tmp, name):
    rec = run(tool, sets, files=os.path.join(tmp, name))
    rec["tail"] = tail_means(os.path.join(tmp, name + ".csv"), TAIL)
    rec["switches"] = switch_events(os.path.join(tmp, name + ".events.csv"))
    return rec


def switch_events(path):
    """The controller_switch events of an events CSV: [time, controller switched to, sensed radius]."""
    out = []
    with open(path) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        head = [h.split(" ")[0] for h in next(rows)]
        if "controller" not in head:
            return out
        for row in rows:
            if row[head.index("kind_name")] == "controller_switch":
                out.append([float(row[0]), int(row[head.index("controller")]), float(row[head.index("r_sensed")])])
    return out


def in_contact_at(path, times):
    """For each time, whether any retainer is in contact at the CSV's first sample at or after it."""
    out = [None] * len(times)
    with open(path) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        head = [h.split(" ")[0] for h in next(rows)]
        flags = [i for i, h in enumerate(head) if h.startswith("contact_ret")]
        for row in rows:
            t = float(row[0])
            for j, tj in enumerate(times):
                if out[j] is None and t >= tj:
                    out[j] = any(float(row[i]) != 0.0 for i in flags)
            if all(x is not None for x in out):
                break
    return out


def run_with_returns(tool, sets, tmp, name):
    """A map run with the supervisor: its summary, its switches and, for each switch back to pd,
    whether a retainer was still in contact then (the files are read and removed at once)."""
    rec = run(tool, sets, files=os.path.join(tmp, name))
    rec["switches"] = switch_events(os.path.join(tmp, name + ".events.csv"))
    back = [sw[0] for sw in rec["switches"] if sw[1] == 0]
    rec["returns_in_contact"] = in_contact_at(os.path.join(tmp, name + ".csv"), back)
    for ext in (".csv", ".events.csv"):
        os.remove(os.path.join(tmp, name + ext))
    return rec


def returned_while_rubbing(on):
    """Whether the supervisor's last switch back to pd came while a retainer was still in contact."""
    flags = on.get("returns_in_contact") or []
    return bool(flags) and flags[-1] is True


def outcome(off, on, exist):
    if not exist["exists"]:
        return "no free orbit"
    if free(off["summary"]):
        return "recovers by itself"
    if free(on["summary"]):
        return "recovered with the supervisor"
    return "stays in contact, back to pd while rubbing" if returned_while_rubbing(on) else "stays in contact"


def record(tool, stamp):
    """Every run of the study; returns the record (docs/results/recovery.json)."""
    data = stamp(tool, "recovery", "scripts/recovery_study.py: touchdown run --json of cases/recovery.cfg with "
                 "--set variants (laws written by recovery_study.py --law), two at a time")
    data["law"] = {"kp": KP, "kd": KD, "derivative_filter": DERIVATIVE_FILTER, "tau": TAU, "zeta": ZETA,
                   "gain_at_speed": GAIN_AT_SPEED, "phase_320": damper_phase(320.0), "clearance": CLEARANCE,
                   "tail_from": TAIL}
    with tempfile.TemporaryDirectory() as tmp:
        jobs = [("case-off", run_with_tail, (tool, [("recovery.enabled", "false")], tmp, "off")),
                ("case-on", run_with_tail, (tool, [], tmp, "on")),
                ("pd-notch", run_with_tail, (tool, point_sets(320.0, 0.01, 0, gain=0.0, notch=0.1), tmp, "notch")),
                ("damper-direct", run_with_tail, (tool, point_sets(320.0, 0.01, 0), tmp, "direct"))]
        for g in (1.0e5, 1.0e6):
            jobs.append(("undamped-%g" % g, run_with_tail,
                         (tool, point_sets(320.0, 0.01, 0, zeta=0.0, gain=g), tmp, "undamped-%g" % g)))
        data["runs"] = parallel(jobs)
        figure(tmp, data["runs"])
    data["phase"] = parallel([("%g" % p, run, (tool, point_sets(320.0, 0.01, 0, phase=p) + [("end_time", "1e-4")]))
                              for p in range(0, 360, 15)])
    data["loop"] = parallel([("pd", modal, (tool, []))] +
                            [("%g" % p, modal, (tool, point_sets(320.0, 0.01, 0, phase=p))) for p in range(0, 360, 15)])
    data["robust"] = parallel([("%g %g" % (p, g), run, (tool, point_sets(320.0, 0.01, 1, phase=p, gain=g)))
                               for p in ROBUST_PHASES for g in ROBUST_GAINS])
    with tempfile.TemporaryDirectory() as tmp:
        jobs = []
        for w in SPEEDS:
            for u in FINAL_U:
                key = "%g %g" % (w, u)
                jobs += [(key + " exists", exists, (tool, w, u)),
                         (key + " off", run, (tool, point_sets(w, u) + [("recovery.enabled", "false")])),
                         (key + " on", run_with_returns, (tool, point_sets(w, u), tmp, "map-%g-%g" % (w, u)))]
        done = parallel(jobs)
    data["map"] = {}
    for w in SPEEDS:
        for u in FINAL_U:
            key = "%g %g" % (w, u)
            point = {"exists": done[key + " exists"], "off": done[key + " off"], "on": done[key + " on"]}
            point["outcome"] = outcome(point["off"], point["on"], point["exists"])
            data["map"][key] = point
    return data


def figure(tmp, runs):
    """docs/figures/recovery-radius.png: the NDE retainer's radius over the run without and with the
    supervisor, and the AMB forces (from the runs' CSV)."""
    cols = ["t", "r_ret0", "Fx_amb0", "Fy_amb0"]
    for name in ("off", "on"):
        with open(os.path.join(tmp, name + ".csv")) as f, open(os.path.join(tmp, name + ".dat"), "w") as out:
            rows = csv.reader(l for l in f if not l.startswith("#"))
            head = [h.split(" ")[0] for h in next(rows)]
            idx = [head.index(c) for c in cols]
            for i, row in enumerate(rows):
                if i % 5 == 0:
                    v = [float(row[j]) for j in idx]
                    out.write("%.6g %.6g %.6g\n" % (v[0], v[1] * 1e3, math.hypot(v[2], v[3])))
    switches = [(t, "") for t, _, _ in runs["case-on"]["switches"]]
    script = """set terminal pngcairo size 900,640 font ",10"
set output "%(out)s"
set multiplot layout 2,1
set grid
set ylabel "NDE retainer radius [mm]"
set key top right
set arrow from graph 0, first %(c)g to graph 1, first %(c)g nohead dt 2
set label "clearance" at graph 0.01, first %(c)g offset 0,0.6
%(arrows)s
plot "%(off)s" using 1:2 with lines lw 1 title "recovery.enabled = false", \\
     "%(on)s" using 1:2 with lines lw 1 title "recovery.enabled = true"
unset arrow
unset label
set xlabel "t [s]"
set ylabel "|F| at the NDE AMB [N]"
plot "%(off)s" using 1:3 with lines lw 1 title "enabled = false", "%(on)s" using 1:3 with lines lw 1 title "enabled = true"
unset multiplot
""" % {"out": os.path.join(ROOT, "docs", "figures", "recovery-radius.png"), "c": CLEARANCE * 1e3,
       "off": os.path.join(tmp, "off.dat"), "on": os.path.join(tmp, "on.dat"),
       "arrows": "\n".join('set arrow from first %g, graph 0 to first %g, graph 1 nohead lc "gray"' % (t, t)
                           for t, _ in switches if t is not None)}
    subprocess.run(["gnuplot"], input=script, universal_newlines=True, check=True)


# --- the docs (render) ------------------------------------------------------------------------------
def _res():
    with open(os.path.join(ROOT, "docs", "results", "recovery.json")) as f:
        return json.load(f)


def _g(x, digits=3):
    return "-" if x is None else "%.*g" % (digits, x)


def _table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows]) + "\n"


def _ending(s):
    return s.get("ending") or s.get("status")


def region_case():
    r = _res()
    rows = []
    for key, label in (("case-off", "`recovery.enabled = false`"), ("case-on", "`recovery.enabled = true`")):
        run_ = r["runs"][key]
        s, t = run_["summary"], run_["tail"]
        sw = "; ".join("%s s to %s (r = %s mm)" % (_g(tt, 4), ("pd-sync" if c == 1 else "pd"), _g(rr * 1e3, 3))
                       for tt, c, rr in run_["switches"]) or "none"
        rows.append([label, _ending(s), _g(s.get("last_contact_time"), 4), _g(s.get("contact_time"), 3), sw,
                     _g(s.get("time_on_recovery"), 4), _g(t["r_ret0"] * 1e3, 3), _g(t["r_ret0"] / CLEARANCE, 2),
                     _g(t["r_amb0"] / CLEARANCE, 2), _g(t["N_ret0"], 4), "%s / %s" % (_g(t["F_amb0"], 4), _g(t["F_amb1"], 4)),
                     _g(s.get("peak_amb_load"), 3)])
    return _table(["run", "ending", "last contact [s]", "time in contact [s]", "switches", "on recovery [s]",
                   "NDE retainer radius [mm]", "/ c", "NDE sensor radius / c", "NDE normal force [N]",
                   "AMB forces [N]", "peak AMB load"], rows) + "\n" + \
        "The radii and forces are means over t >= %g s, from the runs' CSV files. Commands: `%s` and `%s`.\n" % (
            r["law"]["tail_from"], r["runs"]["case-off"]["command"], r["runs"]["case-on"]["command"])


def region_mechanism():
    r = _res()
    rows = []
    for key, label in (("case-off", "pd (the nominal law)"),
                       ("pd-notch", "pd through a notch at W (no synchronous force from the law)"),
                       ("undamped-100000", "pd + undamped resonant, g = 1e5 A/(m s), phi = %s deg" % _g(r["law"]["phase_320"], 3)),
                       ("undamped-1e+06", "pd + undamped resonant, g = 1e6 A/(m s), phi = %s deg" % _g(r["law"]["phase_320"], 3)),
                       ("damper-direct", "pd-sync (pd + synchronous damper) from t = 0")):
        run_ = r["runs"][key]
        s, t = run_["summary"], run_["tail"]
        rows.append([label, _ending(s), _g(s.get("last_contact_time"), 4), _g(t["N_ret0"], 4),
                     "%s / %s" % (_g(t["F_amb0"], 4), _g(t["F_amb1"], 4))])
    return _table(["law driving the AMBs (no supervisor)", "ending", "last contact [s]",
                   "NDE normal force [N], mean from %g s" % r["law"]["tail_from"], "AMB forces [N]"], rows)


def region_phase():
    r = _res()
    stable = [float(p) for p, run_ in r["phase"].items() if run_["summary"].get("stability") == "stable"]
    rows = []
    for p, run_ in sorted(r["phase"].items(), key=lambda kv: float(kv[0])):
        loop = r["loop"][p]
        rows.append([p, run_["summary"].get("stability"), _g(run_["summary"].get("max_real_part"), 3)] +
                    _loop_cells(loop))
    nominal = r["loop"]["pd"]
    return _table(["phi [deg]", "closed loop (pd-sync driving, contact-free)", "largest real part [1/s]",
                   "peak abs S (worst axis)", "at [Hz]", "ISO 14839-3 zone"], rows) + \
        "\nStable for phi in %s deg (steps of 15 deg); the damper's phase %s deg. The nominal pd alone: " \
        "peak abs S %s at %s Hz, zone %s.\n" % (
            ", ".join(_g(p, 3) for p in sorted(stable)), _g(r["law"]["phase_320"], 4),
            *_loop_cells(nominal))


def _loop_cells(loop):
    """The worst axis's sampled sensitivity peak, its frequency and the zone (all "-" when the loop
    is unstable: a sensitivity of an unstable loop is no number to lead with)."""
    peaks = loop.get("sensitivity_peak") or []
    if not loop.get("stable") or not peaks or any(x is None for x in peaks):
        return ["-", "-", "-"]
    i = max(range(len(peaks)), key=lambda j: peaks[j])
    return [_g(peaks[i], 4), _g(loop["sensitivity_peak_frequency"][i], 4), loop.get("sensitivity_zone") or "-"]


def region_robust():
    r = _res()
    rows = []
    for p in ROBUST_PHASES:
        row = ["%g" % p]
        for g in ROBUST_GAINS:
            s = r["robust"]["%g %g" % (p, g)]["summary"]
            row.append(("recovered, back to pd at %s s" % _g(s.get("last_return_time"), 4)) if free(s) else _ending(s))
        rows.append(row)
    return _table(["phi [deg] \\ abs R(jW) [A/m]"] + ["%g" % g for g in ROBUST_GAINS], rows)


def region_map():
    r = _res()
    rows = []
    short = {"no free orbit": "no free orbit", "recovers by itself": "by itself",
             "recovered with the supervisor": "**with the supervisor**", "stays in contact": "stays in contact",
             "stays in contact, back to pd while rubbing": "stays in contact, back to pd while rubbing"}
    for w in SPEEDS:
        row = ["%g" % w]
        for u in FINAL_U:
            p = r["map"]["%g %g" % (w, u)]
            cell = short[p["outcome"]] + ", U W^2 = %s N" % _g(u * w * w, 4)
            s = p["on"]["summary"]
            if p["outcome"] != "no free orbit":
                back = s.get("last_return_time")
                cell += "; %s switch%s, %s" % (s.get("controller_switches"),
                                               "" if s.get("controller_switches") == 1 else "es",
                                               "never back to pd" if back is None else
                                               "last back to pd %s s" % _g(back, 4))
            row.append(cell)
        rows.append(row)
    counts = {}
    for p in r["map"].values():
        counts[p["outcome"]] = counts.get(p["outcome"], 0) + 1
    return _table(["speed [rad/s] \\ final unbalance [kg m]"] + ["%g" % u for u in FINAL_U], rows) + \
        "\n" + "; ".join("%s: %d" % (k, v) for k, v in sorted(counts.items())) + " (of %d points).\n" % len(r["map"])


def span_law_case():
    return tf_block(320.0)


REGIONS = {"recovery-case": region_case, "recovery-mechanism": region_mechanism, "recovery-phase": region_phase,
           "recovery-robust": region_robust, "recovery-map": region_map}


def main(argv):
    if len(argv) >= 2 and argv[0] == "--law":
        speed = float(argv[1])
        print(tf_block(speed, phase=float(argv[2]) if len(argv) > 2 else None))
        return 0
    if len(argv) != 1:
        sys.exit(__doc__)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import docs_record  # noqa: E402  (its stamp and save)
    tool = os.path.join(os.path.abspath(argv[0]), "touchdown")
    docs_record.save("recovery", record(tool, docs_record.stamp))
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "docs_render.py")]).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
