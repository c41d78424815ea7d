#!/usr/bin/env bash
# Plug-in controllers through the case file and the tool: examples/plugin-pd builds with its own
# Makefile against the header alone (a copy, outside the source tree); `touchdown info` prints the
# plug-in; the library's path is relative to the case file's directory; the plug-in PD and PID give
# the same bits as the built-in sampled law with the same numbers (the same case with the law
# written as an `ss` block in z: the samples, the events and the summary's answers compared byte for
# byte); a bad plug-in (no file, no entry symbol, another ABI version, a NaN command mid-run, a
# crash in its init, an init that refuses) and bad plug-in keys each give one line naming the file,
# line and key, exit 2, and never a result that looks complete.
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
# one_line DIR KEY TEXT: exit 2, exactly one line on stderr, naming the case file's line and KEY, with TEXT
one_line() {
    test "$rc" = 2 -a "$(wc -l <"$1/.err")" = 1 && grep -qE "^touchdown: [^ ]*rig-pd.cfg:[0-9]+: $2: .*$3" "$1/.err"
}

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
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not any(w in k for w in ("wall", "realtime", "path"))}
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
    ! cmp -s <(grep -v '^#' "$work/pd-plug/r.csv") <(grep -v '^#' "$work/pid-plug/r.csv")

# ---- bad keys: one line naming the key, exit 2 ---------------------------------------------------
t "$work/nofile" info --set 'controllers[0].plugin.library="nothere.so"' "$ex/rig-pd.cfg"
check "a library that does not exist: one line naming the key, exit 2" one_line "$work/nofile" \
    'controllers\[0\]\.plugin\.library' 'nothere.so'
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
t "$work/unknown" run --set 'controllers[0].plugin.parameters.kx=1.0' "$ex/rig-pd.cfg"
check "an init that refuses (pd.c: an unknown parameter): one line with its reason, exit 2" one_line "$work/unknown" \
    'controllers\[0\]\.plugin\.library' "refused to start: unknown parameter 'kx'"
check "  and no output file" test ! -e "$work/unknown/rig-pd.h5" -a ! -e "$work/unknown/rig-pd.csv"

# ---- the bad plug-ins of tests/plugins -----------------------------------------------------------
bad() { # NAME: rig-pd.cfg with the test plug-in NAME
    cp "$plugins/$1.so" "$ex/" 2>/dev/null || fail "no test plug-in $plugins/$1.so"
}
for name in missing_symbol wrong_abi nan_output crash_init init_fails; do bad "$name"; done
t "$work/sym" run --set 'controllers[0].plugin.library="missing_symbol.so"' "$ex/rig-pd.cfg"
check "a library without the entry symbol: one line naming it, exit 2" one_line "$work/sym" \
    'controllers\[0\]\.plugin\.library' 'td_plugin_controller_entry'
t "$work/abi" run --set 'controllers[0].plugin.library="wrong_abi.so"' "$ex/rig-pd.cfg"
check "a plug-in of another ABI version: one line naming it, exit 2" one_line "$work/abi" \
    'controllers\[0\]\.plugin\.library' 'ABI'
t "$work/crash" run --set 'controllers[0].plugin.library="crash_init.so"' "$ex/rig-pd.cfg"
check "a crash (SIGSEGV) in the plug-in's init: one line naming the key and the signal, exit 2" one_line "$work/crash" \
    'controllers\[0\]\.plugin\.library' 'crashed in its init \(SIGSEGV'
check "  and no output file" test ! -e "$work/crash/rig-pd.h5" -a ! -e "$work/crash/rig-pd.csv"
t "$work/crashinfo" info --set 'controllers[0].plugin.library="crash_init.so"' "$ex/rig-pd.cfg"
check "  info too: the same line, exit 2" one_line "$work/crashinfo" 'controllers\[0\]\.plugin\.library' 'SIGSEGV'
t "$work/refuse" run --set 'controllers[0].plugin.library="init_fails.so"' "$ex/rig-pd.cfg"
check "an init that fails with a message: one line with it, exit 2" one_line "$work/refuse" \
    'controllers\[0\]\.plugin\.library' 'refused to start: '
t "$work/nan" run --json --set 'controllers[0].plugin.library="nan_output.so"' --set end_time=0.05 "$ex/rig-pd.cfg"
check "a NaN command mid-run: exit 2, one error line naming the controller" \
    test "$rc" = 2 -a "$(grep -c . "$work/nan/.err")" = 1 -a -n "$(grep -F '"pd"' "$work/nan/.err")"
check "  the JSON says failed" test "$(jf "$work/nan/.out" status)" != '"success"'
check "  the CSV is marked incomplete (never a complete-looking file)" \
    grep -q '^# incomplete: ' "$work/nan/rig-pd.csv"
h5=$(command -v h5dump || true)
if [ -n "$h5" ]; then
    check "  the HDF5 file says complete = 0" grep -q '(0): 0' <("$h5" -a /complete "$work/nan/rig-pd.h5" 2>/dev/null)
fi

finish
