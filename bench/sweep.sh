#!/usr/bin/env bash
# Throughput of `touchdown sweep`: the same 100-point sweep (cases/rub-damped.cfg to 0.2 s over
# 10 speeds x 10 unbalance steps) with -j 1, -j 2 and, when touchdown is built with MPI,
# `mpirun -np 2` (one worker a rank), alternating, REPEATS times each.
# Prints per run the wall time, the CPU time of the sweep and its workers, the sum of the points'
# own wall times and the load average before it; then the median wall-time ratios -j 1 / -j 2 and
# -j 1 / mpirun -np 2, and checks that every table is the same apart from its wall-time column.
# Usage: bench/sweep.sh [REPEATS]   (TOUCHDOWN=path/to/touchdown, default build/touchdown;
#        MPIRUN=the launcher, default mpirun)
set -euo pipefail
repeats=${1:-3}
tool=$(realpath "${TOUCHDOWN:-build/touchdown}")
mpirun=${MPIRUN:-mpirun}
src=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
args=(--set end_time=0.2 --vary speed=60:150:10 --vary 'schedule[0].magnitude=0.05:0.2:10')
no_wall() { sed '/^#/!s/,[^,]*$//' "$1"; }
modes=("1" "2")
if "$tool" --version | grep -q '^built with MPI' && command -v "$mpirun" >/dev/null; then
    modes+=("np2")
    if "$mpirun" --version 2>&1 | grep -q 'Open MPI'; then
        export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
    fi
fi

echo "# touchdown sweep -j J ${args[*]} cases/rub-damped.cfg"
echo "# $(nproc) online CPUs; $(uname -srm)"
printf '%-4s %-6s %9s %9s %12s  %s\n' run jobs "wall s" "CPU s" "points s" "load average before"
for r in $(seq 1 "$repeats"); do
    for j in "${modes[@]}"; do
        load=$(cut -d' ' -f1-3 /proc/loadavg)
        cmd=("$tool" sweep -q -j "$j")
        [ "$j" = np2 ] && cmd=("$mpirun" -np 2 "$tool" sweep -q -j 1) # two ranks of one worker each
        /usr/bin/time -f '%e %U %S' -o "$work/time" "${cmd[@]}" "${args[@]}" -o "$work/r$r-j$j" \
            "$src/cases/rub-damped.cfg"
        read -r wall user sys <"$work/time"
        points=$(awk -F, '!/^#/ && NR > 1 { s += $NF } END { printf "%.2f", s }' "$work/r$r-j$j.csv")
        printf '%-4s %-6s %9s %9.2f %12s  %s\n' "$r" "$j" "$wall" "$(echo "$user + $sys" | bc)" "$points" "$load"
        echo "$j $wall" >>"$work/walls"
        cmp -s <(no_wall "$work/r1-j1.csv") <(no_wall "$work/r$r-j$j.csv") || echo "TABLE DIFFERS: run $r -j $j"
    done
done
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
m1=$(awk '$1 == 1 { print $2 }' "$work/walls" | median)
m2=$(awk '$1 == 2 { print $2 }' "$work/walls" | median)
echo "median wall time: -j 1 $m1 s, -j 2 $m2 s, ratio -j 1 / -j 2 = $(echo "scale=2; $m1 / $m2" | bc)"
if [ "${#modes[@]}" = 3 ]; then
    m3=$(awk '$1 == "np2" { print $2 }' "$work/walls" | median)
    echo "median wall time: mpirun -np 2 $m3 s, ratio -j 1 / mpirun -np 2 = $(echo "scale=2; $m1 / $m3" | bc)"
fi
