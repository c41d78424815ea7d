#!/usr/bin/python3
"""The sweep study of docs/sweep-study.md: cases/study-a.cfg over speed and unbalance, and the drop of
cases/study-drop.cfg over the drop speed and the races' drag torque, with the single runs the page
reads beside the sweeps.

    sweep_study.py BUILD_DIR     rerun the study: docs/results/sweep_study.json and the study figures
                                 docs/figures/study-*.png (the sweeps one at a time, the single runs two
                                 at a time; the CPU and wall time in the record), then render the docs

scripts/make-docs.sh --full --only sweep_study does the same (docs_record.py's source "sweep_study");
docs_render.py renders the regions and spans of docs/sweep-study.md from the record with REGIONS and
SPANS below. Every number the page quotes is in the record, with the command that gave it; where the
page draws a conclusion from them, the sentence is written here from the numbers (or the rendering
stops, saying which sentence the numbers no longer support). The figures are the sweeps' own plots
(`touchdown plot` of the tables recorded here), so they show the recorded rows; scripts/make-figures.sh
runs the same commands and makes the same figures. Only Debian's python3 modules are used.
"""
import concurrent.futures
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STUDY_A, STUDY_DROP, DROP = "cases/study-a.cfg", "cases/study-drop.cfg", "cases/drop.cfg"
NO_FILES = ["--hdf5", "", "--csv", ""]
DRAG = ("retainers[0].race.drag_torque", "retainers[1].race.drag_torque")
FRICTION = ("retainers[0].friction", "retainers[1].friction")
TIGHT = "{ rtol = 1e-8; atol = 1e-11; }"
# the sweeps, exactly as the page gives them (run from a scratch directory, the case from the root)
SWEEP_A = ["sweep", "-j", "1", "--vary", "speed=50:250:41", "--vary",
           "unbalances[0].magnitude=0.005,0.01,0.015,0.02,0.05,0.1", "-o", "study", STUDY_A]
SWEEP_DROP = ["sweep", "-j", "2", "-o", "study-drop", STUDY_DROP]
PHASES = [0.0, math.pi / 3, 2 * math.pi / 3, math.pi, 4 * math.pi / 3, 5 * math.pi / 3]
PHASE_DRAGS = ["0.02", "3", "5", "10"]
SWEEP_PHASE = ["sweep", "-j", "2", "--vary", "speed=190", "--vary", DRAG[0] + "=" + ",".join(PHASE_DRAGS),
               "--with", DRAG[1] + "=" + ",".join(PHASE_DRAGS),
               "--vary", "unbalances[0].phase=" + ",".join(repr(p) for p in PHASES), "-o", "phase", STUDY_DROP]
PLOTS = [["plot", "-q", "study.h5"], ["plot", "-q", "-d", "study-log", "--log-y", "study.h5"],
         ["plot", "-q", "-d", "study-drop", "--log-x", "--x", DRAG[0], "--y", "speed", "study-drop.h5"],
         ["plot", "-q", "-d", "study-drop", "--log-x", "--x", DRAG[0], "--quantity", "ending_whirl_frequency",
          "study-drop.h5"]]
FIGURES = [("study-log/regime-map.png", "study-a-regime-map.png"), ("study-plots/bifurcation.png", "study-a-bifurcation.png"),
           ("study-plots/sweep-peak_housing_force.png", "study-a-peak-housing-force.png"),
           ("study-drop/regime-map.png", "study-drop-regime-map.png"),
           ("study-drop/sweep-peak_housing_force.png", "study-drop-peak-housing-force.png"),
           ("study-drop/sweep-ending_whirl_frequency.png", "study-drop-whirl-frequency.png")]
# the drop points checked alone, to 1.6 s and at ten times tighter tolerances (speed, drag)
CONVERGE = [(100, "0.02"), (160, "5"), (190, "0.02"), (190, "10"), (250, "0.5"), (250, "10")]
CONVERGE_TIGHT_ONLY = [(130, "5"), (190, "3"), (190, "5"), (250, "0.02"), (250, "3"), (250, "5")]
# the bounces sampled at 20 kHz
BOUNCES = [(190, "0.02"), (190, "1"), (130, "1")]
# "why these two keys": drop.cfg to 0.6 s, (speed, friction, drag)
KEYS_RUNS = ([(190, mu, "0.02") for mu in ("0.1", "0.3")] +
             [(190, mu, t) for t in ("0.2", "0.5") for mu in ("0.1", "0.2", "0.3")] +
             [(190, mu, t) for t in ("5", "10") for mu in ("0.05", "0.1", "0.2", "0.3")] +
             [(80, "0.1", "0.02"), (80, "0.2", "5"), (120, "0.1", "0.02")])
