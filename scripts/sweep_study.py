#!/usr/bin/python3
"""The sweep study of docs/sweep-study.md: cases/study-a.cfg over speed and unbalance, and the drop of
cases/study-drop.cfg over the drop speed and the races' drag torque, with the single runs the page
reads beside the sweeps.

    sweep_study.py BUILD_DIR     rerun the study: docs/results/sweep_study.json and the study figures
                                 docs/figures/study-*.png (the sweeps one at a time, the single runs two
                                 at a time; the CPU and wall time in the record), then render the docs
    sweep_study.py --check TOOL  rerun one recorded run (cases/study-a.cfg at 150 rad/s and 0.05 kg m,
                                 under a second) and compare it with the record (tests/cli/test_docs.sh)

scripts/make-docs.sh --full --only sweep_study does the same (docs_record.py's source "sweep_study");
docs_render.py renders the regions and spans of docs/sweep-study.md from the record with the REGIONS and
SPANS of scripts/sweep_study_page.py. Every number the page quotes is in the record, with the command
that gave it (run as recorded: the runs with files in a scratch directory whose cases/ is the
repository's). The figures are the sweeps' own plots
(`touchdown plot` of the tables recorded here), so they show the recorded rows; they are installed only
once the record is saved. Only Debian's python3 modules are used.
"""
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

