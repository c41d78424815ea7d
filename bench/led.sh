#!/usr/bin/env bash
# The drop's led quantities against the mesh: runs CASE at shaft.refine 2, 4, 8 (24, 48, 96
# elements on the rig) at the case's tolerances with the energy account on, one run at a time, and
# prints each candidate answer at the three meshes with its change from 48 to 96 elements, marking
# those that move more than 2 %: the run's totals and peaks, the energy lost, each retainer's
# totals and bearing duty (docs/theory.md, "The bearing's duty"), its heat and life when the case
# gives a thermal network and a dynamic rating, the sensors' peaks, and means over time windows of
# the sampled normal force, friction power and race speed.
#
#   bench/led.sh [-b TOUCHDOWN] CASE [KEY=VALUE ...]   (extra --set overrides for every run, e.g. a
#                                                    retainers[0].bearing for the duty's PV and stress)
#
# Needs python3 with h5py (scripts/setup.sh installs it) to read the samples.
set -euo pipefail
bin=${TOUCHDOWN:-touchdown}
if [ "${1:-}" = "-b" ]; then bin=$2; shift 2; fi
case_file=${1:?usage: bench/led.sh [-b TOUCHDOWN] CASE [KEY=VALUE ...]}
shift
sets=()
for kv in "$@"; do sets+=(--set "$kv"); done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for refine in 2 4 8; do
  "$bin" run -q --json --csv "" --hdf5 "$tmp/r$refine.h5" "${sets[@]}" --set shaft.refine=$refine --set energy=true \
    "$case_file" > "$tmp/r$refine.json"
done
exec "$(command -v /usr/bin/python3 || command -v python3)" "$(dirname "${BASH_SOURCE[0]}")/led.py" "$tmp"
