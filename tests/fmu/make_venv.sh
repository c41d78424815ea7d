#!/usr/bin/env bash
# The test fixture of the FMU tests: a Python virtual environment VENV (in the build directory) with
# the FMU importer fmpy from PyPI, pinned by REQUIREMENTS (tests/fmu/requirements.txt), on Debian's
# python3 with its packages (numpy) visible. Made once: a VENV whose stamp holds the requirements it
# was made from is kept. A test that needs fmpy fails when it cannot be had (no network, no
# python3-venv): it never skips.
#   make_venv.sh VENV REQUIREMENTS
set -euo pipefail
venv=$1
req=$2
py=/usr/bin/python3
stamp=$venv/touchdown-requirements.txt
if [ -f "$stamp" ] && cmp -s "$stamp" "$req" && "$venv/bin/python" -c 'import fmpy' 2>/dev/null; then
    echo "fmpy: $("$venv/bin/python" -c 'import fmpy; print(fmpy.__version__)') in $venv (made before)"
    exit 0
fi
rm -rf "$venv"
if ! "$py" -m venv --system-site-packages "$venv"; then
    echo "FAIL: $py -m venv failed: the FMU tests need python3-venv (scripts/setup.sh installs it)" >&2
    exit 1
fi
if ! "$venv/bin/python" -m pip install --disable-pip-version-check --no-input -q -r "$req"; then
    echo "FAIL: pip could not install $req from PyPI into $venv: the FMU tests need fmpy (network access to PyPI)" >&2
    rm -rf "$venv"
    exit 1
fi
cp "$req" "$stamp"
echo "fmpy: $("$venv/bin/python" -c 'import fmpy; print(fmpy.__version__)') installed in $venv"
