#!/usr/bin/env bash
# The documentation's numbers against the tool (scripts/make-docs.sh writes them):
#   (a) every generated region of README.md and docs/*.md, rebuilt from the recorded results
#       (docs/results/*.json), equals the text in the file: a number edited by hand, or results
#       recorded without rewriting the docs, fails;
#   (b) the cheap shipped runs, rerun with their recorded arguments, print the recorded numbers
#       (relative tolerance 1e-6, counts and texts exact; wall-clock quantities not compared;
#       scripts/docs_record.py says why the tolerance is that): a change of the tool that moves a
#       documented number fails until scripts/make-docs.sh is rerun. Rerun here: rub-damped (full
#       and reduced rotor: race bodies, mounts, compliant contact) and the penalty case C (the
#       closed-form flight, penalty contact), about 2.5 s of CPU in the plain build and 7 s under
#       ASan (which gives the same numbers). The longer runs (cases A and B to 2 s, D, D10, the
#       drop, the run-up: 2-6 s each, 5-7 times that under ASan) are checked by (a) only, through
#       their records;
#   (c) the case keys the tool knows (touchdown info --keys, the reader's tables) equal
#       docs/results/keys.json, the record the key tables of docs/case-format.md are made from: a
#       key, type, range, unit, default or doc changed in the reader without rerunning
#       scripts/make-docs.sh fails (and (a) fails a key table edited by hand);
#   (d) the shock study's `case` row: cases/shock.cfg as shipped (about 1 s) rerun, its outcome, margins
#       and first contact time against docs/results/shock.json (scripts/shock_study.py --check): (a)
#       checks docs/shock-study.md against the record, this the record against the tool;
#   (e) the sweep study: one of its recorded runs, cases/study-a.cfg at 150 rad/s and 0.05 kg m (under a
#       second), rerun and compared with docs/results/sweep_study.json (scripts/sweep_study.py --check).
# Needs python3 (json, difflib only). Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, finish
py=/usr/bin/python3
[ -x "$py" ] || py=python3

out=$("$py" "$src/scripts/docs_render.py" --check 2>&1)
rc=$?
if [ "$rc" = 0 ]; then pass "generated regions match docs/results/ ($out)"; else fail "generated regions: $out"; fi

# relay: each line of a checker's output (on stdin) as a pass, a fail, or a note
relay() {
    local line
    while IFS= read -r line; do
        case $line in
        ok:*) pass "${line#ok:   }" ;;
        FAIL:*) fail "${line#FAIL: }" ;;
        *) echo "$line" ;;
        esac
    done
}

# the runs of docs/results/runs.json cheap enough to rerun here
cheap=(rub-damped rub-damped/reduced paper-c)
relay < <("$py" "$src/scripts/docs_record.py" --check "$tool" runs "${cheap[@]}" 2>&1)
# (c) the case keys
relay < <("$py" "$src/scripts/docs_record.py" --check-keys "$tool" 2>&1)
# (d) the shock study's case row
relay < <("$py" "$src/scripts/shock_study.py" --check "$tool" 2>&1)
# (e) the sweep study's run
relay < <("$py" "$src/scripts/sweep_study.py" --check "$tool" 2>&1)
check "every cheap run, the case keys, the shock case and the sweep study's run checked (${#cheap[@]} + 3)" test "$checks" -ge $((${#cheap[@]} + 4))
finish
