"""bench/led.sh's table: the answers of runs r2, r4, r8 (24, 48, 96 elements) in DIR, read from their
--json summaries and their HDF5 samples, with the 48 -> 96 change; '> 2 %' marks what moves more."""
import json
import os
import sys

import h5py
import numpy as np

d = sys.argv[1]
R = [2, 4, 8]
js = {r: json.load(open(os.path.join(d, "r%d.json" % r))) for r in R}
rows = [(k, [js[r][k] for r in R]) for k in ["peak_housing_force", "total_impulse", "friction_work",
                                            "contact_time", "final_speed", "peak_normal_force", "settle_time"]]
LOSSES = ["damping_loss", "contact_loss", "drag_loss", "impact_loss"]
if all(js[r]["energy"] for r in R):
    rows += [("energy " + k, [js[r]["energy"][k] for r in R]) for k in LOSSES]
    rows.append(("energy lost (the four)", [sum(js[r]["energy"][k] for k in LOSSES) for r in R]))
for k in ["impulse", "friction_work", "contact_time", "mean_normal_force", "rms_normal_force", "whirl_frequency",
          "contacts", "touch_and_go", "peak_normal_force", "load_ratio", "peak_sliding_velocity",
          "peak_friction_power", "peak_pv", "peak_contact_stress", "peak_race_speed", "race_speed",
          # the heat (with a retainers[].thermal) and the life (with a bearing.dynamic_rating): in the
          # summary only when the case gives them
          "drag_work", "heat", "peak_temperature_rise", "peak_thermal_growth",
          "load_cycles", "damage", "drops_to_failure"]:
    if js[2].get("retainer_" + k) is None:
        continue
    for i in range(len(js[2]["retainer_" + k])):
        rows.append(("retainer %d %s" % (i, k), [js[r]["retainer_" + k][i] for r in R]))
for i in range(len(js[2]["sensor_peak_displacement"])):
    rows.append(("AMB %d sensor peak displacement" % i, [js[r]["sensor_peak_displacement"][i] for r in R]))


def window_mean(r, what, i, w):
    """Time average over the window w of a sampled quantity (trapezoid over the samples)."""
    with h5py.File(os.path.join(d, "r%d.h5" % r), "r") as f:
        t = f["time"][:]
        if what == "friction power":  # F_t opposes v_s: -F_t v_s >= 0 is the heat rate
            v = -f["retainers/friction_force"][:, i] * f["retainers/sliding_velocity"][:, i]
        else:
            v = f["retainers/" + what.replace(" ", "_")][:, i]
    m = (t >= w[0]) & (t <= w[1])
    return float(np.trapz(v[m], t[m]) / (t[m][-1] - t[m][0]))


t_end = js[2]["t_reached"]
first = js[2]["first_contact_time"] or 0.0
for w in [(first, t_end), (first, first + 0.25 * (t_end - first)), (first + 0.5 * (t_end - first), t_end)]:
    for what in ["normal force", "friction power", "race speed"]:
        for i in range(len(js[2]["retainer_impulse"])):
            rows.append(("retainer %d mean %s %.3g-%.3g s" % (i, what, w[0], w[1]),
                         [window_mean(r, what, i, w) for r in R]))


def change(a, b):
    return 100.0 * (b - a) / abs(a) if a not in (None, 0) and b is not None else float("nan")


print("%-46s %15s %15s %15s %10s" % ("answer", "24 elements", "48 elements", "96 elements", "48->96 %"))
for name, v in rows:
    c = change(v[1], v[2])
    print("%-46s %15s %15s %15s %10.3f%s" % (name, *("%.8g" % x if x is not None else "null" for x in v), c,
                                              "  > 2 %" if not abs(c) <= 2.0 else ""))
