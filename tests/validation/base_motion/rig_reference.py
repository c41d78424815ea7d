#!/usr/bin/env python3
"""The reference rig at small amplitude under a housing shock and a housing rotation, against the
linear forced response of its plant, built and integrated here.

    rig_reference.py TOUCHDOWN PLANT_PROBE CASES_DIR

The machine is cases/rig.cfg (PD AMBs with their 100 Hz lag, no gravity, no unbalance) at 190 rad/s,
started at rest. plant_probe (the public API) writes its M, K, C, G and AMB axes in the layout of
tests/validation/control/closed_loop.py, whose `plant` gives the open loop z' = A z + Bu i
(z = [q, v, Fc]); the AMBs' own PD (or PID), i = -(kp xs + kd xs' + kint e), is closed here. The
housing's motion enters as the inertial loads this script builds itself from M, G and the node positions (never from
touchdown's own base-load vectors): with R_x, R_y the unit rigid translations (1 on every node's x
(y) DOF) and T_x, T_y the unit rigid rotations about x, y through z_ref (about x: y_i = -(z_i - z_ref),
theta_i = 1; about y: x_i = z_i - z_ref, phi_i = 1; touchdown/dofs.h's theta = -dy/dz, phi = dx/dz),
    M q'' + (C + Omega G) q' + K q = f_AMB - M R a(t) - M T alpha(t) - Omega G T w(t).
Two runs: (1) a 2 m/s^2, 10 ms half-sine shock along (0.6, -0.8); (2) a half-sine pulse of the
housing's rotation rate, 0.5 rad/s over 0.4 s about the axis (0.6, 0.8) through z_ref = 0.9 m,
which loads the rotor through its inertia (alpha) and its gyroscopic moments (Omega Ip w) alike.

The response is exact: the pulse is the output of an oscillator (s' = nu c, c' = -nu s, nu =
pi/duration, s = sin, c = cos), appended to the state, so the forced system is autonomous and
linear; scipy.linalg.expm of it over each interval between output samples (split at the pulse's
start and end) steps it to round-off. Compared at every sample of `touchdown run`'s CSV: the AMB
sensor nodes 3 and 9 and the retainers (nodes 2 and 10), x and y.

Bound: max |error| / peak < 1e-4. The plant is the same FE model on both sides, so what differs is
the integration: touchdown's IDA at the case's rtol 1e-9, atol 1e-13 m (peaks 3e-5 to 2e-4 m) and
its default BDF order limit 2 gives 1.6e-5 of the peak; at rtol 1e-11 with order 5 the error falls
to 1.4e-8, so it is the integration's and not a difference of model; the expm steps are exact to
~1e-13. A wrong load (sign, lever arm about z_ref, the gyroscopic term's sign or its absence)
changes the response by 1e-2 to 1 of its peak (without the gyroscopic load: 0.25 of it).
"""
import os
import shutil
import subprocess
import sys

import numpy as np
from scipy import linalg

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "control"))
from closed_loop import plant  # noqa: E402
from common import case_dir, compare, run_case, unit  # noqa: E402

BOUND = 1.0e-4
MACHINE = """# written by tests/validation/base_motion/rig_reference.py
@include "rig.cfg"
speed = 190.0;
start = "rest";
solver = { rtol = 1e-9; atol = 1e-13; };
end_time = %(end)s;
output = { sample_rate = 2000.0; nodes = [3, 9]; };
"""
SHOCK = dict(name="shock", end=0.2, amplitude=2.0, duration=0.01, start=0.01, direction=(0.6, -0.8))
ROTATION = dict(name="rotation", end=0.6, rate=0.5, duration=0.4, start=0.02, axis=(0.6, 0.8), reference=0.9)
SENSORS = (3, 9)
RETAINERS = (2, 10)


