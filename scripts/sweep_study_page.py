#!/usr/bin/python3
"""docs/sweep-study.md's generated regions and spans (REGIONS and SPANS, for scripts/docs_render.py), built
from docs/results/sweep_study.json alone (scripts/sweep_study.py records it). Where the page draws a
conclusion from the numbers, the sentence is written here from them, or the rendering stops (fail()),
saying which sentence the numbers no longer support. Only Debian's python3 modules are used.
"""
import json
import math
import os
import re
import sys

from sweep_study import (quote, A_TIGHT, BOUNCES, CONVERGE, CONVERGE_TIGHT_ONLY, DRAG, KEYS_RUNS, PHASE_DRAGS, PHASES, PLOTS,
                         ROOT, STUDY_A, STUDY_DROP, TIGHT)

_cache = {}


def _res():
    if "r" not in _cache:
        with open(os.path.join(ROOT, "docs", "results", "sweep_study.json")) as f:
            _cache["r"] = json.load(f)
    return _cache["r"]


def _val(x):
    """A table cell as a number (None for nan or empty), else the text."""
    try:
        v = float(x)
    except ValueError:
        return x
    return None if math.isnan(v) else v


def _rows(name):
    """The sweep NAME's rows as dicts (column names without their units)."""
    key = "rows " + name
    if key not in _cache:
        sw = _res()["sweeps"][name]
        cols = [c.split(" [")[0] for c in sw["columns"]]
        _cache[key] = [{c: _val(x) for c, x in zip(cols, row)} for row in sw["rows"]]
    return _cache[key]


def _u_rows(u):
    return [r for r in _rows("study") if r["unbalances[0].magnitude"] == u]


def _drop(speed, drag):
    for r in _rows("study-drop"):
        if r["speed"] == speed and r[DRAG[0]] == float(drag):
            return r
    raise KeyError((speed, drag))


def _run(key):
    return _res()["runs"][key]["summary"]


def _g(x, digits=3):
    return "-" if x is None else "%.*g" % (digits, x)


def _f(x, decimals=1):
    return "-" if x is None else "%.*f" % (decimals, x)


def _span(vals, fmt=_g, unit=""):
    """'a to b unit' (or 'a unit' when they agree as written)."""
    vals = [v for v in vals if v is not None]
    if not vals:
        return "-"
    lo, hi = fmt(min(vals)), fmt(max(vals))
    return (lo if lo == hi else "%s to %s" % (lo, hi)) + (" " + unit if unit else "")


def _kn(x):
    return _g(x / 1000.0, 3) + " kN"


def _list(items):
    items = list(items)
    if len(items) <= 1:
        return "".join(items)
    return ", ".join(items[:-1]) + " and " + items[-1]


def _drags():
    return sorted({r[DRAG[0]] for r in _rows("study-drop")})


def _drop_speeds():
    return sorted({r["speed"] for r in _rows("study-drop")})


def _nm(t):
    return "%g N m" % t


def _frac(r):
    return r["contact_time"] / r["t_reached"]


def _pct(x):
    return "%.0f %%" % (100.0 * x)


def _stretches(items, keep):
    """The runs of consecutive ITEMS for which KEEP(item) holds, each a list, in order."""
    groups, cur = [], []
    for x in items:
        if keep(x):
            cur.append(x)
        elif cur:
            groups.append(cur)
            cur = []
    if cur:
        groups.append(cur)
    return groups


def _runs_of(drags):
    """Consecutive drag torques grouped: '0.02-0.5 N m', '3 N m'."""
    groups = _stretches(_drags(), lambda t: t in drags)
    return _list(("%g N m" % g[0]) if len(g) == 1 else ("%g-%g N m" % (g[0], g[-1])) for g in groups)


def _how(ending):
    return "sliding" if ending.startswith("sliding") or ", sliding" in ending else "rolling"


def _critical():
    """The critical speeds of `touchdown modal cases/study-a.cfg`: [(whirl, rad/s, zeta)]."""
    text = _res()["texts"]["modal_a"]["text"]
    block = text.split("critical speeds in")[1].split("unbalance response")[0]
    return [(m.group(1), float(m.group(2)), float(m.group(3)))
            for m in re.finditer(r"(forward|backward)\s+([0-9.]+) rad/s.*zeta ([0-9.]+)", block)]


def _mass():
    return float(re.search(r"mass\s+([0-9.]+) kg in all", _res()["texts"]["info_drop"]["text"]).group(1))


def _case_value(path, pattern):
    with open(os.path.join(ROOT, path)) as f:
        return float(re.search(pattern, f.read()).group(1))


def _u_drop():
    return _case_value(STUDY_DROP, r"unbalances = \( \{ node = 1; magnitude = ([0-9.e-]+);")


def _gravity():
    return _case_value(STUDY_DROP, r"gravity = \{ enabled = true; g = ([0-9.]+);")


def _friction():
    return float(re.search(r"mu ([0-9.]+)", _res()["texts"]["info_drop"]["text"]).group(1))


def _clearance():
    return _rows("study")[0]["section_clearance"]


def fail(what):
    """Stop the rendering: a sentence of the page the record no longer supports."""
    sys.exit("docs_render: docs/sweep-study.md: the record no longer supports: %s (rewrite the sentence)" % what)


# - the commands, as the record ran them -
def _shell(command, width=100):
    """A recorded command ("touchdown ...") as the page's shell line from the repository root, broken
    with backslashes before an option where it passes WIDTH."""
    words = command.split(" ")
    words[0] = "build/touchdown"
    lines, cur = [], ""
    for k, w in enumerate(words):
        if cur and w.startswith("-") and len(cur) + 1 + len(w) + sum(len(x) + 1 for x in words[k + 1:k + 2]) > width:
            lines.append(cur + " \\")
            cur = "    " + w
        else:
            cur = (cur + " " + w) if cur else w
    return "\n".join(lines + [cur])


def _commands(sweep):
    """The sweep SWEEP's recorded command and the plots of its table (PLOTS, as the record ran them)."""
    cmd = _res()["sweeps"][sweep]["command"]
    h5 = cmd.split(" -o ")[1].split(" ")[0] + ".h5"
    plots = [_shell("touchdown " + " ".join(quote(a) for a in p)) for p in PLOTS if p[-1] == h5]
    return "```sh\n%s\n```\n" % "\n".join([_shell(cmd)] + plots)


def region_a_commands():
    return _commands("study")


def region_drop_commands():
    return _commands("study-drop")


def region_phase_commands():
    return _commands("phase")


# - the record and timings -
def span_record():
    r = _res()
    return "%s, %s, source %s, on %d cores of %s, load average %.1f at the start" % (
        r["tool_version"], r["date"][:10], r["revision"], r["machine"]["nproc"], r["machine"]["cpu"] or "an unnamed CPU",
        r["machine"]["loadavg_start"])


