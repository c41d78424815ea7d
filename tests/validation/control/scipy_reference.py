#!/usr/bin/env python3
"""Controllers (touchdown/controller.h) against scipy.signal, at test time.

Usage: scipy_reference.py CONTROLLER_PROBE

Each law below is written once, as the commands controller_probe reads (the library builds it
through the public API) and as polynomials or matrices that scipy.signal works on: freqs/freqz
for the frequency responses, a matrix exponential per time (scipy.linalg.expm) and lsim/dstep for
the step responses, cont2discrete (bilinear,
zoh) and bilinear at a prewarped rate for the sampled laws, zpk2tf and ss2tf for the other
forms. It prints the largest relative difference per law and fails above TOL. Frequency
responses are compared point by point (|G - G_scipy| / |G_scipy|), step responses relative to
the response's largest magnitude (they cross zero).
"""
import subprocess
import sys
import warnings

import numpy as np
from scipy import linalg, signal

TOL = 1e-11  # relative; what the comparisons reach is printed
# signal.step as a second, independent reference of the continuous step responses (a propagation
# from sample to sample, not one exponential per time: step_reference), within what its own
# propagation carries (1.1e-11 of pid_resonant_lowpass on one machine's BLAS)
TOL_PROPAGATED = 1e-10
# scipy warns about a numerator whose leading coefficients are zero; here they are on purpose (a
# strictly proper law, a delay written as leading zeros of z^-1)
warnings.filterwarnings("ignore", category=signal.BadCoefficients)
TWO_PI = 2.0 * np.pi


def polyadd(a, b):
    n = max(len(a), len(b))
    return np.pad(a, (n - len(a), 0)) + np.pad(b, (n - len(b), 0))


def tf_sum(*terms):
    num, den = np.array([0.0]), np.array([1.0])
    for n, d in terms:
        num, den = polyadd(np.polymul(num, d), np.polymul(n, den)), np.polymul(den, d)
    return num, den


# The blocks' transfer functions in s (touchdown/controller.h), as (command, (num, den)).
def pid(kp, ki, kd, f):
    wd = TWO_PI * f
    terms = [([kp], [1.0]), ([ki], [1.0, 0.0])] if ki else [([kp], [1.0])]
    terms.append(([kd * wd, 0.0], [1.0, wd]) if f > 0 else ([kd, 0.0], [1.0]))
    return f"pid {kp!r} {ki!r} {kd!r} {f!r}", tf_sum(*terms)


def leadlag(g, fz, fp):
    return f"leadlag {g!r} {fz!r} {fp!r}", ([g / (TWO_PI * fz), g], [1.0 / (TWO_PI * fp), 1.0])


def lowpass(f, order, zeta):
    w = TWO_PI * f
    tf = ([w], [1.0, w]) if order == 1 else ([w * w], [1.0, 2 * zeta * w, w * w])
    return f"lowpass {f!r} {order} {zeta!r}", tf


def notch(f, width, depth):
    w, zp = TWO_PI * f, width / (2.0 * f)
    return f"notch {f!r} {width!r} {depth!r}", ([1.0, 2 * depth * zp * w, w * w], [1.0, 2 * zp * w, w * w])


def resonant(g, phase_deg, f, zeta=None):
    """g (s cos phi + w sin phi)/(s^2 + 2 zeta w s + w^2); zeta None: the command without damping
    (the block's default, undamped)."""
    w, phi = TWO_PI * f, np.radians(phase_deg)
    cmd = f"resonant {g!r} {phase_deg!r} {f!r}" + ("" if zeta is None else f" {zeta!r}")
    return cmd, ([g * np.cos(phi), g * w * np.sin(phi)], [1.0, 2.0 * (zeta or 0.0) * w, w * w])


def tf_s(num, den):
    return f"tf 0 {len(num)} {' '.join(map(repr, num))} {len(den)} {' '.join(map(repr, den))}", (num, den)