def read_plant(path):
    """The probe's file: closed_loop.py's layout, then the node positions, the retainers, the
    unbalances, gravity and the AMBs' air gaps (plant_probe.c says how). Returns a dict."""
    tok = open(path).read().split()
    pos = 0

    def take(n):
        nonlocal pos
        out = [float(t) for t in tok[pos:pos + n]]
        pos += n
        return out

    def word(w):
        nonlocal pos
        if tok[pos] != w:
            raise SystemExit("%s: expected %s, read %s" % (path, w, tok[pos]))
        pos += 1

    ndof, naxes, omega = take(3)
    ndof, naxes = int(ndof), int(naxes)
    p = {"ndof": ndof, "omega": omega, "axes": [take(5) for _ in range(naxes)]}
    word("pid")
    kp, kint, kd, _ = take(4)   # the derivative filter: none (the AMB's own law)
    p["gains"] = (kp, kint, kd)
    p["mats"] = [np.array(take(ndof * ndof)).reshape(ndof, ndof) for _ in range(4)]
    word("nodes")
    p["z"] = np.array(take(int(take(1)[0])))
    word("retainers")
    p["retainers"] = [(int(r[0]), r[1]) for r in (take(2) for _ in range(int(take(1)[0])))]
    word("unbalances")
    p["unbalances"] = [(int(u[0]), u[1], u[2]) for u in (take(3) for _ in range(int(take(1)[0])))]
    word("gravity")
    p["gravity"] = take(2)
    word("air_gaps")
    p["air_gaps"] = [(int(a[0]), a[1]) for a in (take(2) for _ in range(int(take(1)[0])))]
    return p


def closed(ndof, omega, axes, gains, mats):
    """The AMBs' own loops closed on closed_loop.plant: i_j = -(kp xs_j + kd xs_j' + kint e_j), with
    e_j' = xs_j appended to the state when kint > 0 (touchdown/model.h's td_amb)."""
    A, Bu = plant(ndof, omega, axes, mats)
    kp, kint, kd = gains
    n = A.shape[0]
    nint = len(axes) if kint > 0.0 else 0
    Acl = np.zeros((n + nint, n + nint))
    Acl[:n, :n] = A
    fb = np.zeros((len(axes), n + nint))
    for j, ax in enumerate(axes):
        sen = int(ax[1])
        fb[j, sen] = -kp
        fb[j, ndof + sen] = -kd
        if nint:
            fb[j, n + j] = -kint
            Acl[n + j, sen] = 1.0
    Acl[:n, :] += Bu @ fb
    return Acl


def rigid_fields(ndof, z, zref):
    """R_x, R_y, T_x, T_y (unit translation, unit rotation about x and y through zref)."""
    R = np.zeros((2, ndof))
    T = np.zeros((2, ndof))
    for i, zi in enumerate(z):
        R[0, 4 * i] = R[1, 4 * i + 1] = 1.0
        T[0, 4 * i + 1] = -(zi - zref)
        T[0, 4 * i + 2] = 1.0
        T[1, 4 * i] = zi - zref
        T[1, 4 * i + 3] = 1.0
    return R, T


def forced(A, ndof, loads, pulse, times):
    """States at `times` of z' = A z + [0; M^-1 (s(t) ls + c(t) lc); 0], s, c the pulse's
    oscillator (on between start and start + duration), from rest; loads = (M, ls, lc)."""
    M, ls, lc = loads
    n = A.shape[0]
    nu = np.pi / pulse["duration"]
    aug = np.zeros((n + 2, n + 2))
    aug[:n, :n] = A
    aug[ndof:2 * ndof, n] = np.linalg.solve(M, ls)
    aug[ndof:2 * ndof, n + 1] = np.linalg.solve(M, lc)
    aug[n, n + 1], aug[n + 1, n] = nu, -nu
    t0, t1 = pulse["start"], pulse["start"] + pulse["duration"]
    cache = {}

    def step(x, dt):
        if dt <= 0.0:
            return x
        key = round(dt, 15)
        if key not in cache:
            cache[key] = linalg.expm(aug * dt)
        return cache[key] @ x

    x, t = np.zeros(n + 2), 0.0
    edges = [(t0, (0.0, 1.0)), (t1, (0.0, 0.0))]   # the oscillator switched on, then off
    out = np.zeros((len(times), n))
    for k, tk in enumerate(times):
        while edges and edges[0][0] <= tk:
            edge, osc = edges.pop(0)
            x = step(x, edge - t)
            x[n], x[n + 1] = osc
            t = edge
        x = step(x, tk - t)
        t = tk
        out[k] = x[:n]
    return out


