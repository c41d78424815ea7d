#!/usr/bin/env bash
# Bad input through the tool: every broken case file under tests/data/bad/, plus a directory, a
# missing path, a path through a file, a FIFO, an unreadable file, random binary junk, an empty
# file, bad --set overrides and bad usage.
#
# For each bad case file, `touchdown run FILE` and `touchdown info FILE` must
#   - exit with status 2,
#   - print exactly one line on stderr (nothing on stdout) naming the file, and, where the file
#     has them, the line and the key: the expected FILE:LINE: KEY of every file is read from the
#     table bad_files[] of tests/test_case.c (one table for the library and the tool),
#   - create no file: each command runs in an empty scratch directory that must stay empty, and
#     the source's tests/data/bad/ must not change.
# Bad usage (unknown option, no case, two cases, unknown command) exits 2 and writes no file.
# Args: $1 = the touchdown binary, $2 = the source directory. Runs in the build's tests directory.
set -u
tool=$1
src=$2
work=$(mktemp -d "${PWD}/bad-input.XXXXXX")
trap 'chmod -R u+rwx "$work" 2>/dev/null; rm -rf "$work"' EXIT
scratch=$work/cwd
mkdir -p "$scratch"

. "$(dirname "${BASH_SOURCE[0]}")/common.sh" # fail, pass, check, t, jf, finish

# Run the tool in the empty scratch directory: sets rc, err (stderr text), out (stdout text).
# ${runner[@]} (normally empty) is put in front of the tool, e.g. to drop privileges.
runner=()
run_tool() {
    (cd "$scratch" && "${runner[@]}" "$tool" "$@" >"$work/out" 2>"$work/err" </dev/null)
    rc=$?
    err=$(cat "$work/err")
    out=$(cat "$work/out")
}

# The scratch directory must be empty (no output file, no .partial left behind).
scratch_empty() {
    local left
    left=$(ls -A "$scratch")
    if [ -n "$left" ]; then
        rm -rf "${scratch:?}"/* "${scratch:?}"/.[!.]* 2>/dev/null
        echo "$left" | tr '\n' ' '
        return 1
    fi
    return 0
}

# expect_bad WHAT NEEDLE... -- ARGS: exit 2, one stderr line containing every NEEDLE, empty
# stdout, no file created. One check: a FAIL line lists every way the command fell short.
expect_bad() {
    local what=$1 needles=() n lines left problems=() joined
    shift
    while [ "$1" != "--" ]; do needles+=("$1"); shift; done
    shift
    run_tool "$@"
    lines=$(wc -l <"$work/err")
    if [ "$rc" != 2 ]; then
        problems+=("exit $rc, expected 2 (stderr: $(head -c 300 "$work/err"))")
    fi
    if [ "$lines" != 1 ]; then
        problems+=("$lines lines on stderr, expected 1: $(head -n 3 "$work/err")")
    fi
    if [ -n "$out" ]; then
        problems+=("stdout not empty: $(head -c 200 "$work/out")")
    fi
    for n in "${needles[@]}"; do
        case "$err" in
        *"$n"*) ;;
        *) problems+=("stderr lacks '$n': $err") ;;
        esac
    done
    if ! left=$(scratch_empty); then
        problems+=("created files: $left")
    fi
    if [ ${#problems[@]} = 0 ]; then
        pass "$what -> 2: $err"
    else
        joined=$(printf '%s; ' "${problems[@]}")
        fail "$what: ${joined%; }"
    fi
}

# expect_usage WHAT ARGS: exit 2 and no file created (the usage text may take several lines).
expect_usage() {
    local what=$1 left
    shift
    run_tool "$@"
    if [ "$rc" != 2 ]; then
        fail "$what: exit $rc, expected 2 ($(head -n 2 "$work/err"))"
    elif [ ! -s "$work/err" ]; then
        fail "$what: exit 2 but nothing on stderr"
    elif ! left=$(scratch_empty); then
        fail "$what: created files: $left"
    else
        pass "$what -> 2: $(head -n 1 "$work/err")"
    fi
}

bad_dir=$src/tests/data/bad
before=$(ls -la --time-style=+%s "$bad_dir" | md5sum)

# ---- the table of tests/test_case.c: "file", line, "key"|NULL, "shown"|NULL ------------------
table=$(sed -n '/^static const bad_file bad_files\[\] = {/,/^};/p' "$src/tests/test_case.c" |
    sed -nE 's/^[[:space:]]*\{"([^"]+)", ([0-9]+), (NULL|"[^"]*"), (NULL|"[^"]*")\},.*/\1 \2 \3 \4/p' |
    tr -d '"')
