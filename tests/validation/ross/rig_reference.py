#!/usr/bin/env python3
"""Reference damped natural frequencies of the reference rig from ross-rotordynamics.

The rig of docs/reference-rig.md with
  * Euler-Bernoulli shaft elements (shear_effects=False), rotary inertia and gyroscopics on;
  * the four solid steel discs (m = 10 kg, R = 0.12 m) as ross DiskElements with the inertias of
    their geometry, computed here: t = m/(rho pi R^2), Ip = m R^2/2 = 0.072 kg m^2,
    Id = m (3 R^2 + t^2)/12 = 0.0366675625 kg m^2 (not the rounded 0.036668);
  * the 14.6 kg AMB journals as DiskElements without inertia (Id = Ip = 0): ross's PointMass
    adds its own extra nodes and is meant for bearing supports, not for shaft nodes;
  * each AMB replaced by its lag-free equivalent (tau = 0):
      k_eq = ki kp - ks = 200 * 1e4 - 1e6 = 1e6 N/m, c_eq = ki kd = 200 * 40 = 8000 N s/m,
    as an isotropic ross BearingElement at nodes 3 and 9.

ross 2.x models 6 DOF per node (x, y, z, alpha, beta, theta); its axial and torsional DOFs are
uncoupled from the lateral ones here, so their modes (undamped, and rigid ones that ross drops)
are removed: every ross eigenvalue returned by Rotor.run_modal(sparse=False) is kept only if it
matches (to 1e-9 relative) an eigenvalue of the lateral-only first-order system, formed here
from ross's own assembled M, K, C, G restricted to the DOFs x, y, alpha, beta and solved with
scipy.linalg.eig. Both lists are checked to agree, which also makes sure no lateral mode is lost.

Writes tests/data/rig_ross_reference.csv (the path can be given as the first argument):
  speed_rad_s, mode, sigma_1_s, omega_d_rad_s, zeta, whirl
the first N_MODES lateral modes (omega_d > 0, ascending) at each speed, numbers with 17 digits.
Re-running reproduces the numbers to ~1e-12 (LAPACK round-off), but not always ross's whirl label:
ross calls some modes "mixed" in one run and "forward"/"backward" in another (at rest the pairs are
degenerate and any label is arbitrary). The C test compares labels only where ross gives a pure
sense at a nonzero speed, and compares frequencies and damping ratios everywhere.
Run: python3 tests/validation/ross/rig_reference.py [out.csv]
Needs: pip install ross-rotordynamics 'plotly<6'  (ross 2.3.0 fails to import with plotly 7, which
dropped the 'scattermapbox' template entry ross uses). Not needed by the C build or tests: the
CSV is checked in.
"""
import os
import sys

import numpy as np
import scipy
import scipy.linalg as la

import ross as rs

SPEEDS = (0.0, 90.0, 190.0)  # rad/s: at rest and the paper's cases A and B
N_MODES = 16

# --- rig data (docs/reference-rig.md) ---
E, G_SHEAR, RHO = 2.11e11, 8.1e10, 7810.0
N_ELEMENTS, SHAFT_LENGTH, SHAFT_DIAMETER = 12, 2.0, 0.05
# Solid steel discs given, as in cases/rig.cfg, by mass, outer radius and density; the inertias of
# a uniform cylinder computed here independently of the C library.
DISC_NODES, DISC_MASS, DISC_RADIUS = (1, 5, 7, 11), 10.0, 0.12
DISC_THICKNESS = DISC_MASS / (RHO * np.pi * DISC_RADIUS**2)
DISC_IP = DISC_MASS * DISC_RADIUS**2 / 2.0
DISC_ID = DISC_MASS * (3.0 * DISC_RADIUS**2 + DISC_THICKNESS**2) / 12.0
JOURNAL_NODES, JOURNAL_MASS = (3, 9), 14.6
KS, KI, KP, KD = 1.0e6, 200.0, 1.0e4, 40.0
K_EQ, C_EQ = KI * KP - KS, KI * KD