def ss_series(first, second):
    """The state space of first then second (each (A, B, C, D), SISO)."""
    a1, b1, c1, d1 = first
    a2, b2, c2, d2 = second
    n1, n2 = a1.shape[0], a2.shape[0]
    a = np.block([[a1, np.zeros((n1, n2))], [b2 @ c1, a2]])
    return a, np.vstack([b1, b2 @ d1]), np.hstack([d2 @ c1, c2]), d2 @ d1


def parallel(first, second):
    """The sum of two chains (as chain() gives them): the probe's branch/sum commands, the sum of
    the transfer functions, and the block-diagonal state space fed the same input."""
    (c1, (n1, d1), s1), (c2, (n2, d2), s2) = first, second
    a1, b1, cc1, dd1 = s1
    a2, b2, cc2, dd2 = s2
    k1, k2 = a1.shape[0], a2.shape[0]
    a = np.block([[a1, np.zeros((k1, k2))], [np.zeros((k2, k1)), a2]])
    ss = (a, np.vstack([b1, b2]), np.hstack([cc1, cc2]), dd1 + dd2)
    return c1 + ["branch"] + c2 + ["sum"], tf_sum((n1, d1), (n2, d2)), ss


def chain(*blocks):
    """commands, (num, den) of the product (for frequency responses: polynomials in s are well
    conditioned), and the blocks' tf2ss realisations in series (for time responses and sampling:
    the product's companion form is not, for a sixth-order chain with an integrator)."""
    num, den, ss = np.array([1.0]), np.array([1.0]), None
    pn, pd = np.array([1.0]), np.array([1.0])  # an improper block waits for the next one
    for _, (n, d) in blocks:
        num, den = np.polymul(num, n), np.polymul(den, d)
        pn, pd = np.polymul(pn, n), np.polymul(pd, d)
        if len(np.trim_zeros(pn, "f")) <= len(pd):
            blk = tuple(np.atleast_2d(x) for x in signal.tf2ss(pn, pd))
            ss = blk if ss is None else ss_series(ss, blk)
            pn, pd = np.array([1.0]), np.array([1.0])
    return [cmd for cmd, _ in blocks], (num, den), ss


def ss_response(ss, z):
    a, b, c, d = ss
    return np.array([(c @ np.linalg.solve(zk * np.eye(a.shape[0]) - a, b) + d)[0, 0] for zk in z])


def run_probe(probe, script):
    out = subprocess.run([probe], input=script, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"controller_probe failed: {out.stderr.strip()}")
    rows = {}
    for line in out.stdout.splitlines():
        kind, name, *vals = line.split()
        rows.setdefault((kind, name), []).append([float(v) for v in vals])
    return rows


def rel_freq(rows, ref):
    c = np.array([r[1] + 1j * r[2] for r in rows])
    return float(np.max(np.abs(c - ref) / np.abs(ref)))


def rel_step(rows, ref):
    c = np.array([r[1] for r in rows])
    return float(np.max(np.abs(c - ref)) / np.max(np.abs(ref)))


def step_reference(ss, t):
    """The continuous step response of a SISO state space at the times t, each from one matrix
    exponential (Van Loan): expm([[A, B], [0, 0]] t) holds the integral of e^(A s) B over [0, t] in
    its last column, so y(t) = C that + D, with no error carried from one time to the next.
    signal.step propagates from sample to sample instead (lsim), and for the sixth-order chain
    pid_resonant_lowpass, whose state matrix spans 2 kHz to an undamped 51 Hz pair, what it carries
    reached 1.1e-11 of the response on one machine's BLAS: scipy's own two answers differed by
    that much, the one taken here and touchdown's by 1.5e-13."""
    a, b, c, d = ss
    n = a.shape[0]
    m = np.zeros((n + 1, n + 1))
    m[:n, :n], m[:n, n:] = a, b
    return np.array([(c @ linalg.expm(m * tk)[:n, n:] + d)[0, 0] for tk in t])


