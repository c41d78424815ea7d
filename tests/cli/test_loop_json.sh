#!/usr/bin/env bash
# `touchdown modal --json CASE`: the loop analysis as one JSON object (docs/output-format.md,
# "Loop analysis"), checked by python3's json module:
#   - paper case A: stable, one peak, frequency and zone per controlled axis (4), the worst zone
#     the worst of the axes' and the zone each peak's (A < 3 <= B < 4 <= C < 5 <= D), every value
#     the same as the modal HDF5 file's /loop (h5py), and nothing but the object on stdout;
#   - kp ki below ks (an unstable loop): stable false, every sensitivity answer null, exit 0;
#   - a machine without a controlled axis (kp = kd = 0): no analysis, null answers, said on stderr;
#   - cases/rig-notch.cfg (a rigid-body linear controller from the case file): stable, 4 axes;
#   - cases/rig-digital.cfg (a sampled controller, 10 kHz, one sample of delay): the sampled loop,
#     stable, 4 axes, the grid up to the Nyquist frequency (5 kHz), and the zone its comment states;
#   - cases/paper-a-digital.cfg (its sampled loop grows): stable false, every sensitivity answer null.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/cli-loop.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

fast=(--set modal.speed_steps=2) # the loop is at the case speed: a short Campbell grid
# The cases with their own Campbell grids (a, u, n, r) take the short grid too under the sanitizers
# (TD_TEST_SANITIZED=1), where the grids were most of the test's time: the Campbell sweep is the same
# code for 2 speeds, and what this test checks, the loop analysis, is at the case speed either way.
grid=()
sanitized && grid=("${fast[@]}")
t "$work/a" modal --json -o "$work/a/m" "${grid[@]}" "$case_a"
check "modal --json exits 0" [ "$rc" = 0 ]
check "modal --json prints one line, the object" [ "$(wc -l <"$work/a/.out")" = 1 ]
check "the JSON of case A has the loop's shape and the zones follow the peaks" /usr/bin/python3 - "$work/a/.out" "$work/a/m.h5" <<'PY'
import json, sys
import h5py
d = json.load(open(sys.argv[1]))
zone = lambda p: "A" if p < 3 else "B" if p < 4 else "C" if p < 5 else "D"
assert d["stable"] is True and d["max_real_part"] < 1e-6 and d["sample_rate"] is None, d
assert "sample_rate" not in h5py.File(sys.argv[2], "r")["loop"].attrs
n = len(d["axis"])
assert n == 4 and all(len(d[k]) == n for k in ("sensitivity_peak", "sensitivity_peak_frequency", "sensitivity_zones"))
assert all(p > 1 for p in d["sensitivity_peak"])
assert d["sensitivity_zones"] == [zone(p) for p in d["sensitivity_peak"]], d
assert d["sensitivity_zone"] == max(d["sensitivity_zones"]), d
with h5py.File(sys.argv[2], "r") as f:
    g = f["loop"]
    assert list(g["sensitivity_peak"][...]) == d["sensitivity_peak"]
    assert list(g["sensitivity_peak_frequency"][...]) == d["sensitivity_peak_frequency"]
    assert [z.decode() if isinstance(z, bytes) else z for z in g["sensitivity_zones"][...]] == d["sensitivity_zones"]
    assert g.attrs["stable"] == 1 and g.attrs["sensitivity_zone"] == d["sensitivity_zone"]
    s = abs(g["sensitivity_re"][...] + 1j * g["sensitivity_im"][...])
    assert s.shape == (len(g["frequency"]), 4) and (s.max(axis=0) <= d["sensitivity_peak"]).all()
PY

t "$work/u" modal --json -o "$work/u/m" "${grid[@]}" --set 'ambs[0].kp=1000' --set 'ambs[1].kp=1000' "$case_a"
check "an unstable loop: exit 0" [ "$rc" = 0 ]
check "an unstable loop: stable false, every sensitivity answer null" /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["stable"] is False and d["max_real_part"] > 0, d
assert all(d[k] is None for k in ("sensitivity_peak", "sensitivity_peak_frequency", "sensitivity_zones", "sensitivity_zone")), d
' "$work/u/.out"

t "$work/n" modal --json -o "$work/n/m" "${grid[@]}" --set 'ambs[0].kp=0' --set 'ambs[0].kd=0' --set 'ambs[1].kp=0' \
    --set 'ambs[1].kd=0' "$case_a"
check "no controlled axis: exit 0, null answers" /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["stable"] is None and d["sensitivity_peak"] is None and d["sensitivity_zone"] is None, d
' "$work/n/.out"
check "no controlled axis: said on stderr" grep -q "no loop analysis: no AMB axis is under control" "$work/n/.err"

t "$work/r" modal --json -o "$work/r/m" "${grid[@]}" "$src/cases/rig-notch.cfg"
check "a linear controller from the case file (rigid-body PD + notch): exit 0" [ "$rc" = 0 ]
check "a linear controller from the case file: stable, a peak per driven axis" /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["stable"] is True and d["axis"] == [0, 1, 2, 3] and len(d["sensitivity_peak"]) == 4, d
assert all(p > 1 for p in d["sensitivity_peak"]) and d["sensitivity_zone"] in "ABCD", d
' "$work/r/.out"

t "$work/d" modal --json -o "$work/d/m" "${fast[@]}" "$src/cases/rig-digital.cfg"
check "a sampled controller: exit 0" [ "$rc" = 0 ]
check "a sampled controller: stable, 4 axes, the zone the case's comment states, /loop up to 5 kHz" \
    /usr/bin/python3 - "$work/d/.out" "$work/d/m.h5" "$src/cases/rig-digital.cfg" <<'PY'
import json, re, sys
import h5py
d = json.load(open(sys.argv[1]))
said = re.findall(r"^#.*ISO 14839-3\s*(?:\n#)?\s*zone ([A-D])\b", open(sys.argv[3]).read(), re.M)
assert len(said) == 1, said
assert d["stable"] is True and d["max_real_part"] < 0 and d["axis"] == [0, 1, 2, 3], d
assert d["sample_rate"] == 10000, d
assert d["sensitivity_zone"] == said[0], (d["sensitivity_zone"], said)
assert all(1 < p < 1e3 for p in d["sensitivity_peak"]), d
with h5py.File(sys.argv[2], "r") as f:
    g = f["loop"]
    assert g["frequency"][-1] == 5000.0 and g.attrs["stable"] == 1 and g.attrs["sample_rate"] == 10000.0
    assert list(g["sensitivity_peak"][...]) == d["sensitivity_peak"]
PY
t "$work/dt" modal --csv '' --hdf5 '' "${fast[@]}" "$src/cases/rig-digital.cfg"
check "a sampled controller: the text says the loop is the sampled one" \
    grep -q "sampled at 10000 Hz: the sampled axes' loop at the sample instants" "$work/dt/.out"

t "$work/p" modal --json --csv '' --hdf5 '' "${fast[@]}" "$src/cases/paper-a-digital.cfg"
check "an unstable sampled loop: exit 0, stable false, null answers" /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["stable"] is False and d["max_real_part"] > 0 and d["sample_rate"] == 10000, d
assert all(d[k] is None for k in ("sensitivity_peak", "sensitivity_zones", "sensitivity_zone")), d
' "$work/p/.out"

finish