def span_record_cost():
    r = _res()
    return "%.0f s of CPU and %.0f s of wall time" % (r["cpu_time"], r["record_wall_time"])


def region_a_timing():
    sw = _res()["sweeps"]["study"]
    rows = _rows("study")
    wt = [x["wall_time"] for x in rows]
    speeds = sorted({x["speed"] for x in rows})
    us = sorted({x["unbalances[0].magnitude"] for x in rows})
    done = sum(1 for x in rows if x["status"] == "success")
    return ("```\n%s\n```\n\n%d points (%d speeds, %g rad/s apart, times %d unbalances), %d of them ran to their "
            "ends: %.1f s of wall time and %.1f s of CPU (user + system of the process) on one worker, %.2f s a "
            "point on average and %.2f s at most (the table's `wall_time` column), on the machine of the record "
            "(above) with other jobs beside it.\n") % (
        sw["summary_line"], len(rows), len(speeds), speeds[1] - speeds[0], len(us), done, sw["wall_time"], sw["cpu_time"],
        sum(wt) / len(wt), max(wt))


def region_a_solver():
    out = []
    for s, u in A_TIGHT:
        a, b = _run("a %g %s" % (s, u)), _run("a %g %s tight" % (s, u))
        ra, rb = a.get("section_radius") or [], b.get("section_radius") or []
        n = min(len(ra), len(rb))
        dr = max(abs(x - y) for x, y in zip(ra[:n], rb[:n])) if n else None
        dp = (b["peak_housing_force"] / a["peak_housing_force"] - 1.0) if a["peak_housing_force"] else None
        out.append("| %g rad/s, U = %s kg m | %s, %s | %s, %s | %s | %s |" % (
            s, u, a["regime"], "%.0f N" % a["peak_housing_force"], b["regime"], "%.0f N" % b["peak_housing_force"],
            "-" if dp is None else "%+.2f %%" % (100 * dp), "-" if dr is None else "%.2g um" % (dr * 1e6)))
    return ("| point | defaults: regime, peak housing force | rtol 1e-8, atol 1e-11 | force changed by | section radii "
            "changed by (largest, sample by sample) |\n|---|---|---|---|---|\n" + "\n".join(out) + "\n\n"
            "Commands: `%s` and the same with `--set 'solver=%s'`.\n" % (_res()["runs"]["a 150 0.05"]["command"], TIGHT))


def span_a_contacts():
    rows = [x for x in _rows("study") if x["regime"] != "free"]
    return "%s contact onsets" % _span([x["contacts"] for x in rows], lambda v: "%d" % v)


def span_a_point_time():
    return _span([x["wall_time"] for x in _rows("study") if x["regime"] != "free"], lambda v: "%.2g" % v, "s")


def span_a_crossings():
    rows = _rows("study")
    lo, hi = min(x["speed"] for x in rows), max(x["speed"] for x in rows)
    c = lambda sp: _span([x["section_count"] for x in rows if x["speed"] == sp], lambda v: "%d" % v)
    return "%s crossings at %g rad/s, %s at %g rad/s" % (c(lo), lo, c(hi), hi)


# - study A's map -
def region_a_regimes():
    rows = _rows("study")
    counts = {}
    for x in rows:
        counts[x["regime"]] = counts.get(x["regime"], 0) + 1
    others = [k for k in counts if k not in ("free", "rub")]
    text = "Of the %d points, %s. " % (len(rows), _list("%d %s" % (v, k) for k, v in sorted(counts.items())))
    text += ("No point bounced, whirled backward or failed.\n" if not others else
             "Besides free and rub: %s.\n" % _list(others))
    lines = ["| unbalance [kg m] | speeds in contact [rad/s] (regime rub unless said) |", "|---|---|"]
    for u in sorted({x["unbalances[0].magnitude"] for x in rows}):
        touch = [x for x in _u_rows(u) if x["regime"] != "free"]
        groups = _stretches(_u_rows(u), lambda x: x["regime"] != "free")
        cells = []
        for g in groups:
            rng = "%g" % g[0]["speed"] if len(g) == 1 else "%g-%g" % (g[0]["speed"], g[-1]["speed"])
            odd = sorted({x["regime"] for x in g} - {"rub"})
            cells.append(rng + (" (%s)" % ", ".join(odd) if odd else ""))
        lines.append("| %g | %s |" % (u, ", ".join(cells) if touch else "none: free at every speed"))
    return text + "\n" + "\n".join(lines) + "\n"


def _damped(zetas):
    """How damped modes of damping ratios ZETAS are: heavily over 0.1, lightly under 0.05 (the usual
    reading of a damping ratio; API 617's amplification factor 1 / (2 zeta) is then under 5, over 10)."""
    if min(zetas) > 0.1:
        return "heavily damped"
    if max(zetas) < 0.05:
        return "lightly damped"
    return "damped"


def span_a_rigid_modes():
    c = [x for x in _critical() if x[1] < 180.0]
    if not c:
        fail("the rig has critical speeds under 180 rad/s (its rigid-body modes)")
    return "%s rad/s, %s: zeta %s" % (_span([x[1] for x in c], lambda v: "%.0f" % v), _damped([x[2] for x in c]),
                                      _span([x[2] for x in c], lambda v: "%.2f" % v))


def span_a_bending_modes():
    c = [x for x in _critical() if 180.0 <= x[1] < 300.0]
    if not c:
        fail("the rig has critical speeds from 180 to 300 rad/s (its first bending modes)")
    umin = min(x["unbalances[0].magnitude"] for x in _rows("study"))
    if not any(x["regime"] != "free" and 180.0 <= x["speed"] for x in _u_rows(umin)):
        fail("the smallest unbalance touches near the bending pair")
    p1, p2 = _free_peak(50, 180), _free_peak(180, 250)
    between = [x["section_radius_max"] for x in _u_rows(umin) if p1 and p2 and p1[0] < x["speed"] < p2[0]
               and x["regime"] == "free"]
    if not between or min(between) >= min(p1[1], p2[1]):
        fail("above the rigid-body modes the free orbit shrinks, then grows into the bending pair")
    return ("Above them the free orbit shrinks, then grows into the %s pair near %s rad/s (zeta %s, the first bending "
            "modes)") % (_damped([x[2] for x in c]), _span([x[1] for x in c], lambda v: "%.0f" % v),
                         _span([x[2] for x in c], lambda v: "%.2f" % v))


def _first_touch():
    """Per speed, the smallest unbalance in contact (None: free at every unbalance)."""
    out = {}
    for x in _rows("study"):
        if x["regime"] != "free":
            u = out.get(x["speed"])
            out[x["speed"]] = x["unbalances[0].magnitude"] if u is None else min(u, x["unbalances[0].magnitude"])
        else:
            out.setdefault(x["speed"], None)
    return out


