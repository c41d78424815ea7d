#!/usr/bin/env bash
# Fuzz a reader of untrusted bytes with libFuzzer for SECONDS seconds (default 60).
#   [FUZZ_TARGET=case|journal|vary|plot] scripts/fuzz.sh [SECONDS] [BUILD_DIR]   (default BUILD_DIR: build-fuzz)
# The targets (fuzz/README.md): case, the case-file reader (td_case_load, the default); journal,
# the sweep journal's reader and appender (tools/sweep/sweep_journal.c); vary, the --vary / --with
# parser (td_sweep_grid_vary, _with); plot, result files as touchdown plot loads them
# (tools/plot/plot_file.c, plot_sweep_load.c through lib/io/result.c).
# Installs clang and libclang-rt-14-dev when missing (Debian 12, as root), builds fuzz/ with
# -fsanitize=fuzzer,address,undefined, makes the target's seed corpus (case: from cases/ and
# tests/data/, a case that includes another file becoming "MAIN\n@@@\nINCLUDED" with @include
# "part.cfg", the input format of fuzz/fuzz_case.c, run with the dictionary fuzz/case.dict;
# journal: journals the target's own writer makes; vary: the specs of the tests and docs; plot:
# small result files of the tool, a run, a modal analysis and a sweep table), and runs the fuzzer
# on BUILD_DIR/corpus (case) or BUILD_DIR/corpus-TARGET (kept between runs). A crash, a leak,
# undefined behaviour, a broken contract or a timeout (> 10 s on one input) saves the input under
# fuzz/findings/ (named TARGET-crash-... but for the case target) and exits non-zero; replay one
# with:  BUILD_DIR/fuzz_TARGET fuzz/findings/FILE   (see fuzz/README.md).
# Leaks inside libconfig 1.5 (upstream issue #142) are suppressed by scripts/lsan.supp.
# FUZZ_JOBS=N runs N fuzzing processes in parallel (default 1).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
build=${2:-$here/build-fuzz}
jobs=${FUZZ_JOBS:-1}
target=${FUZZ_TARGET:-case}
case $target in
case | journal | vary | plot) ;;
*)
    echo "fuzz: FUZZ_TARGET must be case, journal, vary or plot (got '$target')" >&2
    exit 2
    ;;
esac

