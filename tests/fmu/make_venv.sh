#!/usr/bin/env bash
# The test fixture of the tests that need a Python package from PyPI (the FMU tests: the FMU importer
# fmpy; the modal tests: ROSS): a Python virtual environment VENV (in the build directory) with the
# packages pinned by REQUIREMENTS (tests/fmu/requirements.txt, tests/modal/requirements.txt), on
# Debian's python3 with its packages visible. Made once: a VENV whose stamp holds the requirements
# it was made from and that imports MODULE (default fmpy) is kept. A test that needs it fails when
# it cannot be had (no network, no python3-venv): it never skips.
#   make_venv.sh VENV REQUIREMENTS [MODULE]
set -euo pipefail
venv=$1
req=$2
module=${3:-fmpy}
py=/usr/bin/python3
stamp=$venv/touchdown-requirements.txt
if [ -f "$stamp" ] && cmp -s "$stamp" "$req" && "$venv/bin/python" -c "import $module" 2>/dev/null; then
    echo "$module: $("$venv/bin/python" -c "import $module; print($module.__version__)") in $venv (made before)"
    exit 0
fi
rm -rf "$venv"
if ! "$py" -m venv --system-site-packages "$venv"; then
    echo "FAIL: $py -m venv failed: the tests of $module need python3-venv (scripts/setup.sh installs it)" >&2
    exit 1
fi
if ! "$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q -r "$req"; then
    echo "FAIL: pip could not install $req from PyPI into $venv: the tests need $module (network access to PyPI)" >&2
    rm -rf "$venv"
    exit 1
fi
cp "$req" "$stamp"
echo "$module: $("$venv/bin/python" -c "import $module; print($module.__version__)") installed in $venv"
