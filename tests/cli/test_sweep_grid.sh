#!/usr/bin/env bash
# `touchdown sweep` grids: the case file's `sweep` group (cases/rub-damped-sweep.cfg) gives the
# table of the equivalent --vary command line, and --vary of one of its keys replaces that axis;
# a log range is a geometric progression with exact ends; a zipped sweep (--with) has a column per
# key and each row is what an independent `touchdown run --set` of that point says; --point-files
# keeps each point's result files, equal to those of `touchdown run` of the point apart from wall
# times; bad specs, bad groups and bad point directories are one line and exit 2.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/sweep-grid.XXXXXX")
trap 'rm -rf "$work"' EXIT
case_r=$src/cases/rub-damped.cfg
case_s=$src/cases/rub-damped-sweep.cfg

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish
need h5dump hdf5-tools
need h5diff hdf5-tools
has() { grep -qF -- "$2" "$1"; }
# The table's header and rows without their last column (wall time).
rows() { grep -v '^#' "$1" | sed 's/,[^,]*$//'; }
same_number() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 == b + 0) }'; }
# A run's CSV file without the lines that hold wall-clock times.
no_wall_lines() { grep -vE 'wall_time|realtime_factor' "$1"; }

# ---- (a) the case file's group against the same sweep on the command line -------------------
t "$work/file" sweep -j 2 --set end_time=0.05 -o s "$case_s"
rcf=$rc
t "$work/cli" sweep -j 2 --set end_time=0.05 --vary speed=60:240:9:log \
    --vary 'schedule[0].magnitude=0.05,0.1,0.2' -o s "$case_r"
check "sweep of the file's group and of --vary: exit 0 (got $rcf, $rc: $(head -c 200 "$work/file/.err"))" \
    test "$rcf" = 0 -a "$rc" = 0
check "the file's group: 27 rows, speed then schedule[0].magnitude" \
    test "$(rows "$work/file/s.csv" | wc -l)" = 28 -a \
    "$(head -n 1 "$work/file/s.csv" | cut -d, -f1-4)" = "point [-],speed,schedule[0].magnitude,status"
check "the file's group and the equivalent --vary give the same rows" \
    cmp -s <(rows "$work/file/s.csv") <(rows "$work/cli/s.csv")
check "the table records where each axis came from" \
    has "$work/file/s.csv" "# from = $case_s:15: sweep.vary[0]"
check "... and the command line's" has "$work/cli/s.csv" "# from = command line"
check "HDF5: /vary/speed has the origin attribute of the file's axis" \
    test -n "$(h5dump -a /vary/speed/origin "$work/file/s.h5" | grep -F 'sweep.vary[0]')"