from recovery_study import parallel  # the studies' runs, two at a time

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
    """Run the tool: (stdout, stderr, return code, wall s, CPU s = user + sys). The CPU time is the
    child's own resource usage from wait4(2), so runs in parallel threads do not count each other's."""
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        start = time.monotonic()
        proc = subprocess.Popen([tool] + args, cwd=cwd, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.monotonic() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        return out.read(), err.read(), proc.returncode, wall, usage.ru_utime + usage.ru_stime


def run(tool, case, sets, out_dir=None, name=None):
    """touchdown run --json of CASE with --set SETS [(key, value)]; with OUT_DIR and NAME, run in OUT_DIR
    (which links cases/ to the repository's) writing NAME.csv there. The command recorded is the one run.
    Stops when the tool fails or its status is not success: a failed run is never recorded as numbers."""
    args = ["run", "--json", "-q", "--hdf5", ""] + (["-o", name] if name else ["--csv", ""])
    for k, v in sets:
        args += ["--set", "%s=%s" % (k, v)]
    args.append(case)
    out, err, rc, wall, cpu = tool_run(tool, args, cwd=out_dir or ROOT)
    command = "touchdown " + " ".join(quote(a) for a in args)
    try:
        summary = json.loads(out)
    except ValueError:
        sys.exit("sweep_study: %s: exit %d, printed no JSON: %s" % (command, rc, err[:300]))
    if rc != 0 or summary.get("status") != "success":
        sys.exit("sweep_study: %s: exit %d, status %s: %s" % (command, rc, summary.get("status"), err[:300]))
    for key in ("hdf5_path", "csv_path", "events_path"):
        if summary.get(key):
            summary[key] = os.path.basename(summary[key])
    print("  %-90s %6.1f s wall %6.1f s CPU" % (command[len("touchdown run --json -q --hdf5 '' "):][:90], wall, cpu),
          flush=True)
    return {"command": command, "cpu_time": round(cpu, 3), "wall_time": round(wall, 3), "summary": summary}


def scratch(tmp):
    """TMP with cases/ linked to the repository's, so that the commands run there read as recorded."""
    os.symlink(os.path.join(ROOT, "cases"), os.path.join(tmp, "cases"))
    return tmp


def drop_sets(speed, drag, more=()):
    return [("speed", "%g" % speed), (DRAG[0], drag), (DRAG[1], drag)] + list(more)


def sweep(tool, args, tmp):
    """A touchdown sweep in TMP: its command, summary line, CPU and wall time, and its table."""
    out, err, rc, wall, cpu = tool_run(tool, args, cwd=tmp)
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
    contact (deg), the range of contact angles (deg, unwrapped), the node's net turn while out at the
    clearance (deg, radius over half of it), and the mean
    angle and race speed in each 50 ms; the no-whirl rolling race speed R_s Omega / R_b."""
    t = cols["t"]
    idx = [i for i, x in enumerate(t) if t0 <= x <= t1]
    out = {}
    for j in range(2):
        th = unwrap([cols["theta_ret%d" % j][i] for i in idx])
        c = [cols["contact_ret%d" % j][i] != 0.0 for i in idx]
        far = [cols["r_ret%d" % j][i] > 0.5 * (rb - rs) for i in idx]
        # the table has extra rows at the contact events (docs/output-format.md), crowded round the
        # contacts: each interval counts by its length, half to each end (trapezoidal rule), for the time
        # in contact and the angle turned in it alike, so that their ratio is the whirl in contact
        contact = sum((t[idx[k + 1]] - t[idx[k]]) * (c[k] + c[k + 1]) / 2 for k in range(len(idx) - 1))
        turned = sum((th[k + 1] - th[k]) * (c[k] + c[k + 1]) / 2 for k in range(len(idx) - 1))
        # the range on the unwrapped angle, so that a contact arc across +-180 degrees is not taken as a
        # full circle
        angles = [math.degrees(th[k]) for k in range(len(idx)) if c[k]]
        # the node's net turn while out at the clearance (radius over half of it), as fall_windows counts
        node_turned = sum(th[k + 1] - th[k] for k in range(len(idx) - 1) if far[k] and far[k + 1])
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
        out["ret%d" % j] = {"contact_time": contact, "turned_in_contact": math.degrees(turned),
                            "contact_angle_min": min(angles) if angles else None,
                            "contact_angle_max": max(angles) if angles else None,
                            "node_turned": math.degrees(node_turned), "windows": windows}
    out["window"] = [t0, t1]
    out["busiest"] = max(range(2), key=lambda j: out["ret%d" % j]["contact_time"])
    out["rolling_race_speed"] = [rs * w["speed"] / rb for w in out["ret0"]["windows"]]
    return out


def fall_windows(cols, t_fail, clearance):
    """drop.cfg run long at 20 kHz: in each 0.1 s from the AMBs' failure, per retainer, the mean angle
    of its node (deg), the net angle it turned through while out at the clearance (radius over half of
    it: a node that goes round the clearance turns 360 deg; a flight through the middle does not count)
    and the fraction of the 0.1 s in contact."""
    t = cols["t"]
    out = []
    w0 = t_fail
    while w0 + 0.1 <= t[-1] + 1e-9:
        sel = [i for i, x in enumerate(t) if w0 <= x < w0 + 0.1]
        row = {"from": round(w0, 3)}
        for j in range(2):
            th = unwrap([cols["theta_ret%d" % j][i] for i in sel])
            out_ = [cols["r_ret%d" % j][i] > 0.5 * clearance for i in sel]
            sx = sum(math.cos(a) for a in th)
            sy = sum(math.sin(a) for a in th)
            row["angle%d" % j] = math.degrees(math.atan2(sy, sx))
            row["turned%d" % j] = math.degrees(abs(sum(th[k + 1] - th[k] for k in range(len(th) - 1)
                                                       if out_[k] and out_[k + 1])))
            # time-weighted: the extra rows at contact events crowd round the contacts (trapezoidal rule)
            c = [cols["contact_ret%d" % j][i] != 0.0 for i in sel]
            row["contact%d" % j] = sum((t[sel[k + 1]] - t[sel[k]]) * (c[k] + c[k + 1]) / 2
                                       for k in range(len(sel) - 1)) / (t[sel[-1]] - t[sel[0]])
        out.append(row)
        w0 += 0.1
    return out


def failure_time():
    """cases/drop.cfg's failure: the time of its schedule's first amb_off entry (cases/include/drop-rig.cfg,
    its one source)."""
    with open(os.path.join(ROOT, "cases", "include", "drop-rig.cfg")) as f:
        return float(re.search(r"\{\s*time = ([0-9.]+);\s*amb_off = 0;", f.read()).group(1))


def bounce_job(tool, tmp, speed, drag, rs, rb):
    name = "b-%g-%s" % (speed, drag)
    rec = run(tool, STUDY_DROP, drop_sets(speed, drag, [("output.sample_rate", "20000")]), out_dir=tmp, name=name)
    name = os.path.join(tmp, name)
    s = rec["summary"]
    end = s["t_reached"]
    rec["measured"] = bounce_measures(read_csv(name + ".csv"), end - s["ending_window"], end, rs, rb)
    for ext in (".csv", ".events.csv"):
        if os.path.exists(name + ext):
            os.remove(name + ext)
    return rec


def fall_job(tool, tmp, clearance):
    rec = run(tool, DROP, [("end_time", "1.5"), ("output.sample_rate", "20000")], out_dir=tmp, name="fall")
    name = os.path.join(tmp, "fall")
    rec["failure_time"] = failure_time()
    rec["windows"] = fall_windows(read_csv(name + ".csv"), rec["failure_time"], clearance)
    for ext in (".csv", ".events.csv"):
        if os.path.exists(name + ext):
            os.remove(name + ext)
    return rec


def texts(tool):
    """The modal text of study-a (its critical speeds) and the info text of study-drop (mass, radii)."""
    out = {}
    for key, args in (("modal_a", ["modal", "--csv", "", "--hdf5", "", STUDY_A]), ("info_drop", ["info", STUDY_DROP])):
        o, err, rc, wall, cpu = tool_run(tool, args)
        if rc != 0:
            sys.exit("sweep_study: touchdown %s: exit %d: %s" % (" ".join(quote(a) for a in args), rc, err[-300:]))
        out[key] = {"command": "touchdown " + " ".join(quote(a) for a in args), "text": o}
    return out


def radii(info_text):
    m = re.search(r"Rs ([0-9.e+-]+) m, Rb ([0-9.e+-]+) m", info_text)
    return float(m.group(1)), float(m.group(2))


def record(tool, stamp):
    """Every run the page quotes; returns the record (docs/results/sweep_study.json) and what to call once
    it is saved (installing the figures)."""
    data = stamp(tool, "sweep_study", "scripts/sweep_study.py: the page's three sweeps in a scratch directory "
                 "(the CPU time of each from wait4(2)), then touchdown run --json of the cases with --set variants, two at a time")
    t0 = time.monotonic()
    data["texts"] = texts(tool)
    rs, rb = radii(data["texts"]["info_drop"]["text"])
    with tempfile.TemporaryDirectory() as tmp:
        scratch(tmp)
        data["sweeps"] = {"study": sweep(tool, SWEEP_A, tmp), "study-drop": sweep(tool, SWEEP_DROP, tmp),
                          "phase": sweep(tool, SWEEP_PHASE, tmp)}
        for args in PLOTS:
            out, err, rc, wall, cpu = tool_run(tool, args, cwd=tmp)
            if rc != 0:
                sys.exit("sweep_study: touchdown %s: %s" % (" ".join(args), err[-300:]))
        figures = {}
        for src, dst in FIGURES:
            with open(os.path.join(tmp, src), "rb") as f:
                figures[dst] = f.read()
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
        scratch(tmp)
        jobs.append(("fall", fall_job, (tool, tmp, rb - rs)))
        for s, t in BOUNCES:
            jobs.append(("bounce %g %s" % (s, t), bounce_job, (tool, tmp, s, t, rs, rb)))
        data["runs"] = parallel(jobs)
    data["radii"] = {"rs": rs, "rb": rb}
    cpu = sum(x["cpu_time"] for x in data["sweeps"].values()) + sum(x["cpu_time"] for x in data["runs"].values())
    data["cpu_time"] = round(cpu, 1)
    data["runs_wall_time"] = round(time.monotonic() - t0, 1)
    return data, lambda: install(figures)


def install(figures):
    """The figures into docs/figures, each through a temporary file and a rename; called once the record
    is saved, so that a record that failed leaves the figures of the record in place."""
    for name, png in figures.items():
        path = os.path.join(ROOT, "docs", "figures", name)
        with open(path + ".tmp", "wb") as f:
            f.write(png)
        os.replace(path + ".tmp", path)


CHECKED_RUN = "a 150 0.05"   # cases/study-a.cfg at 150 rad/s, 0.05 kg m: a rub, well under a second


def check_run(tool):
    """The record's CHECKED_RUN rerun with its recorded arguments against its recorded summary (docs_record's
    comparison and tolerance; wall-clock quantities not compared); 0 when they agree."""
    import docs_record  # noqa: E402  (its comparison and tolerance)
    with open(os.path.join(ROOT, "docs", "results", "sweep_study.json")) as f:
        rec = json.load(f)["runs"][CHECKED_RUN]
    sets = [("speed", "150"), ("unbalances[0].magnitude", "0.05")]
    new = run(tool, STUDY_A, sets)
    if new["command"] != rec["command"]:
        print("FAIL: sweep study: the check's command %s is not the recorded %s" % (new["command"], rec["command"]))
        return 1
    diffs = docs_record.differences(rec["summary"], new["summary"], CHECKED_RUN)
    if diffs:
        print("FAIL: sweep study: %s differs from docs/results/sweep_study.json (rtol %g; rerun scripts/make-docs.sh "
              "--full --only sweep_study): %s" % (new["command"], docs_record.RTOL, "; ".join(diffs[:8])))
        return 1
    print("ok:   sweep study: %s matches docs/results/sweep_study.json (rtol %g)" % (new["command"], docs_record.RTOL))
    return 0


def main(argv):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    if len(argv) == 2 and argv[0] == "--check":
        return check_run(os.path.abspath(argv[1]))
    if len(argv) != 1 or argv[0].startswith("-"):
        sys.exit(__doc__)
    import docs_record  # noqa: E402  (its stamp and save)
    tool = os.path.join(os.path.abspath(argv[0]), "touchdown")
    start = time.monotonic()
    data, after = record(tool, docs_record.stamp)
    data["record_wall_time"] = round(time.monotonic() - start, 1)
    docs_record.save("sweep_study", data)
    after()
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "docs_render.py")]).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
