#!/usr/bin/env python3
"""The compliant housing (housing.body) against an independent model built here with numpy/scipy.

A rigid rotor (a disc on a stiff, all but massless shaft) on two PD AMBs, in a housing that is a
rigid body on two resilient mounts. The reference is written in ABSOLUTE coordinates, unlike
touchdown's (the rotor relative to the housing, the housing's DOFs appended): the rotor's centre
(X, Y) and tilts (theta, phi), the housing's likewise; each AMB's force acts on the rotor and, opposite,
on the housing, in proportion to their relative displacement at the AMB; each mount holds the
housing to the base. Checked:

  1. `touchdown modal`: the closed loop's eigenvalues (8 pairs: 4 rotor + 4 housing modes) against
     the reference's, relative error < 1e-5 (3.3e-7 measured: the shaft's bending, its lowest mode 1e3 times the
     rigid modes' frequency, and its mass, 1e-7 of the discs', are left out of the reference).
     Its steady unbalance response over the speed grid against the reference's, < 1e-4 (1.1e-5
     measured, near the resonances, where the shaft's bending left out moves the amplitude most;
     without the unbalance's share on the housing it is 1e2).
  2. `touchdown run` from rest under gravity and an unbalance (the machine settles on its AMBs and
     mounts, and the unbalance's force, from outside the machine, shakes the housing too): the
     displacement of the rotor relative to the housing at both AMB nodes, against solve_ivp on the
     reference, max error / peak < 1e-4 at every output sample (the run's solver tolerances are
     1e-9 relative, 1e-13 m absolute: 1.4e-5 measured; at the defaults, 1e-6 and 1e-9 m with BDF
     order 2, it is 3e-3, and it falls with the tolerances: the integration's error, not the model's).
  3. The energy account of an undamped machine (no AMB derivative gain, no mount damping) with an
     unbalance, under the base shock and rotation of check 6: the balance's residual < 1e-4 of the
     largest energy term, the base's work on the housing's mounts among them (every power is booked).
  4. A translating body (no inertia: 2 DOFs) under the same checks 1 and 2, its tilt held; and a
     steel shaft (8 elements) whole and Craig-Bampton reduced with every interior mode kept: the same
     modes to 1e-9 (the body's field on the reduced coordinates).
  5. Check 2 with a retainer's race on a mount in the housing (2 more absolute DOFs in the
     reference): the race's displacement relative to the housing too; and its orbit start without
     an unbalance, the static equilibrium (the races' weight on the housing's mounts included): the
     run stays there, within 1e-6 of the static displacements.
  6. A base shock and rotation (the base moves the mounts), with the race; a prescribed speed ramp
     (the unbalance's tangential force too), both as check 2.
  7. In checks 2, 4, 5 and 6 the run's housing body series (/housing/body_displacement, body_tilt)
     against the reference's housing coordinates, and /nodes/absolute_displacement against the
     reference's absolute rotor displacement at the node (plus the base's own motion in check 6),
     max error / peak < 1e-4 as check 2.

usage: housing_body.py TOUCHDOWN WORKDIR
"""
import json
import os
import re
import subprocess
import sys

import numpy as np
from scipy.integrate import solve_ivp

