#!/usr/bin/env bash
# Mesh and tolerance convergence of a case's answers: runs CASE at shaft.refine 1, 2, 4, 8 (12 to
# 96 elements on the rig) and at two solver tolerances, and prints the answers that should converge
# (peak housing force, total impulse, friction work, time in contact, final speed) with the
# instantaneous peak normal force beside them, how the run ended, and the change from 48 to 96
# elements.
#
#   bench/convergence.sh [-b TOUCHDOWN] CASE [KEY=VALUE ...]   (extra --set overrides for every run)
#
# Output: one line per run, then the relative 48 -> 96 changes per tolerance. Needs python3 to read
# the --json summaries.
set -euo pipefail
bin=${TOUCHDOWN:-touchdown}
if [ "${1:-}" = "-b" ]; then bin=$2; shift 2; fi
case_file=${1:?usage: bench/convergence.sh [-b TOUCHDOWN] CASE [KEY=VALUE ...]}
shift
sets=()
for kv in "$@"; do sets+=(--set "$kv"); done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for tol in "1e-6 1e-9" "1e-7 1e-10"; do
  set -- $tol
  for refine in 1 2 4 8; do
    "$bin" run -q --json --hdf5 "" --csv "" "${sets[@]}" --set shaft.refine=$refine --set solver.rtol=$1 \
      --set solver.atol=$2 "$case_file" > "$tmp/r$refine-$1.json"
  done
done
python3 - "$tmp" <<'PY'
import json, sys, os
d = sys.argv[1]
keys = ["peak_housing_force", "total_impulse", "friction_work", "contact_time", "final_speed", "peak_normal_force"]
print("%-7s %-9s %-8s" % ("rtol", "elements", "wall s") + "".join("%22s" % k for k in keys) + "  ending")
for rtol in ["1e-6", "1e-7"]:
    rows = {}
    for refine in [1, 2, 4, 8]:
        r = json.load(open(os.path.join(d, "r%d-%s.json" % (refine, rtol))))
        rows[refine] = r
        print("%-7s %-9d %-8.2f" % (rtol, 12 * refine, r["wall_time"]) + "".join("%22.8g" % r[k] for k in keys) +
              "  " + r.get("ending", ""))
    print("%-7s 48->96 change  " % rtol + "".join(
        "%21.3f%%" % (100.0 * (rows[8][k] - rows[4][k]) / rows[4][k] if rows[4][k] else 0.0) for k in keys))
PY
