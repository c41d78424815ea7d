#!/usr/bin/env bash
# touchdown bench --quick: every paper case runs through the benchmark, the JSON report is
# well formed, counts are positive, the constrained cases hold the drift bound, and the first
# contact of case A lies where the exact solution puts it (0.105443450996 s, test_first_contact).
set -euo pipefail
tool=$1
src=$2
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$tool" bench --quick --json --dir "$src/cases" >"$out" 2>/dev/null
python3 - "$out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
failed = 0
def check(ok, what):
    global failed
    print(("ok:   " if ok else "FAIL: ") + what)
    failed += not ok
cases = {r["case"]: r for r in d["runs"]}
check(sorted(cases) == ["A", "B", "C", "D", "D10"], "all five paper cases ran: %s" % sorted(cases))
for k, r in cases.items():
    check(r["steps"] > 0 and r["residual_evals"] >= r["steps"], "%s: steps %d, residuals %d" % (k, r["steps"], r["residual_evals"]))
    check(r["contact_onsets"] > 0, "%s: %d contact onsets in the quick window" % (k, r["contact_onsets"]))
for k in ("A", "B"):
    check(cases[k]["worst_drift"] < 1e-9, "%s: worst drift %.3g m < 1e-9 m" % (k, cases[k]["worst_drift"]))
check(abs(cases["A"]["first_contact_time"] - 0.105443450996) < 1e-5,
      "A: first contact %.12f s near the exact 0.105443450996 s" % cases["A"]["first_contact_time"])
check(bool(d["ratios"]), "penalty/constrained ratios reported")
sys.exit(1 if failed else 0)
PY
