"""An FMU runs where none of the build tree is: copied to a temporary directory outside the source
and build trees, unpacked there by fmpy and stepped in a fresh process whose environment holds no
library path, it gives the same answers as the copy in the build tree, bit for bit. Its binary
names no RPATH or RUNPATH, the dynamic loader resolves every library it needs outside the trees
(LD_DEBUG=libs of that process), and no file of the FMU names a path of either tree.

    test_relocated.py TOOL SOURCE_DIR BUILD_DIR FMU_BINARY
"""
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from fmu_common import check, child_main, finish, free_run, fresh_process, pack  # noqa: E402

END, H = 0.12, 1e-4


def run(path):
    """Step the FMU (no inputs: the case's own controllers) every H s to END; its answers."""
    return free_run(path, END, H)


child_main(run)
tool, src, build = (os.path.realpath(a) for a in sys.argv[1:4])
trees = [src, build]


def inside(path):
    p = os.path.realpath(path)
    return any(p == t or p.startswith(t + os.sep) for t in trees)


with tempfile.TemporaryDirectory(dir=os.environ.get("TD_FMU_OUTSIDE", "/tmp")) as tmp:
    if not check("the temporary directory %s lies outside the trees" % tmp, not inside(tmp)):
        finish()
    fmu = pack(tool, os.path.join(src, "cases", "paper-a-digital.cfg"), os.path.join(build, "tests", "Relocated.fmu"),
               "none", ["end_time=%g" % END])
    copy = os.path.join(tmp, "away", "Relocated.fmu")
    os.makedirs(os.path.dirname(copy))
    shutil.copy(fmu, copy)
    here_answers = run(fmu)
    unpacked = os.path.join(tmp, "unpacked")
    with zipfile.ZipFile(copy) as z:
        z.extractall(unpacked)
        texts = [(n, z.read(n)) for n in z.namelist()]
    so = os.path.join(unpacked, "binaries", "linux64", "Relocated.so")
    dyn = subprocess.run(["readelf", "-d", so], stdout=subprocess.PIPE, universal_newlines=True).stdout
    check("the binary has no RPATH or RUNPATH", dyn and "RPATH" not in dyn and "RUNPATH" not in dyn,
          [l for l in dyn.splitlines() if "PATH" in l])
    # (the binary's debugging information names its sources: the loader's check below covers it)
    named = [n for n, data in texts for t in trees if t.encode() in data and not n.startswith("binaries/")]
    check("no text file of the FMU (modelDescription.xml, resources/) names the source or build tree", not named,
          str(named))
    os.remove(fmu)  # the build tree's copy is gone: only the one away can serve
    away, loaded = fresh_process(__file__, copy, tmp, os.path.join(tmp, "ld"))
    check("its answers equal the build tree's bit for bit: %s" % here_answers, away == here_answers, str(away))
    # (the importer's own Python libraries come from its virtual environment, which may lie anywhere)
    stray = [l for l in loaded if inside(l) and not l.startswith(os.path.realpath(sys.prefix) + os.sep)]
    check("the loader resolved its libraries (%d) all outside the trees" % len(loaded),
          any(l.endswith("Relocated.so") for l in loaded) and not stray, str(stray))
finish()