def continuous_laws():
    """name -> (commands, (num, den) in s, state space or None (improper: no step response))"""
    return {
        "pid_notch_lowpass": chain(pid(1.0e4, 2.0e5, 40.0, 2000.0), notch(34.4, 6.0, 0.05),
                                   lowpass(2000.0, 2, 0.7)),
        "leadlag_lowpass1": chain(leadlag(1.2e4, 15.0, 150.0), lowpass(500.0, 1, 0.0)),
        "pd_tf_lowpass2": chain(tf_s([40.0, 1.0e4], [1.0]), lowpass(1500.0, 2, 0.5)),
        "pd_unfiltered": chain(pid(1.0e4, 0.0, 40.0, 0.0))[:2] + (None,),
        "notch_then_pd": chain(notch(96.0, 10.0, 0.1), tf_s([40.0, 1.0e4], [1.0]))[:2] + (None,),
        "tf3": chain(tf_s([3.0, 1.0e3, 2.0e6], [1.0, 900.0, 4.0e5, 1.0e8])),
        "resonant": chain(resonant(5.0e3, 60.0, 50.93)),
        "resonant_90": chain(resonant(-2.0e3, 90.0, 120.0)),
        "pd_plus_resonant": parallel(chain(pid(1.0e4, 0.0, 40.0, 2000.0), lowpass(3000.0, 1, 0.0)),
                                     chain(resonant(0.6, 45.0, 50.93))),
        "pid_resonant_lowpass": chain(pid(1.0e4, 0.0, 40.0, 2000.0), resonant(0.3, -30.0, 50.93),
                                      lowpass(2000.0, 2, 0.7)),
        "resonant_damped": chain(resonant(640.0, 243.0, 50.93, 0.02)),
        "resonant_damped_heavy": chain(resonant(-2.0e3, 90.0, 120.0, 0.7)),
        "pd_plus_damped_resonant": parallel(chain(pid(1.0e4, 0.0, 40.0, 2000.0)),
                                            chain(resonant(640.0, 243.0, 50.93, 0.02))),
    }


def sampled_laws(cont):
    """name -> (commands, reference (b, a) in ascending powers of z^-1 or (A, B, C, D), rate, delay)"""
    laws = {}
    for name, rate, method, prewarp, delay in [
            ("pid_notch_lowpass", 1.0e4, "tustin", 0.0, 0), ("pid_notch_lowpass", 1.0e4, "tustin", 34.4, 1),
            ("leadlag_lowpass1", 5.0e3, "zoh", 0.0, 0), ("pd_tf_lowpass2", 1.0e4, "zoh", 0.0, 2),
            ("tf3", 2.0e3, "tustin", 300.0, 3), ("resonant", 1.0e4, "tustin", 50.93, 1),
            ("pid_resonant_lowpass", 1.0e4, "zoh", 0.0, 1), ("pd_plus_resonant", 1.0e4, "tustin", 50.93, 1),
            ("resonant_damped", 1.0e4, "zoh", 0.0, 0), ("pd_plus_damped_resonant", 1.0e4, "tustin", 0.0, 0)]:
        cmds, _, ss = cont[name]
        # Tustin prewarped at w0 is the bilinear map s = (2/T')(z - 1)/(z + 1), T' = 2 tan(w0 T/2)/w0
        w0 = TWO_PI * prewarp
        dt = 2.0 * np.tan(w0 / (2.0 * rate)) / w0 if prewarp else 1.0 / rate
        a, b, c, d, _ = signal.cont2discrete(ss, dt, method="zoh" if method == "zoh" else "bilinear")
        extra = [f"discretise {rate!r} {method} {prewarp!r}"] + ([f"delay {delay}"] if delay else [])
        laws[f"{name}_{method}_{prewarp:g}_d{delay}"] = (cmds + extra, (a, b, c, d), rate, delay)
    b, a = [0.5, -0.2, 0.1], [1.0, -1.1, 0.3, -0.02]
    laws["ztf"] = ([f"tf 1000.0 3 {' '.join(map(repr, b))} 4 {' '.join(map(repr, a))}"], (np.array(b), np.array(a)),
                   1000.0, 0)
    z, p = [0.5], [0.2, 0.6 + 0.3j, 0.6 - 0.3j]
    zb, za = signal.zpk2tf(z, p, 3.0)
    laws["zzpk"] = (["zpk 1000.0 3.0 1 0.5 0.0 2 0.2 0.0 0.6 0.3"], (np.pad(zb, (len(za) - len(zb), 0)), za), 1000.0,
                    0)
    return laws


