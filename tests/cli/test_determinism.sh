#!/usr/bin/env bash
# Determinism: the same case run twice (in two directories) gives byte-identical results:
#   - the CSV (every data row and every comment line) and the event CSV,
#   - the HDF5 file: every dataset and attribute as dumped by h5dump with 17 significant
#     digits (doubles round-trip exactly; h5dump does not show object modification times),
#   - the JSON summary,
# all except the wall-clock quantities (wall_time, solver_wall_time, wall_time_per_revolution,
# realtime_factor). Runs cases/paper-a.cfg (constraint contact) and cases/paper-c.cfg (penalty
# contact) to end_time = 0.3 s (0.15 s under the sanitizers, below): both through many contacts,
# events and integrator restarts.
# The HDF5 checks need h5dump (hdf5-tools): without it the test fails.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/determinism.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

wall='wall_time|realtime_factor'
need h5dump hdf5-tools

# The HDF5 file as text, minus the attributes whose names match $wall (each attribute block runs
# from its ATTRIBUTE line to the closing brace at the same indentation).
h5text() {
    (cd "$(dirname "$1")" && h5dump -m '%.17g' "$(basename "$1")") |
        awk -v pat="$wall" '
            skip { if ($0 == indent "}") skip = 0; next }
            /^ *ATTRIBUTE "/ { name = $0; sub(/^ *ATTRIBUTE "/, "", name); sub(/".*/, "", name)
                               if (name ~ pat) { indent = $0; sub(/ATTRIBUTE.*/, "", indent); skip = 1; next } }
            { print }'
}
csvtext() { grep -vE "^# [a-z_]*($wall)[a-z_]* = " "$1"; }
jsontext() { sed -E "s/\"[a-z_]*($wall)[a-z_]*\":[^,}]*//g" "$1"; }

compare() { # WHAT FILE1 FILE2
    if cmp -s "$2" "$3"; then
        pass "$1 identical ($(wc -l <"$2") lines)"
    else
        fail "$1 differ: $(diff "$2" "$3" | head -n 6 | cut -c1-160 | tr '\n' '|')"
    fi
}

# Under the sanitizers (TD_TEST_SANITIZED=1) the runs end at 0.15 s: past the first contacts
# (0.105 s) with their events, restarts and the same files compared byte for byte; the longer runs,
# through more contacts, are the plain pass's (more than 3000 samples each, 1000 under the
# sanitizers; more than 100 events in both). Measured to 0.15 s, sanitized build: paper-a 1664
# samples and 163 events, paper-c 1764 and 263 (CSV data rows and event rows).
end=0.3
min_rows=3000
if sanitized; then
    end=0.15
    min_rows=1000
fi
for name in paper-a paper-c; do
    for k in 1 2; do
        d=$work/$name-$k
        mkdir -p "$d"
        (cd "$d" && "$tool" run --json --set end_time=$end "$src/cases/$name.cfg" >summary.json 2>stderr.txt)
        rc=$?
        if [ "$rc" != 0 ]; then
            fail "$name run $k: exit $rc ($(head -c 300 "$d/stderr.txt"))"
            continue 2
        fi
    done
    a=$work/$name-1
    b=$work/$name-2
    rows=$(grep -vc '^#' "$a/$name.csv")
    events=$(grep -vc '^#' "$a/$name.events.csv")
    if [ "$rows" -gt "$min_rows" ] && [ "$events" -gt 100 ]; then
        pass "$name: a meaningful run ($((rows - 1)) samples, $((events - 1)) events)"
    else
        fail "$name: too little to compare ($rows CSV lines, $events event lines)"
    fi
    csvtext "$a/$name.csv" >"$work/a.csv"
    csvtext "$b/$name.csv" >"$work/b.csv"
    compare "$name: CSV" "$work/a.csv" "$work/b.csv"
    # the wall-time lines are really there (else the filter would hide nothing and prove nothing)
    if [ "$(grep -cE "^# [a-z_]*($wall)[a-z_]* = " "$a/$name.csv")" -ge 2 ]; then
        pass "$name: CSV wall-clock lines left out of the comparison"
    else
        fail "$name: no wall-clock lines found in the CSV (format changed? update \$wall)"
    fi
    compare "$name: event CSV" "$a/$name.events.csv" "$b/$name.events.csv"
    jsontext "$a/summary.json" >"$work/a.json"
    jsontext "$b/summary.json" >"$work/b.json"
    compare "$name: JSON summary" "$work/a.json" "$work/b.json"
    h5text "$a/$name.h5" >"$work/a.h5.txt"
    h5text "$b/$name.h5" >"$work/b.h5.txt"
    if grep -q 'DATASET "time"' "$work/a.h5.txt" && grep -q 'DATASET "events"' "$work/a.h5.txt"; then
        compare "$name: HDF5 datasets and attributes" "$work/a.h5.txt" "$work/b.h5.txt"
    else
        fail "$name: h5dump shows no /time or /events dataset"
    fi
    if grep -qE "ATTRIBUTE \"[a-z_]*($wall)[a-z_]*\"" "$work/a.h5.txt"; then
        fail "$name: wall-clock attributes not filtered out"
    else
        pass "$name: HDF5 wall-clock attributes left out of the comparison"
    fi
done

finish