def build_rotor():
    steel = rs.Material(name="rig_steel", rho=RHO, E=E, G_s=G_SHEAR)
    shaft = [rs.ShaftElement(L=SHAFT_LENGTH / N_ELEMENTS, idl=0.0, odl=SHAFT_DIAMETER, material=steel,
                             shear_effects=False, rotary_inertia=True, gyroscopic=True)
             for _ in range(N_ELEMENTS)]
    disks = [rs.DiskElement(n=n, m=DISC_MASS, Id=DISC_ID, Ip=DISC_IP) for n in DISC_NODES]
    disks += [rs.DiskElement(n=n, m=JOURNAL_MASS, Id=0.0, Ip=0.0) for n in JOURNAL_NODES]
    bearings = [rs.BearingElement(n=n, kxx=K_EQ, cxx=C_EQ) for n in JOURNAL_NODES]
    return rs.Rotor(shaft, disks, bearings)


def lateral_eigenvalues(rotor, speed):
    """Eigenvalues of the lateral-only system from ross's assembled matrices (upper half plane)."""
    ndof_node = rotor.number_dof
    if ndof_node != 6:
        raise SystemExit("expected ross's 6 DOF per node, got %d" % ndof_node)
    nodes = rotor.ndof // ndof_node
    lat = np.array([ndof_node * i + k for i in range(nodes) for k in (0, 1, 3, 4)])
    M = rotor.M(speed)[np.ix_(lat, lat)]
    K = rotor.K(speed)[np.ix_(lat, lat)]
    C = rotor.C(speed)[np.ix_(lat, lat)]
    G = rotor.G()[np.ix_(lat, lat)]
    n = len(lat)
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-la.solve(M, K), -la.solve(M, C + speed * G)]])
    ev = la.eig(A, right=False)
    ev = ev[ev.imag > 0]
    return ev[np.argsort(ev.imag)]


def ross_modes(rotor, speed):
    """ross's own run_modal eigenvalues and whirl labels, lateral ones only."""
    mr = rotor.run_modal(speed, num_modes=6 * rotor.ndof, sparse=False)
    ev = np.asarray(mr.evalues)
    whirl = list(mr.whirl_direction())
    lat = lateral_eigenvalues(rotor, speed)
    out = []
    for s in lat:
        k = int(np.argmin(np.abs(ev - s)))
        if abs(ev[k] - s) > 1e-9 * abs(s):
            raise SystemExit("speed %g: lateral eigenvalue %r has no ross match (nearest %r)" % (speed, s, ev[k]))
        out.append((ev[k], str(whirl[k])))
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "data", "rig_ross_reference.csv")
    rotor = build_rotor()
    rows = []
    for speed in SPEEDS:
        modes = ross_modes(rotor, speed)
        for i, (s, whirl) in enumerate(modes[:N_MODES]):
            zeta = -s.real / abs(s)
            rows.append("%.17g,%d,%.17g,%.17g,%.17g,%s" % (speed, i, s.real, s.imag, zeta, whirl.lower()))
    with open(path, "w") as f:
        f.write("# Reference rig damped natural frequencies from ross-rotordynamics %s "
                "(numpy %s, scipy %s), written by tests/validation/ross/rig_reference.py\n"
                % (rs.__version__, np.__version__, scipy.__version__))
        f.write("# Euler-Bernoulli (shear off), rotary inertia and gyroscopics on; AMBs as lag-free "
                "bearings k = %.17g N/m, c = %.17g N s/m at nodes 3 and 9; journals 14.6 kg without inertia; "
                "discs m = %.17g kg, Ip = %.17g, Id = %.17g kg m^2\n"
                % (K_EQ, C_EQ, DISC_MASS, DISC_IP, DISC_ID))
        f.write("# lateral modes only (ross's axial/torsional modes removed), omega_d > 0, ascending\n")
        f.write("speed_rad_s,mode,sigma_1_s,omega_d_rad_s,zeta,whirl\n")
        f.write("\n".join(rows) + "\n")
    print("wrote %d rows to %s" % (len(rows), path))


if __name__ == "__main__":
    main()