# ---- the machine (every number the case file gets comes from here) ----
L = 0.4                       # m, shaft length, 2 elements: nodes at z = 0, 0.2, 0.4
Z_NODES = [0.0, 0.2, 0.4]
# three discs at nodes 0, 1, 2 (kg, kg m^2): end discs give the shaft's end rotations an inertia, so
# that the stiff shaft's own modes stay within 1e4 of the rigid ones (a well-conditioned eigenproblem)
DISCS = [(0, 1.0, 0.01, 0.005), (1, 8.0, 0.1, 0.04), (2, 1.0, 0.01, 0.005)]
M_R = sum(d[1] for d in DISCS)
Z_R = sum(d[1] * Z_NODES[d[0]] for d in DISCS) / M_R
ID_R = sum(d[2] + d[1] * (Z_NODES[d[0]] - Z_R) ** 2 for d in DISCS)   # about the centre of mass
IP_R = sum(d[3] for d in DISCS)
KS, KI, KP, KD = 2.0e5, 50.0, 1.0e4, 10.0   # AMB: N/m, N/A, A/m, A s/m
AMB_NODES = [0, 2]
M_H, I_H, Z_H = 20.0, 0.5, 0.25     # housing: kg, kg m^2, m
MOUNTS = [(0.0, 2.0e6, 300.0), (0.5, 1.0e6, 200.0)]   # (z m, k N/m, c N s/m)
RACE = (2, 0.5, 4.0e5, 40.0)  # a retainer's race on a mount at node 2: (node, kg, N/m, N s/m)
CLEARANCE = 1.0e-2            # m, wide: no contact
# the base motion (touchdown/housing.h): a half-sine shock and a half-sine pitch-and-yaw rate pulse
Z_REF = 0.3                   # m, the point the base rotates about
SHOCK = (20.0, 0.01, 0.005, (0.6, -0.8))    # m/s^2, s, s, direction
ROT = (0.5, 0.02, 0.01, (0.8, 0.6))         # rad/s, s, s, axis (about x, about y)
G = 9.81
OMEGA = 200.0
U = 2.0e-4                    # kg m, unbalance at node 1 (phase 0): its force shakes the housing too
RAMP = 600.0                  # rad/s^2, a prescribed speed ramp from OMEGA
END = 0.1
RATE = 2000.0


def case_text(inertia=I_H, kd=KD, mount_c=True, unbalance=0.0, energy=False, race=False, start="rest",
              base=False, ramp=False, name="hb"):
    mounts = ", ".join("{ position = %r; stiffness = %r; damping = %r; }" % (z, k, c if mount_c else 0.0)
                       for z, k, c in MOUNTS)
    ambs = ", ".join("{ node = %d; ks = %r; ki = %r; kp = %r; kd = %r; tau = 0.0; force_capacity = 1.0e4; }"
                     % (n, KS, KI, KP, kd) for n in AMB_NODES)
    discs = ", ".join("{ node = %d; mass = %r; Id = %r; Ip = %r; }" % d for d in DISCS)
    inertia_key = "inertia = %r; " % inertia if inertia > 0.0 else ""
    ret = ("retainers = ( { node = %d; clearance = %r; shaft_radius = 0.025; friction = 0.1; race = { mass = %r; }; mount = { stiffness = %r; "
           "damping = %r; }; } );\n" % (RACE[0], CLEARANCE, RACE[1], RACE[2], RACE[3])) if race else ""
    motion = ("reference = %r; shocks = ( { shape = \"half-sine\"; amplitude = %r; duration = %r; start = %r; "
              "direction = [%r, %r]; } ); rotation = ( { shape = \"half-sine\"; rate = %r; duration = %r; "
              "start = %r; axis = [%r, %r]; } ); " % ((Z_REF,) + SHOCK[:3] + SHOCK[3] + ROT[:3] + ROT[3])) if base else ""
    ramp_text = "speed_ramp = ( { time = 0.0; speed = %r; }, { time = %r; speed = %r; } );\n" % (
        OMEGA, END, OMEGA + RAMP * END) if ramp else ""
    unb = "unbalances = ( { node = 1; magnitude = %r; phase = 0.0; } );\n" % unbalance if unbalance > 0 else ""
    return f"""description = "rigid rotor on two PD AMBs in a housing on two mounts";
shaft = {{ length = {L!r}; elements = 2; outer_diameter = 0.05;
  material = {{ E = 2.1e15; G = 8.1e14; density = 1.0e-3; }}; }};
discs = ( {discs} );
ambs = ( {ambs} );
{unb}{ret}{ramp_text}gravity = {{ g = {0.0 if base else G!r}; }};
housing = {{ {motion}body = {{ mass = {M_H!r}; {inertia_key}centre = {Z_H!r}; mounts = ( {mounts} ); }}; }};
speed = {OMEGA!r};
start = "{start}";
end_time = {END!r};
energy = {"true" if energy else "false"};
solver = {{ rtol = 1e-9; atol = 1e-13; }};
output = {{ csv = "{name}.csv"; sample_rate = {RATE!r}; nodes = [0, 2]; }};
"""


