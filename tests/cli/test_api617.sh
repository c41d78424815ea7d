#!/usr/bin/env bash
# The API 617 report of `touchdown modal` (docs/api617.md) on case A (gravity off, two retainers of
# 0.75 mm at nodes 2 and 10, no operating range):
#   - without gravity the static reactions are no quantity: the text says "no gravity in the case",
#     the files hold NaN (never zeros); with gravity on they are numbers again;
#   - undefined values of the peak table (N_2, AF, margins) print "n/a" in the text, NaN stays in
#     the files;
#   - API 617's amplitude check at the retainers (/running_clearance and the CSV section) against
#     the swept response in the same file: the amplitude is at least the largest grid value of the
#     retainer's node (and at most 5 % above it: the grid's refinement), the ratio is amplitude over
#     clearance, the verdict is ratio <= fraction.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
case_a=$src/cases/paper-a.cfg
work=$(mktemp -d "${PWD}/api617.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

t "$work/a" modal "$case_a" -o m
check "case A modal: exit 0 (got $rc: $(head -c 300 "$work/a/.err"))" test "$rc" = 0
check "case A: 'no gravity in the case' in the text" grep -q "static reactions: none, no gravity in the case" \
    "$work/a/.out"
check "case A: no static reaction printed as a number" \
    sh -c "! grep -qE '^  (amb|bearing) [0-9]+, node [0-9]+: x' '$work/a/.out'"
table=$(sed -n '/^API 617 peaks/,/^ISO 14839-2\|^API 617 amplitude/p' "$work/a/.out")
check "case A: the peak table prints no nan" sh -c "! printf '%s' '$table' | grep -q nan"
check "case A: the peak table prints n/a where undefined" sh -c "printf '%s' '$table' | grep -q 'n/a'"
check "case A: the amplitude check at the retainers is printed" \
    grep -q "^API 617 amplitude at the retainers (close clearances) over the whole sweep" "$work/a/.out"
check "case A CSV: the static reactions are nan" \
    sh -c "sed -n '/^# section: static_reactions/,/^\$/p' '$work/a/m.csv' | grep -E '^(amb|bearing),' | grep -qv ',nan,nan\$' && exit 1 || exit 0"
check "case A CSV: a running_clearance section" grep -q "^# section: running_clearance" "$work/a/m.csv"

py=$(h5py_python)
if [ -z "$py" ]; then
    fail "no python3 with h5py and numpy (scripts/setup.sh installs python3-h5py)"
    finish
fi
out=$("$py" - "$work/a/m.h5" <<'PY' 2>&1
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
amb = f["static_reactions/amb_force"][...]
assert amb.size > 0 and np.all(np.isnan(amb)), f"static reactions without gravity: {amb}"
ur, rc = f["unbalance_response"], f["running_clearance"]
nodes = list(ur["node"][...])
frac = rc.attrs["fraction"]
assert frac == 0.75, frac
assert rc.attrs["speed_min"] == ur["speed"][0] and rc.attrs["speed_max"] == ur["speed"][-1]
for i, node in enumerate(rc["node"][...]):
    grid = np.nanmax(ur["major"][:, nodes.index(node)])
    a, c, q, v = rc["amplitude"][i], rc["clearance"][i], rc["ratio"][i], rc["verdict"][i]
    assert grid <= a <= 1.05 * grid, (node, a, grid)
    assert abs(q - a / c) <= 1e-12 * q, (q, a, c)
    assert v == (1 if q <= frac else 0), (v, q)
    print(f"retainer {i} node {node}: amplitude {a:.6g} m (grid {grid:.6g}), clearance {c:.6g} m, ratio {q:.4g}, verdict {v}")
PY
)
check "case A HDF5: NaN static reactions, /running_clearance against /unbalance_response ($out)" \
    test -n "$out" -a "$(printf '%s' "$out" | grep -c '^retainer')" = 2

# a modal file whose arrays disagree in shape (edited, or written by another program): `touchdown plot`
# refuses it in one line naming the group, and never reads past the shorter array (which the
# sanitizer pass would catch); the file as written plots. Each cut AXIS:DATASET[,DATASET...] drops
# the last row (axis 0) or column (axis 1) of the datasets named, the rest of the file as written:
# /loop's sensitivity (both parts, so that the pair agree) one controlled axis short of the open
# loop L, which is read at the sensitivity's columns; /modes' optional damping ratios and node
# positions, which the plot read as absent when their size was wrong (overdamped modes kept, the
# axis without positions) and now refuses.
t "$work/a" plot -d plots m.h5
check "case A modal file plots: exit 0 (got $rc: $(head -c 300 "$work/a/.err"))" test "$rc" = 0
for cut in 0:unbalance_response/x_amp 0:unbalance_response/major 0:response_peaks/amplitude \
    0:response_peaks/amplification 1:loop/sensitivity_re,loop/sensitivity_im 0:loop/open_loop_re \
    0:modes/zeta 0:modes/node_z; do
    axis=${cut%%:*}
    names=${cut#*:}
    tag=${names%%,*}
    tag=${tag//\//-}
    bad=$work/a/cut-$tag.h5
    IFS=, read -ra datasets <<<"$names"
    "$py" - "$work/a/m.h5" "$bad" "$axis" "${datasets[@]}" <<'PY'
import shutil, sys, h5py
shutil.copyfile(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    for name in sys.argv[4:]:
        data = f[name][...]
        del f[name]
        # one row (or column) fewer than its group's other arrays
        f[name] = data[:-1] if sys.argv[3] == "0" else data[:, :-1]
PY
    t "$work/a" plot -d "plots-$tag" "$bad"
    group=${names%%/*}
    what=$([ "$axis" = 0 ] && echo row || echo column)
    check "plot of a modal file with $names one $what short: exit 2, one line naming /$group (got $rc: $(head -c 300 "$work/a/.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$work/a/.err")" = 1 -a -n "$(grep "unreadable /$group group" "$work/a/.err")"
done

t "$work/g" modal --set 'gravity={enabled=true; g=9.81; direction=[0.0,-1.0];}' "$case_a" -o m
check "case A with gravity: exit 0 (got $rc)" test "$rc" = 0
check "case A with gravity: the static reactions are printed as numbers" \
    grep -qE '^  amb 0, node [0-9]+: x [-0-9.e]+, y [-0-9.e]+$' "$work/g/.out"
finish
