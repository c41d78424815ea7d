#!/usr/bin/env bash
# cases/drop.cfg through the tool, end to end: the rig levitated by PID AMBs under gravity, both
# AMBs fail at 0.05 s, the rotor falls onto its ball-bearing retainers and coasts down on a free
# spin. Physics checked, not only presence: centred before the failure (integral action), the
# spin slows before the failure as its drag and the unbalance's steady orbit (the harmonic solve)
# say, and faster on the retainers, the races spin up from rest, the energy balance
# closes with the spin's kinetic energy and drag in it, the summary says how the drop ended, the
# files carry the rotor speed per sample, and the retainers' networks hold the heat they receive.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/drop.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, h5py_python, finish

t "$work/run" run --json -o "$work/run/drop" --set end_time=0.4 --set energy=true "$src/cases/drop.cfg"
check "drop to 0.4 s: exit 0" test "$rc" = 0
out=$work/run/.out
check "the summary: slowed, an ending, the AMB load, the energy balance" python3 - "$out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["complete"] is True
assert 180.0 < d["final_speed"] < 190.0, d["final_speed"]     # friction and drag slow the free spin
assert d["ending"] not in ("undetermined", "free (no contact)", "recovered"), d["ending"]
assert 0.0 < d["peak_amb_load"] < 1.0                         # levitated within capacity
assert d["first_contact_time"] > 0.05                          # falls after the failure
assert d["shock_outcome"] == "drop", d["shock_outcome"]        # on its retainers with both AMBs off
e = d["energy"]
held = e["kinetic"] + e["elastic"]
lost = e["damping_loss"] + e["contact_loss"] + e["drag_loss"] + e["impact_loss"]
assert abs(e["residual"]) < 1e-5 * held and abs(e["residual"]) < 1e-2 * lost, e
print("ok", d["final_speed"], d["ending"], d["peak_amb_load"], e["residual"] / held, e["residual"] / lost)
PY
py=$(h5py_python)
if [ -z "$py" ]; then
    echo "skip: no python3 with h5py (scripts/setup.sh installs python3-h5py): HDF5 speed dataset not checked"