def span_a_boundary():
    ft = _first_touch()
    speeds = sorted(ft)
    umax = max(x["unbalances[0].magnitude"] for x in _rows("study"))
    lo = ft[speeds[0]]
    start = ("above %g kg m at %g rad/s" % (umax, speeds[0])) if lo is None else ("%g kg m at %g rad/s" % (lo, speeds[0]))
    below = [s for s in speeds if s < 180.0 and ft[s] is not None]
    if not below:
        fail("the smallest unbalance that brings contact falls with speed up to the rigid-body modes")
    umin = min(ft[s] for s in below)
    at = min(s for s in below if ft[s] == umin)
    return "%s to %g kg m from %g rad/s" % (start, umin, at)


# - bifurcation -
def span_a_linear():
    a, b = _u_rows(0.005), _u_rows(0.01)
    ratios = [y["section_radius_max"] / x["section_radius_max"] for x, y in zip(a, b)
              if x["regime"] == "free" and y["regime"] == "free" and x["section_radius_max"]]
    if not ratios or max(abs(q - 2.0) for q in ratios) > 0.02:
        fail("the 0.01 kg m section radius is twice the 0.005 kg m one where both run free")
    return "%s times the 0.005 one where both run free" % _span(ratios, lambda v: "%.3f" % v)


def _free_peak(lo, hi):
    best = None
    for x in _u_rows(0.005):
        if lo <= x["speed"] <= hi and x["regime"] == "free" and (best is None or x["section_radius_max"] > best[1]):
            best = (x["speed"], x["section_radius_max"])
    return best


def span_a_free_peaks():
    p1, p2 = _free_peak(50, 180), _free_peak(180, 250)
    if p1 is None or p2 is None:
        fail("the 0.005 kg m curve runs free at a rigid-body peak under 180 rad/s and a bending peak above")
    c = [x[2] for x in _critical() if 180.0 <= x[1] < 300.0]
    sharp = "the sharp " if c and _damped(c) == "lightly damped" else "the "
    return "near %g rad/s and %sbending resonance near %g rad/s" % (p1[0], sharp, p2[0])


def span_a_press():
    rub = [x for x in _rows("study") if x["regime"] == "rub"]
    if any(x["section_radius_max"] < x["section_clearance"] for x in rub):
        fail("every point in rub reaches the clearance in its section")
    return "up to %.0f um" % (1e6 * max(x["section_radius_max"] - x["section_clearance"] for x in rub))


def _sync_rub():
    """Rub points whose section spreads by less than 2 um: their whirl against the spin."""
    return [x for x in _rows("study") if x["regime"] == "rub" and x["section_radius_max"] - x["section_radius_min"] < 2e-6]


def span_a_sync():
    pts = _sync_rub()
    dev = [abs(x["ending_whirl_frequency"] / (x["speed"] / (2 * math.pi)) - 1.0) for x in pts]
    if max(dev) > 0.01:
        fail("the rub whose section is one dot whirls at the spin (within 1 %)")
    x = [p for p in pts if p["speed"] == 150.0] or pts
    return "within %.2g %% of the spin at all %d such points: %s Hz at %g rad/s" % (
        100 * max(dev), len(pts), _g(x[0]["ending_whirl_frequency"], 4), x[0]["speed"])


def _tight_moves(points):
    """What the tolerance check above says of POINTS (those of them it reran)."""
    said = []
    for x in points:
        k = "a %g %s" % (x["speed"], "%g" % x["unbalances[0].magnitude"])
        if k + " tight" not in _res()["runs"]:
            continue
        ra, rb = _run(k).get("section_radius") or [], _run(k + " tight").get("section_radius") or []
        n = min(len(ra), len(rb))
        if n:
            said.append("at %g rad/s and %g kg m its samples move by up to %.2g um at rtol 1e-8" % (
                x["speed"], x["unbalances[0].magnitude"], 1e6 * max(abs(p - q) for p, q in zip(ra[:n], rb[:n]))))
    return (" The check above reran %d of %d: %s." % (len(said), len(points), "; ".join(said))) if said else \
        " The check above reran none of them."


def region_a_spread():
    pts = [x for x in _rows("study") if x["regime"] != "free" and x["section_radius_max"] - x["section_radius_min"] >= 2e-6]
    if not pts:
        return "No point in contact has a section that spreads by 2 um or more: every rub is period-1.\n"
    intermittent = [x for x in pts if x["section_radius_min"] < x["section_clearance"] - 1e-5]
    lines = ["| point | regime, `ending` | section radius [mm] | whirl [Hz] | spin [Hz] |", "|---|---|---|---|---|"]
    for x in pts:
        lines.append("| %g rad/s, %g kg m | %s, %s | %.3f-%.3f | %s | %s |" % (
            x["speed"], x["unbalances[0].magnitude"], x["regime"], x["ending"], 1e3 * x["section_radius_min"],
            1e3 * x["section_radius_max"], _g(x["ending_whirl_frequency"], 4), _g(x["speed"] / (2 * math.pi), 4)))
    text = "\n".join(lines) + "\n"
    if intermittent:
        text += ("\nAt %s the section reaches well inside the clearance: the rotor touches, is thrown off and returns, "
                 "an intermittent, non-synchronous rub at the edge of the resonance, the non-periodic motion a "
                 "bifurcation diagram is made to show.%s\n") % (
            _list("%g rad/s and %g kg m" % (x["speed"], x["unbalances[0].magnitude"]) for x in intermittent),
            _tight_moves(intermittent))
    return text


def span_a_peak_force():
    rows = _rows("study")
    x = max(rows, key=lambda r: r["peak_housing_force"])
    if x["speed"] != max(r["speed"] for r in rows) or x["unbalances[0].magnitude"] != max(r["unbalances[0].magnitude"] for r in rows):
        fail("the largest peak housing force comes at the top speed and unbalance")
    return "%s at %g rad/s and %g kg m" % (_kn(x["peak_housing_force"]), x["speed"], x["unbalances[0].magnitude"])


def span_a_small_u_force():
    pts = [x for x in _rows("study") if x["unbalances[0].magnitude"] <= 0.01 and x["regime"] != "free"
           and x["speed"] > 180.0]
    past = [x for x in _u_rows(0.01) if x["speed"] > max(p["speed"] for p in pts)] if pts else []
    text = "%s (unbalances up to 0.01 kg m, %s rad/s)" % (
        _span([x["peak_housing_force"] / 1e3 for x in pts], lambda v: "%.1f" % v, "kN"),
        _span([x["speed"] for x in pts], lambda v: "%g" % v))
    if past and all(x["regime"] == "free" for x in past):
        text += "; at %s rad/s, past it, 0.01 kg m runs free" % _span([x["speed"] for x in past], lambda v: "%g" % v)
    return text



