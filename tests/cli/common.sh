# Helpers shared by the CLI test scripts (sourced, not run): each script counts its checks and
# failures, prints "ok:" or "FAIL:" lines (one per check), and ends with finish.
fails=0
checks=0

fail() { echo "FAIL: $*"; fails=$((fails + 1)); checks=$((checks + 1)); }
pass() { echo "ok:   $*"; checks=$((checks + 1)); }
check() { # DESCRIPTION COMMAND...
    local what=$1
    shift
    if "$@"; then pass "$what"; else fail "$what"; fi
}

# The end of a script: the counts, then exit 0 if every check passed, else 1. A script that ran no
# check at all fails too: a finish reached early (a stray call, a skipped block) must not pass.
finish() {
    echo "$((checks - fails)) passed, $fails failed"
    if [ "$checks" = 0 ]; then
        echo "FAIL: no check ran"
        exit 1
    fi
    if [ "$fails" = 0 ]; then exit 0; fi
    exit 1
}

# sanitized: true when the script runs in the sanitizer pass (TD_TEST_SANITIZED=1, set by
# tests/CMakeLists.txt on every test of that build). That pass looks for memory errors and undefined
# behaviour, so a script may then take the same code paths with fewer or shorter runs; each script
# that does says what it still covers there and what only the plain pass checks.
sanitized() { [ "${TD_TEST_SANITIZED:-0}" = 1 ]; }

# t DIR ARGS...: run the tool ($tool) in DIR (created if missing); rc, and DIR/.out, DIR/.err.
t() {
    local d=$1
    shift
    mkdir -p "$d"
    (cd "$d" && "$tool" "$@" >"$d/.out" 2>"$d/.err" </dev/null)
    rc=$?
}

# need PROGRAM PACKAGE: PROGRAM must be on the PATH, else the script ends here with a FAIL line
# naming the package (scripts/setup.sh installs it): a check that needs it never passes by skipping.
need() {
    command -v "$1" >/dev/null && return 0
    fail "$1 not found: the checks that need it cannot run (install $2; scripts/setup.sh does)"
    finish
}

# First top-level "KEY":VALUE of a one-line JSON object (strings keep their quotes).
jf() { grep -oE "\"$2\":(\"[^\"]*\"|[^,}]*)" "$1" | head -n 1 | sed -E "s/^\"$2\"://"; }

# h5py_python: print a python3 that imports h5py and numpy (TD_PYTHON, the first python3 on the
# PATH, or the system's, which scripts/setup.sh gives python3-h5py); print nothing if none does.
h5py_python() {
    local cand
    for cand in ${TD_PYTHON:-} python3 /usr/bin/python3; do
        if command -v "$cand" >/dev/null && "$cand" -c 'import h5py, numpy' 2>/dev/null; then
            echo "$cand"
            return
        fi
    done
}
