#!/usr/bin/env bash
# touchdown fmu: the archive it writes (FMI 2.0's layout, the same bits for the same input, put in
# place whole), and its bad input: each refusal is one line on stderr and exit 2, writes nothing and
# leaves every input as it was; a tool without its FMU binary fails with exit 1. fmpy's view of the
# FMU (validation, simulation) is tests/fmu/.
#   test_fmu.sh TOOL SOURCE_DIR [PLUGIN_DIR]
set -u
tool=$1
src=$2
plugins=${3:-}
. "$src/tests/cli/common.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
case_a=$src/cases/paper-a-digital.cfg

# refused CHECK ARGS...: exit 2, one line on stderr, no file written in $work/r
refused() {
    local what=$1
    shift
    rm -rf "$work/r"
    t "$work/r" fmu "$@"
    local lines
    lines=$(wc -l <"$work/r/.err")
    if [ "$rc" = 2 ] && [ "$lines" = 1 ] && [ -z "$(ls "$work/r")" ]; then
        pass "$what: exit 2, one line: $(cat "$work/r/.err")"
    else
        fail "$what: exit $rc, $lines lines, files: $(ls "$work/r"): $(cat "$work/r/.err")"
    fi
}

# verdict DESCRIPTION: pass or fail by the status of the command just before it
verdict() {
    local s=$?
    if [ "$s" = 0 ]; then pass "$1"; else fail "$1"; fi
}

# entries FMU: its entries, one a line, as Python's zipfile reads them
entries() { /usr/bin/python3 -c 'import sys, zipfile; print("\n".join(zipfile.ZipFile(sys.argv[1]).namelist()))' "$1"; }

t "$work/ok" fmu --help
[ "$rc" = 0 ] && grep -q "touchdown fmu \[OPTIONS\] CASE -o NAME.fmu" "$work/ok/.out"
verdict "--help: exit 0 and the usage"
t "$work/ok" fmu "$case_a" -o Rig.fmu
[ "$rc" = 0 ] && [ -f "$work/ok/Rig.fmu" ]
verdict "writes Rig.fmu (exit 0)"
want=$(printf '%s\n' modelDescription.xml resources/case.cfg resources/touchdown-fmu.cfg binaries/linux64/Rig.so)
got=$(entries "$work/ok/Rig.fmu" 2>&1)
check "its entries: modelDescription.xml, resources/, binaries/linux64/Rig.so" [ "$got" = "$want" ]
cp "$work/ok/Rig.fmu" "$work/first.fmu"
t "$work/ok" fmu -q "$case_a" -o Rig.fmu
[ "$rc" = 0 ] && [ ! -s "$work/ok/.out" ] && cmp -s "$work/first.fmu" "$work/ok/Rig.fmu"
verdict "packed again over the first: exit 0, nothing printed (-q), the same bits"
check "no temporary file left" [ -z "$(find "$work/ok" -name '*.partial')" ]
t "$work/ok" fmu -q "$case_a" -o Rig.fmu --set speed=120
[ "$rc" = 0 ] && ! cmp -s "$work/first.fmu" "$work/ok/Rig.fmu"
verdict "--set changes the FMU (its case settings)"

refused "no -o" "$case_a"
refused "no case" -o A.fmu
refused "an orbit start with inputs" "$case_a" --set 'start="orbit"' -o A.fmu
refused "two cases" "$case_a" "$case_a" -o A.fmu
refused "-o not ending in .fmu" "$case_a" -o A.zip
refused "-o whose name is no C identifier (a dash)" "$case_a" -o my-rig.fmu
refused "-o whose name starts with a digit" "$case_a" -o 2rig.fmu
refused "-o naming only .fmu" "$case_a" -o .fmu
refused "-o in a directory that does not exist" "$case_a" -o nowhere/A.fmu
refused "--inputs that is none of current, force, none" --inputs voltage "$case_a" -o A.fmu
refused "--set of a key that does not exist" --set no_such_key=1 "$case_a" -o A.fmu
refused "--set with a bad value" --set speed=fast "$case_a" -o A.fmu
refused "a case file that does not exist" "$work/none.cfg" -o A.fmu
printf 'speed = 100.0;\nretainers = ( { node = 1; clearance = ; } );\n' >"$work/broken.cfg"
refused "a case with a syntax error" "$work/broken.cfg" -o A.fmu
grep -q "broken.cfg:2" "$work/r/.err" && pass "  ... its line names the file and line" || fail "  ... no file:line: $(cat "$work/r/.err")"