# - the drop study -
def _c():
    r = _res()["radii"]
    return r["rb"] - r["rs"]


def _keys_cell(s):
    races = s.get("retainer_race_speed") or []
    return "%s, %s%s; races at %s rad/s, shaft at %s rad/s" % (
        s["regime"], s["ending"], "" if s.get("ending_whirl_frequency") is None or s["regime"] == "backward whirl"
        else " (%s Hz in contact)" % _g(s["ending_whirl_frequency"], 3),
        "/".join("%.0f" % (x + 0.0) for x in races).replace("-0", "0"), _g(s["final_speed"], 4))


def region_drop_keys():
    lines = ["| speed [rad/s] | friction | race drag [N m] | regime, `ending` at 0.6 s |", "|---|---|---|---|"]
    for sp, mu, t in KEYS_RUNS:
        lines.append("| %g | %s | %s | %s |" % (sp, mu, t, _keys_cell(_run("keys %g %s %s" % (sp, mu, t)))))
    reg = lambda sel: sorted({_run("keys %g %s %s" % k)["regime"] for k in KEYS_RUNS if sel(*k)})
    free_race = reg(lambda sp, mu, t: sp == 190 and float(t) <= 0.5)
    draggy = reg(lambda sp, mu, t: sp == 190 and float(t) >= 5 and float(mu) >= 0.1)
    slick = reg(lambda sp, mu, t: sp == 190 and float(t) >= 5 and float(mu) < 0.1)
    slow = reg(lambda sp, mu, t: sp < 190)
    if len(free_race) != 1 or "backward whirl" not in draggy:
        fail("the friction coefficient alone does not change the regime, a draggy race does (so the study sweeps "
             "the drag and keeps the friction)")
    text = ("At 190 rad/s on races of 0.02 to 0.5 N m every friction from 0.1 to 0.3 ended in %s: on a free-turning "
            "race the friction coefficient alone did not change the regime. " % _list(free_race))
    text += ("On races of 5 and 10 N m at friction 0.1 to 0.3: %s; at friction 0.05: %s. " % (_list(draggy), _list(slick)))
    text += "At 80 and 120 rad/s: %s.\n" % _list(slow)
    return "\n".join(lines) + "\n\n" + text + "\nCommand (one run): `%s`.\n" % _res()["runs"]["keys 190 0.1 10"]["command"]


def _settled():
    """The fall's 0.1 s windows, and the index of the first from which every window has both retainer
    nodes at the bottom (mean angle within 45 degrees of straight down) and turning less than half a turn."""
    w = _res()["runs"]["fall"]["windows"]
    calm = lambda x: all(abs(x["angle%d" % j] + 90.0) <= 45.0 and x["turned%d" % j] < 180.0 for j in range(2))
    k = len(w)
    while k > 0 and calm(w[k - 1]):
        k -= 1
    if k == len(w):
        fail("the drop comes to rest at the bottom of the retainers by the end of the 1.5 s run")
    return w, k


def region_drop_fall():
    rec = _res()["runs"]["fall"]
    w, k = _settled()
    lines = ["| from [s] | mean angle, retainer 0 / 1 [deg] | net angle turned out at the clearance, 0 / 1 [deg] | in contact, 0 / 1 |",
             "|---|---|---|---|"]
    for x in w:
        lines.append("| %.2f | %.0f / %.0f | %.0f / %.0f | %s / %s |" % (
            x["from"], x["angle0"], x["angle1"], x["turned0"], x["turned1"], _pct(x["contact0"]), _pct(x["contact1"])))
    rounds = [x for x in w if max(x["turned0"], x["turned1"]) >= 360.0]
    settled = w[k:]
    text = ("After the failure at %g s %s. From %.2f s on the mean angle of both retainer nodes in every 0.1 s stays "
            "at the bottom (%s degrees, -90 is straight down), each turning through %s degrees net while out at the clearance, in contact %s of each "
            "0.1 s. Command: `%s`.\n") % (
        rec["failure_time"], ("a retainer node goes once round the clearance or more in the 0.1 s from %s s" %
                              _list("%.2f" % x["from"] for x in rounds)) if rounds else "no retainer node goes round the clearance in any 0.1 s",
        settled[0]["from"], _span([x["angle%d" % j] for x in settled for j in range(2)], lambda v: "%.0f" % v),
        _span([x["turned%d" % j] for x in settled for j in range(2)], lambda v: "%.0f" % v),
        _span([x["contact%d" % j] for x in settled for j in range(2)], lambda v: "%.0f" % (100 * v), "%"), rec["command"])
    return "\n".join(lines) + "\n\n" + text


def span_drop_settled():
    w, k = _settled()
    end = _case_value(STUDY_DROP, r"\nend_time = ([0-9.]+);")
    if w[k]["from"] + max(_run("100 0.02")["ending_window"], _run("250 0.5")["ending_window"]) > end + 1e-9:
        fail("the study's end time, %g s, leaves room for the regime's window after the fall" % end)
    return "%.2f s" % w[k]["from"]


def span_drop_windows():
    a, b = _run("100 0.02"), _run("250 0.5")
    return "%.2f s at 100 rad/s, %.2f s at 250 rad/s" % (a["ending_window"], b["ending_window"])


def span_drop_220():
    runs = [_run("220 %s start" % t) for t in ("0.02", "10")]
    if any(s["first_contact_time"] is None or s["first_contact_time"] > 1e-3 for s in runs):
        fail("at 220 rad/s the levitated run starts in contact")
    return "`first_contact_time` %s s, %s into the housing at t = %s s, peak AMB load %s, for drag 0.02 and 10 N m, " \
           "each run to the failure at 0.05 s" % (
               _span([s["first_contact_time"] for s in runs], lambda v: "%.2g" % v),
               _span([s["peak_housing_force"] / 1e3 for s in runs], lambda v: "%.1f" % v, "kN"),
               _span([s["peak_time"] for s in runs], lambda v: "%.2g" % v), _span([s["peak_amb_load"] for s in runs],
                                                                                   lambda v: "%.2f" % v))


def region_drop_timing():
    sw = _res()["sweeps"]["study-drop"]
    rows = _rows("study-drop")
    wt = [x["wall_time"] for x in rows]
    cpu = "; ".join("%s s (%g rad/s, %s N m)" % (_f(_res()["runs"]["%g %s" % k]["cpu_time"]), k[0], k[1]) for k in CONVERGE)
    return ("```\n%s\n```\n\n%d points (%d speeds times %d drag torques) in %.0f s of wall time and %.0f s of CPU on two "
            "workers, %.1f s a point on average, %.1f s at least and %.1f s at most (the table's `wall_time`); "
            "the CPU time (user + system of the process) of single points, run two at a time: %s.\n") % (
        sw["summary_line"], len(rows), len(_drop_speeds()), len(_drags()), sw["wall_time"], sw["cpu_time"],
        sum(wt) / len(wt), min(wt), max(wt), cpu)


