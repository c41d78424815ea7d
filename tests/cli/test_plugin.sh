#!/usr/bin/env bash
# Plug-in controllers through the case file and the tool: examples/plugin-pd builds with its own
# Makefile against the header alone (a copy, outside the source tree); `touchdown info` prints the
# plug-in; the library's path is relative to the case file's directory; the plug-in PD and PID give
# the same bits as the built-in sampled law with the same numbers (the same case with the law
# written as an `ss` block in z: the samples, the events and the summary's answers compared byte for
# byte); a bad plug-in (no file, no entry symbol, another ABI version, a NaN command mid-run, a
# crash in its init, an init that refuses, an init that ends the process with exit(0)) and bad
# plug-in keys each give one line naming the file, line and key, exit 2, and never a result that
# looks complete.
# Args: $1 = the touchdown binary, $2 = the source directory, $3 = the directory of the test
# plug-ins (tests/plugins, built by CMake). Runs in the build's tests directory.
set -u
tool=$1
src=$2
plugins=${3:-}
work=$(mktemp -d "${PWD}/plugin.XXXXXX")
trap 'rm -rf "$work"' EXIT

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

has() { grep -qF -- "$2" "$1"; }
# one_line DIR CASE KEY TEXT: exit 2, exactly one line on stderr, naming CASE's line and KEY, with TEXT
one_line() {
    test "$rc" = 2 -a "$(wc -l <"$1/.err")" = 1 && grep -qE "^touchdown: [^ ]*$2:[0-9]+: $3: .*$4" "$1/.err"
}
# with_library NAME LIBRARY: the example's case as NAME.cfg with its plug-in's library LIBRARY
with_library() {
    sed "s|library = \"pd.so\"|library = \"$2\"|" "$ex/rig-pd.cfg" >"$ex/$1.cfg"
}
differs() { ! cmp -s "$1" "$2"; }
lib_key='controllers\[0\]\.plugin\.library'


# ---- the example, built as a user builds it: make, with only the header ----------------------
ex=$work/ex
mkdir -p "$ex"
cp "$src/examples/plugin-pd/pd.c" "$src/examples/plugin-pd/Makefile" "$src/examples/plugin-pd/rig-pd.cfg" "$ex/"
mkdir -p "$work/prefix/include/touchdown"
cp "$src/include/touchdown/plugin.h" "$work/prefix/include/touchdown/" # the installed header, alone
if make -s -C "$ex" PREFIX="$work/prefix" CFLAGS="-O2 -Werror" >"$work/make.log" 2>&1 && [ -f "$ex/pd.so" ]; then
    pass "examples/plugin-pd builds with its Makefile against plugin.h alone"
else
    fail "examples/plugin-pd did not build: $(head -c 400 "$work/make.log")"
fi

# ---- info: the plug-in controller; its path under the case file's directory -------------------
t "$work/info" info "$ex/rig-pd.cfg"
check "info rig-pd: exit 0" test "$rc" = 0
check "info names the plug-in, its library (under the case's directory), ABI, output, rate, delay" \
    has "$work/info/.out" "controller 0  \"pd\": ambs 0, 1 in bearing coordinates, plug-in $ex/pd.so (ABI 1, current commands), sampled at 10000 Hz, delay 0 samples"
check "info lists its parameters as written" has "$work/info/.out" "parameters: kp = 10000, kd = 40, ki = 0"
check "info says which controller drives each AMB" test "$(grep -c '^amb .*controller 0, tau' "$work/info/.out")" = 2
check "info: the modes are not computed for a plug-in, and says why" \
    grep -qE '^modes +not computed: .*pd' "$work/info/.out"
mkdir -p "$work/elsewhere"
(cd "$work" && "$tool" info ex/rig-pd.cfg >elsewhere/.out 2>elsewhere/.err)
check "the library is found from another directory (ex/pd.so: relative to the case file)" \
    has "$work/elsewhere/.out" "plug-in ex/pd.so"

