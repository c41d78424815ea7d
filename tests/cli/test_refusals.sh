#!/usr/bin/env bash
# Hostile arguments to plot, run, modal and sweep are refused with one line and exit 2, naming
# what the user wrote, and leave nothing behind:
#   plot --quantity NAME where NAME is no number column of the sweep table (a group, a string
#     column, the index, a path into a group, a 2-D dataset, ''): the line names NAME and lists the
#     columns it can plot, which are exactly the table's numeric per-point datasets (read with h5py)
#     and each of which plots; never a crash (the tool under ASan aborts on a bad free);
#   plot refusing leaves no output folder it created (nor its parents), and keeps one that was there;
#   plot of a sweep table whose /status, /regime or /vary/KEY is shorter or longer than /point:
#     one line naming the column, exit 2, never a crash or a leak;
#   run/modal/sweep -o PREFIX naming no file ('', 'dir/', '.', 'dir/..') write no hidden file;
#   sweep --vary ranges whose arithmetic overflows (a log ratio or a linear span beyond a double,
#     on the command line and in a case file's sweep group) name the ends written, not "inf".
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
export LC_ALL=C
work=$(mktemp -d "${PWD}/refusals.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# one_line DIR: stderr is one line and stdout is empty
one_line() { test "$(wc -l <"$1/.err")" = 1 -a ! -s "$1/.out"; }

# ---- plot --quantity ----------------------------------------------------------------------------
t "$work/s" sweep -q --no-progress -j 1 --set end_time=0.02 --vary speed=60,120 -o s "$src/cases/paper-a.cfg"
check "sweep: a 2-point table (exit $rc: $(head -c 200 "$work/s/.err"))" test "$rc" = 0 -a -s "$work/s/s.h5"
for q in vary regime status point vary/speed section_radius ''; do
    t "$work/s" plot --no-run -d "q-$q" --quantity "$q" s.h5
    check "plot --quantity '$q': exit 2, one line naming it and what can be plotted (exit $rc: $(head -c 300 "$work/s/.err"))" \
        test "$rc" = 2 -a -n "$(grep -F -- "--quantity '$q' is not a numeric column" "$work/s/.err" |
            grep -F 'peak_housing_force, ')" && one_line "$work/s"
done
listed=$(sed -E 's/.*\(it has: (.*)\)$/\1/' "$work/s/.err" | sed 's/, /\n/g')
py=$(h5py_python)
if [ -n "$py" ]; then
    numeric=$("$py" - "$work/s/s.h5" <<'EOF'
import sys, h5py, numpy
with h5py.File(sys.argv[1], "r") as f:
    n = f["point"].shape[0]
    for name in sorted(f):
        d = f[name]
        if name != "point" and isinstance(d, h5py.Dataset) and d.shape == (n,) and d.dtype.kind in "fiu":
            print(name)
EOF
)
    check "plot --quantity: the columns listed are the table's numeric per-point datasets (h5py)" \
        test -n "$listed" -a "$listed" = "$numeric"
fi
bad=""
for q in $listed; do
    t "$work/s" plot --no-run -q -d ok --quantity "$q" s.h5
    [ "$rc" = 0 ] || bad="$bad $q($rc)"
done
check "plot --quantity: every column listed plots (refused:$bad)" test -z "$bad"

# ---- plot leaves no folder it made -------------------------------------------------------------
t "$work/s" plot --no-run -d new/sub/dir --quantity regime s.h5
check "plot refused into -d new/sub/dir: exit 2, no new/ left" test "$rc" = 2 -a ! -e "$work/s/new"
t "$work/s" plot --no-run --x status s.h5
check "plot refused into its default folder: exit 2, no s-plots/ left" test "$rc" = 2 -a ! -e "$work/s/s-plots"
mkdir -p "$work/s/kept"
t "$work/s" plot --no-run -d kept/sub --quantity regime s.h5
check "plot refused into kept/sub: kept/ (there before) stays, kept/sub goes" \
    test "$rc" = 2 -a -d "$work/s/kept" -a ! -e "$work/s/kept/sub"