def _groups(rows, label):
    """Consecutive rows with the same label, as (label, [drag, ...])."""
    out = []
    for r in rows:
        lab = label(r)
        if out and out[-1][0] == lab:
            out[-1][1].append(r[DRAG[0]])
        else:
            out.append((lab, [r[DRAG[0]]]))
    return out


def _drags_text(ts):
    return ("%g N m" % ts[0]) if len(ts) == 1 else ("%g-%g N m" % (ts[0], ts[-1]))


def region_drop_rows():
    if {r["regime"] for r in _rows("study-drop")} != {"rub", "bounce", "backward whirl"}:
        fail("the drop's regime map shows rub, bounce and backward whirl (and nothing else)")
    out = []
    for sp in _drop_speeds():
        rows = [_drop(sp, t) for t in _drags()]
        regs = _groups(rows, lambda r: r["regime"])
        if len(regs) == 1:
            head = "%g rad/s: %s everywhere." % (sp, regs[0][0])
        else:
            head = "%g rad/s: %s." % (sp, "; ".join("%s at %s" % (g, _drags_text(ts)) for g, ts in regs))
        endings = "; ".join("%s: %s" % (_drags_text(ts), e) for e, ts in _groups(rows, lambda r: r["ending"]))
        text = "- **%s** `ending`: %s. In contact %s of the run; peak housing force %s." % (
            head, endings, _span([_frac(r) for r in rows], lambda v: "%.0f" % (100 * v), "%"),
            _span([r["peak_housing_force"] / 1e3 for r in rows], lambda v: "%.1f" % v, "kN"))
        rub = [r for r in rows if r["regime"] == "rub" and not r["ending"].startswith("forward")]
        if rub:
            text += " In rub its once-per-revolution section radius is %s mm (clearance %s mm)." % (_span(
                [r["section_radius_min"] * 1e3 for r in rub] + [r["section_radius_max"] * 1e3 for r in rub], lambda v: "%.3f" % v),
                _span([r["section_clearance"] * 1e3 for r in rub], lambda v: "%.3f" % v))
        bounce = [r for r in rows if r["regime"] == "bounce" and not r["ending"].startswith("forward")]
        if bounce:
            text += " The bounces' contact points (forward rubs aside) creep at %s while in contact." % _span(
                [r["ending_whirl_frequency"] for r in bounce], lambda v: "%+.1f" % v, "Hz")
        out.append(text)
    return "\n".join(out) + "\n"


def _weight_side():
    return _mass() * _gravity() / 2.0


def span_drop_forces():
    u = _u_drop()
    return "%s against %.0f N a side (the %.1f kg rotor's weight split evenly)" % (
        _list("%.0f N at %g rad/s" % (u * sp * sp, sp) for sp in _drop_speeds()), _weight_side(), _mass())


def region_drop_race():
    mu, rb = _friction(), _res()["radii"]["rb"]
    cap = mu * _weight_side() * rb
    lines = []
    for sp in _drop_speeds():
        rows = [_drop(sp, t) for t in _drags()]
        sit = [r for r in rows if r["regime"] != "backward whirl" and not r["ending"].startswith("forward")]
        roll = [r[DRAG[0]] for r in sit if r["ending"].startswith("rolling")]
        slide = [r[DRAG[0]] for r in sit if r["ending"].startswith("sliding")]
        if roll and slide and max(roll) < min(slide):
            lines.append("%g rad/s: rolling up to %g N m, sliding from %g N m" % (sp, max(roll), min(slide)))
        elif roll or slide:
            lines.append("%g rad/s: %s" % (sp, "; ".join(
                "%s at %s" % (how, _runs_of(ts)) for how, ts in (("rolling", roll), ("sliding", slide)) if ts)))
    both = [(max(r), min(sl)) for r, sl in _race_changes()]
    where = ""
    if both:
        lo, hi = max(b[0] for b in both), min(b[1] for b in both)
        where = " The change from rolling to sliding falls %s that value%s." % (
            "at or below" if hi <= cap else "at or above" if lo >= cap else "around",
            "" if len({b for b in both}) > 1 else (", between %g and %g N m at every speed where both appear" % (lo, hi)))
    return ("Where the rotor sits or bounces without whirling, the race decides how: %s. The friction torque the "
            "rotor's weight can put on a race is mu (m g / 2) R_b = %g x %.0f N x %.2f mm = %.2f N m (the two "
            "retainers' loads are not measured apart).%s\n") % ("; ".join(lines), mu, _weight_side(), rb * 1e3, cap, where)


def _race_changes():
    out = []
    for sp in _drop_speeds():
        sit = [r for r in (_drop(sp, t) for t in _drags()) if r["regime"] != "backward whirl"
               and not r["ending"].startswith("forward")]
        roll = [r[DRAG[0]] for r in sit if r["ending"].startswith("rolling")]
        slide = [r[DRAG[0]] for r in sit if r["ending"].startswith("sliding")]
        if roll and slide and max(roll) < min(slide):
            out.append((roll, slide))
    return out


def _whirl_point():
    """The convergence point whose 0.8 s and 1.6 s runs both whirl backward: 190 rad/s, 10 N m first."""
    for k in ("190 10", "250 10"):
        if _run(k)["regime"] == "backward whirl" and _run(k + " 1.6")["regime"] == "backward whirl":
            return k
    fail("a backward whirl at 0.8 s that lasts to 1.6 s among the checked points (190 and 250 rad/s, 10 N m)")


def span_drop_mechanism():
    k = _whirl_point()
    s = _run(k)
    n = max(s["retainer_mean_normal_force"])
    mu, rb = _friction(), _res()["radii"]["rb"]
    sp, t = k.split()
    if mu * n * rb <= float(t):
        fail("the whirling rotor's friction torque exceeds the race's drag")
    return ("a mean normal force of %.1f kN a retainer at %s rad/s and %s N m, `retainer_mean_normal_force` of the single "
            "run, makes the friction torque mu N R_b = %.0f N m, against the %s N m of drag" % (n / 1e3, sp, t, mu * n * rb, t))


def span_drop_drag_force():
    t = max(_drags())
    return "%.0f N at %g N m" % (t / _res()["radii"]["rb"], t)


def span_drop_whirl_speeds():
    sp = sorted({r["speed"] for r in _rows("study-drop") if r["regime"] == "backward whirl"})
    no = [x for x in _drop_speeds() if x not in sp]
    return "at %s rad/s and not at %s rad/s" % (_list("%g" % x for x in sp), _list("%g" % x for x in no) or "none")


