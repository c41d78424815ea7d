"""What the FMU tests share: their checks, packing an FMU with the tool, running it through fmpy (the
independent importer, from PyPI: tests/fmu/requirements.txt) and a native run of the same case.
Run by the venv's python (tests/fmu/make_venv.sh), never by the system's."""
import json
import os
import shutil
import subprocess
import sys

from fmpy import calloc, extract, free, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                       fmi2CallbackFunctions, fmi2CallbackLoggerTYPE)
from fmpy.logging import addLoggerProxy
from ctypes import byref

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples"))
import fmu_pd_loop  # noqa: E402

_counts = {"checks": 0, "fails": 0}


def check(what, ok, detail=""):
    """One check: an "ok:" or "FAIL:" line, counted (as tests/cli/common.sh does)."""
    _counts["checks"] += 1
    if ok:
        print("ok:   %s" % what, flush=True)
    else:
        _counts["fails"] += 1
        print("FAIL: %s%s" % (what, (": " + detail) if detail else ""), flush=True)
    return ok


def finish():
    """The counts, then exit 0 if every check passed; a script that ran no check fails."""
    c = _counts
    print("%d passed, %d failed" % (c["checks"] - c["fails"], c["fails"]))
    if c["checks"] == 0:
        print("FAIL: no check ran")
        sys.exit(1)
    sys.exit(0 if c["fails"] == 0 else 1)


def tool_fmu(tool, case, out, inputs="current", sets=(), cwd=None):
    """touchdown fmu CASE -o OUT --inputs INPUTS --set ...: the finished process."""
    args = [tool, "fmu", "-q", "--inputs", inputs, "-o", out]
    for s in sets:
        args += ["--set", s]
    return subprocess.run(args + [case], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True)


def pack(tool, case, out, inputs="current", sets=()):
    """Pack an FMU; stop the script when the tool fails (nothing else can be checked)."""
    proc = tool_fmu(tool, case, out, inputs, sets)
    if not check("touchdown fmu %s --inputs %s %s" % (os.path.basename(case), inputs, " ".join(sets)),
                 proc.returncode == 0 and os.path.isfile(out), "exit %d: %s" % (proc.returncode, proc.stderr.strip())):
        finish()
    return out