def steel(text, reduction=None):
    """The case on a steel shaft of 8 elements (node n becomes 4 n, interior nodes between), whole or
    as a Craig-Bampton reduced rotor (its boundary: the nodes with parts) below `reduction` Hz."""
    text = text.replace("elements = 2;", "elements = 8;")
    text = text.replace("E = 2.1e15; G = 8.1e14; density = 1.0e-3;", "E = 2.11e11; G = 8.1e10; density = 7810.0;")
    text = re.sub(r"node = (\d+)", lambda m: "node = %d" % (4 * int(m.group(1))), text)
    text = text.replace("nodes = [0, 2]", "nodes = [0, 8]")
    text += "modal = { speed_steps = 3; };\n"   # the modes at the case speed are compared: a short Campbell
    return text + ("reduction = { cutoff = %r; };\n" % reduction if reduction else "")


def point(z, zb):
    """Displacement (x, y) at axial z of a rigid body (X, Y, theta, phi) about zb (dofs.h)."""
    d = z - zb
    return np.array([[1.0, 0.0, 0.0, d], [0.0, 1.0, -d, 0.0]])


def reference(tilting=True, kd=KD, mount_c=True, race=False):
    """M, C (with the gyroscopics at OMEGA), K, the weight f, and the maps to the relative
    displacement at the AMB nodes (and of the race), in absolute coordinates [rotor 4 | housing 4 |
    race x, y]."""
    n = 10 if race else 8
    M = np.diag([M_R, M_R, ID_R, ID_R, M_H, M_H, I_H, I_H] + ([RACE[1]] * 2 if race else []))
    K, C = np.zeros((n, n)), np.zeros((n, n))
    C[2, 3], C[3, 2] = OMEGA * IP_R, -OMEGA * IP_R        # Id theta'' + Omega Ip phi' ...
    ke, ce = KI * KP - KS, KI * kd
    rel = []
    for node in AMB_NODES:
        z = Z_NODES[node]
        B = np.hstack([point(z, Z_R), -point(z, Z_H), np.zeros((2, n - 8))])   # relative at the AMB
        K += ke * B.T @ B
        C += ce * B.T @ B
        rel.append(B)
    for z, k, c in MOUNTS:
        B = np.hstack([np.zeros((2, 4)), point(z, Z_H), np.zeros((2, n - 8))])
        K += k * B.T @ B
        C += (c if mount_c else 0.0) * B.T @ B
    f = np.zeros(n)
    f[1], f[5] = -M_R * G, -M_H * G
    if race:   # the race on its mount to the housing at its node
        B = np.hstack([np.zeros((2, 4)), -point(Z_NODES[RACE[0]], Z_H), np.eye(2)])
        K += RACE[2] * B.T @ B
        C += RACE[3] * B.T @ B
        f[9] = -RACE[1] * G
        rel.append(B)
    keep = [i for i in range(n) if tilting or i not in (6, 7)]   # a translating housing: no tilt
    P = np.eye(n)[:, keep]
    return P.T @ M @ P, P.T @ C @ P, P.T @ K @ P, P.T @ f, [b @ P for b in rel]


def state_matrix(M, C, K):
    n = M.shape[0]
    Mi = np.linalg.inv(M)
    return np.block([[np.zeros((n, n)), np.eye(n)], [-Mi @ K, -Mi @ C]])


def run(cmd, cwd):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(cmd), p.returncode, p.stderr.strip()))
    return p.stdout


def number(text):
    try:
        return float(text)
    except ValueError:   # a word column (a mode's whirl)
        return float("nan")


def modal_section(path, name):
    """The rows of section `name` of a `touchdown modal` CSV file, as lists of numbers."""
    rows, section = [], None
    with open(path) as fh:
        for line in fh:
            if line.startswith("# section:"):
                section = line.split(":", 1)[1].strip()
                continue
            if section != name or line.startswith("#") or not line.strip() or not line[0] in "-0123456789":
                continue
            rows.append([number(c) for c in line.split(",")])
    return rows


def modal_roots(tool, cfg, work):
    run([tool, "modal", "-q", cfg, "-o", cfg[:-4] + "-modal"], work)
    return np.array([complex(r[1], r[2]) for r in modal_section(os.path.join(work, cfg[:-4] + "-modal.csv"),
                                                                  "modes")])