def write_case(where, cases, spec, housing):
    shutil.copy(os.path.join(cases, "rig.cfg"), where)
    machine = os.path.join(where, "rig_%s_plant.cfg" % spec["name"])
    with open(machine, "w") as f:
        f.write(MACHINE % spec)
    run = os.path.join(where, "rig_%s.cfg" % spec["name"])
    with open(run, "w") as f:
        f.write(MACHINE % spec + housing)
    return machine, run


def check(touchdown, probe, cases, spec, housing, loads_of):
    where = case_dir("base_motion_rig")
    machine, run = write_case(where, cases, spec, housing)
    plant_file = os.path.join(where, "rig_%s_plant.txt" % spec["name"])
    done = subprocess.run([probe, machine, plant_file], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(done.stderr.strip())
    p = read_plant(plant_file)
    ndof = p["ndof"]
    cols = run_case(touchdown, run, os.path.join(where, "rig_%s.csv" % spec["name"]))
    A = closed(ndof, p["omega"], p["axes"], p["gains"], p["mats"])
    states = forced(A, ndof, loads_of(ndof, p["omega"], p["mats"], p["z"]), spec, cols["t"])
    worst = 0.0
    for label, col, node in [("sensor node %d" % n, "n%d" % n, n) for n in SENSORS] + \
            [("retainer %d" % i, "ret%d" % i, n) for i, n in enumerate(RETAINERS)]:
        for d, name in ((0, "x"), (1, "y")):
            worst = max(worst, compare("%s %s %s" % (spec["name"], label, name), cols["%s_%s" % (name, col)],
                                       states[:, 4 * node + d]))
    print("%s: largest error/peak %.3e (bound %.0e)" % (spec["name"], worst, BOUND))
    return worst


def shock_loads(ndof, omega, mats, z):
    M = mats[0]
    R, _ = rigid_fields(ndof, z, 0.0)
    d = unit(SHOCK["direction"])
    a = SHOCK["amplitude"] * (d[0] * R[0] + d[1] * R[1])   # a(t) = a s(t) along d
    return M, -M @ a, np.zeros(ndof)


def rotation_loads(ndof, omega, mats, z):
    M, G = mats[0], mats[3]
    _, T = rigid_fields(ndof, z, ROTATION["reference"])
    e = unit(ROTATION["axis"])
    Tw = ROTATION["rate"] * (e[0] * T[0] + e[1] * T[1])   # w(t) = rate s(t), alpha = rate nu c(t)
    nu = np.pi / ROTATION["duration"]
    return M, -omega * G @ Tw, -nu * (M @ Tw)


def main():
    touchdown, probe, cases = sys.argv[1:4]
    d, e = unit(SHOCK["direction"]), unit(ROTATION["axis"])
    shock = ('housing = { shocks = ( { shape = "half-sine"; amplitude = %r; duration = %r; start = %r; '
             'direction = [%r, %r]; } ); };\n' % (SHOCK["amplitude"], SHOCK["duration"], SHOCK["start"], d[0], d[1]))
    rotation = ('housing = { reference = %r; rotation = ( { shape = "half-sine"; rate = %r; duration = %r; '
                'start = %r; axis = [%r, %r]; } ); };\n'
                % (ROTATION["reference"], ROTATION["rate"], ROTATION["duration"], ROTATION["start"], e[0], e[1]))
    worst = max(check(touchdown, probe, cases, SHOCK, shock, shock_loads),
                check(touchdown, probe, cases, ROTATION, rotation, rotation_loads))
    if not worst < BOUND:
        raise SystemExit("FAILED")


if __name__ == "__main__":
    main()
