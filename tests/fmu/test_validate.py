"""touchdown fmu's FMUs as an independent importer sees them: fmpy validates each (modelDescription.xml
against the FMI 2.0 schema, its variable names, model structure, start values and units), finds the
64-bit Linux binary the tool packed (the build's touchdown-fmu.so, byte for byte, as NAME.so), the
inputs each --inputs asks for, and simulates it; the same case packs to the same bits, also when read
from another directory.

    test_validate.py TOOL SOURCE_DIR BUILD_DIR FMU_BINARY
"""
import os
import shutil
import sys
import tempfile
import zipfile

import fmpy
from fmpy.validation import validate_fmu

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fmu_common import check, finish, pack, tool_fmu  # noqa: E402

tool, src, build, binary = sys.argv[1:5]
case = os.path.join(src, "cases", "paper-a-digital.cfg")
INPUTS = {"current": ("current_x", "current_y"), "force": ("control_force_x", "control_force_y"), "none": ()}

with tempfile.TemporaryDirectory() as tmp:
    for kind, names in INPUTS.items():
        path = pack(tool, case, os.path.join(tmp, "PaperA_%s.fmu" % kind), kind, ["end_time=0.02"])
        problems = validate_fmu(path)
        check("fmpy validates the FMU (--inputs %s)" % kind, problems == [], "; ".join(problems))
        md = fmpy.read_model_description(path)
        ident = "PaperA_%s" % kind
        check("model identifier %s, co-simulation" % ident,
              md.coSimulation is not None and md.coSimulation.modelIdentifier == ident)
        check("fmpy finds the linux64 binary", "linux64" in fmpy.supported_platforms(path),
              str(fmpy.supported_platforms(path)))
        with zipfile.ZipFile(path) as z:
            names_in = z.namelist()
            so = z.read("binaries/linux64/%s.so" % ident) if "binaries/linux64/%s.so" % ident in names_in else b""
        with open(binary, "rb") as f:
            check("binaries/linux64/%s.so is the build's touchdown-fmu.so" % ident, so == f.read())
        check("modelDescription.xml and resources/ in the archive",
              "modelDescription.xml" in names_in and any(n.startswith("resources/") for n in names_in), str(names_in))
        inputs = sorted(v.name for v in md.modelVariables if v.causality == "input")
        want = sorted("ambs[%d].%s" % (i, n) for i in range(2) for n in names)
        check("inputs for --inputs %s: %s" % (kind, ", ".join(want) or "none"), inputs == want, str(inputs))
        outputs = {v.name for v in md.modelVariables if v.causality == "output"}
        need = {"ambs[0].sensed_x", "ambs[1].sensed_y", "retainers[0].contact_force", "rotor_speed", "events",
                "first_contact_time", "peak_contact_force", "contact_occurred"}
        check("outputs include %s" % ", ".join(sorted(need)), need <= outputs, str(sorted(need - outputs)))
        if kind == "none":
            # fmpy's own driver (simulate_fmu), its inputs none: the case's own controllers run inside
            res = fmpy.simulate_fmu(path, stop_time=0.02, output_interval=1e-3, output=["rotor_speed"])
            check("fmpy.simulate_fmu runs it to its stop time",
                  abs(res["time"][-1] - 0.02) < 1e-12 and all(abs(w - 90.0) < 1e-9 for w in res["rotor_speed"]),
                  "last time %r" % res["time"][-1])
    a, b = os.path.join(tmp, "A.fmu"), os.path.join(tmp, "B", "A.fmu")
    os.mkdir(os.path.dirname(b))
    pack(tool, case, a)
    pack(tool, case, b)
    # the same case read from another directory (a copy of cases/, its @include files with it)
    shutil.copytree(os.path.join(src, "cases"), os.path.join(tmp, "copy", "cases"))
    c = os.path.join(tmp, "C", "A.fmu")
    os.mkdir(os.path.dirname(c))
    pack(tool, os.path.join(tmp, "copy", "cases", "paper-a-digital.cfg"), c)
    with open(a, "rb") as fa, open(b, "rb") as fb, open(c, "rb") as fc:
        first = fa.read()
        check("the same case packs to the same bits, twice", first == fb.read())
        check("... and from a copy of it in another directory (the FMU holds no path of the machine)",
              first == fc.read())
    proc = tool_fmu(tool, case, os.path.join(tmp, "bad-name.fmu"))
    check("a model identifier that is no C identifier: exit 2, one line",
          proc.returncode == 2 and len(proc.stderr.splitlines()) == 1, proc.stderr)
finish()