def check_unbalance_response(cfg, work):
    """`touchdown modal`'s steady unbalance response (its file from check_modes) at every speed of its
    grid against (K - w^2 M + i w (C(w))) X = U w^2 (1, -i) on the rotor's centre, the whole machine
    (absolute coordinates) solved, the AMB nodes' displacement relative to the housing compared."""
    rows = modal_section(os.path.join(work, cfg[:-4] + "-modal.csv"), "unbalance_response")
    worst, count = 0.0, 0
    for speed, node, xa, _, ya, _ in (r[:6] for r in rows):
        if node not in AMB_NODES or speed == 0.0:
            continue
        global OMEGA
        keep, OMEGA = OMEGA, speed
        M, C, K, _, rel = reference(True)
        OMEGA = keep
        F = np.zeros(M.shape[0], complex)
        F[:4] = point(Z_NODES[1], Z_R).T @ (U * speed ** 2 * np.array([1.0, -1.0j]))
        X = np.linalg.solve(K - speed ** 2 * M + 1j * speed * C, F)
        r = rel[AMB_NODES.index(int(node))] @ X
        worst = max(worst, abs(xa - abs(r[0])) / abs(r[0]), abs(ya - abs(r[1])) / abs(r[1]))
        count += 1
    print("%s: steady unbalance response at the AMB nodes, %d speeds x nodes, largest relative error %.3e" % (
        cfg, count, worst))
    if not (count > 0 and worst < 1e-4):
        sys.exit("FAIL %s: the unbalance response differs from the reference (%.3e)" % (cfg, worst))


def check_modes(tool, cfg, work, tilting):
    M, C, K, _, _ = reference(tilting)
    ev = np.linalg.eigvals(state_matrix(M, C, K))
    ref = np.sort_complex(ev[ev.imag > 0])
    got = modal_roots(tool, cfg, work)
    got = np.sort_complex(got[np.abs(got) < 10 * np.abs(ref).max()])   # the stiff shaft's roots aside
    if len(got) != len(ref):
        sys.exit("FAIL %s: %d modes, the reference has %d: %s vs %s" % (cfg, len(got), len(ref), got, ref))
    err = np.max(np.abs(got - ref) / np.abs(ref))
    print("%s: %d closed-loop modes, largest relative eigenvalue error %.3e" % (cfg, len(ref), err))
    if not err < 1e-5:
        sys.exit("FAIL %s: eigenvalues differ:\n%s\n%s" % (cfg, got, ref))


def check_reduced(tool, full, red, work):
    """A flexible (steel) shaft in the housing, whole and Craig-Bampton reduced with every interior
    mode kept (the reduction exact, docs/case-format.md): the same closed-loop modes to 1e-9, so the
    body's field on the reduced coordinates (its boundary DOFs, the modal ones 0) is right."""
    a, b = (np.sort_complex(modal_roots(tool, c, work)) for c in (full, red))
    a, b = a[np.abs(a) < 2e4], b[np.abs(b) < 2e4]   # below 3 kHz
    err = np.max(np.abs(a - b) / np.abs(a)) if len(a) == len(b) and len(a) >= 8 else float("inf")
    print("%s vs %s: %d closed-loop modes below 3 kHz, largest relative difference %.3e" % (full, red, len(a), err))
    if not err < 1e-9:
        sys.exit("FAIL %s: the reduced rotor's modes differ: %s vs %s" % (red, a, b))


