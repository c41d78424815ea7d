#!/usr/bin/env python3
"""Independent reference of the sampled loop analysis (docs/theory.md, "Sensitivity"), run by
tests/test_loop.c at test time.

Reads the machine the C test wrote (the assembled M, K, C, G, each AMB axis's dofs and shorthand
gains, the speed) and the sampled law (a PD with a first-order derivative filter, Tustin, a delay
of whole samples, on some axes; the other axes keep their shorthand PID, closed inside the plant)
and builds the sampled-data loop here, independently of lib/modal/loop.c and sampled.c:

    M q'' + (C + W G) q' + K q = sum_a e_a (ks x_a + Fc_a),   tau Fc_a' = ki i_a - Fc_a,
    shorthand axes: i_a = -(kp xs + kd vs + kint e),  e' = xs;   sampled axes: i_a = u_a held,
    plant from u to the sampled sensors: scipy.signal.cont2discrete(..., method="zoh"),
    K(z): the PD's transfer function by scipy.signal.cont2discrete(..., method="bilinear") times
    z^-delay, its response by scipy.signal.dfreqresp.

S_j = [(I + K P_zoh)^-1]_jj at z = e^{jwT} on the requested frequencies and on a grid up to the
Nyquist frequency (its peak: grid, then scipy.optimize.minimize_scalar between the grid
neighbours); the largest |mu| of the closed loop over one sample, built by hand from the
realisations (scipy.signal.tf2ss); and the compliance at each AMB axis at the sample instants
from that closed-loop matrix with the exact forcing of a sinusoidal force over one sample,
int_0^T exp(A (T - s)) b e^{jws} ds = (jwI - A)^-1 (e^{jwT} I - exp(AT)) b.

usage: sampled_loop_reference.py IN OUT. Needs numpy and scipy: an ImportError fails the test."""
import sys

import numpy as np
import scipy.optimize
import scipy.signal

from loop_reference import read


def plant(d):
    """A, Bu (held currents of the sampled axes), Bf (actuator forces), Cs (their sensors), Ca."""
    nd = int(d["ndof"][0])
    sq = lambda k: d[k].reshape((nd, nd), order="F")
    M, K, C, G = sq("M"), sq("K").copy(), sq("C"), sq("G")
    amb, saxes = d["amb"], [int(a) for a in d["saxes"]]
    na = len(amb)
    integ = [j for j, a in enumerate(amb) if a[6] != 0.0]
    for a in amb:
        K[int(a[0]), int(a[0])] -= a[2]
    n = 2 * nd + na + len(integ)
    Minv = np.linalg.inv(M)
    A = np.zeros((n, n))
    A[:nd, nd:2 * nd] = np.eye(nd)
    A[nd:2 * nd, :nd] = -Minv @ K
    A[nd:2 * nd, nd:2 * nd] = -Minv @ (C + d["omega"][0] * G)
    Bu = np.zeros((n, len(saxes)))
    Bf = np.zeros((n, na))
    Cs = np.zeros((len(saxes), n))
    Ca = np.zeros((na, n))
    for j, a in enumerate(amb):
        act, sen, ks, ki, kp, kd, kint, tau = a
        act, sen, row = int(act), int(sen), 2 * nd + j
        A[nd:2 * nd, row] = Minv[:, act]
        A[row, row] = -1.0 / tau
        A[row, sen] -= ki * kp / tau  # the shorthand's command (zero gains on a sampled axis)
        A[row, nd + sen] -= ki * kd / tau
        if kint != 0.0:
            e = 2 * nd + na + integ.index(j)
            A[row, e] -= ki * kint / tau
            A[e, sen] = 1.0
        Bf[nd:2 * nd, j] = Minv[:, act]
        Ca[j, act] = 1.0
        if j in saxes:
            Bu[row, saxes.index(j)] = ki / tau
            Cs[saxes.index(j), sen] = 1.0
    return A, Bu, Bf, Cs, Ca


