#!/usr/bin/env bash
# Do two builds of the tool give the same outputs, bit for bit, wall-clock fields aside? The check of
# a change that must not change behaviour (a refactoring, a move between files): every shipped case
# (cases/*.cfg; one followed to rest, its first second without its leaps) through run (HDF5, CSV, events, --json summary), modal and info; the three case-file
# sweeps with --point-files and --point-csv and a --vary sweep, each cut to 0.3 s; and
# plot --no-run (gnuplot scripts and data) of two runs, a modal file and three sweep tables.
#   scripts/same-outputs.sh OLD_TOOL NEW_TOOL [WORK_DIR]      (default WORK_DIR: a new temporary one)
# Both tools read one copy of cases/ at one path (the files store the case's path), each writes its
# own tree, and scripts/same_outputs.py compares the trees: HDF5 object by object and attribute by
# attribute (references by the name they point to), CSV cell by cell, JSON key by key, every other
# file byte for byte; the fields that hold wall-clock times are left out. Exit 0 and "identical",
# or exit 1 and one line per difference. Takes a few minutes of CPU per tool.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
old=$(realpath "${1:?usage: same-outputs.sh OLD_TOOL NEW_TOOL [WORK_DIR]}")
new=$(realpath "${2:?usage: same-outputs.sh OLD_TOOL NEW_TOOL [WORK_DIR]}")
work=${3:-$(mktemp -d)}
mkdir -p "$work"
rm -rf "$work/cases"
cp -r "$here/cases" "$work/cases"

# st NAME STDOUT COMMAND...: run COMMAND with its stdout to STDOUT and its stderr to NAME.err, and
# its exit status to NAME.rc (a failing command is an output too)
st() {
    local name=$1 out=$2
    shift 2
    if "$@" >"$out" 2>"$name.err"; then echo 0 >"$name.rc"; else echo $? >"$name.rc"; fi
}

# outputs TOOL DIR: every output of the set by TOOL into DIR
outputs() {
    local tool=$1 dir=$2 c n f
    rm -rf "$dir"
    mkdir -p "$dir"
    cd "$dir"
    for c in "$work"/cases/*.cfg; do
        n=$(basename "$c" .cfg)
        # a case followed to rest runs for minutes: its first second is what is compared, without
        # end_at_rest (a second never reaches rest, and the cut run would carry the warning that it did not)
        cut=()
        if grep -q '^end_at_rest *= *true' "$c"; then cut=(--set end_time=1 --set end_at_rest=false); fi
        # and without its leaps, which start after that second (a start at or after end_time is refused)
        if [ ${#cut[@]} -gt 0 ] && grep -q '^leap *=' "$c"; then cut+=(--set leap.burst=0); fi
        st "$n" "$n.json" "$tool" run -q --json "${cut[@]}" -o "$n" "$c"
        st "$n-modal" /dev/null "$tool" modal -q -o "$n-modal" "$c"
        st "$n-info" "$n.info" "$tool" info "$c"
    done
    for n in rub-damped-sweep study-a study-drop; do
        mkdir -p "pf-$n"
        st "$n-sw" "$n-sw.json" "$tool" sweep -q --json -j 2 --set end_time=0.3 --point-files "pf-$n" --point-csv \
            -o "$n-sw" "$work/cases/$n.cfg"
    done
    st vary-sw vary-sw.json "$tool" sweep -q --json -j 2 --set end_time=0.3 --vary speed=100:200:3 -o vary-sw \
        "$work/cases/paper-c.cfg"
    for f in paper-a rub-damped paper-a-modal rub-damped-sweep-sw study-drop-sw vary-sw; do
        st "plot-$f" "plot-$f.out" "$tool" plot --no-run -d "plot-$f" "$f.h5"
    done
    cd - >/dev/null
}

echo "same-outputs: $old -> $work/old"
outputs "$old" "$work/old"
echo "same-outputs: $new -> $work/new"
outputs "$new" "$work/new"
exec /usr/bin/python3 "$here/scripts/same_outputs.py" "$work/old" "$work/new"
