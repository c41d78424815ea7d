#!/usr/bin/env bash
# Installs the built project into a scratch prefix and builds examples/embed.c against the
# INSTALLED package twice, with find_package(touchdown) and with pkg-config, then runs both.
# This keeps the embedding path from rotting.   scripts/check-install.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
export LD_LIBRARY_PATH="$scratch/prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

echo "check-install: examples/embed.c with find_package(touchdown)"
cmake -S "$here/examples" -B "$scratch/cmake" -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/cmake" >/dev/null
"$scratch/cmake/embed" | tail -n 1

echo "check-install: examples/embed.c with pkg-config"
PKG_CONFIG_PATH="$scratch/prefix/lib/pkgconfig" cc -std=c99 -Wall -Wextra -pedantic -Werror \
    "$here/examples/embed.c" $(PKG_CONFIG_PATH="$scratch/prefix/lib/pkgconfig" pkg-config --cflags --libs touchdown) \
    -o "$scratch/embed-pc"
"$scratch/embed-pc" | tail -n 1
"$scratch/prefix/bin/touchdown" --version

# The cases are installed with the tool, and the installed tool finds them on its own: run from a
# directory without a cases/ folder, 'info' reads an installed case (with its @include of rig.cfg)
# and 'bench' runs case A's short window from PREFIX/share/touchdown/cases.
echo "check-install: the installed cases, and touchdown bench finding them"
cases=$scratch/prefix/share/touchdown/cases
for f in "$here"/cases/*.cfg; do
    [ -f "$cases/$(basename "$f")" ] || { echo "check-install: $(basename "$f") not installed in $cases" >&2; exit 1; }
done
mkdir "$scratch/elsewhere"
(cd "$scratch/elsewhere" && "$scratch/prefix/bin/touchdown" info "$cases/paper-a.cfg" | head -n 1)
(cd "$scratch/elsewhere" && "$scratch/prefix/bin/touchdown" bench --quick --cases A --repeats 1 --json >bench.json)
grep -q '"case":"A"' "$scratch/elsewhere/bench.json" ||
    { echo "check-install: the installed touchdown bench did not run case A" >&2; exit 1; }
echo "check-install: the installed package builds and runs the example both ways, and bench finds its cases"
