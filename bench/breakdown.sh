#!/usr/bin/env bash
# Where the CPU time of a run goes, per IDA step: the cost breakdown of docs/performance.md
# ("Cost per step"). A benchmark, not a test: it asserts no limit.
#
#   bench/breakdown.sh [-n REPEATS] [--json] [--before OLD_BUILD_DIR] [--cases a,b,...] [--no-profile] [BUILD_DIR]
#
# For each case (default cases/drop.cfg, rub-damped.cfg, paper-b.cfg, as shipped, no output files):
# REPEATS runs (default 3) of `touchdown run`, the CPU time (user + system of the tool's process)
# printed is the median; with --before, the tool of OLD_BUILD_DIR runs too, the two alternating run
# by run, so that both see the same load. Beside it, the real-time factor on CPU time, the IDA
# steps and restarts from the JSON summary, and the CPU time per step. Then one run of each tool
# under `perf record --call-graph dwarf` (about 3,000 samples), each sample put in a category by
# the functions on its stack (bench/breakdown.py, CATEGORIES: the flight, event handling and
# restart, outputs and per-point monitors, event location, and inside IDA's step the residual, the
# Jacobian's assembly, the factorisation, the linear solve and IDA's own work), and the category's
# time per step its share times the median CPU time over the steps. Derived: the failed attempts
# (Newton and error-test failures, estimated as their share of all attempts of the step's work) and
# the floor (the residual and the linear solve per step, nothing else). Without perf (or without
# permission to use it) the profile is left out and said so. --json prints one JSON object
# (scripts/make-docs.sh records it). BUILD_DIR defaults to ./build of the source tree.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
for a in "$@"; do
    case $a in -h | --help) sed -n '2,21p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;; esac
done
exec /usr/bin/python3 "$here/bench/breakdown.py" "$@"