# ---- the must-show: the plug-in PD and PID against the built-in sampled law, bit for bit -------
# The built-in law with the plug-in's numbers (pd.c): per axis the states x = [e_{k-1}, s_k],
# i = q1 e_{k-1} + s_k + q0 e_k, x+ = [e_k, s_k + (ki / fs) e_k]; q0 = kp + kd fs = 4.1e5 A/m,
# q1 = -kd fs = -4.0e5 A/m (kp 1.0e4, kd 40, fs 1.0e4: exact in binary), ki / fs = 5 for ki = 5.0e4.
builtin() { # ss block of the PD (no integral) or of the PID
    local law
    if [ "$1" = pd ]; then
        law='ss = { A = ([0.0]); B = ([1.0]); C = ([-4.0e5]); D = ([4.1e5]); domain = "z"; }'
    else
        law='ss = { A = ([0.0, 0.0], [0.0, 1.0]); B = ([1.0], [5.0]); C = ([-4.0e5, 1.0]); D = ([4.1e5]); domain = "z"; }'
    fi
    echo "controllers = ( { name = \"pd\"; ambs = [0, 1]; law = ( { $law; } ); sample_rate = 10000.0; } )"
}
# the summary as JSON without what a wall clock or the outputs' paths say: every answer and count
answers() {
    python3 - "$1" <<'EOF'
import json, sys
# what a wall clock or the outputs' paths say, and the linear analysis, which cannot see a plug-in
DROP = ("wall", "realtime", "path", "stability", "max_real_part")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not any(w in k for w in DROP)}
    return [strip(v) for v in o] if isinstance(o, list) else o
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))
EOF
}
same_run() { # NAME: the plug-in run NAME-plug and the built-in NAME-ref agree in every sample bit
    local a=$work/$1-plug b=$work/$1-ref
    cmp -s <(grep -v '^#' "$a/r.csv") <(grep -v '^#' "$b/r.csv") &&
        cmp -s <(grep -v '^#' "$a/r.events.csv") <(grep -v '^#' "$b/r.events.csv") &&
        test "$(answers "$a/.out")" = "$(answers "$b/.out")" && test "$(jf "$a/.out" status)" = '"success"'
}
window=(--set end_time=0.15 --json -q --hdf5 '' --csv r.csv)
t "$work/pd-plug" run "${window[@]}" "$ex/rig-pd.cfg"
t "$work/pd-ref" run "${window[@]}" --set "$(builtin pd)" "$ex/rig-pd.cfg"
check "the plug-in PD's run and the built-in one succeed" test "$(jf "$work/pd-plug/.out" status)$(jf "$work/pd-ref/.out" status)" = '"success""success"'
check "the PD touches down in the window (the comparison covers contact)" \
    test "$(jf "$work/pd-plug/.out" contacts)" -gt 0 2>/dev/null
check "the plug-in PD equals the built-in sampled PD bit for bit (samples, events, answers)" same_run pd
pid=(--set 'controllers[0].plugin.parameters.ki=5.0e4')
t "$work/pid-plug" run "${window[@]}" "${pid[@]}" "$ex/rig-pd.cfg"
t "$work/pid-ref" run "${window[@]}" --set "$(builtin pid)" "$ex/rig-pd.cfg"
check "the plug-in PID equals the built-in sampled PID bit for bit (samples, events, answers)" same_run pid
check "  and the integral acts: the PID's run differs from the PD's" \
    differs <(grep -v '^#' "$work/pd-plug/r.csv") <(grep -v '^#' "$work/pid-plug/r.csv")
