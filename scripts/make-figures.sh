#!/usr/bin/env bash
# Regenerates the figures in docs/figures/ from the paper's cases; the README and docs show them.
#   scripts/make-figures.sh [BUILD_DIR]
# The sweep studies' figures (docs/figures/study-*.png) are made with the numbers docs/sweep-study.md
# quotes, from the same sweeps, by scripts/sweep_study.py (scripts/make-docs.sh --full --only sweep_study).
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
echo "make-figures: wrote the paper cases' figures to $out"
