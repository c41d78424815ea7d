#!/usr/bin/env bash
# Quick start: install what is missing, build, and run the paper's case A (results in out/).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh" "$here/build"
mkdir -p "$here/out"
cd "$here/out"
"$here/build/touchdown" run "$here/cases/paper-a.cfg"
