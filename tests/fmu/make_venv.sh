#!/usr/bin/env bash
# The test fixture of the tests that need a package from PyPI: a Python virtual environment VENV (in
# the build directory) with the packages pinned by REQUIREMENTS, MODULE among them (default fmpy, the
# FMU importer of the FMU tests, tests/fmu/requirements.txt; rainflow, the life tests' reference,
# tests/life/requirements.txt; ross, the modal tests' reference, tests/modal/requirements.txt), on
# Debian's python3 with its packages (numpy, scipy) visible. PIP_OPTIONs go to pip install (ross:
# --no-deps, its requirements list what its import needs, not its whole declared tree; --no-compile).
# Made once: a VENV whose stamp holds the requirements and options it was made from is kept.
# pip is Debian's (python3-pip) when it is there, seen through --system-site-packages, else the venv's
# own (ensurepip, 25 MB and seconds more). MODULE is imported once at the end with bytecode writing on,
# which checks that the pins are enough and compiles what the import loads (with --no-compile, only
# that). A test that needs MODULE fails when it cannot be had (no network, no python3-venv, a pin
# missing): it never skips.
#   make_venv.sh VENV REQUIREMENTS [MODULE [PIP_OPTION...]]
set -euo pipefail
venv=$1
req=$2
mod=${3:-fmpy}
opts=("${@:4}")
py=/usr/bin/python3
stamp=$venv/touchdown-requirements.txt
made_from() {
    cat "$req"
    if ((${#opts[@]})); then echo "# pip install ${opts[*]}"; fi
}
fail() {
    echo "FAIL: $*" >&2
    rm -rf "$venv"
    exit 1
}
version() {
    env -u PYTHONDONTWRITEBYTECODE "$venv/bin/python" -c "import $mod; print($mod.__version__)" | tail -n 1
}
if [ -f "$stamp" ] && cmp -s "$stamp" <(made_from) && v=$(version 2>/dev/null); then
    echo "$mod: $v in $venv (made before)"
    exit 0
fi
rm -rf "$venv"
if ! "$py" -m venv --without-pip --system-site-packages "$venv"; then
    fail "$py -m venv failed: the tests of $mod need python3-venv (scripts/setup.sh installs it)"
fi
if ! "$venv/bin/python" -m pip --version >/dev/null 2>&1 &&
    ! "$venv/bin/python" -m ensurepip --default-pip >/dev/null; then
    fail "no pip for $venv (neither python3-pip nor ensurepip of python3-venv): the tests need $mod"
fi
if ! "$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q "${opts[@]}" -r "$req"; then
    fail "pip could not install $req from PyPI into $venv: the tests need $mod (network access to PyPI)"
fi
if ! v=$(version); then
    fail "import $mod failed in $venv after installing $req: a package its import needs is not pinned there"
fi
made_from >"$stamp"
echo "$mod: $v installed in $venv"
