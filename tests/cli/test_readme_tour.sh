#!/usr/bin/env bash
# README.md's "A five-minute tour", command by command, as the README writes it: the commands are
# read from README.md itself (the indented code lines of that section, trailing "# ..." comments
# dropped), so this test follows the README. They run in order in a scratch directory set up as
# the quick start leaves a checkout (cases/ and an out/ directory; build/touchdown is the tool
# given to the test), and scripts/quickstart.sh must run the tour's first command, as the README
# says. Every command must exit 0 and print something on stdout; besides:
#   run     the files of -o PREFIX are there (PREFIX.h5, .csv, .events.csv), the CSV complete;
#           with --json, stdout is one JSON object with "complete":true;
#   modal   PREFIX.h5 and PREFIX.csv are there;
#   plot    every "wrote FILE" line names a file that is there, at least one;
#   info    names the shaft's nodes and the first modes.
# `cmake --install build --prefix DIR` installs the build the tool comes from into a scratch
# prefix instead of DIR, and the installed tool must run. A command of another kind fails the
# test (teach it here).
# Cost: the full tour takes minutes (three 2 s runs and the full benchmark), and those runs are
# what cli_test_paper_cases and cli_test_bench check; so each `run` gets --set end_time=0.2 before
# its own arguments (past the unbalance step at 0.1 s and the first impacts: the command line, the
# start, the paths and the outputs are what this test is about) and `bench` gets --quick --cases A
# (cli_test_bench runs every case through --quick).
# TD_TOUR_FULL=1 runs every command exactly as written instead.
# Args: $1 = the touchdown binary, $2 = the source directory.
set -u
tool=$1
src=$2
build=$(cd "$(dirname "$tool")" && pwd)
work=$(mktemp -d "${PWD}/readme-tour.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# The tour's commands: the code lines (4-space indent) between its heading and the next heading.
tour_commands() {
    awk '/^## / { inside = ($0 ~ /^## A five-minute tour/); next }
         inside && /^    [^ ]/ { sub(/^    /, ""); sub(/[ \t]+#.*$/, ""); print }' "$src/README.md"
}
# grep_all FILE REGEX...: every REGEX matches a line of FILE
grep_all() {
    local f=$1 r
    shift
    for r in "$@"; do grep -qE "$r" "$f" || return 1; done
}
run_quiet() { "$@" >/dev/null 2>&1; }
# value_after ARGS... -- OPTION: the word after OPTION in ARGS (empty if absent)
value_after() {
    local want=${*: -1} prev=""
    while [ "$#" -gt 2 ]; do
        [ "$prev" = "$want" ] && { printf '%s\n' "$1"; return; }
        prev=$1
        shift
    done
}

# The scratch checkout, as the quick start leaves it.
scratch=$work/checkout
mkdir -p "$scratch/out"
ln -s "$src/cases" "$scratch/cases"

mapfile -t commands < <(tour_commands)
check "README.md's tour has its commands (${#commands[@]} found)" test "${#commands[@]}" -ge 5
# the README says the quick start ran the tour's first command: it must really be that command
check "scripts/quickstart.sh runs the tour's first command ('${commands[0]:-}')" \
    grep -qxF "${commands[0]:-none}" "$src/scripts/quickstart.sh"
full=${TD_TOUR_FULL:-0}
n=0
for line in "${commands[@]}"; do
    n=$((n + 1))
    out=$work/$n.out
    err=$work/$n.err
    read -r -a words <<<"$line"
    # map the command onto this build and this scratch checkout
    case "$line" in
    "build/touchdown "*)
        args=("${words[@]:1}")
        sub=${args[0]}
        if [ "$full" != 1 ]; then
            case $sub in
            run) args=(run --set end_time=0.2 "${args[@]:1}") ;;
            bench) args+=(--quick --cases A) ;;
            esac
        fi
        cmd=("$tool" "${args[@]}")
        ;;
    "cmake --install build --prefix "*)
        sub=install
        cmd=(cmake --install "$build" --prefix "$work/prefix")
        ;;
    *)
        fail "tour command $n: '$line': this test does not know how to run it (teach tests/cli/test_readme_tour.sh)"
        continue
        ;;
    esac
    (cd "$scratch" && "${cmd[@]}" >"$out" 2>"$err" </dev/null)
    rc=$?
    if [ "$rc" != 0 ]; then
        fail "tour command $n: '$line': exit $rc: $(head -c 300 "$err" | tr '\n' ' ')"
        continue
    fi
    check "tour command $n: '$line': exit 0, output on stdout ($(wc -l <"$out") lines)" test -s "$out"
    case $sub in
    run)
        prefix=$(value_after "${words[@]}" -- -o)
        if [ -n "$prefix" ]; then
            for f in "$prefix.h5" "$prefix.csv" "$prefix.events.csv"; do
                check "tour command $n: wrote $f" test -s "$scratch/$f"
            done
            check "tour command $n: $prefix.csv is complete" test "$(tail -n 1 "$scratch/$prefix.csv")" = "# complete"
        fi
        case " ${words[*]} " in
        *" --json "*)
            check "tour command $n: stdout is one JSON object with \"complete\":true" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if d.get("complete") is True else 1)' "$out" 2>/dev/null
            ;;
        esac
        ;;
    modal)
        prefix=$(value_after "${words[@]}" -- -o)
        if [ -n "$prefix" ]; then
            check "tour command $n: wrote $prefix.h5 and $prefix.csv" test -s "$scratch/$prefix.h5" -a -s "$scratch/$prefix.csv"
        fi
        ;;
    plot)
        wrote=$(sed -nE 's/^wrote (.*)$/\1/p' "$out")
        missing=$(for f in $wrote; do [ -s "$scratch/$f" ] || echo "$f"; done)
        check "tour command $n: $(echo "$wrote" | grep -c .) figures, every one there${missing:+ (missing: $missing)}" \
            test -n "$wrote" -a -z "$missing"
        ;;
    info)
        check "tour command $n: names the shaft's nodes and the first modes" \
            grep_all "$out" '^shaft .* nodes' '^first modes'
        ;;
    install)
        check "tour command $n: the installed tool runs" run_quiet "$work/prefix/bin/touchdown" --version
        ;;
    esac
done

finish
