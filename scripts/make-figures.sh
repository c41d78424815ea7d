#!/usr/bin/env bash
# Regenerates the figures in docs/figures/ from the paper's cases and the worked sweep studies
# (docs/sweep-study.md); the README and docs show them.
#   scripts/make-figures.sh [BUILD_DIR]
# With TD_FIGURES_TABLES=DIR set, the two study sweeps' tables (study.csv, study-drop.csv) are also
# copied to DIR (scripts/make-docs.sh --full records them in docs/results/figures.json).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tool=${1:-$here/build}/touchdown
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
for c in a b c; do
    "$tool" run -q --csv '' -o "paper-$c" "$here/cases/paper-$c.cfg"
done
"$tool" modal -q --csv '' -o paper-a-modal "$here/cases/paper-a.cfg"
# the worked study: docs/sweep-study.md gives these commands and what they take
"$tool" sweep -j 1 --vary speed=50:250:41 --vary 'unbalances[0].magnitude=0.005,0.01,0.015,0.02,0.05,0.1' -o study \
    "$here/cases/study-a.cfg" >/dev/null
"$tool" plot -q -d study study.h5
"$tool" plot -q -d study-log --log-y study.h5 # the regime map over the unbalances' decades
# the second study, the drop: docs/sweep-study.md, "A second study: the drop"
"$tool" sweep -j 2 -o study-drop "$here/cases/study-drop.cfg" >/dev/null
"$tool" plot -q -d study-drop --log-x --x 'retainers[0].race.drag_torque' --y speed study-drop.h5
"$tool" plot -q -d study-drop --log-x --x 'retainers[0].race.drag_torque' --quantity ending_whirl_frequency study-drop.h5
"$tool" plot -q -d a --retainer 0 paper-a.h5
"$tool" plot -q -d b --retainer 0 paper-b.h5
"$tool" plot -q -d ac --retainer 0 paper-a.h5 paper-c.h5
"$tool" plot -q -d m paper-a-modal.h5
out=$here/docs/figures
mkdir -p "$out"
cp a/orbit-r0.png "$out/paper-a-orbit-r0.png"
cp a/radial-force-r0.png "$out/paper-a-radial-force-r0.png"
cp b/orbit-r0.png "$out/paper-b-orbit-r0.png"
cp b/radial-force-r0.png "$out/paper-b-radial-force-r0.png"
cp ac/compare-r0.png "$out/paper-a-vs-c-compare-r0.png"
cp m/campbell.png "$out/paper-a-campbell.png"
cp m/mode-shapes.png "$out/paper-a-mode-shapes.png"
cp study-log/regime-map.png "$out/study-a-regime-map.png"
cp study/bifurcation.png "$out/study-a-bifurcation.png"
cp study/sweep-peak_housing_force.png "$out/study-a-peak-housing-force.png"
cp study-drop/regime-map.png "$out/study-drop-regime-map.png"
cp study-drop/sweep-peak_housing_force.png "$out/study-drop-peak-housing-force.png"
cp study-drop/sweep-ending_whirl_frequency.png "$out/study-drop-whirl-frequency.png"
if [ -n "${TD_FIGURES_TABLES:-}" ]; then
    cp study.csv study-drop.csv "$TD_FIGURES_TABLES/"
fi
echo "make-figures: wrote $(ls "$out" | wc -l) figures to $out"
