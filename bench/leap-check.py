#!/usr/bin/env python3
"""The projective leap checked against the full integration on a stretch where both run
(bench/leap-check.sh says what and how; docs/performance.md, "Long runs: the projective leap").

A benchmark and a check, not a test: it asserts nothing, it records. The drop's bounce is chaotic,
so one full run is one draw: the full integration is an ensemble (`touchdown run --spread N`,
solver.atol within +-1 %), and so is the leap; each summary answer of the leap run is set against
the full ensemble's range."""
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CASE = os.path.join(ROOT, "cases", "drop-to-rest.cfg")
# The summary's answers compared beside the spread's own (its leading answers), and the energy account's terms.
ENERGY = ["drag_loss", "contact_loss", "damping_loss", "residual"]


def run(tool, sets, spread):
    """One `touchdown run --json` of the case with the overrides, its summary and its CPU seconds."""
    args = [tool, "run", "-q", "--json", "--csv", "", "--hdf5", ""]
    if spread > 1:
        args += ["--spread", str(spread)]
    for s in sets:
        args += ["--set", s]
    before = os.times()
    proc = subprocess.run(args + [CASE], stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    after = os.times()
    if proc.returncode != 0:
        sys.exit("leap-check: %s failed (exit %d): %s" % (" ".join(args), proc.returncode, proc.stderr[-1000:]))
    cpu = after.children_user + after.children_system - before.children_user - before.children_system
    return json.loads(proc.stdout), cpu


def answers(summary):
    """The answers compared: the spread's leading ones (the members of its "answers"), the energy terms."""
    out = {}
    for name, a in (summary.get("spread") or {}).get("answers", {}).items():
        out[name] = {"run": a["run"], "least": a["least"], "median": a["median"], "greatest": a["greatest"],
                     "values": a["values"]}
    energy = summary.get("energy") or {}
    for name in ENERGY:
        if name in energy:
            out["energy." + name] = {"run": energy[name]}
    return out


def main():
    build, members, end, factors = os.path.join(ROOT, "build"), 5, 20.0, [20.0]
    argv = sys.argv[1:]
    while argv:
        a = argv.pop(0)
        if a == "-n":
            members = int(argv.pop(0))
        elif a == "--end":
            end = float(argv.pop(0))
        elif a == "--json":
            pass
        else:
            build = a
    tool = os.path.join(build, "touchdown")
    if not os.access(tool, os.X_OK):
        sys.exit("leap-check: no tool at %s (scripts/setup.sh %s builds it)" % (tool, build))
    stretch = ["end_time=%r" % end]
    start = time.monotonic()
    full, full_cpu = run(tool, stretch + ["leap.burst=0"], members)
    leap, leap_cpu = run(tool, stretch, members)
    shipped = {k: leap.get(k) for k in ("leaps", "leapt_time", "leap_decel_power", "leap_decel_speed", "leap_decel_sd")}
    fa, la = answers(full), answers(leap)
    rows = {}
    for name, f in fa.items():
        if name not in la:
            continue
        l = la[name]
        row = {"leap": l["run"], "full_run": f["run"]}
        if "least" in f:
            row.update({"full_least": f["least"], "full_median": f["median"], "full_greatest": f["greatest"],
                        "leap_least": l.get("least"), "leap_greatest": l.get("greatest"),
                        "inside": f["least"] <= l["run"] <= f["greatest"],
                        "ranges_meet": l.get("least") is not None and l["least"] <= f["greatest"]
                        and f["least"] <= l["greatest"]})
        rows[name] = row
    others = {}
    for factor in factors:
        s, cpu = run(tool, stretch + ["leap.factor=%r" % factor], 1)
        others["%g" % factor] = {"cpu": cpu, "leaps": s.get("leaps"), "leapt_time": s.get("leapt_time"),
                                 "answers": {k: v["run"] for k, v in answers(s).items()},
                                 "final_speed": s.get("final_speed"), "contacts": s.get("contacts")}
    with open(CASE) as f:
        leap_line = next((line.split("#")[0].strip() for line in f if line.startswith("leap")), None)
    out = {"case": "cases/drop-to-rest.cfg", "leap": leap_line, "end_time": end, "members": members,
           "full": {"cpu": full_cpu, "command": "touchdown run -q --json --csv '' --hdf5 '' --spread %d --set "
                    "end_time=%g --set leap.burst=0 cases/drop-to-rest.cfg" % (members, end),
                    "steps": full["stats"]["steps"]},
           "leapt": {"cpu": leap_cpu, "command": "touchdown run -q --json --csv '' --hdf5 '' --spread %d --set "
                     "end_time=%g cases/drop-to-rest.cfg" % (members, end),
                     "steps": leap["stats"]["steps"], **shipped},
           "answers": rows, "factors": others, "seconds": time.monotonic() - start}
    json.dump(out, sys.stdout, indent=1, sort_keys=True)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
