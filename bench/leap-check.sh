#!/usr/bin/env bash
# The projective leap against the full integration on a stretch where both run (docs/performance.md,
# "Long runs: the projective leap"). A benchmark and a check, not a test: it asserts no limit.
#
#   bench/leap-check.sh [-n MEMBERS] [--end T] [--json] [BUILD_DIR]
#
# cases/drop-to-rest.cfg to T s (default 20) twice as an ensemble of MEMBERS runs (default 5;
# `touchdown run --spread MEMBERS`, solver.atol within +-1 %: the drop's bounce is chaotic, so one
# run is one draw): integrated throughout (--set leap.burst=0) and with the case's leaps; then the
# leap run once more at leap.factor = 20 (twice the shipped leap). Each answer of the spread (peak
# housing force, impulse, friction work, final speed, contacts, time in contact, ...) is given for
# the leap run against the full ensemble's least, median and greatest, whether it lies inside, and
# whether the two ensembles' ranges meet; the energy account's terms beside; the CPU seconds of
# each. Prints one JSON object (scripts/make-docs.sh --full --only leap-check records it in
# docs/results/leap-check.json).
# BUILD_DIR defaults to ./build of the source tree. About 10 min of CPU at the defaults.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
for a in "$@"; do
    case $a in -h | --help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
done
exec /usr/bin/python3 "$here/bench/leap-check.py" "$@"
