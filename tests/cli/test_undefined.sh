#!/usr/bin/env bash
# A failure is never a number (docs/output-format.md, "Undefined values"): a sweep point that
# failed has NaN for every answer in the CSV ("nan") and the HDF5 table, beside its status, and
# counts as failed (exit 1, --json); a failed run's JSON has null answers, never 0; a run without
# contact has no first-contact time and no revolutions after it (null in JSON, NaN in its files)
# and no whirl frequency;
# touchdown plot leaves the failed point out of the lines, marks it and says so on stderr.
# Cheap: paper case A for 0.03 s, where the start orbit at 190 rad/s lies outside the clearance.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
export LC_ALL=C
work=$(mktemp -d "${PWD}/undefined.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
# Column number of NAME (header text before " [") in a CSV table, and field NAME of row P (text
# in quotes, which may hold commas, blanked first).
col() { head -n 1 "$1" | tr ',' '\n' | sed 's/ \[.*//' | grep -nxF -- "$2" | cut -d: -f1; }
field() { grep "^$2," "$1" | sed -E 's/"[^"]*"/x/g' | cut -d, -f"$(col "$1" "$3")"; }

# ---- a sweep with a failed point: speeds 60 and 90 run (no contact in 0.03 s), 190 fails -------
t "$work/s" sweep -j 2 --set end_time=0.03 --set start=orbit --vary speed=60,90,190 -o s "$case_a"
check "sweep with a failed point: exit 1 (got $rc)" test "$rc" = 1
csv=$work/s/s.csv
bad=""
for q in peak_housing_force total_impulse friction_work contact_time contacts first_contact_time \
    ending_whirl_frequency returned_to_free_orbit section_count final_speed peak_amb_load; do
    v=$(field "$csv" 2 "$q")
    [ "$v" = nan ] || bad="$bad $q=$v"
done
check "CSV: the failed point's answers are all nan, never 0${bad:+:$bad}" test -z "$bad"
check "CSV: beside them its status, 'invalid argument'" test "$(field "$csv" 2 status)" = "invalid argument"
check "CSV: a point without contact has no first-contact time (nan), its counts are 0" \
    test "$(field "$csv" 0 first_contact_time)" = nan -a "$(field "$csv" 0 contacts)" = 0 \
    -a "$(field "$csv" 0 status)" = success -a "$(field "$csv" 0 peak_housing_force)" = 0
t "$work/s" sweep -j 2 --json --set end_time=0.03 --set start=orbit --vary speed=60,90,190 -o s "$case_a"
check "sweep --json: the failure counted (done 2, failed 1, exit 1)" \
    test "$rc" = 1 -a "$(jf "$work/s/.out" done)" = 2 -a "$(jf "$work/s/.out" failed)" = 1

py=$(h5py_python)
if [ -n "$py" ]; then
    got=$("$py" - "$work/s/s.h5" 2>&1 <<'EOF'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
status = [s.decode() if isinstance(s, bytes) else s for s in f["status"][:]]
nan = {k: np.isnan(f[k][:]).tolist() for k in ("peak_housing_force", "total_impulse", "final_speed",
                                                  "contacts", "first_contact_time")}
ok = status == ["success", "success", "invalid argument"] and all(v[2] for v in nan.values())
ok = ok and not any(nan[k][0] for k in ("peak_housing_force", "total_impulse", "final_speed", "contacts"))
ok = ok and nan["first_contact_time"][0]  # no contact: no first-contact time
print(status[2], "NaN:", " ".join(k for k, v in nan.items() if v[2]), "ok" if ok else "WRONG")
EOF
    )
    check "HDF5 table: NaN answers beside the failed point's status, none where the points ran ($got)" \
        test "${got##* }" = ok
else
    echo "skip: no python3 with h5py: the HDF5 table is not read"
fi

# ---- the plot leaves the failed point out and says so --------------------------------------------
t "$work/s" plot --no-run -d p s.h5
dat=$work/s/p/sweep-peak_housing_force.dat
check "plot: exit 0, one stderr line '1 of 3 points failed or not run (invalid argument 1): left out' ($(cat "$work/s/.err"))" \
    test "$rc" = 0 -a -n "$(grep -F 's.h5: 1 of 3 points failed or not run (invalid argument 1): left out' "$work/s/.err")"
check "plot: the line holds the two points that ran, the failed one only among the marks" \
    test "$(awk '!/^#/ && NF == 3 { print $3 }' "$dat" | tr '\n' ' ')" = "0 1 " -a \
    "$(sed -n '/^# failed or not run/,$p' "$dat" | awk '!/^#/ && NF == 2 { print $1, $2 }')" = "190 2" -a \
    -n "$(grep -x 'nfailed = 1 .*' "$work/s/p/sweep-peak_housing_force.gp")"
check "plot: the regime map shows the failed point as 'failed' (code 0)" \
    test "$(awk '!/^#/ && $8 == 2 { print $7 }' "$work/s/p/regime-map.dat")" = 0

# ---- a failed run: null answers in its JSON, never 0 ---------------------------------------------
t "$work/f" run --json -q --csv '' --hdf5 '' --set end_time=0.03 --set start=orbit --set speed=190 "$case_a"
o=$work/f/.out
bad=""
for k in peak_housing_force total_impulse friction_work final_speed contact_time peak_normal_force peak_amb_force \
    peak_amb_load ending_whirl_frequency; do
    [ "$(jf "$o" "$k")" = null ] || bad="$bad $k=$(jf "$o" "$k")"
done
check "failed run (exit 2): its JSON answers are null, never 0${bad:+:$bad}" \
    test "$rc" = 2 -a -z "$bad" -a "$(jf "$o" status)" = '"invalid argument"' -a "$(jf "$o" complete)" = false
check "failed run before any contact: JSON first_contact_time and revolutions_after_contact null" \
    test "$(jf "$o" first_contact_time)" = null -a "$(jf "$o" revolutions_after_contact)" = null

# ---- a run without contact: no first-contact time, no whirl frequency, in JSON and its files ------
t "$work/n" run --json -o n --set end_time=0.03 --set speed=60 "$case_a"
o=$work/n/.out
check "run without contact: JSON first_contact_time, last_contact_time and ending_whirl_frequency null" \
    test "$rc" = 0 -a "$(jf "$o" contacts)" = 0 -a "$(jf "$o" first_contact_time)" = null -a \
    "$(jf "$o" last_contact_time)" = null -a "$(jf "$o" ending_whirl_frequency)" = null
check "run without contact: JSON revolutions_after_contact null, never 0 ($(jf "$o" revolutions_after_contact))" \
    test "$(jf "$o" revolutions_after_contact)" = null
check "run without contact: its CSV says nan, never -1 or 0, for the times, the flags and the revolutions after contact" \
    test "$(grep -cE '^# (summary_first_contact_time|summary_last_contact_time|first_contact_time|summary_ending_whirl_frequency|summary_returned_to_free_orbit|summary_revolutions_after_contact) = nan$' "$work/n/n.csv")" = 6 -a \
    -z "$(grep -E '^# [a-z_]+ = -[12]$' "$work/n/n.csv")"
if [ -n "$py" ]; then
    check "run without contact: its HDF5 attributes are NaN, never -1 or 0" "$py" - "$work/n/n.h5" <<'EOF'
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r").attrs
keys = ("summary_first_contact_time", "summary_last_contact_time", "first_contact_time",
        "summary_ending_whirl_frequency", "summary_returned_to_free_orbit", "summary_free_at_end",
        "summary_revolutions_after_contact")
sys.exit(0 if all(np.isnan(a[k]) for k in keys) else 1)
EOF
fi

# ---- a run that covers no time: no fraction of it in contact (0/0 is not 0) ----------------------
t "$work/z" run --json -q --csv '' --hdf5 '' --set end_time=1e-300 --set speed=60 "$case_a"
o=$work/z/.out
check "run over no time (end_time 1e-300): JSON contact_fraction null, never 0 ($(jf "$o" contact_fraction))" \
    test "$rc" = 0 -a "$(jf "$o" t_reached)" = 0 -a "$(jf "$o" contact_fraction)" = null

finish
