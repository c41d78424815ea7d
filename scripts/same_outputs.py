#!/usr/bin/python3
"""Compare two trees of touchdown outputs (scripts/same-outputs.sh makes them) bit for bit, the
fields that hold wall-clock times aside: exit 0 and "identical", or exit 1 and one line per
difference (a file missing on one side, an HDF5 object or attribute, a CSV, JSON or text file).

  same_outputs.py OLD_DIR NEW_DIR

HDF5 files are compared object by object: every dataset's values, type and shape, every
attribute's value, type and shape (the object references of dimension scales by the name of the
object they point to, since their addresses move with the size of earlier objects), compound
fields by name. CSV files cell by cell (quoted cells kept whole), JSON files key by key, gnuplot
scripts, data files and messages byte for byte; PNG images are not compared (gnuplot's own).
Wall-clock fields are those whose name says so: wall_time, realtime_factor, check_time,
merge_time (docs/output-format.md).
"""
import csv
import json
import os
import re
import sys

import h5py
import numpy as np

WALL = re.compile(r"wall|realtime|check_time|merge_time", re.I)


def strip_json(o):
    """o without the keys that hold wall-clock times, at any depth."""
    if isinstance(o, dict):
        return {k: strip_json(v) for k, v in o.items() if not WALL.search(k)}
    if isinstance(o, list):
        return [strip_json(v) for v in o]
    return o


def csv_rows(path):
    """The rows of a CSV file as lists of cells, without wall-clock columns or comment lines."""
    rows, drop, header = [], [], None
    with open(path, encoding="utf-8", errors="replace", newline="") as f:
        for line in f.read().splitlines():
            if line.startswith("#"):
                if not WALL.search(line):
                    rows.append([line])
                continue
            cells = next(csv.reader([line]))
            if header is None:
                header = cells
                drop = [i for i, c in enumerate(cells) if WALL.search(c)]
            rows.append([c for i, c in enumerate(cells) if i not in drop])
    return rows


def canon(f, value):
    """A value read from file f as bytes that two equal values share (references by name)."""
    a = np.asarray(value)
    if a.dtype.names:
        return b"|".join(canon(f, a[n]) for n in a.dtype.names) + repr(a.dtype.names).encode()
    if a.dtype == object or a.dtype.kind in "OSU":
        cells = []
        for x in a.ravel():
            if isinstance(x, h5py.Reference):
                cells.append(f[x].name if x else "<null>")
            elif isinstance(x, np.ndarray):
                cells.append(repr([f[r].name if isinstance(r, h5py.Reference) else r for r in x.ravel()]))
            else:
                cells.append(repr(x))
        return (repr(cells) + repr(a.shape)).encode()
    return a.tobytes() + str(a.dtype).encode() + repr(a.shape).encode()


def h5_items(path):
    """{object path or path@attribute: canonical bytes} of an HDF5 file, wall-clock fields aside."""
    items = {}
    with h5py.File(path, "r") as f:

        def attrs(name, obj):
            for k, v in obj.attrs.items():
                if not WALL.search(k):
                    items[name + "@" + k] = canon(f, v)

        def visit(name, obj):
            attrs(name, obj)
            if not isinstance(obj, h5py.Dataset) or WALL.search(name.split("/")[-1]):
                return
            a = obj[()]
            if a.dtype.names:
                keep = [n for n in a.dtype.names if not WALL.search(n)]
                items[name] = b"".join(canon(f, a[n]) for n in keep) + repr(keep).encode()
            else:
                items[name] = canon(f, a)

        attrs("/", f)
        f.visititems(visit)
    return items


def differences(old, new, rel):
    """The differences of file rel between the trees, as lines."""
    a, b = os.path.join(old, rel), os.path.join(new, rel)
    if rel.endswith(".png"):
        return []
    if rel.endswith(".h5"):
        x, y = h5_items(a), h5_items(b)
        return ["%s: %s %s" % (rel, k, "differs" if k in x and k in y else "only in " + ("old" if k in x else "new"))
                for k in sorted(set(x) | set(y)) if x.get(k) != y.get(k)]
    if rel.endswith(".json"):
        try:
            same = strip_json(json.load(open(a))) == strip_json(json.load(open(b)))
        except ValueError:  # not JSON (a failed command's empty stdout): the bytes
            same = open(a, "rb").read() == open(b, "rb").read()
    elif rel.endswith(".csv"):
        same = csv_rows(a) == csv_rows(b)
    else:
        same = open(a, "rb").read() == open(b, "rb").read()
    return [] if same else [rel + ": differs"]


def files(root):
    return {os.path.relpath(os.path.join(d, n), root) for d, _, names in os.walk(root) for n in names}


def main(old, new):
    found = []
    a, b = files(old), files(new)
    found += [rel + ": only in old" for rel in sorted(a - b)]
    found += [rel + ": only in new" for rel in sorted(b - a)]
    for rel in sorted(a & b):
        found += differences(old, new, rel)
    for line in found:
        print(line)
    print("identical (%d files)" % len(a) if not found else "%d differences" % len(found))
    return 1 if found else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: same_outputs.py OLD_DIR NEW_DIR")
    sys.exit(main(sys.argv[1], sys.argv[2]))