else
t "$work/modal" modal -q -o "$work/modal/drop" --set "modal.response_speeds=[190.0]" "$src/cases/drop.cfg"
check "the modal analysis of the drop case: exit 0" test "$rc" = 0
check "the HDF5 file: speed per sample, centred before the failure, races spun up" "$py" - "$work/run/drop.h5" "$work/modal/drop.h5" <<'PY'
import sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
t, w = f["time"][:], f["speed"][:]
assert f["speed"].attrs["units"] in (b"rad/s", "rad/s")
# before the failure the drag and the unbalance brake the spin: J w' = -T - c w + U w^2 (Y_r + X_i) / 2,
# the last term the mean drag of the unbalance mass on the spin for the steady orbit (X, Y) of its
# node, which the modal analysis' harmonic solve gives independently (J: the rotor's polar inertia,
# shaft rho pi L R^4 / 2 and four discs of 0.072 kg m^2; T = 0.1 N m, c = 1e-4 N m s/rad)
m = h5py.File(sys.argv[2], "r")
g = m["harmonic/0"]
z = m["modes/node_z"][:]                                   # the unbalance sits at z = 1/6 m (rig node 1)
k = list(g["node"][:]).index(int(np.argmin(np.abs(z - 1.0 / 6.0))))
X = g["x_amp"][k] * np.exp(1j * g["x_phase"][k])
Y = g["y_amp"][k] * np.exp(1j * g["y_phase"][k])
J, T, c, U = 7810.0 * np.pi * 2.0 * 0.025 ** 4 / 2.0 + 4 * 0.072, 0.1, 1e-4, 0.005
before = t < 0.05
drop = w[0] - w[before][-1]
want = (T + c * 190.0 - U * 190.0 ** 2 * (Y.real + X.imag) / 2.0) / J * t[before][-1]
assert w[0] == 190.0 and abs(drop - want) < 1e-3 * want, (drop, want)
assert w[-1] < w[before][-1] - 0.1                             # the retainers' friction brakes it
nodes = list(f["nodes/node"][:])
d = f["nodes/displacement"][:]
amb = [nodes.index(n) for n in f.attrs["amb_nodes"]]
# PID: the orbit at the AMBs turns round the centre: its mean over the last whole revolution
# before the failure (167 samples at 5 kHz, 190 rad/s) is within a sample's share of the orbit
rev = (t >= 0.05 - 2.0 * np.pi / 190.0) & before
mean = np.abs(d[rev][:, amb, :].mean(axis=0)).max()
radius = np.hypot(d[rev][:, amb, 0], d[rev][:, amb, 1]).max()
assert mean < 0.02 * radius, (mean, radius)
assert f["retainers/race_speed"][:, 0].max() > 50.0            # the races spun up from rest
# the whirl rate per sample integrates to the whirl angle swept (unwrapped) over the run: the
# node's orbit keeps clear of the centre (the angle is defined), on the steady orbit and after
th = np.unwrap(f["retainers/whirl_angle"][:, 0])
wr = f["retainers/whirl_rate"][:, 0]
r = np.hypot(f["retainers/x"][:, 0], f["retainers/y"][:, 0])
i0 = 0
assert r.min() > 5e-5, r.min()
swept, integral = th[-1] - th[i0], np.trapz(wr[i0:], t[i0:])
assert abs(swept) > 1.0 and abs(integral - swept) < 0.01 * abs(swept), (swept, integral)
print("ok", drop, want, mean, w[-1], f["retainers/race_speed"][-1, :], swept, integral)
PY
# The retainers' heat (docs/theory.md, "Thermal retainers"; the networks of drop.cfg): the drag work
# against the race speed series integrated independently (T_0 + c_b w) w on the 5 kHz samples, the
# heat as friction plus drag work, the networks' energy at the end (C_r T_r + C_h T_h + G_ha times
# the integral of T_h) against the heat, the peak rise against the series.
check "the heat: drag work from the race speed, heat held by the networks, the peak rise" "$py" - "$work/run/drop.h5" "$out" <<'PY'
import json, sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
d = json.load(open(sys.argv[2]))
t = f["time"][:]
w = f["retainers/race_speed"][:]
Tr, Th = f["retainers/race_temperature"][:], f["retainers/housing_temperature"][:]
assert f["retainers/race_temperature"].attrs["units"] in (b"K", "K")
fw, dw, heat = (np.array(f.attrs["retainer_" + k]) for k in ("friction_work", "drag_work", "heat"))
peak = np.array(f.attrs["retainer_peak_temperature_rise"])
growth = np.array(f.attrs["retainer_peak_thermal_growth"])
assert d["retainer_heat"] == list(heat) and d["retainer_peak_temperature_rise"] == list(peak)
Cr, Ch, Gha, alpha, Rb = 76.0, 1100.0, 2.0, 1.2e-5, 0.02575
for k in range(2):
    drag = np.trapz((0.02 * np.sign(w[:, k]) + 1e-5 * w[:, k]) * w[:, k], t)
    held = Cr * Tr[-1, k] + Ch * Th[-1, k] + Gha * np.trapz(Th[:, k], t)
    assert dw[k] > 0.1 and abs(drag - dw[k]) < 1e-4 * dw[k], (k, drag, dw[k])
    assert heat[k] == fw[k] + dw[k], (k, heat[k], fw[k], dw[k])
    assert abs(held - heat[k]) < 1e-6 * heat[k], (k, held, heat[k])
    assert Tr[0, k] == 0.0 and Tr[:, k].min() >= 0.0 and peak[k] >= Tr[:, k].max() * (1 - 1e-9), (k, peak[k])
    assert abs(growth[k] - alpha * Rb * peak[k]) <= 1e-15 * growth[k], (k, growth[k])
    print("ok", k, drag, dw[k], held, heat[k], peak[k], Tr[:, k].max())
PY
# The run ended while the AMB force still rose: its peak is the force at the end (the last sample's),
# never one of the integrator's step beyond end_time (once 831.2 N at 1.05e-3 s for 829.7 N at 1e-3 s).
t "$work/short" run -q -o "$work/short/drop" --set end_time=0.001 "$src/cases/drop.cfg"
check "drop to 1 ms: exit 0" test "$rc" = 0
check "drop to 1 ms: the peak AMB force and its time are those reached, at the end" "$py" - "$work/short/drop.h5" <<'PY'
import sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
t, F = f["time"][:], f["ambs/force"][:]
end, peak, when = f.attrs["t_end"], f.attrs["peak_amb_force"], f.attrs["peak_amb_time"]
last = np.abs(F[-1]).max()
assert t[-1] == end and np.all(np.diff(np.abs(F).max(axis=(1, 2))) > 0), t  # still rising at the end
assert when <= end, (when, end)
assert when == end and peak == last, (peak, last)
print("ok", end, when, peak, last)
PY
fi
finish