# the log range: a constant ratio 2^(1/4) between neighbours, both ends exact
ratio_bad=$(rows "$work/file/s.csv" | awk -F, 'NR > 1 && $3 == 0.05 { v[n++] = $2 }
    END { if (v[0] != 60 || v[8] != 240) print "ends " v[0] " " v[8];
          for (i = 1; i < n; i++) { r = v[i] / v[i - 1] / 2 ^ 0.25; if (r > 1 + 1e-14 || r < 1 - 1e-14) print i } }')
check "the log range: 60 to 240 exactly, ratio 2^(1/4)${ratio_bad:+: $ratio_bad}" test -z "$ratio_bad"

# --vary of one of the group's keys replaces that axis; the other stays
t "$work/repl" sweep -j 2 --set end_time=0.05 --vary speed=90,190 -o s "$case_s"
check "--vary speed on the file's group: 2 x 3 rows, the command line's speeds first (rc $rc)" \
    test "$rc" = 0 -a "$(rows "$work/repl/s.csv" | wc -l)" = 7 -a \
    "$(rows "$work/repl/s.csv" | sed -n 5p | cut -d, -f1-3)" = "3,190,0.05"

# ---- (b) a zipped sweep against independent runs ----------------------------------------------
zip=(--set end_time=0.2 --vary speed=80,120,160 --with 'unbalances[0].magnitude=0.02,0.04,0.06')
t "$work/zip" sweep -j 2 "${zip[@]}" -o z "$case_r"
check "zipped sweep: exit 0, 3 rows, a column per key (rc $rc)" \
    test "$rc" = 0 -a "$(rows "$work/zip/z.csv" | wc -l)" = 4 -a \
    "$(head -n 1 "$work/zip/z.csv" | cut -d, -f1-4)" = "point [-],speed,unbalances[0].magnitude,status" -a \
    -n "$(grep -Fx '# with = unbalances[0].magnitude=0.02,0.04,0.06' "$work/zip/z.csv")"
bad=""
for p in 0 2; do
    line=$(rows "$work/zip/z.csv" | sed -n "$((p + 2))p")
    IFS=, read -r _ speed mag status _ phf imp fw ct nc _ <<<"$line"
    t "$work/zrun$p" run --json -q --csv '' --hdf5 '' --set end_time=0.2 --set "speed=$speed" \
        --set "unbalances[0].magnitude=$mag" "$case_r"
    o=$work/zrun$p/.out
    [ "$status" = success ] || bad="$bad point $p status $status"
    for pair in "$phf:$(jf "$o" peak_housing_force)" "$imp:$(jf "$o" total_impulse)" \
        "$fw:$(jf "$o" friction_work)" "$ct:$(jf "$o" contact_time)" "$nc:$(jf "$o" contacts)"; do
        same_number "${pair%%:*}" "${pair#*:}" || bad="$bad point $p (${pair})"
    done
done
check "zipped rows equal 'touchdown run --set speed --set unbalances[0].magnitude'${bad:+:$bad}" test -z "$bad"
check "zipped sweep: point 2 is speed 160 with magnitude 0.06" \
    test "$(rows "$work/zip/z.csv" | sed -n 4p | cut -d, -f1-3)" = "2,160,0.06"

# ---- (c) per-point result files ---------------------------------------------------------------
mkdir -p "$work/pf/pts"
t "$work/pf" sweep -j 2 --set end_time=0.05 --vary speed=90,150 --with 'schedule[0].magnitude=0.05,0.2' \
    --point-files pts --point-csv -o p "$case_r"
check "--point-files: exit 0 and a .h5 and .csv per point (rc $rc)" \
    test "$rc" = 0 -a -s "$work/pf/pts/point-000000.h5" -a -s "$work/pf/pts/point-000001.h5" \
    -a -s "$work/pf/pts/point-000000.csv" -a -s "$work/pf/pts/point-000001.csv"
check "--point-files: each point's CSV is complete" \
    test "$(tail -n 1 "$work/pf/pts/point-000000.csv")" = "# complete" -a \
    "$(tail -n 1 "$work/pf/pts/point-000001.csv")" = "# complete"
t "$work/pf1" run -q --set end_time=0.05 --set speed=150 --set 'schedule[0].magnitude=0.2' -o r "$case_r"
check "point 1's CSV equals that of 'touchdown run --set ...' but for wall times" \
    cmp -s <(no_wall_lines "$work/pf/pts/point-000001.csv") <(no_wall_lines "$work/pf1/r.csv")
check "point 1's HDF5 datasets equal those of 'touchdown run --set ...' (h5diff)" \
    h5diff -q --exclude-attribute / "$work/pf/pts/point-000001.h5" "$work/pf1/r.h5"
check "point 1's HDF5 file is flagged complete" \
    test -n "$(h5dump -a /complete "$work/pf/pts/point-000001.h5" | grep -E '^ *\(0\): 1$')"

# ---- (d) bad input: one line naming what is wrong, exit 2, nothing written -------------------
bad_run() { # DIR EXPECTED ARGS...: exit 2, one line holding EXPECTED, no table
    local d=$1 want=$2
    shift 2
    t "$d" sweep --set end_time=0.03 -o b "$@"
    check "sweep $*: exit 2, one line naming '$want' ($(head -n 1 "$d/.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$d/.err")" = 1 -a ! -e "$d/b.csv" -a -n "$(grep -F -- "$want" "$d/.err")"
}
bad_run "$work/b1" "--vary 'speed=0:100:3:log': a log range needs both ends > 0" --vary speed=0:100:3:log "$case_r"
bad_run "$work/b2" "the spacing must be linear or log" --vary speed=1:100:3:lin "$case_r"
bad_run "$work/b3" "unbalances[0].magnitude has 2 values but speed, whose axis it joins, has 3" \
    --vary speed=1,2,3 --with 'unbalances[0].magnitude=0.1,0.2' "$case_r"
bad_run "$work/b4" "--with 'speed=1,2': no axis to join" --with speed=1,2 "$case_r"
bad_run "$work/b4w" "--with 'retainers[0].friction=-1': retainers[0].friction: must be >= 0" \
    --vary speed=80,90 --with 'retainers[0].friction=0.1,-1' "$case_r"
bad_run "$work/b5" "--point-files" --vary speed=80,90 --point-files no/such/dir "$case_r"
bad_run "$work/b6" "--point-csv needs --point-files" --vary speed=80,90 --point-csv "$case_r"
bad_run "$work/b7" "sweep.vary[0].points: the number of points" --set 'sweep.vary[0].points=0' "$case_s"
# a bad group in a file: FILE:LINE: KEY
cp "$src/cases/rub-damped.cfg" "$src/cases/rig.cfg" "$work/"
printf '@include "rub-damped.cfg"\nsweep = {\n  vary = ( { key = "speed"; values = [ 80.0, 90.0 ];\n    with = ( { key = "end_time"; values = [ 0.1 ]; } ); } );\n};\n' >"$work/bad.cfg"
bad_run "$work/b8" "bad.cfg:4: sweep.vary[0].with[0].values: end_time has 1 values but speed" "$work/bad.cfg"
printf '@include "rub-damped.cfg"\nsweep = {\n  vary = ( { key = "speedo"; values = [ 80.0, 90.0 ]; } );\n};\n' >"$work/bad2.cfg"
bad_run "$work/b10" "bad2.cfg:3: sweep.vary[0]: " "$work/bad2.cfg"
check "... and the unknown key" has "$work/b10/.err" "speedo: unknown key"
t "$work/b9" run -q --set end_time=0.001 "$work/bad.cfg"
check "touchdown run of a case with a bad sweep group: exit 2 naming it" \
    test "$rc" = 2 -a -n "$(grep -F 'bad.cfg:4: sweep.vary[0].with[0].values' "$work/b9/.err")"

finish
