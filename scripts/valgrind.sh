#!/usr/bin/env bash
# valgrind memcheck on the tool and the test executables.
#   scripts/valgrind.sh [BUILD_DIR]          (default BUILD_DIR: build; built by scripts/setup.sh)
# Runs, each under  valgrind --leak-check=full --error-exitcode=1  (any memory error or definite
# or possible leak fails it):
#   - touchdown run on every paper case (cases/paper-*.cfg) shortened to end_time =
#     ${TD_VALGRIND_END_TIME:-0.15} s: past the unbalance step at 0.1 s and through the first
#     impacts, so the contact events, restarts and both writers are exercised;
#   - touchdown info and touchdown modal on paper-a, and touchdown run on a bad case file;
#   - every cmocka test executable of BUILD_DIR/tests (in that directory, as ctest runs them).
# Installs valgrind when missing (Debian 12, as root). Prints one line per run and a total; exits
# non-zero if any run had an error. Logs: BUILD_DIR/valgrind/*.log. Not part of CI (too slow:
# see fuzz/README.md for the measured time).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
end_time=${TD_VALGRIND_END_TIME:-0.15}

if ! command -v valgrind >/dev/null; then
    echo "valgrind: installing valgrind" >&2
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    export DEBIAN_FRONTEND=noninteractive
    $sudo apt-get update -qq
    $sudo apt-get install -y -qq --no-install-recommends valgrind >/dev/null
fi
"$here/scripts/setup.sh" "$build" >/dev/null

logs=$build/valgrind
rm -rf "$logs"
mkdir -p "$logs/out"
tool=$build/touchdown
fails=0
runs=0
start=$(date +%s)

# vg NAME EXPECTED_EXIT DIR COMMAND...: run COMMAND in DIR under memcheck.
vg() {
    local name=$1 want=$2 dir=$3 rc t0 errors
    shift 3
    t0=$(date +%s)
    set +e
    (cd "$dir" && CMOCKA_MESSAGE_OUTPUT=stdout valgrind --leak-check=full --error-exitcode=99 \
        --log-file="$logs/$name.log" "$@" >"$logs/$name.out" 2>&1)
    rc=$?
    set -e
    runs=$((runs + 1))
    errors=$(sed -nE 's/.*ERROR SUMMARY: ([0-9]+) errors.*/\1/p' "$logs/$name.log" | tail -n 1)
    if [ "$rc" = 99 ] || [ "${errors:-1}" != 0 ]; then
        fails=$((fails + 1))
        echo "FAIL: $name: ${errors:-?} valgrind errors ($((($(date +%s) - t0))) s), see $logs/$name.log"
        grep -E '^==[0-9]+== (Invalid|Conditional|Use of|Syscall|Mismatched|Source and|[0-9,]+ bytes in)' \
            "$logs/$name.log" | head -n 5
    elif [ "$rc" != "$want" ]; then
        fails=$((fails + 1))
        echo "FAIL: $name: exit $rc, expected $want ($((($(date +%s) - t0))) s): $(tail -n 2 "$logs/$name.out")"
    else
        echo "ok:   $name: no errors, no leaks, exit $rc ($((($(date +%s) - t0))) s)"
    fi
}

for c in "$here"/cases/paper-*.cfg; do
    name=$(basename "$c" .cfg)
    vg "run-$name" 0 "$logs/out" "$tool" run -q --set end_time="$end_time" -o "$name" "$c"
done
vg info-paper-a 0 "$logs/out" "$tool" info "$here/cases/paper-a.cfg"
vg modal-paper-a 0 "$logs/out" "$tool" modal -q -o modal-a "$here/cases/paper-a.cfg"
vg run-bad-case 2 "$logs/out" "$tool" run "$here/tests/data/bad/syntax-error.cfg"
vg run-bad-set 2 "$logs/out" "$tool" run --set speed=fast "$here/cases/paper-a.cfg"
for t in "$build"/tests/test_*; do
    [ -x "$t" ] && [ -f "$t" ] || continue
    vg "$(basename "$t")" 0 "$build/tests" "$t"
done

echo "valgrind: $((runs - fails)) passed, $fails failed ($(($(date +%s) - start)) s; end_time $end_time s for the runs)"
[ "$fails" = 0 ]
