#!/usr/bin/env bash
# `touchdown plot SWEEP.h5`: a sweep table gives the quantity against a swept key, the regime map
# and the bifurcation diagram; their data files hold the table's own numbers (checked against the
# CSV table, written by the same sweep); options the table cannot take are one line and exit 2;
# with gnuplot the figures are drawn without a message.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
export LC_ALL=C
work=$(mktemp -d "${PWD}/sweep-plot.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# The data files print 12 significant digits: numbers are compared to 1e-11 relative.
# Column number of NAME (header text before " [") in the CSV table.
col() { head -n 1 "$1" | tr ',' '\n' | sed 's/ \[.*//' | grep -nxF -- "$2" | cut -d: -f1; }
rows() { grep -v '^#' "$1" | tail -n +2; }

# 4 points of rub-damped (2 speeds x 2 unbalance steps), 0.3 s each: free, bouncing and rubbing
t "$work/s" sweep -j 2 --set end_time=0.3 --vary speed=60,120 --vary 'schedule[0].magnitude=0.05,0.2' -o s \
    "$src/cases/rub-damped.cfg"
check "sweep: exit 0 (got $rc: $(head -c 300 "$work/s/.err"))" test "$rc" = 0
csv=$work/s/s.csv
c_phf=$(col "$csv" peak_housing_force)
c_reg=$(col "$csv" regime)
c_cnt=$(col "$csv" section_count)
c_min=$(col "$csv" section_radius_min)
c_max=$(col "$csv" section_radius_max)
check "sweep table: regime and section columns" test -n "$c_reg" -a -n "$c_cnt" -a -n "$c_min" -a -n "$c_max"

# the section and the regime of a point are those of an independent `touchdown run` of it
t "$work/r" run --json -q --csv '' --hdf5 '' --set end_time=0.3 --set speed=120 --set 'schedule[0].magnitude=0.2' \
    "$src/cases/rub-damped.cfg"
line=$(grep '^3,120,0.2,' "$csv" | sed -E 's/"[^"]*"/x/g')
IFS=, read -r -a f <<<"$line"
radii=$(grep -oE '"section_radius":\[[^]]*\]' "$work/r/.out" | sed -E 's/.*\[//; s/\]//' | tr ',' '\n')
check "sweep row 3: section count, range and regime of 'touchdown run --json' of the point" \
    test "$(jf "$work/r/.out" section_count)" = "${f[$((c_cnt - 1))]}" -a \
    "$(jf "$work/r/.out" regime)" = "\"${f[$((c_reg - 1))]}\"" -a \
    "$(sort -g <<<"$radii" | head -n 1)" = "${f[$((c_min - 1))]}" -a \
    "$(sort -g <<<"$radii" | tail -n 1)" = "${f[$((c_max - 1))]}"

# ---- --no-run: the data files against the table -----------------------------------------------
t "$work/s" plot --no-run -d p s.h5
check "plot --no-run: exit 0 (got $rc: $(cat "$work/s/.err"))" test "$rc" = 0
d=$work/s/p
for f in sweep-peak_housing_force regime-map bifurcation; do
    check "plot: $f.dat and $f.gp" test -s "$d/$f.dat" -a -s "$d/$f.gp"
done
bad=""
regimes=("failed" "free" "rub" "bounce" "backward whirl")
while IFS= read -r line; do
    p=${line%%,*}
    speed=$(cut -d, -f2 <<<"$line")
    # the CSV quotes text with commas (the ending): take the columns from the end of the row
    IFS=, read -r -a f <<<"$(sed -E 's/"[^"]*"/x/g' <<<"$line")"
    phf=${f[$((c_phf - 1))]}
    reg=${f[$((c_reg - 1))]}
    cnt=${f[$((c_cnt - 1))]}
    rmin=${f[$((c_min - 1))]}
    rmax=${f[$((c_max - 1))]}
    awk -v s="$speed" -v q="$phf" -v p="$p" 'function near(a, b) { return a == b || (a - b) ^ 2 <= 1e-22 * b ^ 2 }
        !/^#/ && NF == 3 && $1 + 0 == s + 0 && near($2, q) && $3 == p { found = 1 } END { exit !found }' "$d/sweep-peak_housing_force.dat" || bad="$bad point $p: peak_housing_force"
    code=$(awk -v p="$p" '!/^#/ && $8 == p { print $7 }' "$d/regime-map.dat")
    [ -n "$code" ] && [ "${regimes[$code]}" = "$reg" ] || bad="$bad point $p: regime $reg, map code '$code'"
    # the section: min(count, 64) radii of the point, in mm, from section_radius_min to _max
    kept=$((cnt < 64 ? cnt : 64))
    awk -v p="$p" -v n="$kept" -v lo="$rmin" -v hi="$rmax" 'function near(a, b) { return (a - b) ^ 2 <= 1e-22 * b ^ 2 }
        !/^#/ && NF == 3 && $3 == p { k++; if (k == 1 || $2 < a) a = $2; if (k == 1 || $2 > b) b = $2 }
        END { exit !(k == n && (n == 0 || (near(a, lo * 1e3) && near(b, hi * 1e3)))) }' "$d/bifurcation.dat" ||
        bad="$bad point $p: section ($kept radii from $rmin to $rmax m)"
done < <(rows "$csv")
check "plot data files hold the table's quantity, regime and section radii${bad:+:$bad}" test -z "$bad"
check "bifurcation: the clearance (0.75 mm) dashed" \
    test "$(awk '!/^#/ { print $2 }' "$d/bifurcation-clearance.dat" | sort -u)" = 0.75

t "$work/s" plot --no-run -d q --quantity contacts --x 'schedule[0].magnitude' s.h5
check "plot --quantity contacts --x 'schedule[0].magnitude': exit 0, lines per speed" \
    test "$rc" = 0 -a -s "$work/s/q/sweep-contacts.dat" -a \
    -n "$(grep -F '# speed=120' "$work/s/q/sweep-contacts.dat")"

# a key zipped onto the speed axis (--with) moves along the lines: one line per value of the
# key on the other axis, and that key is the regime map's y
t "$work/z" sweep -j 2 --set end_time=0.1 --vary speed=60,120 --with 'schedule[0].magnitude=0.05,0.2' \
    --vary 'unbalances[0].phase=0,1' -o z "$src/cases/rub-damped.cfg"
t "$work/z" plot --no-run -d p z.h5
check "plot of a zipped sweep: lines by the other axis only, its key the map's y (got $rc: $(cat "$work/z/.err"))" \
    test "$rc" = 0 -a "$(grep -c '^# unbalances\[0\].phase=' "$work/z/p/sweep-peak_housing_force.dat")" = 2 -a \
    -n "$(grep -F '2 unbalances[0].phase' "$work/z/p/regime-map.dat")"

# ---- log axes: tiles meet at the geometric means (60 and 120: sqrt(7200) = 84.8528137424) ------
t "$work/s" plot --no-run -d lg --log-x --log-y s.h5
check "plot --log-x --log-y: exit 0, tile edges halfway along the logs, log scales in the scripts (got $rc)" \
    test "$rc" = 0 -a "$(awk '!/^#/ && $1 == 60 { print $4 }' "$work/s/lg/regime-map.dat" | sort -u)" = 84.8528137424 -a \
    "$(awk '!/^#/ && $1 == 120 { print $3 }' "$work/s/lg/regime-map.dat" | sort -u)" = 84.8528137424 -a \
    "$(awk '!/^#/ && $2 == 0.05 { print $6 }' "$work/s/lg/regime-map.dat" | sort -u)" = 0.1 -a \
    -n "$(grep -x 'logx = 1' "$work/s/lg/bifurcation.gp")" -a -n "$(grep -x 'logy = 0' "$work/s/lg/bifurcation.gp")" -a \
    -n "$(grep -x 'logy = 1' "$work/s/lg/regime-map.gp")"
t "$work/z" plot --no-run -d lgz --log-x --x 'unbalances[0].phase' z.h5
check "plot --log-x of a key with the value 0: exit 2, one line naming it ($(cat "$work/z/.err"))" \
    test "$rc" = 2 -a "$(wc -l <"$work/z/.err")" = 1 -a -n "$(grep -F -- '--log-x: unbalances[0].phase' "$work/z/.err")"

# ---- bad options: one line, exit 2 --------------------------------------------------------------
for args in "--quantity nosuch" "--x nosuch" "--x speed --y speed" "--quantity ending" "--x status"; do
    t "$work/s" plot --no-run -d bad $args s.h5
    check "plot $args: exit 2, one line ($(cat "$work/s/.err"))" \
        test "$rc" = 2 -a "$(wc -l <"$work/s/.err")" = 1
done

# ---- gnuplot ------------------------------------------------------------------------------------
need gnuplot gnuplot-nox
t "$work/s" plot -d g s.h5
ok=1
for f in sweep-peak_housing_force regime-map bifurcation; do
    [ -s "$work/s/g/$f.png" ] || ok=0
done
check "plot with gnuplot: exit 0, three PNGs, no gnuplot message (got $rc: $(cat "$work/s/.err"))" \
    test "$rc" = 0 -a "$ok" = 1 -a -z "$(find "$work/s/g" -name '*.log' -size +0)"
finish