t "$work/delay-plug" run "${window[@]}" --set 'controllers[0].delay=1' "$ex/rig-pd.cfg"
t "$work/delay-ref" run "${window[@]}" --set "$(builtin pd)" --set 'controllers[0].delay=1' "$ex/rig-pd.cfg"
# With a delay the dynamics are the same (the plug-in's queue, the built-in law's delay states) but
# not the solver's tolerance scale: a built-in law without direct gain is scaled by its gain at the
# magnet's frequency, a plug-in by its measured direct gain (lib/sim/setup.c law_gain), so the steps
# differ and the answers agree to the tolerance: the first contact to 1e-9 s, the peak normal force
# to 1e-4 relative (measured: equal, and 2.4e-6), the same number of contacts.
close_run() {
    python3 - "$work/$1-plug/.out" "$work/$1-ref/.out" <<'EOF'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
dt = abs(a["first_contact_time"] - b["first_contact_time"])
dp = abs(a["peak_normal_force"] - b["peak_normal_force"]) / b["peak_normal_force"]
print("  delay 1: first contact %.3g s apart, peak normal force %.3g relative, contacts %d and %d"
      % (dt, dp, a["contacts"], b["contacts"]))
sys.exit(0 if a["status"] == b["status"] == "success" and dt <= 1e-9 and dp <= 1e-4 and a["contacts"] == b["contacts"] else 1)
EOF
}
check "with one sample of delay: the same to the solver's tolerance" close_run delay
check "the plug-in run claims no stability it cannot know (unchecked: no linear law for the analysis)" \
    test "$(jf "$work/pd-plug/.out" stability)" = '"unchecked"' -a "$(jf "$work/pd-plug/.out" max_real_part)" = null
t "$work/text" run --set end_time=0.001 --hdf5 '' "$ex/rig-pd.cfg"
check "  and its summary says why: the plug-in (not a count of states)" \
    grep -qE '^contact-free system +stability not checked: modal: controller 0 \("pd"\) is a plug-in' "$work/text/.out"
t "$work/modal" modal "$ex/rig-pd.cfg"
check "touchdown modal refuses a plug-in case naming the controller, exit 2" \
    test "$rc" = 2 -a "$(wc -l <"$work/modal/.err")" = 1 -a -n "$(grep -F 'controller 0 ("pd") is a plug-in' "$work/modal/.err")"

# ---- bad keys: one line naming the key, exit 2 ---------------------------------------------------
with_library nofile nothere.so
t "$work/nofile" info "$ex/nofile.cfg"
check "a library that does not exist: one line naming the file, line and key, exit 2" \
    one_line "$work/nofile" nofile.cfg "$lib_key" 'cannot load .*nothere.so'
t "$work/law" info --set 'controllers[0].law=( { gain = 1.0; } )' "$ex/rig-pd.cfg"
check "a plug-in and a law: refused" test "$rc" = 2 -a -n "$(grep -F 'controllers[0].law: ' "$work/law/.err")"
t "$work/rigid" info --set 'controllers[0].coordinates="rigid"' "$ex/rig-pd.cfg"
check "a plug-in in rigid coordinates: refused" test "$rc" = 2 -a -n "$(grep -F 'controllers[0].coordinates: ' "$work/rigid/.err")"
sed 's/^ *sample_rate = 10000.0;.*$//' "$ex/rig-pd.cfg" >"$ex/norate.cfg"
t "$work/norate" info "$ex/norate.cfg"
check "a plug-in without sample_rate: refused naming it" test "$rc" = 2 -a -n "$(grep -F 'sample_rate' "$work/norate/.err")"
t "$work/par" info --set 'controllers[0].plugin.parameters.kp="big"' "$ex/rig-pd.cfg"
check "a parameter that is not a number: refused naming it" \
    test "$rc" = 2 -a -n "$(grep -F 'controllers[0].plugin.parameters.kp: ' "$work/par/.err")"
sed 's/ki = 0.0;/ki = 0.0; kx = 1.0;/' "$ex/rig-pd.cfg" >"$ex/unknown.cfg"
t "$work/unknown" run "$ex/unknown.cfg"
check "an init that refuses (pd.c: an unknown parameter): one line with its reason, exit 2" \
    one_line "$work/unknown" unknown.cfg "$lib_key" "refused to start: unknown parameter 'kx'"
check "  and no output file" test ! -e "$work/unknown/unknown.h5" -a ! -e "$work/unknown/unknown.csv"

# ---- the bad plug-ins of tests/plugins, each beside a copy of the case ---------------------------
for name in no_entry wrong_abi nan crash refuse exits; do
    cp "$plugins/$name.so" "$ex/" || fail "no test plug-in $plugins/$name.so"
    with_library "$name" "$name.so"
