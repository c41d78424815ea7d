"""The rainflow counter (touchdown/assess.h td_rainflow, through tests/life/rainflow_probe) against
an independent implementation of ASTM E1049-85 5.4.4, the PyPI package rainflow (pinned in
tests/life/requirements.txt): the same cycles (range, mean, count), as multisets, on known
histories: the standard's Fig. 6 example, seeded random histories, and a drop-like contact load
(impacts of decaying height, zero between them, then a rolling load with a whirl ripple).
With the gate 0 (the package has none), both count every strict turn.
   rainflow_reference.py PROBE"""
import math
import random
import subprocess
import sys

import rainflow


def probe_cycles(probe, series, gate=0.0):
    text = "%r\n" % gate + "\n".join(repr(float(x)) for x in series) + "\n"
    out = subprocess.run([probe], input=text, capture_output=True, text=True, check=True).stdout
    return [tuple(float(v) for v in line.split()) for line in out.splitlines()]


def reference_cycles(series):
    return [(rng, mean, count) for rng, mean, count, _, _ in rainflow.extract_cycles(list(series))]


def key(cycle, scale):
    """A cycle as a comparable key, its range and mean to 1e-12 of the history's scale."""
    rng, mean, count = cycle
    return (round(rng / scale * 1e12), round(mean / scale * 1e12), count)


def drop_like(rng):
    """Impacts of decaying height with zero load between them, then a rolling load with a ripple."""
    x, t = [], 0.0
    for k in range(12):
        peak = 4000.0 * 0.7**k * (1.0 + 0.1 * rng.random())
        for i in range(20):
            x.append(peak * math.sin(math.pi * i / 19) ** 2)
        x.extend([0.0] * (3 + k))
    for i in range(400):
        t = i * 1e-3
        x.append(600.0 + 150.0 * math.sin(2 * math.pi * 37.0 * t) + 40.0 * math.sin(2 * math.pi * 211.0 * t))
    return x


def main():
    probe = sys.argv[1]
    rng = random.Random(20261127)
    histories = {
        "ASTM E1049-85 Fig. 6": [-2, 1, -3, 5, -1, 3, -4, 4, -2],
        "drop-like contact load": drop_like(rng),
    }
    for n in (3, 10, 100, 1000, 5000):
        histories["random walk of %d" % n] = [0.0]
        for _ in range(n - 1):
            histories["random walk of %d" % n].append(histories["random walk of %d" % n][-1] + rng.gauss(0, 1))
        histories["white noise of %d" % n] = [rng.uniform(-1e3, 1e3) for _ in range(n)]
    failed = 0
    for name, series in histories.items():
        scale = max(abs(v) for v in series) or 1.0
        mine = sorted(key(c, scale) for c in probe_cycles(probe, series))
        theirs = sorted(key(c, scale) for c in reference_cycles(series))
        total = sum(c[2] for c in mine)
        status = "same" if mine == theirs else "DIFFERENT"
        print("%-24s %5d values: %4d cycles counted (%g in all), %s as rainflow %s"
              % (name, len(series), len(mine), total, status, rainflow.__version__))
        if mine != theirs:
            failed += 1
            print("  probe only:", sorted(set(mine) - set(theirs))[:5])
            print("  rainflow only:", sorted(set(theirs) - set(mine))[:5])
    astm = sorted(probe_cycles(probe, histories["ASTM E1049-85 Fig. 6"]))
    table4 = {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}
    got = {}
    for rng_, _, count in astm:
        got[rng_] = got.get(rng_, 0.0) + count
    if got != table4:
        failed += 1
        print("ASTM E1049-85 Table 4: want %s, got %s" % (table4, got))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