def read_csv(path):
    with open(path) as fh:
        head = fh.readline().strip().split(",")
    return head, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def check_response(tool, cfg, work, tilting, race=False):
    run([tool, "run", "-q", cfg], work)
    head, data = read_csv(os.path.join(work, cfg[:-4] + ".csv"))
    t = data[:, 0]
    M, C, K, f, rel = reference(tilting, race=race)
    n = M.shape[0]
    A = state_matrix(M, C, K)
    Mi = np.linalg.inv(M)
    Pu = np.zeros((n, 2))
    Pu[:4] = point(Z_NODES[1], Z_R).T   # the unbalance acts on the rotor only (absolute coordinates)

    def rhs(tt, x):
        fu = U * OMEGA ** 2 * np.array([np.cos(OMEGA * tt), np.sin(OMEGA * tt)])
        return A @ x + np.concatenate([np.zeros(n), Mi @ (f + Pu @ fu)])

    x0 = np.zeros(2 * n)
    if race:   # the race starts resting on its mount under its weight (the rest start's)
        x0[n - 1] = -RACE[1] * G / RACE[2]
    sol = solve_ivp(rhs, (0.0, t[-1]), x0, t_eval=t, method="DOP853", rtol=1e-11, atol=1e-15)
    columns = ["%s_n%d [m]" % (a, node) for node in AMB_NODES for a in "xy"] + (["xr_ret0 [m]", "yr_ret0 [m]"]
                                                                               if race else [])
    worst = 0.0
    for i, col in enumerate(columns):
        r = (rel[i // 2] @ sol.y[:n])[i % 2]
        peak = np.max(np.abs(r))
        if peak > 0.0:
            worst = max(worst, np.max(np.abs(data[:, head.index(col)] - r)) / peak)
    print("%s: %s relative to the housing from rest, max error / peak %.3e over %d samples" % (
        cfg, "the AMB nodes and the race" if race else "the AMB nodes", worst, len(t)))
    if not worst < 1e-4:
        sys.exit("FAIL %s: the response differs from the reference (max error / peak %.3e)" % (cfg, worst))
    check_body_outputs(cfg, head, data, sol.y[:n], tilting)


def check_body_outputs(cfg, head, data, x, tilting, base=False):
    """The housing body's own series (its centre's x, y relative to the base and its tilts) against the
    reference's housing coordinates x = [rotor 4 | housing 4 or 2 | ...] (n, samples), and the nodes'
    absolute displacement: the reference's rotor field at the node (its coordinates are absolute in
    the base's frame), plus with base motion the base's own rigid motion from the run's /housing
    columns (checked against closed forms elsewhere)."""
    hz = x[4:8] if tilting else np.vstack([x[4:6], np.zeros((2, x.shape[1]))])
    worst = 0.0
    for i, col in enumerate(["x_housing_body [m]", "y_housing_body [m]", "tiltx_housing_body [rad]",
                             "tilty_housing_body [rad]"]):
        peak = np.max(np.abs(hz[i]))
        if peak > 0.0:
            worst = max(worst, np.max(np.abs(data[:, head.index(col)] - hz[i])) / peak)
        elif np.any(data[:, head.index(col)] != 0.0):
            worst = float("inf")
    for node in (0, 2):
        z = Z_NODES[node]
        ref = point(z, Z_R) @ x[:4]
        if base:
            col = lambda name: data[:, head.index(name)]
            ref = ref + np.vstack([col("x_housing [m]") + (z - Z_REF) * col("roty_housing [rad]"),
                                   col("y_housing [m]") - (z - Z_REF) * col("rotx_housing [rad]")])
        for k, a in enumerate("xy"):
            got = data[:, head.index("%s_abs_n%d [m]" % (a, node))]
            worst = max(worst, np.max(np.abs(got - ref[k])) / np.max(np.abs(ref[k])))
    print("%s: the housing body's series and the nodes' absolute displacement, max error / peak %.3e" % (cfg, worst))
    if not worst < 1e-4:
        sys.exit("FAIL %s: the housing body's outputs differ from the reference (max error / peak %.3e)" % (cfg,
                                                                                                        worst))


def half_sine(p, t):
    """A half-sine pulse (amplitude, duration, start) at t, and its rate of change."""
    a, d, t0 = p[:3]
    tau = t - t0
    if tau < 0.0 or tau >= d:
        return 0.0, 0.0
    return a * np.sin(np.pi * tau / d), a * np.pi / d * np.cos(np.pi * tau / d)


def check_base(tool, cfg, work):
    """The base moves the mounts: a translational shock a(t) and a rotation rate w(t) about x and y
    through Z_REF. The reference is written in the base's frame for each body on its own: every
    body's d'Alembert load -m (a + alpha x (z - Z_REF)) at its centre and -I alpha on its tilts, the
    rotor's gyroscopic moment of its absolute tilt rate (the base's rate w added to its own); the
    AMBs act between rotor and housing, the mounts between housing and base. Gravity off (the
    housing frame's gravity is not rotated by the base: touchdown/housing.h). A race on its mount
    takes its own d'Alembert load."""
    run([tool, "run", "-q", cfg], work)
    head, data = read_csv(os.path.join(work, cfg[:-4] + ".csv"))
    t = data[:, 0]
    M, C, K, f, rel = reference(True, race=True)
    n = M.shape[0]
    A = state_matrix(M, C, K)
    Mi = np.linalg.inv(M)
    ds, dr = np.array(SHOCK[3]) / np.hypot(*SHOCK[3]), np.array(ROT[3]) / np.hypot(*ROT[3])

    def load(tt):
        acc = half_sine(SHOCK, tt)[0] * ds
        w, alpha = (v * dr for v in half_sine(ROT, tt))
        out = np.zeros(n)
        for base, m, inertia, zb in ((0, M_R, ID_R, Z_R), (4, M_H, I_H, Z_H)):
            d = zb - Z_REF   # about x: y = -d angle; about y: x = d angle
            out[base:base + 4] -= np.array([m * (acc[0] + d * alpha[1]), m * (acc[1] - d * alpha[0]),
                                            inertia * alpha[0], inertia * alpha[1]])
        d = Z_NODES[RACE[0]] - Z_REF   # the race on its mount, translating only
        out[8:10] -= RACE[1] * np.array([acc[0] + d * alpha[1], acc[1] - d * alpha[0]])
        out[2] -= OMEGA * IP_R * w[1]   # Id theta'' + Omega Ip (phi' + w_y) ...
        out[3] += OMEGA * IP_R * w[0]   # Id phi'' - Omega Ip (theta' + w_x) ...
        return out

    sol = solve_ivp(lambda tt, x: A @ x + np.concatenate([np.zeros(n), Mi @ load(tt)]), (0.0, t[-1]),
                    np.zeros(2 * n), t_eval=t, method="DOP853", rtol=1e-11, atol=1e-15, max_step=1e-3)
    worst = 0.0
    for i, col in enumerate(["%s_n%d [m]" % (a, node) for node in AMB_NODES for a in "xy"] + ["xr_ret0 [m]",
                                                                                             "yr_ret0 [m]"]):
        r = (rel[i // 2] @ sol.y[:n])[i % 2]
        worst = max(worst, np.max(np.abs(data[:, head.index(col)] - r)) / np.max(np.abs(r)))
    print("%s: base shock and rotation, the AMB nodes and the race relative to the housing, max error / peak %.3e "
          "over %d "
          "samples" % (cfg, worst, len(t)))
    if not worst < 1e-4:
        sys.exit("FAIL %s: the base-excited response differs from the reference (max error / peak %.3e)" % (cfg,
                                                                                                          worst))
    check_body_outputs(cfg, head, data, sol.y[:n], True, base=True)


def check_ramp(tool, cfg, work):
    """A prescribed speed ramp Omega(t) = OMEGA + RAMP t: the gyroscopic term follows it, and the
    unbalance's force U (Omega^2 cos phi + RAMP sin phi, Omega^2 sin phi - RAMP cos phi) with
    phi = OMEGA t + RAMP t^2 / 2 acts on the whole machine."""
    run([tool, "run", "-q", cfg], work)
    head, data = read_csv(os.path.join(work, cfg[:-4] + ".csv"))
    t = data[:, 0]
    M, C, K, f, rel = reference(True)
    n = M.shape[0]
    Mi = np.linalg.inv(M)
    Gy = np.zeros((n, n))
    Gy[2, 3], Gy[3, 2] = IP_R, -IP_R
    C0 = C - OMEGA * Gy
    Pu = np.zeros((n, 2))
    Pu[:4] = point(Z_NODES[1], Z_R).T

    def rhs(tt, x):
        w, ph = OMEGA + RAMP * tt, OMEGA * tt + 0.5 * RAMP * tt * tt
        fu = U * np.array([w * w * np.cos(ph) + RAMP * np.sin(ph), w * w * np.sin(ph) - RAMP * np.cos(ph)])
        acc = Mi @ (f + Pu @ fu - K @ x[:n] - (C0 + w * Gy) @ x[n:])
        return np.concatenate([x[n:], acc])

    sol = solve_ivp(rhs, (0.0, t[-1]), np.zeros(2 * n), t_eval=t, method="DOP853", rtol=1e-11, atol=1e-15)
    worst = 0.0
    for i, col in enumerate(["%s_n%d [m]" % (a, node) for node in AMB_NODES for a in "xy"]):
        r = (rel[i // 2] @ sol.y[:n])[i % 2]
        worst = max(worst, np.max(np.abs(data[:, head.index(col)] - r)) / np.max(np.abs(r)))
    print("%s: a speed ramp, the AMB nodes relative to the housing, max error / peak %.3e over %d samples" % (
        cfg, worst, len(t)))
    if not worst < 1e-4:
        sys.exit("FAIL %s: the ramp's response differs from the reference (max error / peak %.3e)" % (cfg, worst))


def check_static(tool, cfg, work):
    """The orbit start of an unforced machine is its static equilibrium under gravity, the races'
    weight on the housing's mounts included: the run stays there."""
    run([tool, "run", "-q", cfg], work)
    head, data = read_csv(os.path.join(work, cfg[:-4] + ".csv"))
    M, C, K, f, rel = reference(True, race=True)
    x = np.linalg.solve(K, f)
    columns = ["%s_n%d [m]" % (a, node) for node in AMB_NODES for a in "xy"] + ["xr_ret0 [m]", "yr_ret0 [m]"]
    worst, scale = 0.0, 0.0
    for i, col in enumerate(columns):
        r = (rel[i // 2] @ x)[i % 2]
        scale = max(scale, abs(r))
        worst = max(worst, np.max(np.abs(data[:, head.index(col)] - r)))
    print("%s: the orbit start at rest under gravity, largest departure from the static reference %.3e m "
          "(of %.3e m)" % (cfg, worst, scale))
    if not worst < 1e-6 * scale:
        sys.exit("FAIL %s: the start is not the static equilibrium" % cfg)


def check_energy(tool, cfg, work):
    out = json.loads(run([tool, "run", "-q", "--json", cfg], work))
    e = out["energy"] if "energy" in out else out
    terms = {k: v for k, v in e.items() if isinstance(v, (int, float)) and k != "residual"}
    scale = max(abs(v) for v in terms.values())
    res = abs(e["residual"])
    print("%s: energy residual %.3e J of the largest term %.3e J (%.2e)" % (cfg, res, scale, res / scale))
    if not (scale > 0.0 and res < 1e-4 * scale and abs(e["housing_work"]) > 1e-2 * scale):
        sys.exit("FAIL %s: the energy account does not close: %s" % (cfg, e))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    tool, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    cases = {"hb4.cfg": case_text(unbalance=U, name="hb4"), "hb2.cfg": case_text(inertia=0.0, unbalance=U, name="hb2"),
             "hb_steel.cfg": steel(case_text(unbalance=U, name="hb_steel")),
             "hb_steel_reduced.cfg": steel(case_text(unbalance=U, name="hb_steel_reduced"), 1.0e7),
             "hb_race.cfg": case_text(unbalance=U, race=True, name="hb_race"),
             "hb_base.cfg": case_text(base=True, race=True, name="hb_base"),
             "hb_ramp.cfg": case_text(unbalance=U, ramp=True, name="hb_ramp"),
             "hb_static.cfg": case_text(race=True, start="orbit", name="hb_static"),
             "hb_energy.cfg": case_text(kd=0.0, mount_c=False, unbalance=1e-4, energy=True, base=True,
                                        name="hb_energy")}
    for name, text in cases.items():
        with open(os.path.join(work, name), "w") as fh:
            fh.write(text)
    check_modes(tool, "hb4.cfg", work, True)
    check_unbalance_response("hb4.cfg", work)
    check_response(tool, "hb4.cfg", work, True)
    check_reduced(tool, "hb_steel.cfg", "hb_steel_reduced.cfg", work)
    check_modes(tool, "hb2.cfg", work, False)
    check_response(tool, "hb2.cfg", work, False)
    check_response(tool, "hb_race.cfg", work, True, race=True)
    check_base(tool, "hb_base.cfg", work)
    check_ramp(tool, "hb_ramp.cfg", work)
    check_static(tool, "hb_static.cfg", work)
    check_energy(tool, "hb_energy.cfg", work)
    print("ok")


if __name__ == "__main__":
    main()