# inputs are never overwritten: the case file itself, an @include file, and a file that is not an FMU
mkdir -p "$work/in"
cp "$src/cases/jeffcott.cfg" "$work/in/Case.fmu"
cp "$work/in/Case.fmu" "$work/case.keep"
rm -rf "$work/r"
t "$work/in" fmu Case.fmu -o Case.fmu
[ "$rc" = 2 ] && [ "$(wc -l <"$work/in/.err")" = 1 ] && cmp -s "$work/in/Case.fmu" "$work/case.keep"
verdict "-o the case file itself: exit 2, one line, the case as it was"
cp "$src/cases/jeffcott.cfg" "$work/in/Inc.fmu"
printf '@include "Inc.fmu"\n' >"$work/in/top.cfg"
t "$work/in" fmu top.cfg -o Inc.fmu
[ "$rc" = 2 ] && grep -q "@include file" "$work/in/.err" && cmp -s "$work/in/Inc.fmu" "$work/case.keep"
verdict "-o an @include file: exit 2, one line, the file as it was"
printf 'notes\n' >"$work/in/Notes.fmu"
t "$work/in" fmu "$case_a" -o Notes.fmu
[ "$rc" = 2 ] && [ "$(cat "$work/in/Notes.fmu")" = notes ]
verdict "-o an existing file that is no FMU: exit 2, the file as it was"
mkdir -p "$work/in/Dir.fmu"
t "$work/in" fmu "$case_a" -o Dir.fmu
[ "$rc" = 2 ] && [ -d "$work/in/Dir.fmu" ]
verdict "-o a directory: exit 2"
check "no temporary file left by the refusals" [ -z "$(find "$work/in" -name '*.partial')" ]

# a case whose controller is a plug-in (the example's, with the test PD of PLUGIN_DIR beside it): the
# FMU carries the library in resources/plugins/ and points its controller at it; a plug-in that
# crashes in its init is refused at packing (the tool's probe), one line, exit 2, no file
mkdir -p "$work/plug"
sed 's/ ki = 0.0;//' "$src/examples/plugin-pd/rig-pd.cfg" >"$work/plug/rig-pd.cfg"
cp "$plugins/pd.so" "$work/plug/pd.so" || fail "no test plug-in $plugins/pd.so"
t "$work/plug" fmu --inputs none rig-pd.cfg -o Plug.fmu
[ "$rc" = 0 ] && entries "$work/plug/Plug.fmu" | grep -qx resources/plugins/pd.so &&
    /usr/bin/python3 -c 'import sys, zipfile; sys.stdout.buffer.write(zipfile.ZipFile(sys.argv[1]).read("resources/plugins/pd.so"))' \
        "$work/plug/Plug.fmu" | cmp -s - "$plugins/pd.so" &&
    /usr/bin/python3 -c 'import sys, zipfile; print(zipfile.ZipFile(sys.argv[1]).read("resources/touchdown-fmu.cfg").decode())' \
        "$work/plug/Plug.fmu" | grep -qF '"controllers[0].plugin.library=\"plugins/pd.so\""'
verdict "a plug-in case: its library's bytes in resources/plugins/pd.so, the controller pointed at it"
cp "$plugins/crash.so" "$work/plug/pd.so"
rm -rf "$work/r"
mkdir -p "$work/r"
cp "$work/plug/rig-pd.cfg" "$work/plug/pd.so" "$work/r/"
t "$work/r" fmu --inputs none rig-pd.cfg -o Crash.fmu
[ "$rc" = 2 ] && [ "$(wc -l <"$work/r/.err")" = 1 ] && grep -q "controllers\[0\].plugin.library: .*crashed in its init" "$work/r/.err" &&
    [ ! -e "$work/r/Crash.fmu" ]
verdict "a plug-in crashing in its init: refused at packing, exit 2, one line naming the key: $(cat "$work/r/.err")"

# a tool copied away from its FMU binary: exit 1 (it cannot be written), one line, no file
mkdir -p "$work/alone"
cp "$tool" "$work/alone/touchdown"
(cd "$work/alone" && ./touchdown fmu "$case_a" -o A.fmu >.out 2>.err)
rc=$?
[ "$rc" = 1 ] && [ "$(wc -l <"$work/alone/.err")" = 1 ] && grep -q touchdown-fmu.so "$work/alone/.err" &&
    [ ! -e "$work/alone/A.fmu" ]
verdict "without touchdown-fmu.so beside it nor installed: exit 1, one line naming it, no file"
finish