missing=()
command -v clang >/dev/null || missing+=(clang)
dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "install ok installed" || missing+=(libclang-rt-14-dev)
if ((${#missing[@]})); then
    echo "fuzz: installing ${missing[*]}" >&2
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get update -qq
    $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
"$here/scripts/setup.sh" "$here/build" >/dev/null # the project's own dependencies

CC=clang cmake -S "$here/fuzz" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" --target "fuzz_$target" --parallel "$(nproc)" >/dev/null

# ---- seed corpus ---------------------------------------------------------------------------
seeds=$build/seeds-$target
corpus=$build/corpus-$target
prefix=$here/fuzz/findings/$target-
if [ "$target" = case ]; then
    seeds=$build/seeds corpus=$build/corpus prefix=$here/fuzz/findings/
fi
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus" "$here/fuzz/findings"

seeds_case() {
    local n=0 f inc out set
    for f in "$here"/cases/*.cfg "$here"/tests/data/case/*.cfg "$here"/tests/data/bad/*.cfg "$here"/tests/data/robust/*.cfg; do
        n=$((n + 1))
        inc=$(sed -nE 's/^[[:space:]]*@include[[:space:]]+"([^"/]+)".*/\1/p' "$f" | head -n 1)
        out=$seeds/$(printf '%03d' $n)-$(basename "$f")
        if [ -n "$inc" ] && [ -f "$(dirname "$f")/$inc" ]; then
            { sed -E "s|^([[:space:]]*@include[[:space:]]+)\"$inc\"|\1\"part.cfg\"|" "$f"
              printf '\n@@@\n'
              cat "$(dirname "$f")/$inc"; } >"$out"
        else
            cp "$f" "$out"
        fi
    done
    # a few with overrides: paper-a's seed ("MAIN @@@ RIG") plus a third part, one --set per line
    for set in $'speed=190\ncontact.model=penalty\nretainers[0].friction=0.2' $'retainers[1].clearance=1e-3\nsolver.rtol=1e-8' \
        $'schedule=({time=0.1; amb_off=0;})\noutput.nodes=[2, 10]' $'speed=fast\nunbalances[9].phase=1'; do
        n=$((n + 1))
        { cat "$seeds/"*-paper-a.cfg | head -c 100000; printf '\n@@@\n%s\n' "$set"; } >"$seeds/$(printf '%03d' $n)-overrides.cfg"
    done
}

# journals written by the target's own writer (whole, torn, zero-filled, of 1 and 64 points)
seeds_journal() {
    TD_FUZZ_MAKE_SEEDS=$seeds "$build/fuzz_journal" -runs=0 >/dev/null 2>&1
}

# one spec a line, "+" for --with: the forms of the tests and docs, and their edges
seeds_vary() {
    local n=0 spec
    for spec in 'speed=60:150:4' $'speed=60:150:4\nschedule[0].magnitude=0.05,0.1,0.2' 'speed=1:1000:7:log' \
        $'speed=60,90\n+unbalances[0].magnitude=0.1,0.2' 'contact.model="penalty",constraint' \
        'output.nodes=[1, 2],[3]' 'speed=0.1:0.7:7:linear' 'end_time=0.001,500' 'start="a,b",orbit' \
        'speed=1e300:1.7e308:3' 'speed=1e-300:1e300:5:log' 'speed=-5:5:1' 'retainers[1].clearance=1e-3'; do
        n=$((n + 1))
        printf '%s\n' "$spec" >"$seeds/$(printf '%03d' $n)-spec"
    done
}

# small result files of the tool (built by scripts/setup.sh): a run, a modal analysis, a sweep
seeds_plot() {
    local td=$here/build/touchdown a=$here/cases/paper-a.cfg
    (cd "$seeds" && "$td" run -q --set end_time=0.002 --set output.sample_rate=2000 --csv '' --hdf5 run.h5 "$a" &&
        "$td" run -q --set end_time=0.001 --csv '' --hdf5 rub.h5 "$here/cases/rub-damped.cfg" &&
        "$td" modal -q --csv '' --hdf5 modal.h5 "$a" &&
        "$td" sweep -q -j 1 --set end_time=0.001 --vary speed=60,90 -o sweep "$a") >/dev/null
    rm -f "$seeds"/*.csv
}

"seeds_$target"
echo "fuzz: $target: $(ls "$seeds" | wc -l) seed inputs, corpus $(ls "$corpus" | wc -l) inputs, $seconds s, $jobs job(s)"

# ---- run ----------------------------------------------------------------------------------
# Fork mode (even with one job) with -ignore_crashes: a finding is saved and fuzzing goes on, so
# one run collects every finding it meets instead of stopping at the first.
# plot: the slow unwinder sees through HDF5's frames, so that lsan.supp can name them; and
# malloc returns NULL for the absurd sizes HDF5 asks for on a corrupt header, as it does outside
# ASan (HDF5 then fails the open: fuzz/README.md, P3), instead of ASan stopping there
hdf5=""
[ "$target" = plot ] && hdf5=:fast_unwind_on_malloc=0:allocator_may_return_null=1
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1$hdf5}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/scripts/lsan.supp:print_suppressions=0}
findings() { ls "$here/fuzz/findings" | grep -cE "^${prefix##*/}(crash|leak|timeout|oom)-" || true; }
extra=(-max_len=65536)
[ "$target" = case ] && extra+=(-dict="$here/fuzz/case.dict")
[ "$target" = vary ] && extra=(-max_len=4096)
[ "$target" = plot ] && extra=(-max_len=1048576)
log=$build/fuzz-$target.log
before=$(findings)
set +e
(cd "$build" && "./fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 "${extra[@]}" \
    -artifact_prefix="$prefix" -print_final_stats=1 \
    -fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 "$corpus" "$seeds") >"$log" 2>&1
rc=$?
set -e
after=$(findings)
execs=$(grep -oE '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
{ grep -aE 'contract broken|ERROR: (AddressSanitizer|LeakSanitizer)|runtime error|Test unit written' "$log" || true; } |
    sed -E 's/td-fuzz\.[A-Za-z0-9]+/td-fuzz.X/g' | cut -c1-300 | sort | uniq -c | sort -rn | head -n 40
echo "fuzz: $target: libFuzzer exit $rc, ${execs:-0} executions in $seconds s, corpus now $(ls "$corpus" | wc -l) inputs," \
    "$((after - before)) new findings under fuzz/findings/ (log: $log)"
[ "$rc" = 0 ] && [ "$after" = "$before" ]