def region_drop_whirl_freq():
    rows = _rows("study-drop")
    parts = []
    rub = [r for r in rows if r["regime"] == "rub" and not r["ending"].startswith("forward")]
    if rub:
        parts.append("where the rotor sits (rub, %d points) it is %s" % (
            len(rub), _span([r["ending_whirl_frequency"] for r in rub], lambda v: "%+.1f" % v, "Hz")))
    fwd = [r for r in rows if r["ending"].startswith("forward")]
    if fwd:
        parts.append("the forward rubs (%s) are at %s, the spin at %s" % (
            "; ".join("%g rad/s at %s" % (sp, _runs_of([r[DRAG[0]] for r in fwd if r["speed"] == sp]))
                      for sp in sorted({r["speed"] for r in fwd})),
            _span([r["ending_whirl_frequency"] for r in fwd], lambda v: "%.1f" % v, "Hz"),
            _span([r["final_speed"] / (2 * math.pi) for r in fwd], lambda v: "%.1f" % v, "Hz")))
    bw = [r for r in rows if r["regime"] == "backward whirl"]
    if bw:
        parts.append("the backward whirls are at %s" % _span([r["ending_whirl_frequency"] for r in bw], lambda v: "%.1f" % v, "Hz"))
    for sp in _drop_speeds():
        b = [r for r in rows if r["speed"] == sp and r["regime"] == "bounce" and not r["ending"].startswith("forward")]
        if b:
            parts.append("the bounces at %g rad/s creep at %s while in contact" % (
                sp, _span([r["ending_whirl_frequency"] for r in b], lambda v: "%+.1f" % v, "Hz")))
    return "In the table: " + "; ".join(parts) + ".\n"


def region_drop_rolling():
    k = _whirl_point()
    rs, rb, c = _res()["radii"]["rs"], _res()["radii"]["rb"], _c()
    sp, t = k.split()
    out = []
    ratios = []
    for key, label in ((k, "at 0.8 s"), (k + " 1.6", "run to 1.6 s")):
        s = _run(key)
        om, races = s["final_speed"], s["retainer_race_speed"]
        wb = sum(races) / len(races)
        pred = -(rs * om - rb * wb) / c / (2 * math.pi)
        ratios += [w / (rs * om / rb) for w in races]
        out.append("%s, Omega = %.1f rad/s and races at %s rad/s give -(%g x %.1f - %g x %.1f) / %g = %.0f Hz, against "
                   "%.1f Hz measured over the last %.3f s (the dry-whip limit at that spin: %.0f Hz)" % (
                       label, om, " and ".join("%.1f" % w for w in races), rs, om, rb, wb, c, pred,
                       s["ending_whirl_frequency"], s["ending_window"], -rs * om / c / (2 * math.pi)))
    if any(abs(_run(x)["ending_whirl_frequency"]) > 0.3 * rs * _run(x)["final_speed"] / c / (2 * math.pi)
           for x in (k, k + " 1.6")):
        fail("the whirls are far slower than the dry whip")
    healthy = _drop(float(sp), "0.02")
    if not _run(k + " 1.6")["final_speed"] < _run(k)["final_speed"] < healthy["final_speed"]:
        fail("the backward whirl brakes the rotor: slower at 0.8 s than on the healthy race, slower still by 1.6 s")
    return ("Checked on the point at %s rad/s and %s N m (single runs, `touchdown run --json`, race speeds "
            "`retainer_race_speed` at the end): %s. The races turn at %s of the no-whirl rolling speed R_s Omega / R_b. "
            "The backward whirl also brakes the rotor: it ends at %.1f rad/s at 0.8 s against %.1f rad/s on the healthy "
            "race (0.02 N m), and at %.1f rad/s by 1.6 s.\n") % (
        sp, t, "; ".join(out), _span(ratios, lambda v: "%.0f" % (100 * v), "%"), _run(k)["final_speed"],
        healthy["final_speed"], _run(k + " 1.6")["final_speed"])


def span_drop_dry_whip():
    rs, c = _res()["radii"]["rs"], _c()
    sp = float(_whirl_point().split()[0])  # the whirl region_drop_rolling checks
    return "-%.0f times the spin: %.0f Hz at %g rad/s" % (rs / c, -rs * sp / c / (2 * math.pi), sp)


def region_drop_peak():
    parts, ratios = [], []
    for sp in _drop_speeds():
        rows = [_drop(sp, t) for t in _drags()]
        calm = [r for r in rows if r["regime"] != "backward whirl"]
        bw = [r for r in rows if r["regime"] == "backward whirl"]
        text = "%g rad/s: %s" % (sp, _span([r["peak_housing_force"] / 1e3 for r in calm], lambda v: "%.1f" % v, "kN"))
        if bw:
            mean = sum(r["peak_housing_force"] for r in calm) / len(calm) if calm else None
            text += " without whirl, %s in backward whirl (%s)" % (
                _list("%.1f" % (r["peak_housing_force"] / 1e3) for r in bw) + " kN", _list("%g N m" % r[DRAG[0]] for r in bw))
            if mean:
                ratios += [r["peak_housing_force"] / mean for r in bw]
        parts.append(text)
    if not ratios or min(ratios) <= 1.0:
        fail("backward whirl raises the peak housing force above the mean of the same speed's points without whirl")
    times = "; ".join("%s at %g rad/s and %s N m (%s)" % (_g(_run("%g %s" % k)["peak_time"], 2) + " s", k[0], k[1],
                                                            _run("%g %s" % k)["regime"]) for k in CONVERGE)
    return ("Peak housing force by speed: %s. Backward whirl raises it %s times the mean of the same speed's points "
            "without whirl. When the peak comes, in the single runs: %s.\n") % (
        "; ".join(parts), _span(ratios, lambda v: "%.1f" % v), times)


def _pctg(x):
    """A relative change in percent: two significant digits, no exponent."""
    p = 100.0 * x
    return "%.0f" % p if abs(p) >= 10 else "%.2g" % p


def _cell(s, ref=None):
    text = "%s (%s), %.0f N" % (s["regime"], s["ending"], s["peak_housing_force"])
    if ref is not None:
        d = s["peak_housing_force"] / ref["peak_housing_force"] - 1.0
        text += " (same)" if abs(d) < 5e-7 else " (%s%s %%)" % ("+" if d > 0 else "", _pctg(d))
    return text


