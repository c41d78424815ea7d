#!/usr/bin/env bash
# The HDF5 files as other programs read them, checked with h5dump (Debian package hdf5-tools, an
# independent reader; without it, or h5diff, the test fails):
#   - dimension scales: /time, /component, /nodes/node, /retainers/retainer, /ambs/amb, /event are
#     scales (CLASS = "DIMENSION_SCALE") and every sample dataset carries a DIMENSION_LIST whose
#     first entry is /time; the modal file's Campbell tables have /campbell/speed;
#   - text: string attributes are variable-length UTF-8 (h5py reads them as str) and show as text;
#   - compression: --compress N and output.compression = N put SHUFFLE and DEFLATE N on the
#     datasets, and the data read back identical to the uncompressed file (h5diff); a level
#     outside 0..9 is bad input (exit 2) naming the key.
# With a python3 that has xarray and h5netcdf (never required), tests/cli/xarray_check.py also
# opens the files through xarray and checks the named dimensions.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/cli-hdf5.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# A short run of case A with a few contacts (events), HDF5 only.
run_a() { # PREFIX ARGS...
    local p=$1
    shift
    (cd "$work" && "$tool" run -q --csv '' --hdf5 "$p.h5" --set end_time=0.15 "$@" "$case_a" >"$p.out" 2>"$p.err")
}

# The exit code and the stderr of a run given bad compression settings.
run_a bad-cli --compress 12
rc=$?
check "--compress 12: exit 2, names the option ($(head -c 200 "$work/bad-cli.err"))" \
    test "$rc" = 2 -a -n "$(grep -- '--compress: expected a deflate level 0..9' "$work/bad-cli.err")"
run_a bad-key --set output.compression=10
rc=$?
check "output.compression = 10: exit 2, one line naming the key ($(head -c 200 "$work/bad-key.err"))" \
    test "$rc" = 2 -a -n "$(grep 'compression' "$work/bad-key.err")" -a "$(wc -l <"$work/bad-key.err")" = 1

need h5dump hdf5-tools
need h5diff hdf5-tools

run_a plain
check "plain run: exit 0" test $? = 0
run_a packed --compress 6
check "--compress 6: exit 0" test $? = 0
run_a keyed --set output.compression=3
check "output.compression = 3: exit 0" test $? = 0
h5dump -H -A "$work/plain.h5" >"$work/plain.txt" 2>&1
h5dump -p -H "$work/packed.h5" >"$work/packed.txt" 2>&1
h5dump -p -H "$work/keyed.h5" >"$work/keyed.txt" 2>&1

# ---- dimension scales ----------------------------------------------------------------------
# attribute block of one object: from its DATASET line to the next DATASET/GROUP line
block() { awk -v name="$2" '$0 ~ "(DATASET|GROUP) \"" name "\"" {on = 1; print; next} on && /(DATASET|GROUP) "/ {exit} on {print}' "$1"; }
# the scales in the DIMENSION_LIST of one dataset, one path a line, in axis order
axes() { block "$1" "$2" | grep -A8 'ATTRIBUTE "DIMENSION_LIST"' | grep -oE 'DATASET [0-9]+ "/[a-z_/]+"' | cut -d'"' -f2; }
for scale in time component node retainer amb event; do
    if block "$work/plain.txt" "$scale" | grep -A12 'ATTRIBUTE "CLASS"' | grep -q '"DIMENSION_SCALE"'; then
        pass "/$scale is a dimension scale"
    else
        fail "/$scale is not a dimension scale"
    fi
done
block "$work/plain.txt" time | grep -q 'ATTRIBUTE "REFERENCE_LIST"' && pass "/time has a REFERENCE_LIST" ||
    fail "/time has no REFERENCE_LIST"