def check_continuous(rows, laws, f, t):
    worst = 0.0
    for name, (_, (num, den), ss) in laws.items():
        _, ref = signal.freqs(num, den, worN=TWO_PI * f)
        e = rel_freq(rows[("freq", name)], ref)
        print(f"{name:36s} continuous  freq {e:.2e}", end="")
        worst = max(worst, e)
        if ss is not None:
            e = rel_step(rows[("step", name)], step_reference(ss, t))
            _, ys = signal.step(signal.StateSpace(*ss), T=t)
            e2 = rel_step(rows[("step", name)], ys)
            print(f"  step {e:.2e}  (signal.step {e2:.2e})", end="")
            worst = max(worst, e, e2 * TOL / TOL_PROPAGATED)  # each against its own tolerance
        print()
    return worst


def sampled_reference(ref, rate, delay, fk, n):
    """Frequency response at fk and the first n step samples of a sampled reference law."""
    z = np.exp(1j * TWO_PI * fk / rate)
    if len(ref) == 2:  # (b, a) in powers of z^-1; dlti wants positive powers: pad at the end
        b, a = ref
        _, g = signal.freqz(b, a, worN=fk, fs=rate)
        m = max(len(b), len(a))
        sys_d = signal.dlti(np.pad(b, (0, m - len(b))), np.pad(a, (0, m - len(a))), dt=1.0 / rate)
    else:
        g = ss_response(ref, z)
        sys_d = signal.dlti(*ref, dt=1.0 / rate)
    ys = signal.dlsim(sys_d, np.ones(n))[1]
    return g * z ** -delay, np.concatenate([np.zeros(delay), ys[: n - delay, 0]])


def check_sampled(rows, laws, f):
    worst = 0.0
    for name, (_, ref, rate, delay) in laws.items():
        fk = f[f < 0.5 * rate]
        g, ys = sampled_reference(ref, rate, delay, fk, len(rows[("step", name)]))
        e1 = rel_freq(rows[("freq", name)], g)
        e2 = rel_step(rows[("step", name)], ys)
        print(f"{name:36s} sampled     freq {e1:.2e}  step {e2:.2e}")
        worst = max(worst, e1, e2)
    return worst


# A MIMO state-space law (2 states, 2 inputs, 2 outputs), continuous and by ZOH.
SS_A = np.array([[-120.0, 40.0], [-300.0, -15.0]])
SS_B = np.array([[1.0, 0.5], [0.0, 2.0]])
SS_C = np.array([[3.0, -1.0], [0.7, 0.0]])
SS_D = np.array([[0.1, 0.0], [0.2, -0.3]])
SS_RATE = 4000.0


def ss_command():
    flat = [SS_A.flatten("F"), SS_B.flatten("F"), SS_C.flatten("F"), SS_D.flatten("F")]
    return "ss 0 2 2 2 " + " ".join(repr(float(v)) for m in flat for v in m)


