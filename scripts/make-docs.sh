#!/usr/bin/env bash
# Regenerates every number and figure the documentation quotes from the tool: reruns them, records
# them in docs/results/*.json (one file per source, stamped with the tool's version, the source
# revision, the date, the machine and the commands), then rewrites the generated regions of
# README.md and docs/*.md from those records (<!-- generated: NAME --> ... <!-- end generated -->
# blocks and <!-- gen: NAME -->...<!-- /gen --> spans; scripts/docs_render.py says which is which).
#   scripts/make-docs.sh [BUILD_DIR]           the fast part: the shipped cases as they are, the
#                                              critical speeds, the validation tests quoted, the
#                                              case keys (about 55 s on 2 cores)
#   scripts/make-docs.sh --full [BUILD_DIR]    also the slow part: touchdown bench, bench/digital.sh
#                                              (about 1 min of CPU), the paper's cases
#                                              at converged settings, tolerance, mesh and convergence
#                                              studies, the spread of the answers of the paper's cases,
#                                              the drop and the damped rub (touchdown run --spread 5,
#                                              about 2 min of CPU), the figures of the paper's cases
#                                              (scripts/make-figures.sh), the sweep study (scripts/sweep_study.py
#                                              with its figures; its record gives its CPU and wall time), and
#                                              touchdown bench --scaling (about 6 min of CPU more: its
#                                              record says how much)
#   scripts/make-docs.sh --render              only rewrite the regions from the recorded results
#   scripts/make-docs.sh --full --only SOURCE  rerun one source (runs, modal, validation, keys, bench,
#                                              digital, scaling, references, intervals, tolerances, mesh,
#                                              convergence, spread, figures, recovery, report, drop_sweep,
#                                              shock, sweep_study, breakdown, leap-check), then render; breakdown
#                                              (bench/breakdown.sh, about 1 min of CPU and perf) measures
#                                              beside the tool the build in TD_BENCH_BEFORE when that is set
#                                              (twice the time); leap-check (bench/leap-check.sh, about
#                                              6 min of CPU) the leap against the full integration
# BUILD_DIR defaults to ./build (scripts/setup.sh builds it). tests/cli/test_docs.sh checks that
# the docs match the records and that the tool still prints the recorded numbers.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=fast
build=$here/build
only=()
while [ $# -gt 0 ]; do
    case $1 in
    --full) mode=full ;;
    --render) mode=render ;;
    --only) only+=("$2"); shift ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) build=$(cd "$1" && pwd) ;;
    esac
    shift
done
py=/usr/bin/python3
[ -x "$py" ] || py=python3
start=$(date +%s)
if [ "$mode" != render ]; then
    if [ ! -x "$build/touchdown" ]; then
        echo "make-docs: no tool at $build/touchdown: build it first (scripts/setup.sh $build)" >&2
        exit 2
    fi
    if [ ${#only[@]} -gt 0 ]; then
        fast=() slow=()
        for s in "${only[@]}"; do
            case $s in runs | modal | validation | keys) fast+=("$s") ;; *) slow+=("$s") ;; esac
        done
        [ ${#fast[@]} -eq 0 ] || "$py" "$here/scripts/docs_record.py" "$build" fast "${fast[@]}"
        [ ${#slow[@]} -eq 0 ] || "$py" "$here/scripts/docs_record.py" "$build" slow "${slow[@]}"
    else
        "$py" "$here/scripts/docs_record.py" "$build" fast
        fast_end=$(date +%s)
        echo "make-docs: fast part $((fast_end - start)) s"
        if [ "$mode" = full ]; then
            "$py" "$here/scripts/docs_record.py" "$build" slow
            echo "make-docs: slow part $(($(date +%s) - fast_end)) s"
        fi
    fi
fi
"$py" "$here/scripts/docs_render.py"
echo "make-docs: done in $(($(date +%s) - start)) s"
