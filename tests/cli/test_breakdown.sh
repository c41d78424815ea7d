#!/usr/bin/env bash
# bench/breakdown.sh (docs/performance.md, "Cost per step"):
#   - a sample's stack goes to the first category whose functions it holds, the phases around
#     IDA's step first: a residual evaluated inside an event's restart is the restart's, KLU's
#     triangular solve inside the linear solver's solve is the solve's, a root function inside
#     IDASolve is the event location's, and a stack with none of them is "other";
#   - a run of rub-damped without the profile (--no-profile: perf is not needed here) reports the
#     step and restart counts the tool's own JSON summary gives for the same case, and the CPU per
#     step and real-time factor from its CPU time.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
. "$(dirname "${BASH_SOURCE[0]}")/common.sh"
py=/usr/bin/python3
[ -x "$py" ] || py=python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

out=$("$py" - "$src" <<'PY'
import sys
sys.path.insert(0, sys.argv[1] + "/bench")
import breakdown as b
cases = [
    (["structural", "td_sim_residual", "res_cb", "IDAReInit", "td_sim_restart", "restart_integrator",
      "handle_stop", "td_sim_advance", "td_run"], "events"),
    (["klu_lsolve", "klu_solve", "ls_solve", "SUNLinSolSolve", "idaLsSolve", "SUNNonlinSolSolve_Newton", "IDASolve",
      "td_sim_advance"], "solve"),
    (["td_sim_roots", "root_cb", "IDASolve", "td_sim_advance"], "location"),
    (["structural", "td_sim_residual", "res_cb", "SUNNonlinSolSolve_Newton", "IDASolve", "td_sim_advance"], "residual"),
    (["klu_refactor", "ls_setup", "idaLsSetup", "IDASolve"], "factor"),
    (["td_sim_jacobian", "jac_cb", "idaLsSetup", "IDASolve"], "jacobian"),
    (["axpby", "N_VLinearSum", "IDASolve", "td_sim_advance"], "ida"),
    (["td_thermal_network_step", "td_sim_thermal_point", "td_sim_totals_point", "accept_point", "td_sim_advance"],
     "outputs"),
    (["hypot", "td_sim_flight_advance", "td_sim_advance"], "flight"),
    (["do_lookup_x", "_dl_relocate_object", "_start"], "other"),
]
bad = [(s[0], want, b.classify(s)) for s, want in cases if b.classify(s) != want]
print("bad: %r" % bad if bad else "ok %d" % len(cases))
PY
)
check "the stacks go to their categories ($out)" test "${out%% *}" = ok

"$tool" run -q --json --hdf5 '' --csv '' "$src/cases/rub-damped.cfg" >"$work/run.json" 2>"$work/run.err"
check "touchdown run of rub-damped: exit 0" test $? = 0
(cd "$src" && bash bench/breakdown.sh --json -n 1 --no-profile --cases rub-damped "$(dirname "$tool")") \
    >"$work/b.json" 2>"$work/b.err"
check "bench/breakdown.sh --no-profile: exit 0" test $? = 0
out=$("$py" - "$work/run.json" "$work/b.json" <<'PY'
import json, sys
run, b = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
r = b["cases"]["rub-damped"]["after"]
st = run["stats"]
errors = []
for k in ("steps", "restarts", "error_test_fails", "nonlinear_fails"):
    if r[k] != st[k]:
        errors.append("%s %r, the run's %r" % (k, r[k], st[k]))
cpu = r["cpu_median"]
if not (cpu > 0 and abs(r["us_per_step"] - 1e6 * cpu / st["steps"]) <= 1e-9 * r["us_per_step"]):
    errors.append("us_per_step %r for %r s over %d steps" % (r["us_per_step"], cpu, st["steps"]))
if abs(r["realtime_factor_cpu"] * cpu - (run["t_reached"] - run["t_start"])) > 1e-9:
    errors.append("realtime_factor_cpu %r" % r["realtime_factor_cpu"])
if r["profile"] is not None or "us_per_step_by_category" in r:
    errors.append("a profile without perf")
print("; ".join(errors) if errors else "ok")
PY
)
check "the counts are the run's, the CPU per step and real-time factor its CPU time's ($out)" test "$out" = ok
finish
