#!/usr/bin/env bash
# Install what is missing, build warnings-as-errors, and run the whole test suite.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh" "$here/build" -DTD_WERROR=ON
# the embedding example, built against the installed package (find_package and pkg-config)
"$here/scripts/check-install.sh" "$here/build"
ctest --test-dir "$here/build" --output-on-failure --parallel "$(nproc)"
