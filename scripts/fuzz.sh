#!/usr/bin/env bash
# Fuzz the case-file reader (td_case_load) with libFuzzer for SECONDS seconds (default 60).
#   scripts/fuzz.sh [SECONDS] [BUILD_DIR]          (default BUILD_DIR: build-fuzz)
# Installs clang and libclang-rt-14-dev when missing (Debian 12, as root), builds fuzz/ with
# -fsanitize=fuzzer,address,undefined, makes the seed corpus from cases/ and tests/data/ (a case
# that includes another file becomes "MAIN\n@@@\nINCLUDED" with @include "part.cfg", the input
# format of fuzz/fuzz_case.c), and runs the fuzzer on BUILD_DIR/corpus (kept between runs) with
# the dictionary fuzz/case.dict. A crash, a leak, undefined behaviour, a broken contract or a
# timeout (> 10 s on one input) saves the input under fuzz/findings/ and exits non-zero; replay
# one with:  BUILD_DIR/fuzz_case fuzz/findings/crash-...   (see fuzz/README.md).
# Leaks inside libconfig 1.5 (upstream issue #142) are suppressed by scripts/lsan.supp.
# FUZZ_JOBS=N runs N fuzzing processes in parallel (default 1).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
seconds=${1:-60}
build=${2:-$here/build-fuzz}
jobs=${FUZZ_JOBS:-1}

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
cmake --build "$build" --target fuzz_case --parallel "$(nproc)" >/dev/null

# ---- seed corpus ---------------------------------------------------------------------------
seeds=$build/seeds
rm -rf "$seeds"
mkdir -p "$seeds" "$build/corpus" "$here/fuzz/findings"
n=0
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
echo "fuzz: $(ls "$seeds" | wc -l) seed inputs, corpus $(ls "$build/corpus" | wc -l) inputs, $seconds s, $jobs job(s)"

# ---- run ----------------------------------------------------------------------------------
# Fork mode (even with one job) with -ignore_crashes: a finding is saved and fuzzing goes on, so
# one run collects every finding it meets instead of stopping at the first.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$here/scripts/lsan.supp:print_suppressions=0}
log=$build/fuzz.log
before=$(ls "$here/fuzz/findings" | grep -cE '^(crash|leak|timeout|oom)-' || true)
set +e
(cd "$build" && ./fuzz_case -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -dict="$here/fuzz/case.dict" -artifact_prefix="$here/fuzz/findings/" -print_final_stats=1 \
    -fork="$jobs" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 "$build/corpus" "$seeds") >"$log" 2>&1
rc=$?
set -e
after=$(ls "$here/fuzz/findings" | grep -cE '^(crash|leak|timeout|oom)-' || true)
execs=$(grep -oE '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
{ grep -aE 'contract broken|ERROR: (AddressSanitizer|LeakSanitizer)|runtime error|Test unit written' "$log" || true; } |
    sed -E 's/td-fuzz\.[A-Za-z0-9]+/td-fuzz.X/g' | cut -c1-300 | sort | uniq -c | sort -rn | head -n 40
echo "fuzz: libFuzzer exit $rc, ${execs:-0} executions in $seconds s, corpus now $(ls "$build/corpus" | wc -l) inputs," \
    "$((after - before)) new findings under fuzz/findings/ (log: $log)"
[ "$rc" = 0 ] && [ "$after" = "$before" ]
