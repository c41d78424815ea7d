#!/usr/bin/env bash
# A rotor that nothing holds (the rig of case A with its AMBs removed: free-free) through the tool.
# Its rigid-body roots at 0 are defective, and the eigen-solver's rounding moves them by about
# sqrt(eps) times the spectral radius: they are marginal, not unstable (TD_MODAL_MARGINAL_REAL_PART).
#   - touchdown run with start = "orbit" takes the steady unbalance orbit (exit 0, "start orbit",
#     the contact-free system "stable"), and touchdown modal calls it marginally stable;
#   - under gravity it has no static position: start = "orbit" is refused with one line (exit 2,
#     no file), start = "auto" starts at rest and says why.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
case_a=$src/cases/paper-a.cfg
work=$(mktemp -d "${PWD}/free-rotor.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

free=(--set 'ambs=()' --set end_time=0.01)

t "$work/orbit" run -q "${free[@]}" --set 'start="orbit"' --json "$case_a" -o r
check "free-free, start = orbit: exit 0 (got $rc: $(head -c 300 "$work/orbit/.err"))" test "$rc" = 0
check "free-free, start = orbit: the orbit is used (start $(jf "$work/orbit/.out" start))" \
    test "$(jf "$work/orbit/.out" start)" = '"orbit"'
check "free-free, start = orbit: the contact-free system is stable (stability $(jf "$work/orbit/.out" stability))" \
    test "$(jf "$work/orbit/.out" stability)" = '"stable"'

t "$work/modal" modal "${free[@]}" "$case_a" -o m
check "free-free, modal: exit 0 (got $rc)" test "$rc" = 0
check "free-free, modal: marginally stable ($(head -n 1 "$work/modal/.out"))" \
    grep -q '^modes at 90 rad/s (marginally stable' "$work/modal/.out"

t "$work/fall" run "${free[@]}" --set 'start="orbit"' --set 'gravity={enabled=true;}' "$case_a" -o r
check "free-free under gravity, start = orbit: exit 2 (got $rc)" test "$rc" = 2
check "free-free under gravity, start = orbit: one line naming the start ($(cat "$work/fall/.err"))" \
    test "$(wc -l <"$work/fall/.err")" = 1 -a -n "$(grep 'start = "orbit": .*not held' "$work/fall/.err")"
check "free-free under gravity, start = orbit: no file ($(ls -A "$work/fall" | grep -v '^\.' | tr '\n' ' '))" \
    test -z "$(ls "$work/fall")"

t "$work/auto" run -q "${free[@]}" --set 'start="auto"' --set 'gravity={enabled=true;}' --json "$case_a" -o r
check "free-free under gravity, start = auto: exit 0 (got $rc: $(head -c 300 "$work/auto/.err"))" test "$rc" = 0
check "free-free under gravity, start = auto: at rest, saying why ($(jf "$work/auto/.out" start_reason))" \
    test "$(jf "$work/auto/.out" start)" = '"rest"' -a -n "$(jf "$work/auto/.out" start_reason | grep 'not held')"

finish
