#!/usr/bin/env python3
"""touchdown modal's API 617 report of the rig (cases/rig.cfg) against ROSS (ross-rotordynamics).

The machine is read from the case file itself (libconf) and built twice: as a touchdown case (the
file included, the AMBs given again without their force lag: tau = 0, so that each axis is exactly
the spring k = ki kp - ks and damper c = ki kd that ROSS's BearingElement holds) and as a ROSS rotor
(Euler-Bernoulli elements with rotary inertia and gyroscopics, the discs' Ip and Id from their
geometry as docs/case-format.md computes them, the laminations as discs without inertia). Compared:
  - every critical speed touchdown lists, against the crossing of the same whirl branch of ROSS's
    eigenvalues with the 1x line (scipy's brentq on ROSS's run_modal);
  - the log decrement of the lowest vibration modes at the case speed (from ROSS's eigenvalues by
    ROSS's own formula, run_modal: 2 pi zeta / sqrt(1 - zeta^2), zeta = -Re s / |s|);
  - each response peak with an amplification factor: its speed, amplitude and half-power speeds
    found again on ROSS's unbalance response (run_unbalance_response, scipy's minimize_scalar and
    brentq), hence AF = N_c / (N_2 - N_1), and the separation margin and the API 617 requirement
    recomputed from those;
  - the static reactions under gravity against ROSS's run_static bearing forces.
Exit 0 when everything agrees within the tolerances below, 1 otherwise (printing every number).
usage: ross_rig.py TOUCHDOWN RIG_CFG WORKDIR
"""
import csv
import math
import os
import subprocess
import sys
import warnings

warnings.filterwarnings("ignore")
# one BLAS thread: the matrices are 156 x 156, and a thread pool on busy cores only costs time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import libconf  # noqa: E402
import numpy as np  # noqa: E402
import ross as rs  # noqa: E402
from scipy.optimize import brentq, minimize_scalar  # noqa: E402

SPEED = 150.0  # rad/s, the case speed: modes and log decrements there
UNBALANCE = (1, 1.0e-4)  # node, kg m
OPERATING = (250.0, 400.0)  # rad/s
NODES = [1, 3]  # the unbalanced disc and an AMB sensor
G = 9.8065  # m/s^2, ROSS's (Rotor.gravitational_force)
# relative tolerances: the same finite elements give the same roots and responses to rounding; a
# peak's speed (a flat maximum) is located only to a fraction of its width N_c / AF by either
# minimiser (about sqrt(eps) of the amplitude), so its tolerance is TOL_PEAK / AF, and AF and SM
# inherit it
TOL_CRITICAL = 1e-9
TOL_LOGDEC = 1e-9
TOL_PEAK = 2e-5  # over AF: peak speed, AF, SM
TOL_CURVE = 1e-9  # peak amplitude, half-power speeds
TOL_FORCE = 1e-9  # static reactions


def amb_override(ambs):
    """The rig's AMBs again, with tau = 0 in place of their bandwidth (the lag switched off)."""
    out = []
    for a in ambs:
        keys = [f"{k} = {str(v).lower() if isinstance(v, bool) else repr(v)};" for k, v in a.items()
                if k not in ("bandwidth", "tau")]
        out.append("{ " + " ".join(keys) + " tau = 0.0; }")
    return "ambs=( " + ", ".join(out) + " )"


def run_touchdown(touchdown, rig_cfg, work):
    case = os.path.join(work, "rig-nolag.cfg")
    with open(case, "w") as f:
        f.write(f"@include \"{os.path.relpath(rig_cfg, work)}\"\n")  # libconfig: relative to the file
        f.write(f"speed = {SPEED};\nend_time = 0.1;\nstart = \"rest\";\n")
        f.write(f"gravity = {{ g = {G}; }};\n")
        f.write(f"unbalances = ( {{ node = {UNBALANCE[0]}; magnitude = {UNBALANCE[1]}; phase = 0.0; }} );\n")
        f.write("modal = { speed_min = 0.0; speed_max = 700.0; speed_steps = 71; modes = 8;\n")
        f.write(f"  operating_speed_min = {OPERATING[0]}; operating_speed_max = {OPERATING[1]};\n")
        f.write(f"  response_nodes = {NODES}; }};\n")
    cfg = libconf.load(open(rig_cfg))
    out = os.path.join(work, "rig-nolag-modal")
    subprocess.run([touchdown, "modal", "-q", "--set", amb_override(cfg["ambs"]), "-o", out, "--hdf5", "", case],
                   check=True)
    return read_sections(out + ".csv")


