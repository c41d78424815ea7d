#!/usr/bin/env bash
# touchdown report, end to end: the report of a real drop (cases/drop.cfg to 0.15 s) checked against
# the run file's own attributes read independently (h5py); a file without some quantities (an older
# file: attributes removed) says "not in this file" and null, never 0; the case's text read back for
# its description and limits; an incomplete run said so first with no number given as an answer; bad
# input (missing file, not HDF5, a modal file) and refusals (an output that is the run file, that is
# a directory, a missing directory, a prefix naming no file) exit 2 and write nothing; a gnuplot
# that fails exits 1 and leaves nothing either.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/report.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, h5py_python, finish

py=$(h5py_python)
if [ -z "$py" ]; then
    fail "no python3 with h5py (scripts/setup.sh installs python3-h5py): the report cannot be checked"
    finish
fi

# nothing_but DIR FILE...: DIR holds exactly the files named (no report files, no .partial left)
nothing_but() {
    local d=$1 want=""
    shift
    [ $# -gt 0 ] && want=$(printf '%s\n' "$@" | sort | tr '\n' ' ')
    test "$(cd "$d" && ls -A | grep -v '^\.out$' | grep -v '^\.err$' | sort | tr '\n' ' ')" = "$want"
}

t "$work" --help
t "$work/help" report --help
check "report --help: exit 0 and the usage" test "$rc" = 0 -a -n "$(grep 'usage: touchdown report' "$work/help/.out")"
check "touchdown --help lists report" grep -q '^  report RUN.h5' "$work/.out"

# ---- a real run -----------------------------------------------------------------------------------
# the limits and one bearing's ratings as --set overrides (retainer 1's bearing without ratings): the
# report reads them back from the case text the file holds, where the overrides are recorded as
# comment lines
t "$work/run" run -q -o "$work/run/drop" --set end_time=0.15 \
    --set "retainers[0].bearing={static_rating=5000.0;dynamic_rating=27000.0;}" --set "retainers[1].bearing={width=0.018;}" \
    --set "limits={temperature_rise=40.0;drops=100.0;zones=[0.25,0.4,0.55];}" "$src/cases/drop.cfg"
check "drop to 0.15 s: exit 0" test "$rc" = 0
t "$work/rep" report -o "$work/rep/r" "$work/run/drop.h5"
check "report: exit 0" test "$rc" = 0
check "report: PREFIX.txt, .json, .png and nothing else" nothing_but "$work/rep" r.txt r.json r.png
check "report: stdout is the text file" cmp -s "$work/rep/.out" "$work/rep/r.txt"
check "report: the figure is a PNG" test "$(head -c 4 "$work/rep/r.png" | tail -c 3)" = PNG
check "report: no error output" test ! -s "$work/rep/.err"
check "the report's quantities are the file's attributes, by name, retainer and sensor" "$py" - "$work/run/drop.h5" \
    "$work/rep/r.json" "$work/rep/r.txt" <<'PY'
import json, math, sys
import h5py
f = h5py.File(sys.argv[1], "r")
d = json.load(open(sys.argv[2]))
text = open(sys.argv[3]).read()
assert d["complete"] is True and d["incomplete_reason"] is None
assert d["description"] == "Rig drop at 190 rad/s: PID AMBs fail, ball-bearing retainers, free coast-down"
assert d["limits"]["from_case"] is True, d["limits"]
assert d["retainers"] == len(f.attrs["retainer_clearance"]) == 2
assert d["ending"] == (lambda v: v.decode() if isinstance(v, bytes) else v)(f.attrs["summary_ending"])
seen = flagged = 0
for q in d["quantities"]:
    name, k = q["name"], q["retainer"] if "retainer" in q else q["sensor"]
    if name not in f.attrs:
        assert q["state"] == "not in this file" and q["value"] is None and q["verdict"] is None, q
        continue
    v = f.attrs[name]
    v = float(v if k is None else v[k])
    if math.isnan(v):
        assert q["state"] == "not computed" and q["value"] is None, q
    else:
        assert q["state"] == "value" and q["value"] == v, (q, v)   # %.17g: the same double
        seen += 1
    # the flag that judges it: the contact totals' for what docs/output-format.md says it covers, the
    # rigid peak's for the contact load and what follows from it (the summary's "rigid constraint" line)
    totals = ("summary_total_impulse", "summary_contact_time", "summary_contacts", "summary_ending_whirl_frequency",
              "retainer_impulse", "retainer_contact_time", "retainer_load_cycles", "retainer_damage",
              "retainer_drops_to_failure")
    peaks = ("summary_peak_normal_force", "retainer_peak_normal_force", "retainer_load_ratio",
             "retainer_peak_contact_stress", "retainer_peak_pv", "retainer_peak_friction_power")
    flag = ("summary_contact_totals_converge" if name in totals else
            "summary_peak_normal_force_converges" if name in peaks else None)
    if q["state"] == "value":
        assert q["converges"] == (bool(f.attrs[flag]) if flag and flag in f.attrs else None), (q, flag)
        if q["converges"] is False:
            flagged += 1
assert seen >= 9 + 2 * 5, seen     # the run's nine and each retainer's five of 0.14.0 at least
# the limits of the case, and each judged quantity against its own
lim = d["limits"]
assert lim["temperature_rise"] == 40.0 and lim["drops"] == 100.0 and lim["zones"] == [0.25, 0.4, 0.55], lim
assert lim["static_rating"] == [5000.0, None] and lim["dynamic_rating"] == [27000.0, None], lim
rule = {"retainer_load_ratio": (1.0, lambda v, l: v <= l), "retainer_peak_temperature_rise": (40.0, lambda v, l: v <= l),
        "retainer_drops_to_failure": (100.0, lambda v, l: v >= l), "sensor_zone": (1.0, lambda v, l: v <= l),
        "retainer_peak_contact_stress": (4.2e9, lambda v, l: v <= l)}   # ISO 76: 4200 MPa, ball bearings
# totals over the run that only grow: within only for a run that ended at rest (1 % of the start speed)
grow = ("retainer_peak_temperature_rise", "retainer_drops_to_failure")
rest = abs(f.attrs["summary_final_speed"]) < 0.01 * abs(f.attrs["speed"])
assert not rest, "the drop to 0.15 s ends spinning"
judged = 0
for q in d["quantities"]:
    assert q["over_the_run"] == (q["name"] in ("retainer_drag_work", "retainer_heat", "retainer_peak_temperature_rise",
                                               "retainer_peak_thermal_growth", "retainer_load_cycles",
                                               "retainer_damage", "retainer_drops_to_failure")), q
    if q["name"] not in rule:
        assert q["limit"] is None and q["verdict"] in (None, "no limit"), q
        continue
    want, within = rule[q["name"]]
    assert q["limit"] == want, q
    if q["state"] == "value":
        verdict = "within" if within(q["value"], want) else "exceeds"
        if verdict == "within" and q["name"] in grow and not rest:
            verdict = "not judged: the run ended before the rotor came to rest"
        assert q["verdict"] == verdict, q
        judged += 1
    else:
        assert q["verdict"] is None, q
assert "limits        from the case: temperature rise 40 K, drops 100, ISO 14839-2 zone boundaries 0.25, 0.4, 0.55 of C_min, zone B at most" in text
assert d["limits"]["zone"] == "B", d["limits"]   # the default: ISO 14839-2's zone B
assert "peak race temperature rise, over the run" in text and "damage (Miner), over the run" in text
assert "retainer 0 bearing: static rating C0 5000 N, dynamic rating C 27000 N" in text
assert "retainer 1 bearing: static rating C0 none given, dynamic rating C none given" in text
# the text: the first line names the file; a quantity's value as %.6g beside its label
assert text.startswith("drop report of "), text[:80]
assert "  %-52s %-26s -  " % ("peak housing force", "%.6g N" % f.attrs["summary_peak_housing_force"]) in text
if f.attrs["summary_settled"] == 0:
    assert "time to settle" + " " * 39 + "not settled within the run" in text, text
# a C0 below the landing's peak force: the load ratio exceeds 1 wherever the file has it
for q in d["quantities"]:
    if q["name"] == "retainer_load_ratio" and q["retainer"] == 0 and q["state"] == "value":
        assert q["value"] > 1.0 and q["verdict"] == "exceeds", q
        assert "peak normal force / static rating C0%s%.6g" % (" " * 17, q["value"]) in text
print("ok", seen, "values,", judged, "judged against a limit,", flagged, "flagged as not converging")
PY

# ---- a rigid constraint: every peak of the contact load flagged, as the summary flags them --------
t "$work/rigid" run -q -o "$work/rigid/a" --set end_time=0.3 "$src/cases/paper-a.cfg"
check "paper-a to 0.3 s: exit 0" test "$rc" = 0
t "$work/rigid" report --json -o "$work/rigid/r" "$work/rigid/a.h5"
check "rigid constraint: the retainers' load, power, PV and stress peaks are flagged; an unsettled run says so" \
    "$py" - "$work/rigid/a.h5" "$work/rigid/.out" "$work/rigid/r.txt" <<'PY'
import json, sys
import h5py
f = h5py.File(sys.argv[1], "r")
d = json.load(open(sys.argv[2]))
text = open(sys.argv[3]).read()
assert f.attrs["summary_peak_normal_force_converges"] == 0 and f.attrs["summary_settled"] == 0
peaks = [q for q in d["quantities"] if q["name"] in ("retainer_peak_normal_force", "retainer_peak_friction_power")]
assert len(peaks) == 4 and all(q["converges"] is False for q in peaks), peaks
assert "  %-52s %-26s %-26s -  [does not converge with the mesh]" % ("peak contact normal force", "%.6g N" %
       f.attrs["retainer_peak_normal_force"][0], "-") in text, text
assert "  %-52s %-26s" % ("time to settle", "not settled within the run") in text, text
# no dynamic rating in the case: the run writes no life, and the report says why (not "not in this file")
assert "retainer_damage" not in f.attrs
life = [q for q in d["quantities"] if q["name"] in ("retainer_damage", "retainer_drops_to_failure", "retainer_load_cycles")]
assert len(life) == 6 and all(q["state"] == "not computed (no dynamic rating C)" and q["value"] is None for q in life), life
print("ok")
PY

# ---- an older file: quantities absent are "not in this file", never 0 --------------------------
cp "$work/run/drop.h5" "$work/run/old.h5"
"$py" - "$work/run/old.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    del f.attrs["summary_peak_housing_force"], f.attrs["retainer_friction_work"]
    if "retainer_load_ratio" in f.attrs:  # a quantity of this version's, absent from an older file
        del f.attrs["retainer_load_ratio"]
PY
t "$work/old" report --json -o "$work/old/r" "$work/run/old.h5"
check "older file: exit 0" test "$rc" = 0
check "older file: the absent quantities are null and 'not in this file'" "$py" - "$work/old/.out" "$work/old/r.txt" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
gone = [q for q in d["quantities"] if q["name"] in ("summary_peak_housing_force", "retainer_friction_work",
                                                     "retainer_load_ratio")]
assert len(gone) == 5, gone
assert all(q["value"] is None and q["state"] == "not in this file" for q in gone), gone
text = open(sys.argv[2]).read()
assert "  peak housing force%snot in this file" % (" " * 35) in text
assert "  friction work%snot in this file" % (" " * 40) in text
print("ok")
PY

# ---- the case text unreadable: no limits, said why; the report still written -------------------
cp "$work/run/drop.h5" "$work/run/nocase.h5"
"$py" - "$work/run/nocase.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    f.attrs["case_text"] = "shaft = { this is not a case"
PY
t "$work/nocase" report --json -o "$work/nocase/r" "$work/run/nocase.h5"
check "unreadable case text: exit 0, no limits, the reason given" test "$rc" = 0 -a \
    "$(jf "$work/nocase/.out" from_case)" = false -a -n "$(grep -o '"why_none":"its case text could not be read' "$work/nocase/.out")"

# ---- a run without retainers (the Jeffcott rotor): a report of the run alone, no retainer part ----
t "$work/jr" run -q -o "$work/jr/j" --set end_time=0.02 "$src/cases/jeffcott.cfg"
t "$work/jrep" report --json -o "$work/jrep/r" "$work/jr/j.h5"
check "no retainer: exit 0, the three files" test "$rc" = 0 -a -s "$work/jrep/r.png" -a -s "$work/jrep/r.txt"
check "no retainer: no retainer's quantity listed" test "$(jf "$work/jrep/.out" retainers)" = 0 -a \
    -z "$(grep -o '"retainer":[0-9]' "$work/jrep/.out")"

# ---- an incomplete run: said first, no number given as an answer -------------------------------
t "$work/bad" run -q -o "$work/bad/bad" --set end_time=0.1 --set solver.atol=1e-300 "$src/cases/drop.cfg"
check "a solver failure: the run exits 1" test "$rc" = 1
t "$work/badrep" report --json -o "$work/badrep/r" "$work/bad/bad.h5"
check "incomplete run: the report exits 0" test "$rc" = 0
check "incomplete run: the first line says so" grep -q '^THE RUN DID NOT COMPLETE' <(head -n 1 "$work/badrep/r.txt")
check "incomplete run: complete false, every quantity null, none judged" "$py" - "$work/badrep/.out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["complete"] is False and "IDA" in d["incomplete_reason"] and d["ending"] is None, d
assert all(q["value"] is None and q["verdict"] is None for q in d["quantities"])
assert any(q["state"].startswith("not an answer") for q in d["quantities"])
print("ok")
PY

# ---- bad input: exit 2, one line naming the file, nothing written ------------------------------
t "$work/in1" report -o "$work/in1/r" "$work/nosuch.h5"
check "missing file: exit 2, one line naming it" test "$rc" = 2 -a "$(wc -l <"$work/in1/.err")" = 1 -a \
    -n "$(grep -F "$work/nosuch.h5" "$work/in1/.err")"
check "missing file: nothing written" nothing_but "$work/in1"
echo "not hdf5" >"$work/text.h5"
t "$work/in2" report -o "$work/in2/r" "$work/text.h5"
check "not HDF5: exit 2, one line" test "$rc" = 2 -a "$(wc -l <"$work/in2/.err")" = 1
check "not HDF5: nothing written" nothing_but "$work/in2"
t "$work/modal" modal -q -o "$work/modal/m" --set "modal.speed_steps=2" "$src/cases/jeffcott.cfg"
t "$work/in3" report -o "$work/in3/r" "$work/modal/m.h5"
check "a modal file: exit 2, 'a modal file, not a run file'" test "$rc" = 2 -a \
    -n "$(grep 'a modal file, not a run file' "$work/in3/.err")"
check "a modal file: nothing written" nothing_but "$work/in3"
t "$work/in4" report
check "no run file: exit 2" test "$rc" = 2
t "$work/in4" report --bogus "$work/run/drop.h5"
check "unknown option: exit 2" test "$rc" = 2

# ---- refusals: the run file never overwritten, no output that is not a file --------------------
mkdir -p "$work/ref"
cp "$work/run/drop.h5" "$work/ref/in.png"
sum=$(cksum <"$work/ref/in.png")
t "$work/ref" report -o "$work/ref/in" "$work/ref/in.png"
check "an output that is the run file: exit 2, the run file unchanged" test "$rc" = 2 -a "$(cksum <"$work/ref/in.png")" = "$sum"
check "an output that is the run file: nothing else written" nothing_but "$work/ref" in.png
mkdir -p "$work/ref/d.json"
t "$work/ref" report -o "$work/ref/d" "$work/run/drop.h5"
check "an output that is a directory: exit 2" test "$rc" = 2
check "an output that is a directory: nothing written" nothing_but "$work/ref" in.png d.json
t "$work/ref" report -o "$work/ref/missing/r" "$work/run/drop.h5"
check "an output directory that does not exist: exit 2" test "$rc" = 2
for p in "" "$work/ref/" "."; do
    t "$work/ref" report -o "$p" "$work/run/drop.h5"
    check "--output '$p' names no file: exit 2" test "$rc" = 2
done
check "refusals: nothing written" nothing_but "$work/ref" in.png d.json

# ---- gnuplot fails: exit 1, nothing left -------------------------------------------------------
mkdir -p "$work/gp"
(cd "$work/gp" && TOUCHDOWN_GNUPLOT=/bin/false "$tool" report -o "$work/gp/r" "$work/run/drop.h5" >.out 2>.err)
rc=$?
check "gnuplot fails: exit 1" test "$rc" = 1
check "gnuplot fails: no report file, no temporary left" nothing_but "$work/gp"

finish
