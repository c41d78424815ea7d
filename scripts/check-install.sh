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
echo "check-install: the installed package builds and runs the example both ways"