def read_sections(path):
    """The modal CSV file's sections: name -> list of rows (dicts by column)."""
    sections, name, header = {}, None, None
    for line in open(path):
        line = line.rstrip("\n")
        if line.startswith("# section: "):
            name, header = line[len("# section: "):], None
            sections[name] = []
        elif not line or line.startswith("#"):
            continue
        elif header is None:
            header = line.split(",")
        else:
            sections[name].append(dict(zip(header, next(csv.reader([line])))))
    return sections


def ross_rotor(rig_cfg):
    cfg = libconf.load(open(rig_cfg))
    sh, mat = cfg["shaft"], cfg["shaft"]["material"]
    steel = rs.Material(name="rig_steel", rho=mat["density"], E=mat["E"], G_s=mat["G"])
    ne = sh["elements"]
    shaft = [rs.ShaftElement(L=sh["length"] / ne, idl=sh["inner_diameter"], odl=sh["outer_diameter"], material=steel,
                             n=i, shear_effects=False, rotary_inertia=True, gyroscopic=True) for i in range(ne)]
    discs = []
    for d in cfg["discs"]:  # docs/case-format.md, discs: t = m / (rho pi R^2), Ip = m R^2 / 2, Id = m (3 R^2 + t^2) / 12
        m, r = d["mass"], d["radius"]
        t = m / (d["density"] * math.pi * r * r)
        discs.append(rs.DiskElement(n=d["node"], m=m, Ip=m * r * r / 2, Id=m * (3 * r * r + t * t) / 12))
    discs += [rs.DiskElement(n=p["node"], m=p["mass"], Id=0.0, Ip=0.0) for p in cfg["point_masses"]]
    bearings = [rs.BearingElement(n=a["node"], kxx=a["ki"] * a["kp"] - a["ks"], cxx=a["ki"] * a["kd"])
                for a in cfg["ambs"]]
    return rs.Rotor(shaft, discs, bearings)


def lateral_modes(rotor, speed):
    """ROSS's lateral vibration modes at `speed`: (eigenvalue, whirl, log decrement), omega_d > 1."""
    # sparse=False: scipy.linalg.eig of the whole state matrix, every root, whatever num_modes; num_modes
    # only sets how many of them ROSS turns into mode shapes for its plots (orbits by numba), none here
    m = rotor.run_modal(speed, num_modes=0, sparse=False)
    nd = rotor.number_dof  # per node: x, y, z, alpha, beta, theta
    out = []
    for i, s in enumerate(m.evalues):
        v = m.evectors[: rotor.ndof, i].reshape(-1, nd)
        x, y = v[:, 0], v[:, 1]
        if s.imag <= 1.0 or np.linalg.norm(np.abs(v[:, [0, 1]])) <= np.linalg.norm(np.abs(v[:, [2, 5]])):
            continue  # not a lateral vibration mode
        # the whirl sense of touchdown/modal.h, h = -2 Im(conj(X) Y) / (|X|^2 + |Y|^2), amplitude-weighted
        h = -2.0 * np.sum(np.imag(np.conj(x) * y)) / np.sum(np.abs(x) ** 2 + np.abs(y) ** 2)
        zeta = -s.real / abs(s)  # ROSS's run_modal: its log_dec holds the first half of the roots only
        out.append((s, "forward" if h > 0 else "backward", 2 * np.pi * zeta / np.sqrt(1 - zeta**2)))
    return out


def ross_critical(rotor, nc, whirl):
    """The speed where ROSS's `whirl` branch nearest to nc crosses the 1x line (brentq within +-10 %)."""
    def gap(w):
        modes = [s.imag for s, wh, _ in lateral_modes(rotor, w) if wh == whirl]
        return min(modes, key=lambda wd: abs(wd - nc)) - w
    return brentq(gap, 0.9 * nc, 1.1 * nc, rtol=1e-12)


def major(rotor, w, node):
    """ROSS's orbit major semi-axis (m) at `node` and speed w: |X + iY|/2 + |X - iY|/2."""
    r = rotor.run_unbalance_response(node=UNBALANCE[0], unbalance_magnitude=UNBALANCE[1], unbalance_phase=0.0,
                                     frequency=[w])
    x, y = r.forced_resp[rotor.number_dof * node, 0], r.forced_resp[rotor.number_dof * node + 1, 0]
    return 0.5 * (abs(x + 1j * y) + abs(x - 1j * y))


