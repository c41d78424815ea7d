#!/usr/bin/env bash
# The test fixture of the tests that need a package from PyPI: a Python virtual environment VENV (in
# the build directory) with the packages pinned by REQUIREMENTS, MODULE among them (default fmpy, the
# FMU importer of the FMU tests, tests/fmu/requirements.txt; rainflow, the life tests' reference,
# tests/life/requirements.txt), on Debian's python3 with its packages (numpy) visible. Made once: a
# VENV whose stamp holds the requirements it was made from is kept. A test that needs MODULE fails
# when it cannot be had (no network, no python3-venv): it never skips.
#   make_venv.sh VENV REQUIREMENTS [MODULE]
set -euo pipefail
venv=$1
req=$2
mod=${3:-fmpy}
py=/usr/bin/python3
stamp=$venv/touchdown-requirements.txt
if [ -f "$stamp" ] && cmp -s "$stamp" "$req" && "$venv/bin/python" -c "import $mod" 2>/dev/null; then
    echo "$mod: $("$venv/bin/python" -c "import $mod; print($mod.__version__)") in $venv (made before)"
    exit 0
fi
rm -rf "$venv"
if ! "$py" -m venv --system-site-packages "$venv"; then
    echo "FAIL: $py -m venv failed: the tests of $mod need python3-venv (scripts/setup.sh installs it)" >&2
    exit 1
fi
if ! "$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q -r "$req"; then
    echo "FAIL: pip could not install $req from PyPI into $venv: the tests need $mod (network access to PyPI)" >&2
    rm -rf "$venv"
    exit 1
fi
cp "$req" "$stamp"
echo "$mod: $("$venv/bin/python" -c "import $mod; print($mod.__version__)") installed in $venv"
