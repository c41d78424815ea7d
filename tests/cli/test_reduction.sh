#!/usr/bin/env bash
# The reduced (Craig-Bampton) rotor through the tool, always against the full model:
#   - `touchdown info` and `touchdown modal` with reduction.cutoff print the comparison with the full
#     model; with every fixed-interface mode kept (a cut-off above them all) the largest errors are
#     rounding (< 1e-9); with a 2 kHz cut-off there is a row per mode below it, those below half
#     the cut-off within the Ritz bound (f/f_c)^2 of tests/test_reduce.c, the response within 1e-4;
#   - `touchdown run` of a reduced rotor writes every node, the interior nodes expanded through the
#     reduction: with every mode kept they follow the full model's run to the solver's tolerance
#     (1e-8 m, the clearance being 7.5e-4 m) until the unbalance step at 0.1 s;
#   - a bad cut-off through --set is refused with exit 2 and one line naming reduction.cutoff (the
#     bad case files are in tests/data/bad/, checked by test_bad_input.sh);
#   - bench/reduction.sh runs and prints a row per cut-off.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/reduction.XXXXXX")
trap 'rm -rf "$work"' EXIT
. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, finish
rub=$src/cases/rub-damped.cfg

# largest FIELD ("frequencies" or "unbalance response") of the report in FILE
largest() { sed -n "s/.*largest relative error: frequencies \([^,]*\), unbalance response \(.*\)$/\1 \2/p" "$1"; }
below() { python3 -c "import sys; sys.exit(0 if float('$1') < float('$2') else 1)"; }

t "$work/info" info --set reduction.cutoff=1e9 "$rub"
check "info with every mode kept: exit 0" [ "$rc" = 0 ]
check "info says the rotor is reduced" grep -q "^reduction    Craig-Bampton below 1e+09 Hz: 32 boundary DOFs + 20" "$work/info/.out"
read -r ef er <<<"$(largest "$work/info/.out")"
check "info with every mode kept: frequencies exact (${ef:-none})" below "${ef:-1}" 1e-9
check "info with every mode kept: unbalance response exact (${er:-none})" below "${er:-1}" 1e-9

t "$work/modal" modal --set reduction.cutoff=2000 -o "$work/modal/m" "$rub"
check "modal at 2 kHz: exit 0" [ "$rc" = 0 ]
rows=$(sed -n '/^reduction error against the full model/,/largest/p' "$work/modal/.out" | grep -cE '^  [0-9]+ ')
check "modal at 2 kHz: a row per mode below the cut-off ($rows)" [ "$rows" -ge 20 ]
# the Ritz bound of tests/test_reduce.c: |df|/f <= (f/f_N)^2 <= (f/cutoff)^2 below half the cut-off
bad_rows=$(sed -n '/^reduction error against the full model/,/largest/p' "$work/modal/.out" |
    awk '/^  [0-9]+ / { f = $2; e = $4; if (f < 1000 && e > (f / 2000) ^ 2) n++ } END { print n + 0 }')
check "modal at 2 kHz: frequencies below 1 kHz within (f/f_c)^2 ($bad_rows outside)" [ "$bad_rows" = 0 ]
read -r ef er <<<"$(largest "$work/modal/.out")"
check "modal at 2 kHz: every frequency below the cut-off within 10 % (${ef:-none})" below "${ef:-1}" 0.1
check "modal at 2 kHz: unbalance response within 1e-4 (${er:-none})" below "${er:-1}" 1e-4
check "modal at 2 kHz: files written" test -s "$work/modal/m.csv" -a -s "$work/modal/m.h5"

t "$work/run" run -q --hdf5 "" --csv full.csv --set end_time=0.12 "$rub"
check "full run: exit 0" [ "$rc" = 0 ]
t "$work/run" run -q --hdf5 "" --csv red.csv --set end_time=0.12 --set reduction.cutoff=1e9 "$rub"
check "reduced run: exit 0" [ "$rc" = 0 ]
diff_before_step=$(python3 - "$work/run/full.csv" "$work/run/red.csv" <<'PY'
import sys
def table(path):
    lines = [l for l in open(path) if not l.startswith("#") and l.strip()]
    head = lines[0].strip().split(",")
    return head, {float(r.split(",")[0]): [float(v) for v in r.strip().split(",")] for r in lines[1:]}
hf, full = table(sys.argv[1])
hr, red = table(sys.argv[2])
if hf != hr:
    print("columns differ"); sys.exit()
nodes = [i for i, h in enumerate(hf) if h.startswith(("x_n", "y_n"))]
worst = max(abs(red[t][i] - full[t][i]) for t in full if t < 0.1 and t in red for i in nodes)
print("%.3e %d" % (worst, len(nodes)))
PY
)
read -r worst ncols <<<"$diff_before_step"
check "reduced run writes all 13 nodes (${ncols:-0} columns)" [ "${ncols:-0}" = 26 ]
check "reduced run follows the full one before the step (${worst:-none} m)" below "${worst:-1}" 1e-8

t "$work/bad" info --set reduction.cutoff=-3 "$rub"
check "negative cut-off: exit 2" [ "$rc" = 2 ]
check "negative cut-off: one line naming reduction.cutoff" \
    bash -c '[ "$(wc -l <"$1")" = 1 ] && grep -q "reduction.cutoff: must be > 0" "$1" && ! [ -s "$2" ]' _ \
    "$work/bad/.err" "$work/bad/.out"
t "$work/bad" run --set reduction.cutoff=\"fast\" "$rub"
check "string cut-off: exit 2" [ "$rc" = 2 ]
check "string cut-off: names reduction.cutoff" grep -q "reduction.cutoff: expected a number" "$work/bad/.err"
t "$work/bad" info --set reduction.modes=3 "$rub"
check "unknown reduction key: exit 2" [ "$rc" = 2 ]

TOUCHDOWN=$tool bash "$src/bench/reduction.sh" -s "end_time=0.05" "$rub" 2000 >"$work/bench.out" 2>&1
check "bench/reduction.sh: exit 0" [ $? = 0 ]
check "bench/reduction.sh: a row for the cut-off" grep -q "^cut-off 2000 *36 " "$work/bench.out"
finish
