"""Shared by the base-motion references: run the tool on a case, read its CSV samples, build the
housing's pulses and compare. Nothing here comes from touchdown but its output file."""
import csv
import math
import os
import subprocess

import numpy as np


def run_case(touchdown, case, csv_path, extra=()):
    """`touchdown run CASE` writing only the CSV; returns the columns by name (units stripped)."""
    cmd = [touchdown, "run", case, "-q", "--hdf5", "", "--csv", csv_path] + list(extra)
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit("%s failed (%d): %s" % (" ".join(cmd), done.returncode, done.stderr.strip()))
    return read_csv(csv_path)


def read_csv(path):
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    rows = list(csv.reader(lines))
    names = [h.split(" [")[0].strip() for h in rows[0]]
    data = np.array([[float(v) for v in r] for r in rows[1:] if r], dtype=float)
    return {n: data[:, i] for i, n in enumerate(names)}


def half_sine(t, start, duration):
    """The unit half-sine pulse (MIL-STD-810 / IEC 60068-2-27 shape) and its phase rate pi/duration."""
    u = (np.asarray(t, dtype=float) - start) / duration
    return np.where((u >= 0.0) & (u <= 1.0), np.sin(math.pi * np.clip(u, 0.0, 1.0)), 0.0)


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def compare(label, ours, theirs):
    """max |ours - theirs| / max |theirs| over every sample; prints it with the peak."""
    peak = float(np.max(np.abs(theirs)))
    err = float(np.max(np.abs(ours - theirs)))
    print("%-28s peak %.6e m  max error %.3e m  error/peak %.3e" % (label, peak, err, err / peak))
    return err / peak


def case_dir(name):
    """A fresh directory for a generated case under the working directory."""
    path = os.path.abspath(name)
    os.makedirs(path, exist_ok=True)
    return path
