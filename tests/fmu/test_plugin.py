"""An FMU of a case whose controller is a plug-in (examples/plugin-pd/rig-pd.cfg with the test PD,
tests/plugins/pd.c) carries its library: the case and the library are copied to a temporary
directory outside the trees, packed from there, and that directory is removed before the FMU runs.
Stepped through fmpy (no inputs: the plug-in inside) in a fresh process with no library path, its
answers equal touchdown run of the case bit for bit, and the dynamic loader took the plug-in from
the FMU's own resources/plugins/ (LD_DEBUG=libs of that process), never from where it was packed.
The same case with the NaN plug-in (tests/plugins/nan.c, NaN from sample 3): doStep is fmi2Error
with one line naming the controller, and the process ends normally.

    test_plugin.py TOOL SOURCE_DIR BUILD_DIR FMU_BINARY
"""
import os
import shutil
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from fmu_common import (FMICallException, Instance, check, child_main, finish, fresh_process,  # noqa: E402
                        native, pack, results, step_to)

END, H = 0.12, 1e-3


def run(path):
    """Step the FMU every H s to END (fmi2Error stops it): its answers, or its last message."""
    inst = Instance(path)
    inst.start(0.0, END)
    try:
        step_to(inst, END, H)
        out = results(inst)
    except FMICallException as e:
        out = {"error": str(e), "messages": [m for s, m in inst.messages]}
    inst.free()
    return out


child_main(run)
tool, src, build = (os.path.realpath(a) for a in sys.argv[1:4])


def write_case(where, library):
    """The example's case in `where`, its plug-in a copy of `library` named pd.so beside it (the
    test PD takes kp and kd only: the example's ki = 0 is left out)."""
    os.makedirs(where)
    with open(os.path.join(src, "examples", "plugin-pd", "rig-pd.cfg")) as f:
        text = f.read().replace(" ki = 0.0;", "")
    with open(os.path.join(where, "rig-pd.cfg"), "w") as f:
        f.write(text)
    shutil.copy(library, os.path.join(where, "pd.so"))
    return os.path.join(where, "rig-pd.cfg")


sets = ["end_time=%g" % END]
with tempfile.TemporaryDirectory(dir=os.environ.get("TD_FMU_OUTSIDE", "/tmp")) as tmp:
    case = write_case(os.path.join(tmp, "case"), os.path.join(build, "tests", "plugins", "pd.so"))
    direct = native(tool, case, sets)
    fmu = pack(tool, case, os.path.join(tmp, "Plug.fmu"), "none", sets)
    shutil.rmtree(os.path.join(tmp, "case"))  # the case and its library where they were packed are gone
    answers, loaded = fresh_process(__file__, fmu, tmp, os.path.join(tmp, "ld"))
    keys = ("first_contact_time", "peak_normal_force", "events")
    check("its answers equal touchdown run of the case bit for bit: %s" % answers,
          answers is not None and "error" not in answers and all(answers[k] == direct[k] for k in keys),
          "native %s" % {k: direct[k] for k in keys})
    plugins = [l for l in loaded if os.path.basename(l) == "pd.so"]  # (opened at instantiation and initialisation)
    check("the loader took the plug-in from the FMU's resources/plugins/: %s" % plugins,
          plugins and all(p.endswith(os.path.join(os.sep, "resources", "plugins", "pd.so"))
                          and not p.startswith(os.path.join(tmp, "case") + os.sep) for p in plugins))

    case = write_case(os.path.join(tmp, "nan"), os.path.join(build, "tests", "plugins", "nan.so"))
    fmu = pack(tool, case, os.path.join(tmp, "NaN.fmu"), "none", sets)
    shutil.rmtree(os.path.join(tmp, "nan"))
    answers, loaded = fresh_process(__file__, fmu, tmp, os.path.join(tmp, "ld-nan"))
    errors = answers["messages"] if answers and "error" in answers else []
    check("the NaN plug-in: doStep is fmi2Error with one line naming the controller: %s" % errors,
          len(errors) == 1 and "controller 0" in errors[0] and "nan" in errors[0] and "\n" not in errors[0],
          str(answers))
finish()
