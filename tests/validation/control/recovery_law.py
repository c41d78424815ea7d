#!/usr/bin/env python3
"""cases/recovery.cfg's recovery law, written as one transfer function by scripts/recovery_study.py
(--law 320), is the rig's PD plus a damped synchronous resonant block in parallel, as blocks:

    parallel = ( { pid = { kp; kd; derivative_filter; }; },
                 { resonant = { gain = G; phase = PHI; damping = ZETA; }; } )

with G = GAIN_AT_SPEED 2 ZETA W, PHI = damper_phase(W), ZETA and the PD's gains from the study
script (W = 320 rad/s, the case's speed, where the resonant's frequency defaults to). An independent
check of the script's polynomial algebra: the blocks are realised by the library's closed forms
and summed by td_controller_parallel, and also evaluated here directly in complex arithmetic.

Usage: recovery_law.py CONTROLLER_PROBE

Frequency responses over 1..2000 Hz (and at W itself), point by point, |G - G_ref| / |G_ref|:
1. the continuous laws (before sampling): the case's tf (its coefficients as written in the case
   file) against the blocks built by the controller API, and both against the closed form;
2. as the case reader builds them, sampled the same way (the case's Tustin at 10 kHz): the case's
   controller 1 against the same case with its law replaced by the block form (every AMB axis);
3. the study's PD gains are the case's nominal law (controller 0) in the same way.
And the case's comment, which gives the law as blocks, has these numbers.
"""
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import recovery_study as rs  # noqa: E402  (the study's law and its constants)

CASE = os.path.join(ROOT, rs.CASE)
SPEED = 320.0  # rad/s, cases/recovery.cfg's speed; its recovery law is recovery_study.py --law 320
TOL = 1e-10    # relative; what the comparisons reach is printed
AXES = 4       # two AMBs, x and y each


def block_values(speed):
    """G, PHI (deg), ZETA of the damped resonant block, as the study's law() sets them."""
    return rs.GAIN_AT_SPEED * 2.0 * rs.ZETA * speed, rs.damper_phase(speed), rs.ZETA


def closed_form(f_hz, speed):
    """PD + g (s cos phi + W sin phi)/(s^2 + 2 zeta W s + W^2) at s = j 2 pi f, term by term."""
    g, phase, zeta = block_values(speed)
    phi, wf = math.radians(phase), 2.0 * math.pi * rs.DERIVATIVE_FILTER
    out = []
    for f in f_hz:
        s = 2j * math.pi * f
        pd = rs.KP + rs.KD * wf * s / (s + wf)
        out.append(pd + g * (s * math.cos(phi) + speed * math.sin(phi)) / (s * s + 2.0 * zeta * speed * s + speed ** 2))
    return out


def case_tf():
    """num, den of the case's recovery law, as written in the case file (its one tf block)."""
    with open(CASE) as fh:
        text = fh.read()
    law = re.search(r'name = "pd-sync";.*?tf = \{ num = \[([^]]*)\];\s*den = \[([^]]*)\];', text, re.S)
    if not law:
        sys.exit("recovery_law: no tf law in the pd-sync controller of %s" % CASE)
    return [float(x) for x in law.group(1).split(",")], [float(x) for x in law.group(2).split(",")]


def block_law(speed):
    """The recovery law as blocks in the case file's syntax (the resonant's frequency left to the
    case's speed)."""
    g, phase, zeta = block_values(speed)
    return ("( { parallel = ( { pid = { kp = %r; kd = %r; derivative_filter = %r; }; }, "
            "{ resonant = { gain = %r; phase = %r; damping = %r; }; } ); } )"
            % (rs.KP, rs.KD, rs.DERIVATIVE_FILTER, g, phase, zeta))


def comment_says_blocks(speed):
    """Whether the case's comment gives the block form with the script's numbers (`law = ...;`)."""
    with open(CASE) as fh:
        comment = " ".join(line.lstrip("#") for line in fh if line.startswith("#"))
    return ("law = %s;" % block_law(speed)) in " ".join(comment.split())


def probe_script(f_hz, speed):
    num, den = case_tf()
    g, phase, zeta = block_values(speed)
    fs = "freq " + " ".join(map(repr, f_hz))
    pd = "pid %r 0.0 %r %r" % (rs.KP, rs.KD, rs.DERIVATIVE_FILTER)
    return "\n".join([
        "law tf", "tf 0 %d %s %d %s" % (len(num), " ".join(map(repr, num)), len(den), " ".join(map(repr, den))), fs,
        "law blocks", pd, "branch", "resonant %r %r %r %r" % (g, phase, speed / (2.0 * math.pi), zeta), "sum", fs,
        "law case_tf", "case 1 " + CASE, fs,
        "law case_blocks", "set controllers[1].law=" + block_law(speed), "case 1 " + CASE, fs,
        "law case_pd", "case 0 " + CASE, fs,
        "law pd_sampled", pd, "discretise 10000.0 tustin 0.0", fs]) + "\n"


def run_probe(probe, script):
    out = subprocess.run([probe], input=script, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("controller_probe failed: %s" % out.stderr.strip())
    rows = {}
    for line in out.stdout.splitlines():
        kind, name, *vals = line.split()
        v = [float(x) for x in vals[1:]]
        rows.setdefault(name, []).append([complex(v[i], v[i + 1]) for i in range(0, len(v), 2)])
    return rows


def rel(got, ref):
    return max(abs(a - b) / abs(b) for a, b in zip(got, ref))


def entry(rows, name, i, j):
    """Entry (i, j) of a MIMO law's responses (column-major, AXES outputs)."""
    return [r[i + AXES * j] for r in rows[name]]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    f = [10.0 ** (k * math.log10(2000.0) / 199) for k in range(200)] + [SPEED / (2.0 * math.pi)]
    rows = run_probe(sys.argv[1], probe_script(f, SPEED))
    ref = closed_form(f, SPEED)
    tf, blocks = [r[0] for r in rows["tf"]], [r[0] for r in rows["blocks"]]
    sampled = []  # the sampled laws, axis by axis; an axis's law does not reach another axis
    for i in range(AXES):
        sampled.append(rel(entry(rows, "case_blocks", i, i), entry(rows, "case_tf", i, i)))
        for j in range(AXES):
            if i != j and (any(entry(rows, "case_tf", i, j)) or any(entry(rows, "case_blocks", i, j))):
                sys.exit("recovery_law: axis %d reaches axis %d" % (j, i))
    pd = max(rel(entry(rows, "case_pd", i, i), [r[0] for r in rows["pd_sampled"]]) for i in range(AXES))
    checks = [("continuous: the case's tf against the blocks (API)", rel(tf, blocks)),
              ("continuous: the case's tf against the closed form", rel(tf, ref)),
              ("continuous: the blocks (API) against the closed form", rel(blocks, ref)),
              ("sampled (case reader, Tustin 10 kHz): tf against the blocks", max(sampled)),
              ("sampled: the case's pd against the study's PD gains", pd)]
    if not comment_says_blocks(SPEED):
        sys.exit("recovery_law: the comment of %s does not give the law as blocks: law = %s;"
                 % (CASE, block_law(SPEED)))
    print("the case's comment gives the law as blocks with the study's numbers")
    for what, e in checks:
        print("%-62s %.2e" % (what, e))
    worst = max(e for _, e in checks)
    print("largest relative difference %.2e (tolerance %.0e); G %r, PHI %r deg, ZETA %r"
          % ((worst, TOL) + block_values(SPEED)))
    if not worst <= TOL:
        sys.exit("the recovery case's tf law is not the PD plus the damped resonant block")


if __name__ == "__main__":
    main()
