#!/usr/bin/env bash
# Run touchdown's benchmark and keep its results under bench/results/.
#
#   bench/run.sh [--quick] [BUILD_DIR]
#
# BUILD_DIR defaults to ./build of the source tree (configured and built by scripts/setup.sh when
# it has no touchdown tool yet). Writes bench/results/STAMP.txt (the tables) and STAMP-*.json
# (the same numbers as JSON), STAMP = UTC time and host. Runs, in order:
#   1. the paper's cases A, C, B, D, D10 at the case files' tolerances (rtol 1e-6, atol 1e-9);
#   2. the same with the step bounded by 6e-6 s (0.5 / the rig's highest natural frequency), and
#   3. at rtol 1e-8, atol 1e-10: the two settings found to put case A's first contact within
#      1e-7 s of the exact time (at 1. it is 8e-7 s off; docs/performance.md);
#   4. (not with --quick) the scaling study: case A refined to 13, 49, 97 and 193 nodes;
#   5. (not with --quick) extra information, not the rig: the shaft with Rayleigh damping
#      beta = 1e-6 s (damping ratio at most 4 % at the highest mode, 0.006 % at the first), 1 repeat.
# The whole run takes about 7 minutes on 2 cores (--quick: about 10 s). Each step is one
# `touchdown bench` invocation: see `touchdown bench --help` for what is measured and how.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
quick=()
build=$here/build
for arg in "$@"; do
    case $arg in
    --quick) quick=(--quick) ;;
    -h | --help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) build=$arg ;;
    esac
done

tool=$build/touchdown
if [ ! -x "$tool" ]; then
    "$here/scripts/setup.sh" "$build"
fi

out=$here/bench/results
mkdir -p "$out"
stamp=$(date -u +%Y%m%dT%H%M%SZ)-$(hostname -s 2>/dev/null || echo host)
[ ${#quick[@]} -gt 0 ] && stamp=$stamp-quick
revision=$(git -C "$here" describe --always --dirty 2>/dev/null || echo unknown)

{
    echo "# touchdown bench, $stamp, source $revision, tool $tool"
    echo
    echo "## 1. case files' tolerances (rtol 1e-6, atol 1e-9)"
    "$tool" bench "${quick[@]}" --dir "$here/cases" -o "$out/$stamp-default.json"
    echo
    echo "## 2. case files' tolerances, max_step 6e-6 s"
    "$tool" bench "${quick[@]}" --dir "$here/cases" --set solver.max_step=6e-6 -o "$out/$stamp-maxstep.json"
    echo
    echo "## 3. rtol 1e-8, atol 1e-10"
    "$tool" bench "${quick[@]}" --dir "$here/cases" --set solver.rtol=1e-8 --set solver.atol=1e-10 \
        -o "$out/$stamp-tight.json"
    if [ ${#quick[@]} -eq 0 ]; then
        echo
        echo "## 4. scaling: case A refined"
        "$tool" bench --scaling --dir "$here/cases" -o "$out/$stamp-scaling.json"
        echo
        echo "## 5. extra information, not the rig: Rayleigh damping beta = 1e-6 s on the shaft"
        "$tool" bench --repeats 1 --dir "$here/cases" --set "shaft.rayleigh={beta=1e-6;}" \
            -o "$out/$stamp-rayleigh.json"
    fi
} | tee "$out/$stamp.txt"
echo "bench: results in $out/$stamp.txt and $out/$stamp-*.json" >&2