def check_state_space(rows, f, t):
    worst = 0.0
    got = np.array([r[1:] for r in rows[("freq", "mimo")]])  # per f: (re, im) of G column-major
    for j in range(2):
        num, den = signal.ss2tf(SS_A, SS_B, SS_C, SS_D, input=j)
        for i in range(2):
            _, ref = signal.freqs(num[i], den, worN=TWO_PI * f)
            c = got[:, 2 * (i + 2 * j)] + 1j * got[:, 2 * (i + 2 * j) + 1]
            worst = max(worst, float(np.max(np.abs(c - ref) / np.abs(ref))))
    u = np.zeros((len(t), 2))
    u[:, 1] = 1.0
    _, ys, _ = signal.lsim(signal.StateSpace(SS_A, SS_B, SS_C, SS_D), u, t)
    c = np.array([r[1:] for r in rows[("step", "mimo")]])
    e = float(np.max(np.abs(c - ys)) / np.max(np.abs(ys)))
    ad, bd, cd, dd, _ = signal.cont2discrete((SS_A, SS_B, SS_C, SS_D), 1.0 / SS_RATE, method="zoh")
    m = rows[("matrices", "mimo_zoh")][0]
    mine = np.array(m[4:])
    ref = np.concatenate([x.flatten("F") for x in (ad, bd, cd, dd)])
    em = float(np.max(np.abs(mine - ref)) / np.max(np.abs(ref)))
    print(f"{'mimo (ss2tf, lsim, cont2discrete zoh)':36s} freq {worst:.2e}  step {e:.2e}  zoh matrices {em:.2e}")
    # Tustin by cont2discrete (bilinear) on the matrices, compared by response (the realisations differ)
    ad, bd, cd, dd, _ = signal.cont2discrete((SS_A, SS_B, SS_C, SS_D), 1.0 / SS_RATE, method="bilinear")
    fk = f[f < 0.5 * SS_RATE]
    got = np.array([r[1:] for r in rows[("freq", "mimo_tustin")]])
    et = 0.0
    for k, fr in enumerate(fk):
        zk = np.exp(1j * TWO_PI * fr / SS_RATE)
        g = (cd @ np.linalg.solve(zk * np.eye(2) - ad, bd) + dd).flatten("F")
        et = max(et, float(np.max(np.abs(got[k, 0::2] + 1j * got[k, 1::2] - g) / np.abs(g))))
    print(f"{'mimo tustin (cont2discrete bilinear)':36s} freq {et:.2e}")
    return max(worst, e, em, et)


def check_minimal(rows, f):
    """(s + 2)/((s + 2)(s + 5)) realised with 2 states; minimal() keeps 1 and the response 1/(s + 5)."""
    order = int(rows[("matrices", "cancel_min")][0][0])
    _, ref = signal.freqs([1.0], [1.0, 5.0], worN=TWO_PI * f)
    e = rel_freq(rows[("freq", "cancel_min")], ref)
    print(f"{'minimal of a cancelling pole-zero':36s} order {order} (of 2)  freq {e:.2e}")
    if order != 1:
        sys.exit("minimal() kept the cancelled state")
    return e


def build_script(cont, samp, f, t):
    fs = " ".join(map(repr, f))
    lines = []
    for name, (cmds, _, ss) in cont.items():
        lines += [f"law {name}"] + cmds + [f"freq {fs}"]
        if ss is not None:
            lines.append("step 0 " + " ".join(map(repr, t)))
    for name, (cmds, _, rate, _) in samp.items():
        lines += [f"law {name}"] + cmds + ["freq " + " ".join(map(repr, f[f < 0.5 * rate]))]
        lines.append("step 0 " + " ".join(repr(k / rate) for k in range(60)))
    lines += ["law mimo", ss_command(), f"freq {fs}", "step 1 " + " ".join(map(repr, t))]
    lines += ["law mimo_zoh", ss_command(), f"discretise {SS_RATE!r} zoh 0", "matrices"]
    lines += ["law mimo_tustin", ss_command(), f"discretise {SS_RATE!r} tustin 0",
              "freq " + " ".join(map(repr, f[f < 0.5 * SS_RATE]))]
    lines += ["law cancel_min", "tf 0 2 1.0 2.0 3 1.0 7.0 10.0", "minimal", "matrices", f"freq {fs}"]
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    f = np.concatenate([np.logspace(-1, np.log10(4900.0), 57), [34.4, 96.0, 300.0]])
    t = np.linspace(0.0, 0.02, 201)
    cont = continuous_laws()
    samp = sampled_laws(cont)
    rows = run_probe(sys.argv[1], build_script(cont, samp, f, t))
    worst = max(check_continuous(rows, cont, f, t), check_sampled(rows, samp, f),
                check_state_space(rows, f, t), check_minimal(rows, f))
    print(f"largest relative difference {worst:.2e} (tolerance {TOL:.0e})")
    if not worst <= TOL:
        sys.exit("controllers differ from scipy.signal")


if __name__ == "__main__":
    main()