for ds in displacement x y radial_position radial_velocity whirl_angle normal_force friction_force \
    sliding_velocity contact_state force; do
    dl=$(axes "$work/plain.txt" "$ds" | head -n 1)
    if [ "$dl" = /time ]; then pass "$ds: first axis is /time"; else fail "$ds: first axis is '$dl', not /time"; fi
done
dl=$(axes "$work/plain.txt" displacement | tr '\n' ' ')
check "displacement axes: /time /nodes/node /component ($dl)" test "$dl" = "/time /nodes/node /component "
dl=$(axes "$work/plain.txt" events)
check "events axis: /event ($dl)" test "$dl" = "/event"

# ---- text ----------------------------------------------------------------------------------
for a in status case_text library_version units; do
    txt=$(h5dump -a "/$a" "$work/plain.h5" 2>&1)
    if grep -q 'STRSIZE H5T_VARIABLE' <<<"$txt" && grep -q 'CSET H5T_CSET_UTF8' <<<"$txt" &&
        grep -qE '\(0\): "[^"]' <<<"$txt"; then
        pass "/$a: variable-length UTF-8 text"
    else
        fail "/$a: not variable-length UTF-8 text: $(head -c 300 <<<"$txt" | tr '\n' ' ')"
    fi
done
txt=$(h5dump -a /retainers/normal_force/units "$work/plain.h5" 2>&1)
check "a units attribute reads as text" grep -q '(0): "N"' <<<"$txt"

# ---- compression ---------------------------------------------------------------------------
for f in packed:6 keyed:3; do
    n=${f%%:*}
    lv=${f##*:}
    filt=$(block "$work/$n.txt" normal_force | grep -cE 'SHUFFLE|DEFLATE \{ LEVEL '"$lv"' \}')
    check "$n: /retainers/normal_force has SHUFFLE and DEFLATE $lv" test "$filt" = 2
done
check "plain: no filter" test -z "$(h5dump -p -H "$work/plain.h5" | grep -E 'DEFLATE|SHUFFLE')"
for ds in /time /nodes/displacement /retainers/normal_force /retainers/contact_state /ambs/force /events; do
    if h5diff "$work/plain.h5" "$work/packed.h5" "$ds" "$ds" >"$work/diff.txt" 2>&1; then
        pass "$ds: identical with and without compression"
    else
        fail "$ds differs with compression: $(head -c 200 "$work/diff.txt")"
    fi
done
n0=$(h5dump -H -d /time "$work/plain.h5" | sed -nE 's/.*SIMPLE \{ \( ([0-9]+) \).*/\1/p' | head -n 1)
check "the runs have data (${n0:-no} samples)" test "${n0:-0}" -gt 1000

# ---- modal file ----------------------------------------------------------------------------
(cd "$work" && "$tool" modal -q -o modal "$case_a" >/dev/null 2>"$work/modal.err")
if [ -s "$work/modal.h5" ]; then
    h5dump -H -A "$work/modal.h5" >"$work/modal.txt" 2>&1
    dl=$(axes "$work/modal.txt" omega_d | head -n 2 | tr '\n' ' ')
    check "modal: /campbell/omega_d axes /campbell/speed /campbell/branch ($dl)" \
        test "$dl" = "/campbell/speed /campbell/branch "
else
    fail "modal: no modal.h5 ($(head -c 200 "$work/modal.err"))"
fi

# ---- optional: xarray ----------------------------------------------------------------------
py=${TD_PYTHON:-python3}
if command -v "$py" >/dev/null && "$py" -c 'import xarray, h5netcdf' 2>/dev/null; then
    if "$py" "$src/tests/cli/xarray_check.py" "$work/packed.h5" >"$work/xr.txt" 2>&1; then
        pass "xarray reads the named dimensions ($(tail -n 1 "$work/xr.txt"))"
    else
        fail "xarray: $(tail -n 5 "$work/xr.txt" | tr '\n' ' ')"
    fi
else
    echo "skip: python3 with xarray and h5netcdf not found (optional): xarray check not run"
fi

finish
