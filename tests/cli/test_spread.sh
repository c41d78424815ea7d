#!/usr/bin/env bash
# touchdown run --spread N (docs/validation.md, "Does this run's answer settle?"), on case A to
# 0.12 s, through its first impacts (about 0.1 s a run):
#   1. --json --spread 3: one JSON object, the run's summary with a member "spread" of 3 runs, the
#      atol factors 1, 1.01, 0.99, and member 0's value of every answer equal to the run's own
#      summary value; the summary itself equal to the one without --spread (wall-clock fields
#      aside), which has no "spread" member; member 1's values equal a run of the case with
#      --set solver.atol at 1.01 times the run's (the case reader's path, not the ensemble's);
#   2. the text: the summary, then a spread line, one line per answer and the rule;
#   3. a bad N (even, below 3, above 21, not a whole number): exit 2, one line on stderr naming
#      --spread, nothing on stdout;
#   4. a run that fails (solver.atol = 1e-300: IDA fails at the first impact): exit 1, no further
#      runs, "spread": null;
#   5. run --help documents --spread.
# Needs python3 (json only). Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, finish, t
case_a=$src/cases/paper-a.cfg
work=$(mktemp -d "${PWD}/spread.XXXXXX")
trap 'rm -rf "$work"' EXIT
short=(--hdf5 '' --csv '' --set end_time=0.12 --set solver.atol=1e-12)

# 1. the JSON
t "$work/s" run -q --json --spread 3 "${short[@]}" "$case_a"
check "--spread 3 --json: exit 0 (rc $rc)" test "$rc" = 0
cp "$work/s/.out" "$work/spread.json"
t "$work/p" run -q --json "${short[@]}" "$case_a"
check "without --spread: exit 0 (rc $rc)" test "$rc" = 0
cp "$work/p/.out" "$work/plain.json"
t "$work/m" run -q --json --hdf5 '' --csv '' --set end_time=0.12 \
    --set "solver.atol=$(python3 -c 'print(repr(1e-12 * 1.01))')" "$case_a"
cp "$work/m/.out" "$work/member1.json"
check "the JSON's spread: member 0 is the run, member 1 the case at 1.01 atol" \
    python3 - "$work/spread.json" "$work/plain.json" "$work/member1.json" <<'PY'
import json, sys
text = open(sys.argv[1]).read()
d, plain, m1 = json.loads(text), json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
assert text.count("\n") == 1, "one JSON object on one line"
sp = d["spread"]
assert sp["members"] == 3 and sp["completed"] == 3 and sp["failed"] == 0, sp
assert sp["atol_factors"] == [1, 1.01, 0.99], sp["atol_factors"]
assert sp["status"] == ["success"] * 3, sp["status"]
assert sp["ending"] == d["ending"] and sp["same_ending"] <= 3
names = ["peak_housing_force", "total_impulse", "friction_work", "final_speed", "contacts", "contact_time",
         "first_contact_time", "peak_normal_force", "peak_amb_force"]
assert list(sp["answers"]) == names, list(sp["answers"])
for name in names:
    a = sp["answers"][name]
    assert a["values"][0] == d[name] == a["run"], (name, a["values"][0], d[name])
    assert a["values"][1] == m1[name], (name, a["values"][1], m1[name])
    v = [x for x in a["values"] if x is not None]
    assert a["count"] == len(v) == 3 and a["least"] == min(v) and a["greatest"] == max(v), (name, a)
    assert a["median"] == sorted(v)[1], (name, a)
    assert a["spread"] == (0 if max(v) == min(v) else (max(v) - min(v)) / abs(sorted(v)[1])), (name, a)
    assert a["settles"] == (a["spread"] <= 0.02), (name, a)
assert "spread" not in plain, "no spread member without --spread"
wall = {"wall_time", "solver_wall_time", "wall_time_per_revolution", "realtime_factor"}
strip = lambda s: {k: v for k, v in s.items() if k not in wall and k != "stats" and k != "spread"}
assert strip(d) == strip(plain), "the run's own summary is the same with --spread"
PY

# 2. the text
t "$work/x" run --spread 3 "${short[@]}" "$case_a"
check "--spread 3 text: exit 0 (rc $rc)" test "$rc" = 0
check "the text: the summary, then the spread over 3 runs" grep -q '^spread  *3 runs, solver.atol x 0.99 .. 1.01' "$work/x/.out"
check "the text: one line per answer and the rule" test "$(sed -n '/^spread /,$p' "$work/x/.out" | grep -cE \
    '^  (peak housing force|total impulse|friction work|final speed|contacts|time in contact|first contact|peak normal force|peak AMB force|rule) ')" = 10
check "the text: a settle verdict on each answer" test "$(grep -cE ': (settles|does not settle)$' "$work/x/.out")" = 9
check "the text: the summary comes first" test "$(grep -n '^status ' "$work/x/.out" | cut -d: -f1)" = 1

# 3. bad N
for n in 4 2 1 0 23 -3 abc '' 3x 2.5 ' 5x'; do
    t "$work/bad" run --spread "$n" "${short[@]}" "$case_a"
    if [ "$rc" = 2 ] && [ "$(wc -l <"$work/bad/.err")" = 1 ] && grep -q -- '--spread' "$work/bad/.err" && [ ! -s "$work/bad/.out" ]; then
        pass "--spread '$n': exit 2, one line ($(cat "$work/bad/.err"))"
    else
        fail "--spread '$n': rc $rc, stderr: $(cat "$work/bad/.err")"
    fi
done

# 4. a failed run: no spread measured
t "$work/f" run -q --json --spread 3 --hdf5 '' --csv '' --set end_time=0.2 --set solver.atol=1e-300 "$case_a"
check "a failed run with --spread: exit 1 (rc $rc)" test "$rc" = 1
check "a failed run with --spread: \"spread\": null" python3 -c \
    'import json, sys; d = json.load(open(sys.argv[1])); sys.exit(not ("spread" in d and d["spread"] is None and d["status"] != "success"))' \
    "$work/f/.out"

# 5. the help
t "$work/h" run --help
check "run --help documents --spread" grep -q -- '--spread N' "$work/h/.out"
finish