def native(tool, case, sets=(), events_csv=None):
    """touchdown run of the case without files (or with only its CSV, for its events file, when
    events_csv names it): its JSON summary's statistics."""
    args = [tool, "run", "-q", "--json", "--hdf5", "", "--csv", events_csv or ""]
    for s in sets:
        args += ["--set", s]
    proc = subprocess.run(args + [case], stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if not check("touchdown run %s %s" % (os.path.basename(case), " ".join(sets)), proc.returncode == 0,
                 proc.stderr.strip()):
        finish()
    return json.loads(proc.stdout)["stats"]


def event_times(events_csv):
    """The times of the events in a run's events file (docs/output-format.md), in order."""
    with open(events_csv) as f:
        lines = [line for line in f if not line.startswith("#")]
    return [float(line.split(",")[0]) for line in lines[1:] if line.strip()]


class Instance:
    """One co-simulation instance of an FMU through fmpy, its log messages kept (one per line)."""

    def __init__(self, path, unzipdir=None, guid=None, instantiate=True):
        self.md = read_model_description(path, validate=True)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.own_dir = unzipdir is None  # unpacked here: removed by free
        self.dir = unzipdir or extract(path)
        self.messages = []
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(byref(self.callbacks))  # the FMU's variadic logger, formatted for Python
        self.fmu = FMU2Slave(guid=guid or self.md.guid, unzipDirectory=self.dir,
                             modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName="test")
        if instantiate:
            self.fmu.instantiate(callbacks=self.callbacks, loggingOn=False)

    def _log(self, env, name, status, category, message):
        self.messages.append((status, message.decode("utf-8", "replace")))

    def start(self, t0=0.0, stop=None, parameters=None):
        self.fmu.setupExperiment(startTime=t0, stopTime=stop)
        self.fmu.enterInitializationMode()
        for name, value in (parameters or {}).items():
            self.set([name], [value])
        self.fmu.exitInitializationMode()

    def get(self, names):
        out = []
        for n in names:
            kind = self.types[n]
            vr = [self.vr[n]]
            out.append(self.fmu.getReal(vr)[0] if kind == "Real" else self.fmu.getInteger(vr)[0]
                       if kind == "Integer" else bool(self.fmu.getBoolean(vr)[0]))
        return out

    def set(self, names, values):
        self.fmu.setReal([self.vr[n] for n in names], [float(v) for v in values])

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        if self.own_dir:
            shutil.rmtree(self.dir, ignore_errors=True)


def step_to(inst, end, h):
    """Step the started instance from 0 every h s to `end` (communication points k h, exactly as an
    importer computes them); an fmi2Error raises FMICallException. The number of steps."""
    n = int(round(end / h))
    for k in range(n):
        inst.fmu.doStep(currentCommunicationPoint=k * h, communicationStepSize=h)
    return n


def free_run(path, end, h):
    """The FMU at `path` with no inputs (the case's own controllers inside), stepped every h s to `end`:
    its answers."""
    inst = Instance(path)
    inst.start(0.0, end)
    step_to(inst, end, h)
    out = results(inst)
    inst.free()
    return out


def child_main(run):
    """In a script run as `SCRIPT --child FMU` (by fresh_process): print run(FMU) as JSON and exit."""
    if len(sys.argv) == 3 and sys.argv[1] == "--child":
        print(json.dumps(run(sys.argv[2])))
        sys.exit(0)


def fresh_process(script, fmu, tmp, ld):
    """`script --child FMU` in a fresh process, in tmp, its environment holding no library path (PATH
    /usr/bin:/bin, HOME tmp), its dynamic loader's log into ld.PID (LD_DEBUG=libs): checks that it ended
    normally; its answers (child_main's JSON, None if it failed) and the libraries its loader
    initialised."""
    env = {"PATH": "/usr/bin:/bin", "HOME": tmp, "LD_DEBUG": "libs", "LD_DEBUG_OUTPUT": ld}
    proc = subprocess.run([sys.executable, os.path.abspath(script), "--child", fmu], cwd=tmp, env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    check("the FMU runs in a fresh process with no library path that ends normally (exit 0)", proc.returncode == 0,
          "exit %d: %s" % (proc.returncode, proc.stderr[-800:]))
    loaded = []
    for name in os.listdir(os.path.dirname(ld)):
        if name.startswith(os.path.basename(ld) + "."):
            with open(os.path.join(os.path.dirname(ld), name)) as f:
                loaded += [l.split("calling init:")[1].strip() for l in f if "calling init:" in l]
    return (json.loads(proc.stdout.splitlines()[-1]) if proc.returncode == 0 else None), loaded


def results(inst):
    """The run's answers as the FMU gives them (examples/fmu_pd_loop.py reads them), under the names of
    the native run's statistics."""
    out = fmu_pd_loop.answers(inst.fmu, inst.vr)
    out["peak_normal_force"] = out.pop("peak_contact_force")
    return out


def pd_loop(path, end, h, events=None):
    """The FMU (inputs: AMB currents) in a loop closed by cases/paper-a-digital.cfg's PD per AMB axis
    in Python, stepped every h s to `end`: examples/fmu_pd_loop.py, the loop docs/fmu.md shows. Its
    answers under the names of the native run's statistics, and the number of steps; the list
    `events`, if given, receives the event count after each step."""
    d = fmu_pd_loop.PAPER_A_DIGITAL
    after = (lambda k, fmu, vr: events.append(fmu.getInteger([vr["events"]])[0])) if events is not None else None
    answers, n = fmu_pd_loop.run(path, end, h, d["kp"], d["kd"], d["fc"], d["delay"], after_step=after)
    answers["peak_normal_force"] = answers.pop("peak_contact_force")
    return answers, n


def close(a, b, rtol=0.0, atol=0.0):
    return a is not None and b is not None and abs(a - b) <= atol + rtol * max(abs(a), abs(b))


__all__ = ["check", "finish", "tool_fmu", "pack", "native", "event_times", "Instance", "step_to", "free_run", "child_main",
           "fresh_process", "results", "pd_loop", "close", "FMICallException"]