def region_drop_converge():
    lines = ["| speed, drag | study: 0.8 s, rtol 1e-7 | 1.6 s | rtol 1e-8, atol 1e-11 |", "|---|---|---|---|"]
    for sp, t in CONVERGE:
        k = "%g %s" % (sp, t)
        a = _run(k)
        tight = _cell(_run(k + " tight"), a)
        if k + " tight 1.6" in _res()["runs"]:
            tight += "; to 1.6 s at these tolerances: " + _cell(_run(k + " tight 1.6"), a)
        lines.append("| %g rad/s, %s N m | %s | %s | %s |" % (sp, t, _cell(a), _cell(_run(k + " 1.6"), a), tight))
    lines += ["", "and, at the tighter tolerances only (0.8 s; the study's column is the sweep's row):", "",
              "| speed, drag | study: 0.8 s, rtol 1e-7 | rtol 1e-8, atol 1e-11 |", "|---|---|---|"]
    for sp, t in CONVERGE_TIGHT_ONLY:
        row = _drop(sp, t)
        lines.append("| %g rad/s, %s N m | %s | %s |" % (sp, t, _cell(row), _cell(_run("%g %s tight" % (sp, t)), row)))
    same = [k for k in CONVERGE if _run("%g %s" % k)["ending"] != _drop(*k)["ending"]
            or abs(_run("%g %s" % k)["peak_housing_force"] - _drop(*k)["peak_housing_force"]) > 1e-6 * _drop(*k)["peak_housing_force"]]
    note = ("Each single run at 0.8 s gives its sweep row's `ending` and peak housing force." if not same else
            "The single runs at 0.8 s of %s differ from their sweep rows." % _list("%g rad/s, %s N m" % k for k in same))
    return "\n".join(lines) + "\n\n" + note + " Command: `%s`, with `--set end_time=1.6` or `--set 'solver=%s'`.\n" % (
        _res()["runs"]["190 10"]["command"], TIGHT)


def _checks():
    """Per checked point: (label, [(variant, summary)]) with the study's result first."""
    out = []
    for sp, t in CONVERGE:
        k = "%g %s" % (sp, t)
        v = [("0.8 s", _run(k)), ("1.6 s", _run(k + " 1.6")), ("rtol 1e-8", _run(k + " tight"))]
        if k + " tight 1.6" in _res()["runs"]:
            v.append(("rtol 1e-8 to 1.6 s", _run(k + " tight 1.6")))
        out.append(("%g rad/s, %s N m" % (sp, t), v))
    for sp, t in CONVERGE_TIGHT_ONLY:
        out.append(("%g rad/s, %s N m" % (sp, t), [("0.8 s", _drop(sp, t)), ("rtol 1e-8", _run("%g %s tight" % (sp, t)))]))
    return out


def region_drop_verdict():
    held, moved = [], []
    for label, v in _checks():
        regs = [s["regime"] for _, s in v]
        if len(set(regs)) == 1:
            f = [s["peak_housing_force"] for _, s in v]
            held.append("%s (%s; the peak housing force moves by %s %%)" % (
                label, regs[0], _pctg((max(f) - min(f)) / min(f))))
        else:
            moved.append("%s (%s)" % (label, ", ".join("%s %s" % (n, s["regime"]) for n, s in v)))
    whirl_moved = [m for label, v in _checks() for m in [label]
                   if any(s["regime"] == "backward whirl" for _, s in v) and len({s["regime"] for _, s in v}) > 1]
    text = "The regime holds in every check at %s.\n\nThe regime moves at %s.\n" % (
        _list(held) or "no point", _list(moved) or "no point")
    if whirl_moved:
        text += ("\nWhether a draggy race ends in backward whirl is not settled by these runs at %s: a longer run or "
                 "a tenth of the tolerance starts or stops the whirl there. The red tiles at such points mark where "
                 "backward whirl can follow the drop, not where it must; the unbalance phase (below) puts a number "
                 "on it.\n" % _list(whirl_moved))
    else:
        text += "\nEvery backward whirl checked held its regime in every check.\n"
    # the points whose backward whirl's peak force moves by over 10 % between the checks (chosen by the numbers)
    loose, timed, late = [], 0, 0
    for label, v in _checks():
        f = [s["peak_housing_force"] for _, s in v]
        if any(s["regime"] == "backward whirl" for _, s in v) and (max(f) - min(f)) / min(f) > 0.1:
            loose.append("%s: %s" % (label, ", ".join("%.1f kN (%s%s)" % (
                s["peak_housing_force"] / 1e3, n, ", whirl" if s["regime"] == "backward whirl" else "") for n, s in v)))
            for _, s in v:
                if s["regime"] == "backward whirl" and s.get("peak_time") is not None and s.get("ending_window"):
                    timed += 1
                    late += s["peak_time"] >= s["t_reached"] - s["ending_window"]
    if loose:
        text += ("\nThe peak force where backward whirl comes is not a converged number: it moves by over 10 %% between "
                 "the checks at %s. Of the %d such whirls whose single run gives the peak's time, %d peak in the "
                 "stretch the whirl is judged on (the run's last `ending_window`).\n") % ("; ".join(loose), timed, late)
    else:
        text += "\nThe peak force of every backward whirl checked moves by 10 % or less between the checks.\n"
    return text


def region_drop_phase():
    sw = _res()["sweeps"]["phase"]
    rows = _rows("phase")
    lines = ["| drag | phases (of %d) ending in backward whirl | its whirl and peak housing force | the other phases: "
             "regimes, peak housing force |" % len(PHASES), "|---|---|---|---|"]
    ratios, counts = [], {}
    for t in PHASE_DRAGS:
        pts = [r for r in rows if r[DRAG[0]] == float(t)]
        bw = [r for r in pts if r["regime"] == "backward whirl"]
        other = [r for r in pts if r["regime"] != "backward whirl"]
        counts[t] = len(bw)
        phase = lambda r: "%.0f" % math.degrees(r["unbalances[0].phase"])
        if other:
            mean = sum(r["peak_housing_force"] for r in other) / len(other)
            ratios += [r["peak_housing_force"] / mean for r in bw]
        regs = {}
        for r in other:
            regs[r["regime"]] = regs.get(r["regime"], 0) + 1
        lines.append("| %s N m | %d%s | %s | %s; %s |" % (
            t, len(bw), " (%s degrees)" % _list(phase(r) for r in bw) if bw else "",
            "; ".join("%.1f Hz, %.1f kN" % (r["ending_whirl_frequency"], r["peak_housing_force"] / 1e3) for r in bw) or "-",
            ", ".join("%d %s" % (v, k) for k, v in sorted(regs.items())) or "-",
            _span([r["peak_housing_force"] / 1e3 for r in other], lambda v: "%.1f" % v, "kN")))
    draggy = [counts[t] for t in PHASE_DRAGS if float(t) >= 3]
    healthy = counts["0.02"]
    zero = [t for t in PHASE_DRAGS if any(r["regime"] == "backward whirl" and r["unbalances[0].phase"] == 0.0
                                          for r in rows if r[DRAG[0]] == float(t))]
    h = [r["peak_housing_force"] / 1e3 for r in rows if r[DRAG[0]] == 0.02 and r["regime"] != "backward whirl"]
    text = ("At 190 rad/s a draggy race (3 to 10 N m) lets the drop end in backward whirl in %s of %d phases, and the "
            "healthy race in %d. The study's phase, 0, %s. The whirls' peak force is %s times the mean of "
            "the same drag's phases without whirl; the phase alone moves the peak force of a drop without whirl on "
            "the healthy race over %s, so the drop.cfg point is one sample of a spread.\n") % (
        _span(draggy, lambda v: "%d" % v), len(PHASES), healthy,
        ("whirls at %s N m" % _list(zero)) if zero else "ends in backward whirl at none of the drags", _span(ratios, lambda v: "%.1f" % v) if ratios else "-",
        _span(h, lambda v: "%.1f" % v, "kN"))
    return "```\n%s\n```\n\n%s\n\n%s" % (sw["summary_line"], "\n".join(lines), text)


