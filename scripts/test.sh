#!/usr/bin/env bash
# Install what is missing, build (scripts/setup.sh: warnings as errors, the configuration
# scripts/quickstart.sh uses too), check the installed package builds the embedding example, and
# run the whole test suite; then, as a second pass, the same suite built with AddressSanitizer +
# UndefinedBehaviorSanitizer in its own build directory (scripts/sanitize.sh).
# TD_SANITIZE_PASS=0 skips the second pass.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/scripts/setup.sh" "$here/build"

# the install, from a moved prefix with no LD_LIBRARY_PATH: the installed tool runs a case, the
# embedding example builds with find_package and pkg-config (shared and static) and runs, the docs
"$here/scripts/check-install.sh" "$here/build"

echo "test: pass 1 of 2: the suite ($here/build)"
ctest --test-dir "$here/build" --output-on-failure --parallel "$(nproc)"
if [ "${TD_SANITIZE_PASS:-1}" != 0 ]; then
    echo "test: pass 2 of 2: the suite under ASan + UBSan ($here/build-sanitize)"
    "$here/scripts/sanitize.sh" "$here/build-sanitize"
fi
