#!/usr/bin/python3
"""The sampled controller of a run against scipy.signal.dlsim (tests/test_sampler.c writes the file).

    sampler_dlsim.py RECORDS

RECORDS holds, one item per line, `n nin nout rate`, then the realisation as the model keeps it
(A n x n, B n x nin, C nout x n, D nout x nin, each row by row on one line per row), then `N`, then
N lines `k t e_1 .. e_nin u_1 .. u_nout`: the samples the simulation took, its inputs e_k and
outputs i_k. scipy.signal.dlsim drives the same realisation, from rest, with the recorded inputs;
its outputs must equal the recorded ones to 1e-9 of their largest magnitude (the two sum the
products in different orders; nothing else differs). Exit 0 and one line "dlsim: ..." when they do,
exit 1 otherwise. A missing scipy is a failure (exit 1), not a skip: setup.sh installs it.
"""
import sys

try:
    import numpy as np
    from scipy import signal
except ImportError as e:
    print("sampler_dlsim: scipy is needed (python3-scipy): %s" % e)
    sys.exit(1)


def rows(lines, count, width):
    m = np.array([[float(v) for v in lines.pop(0).split()] for _ in range(count)]).reshape(count, width)
    return m


def main(path):
    lines = [ln for ln in open(path).read().splitlines() if ln.strip()]
    n, nin, nout, rate = lines.pop(0).split()
    n, nin, nout, rate = int(n), int(nin), int(nout), float(rate)
    A, B = rows(lines, n, n), rows(lines, n, nin)
    C, D = rows(lines, nout, n), rows(lines, nout, nin)
    count = int(lines.pop(0))
    rec = np.array([[float(v) for v in lines.pop(0).split()] for _ in range(count)])
    k, e, u = rec[:, 0], rec[:, 2:2 + nin], rec[:, 2 + nin:2 + nin + nout]
    if not np.array_equal(k, np.arange(count)):
        print("sampler_dlsim: the samples are not 0, 1, 2, ... in order")
        return 1
    _, y, _ = signal.dlsim((A, B, C, D, 1.0 / rate), e)
    scale = max(np.max(np.abs(u)), 1e-300)
    err = np.max(np.abs(y - u)) / scale
    print("dlsim: %d samples, %d inputs, %d outputs, max |i - dlsim| = %.3e of max |i| = %.6g A"
          % (count, nin, nout, err, scale))
    return 0 if err <= 1e-9 else 1


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: sampler_dlsim.py RECORDS")
    sys.exit(main(sys.argv[1]))