n_table=$(printf '%s\n' "$table" | grep -c .)
check "read $n_table entries (at least 40) from the bad_files table of tests/test_case.c" test "$n_table" -ge 40

# The commands each file goes through. `run` and `info` read a case by the same reader and refuse
# it by the same rule; under the sanitizers (TD_TEST_SANITIZED=1) `run` takes every file and
# `info` every other one, so every refusal path is still taken by the sanitized tool, and `info`'s
# own path (its set-up and its error line) on half of them; `info` on every file, message checked,
# is the plain pass's.
cmds_of() { # N: the commands for the N-th file
    if sanitized && [ $(($1 % 2)) = 0 ]; then echo run; else echo run info; fi
}
n_files=0
for path in "$bad_dir"/*.cfg; do
    file=$(basename "$path")
    n_files=$((n_files + 1))
    entry=$(printf '%s\n' "$table" | awk -v f="$file" '$1 == f { print; exit }')
    if [ -z "$entry" ]; then
        fail "$file is not in the bad_files table of tests/test_case.c (checking exit code only)"
        for cmd in $(cmds_of $n_files); do expect_bad "$cmd $file" "$file" -- "$cmd" "$path"; done
        continue
    fi
    read -r _ line key shown <<<"$entry"
    [ "$shown" = NULL ] && shown=$file
    # the message names the file (as given, or the included file) and its line, then the key
    if [ "$shown" = "$file" ]; then name=$path; else name=$shown; fi
    if [ "$key" = NULL ]; then where="$shown:$line: "; else where="$shown:$line: $key: "; fi
    for cmd in $(cmds_of $n_files); do
        expect_bad "$cmd $file" "touchdown" "$name" "$where" -- "$cmd" "$path"
    done
done
check "$n_files files (at least 40) under tests/data/bad/, as many as the table of tests/test_case.c ($n_table)" \
    test "$n_files" -ge 40 -a "$n_files" = "$n_table"

# ---- exact messages: the whole stderr line of these files ("|" separates the file from what
# follows its path); each is in the table above as well. The commands: cmds_of's, as above, by the
# file's place in this list --------------------------------------------------------------------
n_exact=0
while IFS='|' read -r file rest; do
    [ -z "$file" ] && continue
    n_exact=$((n_exact + 1))
    for cmd in $(cmds_of $n_exact); do
        rest=${rest//BAD/$bad_dir} # BAD: the directory, where a message names a second place in the file
        run_tool "$cmd" "$bad_dir/$file"
        if created=$(scratch_empty); then created=""; else created="; created files: $created"; fi
        if [ "$rc" = 2 ] && [ "$err" = "touchdown: $bad_dir/$file$rest" ] && [ -z "$created" ]; then
            pass "$cmd $file -> exact message"
        else
            fail "$cmd $file: exit $rc, stderr '$err', expected 'touchdown: $bad_dir/$file$rest'$created"
        fi
    done
done <<'EOF'
end-time-unbounded.cfg|:4: end_time: 10000 Hz over 1e+12 s makes 1e+16 output samples (at most 1e+08)
solver-max-step-tiny.cfg|:5: solver.max_step: max_step 1e-300 s over 0.1 s forces 1e+299 solver steps (at most 1e+08)
amb-bandwidth-tiny.cfg|:5: ambs[0].bandwidth: the time constant tau = 1 / (2 pi bandwidth) overflows (to inf)
disc-inertia-overflow.cfg|:5: discs[0].radius: the disc inertia from radius, thickness (or mass) and density overflows (to inf)
shaft-diameter-overflow.cfg|:7: shaft.outer_diameter: the second moment of area pi (D^4 - d^4) / 64 overflows (to inf)
shaft-nodes-too-close.cfg|:4: shaft.nodes: an element stiffness E I / L^3 from the element length L overflows (to inf)
speed-overflow-orbit.cfg|:3: speed: 1e+300 rad/s over 0.1 s makes 1.59e+298 shaft revolutions (at most 1e+06)
unbalance-force-overflow.cfg|:6: unbalances[0].magnitude: the unbalance force U Omega^2 = 1e+300 kg m x (100 rad/s)^2 = 1e+304 N exceeds 1e+12 N; see speed at BAD/../case/run.cfg:2
unbalance-wrap-same-line.cfg|:5: unbalances[0].magnitude: integer 4294967296 is out of range (at most 2147483647; libconfig would read 0)
line-endings-cr.cfg|:5: carriage return without a line feed (CR-only line endings are not supported; save the file with LF or CRLF line endings)
speed-unbounded.cfg|:3: speed: 1e+20 rad/s over 0.1 s makes 1.59e+18 shaft revolutions (at most 1e+06)
shaft-section-smaller-than-bore.cfg|:8: shaft.sections[0].outer_diameter: the section's outer diameter 0.02 m (element 1) must be larger than the inner diameter 0.03 m of shaft.inner_diameter at BAD/shaft-section-smaller-than-bore.cfg:7
solver-atol-above-clearance.cfg|:6: solver.atol: the displacement tolerance 0.001 m must be at most 1e-03 of the smallest gap, the clearance 0.00075 m of retainer 0 (at most 7.5e-07 m): the contacts would not be resolved
shaft-nodes-overflow.cfg|:4: shaft.nodes[1]: the element length from the node positions overflows (to inf)
shaft-damping-overflow.cfg|:8: shaft.damping.frequencies: the Rayleigh coefficients alpha = 2 zeta w1 w2 / (w1 + w2) and beta = 2 zeta / (w1 + w2) overflow (w = 2 pi f, the largest f 1e+308 Hz)
EOF

# ---- paths that are not readable case files -----------------------------------------------
mkdir -p "$work/in"
: >"$work/in/empty.cfg"
head -c 4096 /dev/urandom >"$work/in/junk.cfg"                 # random binary junk
printf 'speed = 1;\x00\x01\x02 end_time = 1;\n' >"$work/in/nul.cfg" # text with a NUL byte
mkfifo "$work/in/fifo.cfg"
printf 'speed = 1.0;\n' >"$work/in/locked.cfg"
chmod 000 "$work/in/locked.cfg"
for cmd in run info; do
    expect_bad "$cmd on a directory" "$src/cases" "directory" -- "$cmd" "$src/cases"
    expect_bad "$cmd on a missing path" "$work/in/no-such.cfg" -- "$cmd" "$work/in/no-such.cfg"
    expect_bad "$cmd on a path through a file" "$src/cases/paper-a.cfg/x.cfg" -- "$cmd" "$src/cases/paper-a.cfg/x.cfg"
    expect_bad "$cmd on a FIFO" "$work/in/fifo.cfg" -- "$cmd" "$work/in/fifo.cfg"
    expect_bad "$cmd on an empty file" "$work/in/empty.cfg:1: " -- "$cmd" "$work/in/empty.cfg"
    expect_bad "$cmd on binary junk" "$work/in/junk.cfg" -- "$cmd" "$work/in/junk.cfg"
    expect_bad "$cmd on a file with a NUL byte" "$work/in/nul.cfg:1: " -- "$cmd" "$work/in/nul.cfg"
    expect_bad "$cmd on an empty path" "cannot read" -- "$cmd" ""
done
# An unreadable file: root ignores permissions, so drop to 'nobody' when running as root.
if [ "$(id -u)" != 0 ]; then
    for cmd in run info; do
        expect_bad "$cmd on an unreadable file" "$work/in/locked.cfg" "ermission denied" -- "$cmd" "$work/in/locked.cfg"
    done
elif command -v setpriv >/dev/null && setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null &&
    setpriv --reuid=65534 --regid=65534 --clear-groups "$tool" --version >/dev/null 2>&1; then
    chmod 777 "$scratch" "$work" "$work/in"
    runner=(setpriv --reuid=65534 --regid=65534 --clear-groups)
    for cmd in run info; do
        expect_bad "$cmd on an unreadable file (as nobody)" "$work/in/locked.cfg" "ermission denied" -- \
            "$cmd" "$work/in/locked.cfg"
    done
    runner=()
    chmod 700 "$scratch" "$work" "$work/in"
else
    echo "skip: unreadable file (running as root without a usable setpriv)"
fi

# ---- out of memory while reading: a 12 MiB case with a 6-million-entry array used to crash
# libconfig (SIGSEGV, nothing printed) under a memory limit; the entries are counted before it
# parses, and what it will allocate is asked for first. Skipped where the tool cannot start
# under the limit at all (sanitizer builds reserve terabytes of address space).
awk 'BEGIN { printf "speed = 1.0;\nend_time = 1.0;\nx = ["; for (i = 0; i < 6000000; i++) printf "1,"; print "1];" }' \
    >"$work/in/array-6m.cfg"
awk 'BEGIN { printf "speed = 1.0;\nend_time = 1.0;\nx = ["; for (i = 0; i < 199000; i++) printf "1,"; print "1];" }' \
    >"$work/in/array-199k.cfg"
if (ulimit -v 40000 && "$tool" --version >/dev/null 2>&1); then
    for limit in 200000 60000; do
        runner=(bash -c "ulimit -v $limit && exec \"\$@\"" limit)
        expect_bad "info on a 6-million-entry array (ulimit -v $limit)" \
            "$work/in/array-6m.cfg:3: more than 200000 settings and list or array entries in one case" -- \
            info "$work/in/array-6m.cfg"
        runner=()
    done
    # the least address space the tool starts in (it grows with the code), plus 8 MiB: room to read
    # the 400 kB file, far from the 52 MB its parse would need
    base=40000
    while [ "$base" -lt 120000 ] && ! (ulimit -v "$base" && "$tool" --version >/dev/null 2>&1); do
        base=$((base + 2000))
    done
    small=$((base + 8000))
    runner=(bash -c "ulimit -v $small && exec \"\$@\"" limit)
    expect_bad "info on a 199000-entry array (ulimit -v $small)" \
        "$work/in/array-199k.cfg: out of memory: parsing 199004 settings needs about" -- info "$work/in/array-199k.cfg"
    runner=()
else
    echo "skip: the tool cannot start under ulimit -v 40000"
fi

# ---- bad --set overrides: one line naming the case, the override and the key --------------
case_a=$src/cases/paper-a.cfg
while IFS='|' read -r set needle; do
    [ -z "$set" ] && continue
    for cmd in run info; do
        expect_bad "$cmd --set '$set'" "$case_a" "--set '$set'" "$needle" -- "$cmd" --set "$set" "$case_a"
    done
done <<'EOF'
speed=fast|speed: 
speed=-1|speed: 
speed=1e999|speed: 
speed=nan|speed
speed=[1,2]|speed: 
nokey=1|nokey: 
retainers[0].clearence=1e-3|retainers[0].clearence: 
retainers[7].friction=0.1|[7]
retainers[0].clearance=0.01|retainers[0].clearance: 
contact.model=hertz|contact.model: 
solver.rtol=0|solver.rtol: 
shaft.elements=0|shaft.elements: 
end_time=0|end_time: 
end_time=1e12|end_time: 10000 Hz over 1e+12 s makes 1e+16 output samples (at most 1e+08)
solver.max_step=1e-300|solver.max_step: max_step 1e-300 s over 2 s forces 2e+300 solver steps
solver.atol=1e6|solver.atol: the displacement tolerance 1e+06 m must be at most 1e-03 of the smallest gap
speed=1e20|speed: 1e+20 rad/s over 2 s makes 3.18e+19 shaft revolutions
speed|KEY=VALUE
=1|KEY=VALUE
speed="abc|speed
EOF

# ---- the case reader's own rules, forms and getters through its tables: the whole message of a
# --set on tests/data/case/all-keys.cfg (a row check, a custom reader or a typed getter of each
# kind; the text as the reader gave it before it read by tables; @CASE@ stands for the file). A rule
# that compares the key with another says where that one was written: a line of the file, or the
# --set that gave it, when the key it fails at is in the file ---------------------------------
all_keys=$src/tests/data/case/all-keys.cfg
while IFS='|' read -r set rest; do
    [ -z "$set" ] && continue
    rest=${rest//@CASE@/$all_keys}
    run_tool info -n 1 --set "$set" "$all_keys"
    if [ "$rc" = 2 ] && [ "$err" = "touchdown: $all_keys$rest" ] && [ -z "$out" ]; then
        pass "info --set '$set' -> exact message"
    else
        fail "info --set '$set': exit $rc, stderr '$err', expected 'touchdown: $all_keys$rest'"
    fi
done <<'EOF'
solver.initial_step=1.0|: --set 'solver.initial_step=1.0': solver.initial_step: 1 s is larger than max_step 0.0001 s; see solver.max_step at @CASE@:71
solver.max_step=1e-7|:71: solver.initial_step: 1e-06 s is larger than max_step 1e-07 s; see solver.max_step at @CASE@: --set 'solver.max_step=1e-7'
contact.exponent=0.5|: --set 'contact.exponent=0.5': contact.exponent: must be >= 1 (got 0.5)
modal.speed_max=1.0|: --set 'modal.speed_max=1.0': modal.speed_max: speed_max (1 rad/s) must be larger than speed_min (10 rad/s); see modal.speed_min at @CASE@:74
modal.speed_min=1e9|:74: modal.speed_max: speed_max (500 rad/s) must be larger than speed_min (1e+09 rad/s); see modal.speed_min at @CASE@: --set 'modal.speed_min=1e9'
modal.speed_steps=100000|: --set 'modal.speed_steps=100000': modal.speed_steps: 100000 speeds on a model of 28 DOFs is too much work: speed_steps x DOFs must stay below 200000 (here at most 7142 speeds; see docs/performance.md); see shaft.elements at @CASE@:13
modal.modes=1000|: --set 'modal.modes=1000': modal.modes: must lie in [1, 28] (got 1000); see shaft.elements at @CASE@:13
output.nodes=[1, 1]|: --set 'output.nodes=[1, 1]': output.nodes[1]: node 1 is listed twice
output.nodes=[99]|: --set 'output.nodes=[99]': output.nodes[0]: node 99 is out of range (the shaft has nodes 0..6); see shaft.elements at @CASE@:13
gravity.direction=[1.0, 2.0, 3.0]|: --set 'gravity.direction=[1.0, 2.0, 3.0]': gravity.direction: too many entries (3, at most 2)
gravity.direction=[0.0, 0.0]|: --set 'gravity.direction=[0.0, 0.0]': gravity.direction: must not be the zero vector
gravity.direction=[1.0]|: --set 'gravity.direction=[1.0]': gravity.direction: expected two components [gx, gy], got 1
shaft.nodes=[0.0, 1.0]|: --set 'shaft.nodes=[0.0, 1.0]': shaft.nodes: give either 'nodes' or 'length' + 'elements', not both
shaft.sections[0].element=1|: --set 'shaft.sections[0].element=1': shaft.sections[0].element: give either 'element' or 'from' + 'to', not both
shaft.sections[0].to=-1|: --set 'shaft.sections[0].to=-1': shaft.sections[0].to: must lie in [0, 5] (got -1)
shaft.sections[0].to=9|: --set 'shaft.sections[0].to=9': shaft.sections[0].to: must lie in [0, 5] (got 9); see shaft.elements at @CASE@:13
shaft.elements=2|:20: shaft.sections[1].element: must lie in [0, 1] (got 4); see shaft.elements at @CASE@: --set 'shaft.elements=2'
shaft.sections[1].element=0|:20: shaft.sections[1]: element 0 is already in sections[0]; sections must not overlap
shaft.refine=5000|: --set 'shaft.refine=5000': shaft.refine: 6 elements split 5000 times make 30000 (at most 10000)
shaft.damping={ ratio = 0.01; frequencies = [10.0]; }|: --set 'shaft.damping={ ratio = 0.01; frequencies = [10.0]; }': shaft.damping: give either 'rayleigh' or 'damping', not both
shaft.rayleigh.gamma=1.0|: --set 'shaft.rayleigh.gamma=1.0': shaft.rayleigh.gamma: unknown key (valid here: alpha, beta)
discs[0].radius=0.1|: --set 'discs[0].radius=0.1': discs[0].radius: give either mass + Ip + Id or the geometry (radius + density + thickness or mass), not both
ambs[0].bandwidth=100.0|: --set 'ambs[0].bandwidth=100.0': ambs[0].bandwidth: give either tau or bandwidth, not both
ambs[1].bandwidth=-1.0|: --set 'ambs[1].bandwidth=-1.0': ambs[1].bandwidth: must be > 0 (got -1)
ambs[0].slew_rate=-1.0|: --set 'ambs[0].slew_rate=-1.0': ambs[0].slew_rate: must be >= 0 (got -1)
ambs[0].tau=0.0|:36: ambs[0].slew_rate: a slew-rate limit (400 A/s) needs a force lag, tau > 0 or a bandwidth (got tau = 0)
schedule[0].amb_off=0|:61: schedule[0].amb_on: a schedule entry makes one change: unbalance, amb_off or amb_on
schedule[0].amb_on=1.5|: --set 'schedule[0].amb_on=1.5': schedule[0].amb_on: expected an integer, got the number 1.5 (write integers without a point)
description=1|: --set 'description=1': description: expected a string "...", got an integer
speed="x"|: --set 'speed="x"': speed: expected a number, got the string "x"
retainers[0].bore_radius="x"|: --set 'retainers[0].bore_radius="x"': retainers[0].bore_radius: expected a number, got the string "x"
retainers[0].race.mass="x"|: --set 'retainers[0].race.mass="x"': retainers[0].race.mass: expected a number, got the string "x"
retainers[0].mount.damping="x"|: --set 'retainers[0].mount.damping="x"': retainers[0].mount.damping: expected a number, got the string "x"
retainers[0].contact.damping="x"|: --set 'retainers[0].contact.damping="x"': retainers[0].contact.damping: must be one of "none", "hunt-crossley", "kelvin-voigt" (got "x")
shaft.material.E=0|: --set 'shaft.material.E=0': shaft.material.E: must be > 0 (got 0)
shaft.sections[0].material.E=-1|: --set 'shaft.sections[0].material.E=-1': shaft.sections[0].material.E: must be > 0 (got -1)
shaft.shear_coefficient="x"|: --set 'shaft.shear_coefficient="x"': shaft.shear_coefficient: must be one of "hutchinson", "cowper" (got "x")
shaft.shear_coefficient=[1]|: --set 'shaft.shear_coefficient=[1]': shaft.shear_coefficient: expected a number, got an array [ ... ]
spin.free=1|: --set 'spin.free=1': spin.free: expected true or false, got an integer
point_masses[0].nodde=1|: --set 'point_masses[0].nodde=1': point_masses[0].nodde: unknown key; did you mean 'node'?
modal.response_speeds=[-1.0]|: --set 'modal.response_speeds=[-1.0]': modal.response_speeds[0]: must be >= 0 (got -1)
output.compression=10|: --set 'output.compression=10': output.compression: must lie in [0, 9] (got 10)
energy=1|: --set 'energy=1': energy: expected true or false, got an integer
start="x"|: --set 'start="x"': start: must be one of "orbit", "rest", "auto" (got "x")
discs=1|: --set 'discs=1': discs: expected a list of groups ( { ... }, { ... } ), got an integer
discs=(1)|: --set 'discs=(1)': discs[0]: expected a group { ... }, got an integer
gravity=1|: --set 'gravity=1': gravity: expected a group { ... }, got an integer
EOF
long=$(printf 'A%.0s' $(seq 1100))
run_tool info --set "output.hdf5=\"$long\"" "$all_keys"
check "info: an output path of 1100 characters -> path too long" test "$rc" = 2 -a \
    "${err##*: }" = "path too long (1100 characters, at most 1023)"

# ---- bad usage -----------------------------------------------------------------------------
expect_usage "no arguments"
expect_usage "unknown command" frobnicate "$case_a"
for cmd in run info modal; do
    expect_usage "$cmd without a case" "$cmd"
    expect_usage "$cmd with two cases" "$cmd" "$case_a" "$case_a"
    expect_usage "$cmd with an unknown option" "$cmd" --bogus "$case_a"
    expect_usage "$cmd -s without its argument" "$cmd" "$case_a" -s
done
expect_usage "run --output without its argument" run "$case_a" --output
expect_usage "info --modes 0" info --modes 0 "$case_a"
expect_usage "info --keys with a case file" info --keys "$case_a"
run_tool info --keys
check "info --keys: exit 0, a JSON array of the case keys on stdout, nothing on stderr" \
    test "$rc" = 0 -a -z "$err" -a "${out:0:1}" = "[" -a "${out: -1}" = "]"
# a speed the library does not take (touchdown/dofs.h: >= 0, the spin about +z), as in the case file
for w in -5 -1e-9 nan inf; do
    expect_bad "modal --speed $w" "touchdown modal: --speed wants a speed >= 0 in rad/s, not '$w'" -- \
        modal --speed "$w" "$case_a"
done
expect_usage "info --modes x" info --modes x "$case_a"

after=$(ls -la --time-style=+%s "$bad_dir" | md5sum)
check "tests/data/bad/ unchanged while the tool read it" test "$before" = "$after"

finish