# study-a's solver check: (speed, unbalance)
A_TIGHT = [(150, "0.05"), (250, "0.1"), (210, "0.01")]


def quote(a):
    if a == "":
        return "''"
    return "'%s'" % a if re.search(r"[ ;{}\[\]\"]", a) else a


def tool_run(tool, args, cwd=ROOT):
    """Run the tool under /usr/bin/time: (stdout, stderr, return code, wall s, CPU s = user + sys)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as tf:
        start = time.monotonic()
        proc = subprocess.run(["/usr/bin/time", "-f", "%U %S", "-o", tf.name, tool] + args, cwd=cwd,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
        wall = time.monotonic() - start
        user, sys_ = (float(x) for x in tf.read().split()[-2:])
    return proc.stdout, proc.stderr, proc.returncode, wall, user + sys_


def run(tool, case, sets, csv_path=None):
    """touchdown run --json of CASE with --set SETS [(key, value)]; a CSV when csv_path is given."""
    args = ["run", "--json", "-q", "--hdf5", ""] + (["-o", csv_path] if csv_path else ["--csv", ""])
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    args.append(case)
    out, err, rc, wall, cpu = tool_run(tool, args)
    try:
        summary = json.loads(out)
    except ValueError:
        sys.exit("sweep_study: touchdown %s printed no JSON: %s" % (" ".join(args), err[:300]))
    for key in ("hdf5_path", "csv_path", "events_path"):
        if summary.get(key):
            summary[key] = os.path.basename(summary[key])
    words = [os.path.basename(a) + ".csv" if csv_path and a == csv_path else quote(a) for a in args]
    print("  %-90s %6.1f s wall %6.1f s CPU" % (" ".join(words[5:])[:90], wall, cpu), flush=True)
    return {"command": "touchdown " + " ".join(words), "cpu_time": round(cpu, 3), "wall_time": round(wall, 3),
            "summary": summary}


def drop_sets(speed, drag, more=()):
    return [("speed", "%g" % speed), (DRAG[0], drag), (DRAG[1], drag)] + list(more)


def sweep(tool, args, tmp):
    """A touchdown sweep in TMP: its command, summary line, CPU and wall time, and its table."""
    case = args[-1]
    out, err, rc, wall, cpu = tool_run(tool, args[:-1] + [os.path.join(ROOT, case)], cwd=tmp)
    if rc != 0:
        sys.exit("sweep_study: touchdown %s: exit %d: %s" % (" ".join(args), rc, err[-500:]))
    line = [l for l in (out + err).splitlines() if l.startswith("sweep:")]
    name = args[args.index("-o") + 1]
    with open(os.path.join(tmp, name + ".csv")) as f:
        rows = list(csv.reader(l for l in f if not l.startswith("#")))
    print("  %-90s %6.1f s wall %6.1f s CPU" % (" ".join(args)[:90], wall, cpu), flush=True)
    return {"command": "touchdown " + " ".join(quote(a) for a in args), "summary_line": line[-1] if line else None,
            "cpu_time": round(cpu, 3), "wall_time": round(wall, 3), "columns": rows[0], "rows": rows[1:]}


def read_csv(path):
    with open(path) as f:
        rows = csv.reader(l for l in f if not l.startswith("#"))
        head = [h.split(" ")[0] for h in next(rows)]
        cols = {h: [] for h in head}
        for row in rows:
            for h, x in zip(head, row):
                cols[h].append(float(x))
    return cols


def unwrap(a):
    out, off = [a[0]], 0.0
    for p, q in zip(a, a[1:]):
        d = q - p
        if d > math.pi:
            off -= 2 * math.pi
        elif d < -math.pi:
            off += 2 * math.pi
        out.append(q + off)
    return out


def bounce_measures(cols, t0, t1, rs, rb):
    """Over [t0, t1]: per retainer the time in contact, the angle the contact point turns while in
    contact (deg), the range of contact angles (deg), the node's angle from start to end, and the mean
    angle and race speed in each 50 ms; the no-whirl rolling race speed R_s Omega / R_b."""
    t = cols["t"]
    idx = [i for i, x in enumerate(t) if t0 <= x <= t1]
    out = {}
    for j in range(2):
        th = unwrap([cols["theta_ret%d" % j][i] for i in idx])
        c = [cols["contact_ret%d" % j][i] != 0.0 for i in idx]
        dt = (t[idx[-1]] - t[idx[0]]) / max(1, len(idx) - 1)
        turned = sum(th[k + 1] - th[k] for k in range(len(idx) - 1) if c[k] and c[k + 1])
        angles = [math.degrees(math.atan2(math.sin(th[k]), math.cos(th[k]))) for k in range(len(idx)) if c[k]]
        windows = []
        w0 = t0
        while w0 < t1 - 1e-9:
            sel = [k for k, i in enumerate(idx) if w0 <= t[i] < w0 + 0.05]
            if sel:
                sx = sum(math.cos(th[k]) for k in sel)
                sy = sum(math.sin(th[k]) for k in sel)
                windows.append({"from": w0, "mean_angle": math.degrees(math.atan2(sy, sx)),
                                "race_speed": sum(cols["wr_ret%d" % j][idx[k]] for k in sel) / len(sel),
                                "speed": sum(cols["speed"][idx[k]] for k in sel) / len(sel)})
            w0 += 0.05
        out["ret%d" % j] = {"contact_time": sum(c) * dt, "turned_in_contact": math.degrees(turned),
                            "contact_angle_min": min(angles) if angles else None,
                            "contact_angle_max": max(angles) if angles else None,
                            "node_turned": math.degrees(th[-1] - th[0]), "windows": windows}
    out["window"] = [t0, t1]
    out["busiest"] = max(range(2), key=lambda j: out["ret%d" % j]["contact_time"])
    out["rolling_race_speed"] = [rs * w["speed"] / rb for w in out["ret0"]["windows"]]
    return out


def fall_windows(cols):
    """drop.cfg run long at 20 kHz: in each 0.1 s, per retainer, the mean angle of its node (deg) and
    the fraction of the 0.1 s in contact."""
    t = cols["t"]
    out = []
    w0 = 0.0
    while w0 < t[-1] - 1e-9:
        sel = [i for i, x in enumerate(t) if w0 <= x < w0 + 0.1]
        row = {"from": round(w0, 3)}
        for j in range(2):
            sx = sum(math.cos(cols["theta_ret%d" % j][i]) for i in sel)
            sy = sum(math.sin(cols["theta_ret%d" % j][i]) for i in sel)
            row["angle%d" % j] = math.degrees(math.atan2(sy, sx))
            row["contact%d" % j] = sum(1 for i in sel if cols["contact_ret%d" % j][i] != 0.0) / len(sel)
            row["radius%d" % j] = max(cols["r_ret%d" % j][i] for i in sel)
        out.append(row)
        w0 += 0.1
    return out


def bounce_job(tool, tmp, speed, drag, rs, rb):
    name = os.path.join(tmp, "b-%g-%s" % (speed, drag))
    rec = run(tool, STUDY_DROP, drop_sets(speed, drag, [("output.sample_rate", "20000")]), csv_path=name)
    s = rec["summary"]
    end = s["t_reached"]
    rec["measured"] = bounce_measures(read_csv(name + ".csv"), end - s["ending_window"], end, rs, rb)
    for ext in (".csv", ".events.csv"):
        if os.path.exists(name + ext):
            os.remove(name + ext)
    return rec


def fall_job(tool, tmp):
    name = os.path.join(tmp, "fall")
    rec = run(tool, DROP, [("end_time", "1.5"), ("output.sample_rate", "20000")], csv_path=name)
    rec["windows"] = fall_windows(read_csv(name + ".csv"))
    for ext in (".csv", ".events.csv"):
        if os.path.exists(name + ext):
            os.remove(name + ext)
    return rec


def texts(tool):
    """The modal text of study-a (its critical speeds) and the info text of study-drop (mass, radii)."""
    out = {}
    for key, args in (("modal_a", ["modal", STUDY_A]), ("info_drop", ["info", STUDY_DROP])):
        o, err, rc, wall, cpu = tool_run(tool, args)
        out[key] = {"command": "touchdown " + " ".join(args), "text": o}
    return out


def parallel(jobs):
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {key: pool.submit(fn, *args) for key, fn, args in jobs}
        return {key: f.result() for key, f in futures.items()}


def radii(info_text):
    m = re.search(r"Rs ([0-9.e+-]+) m, Rb ([0-9.e+-]+) m", info_text)
    return float(m.group(1)), float(m.group(2))


def record(tool, stamp):
    """Every run the page quotes; returns the record (docs/results/sweep_study.json)."""
    data = stamp(tool, "sweep_study", "scripts/sweep_study.py: the page's three sweeps in a scratch directory "
                 "(each under /usr/bin/time), then touchdown run --json of the cases with --set variants, two at a time")
    t0 = time.monotonic()
    data["texts"] = texts(tool)
    rs, rb = radii(data["texts"]["info_drop"]["text"])
    with tempfile.TemporaryDirectory() as tmp:
        data["sweeps"] = {"study": sweep(tool, SWEEP_A, tmp), "study-drop": sweep(tool, SWEEP_DROP, tmp),
                          "phase": sweep(tool, SWEEP_PHASE, tmp)}
        for args in PLOTS:
            out, err, rc, wall, cpu = tool_run(tool, args, cwd=tmp)
            if rc != 0:
                sys.exit("sweep_study: touchdown %s: %s" % (" ".join(args), err[-300:]))
        for src, dst in FIGURES:
            shutil.copyfile(os.path.join(tmp, src), os.path.join(ROOT, "docs", "figures", dst))
    jobs = []
    for s, u in A_TIGHT:
        base = [("speed", "%g" % s), ("unbalances[0].magnitude", u)]
        jobs += [("a %g %s" % (s, u), run, (tool, STUDY_A, base)),
                 ("a %g %s tight" % (s, u), run, (tool, STUDY_A, base + [("solver", TIGHT)]))]
    for s, t in CONVERGE:
        k = "%g %s" % (s, t)
        jobs += [(k, run, (tool, STUDY_DROP, drop_sets(s, t))),
                 (k + " 1.6", run, (tool, STUDY_DROP, drop_sets(s, t, [("end_time", "1.6")]))),
                 (k + " tight", run, (tool, STUDY_DROP, drop_sets(s, t, [("solver", TIGHT)])))]
    for s, t in CONVERGE_TIGHT_ONLY:
        jobs.append(("%g %s tight" % (s, t), run, (tool, STUDY_DROP, drop_sets(s, t, [("solver", TIGHT)]))))
    jobs.append(("190 10 tight 1.6", run, (tool, STUDY_DROP, drop_sets(190, "10", [("solver", TIGHT), ("end_time", "1.6")]))))
    for t in ("0.02", "10"):
        jobs.append(("220 %s start" % t, run, (tool, STUDY_DROP, drop_sets(220, t, [("end_time", "0.05")]))))
    for s, mu, t in KEYS_RUNS:
        jobs.append(("keys %g %s %s" % (s, mu, t), run,
                     (tool, DROP, [("end_time", "0.6"), ("speed", "%g" % s), (FRICTION[0], mu), (FRICTION[1], mu),
                                   (DRAG[0], t), (DRAG[1], t)])))
    with tempfile.TemporaryDirectory() as tmp:
        jobs.append(("fall", fall_job, (tool, tmp)))
        for s, t in BOUNCES:
            jobs.append(("bounce %g %s" % (s, t), bounce_job, (tool, tmp, s, t, rs, rb)))
        data["runs"] = parallel(jobs)
    data["radii"] = {"rs": rs, "rb": rb}
    cpu = sum(x["cpu_time"] for x in data["sweeps"].values()) + sum(x["cpu_time"] for x in data["runs"].values())
    data["cpu_time"] = round(cpu, 1)
    data["runs_wall_time"] = round(time.monotonic() - t0, 1)
    return data


def main(argv):
    if len(argv) != 1:
        sys.exit(__doc__)
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import docs_record  # noqa: E402  (its stamp and save)
    tool = os.path.join(os.path.abspath(argv[0]), "touchdown")
    start = time.monotonic()
    data = record(tool, docs_record.stamp)
    data["record_wall_time"] = round(time.monotonic() - start, 1)
    docs_record.save("sweep_study", data)
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "docs_render.py")]).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
