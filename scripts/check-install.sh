#!/usr/bin/env bash
# Installs the built project into a scratch prefix, moves the prefix (an install must not depend on
# where it was made), and then uses it as a user would, with no LD_LIBRARY_PATH:
#   - the installed tool runs: --version, info and a short run of an installed case, and bench
#     finds its cases; touchdown fmu packs the installed FMU binary;
#   - the pkg-config file names no absolute library path, and the CMake package no absolute path
#     at all: it finds the dependencies again where it is used (a missing one is named);
#   - examples/plugin-pd builds with its Makefile against the installed header alone, and the
#     installed tool runs its case with the plug-in;
#   - examples/ (the installed copy in share/doc/touchdown) builds with find_package(touchdown),
#     shared and static; examples/embed.c builds with pkg-config, shared (-Wl,-rpath, as the README
#     says) and static (pkg-config --static); each program runs and all print the same result;
#   - a program linked to the shared library with no run-time path fails to start, which is why the
#     README's "Use from C" gives one;
#   - the documentation is installed, and the README's links into docs/ and examples/ resolve in
#     the installed copy.
# Any failure stops it with exit 1.   scripts/check-install.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
unset LD_LIBRARY_PATH
fail() { echo "check-install: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$scratch/made" >/dev/null
mv "$scratch/made" "$scratch/prefix"
prefix=$scratch/prefix
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig"
cases=$prefix/share/touchdown/cases
doc=$prefix/share/doc/touchdown

# The cases are installed with the tool, and the installed tool finds them on its own: run from a
# directory without a cases/ folder, 'info' reads an installed case (with its @include of rig.cfg),
# 'run' runs a short window of it and 'bench' runs case A's short window from the installed cases.
echo "check-install: the installed tool"
"$prefix/bin/touchdown" --version
for f in "$here"/cases/*.cfg; do
    [ -f "$cases/$(basename "$f")" ] || fail "$(basename "$f") not installed in $cases"
done
mkdir "$scratch/elsewhere"
cd "$scratch/elsewhere"
"$prefix/bin/touchdown" info "$cases/paper-a.cfg" | head -n 1
"$prefix/bin/touchdown" run -q --json -o short --set end_time=0.15 "$cases/paper-a.cfg" >run.json ||
    fail "the installed touchdown did not run $cases/paper-a.cfg"
[ -s short.h5 ] && [ -s short.csv ] || fail "the installed touchdown run wrote no short.h5/short.csv"
grep -q '"status":"success"' run.json || fail "the installed touchdown run did not succeed: $(head -c 300 run.json)"
"$prefix/bin/touchdown" bench --quick --cases A --repeats 1 --json >bench.json
grep -q '"case":"A"' bench.json || fail "the installed touchdown bench did not run case A"
# touchdown fmu packs the installed FMU binary (LIBDIR/touchdown/touchdown-fmu.so, found from the
# tool's own directory) as the FMU's binaries/linux64/NAME.so
fmu_so=$(find "$prefix" -name touchdown-fmu.so -path '*/touchdown/*' | head -n 1)
[ -n "$fmu_so" ] || fail "touchdown-fmu.so is not installed under $prefix"
"$prefix/bin/touchdown" fmu -q --set end_time=0.15 -o PaperA.fmu "$cases/paper-a-digital.cfg" ||
    fail "the installed touchdown fmu did not pack $cases/paper-a-digital.cfg"
/usr/bin/python3 -c 'import sys, zipfile; sys.exit(zipfile.ZipFile(sys.argv[1]).read("binaries/linux64/PaperA.so")
                     != open(sys.argv[2], "rb").read())' PaperA.fmu "$fmu_so" ||
    fail "the installed touchdown fmu did not pack the installed $fmu_so"

echo "check-install: touchdown.pc: $(pkg-config --print-requires-private touchdown | tr '\n' ' ')"
static_libs=$(pkg-config --static --libs touchdown)
if grep -Eq '(^| )/[^ ]*\.(so|a)( |$)' <<<"$static_libs"; then
    fail "pkg-config --static --libs touchdown lists library paths: $static_libs"
fi

# The CMake package names its dependencies by imported targets that touchdownConfig.cmake finds
# again (cmake/TouchdownDeps.cmake); no path of the machine that built it (Debian's
# /usr/lib/x86_64-linux-gnu/hdf5/serial/libhdf5.so, say) may be in it, and its own files go by
# ${_IMPORT_PREFIX}. A dependency hidden from find_package(touchdown) shows that it looks them up.
echo "check-install: the CMake package names no absolute path and finds its dependencies again"
if abs=$(grep -nE '(^|[";( ])/[A-Za-z]' "$prefix"/lib/cmake/touchdown/*.cmake); then
    fail "the installed CMake package names absolute paths: $(cut -c1-300 <<<"$abs")"
fi
if cmake -S "$doc/examples" -B "$scratch/cmake-nogsl" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_DISABLE_FIND_PACKAGE_GSL=ON >"$scratch/nogsl.log" 2>&1; then
    fail "find_package(touchdown) was found with GSL hidden from it: it does not look it up"
fi
grep -q 'touchdown needs GSL' "$scratch/nogsl.log" ||
    fail "find_package(touchdown) with GSL hidden: $(tail -n 5 "$scratch/nogsl.log")"

# Each program prints its last line; all four must agree (one library, one example).
echo "check-install: examples/ with find_package(touchdown), shared and static"
cmake -S "$doc/examples" -B "$scratch/cmake" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$scratch/cmake" >/dev/null
"$scratch/cmake/embed" | tail -n 1 >"$scratch/cmake-shared.txt"
"$scratch/cmake/embed_static" | tail -n 1 >"$scratch/cmake-static.txt"

echo "check-install: examples/embed.c with pkg-config, shared (-Wl,-rpath) and static (--static)"
cc_flags=(-std=c99 -Wall -Wextra -pedantic -Werror)
# shellcheck disable=SC2046  # pkg-config's output is a list of flags
cc "${cc_flags[@]}" "$doc/examples/embed.c" $(pkg-config --cflags --libs touchdown) \
    -Wl,-rpath,"$(pkg-config --variable=libdir touchdown)" -o "$scratch/embed-pc"
# shellcheck disable=SC2046
cc "${cc_flags[@]}" "$doc/examples/embed.c" \
    $(pkg-config --static --cflags --libs touchdown | sed 's/-ltouchdown /-l:libtouchdown.a /') \
    -o "$scratch/embed-pc-static"
if readelf -d "$scratch/embed-pc-static" | grep -q 'libtouchdown\.so'; then
    fail "the program built with pkg-config --static needs libtouchdown.so"
fi
"$scratch/embed-pc" | tail -n 1 >"$scratch/pc-shared.txt"
"$scratch/embed-pc-static" | tail -n 1 >"$scratch/pc-static.txt"
for r in cmake-static pc-shared pc-static; do
    cmp -s "$scratch/cmake-shared.txt" "$scratch/$r.txt" ||
        fail "$r printed '$(cat "$scratch/$r.txt")', find_package's shared build '$(cat "$scratch/cmake-shared.txt")'"
done
echo "check-install: all four print: $(cat "$scratch/cmake-shared.txt")"

# shellcheck disable=SC2046
cc "${cc_flags[@]}" "$doc/examples/embed.c" $(pkg-config --cflags --libs touchdown) -o "$scratch/embed-norpath"
if "$scratch/embed-norpath" >/dev/null 2>"$scratch/norpath.err"; then
    fail "a program linked to the shared library in $prefix started with no run-time path"
fi
grep -q 'libtouchdown\.so.*cannot open' "$scratch/norpath.err" ||
    fail "without a run-time path: $(cat "$scratch/norpath.err")"
echo "check-install: without a run-time path, as the README says: $(head -n 1 "$scratch/norpath.err")"

# The plug-in example builds with its own Makefile against the installed header alone (a copy of
# the installed example, as a user takes it), and the installed tool runs its case with it.
echo "check-install: examples/plugin-pd with make against the installed header, run by the installed tool"
cp -r "$doc/examples/plugin-pd" "$scratch/plugin-pd"
make -s -C "$scratch/plugin-pd" PREFIX="$prefix" CFLAGS="-O2 -Werror" || fail "examples/plugin-pd did not build"
"$prefix/bin/touchdown" run -q --json -o "$scratch/plugin-pd/short" --set end_time=0.11 \
    "$scratch/plugin-pd/rig-pd.cfg" >"$scratch/plugin.json" 2>"$scratch/plugin.err" ||
    fail "the installed touchdown did not run rig-pd.cfg: $(head -c 300 "$scratch/plugin.err")"
grep -q '"status":"success"' "$scratch/plugin.json" ||
    fail "the installed touchdown run of rig-pd.cfg did not succeed: $(head -c 300 "$scratch/plugin.json")"

echo "check-install: the documentation in share/doc/touchdown"
for f in README.md "$here"/docs/*.md "$here"/docs/figures/*; do
    rel=${f#"$here/"}
    [ -f "$doc/$rel" ] || fail "$rel not installed in $doc"
done
for link in $(grep -oE '\]\((docs|examples)/[^)#]*' "$doc/README.md" | cut -c3-); do
    [ -e "$doc/$link" ] || fail "the installed README links to $link, which is not installed"
done
echo "check-install: the installed tool, package, example and documentation work from a moved prefix"
