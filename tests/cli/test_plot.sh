#!/usr/bin/env bash
# touchdown plot: figures from simulation and modal files, options, and error handling.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory,
# where test_plot_fixture (tests/test_plot_fixture.c) writes synthetic result files through the
# public td_writer API. When 'touchdown run' works, a short real run is plotted too.
# gnuplot runs in the C locale (that of a bare system or a CI job), where an encoding it cannot
# convert makes it warn; every warning fails the test: touchdown plot keeps gnuplot's messages in
# DIR/NAME.log only when there are any, so no .log file may be left (no_gnuplot_messages).
set -u
tool=$1
src=$2
fails=0
export LC_ALL=C
work=$(mktemp -d "${PWD}/plot-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
pass() { echo "ok:   $*"; }

# A non-empty PNG (magic bytes 89 50 4E 47 0D 0A 1A 0A).
is_png() {
    [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
}

expect_pngs() { # DIR NAME...
    local dir=$1 name ok=1
    shift
    for name in "$@"; do
        if ! is_png "$dir/$name.png"; then fail "$dir/$name.png is missing or not a PNG"; ok=0; fi
        if [ ! -s "$dir/$name.gp" ]; then fail "$dir/$name.gp is missing"; ok=0; fi
    done
    [ $ok = 1 ] && pass "$dir: $* (PNG + script)"
    no_gnuplot_messages "$dir"
}

# gnuplot printed nothing (no warning) for any figure of DIR: no NAME.log left there.
no_gnuplot_messages() { # DIR
    local logs
    logs=$(find "$1" -name '*.log' -size +0 2>/dev/null)
    if [ -n "$logs" ]; then
        fail "$1: gnuplot printed messages (LC_ALL=$LC_ALL): $(cat $logs | head -n 3 | tr '\n' ' ')"
    else
        pass "$1: gnuplot printed no message (LC_ALL=$LC_ALL)"
    fi
}

# Exit status CODE and exactly one line on stderr.
expect_error() { # CODE DESCRIPTION ARGS...
    local code=$1 what=$2 rc lines
    shift 2
    "$tool" plot "$@" >"$work/out" 2>"$work/err"
    rc=$?
    lines=$(wc -l <"$work/err")
    if [ "$rc" != "$code" ]; then
        fail "$what: exit $rc, expected $code ($(head -n 3 "$work/err"))"
    elif [ "$lines" != 1 ]; then
        fail "$what: $lines lines on stderr, expected 1: $(cat "$work/err")"
    else
        pass "$what: exit $code, '$(cat "$work/err")'"
    fi
}

if [ ! -x ./test_plot_fixture ]; then
    echo "FAIL: ./test_plot_fixture not built (run in the build's tests directory)"
    exit 1
fi
if ! TD_PLOT_FIXTURE_DIR="$work" ./test_plot_fixture >"$work/fixture.log" 2>&1; then
    cat "$work/fixture.log"
    echo "FAIL: the fixture program failed"
    exit 1
fi
cd "$work" || exit 1

# ---- help ---------------------------------------------------------------------------------
if "$tool" plot --help >help.txt 2>&1 && grep -q -- '--retainer' help.txt && grep -q -- '--no-run' help.txt &&
    grep -q 'exit codes' help.txt; then
    pass "--help"
else
    fail "--help"
fi

# ---- one simulation file, default directory -----------------------------------------------
if "$tool" plot plot-fixture-constraint.h5 >out.txt 2>err.txt; then
    d=plot-fixture-constraint-plots
    expect_pngs "$d" orbit-r0 orbit-r1 radial-force-r0 radial-force-r1 amb-forces
    # one 'wrote' line per figure, nothing on stderr
    [ "$(grep -c '^wrote ' out.txt)" = 5 ] && [ ! -s err.txt ] && pass "5 'wrote' lines, quiet stderr" ||
        fail "output: $(cat out.txt err.txt)"
    # data: every sample (0.6 s at 2 kHz = 1201) with mm and N columns; the clearance in the script
    n=$(grep -vc '^#' "$d/retainer0.dat")
    [ "$n" = 1201 ] && pass "retainer0.dat has 1201 samples" || fail "retainer0.dat has $n samples"
    awk '!/^#/ && $6 == 1 { if ($4 < 0.7499 || $4 > 0.7501) bad = 1; c++ } END { exit !(c > 0 && !bad) }' \
        "$d/retainer0.dat" && pass "contact samples sit at r = 0.75 mm" || fail "contact rows of retainer0.dat"
    grep -q '^c = 0.75 ' "$d/orbit-r0.gp" && grep -q 'size ratio -1' "$d/orbit-r0.gp" &&
        pass "orbit script: clearance 0.75 mm, equal axes" || fail "orbit-r0.gp lacks the clearance or equal axes"
    [ "$(grep -vc '^#' "$d/contacts0.dat")" -ge 1 ] && [ "$(grep -vc '^#' "$d/contacts1.dat")" = 0 ] &&
        pass "contact intervals: some at retainer 0, none at retainer 1" || fail "contact interval files"
    grep -q 'Plot fixture: synthetic whirl' "$d/radial-force-r0.gp" && pass "title from the case description" ||
        fail "the case description is not in the title"
    # the kept scripts rerun on their own
    rm -f "$d/orbit-r0.png"
    (cd "$d" && gnuplot orbit-r0.gp) 2>rerun.err && is_png "$d/orbit-r0.png" && pass "gnuplot orbit-r0.gp reruns" ||
        fail "rerunning orbit-r0.gp"
    [ ! -s rerun.err ] && pass "the rerun prints nothing" || fail "the rerun printed: $(head -n 3 rerun.err)"
    # and in a UTF-8 locale, when the system has one
    if locale -a 2>/dev/null | grep -qix 'C.utf-\?8'; then
        rm -f "$d/orbit-r0.png"
        (cd "$d" && LC_ALL=C.UTF-8 gnuplot orbit-r0.gp) 2>rerun.err && is_png "$d/orbit-r0.png" &&
            [ ! -s rerun.err ] && pass "the rerun prints nothing in C.UTF-8 either" ||
            fail "rerun in C.UTF-8: $(head -n 3 rerun.err)"
    fi
else
    fail "plot of one simulation file: $(cat err.txt)"
fi

# ---- options ------------------------------------------------------------------------------
if "$tool" plot -q -d win --retainer 1 --from 0.1 --to 0.2 plot-fixture-constraint.h5 2>err.txt; then
    expect_pngs win orbit-r1 radial-force-r1 amb-forces
    [ ! -e win/orbit-r0.png ] && pass "--retainer 1 leaves retainer 0 out" || fail "--retainer 1 drew retainer 0"
    awk '!/^#/ { if ($1 < 0.1 || $1 > 0.2) bad = 1; n++ } END { exit !(n >= 200 && !bad) }' win/retainer1.dat &&
        pass "--from/--to window" || fail "--from/--to: samples outside [0.1, 0.2] s"
else
    fail "plot with --retainer/--from/--to: $(cat err.txt)"
fi
if "$tool" plot -q --no-run -d norun plot-fixture-constraint.h5 2>err.txt && [ -s norun/orbit-r0.gp ] &&
    [ -s norun/retainer0.dat ] && ! ls norun/*.png >/dev/null 2>&1; then
    pass "--no-run writes scripts and data only"
else
    fail "--no-run"
fi
if "$tool" plot -q --format svg -d svg plot-fixture-constraint.h5 2>err.txt && [ -s svg/orbit-r0.svg ] &&
    grep -q '<svg' svg/orbit-r0.svg; then
    pass "--format svg"
else
    fail "--format svg: $(cat err.txt)"
fi

# ---- an incomplete run is plotted and says so ---------------------------------------------
if "$tool" plot -q -d inc plot-fixture-incomplete.h5 2>err.txt; then
    expect_pngs inc orbit-r0 radial-force-r0
    grep -q 'INCOMPLETE: solver failure at t = 0.25 s' inc/radial-force-r0.gp && pass "incomplete run flagged in the title" ||
        fail "incomplete run not flagged"
else
    fail "plot of an incomplete file: $(cat err.txt)"
fi

# ---- projective leap: no line across a leap, and no break anywhere else -----------------------
# plot-fixture-leap.h5 (tests/test_plot_fixture.c, write_leaps): leaps from 0.05 s (where an
# event's row and the grid's share the time) to 0.25 s and from 0.3 s to 0.45 s. The data files
# break their line (a blank line) between each leap's start and the row it lands on, and only
# there: not between the two rows at 0.05 s. touchdown report's data (report.dat, kept by a
# gnuplot that copies it before it draws) breaks at the same places, by the same rule.
# BEFORE AFTER pairs around each blank line of a data file: "0.05>0.25 0.3>0.45"
breaks() { awk '/^#/ { next } /^$/ { b = 1; next } { if (b) printf "%s%s>%s", n++ ? " " : "", p, $1; b = 0; p = $1 }' "$1"; }
if "$tool" plot -q --no-run -d leap plot-fixture-leap.h5 2>err.txt; then
    for f in retainer0 retainer1 ambs; do
        test "$(breaks leap/$f.dat)" = "0.05>0.25 0.3>0.45" && pass "leaps: $f.dat breaks at the two leaps only" ||
            fail "leaps: $f.dat breaks at '$(breaks leap/$f.dat)', not '0.05>0.25 0.3>0.45'"
    done
else
    fail "plot of a file with leaps: $(cat err.txt)"
fi
printf '#!/bin/sh\ncp report.dat "%s/report-leap.dat" && exec gnuplot "$@"\n' "$work" >keep-gnuplot
chmod +x keep-gnuplot
if TOUCHDOWN_GNUPLOT="$work/keep-gnuplot" "$tool" report -o leap-report plot-fixture-leap.h5 >/dev/null 2>err.txt; then
    test "$(breaks report-leap.dat)" = "0.05>0.25 0.3>0.45" && pass "leaps: the report's data breaks at the two leaps only" ||
        fail "leaps: the report's data breaks at '$(breaks report-leap.dat)', not '0.05>0.25 0.3>0.45'"
else
    fail "report of a file with leaps: $(cat err.txt)"
fi

# ---- several files: overlays with the file names as legend --------------------------------
if "$tool" plot -q -d cmp plot-fixture-constraint.h5 plot-fixture-penalty.h5 2>err.txt; then
    expect_pngs cmp compare-r0 compare-r1 plot-fixture-constraint-orbit-r0 plot-fixture-penalty-radial-force-r0
    # the legend labels are the array label[] that the template's plot command takes its titles from
    grep -q 'label\[1\] = "plot-fixture-constraint"' cmp/compare-r0.gp &&
        grep -q 'label\[2\] = "plot-fixture-penalty"' cmp/compare-r0.gp && grep -q 'title label\[i\]' cmp/compare-r0.gp &&
        pass "overlay legend from the file names" || fail "overlay legend"
else
    fail "plot of two files: $(cat err.txt)"
fi

# ---- a modal file -------------------------------------------------------------------------
if "$tool" modal -q -o modal "$src/cases/paper-a.cfg" >/dev/null 2>err.txt; then
    if "$tool" plot -q modal.h5 2>err.txt; then
        expect_pngs modal-plots campbell mode-shapes sensitivity open-loop nyquist compliance
        grep -q "x/(2\*pi)" modal-plots/campbell.gp && pass "Campbell diagram has the 1x line" || fail "no 1x line"
    else
        fail "plot of a modal file: $(cat err.txt)"
    fi
else
    fail "touchdown modal failed, cannot test the modal figures: $(head -n 2 err.txt)"
fi

# ---- every kind of kept script reruns on its own, silently ---------------------------------
# (each is a template from tools/plot/gp/ with its variables in front: nothing else is needed)
if [ -d modal-plots ]; then
    rerun_ok=1
    for gp in plot-fixture-constraint-plots/*.gp cmp/*.gp modal-plots/*.gp; do
        png=${gp%.gp}.png
        rm -f "$png"
        if ! (cd "$(dirname "$gp")" && gnuplot "$(basename "$gp")") 2>rerun.err || ! is_png "$png" || [ -s rerun.err ]; then
            fail "rerunning $gp: $(head -n 3 rerun.err)"
            rerun_ok=0
        fi
    done
    [ $rerun_ok = 1 ] && pass "every script (simulation, compare, modal) reruns on its own"
fi

# ---- a real run, when the simulation works ------------------------------------------------
# (case A to 0.2 s: the unbalance step at 0.1 s and the first contacts; an incomplete file is
# plotted too, it is still a result file)
(timeout 300 "$tool" run -q --no-progress --set end_time=0.2 -o run "$src/cases/paper-a.cfg") >/dev/null 2>run.err
if [ -s run.h5 ]; then
    if "$tool" plot -q run.h5 2>err.txt; then
        expect_pngs run-plots orbit-r0 radial-force-r0 amb-forces
        # the shaded contact intervals against the event table (CSV events file): one interval
        # per onset at retainer 0, starting at the onset time
        if [ -s run.events.csv ]; then
            awk -F, '!/^#/ && NR > 1 && $4 == 0 && ($3 == "contact_onset" || $3 == "penalty_enter") { print $1 }' \
                run.events.csv >onsets.txt
            grep -v '^#' run-plots/contacts0.dat | awk '{ print $1 }' >starts.txt
            if [ "$(wc -l <onsets.txt)" -gt 0 ] && [ "$(wc -l <onsets.txt)" = "$(wc -l <starts.txt)" ] &&
                paste onsets.txt starts.txt | awk '{ d = $1 - $2; if (d < 0) d = -d; if (d > 1e-9) bad = 1 }
                                                   END { exit bad }'; then
                pass "contact intervals start at the $(wc -l <onsets.txt) onset events"
            else
                fail "contact intervals ($(wc -l <starts.txt)) do not match the onset events ($(wc -l <onsets.txt))"
            fi
        fi
    else
        fail "plot of a real run: $(cat err.txt)"
    fi
else
    echo "note: 'touchdown run' wrote no file in this build; real-run plotting not tested ($(head -c 200 run.err))"
fi

# ---- housing motion: its figure, the housing's acceleration in g against the prescribed pulse ----
# (case A to 0.03 s under a 5 g half-sine from 5 ms to 15 ms: the peak, -5 g at 10 ms, is a sample;
# a run without housing motion, above, has no housing figure)
(timeout 300 "$tool" run -q --no-progress --set end_time=0.03 \
    --set 'housing={shocks=({shape="half-sine";amplitude=49.03325;duration=0.01;start=0.005;direction=[0.0,-1.0];});}' \
    -o shock "$src/cases/paper-a.cfg") >/dev/null 2>shock.err
if [ -s shock.h5 ]; then
    if "$tool" plot -q shock.h5 2>err.txt; then
        expect_pngs shock-plots housing
        awk '!/^#/ && $1 == 0.01 { found = 1; if ($3 > -5 - 1e-6 && $3 < -5 + 1e-6) ok = 1 } END { exit !(found && ok) }' \
            shock-plots/housing.dat && pass "housing figure: -5 g at the pulse's middle" ||
            fail "housing figure data: $(grep -v '^#' shock-plots/housing.dat | awk '$1 == 0.01')"
    else
        fail "plot of a run with housing motion: $(cat err.txt)"
    fi
    [ ! -e run-plots/housing.gp ] && pass "no housing figure without housing motion" || fail "a housing figure without housing motion"
else
    fail "a run with housing motion wrote no file ($(head -c 200 shock.err))"
fi

# ---- a housing body (no base motion): the same figure, with the body's displacement relative to the
# base in columns 6, 7 (mm): at the last sample those of the run's CSV (x_housing_body, y_housing_body, m)
(timeout 300 "$tool" run -q --no-progress --set end_time=0.03 \
    --set 'housing={body={mass=50.0;centre=0.5;mounts=({position=0.0;stiffness=1.0e7;damping=1.0e3;},{position=1.0;stiffness=1.0e7;damping=1.0e3;});};}' \
    -o body "$src/cases/paper-a.cfg") >/dev/null 2>body.err
if [ -s body.h5 ] && "$tool" plot -q body.h5 2>err.txt; then
    expect_pngs body-plots housing
    want=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i ~ /^x_housing_body /) cx = i; if ($i ~ /^y_housing_body /) cy = i } }
                    NR > 1 && !/^#/ { x = $cx; y = $cy } END { printf "%.6e %.6e", 1e3 * x, 1e3 * y }' body.csv)
    got=$(awk '!/^#/ { x = $6; y = $7 } END { printf "%.6e %.6e", x, y }' body-plots/housing.dat)
    [ "$got" = "$want" ] && [ "$want" != "0.000000e+00 0.000000e+00" ] &&
        pass "housing figure of a body: its displacement $got mm at the end, as the run's CSV" ||
        fail "housing figure of a body: $got mm, the CSV $want mm"
else
    fail "plot of a run with a housing body: $(head -c 200 body.err) $(cat err.txt)"
fi

# ---- bad input: exit 2, one line on stderr ------------------------------------------------
echo "not hdf5" >text.h5
expect_error 2 "missing file" missing.h5
expect_error 2 "not an HDF5 file" text.h5
expect_error 2 "HDF5 but not a touchdown file" plot-fixture-foreign.h5
expect_error 2 "retainer out of range" --retainer 7 plot-fixture-constraint.h5
expect_error 2 "empty time window" --from 5 plot-fixture-constraint.h5
expect_error 2 "--from after --to" --from 0.3 --to 0.1 plot-fixture-constraint.h5
expect_error 2 "bad --format" --format jpg plot-fixture-constraint.h5
expect_error 2 "unknown option" --frobnicate plot-fixture-constraint.h5
expect_error 2 "no file" -d x
# ---- gnuplot missing or failing: exit 1, one line -----------------------------------------
TOUCHDOWN_GNUPLOT=/nonexistent/gnuplot expect_error 1 "gnuplot missing" -d nognuplot plot-fixture-constraint.h5
[ -s nognuplot/orbit-r0.gp ] && pass "scripts kept when gnuplot is missing" || fail "no scripts without gnuplot"
printf '#!/bin/sh\nexit 1\n' >failing-gnuplot # a gnuplot that fails silently
chmod +x failing-gnuplot
TOUCHDOWN_GNUPLOT="$work/failing-gnuplot" expect_error 1 "gnuplot failing" -d badgnuplot plot-fixture-constraint.h5
# gnuplot's own error line is the message
printf '#!/bin/sh\necho "         plot foo" >&2\necho "\\"$1\\" line 7: undefined variable: foo" >&2\nexit 1\n' >fake-gnuplot
chmod +x fake-gnuplot
TOUCHDOWN_GNUPLOT="$work/fake-gnuplot" expect_error 1 "gnuplot error message" -d fakegnuplot plot-fixture-constraint.h5
grep -q 'line 7: undefined variable: foo' err && pass "gnuplot's error line reported" || fail "gnuplot's message: $(cat err)"

if [ $fails -ne 0 ]; then
    echo "$fails check(s) failed"
    exit 1
fi
echo "all plot checks passed"
