#!/usr/bin/env bash
# Accuracy of a case's contact sequence against a converged reference: runs CASE once at the
# reference settings (default: rtol 1e-11, atol 1e-14 m, BDF order <= 5) and once per setting given,
# and prints for each the CPU time, the contact intervals, and the largest error of the first N
# contact intervals' starts, ends and peak normal forces against the reference (N = 10 unless -n).
#
#   bench/intervals.sh [-b TOUCHDOWN] [-n N] [-r "KEY=VALUE ..."] CASE "KEY=VALUE ..." ...
#
# Each quoted argument after CASE is one setting: space-separated --set overrides ("" for the
# case's own). Example, case B to 0.3 s at BDF order 2 and 5:
#   bench/intervals.sh cases/paper-b.cfg "end_time=0.3" "end_time=0.3 solver.max_order=5"
# The reference takes the end_time of the first setting. Needs python3 to read the events files.
set -euo pipefail
bin=${TOUCHDOWN:-touchdown}
count=10
ref_sets="solver.rtol=1e-11 solver.atol=1e-14 solver.max_order=5"
while [ $# -gt 0 ]; do
  case $1 in
    -b) bin=$2; shift 2 ;;
    -n) count=$2; shift 2 ;;
    -r) ref_sets=$2; shift 2 ;;
    *) break ;;
  esac
done
case_file=${1:?usage: bench/intervals.sh [-b TOUCHDOWN] [-n N] [-r SETS] CASE SETS ...}
shift
[ $# -gt 0 ] || { echo "bench/intervals.sh: no setting to compare" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
end_of() { # the end_time=... of a setting, if it has one
  local kv
  for kv in $1; do case $kv in end_time=*) echo "$kv" ;; esac; done
}
run() { # run NAME SETS: events to $tmp/NAME.events.csv, CPU seconds to $tmp/NAME.cpu
  local name=$1 kv args=()
  for kv in $2; do args+=(--set "$kv"); done
  /usr/bin/env time -f %U -o "$tmp/$name.cpu" "$bin" run -q --hdf5 "" --csv "$tmp/$name.csv" \
    --set output.sample_rate=1000 "${args[@]}" "$case_file"
}
run ref "$ref_sets $(end_of "$1")"
i=0
for sets in "$@"; do
  run "s$i" "$sets"
  echo "$sets" > "$tmp/s$i.sets"
  i=$((i + 1))
done
python3 - "$(dirname "${BASH_SOURCE[0]}")" "$tmp" "$i" "$count" "$ref_sets" <<'PY'
import os, sys
sys.path.insert(0, sys.argv[1])
from contact_intervals import contact_intervals
d, runs, n, ref_sets = sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]

def intervals(name):
    return contact_intervals(os.path.join(d, name + ".events.csv"))

def cpu(name):
    return float(open(os.path.join(d, name + ".cpu")).read().split()[-1])

ref = intervals("ref")
print("reference (%s): %d intervals, %.2f s CPU" % (ref_sets, len(ref), cpu("ref")))
print("%-58s %8s %10s %12s %12s %12s" % ("setting", "CPU s", "intervals", "start err s", "end err s",
                                         "peak err"))
for i in range(runs):
    run = intervals("s%d" % i)
    m = min(n, len(ref), len(run))
    ds = max((abs(a[0] - b[0]) for a, b in zip(ref[:m], run[:m])), default=float("nan"))
    closed = [(a, b) for a, b in zip(ref[:m], run[:m]) if a[1] and b[1]]
    de = max((abs(a[1] - b[1]) for a, b in closed), default=float("nan"))
    dp = max((abs(a[2] - b[2]) / a[2] for a, b in closed if a[2] > 0), default=float("nan"))
    sets = open(os.path.join(d, "s%d.sets" % i)).read().strip() or "(the case's own)"
    print("%-58s %8.2f %10d %12.2e %12.2e %12.2e" % (sets, cpu("s%d" % i), len(run), ds, de, dp))
PY