def region_drop_creep():
    rows = _rows("study-drop")
    spin = lambda r: r["final_speed"] / (2 * math.pi)
    fast = [r for r in rows if r["regime"] == "bounce" and r["ending_whirl_frequency"] is not None
            and r["ending_whirl_frequency"] <= -0.05 * spin(r)]
    round_ = [r for r in rows if r["regime"] == "backward whirl" and "bouncing" in r["ending"]]
    if not fast:
        fail("some bounces have contact points that creep backward faster than 5 % of the spin while in contact")
    text = ("In this study %d bounces have contact points that creep backward faster than 5 %% of the spin while in "
            "contact: %s.") % (len(fast), _list("%g rad/s and %g N m (%+.1f Hz)" % (
                r["speed"], r[DRAG[0]], r["ending_whirl_frequency"]) for r in fast))
    if round_:
        text += " In contact under half the stretch too, but carried round: %s, a backward whirl." % _list(
            "%g rad/s and %g N m (%.1f Hz)" % (r["speed"], r[DRAG[0]], r["ending_whirl_frequency"]) for r in round_)
    lines = ["| point | `ending`, `ending_whirl_frequency` | busiest retainer: in contact, angle turned while in contact | "
             "where the contacts are (-90 degrees is straight down) | node's net turn out at the clearance | mean "
             "angle in each 50 ms |", "|---|---|---|---|---|---|"]
    turned = []
    for sp, t in BOUNCES:
        rec = _res()["runs"]["bounce %g %s" % (sp, t)]
        s, m = rec["summary"], rec["measured"]
        b = m["ret%d" % m["busiest"]]
        turned.append(abs(b["turned_in_contact"]))
        # the angle turned in contact over the time in contact, from the 20 kHz table, against the tool's own
        # ending_whirl_frequency (the whirl of the retainer most in contact, docs/output-format.md "Run
        # summary"): a check of both measures
        f = b["turned_in_contact"] / 360.0 / b["contact_time"]
        if s["ending_whirl_frequency"] is None or abs(f - s["ending_whirl_frequency"]) > 0.02 * abs(s["ending_whirl_frequency"]):
            fail("the bounce at %g rad/s and %s N m: its angle turned over its time in contact, %.3f Hz, is the tool's "
                 "ending_whirl_frequency %s Hz (within 2 %%)" % (sp, t, f, s["ending_whirl_frequency"]))
        lines.append("| %g rad/s, %s N m | %s; %.3f Hz | %.3f s of %.3f s, %.0f degrees | %.0f to %.0f degrees | %.0f degrees "
                     "| %s degrees |" % (sp, t, s["ending"], s["ending_whirl_frequency"], b["contact_time"],
                                         m["window"][1] - m["window"][0], b["turned_in_contact"], b["contact_angle_min"],
                                         b["contact_angle_max"], b["node_turned"],
                                         _span([w["mean_angle"] for w in b["windows"]], lambda v: "%.0f" % v)))
    if max(turned) >= 360.0:
        fail("the sampled bounces' contact points turn less than a turn while in contact")
    rec = _res()["runs"]["bounce 190 0.02"]
    m, s = rec["measured"], rec["summary"]
    races = [w["race_speed"] for j in range(2) for w in m["ret%d" % j]["windows"]]
    roll = m["rolling_race_speed"]
    rs, rb, c = _res()["radii"]["rs"], _res()["radii"]["rb"], _c()
    mean_race = sum(races) / len(races)
    om = sum(w["speed"] for w in m["ret0"]["windows"]) / len(m["ret0"]["windows"])
    after = ("\nThese contact points turn %s degrees while in contact, short of the turn the rule asks for. At 190 rad/s "
             "and 0.02 N m the races turn at %s rad/s (50 ms means) against R_s Omega / R_b = %s rad/s: a race at their "
             "mean, %.1f rad/s, makes rolling contact creep at %.1f Hz. Command: `%s`.\n") % (
        _span(turned, lambda v: "%.0f" % v), _span(races, lambda v: "%.1f" % v), _span(roll, lambda v: "%.1f" % v), mean_race,
        (rb * mean_race - rs * om) / c / (2 * math.pi), rec["command"])
    return text + "\n\n" + "\n".join(lines) + "\n" + after


REGIONS = {"sweep-a-commands": region_a_commands, "drop-commands": region_drop_commands,
           "drop-phase-commands": region_phase_commands, "sweep-a-timing": region_a_timing, "sweep-a-solver": region_a_solver, "sweep-a-regimes": region_a_regimes,
           "sweep-a-spread": region_a_spread, "drop-keys": region_drop_keys, "drop-fall": region_drop_fall,
           "drop-timing": region_drop_timing, "drop-rows": region_drop_rows, "drop-race": region_drop_race,
           "drop-whirl-freq": region_drop_whirl_freq, "drop-rolling": region_drop_rolling, "drop-peak": region_drop_peak,
           "drop-converge": region_drop_converge, "drop-verdict": region_drop_verdict, "drop-phase": region_drop_phase,
           "drop-creep": region_drop_creep}
SPANS = {"sweep-record": span_record, "sweep-record-cost": span_record_cost, "sweep-a-contacts": span_a_contacts,
         "sweep-a-point-time": span_a_point_time, "sweep-a-crossings": span_a_crossings,
         "sweep-a-rigid-modes": span_a_rigid_modes, "sweep-a-bending-modes": span_a_bending_modes,
         "sweep-a-boundary": span_a_boundary, "sweep-a-linear": span_a_linear, "sweep-a-free-peaks": span_a_free_peaks,
         "sweep-a-press": span_a_press, "sweep-a-sync": span_a_sync, "sweep-a-peak-force": span_a_peak_force,
         "sweep-a-small-u-force": span_a_small_u_force, "drop-settled": span_drop_settled,
         "drop-windows": span_drop_windows, "drop-220": span_drop_220, "drop-forces": span_drop_forces,
         "drop-mechanism": span_drop_mechanism, "drop-drag-force": span_drop_drag_force,
         "drop-whirl-speeds": span_drop_whirl_speeds, "drop-dry-whip": span_drop_dry_whip}

