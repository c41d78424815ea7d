#!/usr/bin/env python3
"""Independent reference of the loop analysis (docs/theory.md, "Sensitivity"), run by
tests/test_loop.c at test time.

Reads the machine the C test wrote (the assembled M, K, C, G, the AMB axes' dofs and gains, the
speed, and the closed-loop state matrix of the existing modal path) and builds the loop here from
the AMB law of docs/reference-rig.md, independently of lib/modal/loop.c:

    M q'' + (C + W G) q' + K q = sum_a e_a (ks x_a + Fc_a),   tau Fc_a' = ki i_a - Fc_a,
    i = K(s) e,   e = -xs,   K(s) = kp + kd s + kint / s   (scipy.signal.freqs).

S_j = [(I + K P)^-1]_jj on a grid, its peak (grid, then scipy.optimize.minimize_scalar between the
grid neighbours), S at the requested frequencies, and the compliance at each AMB axis from the
closed-loop state matrix: x_a / F_a = e_a^T (jw I - A_cl)^-1 [0; M^-1 e_a; 0].

usage: loop_reference.py IN OUT. Needs numpy and scipy: an ImportError fails the test."""
import sys

import numpy as np
import scipy.optimize
import scipy.signal


def read(path):
    d = {"amb": []}
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "amb":
                d["amb"].append([float(x) for x in w[1:]])
            else:
                d[w[0]] = np.array([float(x) for x in w[1:]])
    return d


def plant(d):
    nd = int(d["ndof"][0])
    sq = lambda k: d[k].reshape((nd, nd), order="F")
    M, K, C, G = sq("M"), sq("K").copy(), sq("C"), sq("G")
    amb = d["amb"]
    na = len(amb)
    W = d["omega"][0]
    for a in amb:  # the magnet's negative stiffness: F = ks x at the actuator
        K[int(a[0]), int(a[0])] -= a[2]
    n = 2 * nd + na
    Minv = np.linalg.inv(M)
    A = np.zeros((n, n))
    A[:nd, nd:2 * nd] = np.eye(nd)
    A[nd:2 * nd, :nd] = -Minv @ K
    A[nd:2 * nd, nd:2 * nd] = -Minv @ (C + W * G)
    B = np.zeros((n, na))
    Cs = np.zeros((na, n))
    for j, a in enumerate(amb):
        act, sen, ks, ki, kp, kd, kint, tau = a
        A[nd:2 * nd, 2 * nd + j] = Minv[:, int(act)]
        A[2 * nd + j, 2 * nd + j] = -1.0 / tau
        B[2 * nd + j, j] = ki / tau
        Cs[j, int(sen)] = 1.0
    return A, B, Cs, Minv, nd


def controller(d, w):
    """K(jw) per axis from scipy.signal: kp + kd s + kint / s."""
    out = []
    for a in d["amb"]:
        kp, kd, kint = a[4], a[5], a[6]
        if kint != 0.0:
            _, h = scipy.signal.freqs([kd, kp, kint], [1.0, 0.0], worN=[w])
        else:
            _, h = scipy.signal.freqs([kd, kp], [1.0], worN=[w])
        out.append(h[0])
    return np.diag(out)


def sensitivity(d, sysm, f):
    A, B, Cs, _, _ = sysm
    w = 2 * np.pi * f
    P = Cs @ np.linalg.solve(1j * w * np.eye(A.shape[0]) - A, B)
    Kw = controller(d, w)
    return np.diag(np.linalg.inv(np.eye(P.shape[0]) + Kw @ P))


def peaks(d, sysm):
    grid = np.logspace(np.log10(0.5), np.log10(5000.0), 800)
    s = np.array([np.abs(sensitivity(d, sysm, f)) for f in grid])
    res = []
    for j in range(s.shape[1]):
        k = int(np.argmax(s[:, j]))
        fun = lambda x: -np.abs(sensitivity(d, sysm, np.exp(x))[j])
        r = scipy.optimize.minimize_scalar(fun, bounds=(np.log(grid[k - 1]), np.log(grid[k + 1])),
                                           method="bounded", options={"xatol": 1e-12})
        res.append((-r.fun, np.exp(r.x)) if -r.fun > s[k, j] else (s[k, j], grid[k]))
    return res


def compliance(d, sysm, f):
    _, _, _, Minv, nd = sysm
    Acl = d["Acl"]
    n = int(np.sqrt(Acl.size))
    Acl = Acl.reshape((n, n), order="F")
    out = []
    for a in d["amb"]:
        act = int(a[0])
        b = np.zeros(n)
        b[nd:2 * nd] = Minv[:, act]
        z = np.linalg.solve(2j * np.pi * f * np.eye(n) - Acl, b)
        out.append(z[act])
    return out


def main():
    d = read(sys.argv[1])
    sysm = plant(d)
    with open(sys.argv[2], "w") as out:
        for f in d["freq"]:
            for j, s in enumerate(sensitivity(d, sysm, f)):
                out.write("S %d %.17g %.17g %.17g\n" % (j, f, s.real, s.imag))
            for j, c in enumerate(compliance(d, sysm, f)):
                out.write("X %d %.17g %.17g %.17g\n" % (j, f, c.real, c.imag))
        for j, (p, fp) in enumerate(peaks(d, sysm)):
            out.write("P %d %.17g %.17g\n" % (j, p, fp))


if __name__ == "__main__":
    main()
