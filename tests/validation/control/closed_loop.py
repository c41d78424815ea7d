#!/usr/bin/env python3
"""Closed-loop eigenvalues of an AMB rotor with a linear controller on every AMB axis, built here
from the plant's matrices alone (an independent reference for touchdown's closed-loop analysis).

Input (argv[1], text, written by tests/test_sim_controller.c):
  line 1:  ndof naxes omega
  naxes lines:  actuator_dof sensor_dof ks ki tau     (one per AMB axis)
  line:    the law: "leadlag_notch gain zero(Hz) pole(Hz) notch_frequency(Hz) width(Hz) depth"
           or "pid_tustin kp kd derivative_filter(Hz) sample_rate(Hz)"
  then M, K, C, G: ndof rows of ndof numbers each.

leadlag_notch, continuous: the lead-lag g (1 + s/wz)/(1 + s/wp) followed by the notch
(s^2 + 2 zz wn s + wn^2)/(s^2 + 2 zp wn s + wn^2), zp = width/(2 f), zz = depth zp.
pid_tustin, sampled: kp + kd s/(1 + s/wd) mapped by Tustin's rule (scipy.signal.cont2discrete,
"bilinear") at the sample rate, the plant discretised by zero-order hold over one period (its own
matrix exponential, scipy.linalg.expm of the augmented matrix), the current held from each sample
to the next; eigenvalues mu of the loop over one period are reported as s = ln(mu) rate.
Either law acts on the error e = -xs and commands the current i; the amplifier's force Fc follows
ki i through the lag tau Fc' = ki i - Fc (tau = 0: Fc = ki i), the bearing adds ks x at the
actuator. The transfer functions go through scipy.signal.tf2ss (its own realisation, not
touchdown's), the loop is closed by hand in numpy, and numpy.linalg.eigvals gives the eigenvalues.

Output: one eigenvalue per line, "re im", every eigenvalue of the closed loop.
"""
import sys

import numpy as np
from scipy import linalg, signal


def read(path):
    with open(path) as f:
        tokens = f.read().split()
    pos = 0

    def take(n):
        nonlocal pos
        out = [float(t) for t in tokens[pos:pos + n]]
        pos += n
        return out

    ndof, naxes, omega = take(3)
    ndof, naxes = int(ndof), int(naxes)
    axes = [take(5) for _ in range(naxes)]
    kind = tokens[pos]
    pos += 1
    law = (kind, take(6 if kind == "leadlag_notch" else 4))
    mats = [np.array(take(ndof * ndof)).reshape(ndof, ndof) for _ in range(4)]
    return ndof, omega, axes, law, mats


def controller(law):
    g, fz, fp, fn, width, depth = law[1]
    wz, wp, wn = 2 * np.pi * fz, 2 * np.pi * fp, 2 * np.pi * fn
    zp = width / (2 * fn)
    zz = depth * zp
    num = np.polymul(g * np.array([1 / wz, 1.0]), [1.0, 2 * zz * wn, wn * wn])
    den = np.polymul([1 / wp, 1.0], [1.0, 2 * zp * wn, wn * wn])
    return signal.tf2ss(num, den)


def closed_loop(ndof, omega, axes, law, mats):
    M, K, C, G = mats
    Ak, Bk, Ck, Dk = controller(law)
    nk = Ak.shape[0]
    nlag = sum(1 for a in axes if a[4] > 0)
    n = 2 * ndof + nlag + nk * len(axes)
    A = np.zeros((n, n))
    Minv = np.linalg.inv(M)
    A[:ndof, ndof:2 * ndof] = np.eye(ndof)
    # M v' = -K q - (C + omega G) v + sum over axes of (ks x_act + Fc) at the actuator
    F = np.zeros((ndof, n))
    F[:, :ndof] = -K
    F[:, ndof:2 * ndof] = -(C + omega * G)
    lag = 2 * ndof
    ctl = 2 * ndof + nlag
    for act, sen, ks, ki, tau in axes:
        act, sen = int(act), int(sen)
        F[act, act] += ks
        # i = Ck xk + Dk e, e = -xs; xk' = Ak xk + Bk e
        irow = np.zeros(n)
        irow[ctl:ctl + nk] = Ck[0]
        irow[sen] -= Dk[0, 0]
        A[ctl:ctl + nk, ctl:ctl + nk] = Ak
        A[ctl:ctl + nk, sen] -= Bk[:, 0]
        if tau > 0:
            F[act, lag] += 1.0
            A[lag, :] += ki * irow / tau
            A[lag, lag] -= 1.0 / tau
            lag += 1
        else:
            F[act, :] += ki * irow
        ctl += nk
    A[ndof:2 * ndof, :] = Minv @ F
    return np.linalg.eigvals(A)


def plant(ndof, omega, axes, mats):
    """The plant z' = A z + Bu i, z = [q, v, Fc of the lagged axes], i the axes' currents."""
    M, K, C, G = mats
    nlag = sum(1 for a in axes if a[4] > 0)
    n = 2 * ndof + nlag
    Minv = np.linalg.inv(M)
    F = np.zeros((ndof, n))
    F[:, :ndof] = -K
    F[:, ndof:2 * ndof] = -(C + omega * G)
    A = np.zeros((n, n))
    Bu = np.zeros((n, len(axes)))
    A[:ndof, ndof:2 * ndof] = np.eye(ndof)
    lag = 2 * ndof
    fi = np.zeros((ndof, len(axes)))
    for j, (act, sen, ks, ki, tau) in enumerate(axes):
        act = int(act)
        F[act, act] += ks
        if tau > 0:
            F[act, lag] += 1.0
            A[lag, lag] = -1.0 / tau
            Bu[lag, j] = ki / tau
            lag += 1
        else:
            fi[act, j] = ki
    A[ndof:2 * ndof, :] = Minv @ F
    Bu[ndof:2 * ndof, :] = Minv @ fi
    return A, Bu


def sampled_loop(ndof, omega, axes, law, mats):
    kp, kd, fd, rate = law[1]
    T = 1.0 / rate
    wd = 2 * np.pi * fd
    numd, dend, _ = signal.cont2discrete(([kp / wd + kd, kp], [1 / wd, 1.0]), T, method="bilinear")
    Ak, Bk, Ck, Dk = signal.tf2ss(np.ravel(numd), np.ravel(dend))
    A, Bu = plant(ndof, omega, axes, mats)
    n, m = Bu.shape
    aug = np.zeros((n + m, n + m))
    aug[:n, :n] = A
    aug[:n, n:] = Bu
    E = linalg.expm(aug * T)
    Phi, Gam = E[:n, :n], E[:n, n:]
    nk = Ak.shape[0]
    N = n + nk * m
    P = np.zeros((N, N))
    P[:n, :n] = Phi
    for j, (act, sen, ks, ki, tau) in enumerate(axes):
        sen = int(sen)
        xo = n + nk * j
        # u = Ck x + Dk e, e = -xs; x+ = Ak x + Bk e
        P[:n, sen] -= Gam[:, j] * Dk[0, 0]
        P[:n, xo:xo + nk] += np.outer(Gam[:, j], Ck[0])
        P[xo:xo + nk, xo:xo + nk] = Ak
        P[xo:xo + nk, sen] -= Bk[:, 0]
    mu = np.linalg.eigvals(P).astype(complex)
    return np.log(mu) * rate


def main():
    data = read(sys.argv[1])
    ev = sampled_loop(*data) if data[3][0] == "pid_tustin" else closed_loop(*data)
    for z in ev:
        print("%.17g %.17g" % (z.real, z.imag))


if __name__ == "__main__":
    main()
