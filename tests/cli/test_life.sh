#!/usr/bin/env bash
# The touchdown bearing's life through the tool (docs/theory.md, "Touchdown bearing life"): a run
# whose retainers' bearings have a dynamic rating says their damage, load cycles and drops to
# failure in the text summary, the JSON (drops = 1 / damage; null for a retainer without a rating,
# never 0) and its files (HDF5 and CSV attributes); a run without one has none of it, in no output;
# a sweep has the drops_to_failure column (the fewest over the retainers) only when its points are
# rated. Cheap: cases/drop.cfg to 0.08 s (the fall at 0.05 s, the first impacts), its bearings (a
# 6011 on each retainer) given or stripped of their dynamic rating by overrides.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
export LC_ALL=C
work=$(mktemp -d "${PWD}/life.XXXXXX")
trap 'rm -rf "$work"' EXIT
drop=$src/cases/drop.cfg
rated="retainers[0].bearing = { dynamic_rating = 30700.0; }"
unrated0="retainers[0].bearing = { static_rating = 21200.0; }"
unrated1="retainers[1].bearing = { static_rating = 21200.0; }"

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# JSON: print the three life arrays of retainer 0 and 1 and check drops = 1 / damage.
life_json() {
    /usr/bin/python3 - "$1" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
dmg, drops, cyc = d["retainer_damage"], d["retainer_drops_to_failure"], d["retainer_load_cycles"]
ok = dmg[0] > 0 and cyc[0] >= 1 and drops[0] == 1.0 / dmg[0] and dmg[1] is None and drops[1] is None \
    and cyc[1] is None
print("%s damage %r cycles %r drops %r" % ("ok" if ok else "bad", dmg, cyc, drops))
EOF
}

# ---- a rated retainer 0, an unrated retainer 1 ----------------------------------------------
t "$work/r" run --json --set end_time=0.08 --set "$rated" --set "$unrated1" -o r "$drop"
check "run with a rated retainer: exit 0 (got $rc)" test "$rc" = 0
got=$(life_json "$work/r/.out")
check "JSON: retainer 0's damage > 0, its drops 1 / damage, retainer 1's null ($got)" test "${got%% *}" = ok
t "$work/r" run --set end_time=0.08 --set "$rated" --set "$unrated1" -o r "$drop"
check "text: retainer 0's life line with its drops to failure" \
    grep -qE "^retainer 0  life +damage [0-9.e+-]+ over [0-9.]+ load cycles, over the run \(0 s to 0.08 s\): [0-9.e+]+ drops to failure \(ISO 281 L10\); the run ended before the rotor came to rest" "$work/r/.out"
# to 0.08 s the rotor bounces at its end: the damage, a sum over the rainflow cycles of those
# impacts, is flagged with the contact totals (docs/validation.md: 40 % from 48 to 96 elements)
check "text: the bouncing run's life flagged with the contact totals" \
    grep -qE "^not converged .*, the life's load cycles, damage and drops to failure \(it bounces" "$work/r/.out"
check "text: retainer 1 has no rating, and says which key gives one" \
    grep -qF "retainer 1  life            no rating (retainers[1].bearing.dynamic_rating)" "$work/r/.out"
check "CSV: the attributes retainer_damage, retainer_drops_to_failure, retainer_load_cycles (nan for retainer 1)" \
    test "$(grep -cE '^# retainer_(damage|drops_to_failure|load_cycles) = [0-9.e+-]+ nan$' "$work/r/r.csv")" = 3
if command -v h5dump >/dev/null; then
    check "HDF5: retainer_drops_to_failure, one value per retainer" \
        grep -qE '\(0\): [0-9.e+]+, nan' <(h5dump -a retainer_drops_to_failure "$work/r/r.h5")
else
    fail "h5dump is missing (scripts/setup.sh installs hdf5-tools)"
fi

# ---- a rated bearing the run never loads: unlimited, not "no drops" (0) -------------------------
t "$work/u" run --json --set end_time=0.01 --set "$rated" --set "$unrated1" -o u "$drop"
check "rated, no contact: JSON damage 0, drops to failure null (infinite)" /usr/bin/python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["contacts"] == 0 and d["retainer_damage"][0] == 0 and d["retainer_drops_to_failure"][0] is None, d' \
    "$work/u/.out"
t "$work/u" run --set end_time=0.01 --set "$rated" --set "$unrated1" -o u "$drop"
check "rated, no contact: the text says unlimited (no damage)" \
    grep -qE "^retainer 0  life +damage 0 over 0 load cycles, .*drops to failure unlimited \(no damage\)" "$work/u/.out"
check "rated, no contact: the CSV holds inf (no damage), nan for the unrated retainer" \
    grep -qE '^# retainer_drops_to_failure = inf nan$' "$work/u/u.csv"

# ---- no rating: none of it ------------------------------------------------------------------
t "$work/n" run --json --set end_time=0.08 --set "$unrated0" --set "$unrated1" -o n "$drop"
check "run without a rating: exit 0, no life in the JSON" test "$rc" = 0 -a -z "$(grep -o 'retainer_damage' "$work/n/.out")"
t "$work/n" run --set end_time=0.08 --set "$unrated0" --set "$unrated1" -o n "$drop"
check "... none in the text summary, nor in the CSV attributes" \
    test -z "$(grep -E ' life |retainer_damage|drops_to_failure|load_cycles' "$work/n/.out" "$work/n/n.csv")"
check "... and its contact totals flagged without the life" \
    grep -qE "^not converged .*in the contacts \(it bounces" "$work/n/.out"

# ---- sweeps: the column only for rated points -----------------------------------------------
t "$work/s" sweep -j 2 --set end_time=0.08 --set "$rated" --vary speed=150,190 -o s "$drop"
check "rated sweep: exit 0 (got $rc)" test "$rc" = 0
check "rated sweep: the drops_to_failure column, a number for each point" \
    test "$(/usr/bin/python3 -c '
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
print(sum(float(r["drops_to_failure [1]"]) > 0 for r in rows))' "$work/s/s.csv")" = 2
t "$work/u" sweep -j 2 --set end_time=0.08 --set "$unrated0" --set "$unrated1" --vary speed=150,190 -o u "$drop"
check "sweep without a rating: no drops_to_failure column" test "$rc" = 0 -a -z "$(grep -o drops_to_failure "$work/u/u.csv")"
finish