def ross_peak(rotor, node, nc, af):
    """Peak speed, amplitude and half-power speeds of ROSS's curve near nc (af: a guess of its AF)."""
    pk = minimize_scalar(lambda w: -major(rotor, w, node), bounds=(0.95 * nc, 1.05 * nc), method="bounded",
                         options={"xatol": 1e-9 * nc})
    wc, amp = pk.x, -pk.fun
    level = amp / math.sqrt(2.0)
    sides = []
    for d in (-1, 1):  # bracket each half-power speed by steps of 1/(2 AF) of the peak's (touchdown's AF)
        step = d * 0.5 * nc / af
        w = wc
        while major(rotor, w + step, node) > level:
            w += step
        sides.append(brentq(lambda v: major(rotor, v, node) - level, w, w + step, rtol=1e-12))
    return wc, amp, sides[0], sides[1]


def required_margin(af, above):
    """API 617 7th ed. 2.6.2.10 (docs/api617.md), written out again: none below AF 2.5."""
    if af < 2.5:
        return 0.0
    f = 17.0 * (1.0 - 1.0 / (af - 1.5))
    return min(26.0, 10.0 + f) if above else min(16.0, f)


class Check:
    def __init__(self):
        self.bad = 0

    def __call__(self, what, ours, ref, tol):
        err = abs(ours - ref) / abs(ref)
        ok = err <= tol
        self.bad += not ok
        print(f"{'ok ' if ok else 'BAD'} {what}: touchdown {ours:.10g}, ROSS {ref:.10g}, rel. diff {err:.2e} "
              f"(tol {tol:g})")


def compare_critical(check, rotor, sec):
    for row in sec["critical_speeds"]:
        nc, whirl = float(row["speed_rad_s"]), row["whirl"]
        check(f"critical speed ({whirl})", nc, ross_critical(rotor, nc, whirl), TOL_CRITICAL)


def compare_log_dec(check, rotor, sec):
    ross = lateral_modes(rotor, SPEED)
    for row in sec["modes"][:12]:
        if float(row["zeta"]) >= 0.99:
            continue
        s = complex(float(row["sigma_1_s"]), float(row["omega_d_rad_s"]))
        ref = min(ross, key=lambda m: abs(m[0] - s))
        check(f"log decrement of the mode at {s.imag:.6g} rad/s", float(row["log_decrement"]), ref[2], TOL_LOGDEC)


def compare_peaks(check, rotor, sec):
    n = 0
    for row in sec["response_peaks"]:
        if row["amplification"] == "nan":
            continue
        node, nc = int(row["node"]), float(row["speed_rad_s"])
        wc, amp, w1, w2 = ross_peak(rotor, node, nc, float(row["amplification"]))
        af = wc / (w2 - w1)
        lo, hi = OPERATING
        below, above = 100.0 * (lo - wc) / lo, 100.0 * (wc - hi) / hi
        tol = TOL_PEAK / max(af, 1.0)
        check(f"node {node} peak speed", nc, wc, tol)
        check(f"node {node} peak amplitude", float(row["amplitude_m"]), amp, TOL_CURVE)
        check(f"node {node} N_1", float(row["speed_low_rad_s"]), w1, TOL_CURVE)
        check(f"node {node} N_2", float(row["speed_high_rad_s"]), w2, TOL_CURVE)
        check(f"node {node} AF", float(row["amplification"]), af, tol)
        check(f"node {node} SM", float(row["margin_percent"]), max(below, above), tol * 100)
        req = required_margin(af, above > below)
        if req > 0.0:
            check(f"node {node} required SM", float(row["required_margin_percent"]), req, tol)
        n += 1
    return n


def compare_static(check, rotor, sec):
    rotor.run_static()
    forces = rotor.bearing_forces_nodal
    for row in sec["static_reactions"]:
        ref = forces[f"node_{row['node']}"]
        check(f"static reaction at node {row['node']}", float(row["Fy_N"]), ref, TOL_FORCE)


def main():
    touchdown, rig_cfg, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    sec = run_touchdown(touchdown, rig_cfg, work)
    rotor = ross_rotor(rig_cfg)
    print(f"ROSS {rs.__version__}: rig of {rotor.m:.6g} kg")
    check = Check()
    compare_critical(check, rotor, sec)
    compare_log_dec(check, rotor, sec)
    peaks = compare_peaks(check, rotor, sec)
    compare_static(check, rotor, sec)
    if len(sec["critical_speeds"]) < 2 or peaks < 1:
        print(f"BAD: too little to compare ({len(sec['critical_speeds'])} critical speeds, {peaks} peaks with an AF)")
        check.bad += 1
    print(f"{check.bad} disagreements")
    return 1 if check.bad else 0


if __name__ == "__main__":
    sys.exit(main())
