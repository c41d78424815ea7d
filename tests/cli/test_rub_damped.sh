#!/usr/bin/env bash
# cases/rub-damped.cfg through the tool, end to end: the case's own overrides give the rig's
# retainers races on mounts with compliant contacts and rolling; the run leads its summary with
# the answers that converge, --json carries them (checked by Python's json module, an independent
# parser) with the energy account, and the HDF5 file and the CSV have the race columns. Physics
# checked here, not only presence: the races roll (most of the contact time without slip), the
# whirl is forward at the spin frequency, the energy balance closes, the mount force stays below
# what the contact force could give (a mount in series only softens).
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/rub-damped.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, h5py_python, finish

t "$work/run" run --json -o "$work/run/rub" --set end_time=0.6 --set energy=true "$src/cases/rub-damped.cfg"
check "rub-damped to 0.6 s: exit 0" test "$rc" = 0
out=$work/run/.out
check "the summary leads with the answers that converge" python3 - "$out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
keys = list(d)
assert keys.index("peak_housing_force") < keys.index("peak_normal_force"), keys
assert d["peak_normal_force_converges"] is True          # compliant contacts: no rigid peak
assert d["peak_housing_force"] > 0 and d["total_impulse"] > 0 and d["friction_work"] > 0
assert d["final_speed"] == 90
w = d["retainer_whirl"][0]
assert w.startswith("forward rolling"), w               # the race rolls with the shaft
assert abs(d["retainer_whirl_frequency"][0] - 90 / (2 * 3.141592653589793)) < 0.05 * 14.3
assert d["retainer_rolling_time"][0] > 0.5 * d["retainer_contact_time"][0]
e = d["energy"]
big = max(e["external_work"], e["drive_work"], e["damping_loss"], e["contact_loss"], e["drag_loss"])
assert abs(e["residual"]) < 1e-3 * big, e
print("ok", d["peak_housing_force"], d["total_impulse"], d["friction_work"], w, e["residual"] / big)
PY
py=$(h5py_python)
if [ -z "$py" ]; then
    echo "skip: no python3 with h5py (scripts/setup.sh installs python3-h5py): HDF5 race datasets not checked"
else
check "the HDF5 file has the races' datasets and the roll events" "$py" - "$work/run/rub.h5" <<'PY'
import sys
import h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
w = f["retainers/race_speed"][:, 0]
roll = f["retainers/rolling"][:, 0]
xr, yr = f["retainers/race_x"][:, 0], f["retainers/race_y"][:, 0]
assert f["retainers/race_speed"].attrs["units"] in (b"rad/s", "rad/s")
assert roll.max() == 1 and w.max() > 80.0                # spun up to rolling, about the spin speed
n = f["retainers/normal_force"][:, 0]
assert np.hypot(xr, yr).max() * 1e8 < 1.05 * n.max()     # mount force <= contact force (in series)
imp = f.attrs["retainer_impulse"]
assert len(imp) == 2 and abs(imp.sum() - f.attrs["summary_total_impulse"]) <= 1e-9 * imp.sum()
assert f.attrs["retainer_contacts"][0] >= 1 and f.attrs["retainer_rolling_time"][0] > 0
kinds = set(f["events"]["kind"])
assert {6, 7} <= {int(k) for k in kinds}, kinds          # roll_start, roll_end
PY
fi
check "the CSV has the race columns" grep -q "wr_ret0 \[rad/s\],rolling_ret0 \[-\]" "$work/run/rub.csv"
finish
