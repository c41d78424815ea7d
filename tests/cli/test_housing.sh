#!/usr/bin/env bash
# The housing's prescribed motion through the tool: a case whose acceleration history is a CSV file
# (ms and g in its header) under a subdirectory of the case file's directory, run from elsewhere:
#   - the path is resolved against the case file's directory, the run completes, and with the
#     energy account its JSON, text summary and HDF5 file give housing_work, which closes the
#     balance (the residual a small fraction of it);
#   - the same case without its housing has no housing_work anywhere (the outputs of a case without
#     housing motion keep their form);
#   - the CSV is an input: an output aimed at it is refused (exit 2) and it is left as it was.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/housing.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

mkdir -p "$work/case/records"
cp "$src/cases/jeffcott.cfg" "$work/case/"
printf 't [ms], ax [g], ay [g]\n0, 0, 0\n4, 0.5, 3\n8, 0, 0\n' >"$work/case/records/shock.csv"
cp "$work/case/records/shock.csv" "$work/shock.orig"
cat >"$work/case/housing.cfg" <<'EOF'
@include "jeffcott.cfg"
energy = true;
housing = { history = { file = "records/shock.csv"; start = 0.01; }; };
EOF
args=(--set end_time=0.05)

t "$work/run" run --json "${args[@]}" ../case/housing.cfg -o h
check "history from a CSV under the case's directory: exit 0 (got $rc: $(head -c 300 "$work/run/.err"))" test "$rc" = 0
hw=$(grep -oE '"housing_work":[^,}]*' "$work/run/.out" | sed 's/.*://')
res=$(grep -oE '"residual":[^,}]*' "$work/run/.out" | sed 's/.*://')
check "JSON: energy.housing_work given ($hw J) and the residual ($res J) below 1e-2 of it" \
    python3 -c "import sys; h, r = float('$hw'), float('$res'); sys.exit(0 if h > 1e-3 and abs(r) < 1e-2 * h else 1)"
t "$work/text" run "${args[@]}" ../case/housing.cfg -o h
check "text summary: the housing's work ($(grep 'energy housing work' "$work/text/.out"))" \
    grep -q '^energy housing work  *[0-9.e+-]* J' "$work/text/.out"
py=$(h5py_python)
if [ -n "$py" ]; then
    check "HDF5: summary_energy_housing_work is the JSON's" "$py" -c "
import h5py, sys
v = h5py.File('$work/run/h.h5', 'r').attrs['summary_energy_housing_work']
sys.exit(0 if abs(float(v) - float('$hw')) <= 1e-12 * abs(float(v)) else 1)"
else
    fail "h5py not found: the HDF5 check cannot run (install python3-h5py; scripts/setup.sh does)"
fi

t "$work/none" run --json --set end_time=0.05 --set energy=true ../case/jeffcott.cfg -o n
check "without housing motion: exit 0 (got $rc)" test "$rc" = 0
check "without housing motion: no housing_work in the JSON, the text or the file" \
    test -z "$(grep -l 'housing_work' "$work/none/.out" "$work/none/n.h5" 2>/dev/null)"

t "$work/clobber" run "${args[@]}" --set 'output.csv="../case/records/shock.csv"' ../case/housing.cfg
check "an output aimed at the CSV record: exit 2 (got $rc: $(cat "$work/clobber/.err"))" test "$rc" = 2
check "the refusal names the record an input file of the case, not an @include file ($(cat "$work/clobber/.err"))" \
    grep -q 'the same file as the input file of the case (an @include file or a record it reads)' "$work/clobber/.err"
check "the CSV record is left as it was" cmp -s "$work/case/records/shock.csv" "$work/shock.orig"

finish