done
t "$work/sym" run "$ex/no_entry.cfg"
check "a library without the entry symbol: one line naming the file, line and key, exit 2" \
    one_line "$work/sym" no_entry.cfg "$lib_key" 'td_plugin_controller_entry'
t "$work/abi" run "$ex/wrong_abi.cfg"
check "a plug-in of another ABI version: one line naming both versions, exit 2" \
    one_line "$work/abi" wrong_abi.cfg "$lib_key" 'ABI version [0-9]+; this touchdown runs version 1'
t "$work/crash" run "$ex/crash.cfg"
check "a crash (SIGSEGV) in the plug-in's init: one line naming the file, line, key and signal, exit 2" \
    one_line "$work/crash" crash.cfg "$lib_key" 'crashed in its init \(SIGSEGV'
check "  and no output file, no core file" test -z "$(ls "$work/crash")"
t "$work/crashinfo" info "$ex/crash.cfg"
check "  info too: the same line, exit 2" one_line "$work/crashinfo" crash.cfg "$lib_key" 'SIGSEGV'
t "$work/exits" run "$ex/exits.cfg"
check "a plug-in that ends the process (exit(0)) in its init: one line naming the file, line, key and call, exit 2" \
    one_line "$work/exits" exits.cfg "$lib_key" 'ended the process in its init \(exit status 0\)'
check "  and no output file" test -z "$(ls "$work/exits")"
t "$work/refuse" run "$ex/refuse.cfg"
check "an init that fails with a message: one line with it, exit 2" \
    one_line "$work/refuse" refuse.cfg "$lib_key" 'refused to start: .'
t "$work/nan" run --json "$ex/nan.cfg"
check "a NaN command mid-run: exit 2, one error line naming the controller and the sample" \
    one_line "$work/nan" nan.cfg "$lib_key" '"pd".* sample [0-9]+.*nan'
check "  the time it failed at is said once (the sample is at an output time, not on the way to one)" \
    grep -qF 'simulation failed at t = 0.0003000000 s: controller 0: plug-in "pd" failed at sample 3' "$work/nan/.err"
check "  the JSON says it failed, with no answers" \
    test "$(jf "$work/nan/.out" status)" != '"success"' -a "$(jf "$work/nan/.out" peak_normal_force)" = null
check "  the CSV is marked incomplete (never a complete-looking file)" grep -q '^# incomplete: ' "$work/nan/nan.csv"

# ---- a sweep: over a plug-in's parameter, and a point whose plug-in crashes in its worker ---------
t "$work/sweep" sweep --vary 'controllers[0].plugin.parameters.kp=1.0e4,1.2e4' --vary \
    'controllers[0].plugin.library="pd.so","crash.so"' --set end_time=0.12 -o sw "$ex/rig-pd.cfg"
check "a sweep over a plug-in's parameter and library: the tool survives a crashing point's worker" \
    test -f "$work/sweep/sw.csv" -a "$(grep -c ',success,' "$work/sweep/sw.csv")" = 2
# (the worker dies of SIGSEGV; under a sanitiser, whose handler catches it, it ends with status 1)
check "  the crashing points fail, their worker's death said" test "$(grep -c 'worker died: ' "$work/sweep/.err")" = 2
check "  the parameter reaches the plug-in: kp 1.0e4 and 1.2e4 give different answers" \
    python3 -c 'import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "success"]
sys.exit(len({r["peak_housing_force [N]"] for r in rows}) != 2)' "$work/sweep/sw.csv"
# h5dump comes with hdf5-tools (scripts/setup.sh): without it the check fails, never skips
if h5=$(command -v h5dump); then
    check "  the HDF5 file says complete = 0" grep -q '(0): 0' <("$h5" -a /complete "$work/nan/nan.h5" 2>/dev/null)
else
    fail "  the HDF5 file says complete = 0: no h5dump to read it (hdf5-tools, scripts/setup.sh)"
fi

finish
