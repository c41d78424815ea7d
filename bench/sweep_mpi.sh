#!/usr/bin/env bash
# The cost model of `touchdown sweep` under MPI, at 1 and 2 ranks (one worker each) beside the
# sweep without MPI (-j 1):
#   start-up   a sweep of one trivially short point (cases/rub-damped.cfg to 1e-4 s): launch,
#              MPI_Init, the check, one fork, the table, MPI_Finalize; wall time from outside,
#              REPEATS times each;
#   10,000     10,000 trivially short points (10,000 speeds): the check of every point's case
#              (check_time), the merge of the parts and the writing of the 10,000-row table
#              (merge_time), and what the sweep adds per point beyond the points' own wall
#              times (hand-out, fork, pipe): (wall - merge) x workers - sum of the points, wall
#              being the JSON wall_time (from the end of the check to the end of the table);
#   realistic  20 points of cases/rub-damped.cfg to its own end (2 s simulated; 10 speeds x 2
#              unbalance steps): wall time, CPU time, mean wall time of a point.
# Every table of a group is checked equal to the first (wall-time column cut).
# Usage: bench/sweep_mpi.sh [REPEATS]   (TOUCHDOWN=path/to/touchdown, default build/touchdown;
#        MPIRUN=the launcher, default mpirun)
set -euo pipefail
repeats=${1:-3}
tool=$(realpath "${TOUCHDOWN:-build/touchdown}")
mpirun=${MPIRUN:-mpirun}
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
case_r=$src/cases/rub-damped.cfg
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tool" --version | grep -q '^built with MPI' || { echo "touchdown is built without MPI" >&2; exit 1; }
if "$mpirun" --version 2>&1 | grep -q 'Open MPI'; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fi
no_wall() { sed '/^#/!s/,[^,]*$//' "$1"; }
jf() { grep -oE "\"$2\":[^,}]*" "$1" | head -n 1 | sed -E "s/^\"$2\"://"; }
points_sum() { awk -F, '!/^#/ && NR > 1 { s += $NF } END { printf "%.3f", s }' "$1"; }

# run LABEL NAME ARGS...: the sweep without MPI (LABEL "-j 1") or under mpirun -np R (LABEL
# "np R"), in $work, its JSON in $work/NAME.json and /usr/bin/time's "wall user sys" in NAME.time.
run() {
    local label=$1 name=$2
    shift 2
    local launch=()
    [ "$label" != "-j 1" ] && launch=("$mpirun" -np "${label#np }")
    (cd "$work" && /usr/bin/time -f '%e %U %S' -o "$name.time" "${launch[@]}" "$tool" sweep --json -j 1 "$@" \
        -o "$name" "$case_r" >"$name.json")
}
same() { cmp -s <(no_wall "$work/$1.csv") <(no_wall "$work/$2.csv") || echo "TABLE DIFFERS: $2"; }

echo "# touchdown $("$tool" --version | head -n 1 | cut -d' ' -f2); $("$tool" --version | tail -n 1)"
echo "# $(nproc) online CPUs; $(uname -srm); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

echo "## start-up: one point of 1e-4 s (wall s from outside; the point's own wall s)"
printf '%-6s %-4s %8s %10s %9s\n' layout run "wall s" "point s" "check s"
for r in $(seq 1 "$repeats"); do
    for l in "-j 1" "np 1" "np 2"; do
        n=start-${l// /}-$r
        run "$l" "$n" --set end_time=1e-4 --vary speed=90
        printf '%-6s %-4s %8s %10s %9.4f\n' "$l" "$r" "$(cut -d' ' -f1 "$work/$n.time")" \
            "$(points_sum "$work/$n.csv")" "$(jf "$work/$n.json" check_time)"
        same start--j1-1 "$n"
    done
done

echo "## 10,000 points of 1e-4 s"
printf '%-6s %8s %8s %8s %10s %10s %s\n' layout "wall s" "check s" "merge s" "points s" "added ms" "load before"
for l in "-j 1" "np 1" "np 2"; do
    n=tenk-${l// /}
    load=$(cut -d' ' -f1-3 /proc/loadavg)
    run "$l" "$n" --set end_time=1e-4 --vary speed=60:150:10000
    wall=$(jf "$work/$n.json" wall_time)
    check=$(jf "$work/$n.json" check_time)
    merge=$(jf "$work/$n.json" merge_time)
    workers=$(($(jf "$work/$n.json" ranks) * $(jf "$work/$n.json" jobs)))
    sum=$(points_sum "$work/$n.csv")
    added=$(echo "scale=3; (($wall - $merge) * $workers - $sum) * 1000 / 10000" | bc)
    printf '%-6s %8.2f %8.3f %8.3f %10s %10s %s\n' "$l" "$wall" "$check" "$merge" "$sum" "$added" "$load"
    same tenk--j1 "$n"
done
ls -l "$work"/tenk--j1.csv "$work"/tenk--j1.h5 | awk '{ print "# table files: " $5 " bytes " $NF }' | sed "s|$work/||"

echo "## realistic: 20 points of rub-damped to 2 s"
printf '%-6s %8s %8s %12s %s\n' layout "wall s" "CPU s" "mean point s" "load before"
for l in "-j 1" "np 1" "np 2"; do
    n=real-${l// /}
    load=$(cut -d' ' -f1-3 /proc/loadavg)
    run "$l" "$n" --vary speed=60:150:10 --vary 'schedule[0].magnitude=0.05,0.2'
    read -r wall user sys <"$work/$n.time"
    printf '%-6s %8s %8.2f %12.3f %s\n' "$l" "$wall" "$(echo "$user + $sys" | bc)" \
        "$(echo "$(points_sum "$work/$n.csv") / 20" | bc -l)" "$load"
    same real--j1 "$n"
done
