# What the benchmarks that time the tool share (sourced by bench/digital.sh and bench/fmu.sh, not
# run): their options, and one run of the tool with its CPU time.

# bench_options HELP_LINES "$@": -n REPEATS (default 3), --json, -h (prints the script's header
# comment, lines HELP_LINES, e.g. '2,15p'), --end T (only for a script that set `end`, its default,
# before), and BUILD_DIR (default ./build of the source tree) into repeats, json, end and build;
# then tool (BUILD_DIR/touchdown, exit 2 when it is missing) and work, a temporary directory removed
# at exit.
bench_options() {
    local help=$1
    shift
    build=$here/build
    repeats=3
    json=0
    while [ $# -gt 0 ]; do
        case $1 in
        -n) repeats=$2; shift ;;
        --end) [ -n "${end+set}" ] || { echo "${0##*/}: no option --end" >&2; exit 2; }; end=$2; shift ;;
        --json) json=1 ;;
        -h | --help) sed -n "$help" "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) build=$1 ;;
        esac
        shift
    done
    tool=$build/touchdown
    [ -x "$tool" ] || { echo "${0##*/}: no tool at $tool (scripts/setup.sh $build builds it)" >&2; exit 2; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
}

# bench_run NAME ARGS...: `touchdown run` of ARGS (the case last) once with no output files, its
# JSON summary into $work/NAME.json and its CPU seconds (user + system of the tool's process: this
# shell's children's times before and after) appended to $work/NAME.cpu, a line per run; a failed
# run ends the benchmark with the tool's message.
bench_run() {
    local name=$1 t0 t1
    shift
    t0=$(awk '{ print $14 + $15 + $16 + $17 }' /proc/$$/stat)
    "$tool" run -q --json --hdf5 '' --csv '' "$@" >"$work/$name.json" 2>"$work/$name.err" || {
        echo "${0##*/}: touchdown run $* failed:" >&2
        cat "$work/$name.err" >&2
        exit 1
    }
    t1=$(awk '{ print $14 + $15 + $16 + $17 }' /proc/$$/stat)
    echo "$t0 $t1" | awk -v hz="$(getconf CLK_TCK)" '{ printf "%.2f\n", ($2 - $1) / hz }' >>"$work/$name.cpu"
}
