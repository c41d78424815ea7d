#!/usr/bin/env bash
# Quick start: install what is missing, build (scripts/setup.sh, the same configuration as
# scripts/test.sh, so running that next rebuilds nothing), and run the paper's case A from the
# repository root into out/ with the first command of README.md's tour, so the tour's paths
# (out/paper-a.h5, ...) are there after it.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh" "$here/build"
cd "$here"
mkdir -p out
build/touchdown run -o out/paper-a cases/paper-a.cfg
echo "quickstart: case A's results are in out/ (paper-a.h5, paper-a.csv, paper-a.events.csv);" \
    "next: README.md, 'A five-minute tour'"
