"""Bad input to an FMU through fmpy: each is fmi2Error (fmpy raises) with one line through the FMU's
logger naming what was wrong, and nothing crashes. Each case runs in its own process, which must
end normally (a crash is a signal, never an exit code) after freeing the instance.

    test_bad_inputs.py TOOL SOURCE_DIR BUILD_DIR FMU_BINARY
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from fmu_common import FMICallException, Instance, check, finish, pack  # noqa: E402
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated  # noqa: E402

H = 1e-4


def nan_input(inst):
    inst.set(["ambs[0].current_x"], [math.nan])
    inst.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)


def inf_input(inst):
    inst.set(["ambs[1].current_y"], [math.inf])
    inst.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)


def set_output(inst):
    inst.fmu.setReal([inst.vr["ambs[0].sensed_x"]], [1.0])


def unknown_reference(inst):
    inst.fmu.setReal([max(inst.vr.values()) + 1000], [1.0])


def wrong_time(inst):
    inst.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
    inst.fmu.doStep(currentCommunicationPoint=0.5, communicationStepSize=H)


def zero_step(inst):
    inst.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=0.0)


def unknown_category(inst):
    inst.fmu.setDebugLogging(True, ["logEvents", "logNothing"])


# name: (what it does to an FMU with current inputs, a word its message must hold)
STEPPING = {"NaN current input": (nan_input, "nan"), "infinite current input": (inf_input, "inf"),
            "setReal of an output": (set_output, "sensed_x"), "an unknown value reference": (unknown_reference, "no variable"),
            "doStep at a time that is not the FMU's": (wrong_time, "time"),
            "doStep of zero length": (zero_step, "step"),
            "an unknown log category": (unknown_category, "'logNothing' is no log category")}
PARAMETERS = {"negative clearance": ({"retainers[0].clearance": -1.0e-3}, "clearance"),
              "NaN speed": ({"speed": math.nan}, "speed"),
              "negative speed": ({"speed": -5.0}, "fmi2ExitInitializationMode: parameter speed = -5: must be >= 0")}


def status_queries(path):
    """FMI 2.0, 4.2.3: fmi2Terminated is fmi2OK and false, the last successful time the step's end."""
    inst = Instance(path)
    try:
        inst.start(0.0, 0.01)
        inst.fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=H)
        terminated, last = inst.fmu.getBooleanStatus(fmi2Terminated), inst.fmu.getRealStatus(fmi2LastSuccessfulTime)
        check("getBooleanStatus(fmi2Terminated): fmi2OK, false", terminated is False, str(terminated))
        check("getRealStatus(fmi2LastSuccessfulTime): the step's end", last == H, repr(last))
    except FMICallException as e:
        check("the status queries: fmi2OK", False, str(e))
    inst.free()


def child(kind, name, path):
    """One bad input in this process: print what the FMU said (JSON)."""
    out = {"raised": None, "messages": []}
    inst = None
    try:
        if kind == "stepping":
            inst = Instance(path)
            inst.start(0.0, 0.01)
            STEPPING[name][0](inst)
        elif kind == "parameter":
            inst = Instance(path)
            inst.start(0.0, 0.01, PARAMETERS[name][0])
        else:  # an FMU whose unpacked directory was spoiled, or a wrong GUID
            inst = Instance(path, unzipdir=sys.argv[5] if len(sys.argv) > 5 else None,
                            guid="{00000000-0000-0000-0000-000000000000}" if name == "wrong GUID" else None,
                            instantiate=False)
            inst.fmu.instantiate(callbacks=inst.callbacks)
            inst.start(0.0, 0.01)
    except FMICallException as e:
        out["raised"] = str(e)
    except Exception as e:  # fmpy: "Failed to instantiate model"
        out["raised"] = str(e)
    if inst is not None:
        out["messages"] = [m for s, m in inst.messages if s >= 3]  # fmi2Error and fmi2Fatal
        if inst.fmu.component:
            inst.fmu.fmi2FreeInstance(inst.fmu.component)
    print(json.dumps(out))


def judge(what, proc, word):
    if not check("%s: the process ends normally" % what, proc.returncode == 0,
                 "exit %d: %s" % (proc.returncode, proc.stderr[-600:])):
        return
    out = json.loads(proc.stdout.splitlines()[-1])
    msgs = out["messages"]
    check("%s: fmi2Error (%s)" % (what, out["raised"]), out["raised"] is not None)
    check("%s: one line through the logger: %s" % (what, msgs[0] if msgs else None),
          len(msgs) >= 1 and all("\n" not in m.strip() and m.strip() for m in msgs) and
          word.lower() in msgs[0].lower(), str(msgs))


def run_child(*args):
    return subprocess.run([sys.executable, os.path.abspath(__file__), "--child"] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True)


if len(sys.argv) > 1 and sys.argv[1] == "--child":
    child(*sys.argv[2:5])
    sys.exit(0)

tool, src = sys.argv[1:3]
with tempfile.TemporaryDirectory() as tmp:
    fmu = pack(tool, os.path.join(src, "cases", "paper-a-digital.cfg"), os.path.join(tmp, "Bad.fmu"), "current",
               ["end_time=0.01"])
    for name, (_, word) in STEPPING.items():
        judge(name, run_child("stepping", name, fmu), word)
    for name, (_, word) in PARAMETERS.items():
        judge("parameter: " + name, run_child("parameter", name, fmu), word)
    judge("wrong GUID", run_child("setup", "wrong GUID", fmu), "guid")
    status_queries(fmu)
    for spoil, word in [("resources/case.cfg", "case.cfg"), ("resources/touchdown-fmu.cfg", "touchdown-fmu.cfg")]:
        d = os.path.join(tmp, "spoiled-" + os.path.basename(spoil))
        with zipfile.ZipFile(fmu) as z:
            z.extractall(d)
        with open(os.path.join(d, spoil), "w") as f:
            f.write("this is { not a case\n")
        judge("a spoiled %s" % spoil, run_child("setup", "spoiled", fmu, d), word)
        shutil.rmtree(d)
finish()