# ---- plot of a table whose per-point columns disagree in length -------------------------------
# /status, /regime or a text /vary/KEY rewritten (h5py) shorter or longer than /point: refused with
# one line naming the column, never a crash (what was read is freed by its own length; under ASan
# a bad free or a leak aborts)
if [ -n "$py" ]; then
    t "$work/m" sweep -q --no-progress -j 1 --set end_time=0.002 --vary speed=60:120:8 -o m \
        "$src/tests/data/case/amb-jeffcott.cfg"
    check "sweep: an 8-point table (exit $rc: $(head -c 200 "$work/m/.err"))" test "$rc" = 0 -a -s "$work/m/m.h5"
    for edit in status:1 status:11 regime:2 vary/speed:3; do
        name=${edit%:*}
        cp "$work/m/m.h5" "$work/m/e.h5"
        "$py" - "$work/m/e.h5" "$name" "${edit#*:}" <<'EOF'
import sys, h5py
with h5py.File(sys.argv[1], "r+") as f:
    name, n = sys.argv[2], int(sys.argv[3])
    del f[name]
    f.create_dataset(name, data=["success"] * n, dtype=h5py.string_dtype())
EOF
        t "$work/m" plot --no-run -d e-plots e.h5
        check "plot of a table whose /$name has ${edit#*:} of 8 entries: exit 2, one line naming it (exit $rc: $(head -c 300 "$work/m/.err"))" \
            test "$rc" = 2 -a -n "$(grep -F "/$name" "$work/m/.err")" -a ! -e "$work/m/e-plots" && one_line "$work/m"
    done
    rm -rf "$work/m" # the -o checks below expect nothing else in $work
fi

# ---- -o PREFIX that names no file ---------------------------------------------------------------
mkdir -p "$work/o/d"
for cmd in run modal sweep; do
    extra=()
    [ "$cmd" = sweep ] && extra=(--vary speed=60,61)
    for p in '' d/ . d/..; do
        t "$work/o" "$cmd" -q --set end_time=0.01 "${extra[@]}" -o "$p" "$src/cases/paper-a.cfg"
        check "$cmd -o '$p': exit 2, one line naming --output '$p', no file written (exit $rc: $(head -c 200 "$work/o/.err"))" \
            test "$rc" = 2 -a -n "$(grep -F -- "--output '$p' names no file" "$work/o/.err")" -a \
            -z "$(ls -A "$work/o/d")" -a "$(ls -A "$work/o" | tr '\n' ' ')" = ".err .out d " -a \
            -z "$(ls -A "$work" | grep -v '^[os]$')" && one_line "$work/o"
    done
done

# ---- --vary whose arithmetic overflows ----------------------------------------------------------
for v in 'speed=1e-300:1e300:3:log' 'speed=1e300:1e-300:3:log' 'speed=1e-320:1:3:log' \
    'speed=-1.5e308:1.5e308:3' 'speed=1.5e308:-1.5e308:4:linear'; do
    t "$work/v" sweep -q --no-progress --set end_time=0.01 --vary "$v" -o v "$src/cases/paper-a.cfg"
    from=$(sed -E 's/^speed=([^:]*):.*/\1/' <<<"$v")
    to=$(sed -E 's/^speed=[^:]*:([^:]*):.*/\1/' <<<"$v")
    check "sweep --vary '$v': exit 2, one line naming the range $from to $to, no 'inf' (exit $rc: $(head -c 300 "$work/v/.err"))" \
        test "$rc" = 2 -a -n "$(grep -F -- "--vary '$v': " "$work/v/.err" | grep -F "from $from to $to")" -a \
        -z "$(grep -i 'inf' "$work/v/.err")" -a -z "$(ls "$work/v")" && one_line "$work/v"
done
t "$work/v" sweep -q --no-progress -j 1 --set end_time=0.01 --vary 'speed=1e-300:1e300:2:log' -o v2 \
    --set 'speed=60' "$src/cases/paper-a.cfg"
check "sweep --vary 'speed=1e-300:1e300:2:log': two points, nothing computed between them: not refused by the range" \
    test -z "$(grep -F 'range' "$work/v/.err")"
rm -f "$work"/v/v2*
cp -r "$src/cases" "$work/v/cases"
cat >"$work/v/cases/wide.cfg" <<EOF
@include "paper-a.cfg"
sweep = {
  vary = ( { key = "speed"; from = 1e-300; to = 1e300; points = 5; spacing = "log"; } );
};
EOF
t "$work/v" sweep -q --no-progress --set end_time=0.01 -o w cases/wide.cfg
check "a case file's sweep range beyond a double: exit 2, FILE:LINE: sweep.vary[0].to (exit $rc: $(head -c 300 "$work/v/.err"))" \
    test "$rc" = 2 -a -n "$(grep -E 'wide\.cfg:3: sweep\.vary\[0\]\.to: .*from 1e-300 to 1e\+?300' "$work/v/.err")" &&
    one_line "$work/v"

finish