def law(d):
    """The sampled PD as a discrete transfer function (num, den in z, descending), delay included."""
    rate, delay, kp, kd, fd = d["sampled"]
    wd = 2.0 * np.pi * fd
    num, den, _ = scipy.signal.cont2discrete(([kp / wd + kd, kp], [1.0 / wd, 1.0]), 1.0 / rate, method="bilinear")
    return np.ravel(num), np.concatenate([np.ravel(den), np.zeros(int(delay))])


class Loop:
    def __init__(self, d):
        self.rate = d["sampled"][0]
        self.T = 1.0 / self.rate
        self.A, Bu, self.Bf, self.Cs, self.Ca = plant(d)
        n = self.A.shape[0]
        self.Ad, self.Bd, _, _, _ = scipy.signal.cont2discrete((self.A, Bu, self.Cs, np.zeros((Bu.shape[1],) * 2)),
                                                               self.T, method="zoh")
        self.num, self.den = law(d)
        self.k = scipy.signal.dlti(self.num, self.den, dt=self.T)
        ak, bk, ck, dk = scipy.signal.tf2ss(self.num, self.den)
        ns, nk = Bu.shape[1], ak.shape[0]
        # hand closed loop over one sample: u = Ck xk + Dk e, e = -Cs xp, each sampled axis its own law
        P = np.zeros((n + ns * nk, n + ns * nk))
        P[:n, :n] = self.Ad
        for j in range(ns):
            r = slice(n + j * nk, n + (j + 1) * nk)
            P[:n, :n] -= dk[0, 0] * np.outer(self.Bd[:, j], self.Cs[j])
            P[:n, r] = np.outer(self.Bd[:, j], ck[0])
            P[r, :n] = -np.outer(bk[:, 0], self.Cs[j])
            P[r, r] = ak
        self.P = P
        self.n = n

    def sensitivity(self, f):
        wT = 2.0 * np.pi * f * self.T
        z = np.exp(1j * wT)
        Pz = self.Cs @ np.linalg.solve(z * np.eye(self.n) - self.Ad, self.Bd)
        _, h = scipy.signal.dfreqresp(self.k, w=[wT])
        Kz = h[0] * np.eye(Pz.shape[0])
        return np.diag(np.linalg.inv(np.eye(Pz.shape[0]) + Kz @ Pz))

    def compliance(self, f):
        w = 2.0 * np.pi * f
        z = np.exp(1j * w * self.T)
        N = self.P.shape[0]
        out = []
        for j in range(self.Bf.shape[1]):
            b = np.zeros(N, dtype=complex)
            b[:self.n] = np.linalg.solve(1j * w * np.eye(self.n) - self.A,
                                         (z * np.eye(self.n) - self.Ad) @ self.Bf[:, j])
            x = np.linalg.solve(z * np.eye(N) - self.P, b)
            out.append(self.Ca[j] @ x[:self.n])
        return out

    def peaks(self):
        grid = np.logspace(np.log10(0.5), np.log10(min(5000.0, 0.5 * self.rate)), 800)
        s = np.array([np.abs(self.sensitivity(f)) for f in grid])
        res = []
        for j in range(s.shape[1]):
            k = int(np.argmax(s[:, j]))
            fun = lambda x: -np.abs(self.sensitivity(np.exp(x))[j])
            r = scipy.optimize.minimize_scalar(fun, bounds=(np.log(grid[k - 1]), np.log(grid[min(k + 1, 799)])),
                                               method="bounded", options={"xatol": 1e-12})
            res.append((-r.fun, np.exp(r.x)) if -r.fun > s[k, j] else (s[k, j], grid[k]))
        return res


def main():
    d = read(sys.argv[1])
    lp = Loop(d)
    with open(sys.argv[2], "w") as out:
        for f in d["freq"]:
            for j, s in enumerate(lp.sensitivity(f)):
                out.write("S %d %.17g %.17g %.17g\n" % (j, f, s.real, s.imag))
            for j, c in enumerate(lp.compliance(f)):
                out.write("X %d %.17g %.17g %.17g\n" % (j, f, c.real, c.imag))
        for j, (p, fp) in enumerate(lp.peaks()):
            out.write("P %d %.17g %.17g\n" % (j, p, fp))
        out.write("R 0 %.17g 0\n" % np.max(np.abs(np.linalg.eigvals(lp.P))))


if __name__ == "__main__":
    main()
