#!/usr/bin/env python3
"""Close the loop of a touchdown FMU with your own controller in Python, through fmpy (pip install fmpy).

    touchdown fmu cases/paper-a-digital.cfg --inputs current --set end_time=0.16 -o PaperA.fmu
    python3 fmu_pd_loop.py PaperA.fmu [--step 1e-4] [--end 0.16] [--kp 1e4] [--kd 40] [--filter 2000] [--delay 1]

Every --step seconds (the communication step: the controller's sample time) it reads each AMB
axis's sensed displacement, computes the axis's current with a PD, kp + kd s / (1 + s / (2 pi
filter)), discretised by Tustin's rule and applied --delay samples later (what a DSP does), sets
it as the FMU's input and steps the FMU; then it prints the run's answers as the FMU gives them
(first contact time, peak contact force, events). The defaults are cases/paper-a-digital.cfg's
own digital PD, so the answers match `touchdown run` of that case (docs/fmu.md says how closely).
Replace PD with your controller: it sees what the sensors see and returns currents.
"""
import argparse
import math
import shutil

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


# cases/paper-a-digital.cfg's digital PD: kp A/m, kd A s/m, the derivative filter's corner Hz, samples
# of delay (its controllers[0]); the defaults below
PAPER_A_DIGITAL = {"kp": 1.0e4, "kd": 40.0, "fc": 2000.0, "delay": 1}


class PD:
    """kp + kd s / (1 + s / (2 pi fc)) on the error e = -xs (the reference is the centre), by
    Tustin's rule s = (2/T)(1 - z^-1)/(1 + z^-1) at the sample time T; the current of sample k is
    applied `delay` samples later."""

    def __init__(self, kp, kd, fc, T, delay):
        a, wf = 2.0 / T, 2.0 * math.pi * fc
        self.kp, self.b, self.c = kp, kd * wf * a / (a + wf), (wf - a) / (a + wf)
        self.e = self.d = 0.0
        self.queue = [0.0] * delay

    def step(self, xs):
        e = -xs
        self.d = self.b * (e - self.e) - self.c * self.d  # the filtered derivative's recursion
        self.e = e
        self.queue.append(self.kp * e + self.d)
        return self.queue.pop(0)


def open_fmu(path, callbacks=None):
    """An instantiated co-simulation instance of the FMU at path, its description and its value
    references by name."""
    md = read_model_description(path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=extract(path), modelIdentifier=md.coSimulation.modelIdentifier,
                    instanceName="touchdown")
    fmu.instantiate(callbacks=callbacks)
    return fmu, md, {v.name: v.valueReference for v in md.modelVariables}


def answers(fmu, vr):
    """The run's answers so far, as the FMU gives them; the first contact time None before one."""
    occurred = fmu.getBoolean([vr["contact_occurred"]])[0]
    return {"first_contact_time": fmu.getReal([vr["first_contact_time"]])[0] if occurred else None,
            "peak_contact_force": fmu.getReal([vr["peak_contact_force"]])[0],
            "events": fmu.getInteger([vr["events"]])[0]}


def run(path, end, step, kp, kd, fc, delay, callbacks=None, after_step=None):
    """The loop: the FMU's answers at `end` and the number of steps taken; after_step(k, fmu, vr), if
    given, is called after each step k (which ends at (k + 1) step)."""
    fmu, md, vr = open_fmu(path, callbacks)
    # the AMB axes: inputs ambs[i].current_x and _y, each with its sensor ambs[i].sensed_x or _y
    axes = [v.name.split(".current_") for v in md.modelVariables if v.causality == "input" and ".current_" in v.name]
    sensed = [vr["%s.sensed_%s" % (amb, axis)] for amb, axis in axes]
    currents = [vr["%s.current_%s" % (amb, axis)] for amb, axis in axes]
    laws = [PD(kp, kd, fc, step, delay) for _ in axes]
    fmu.setupExperiment(startTime=0.0, stopTime=end)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    n = int(round(end / step))
    for k in range(n):
        xs = fmu.getReal(sensed)
        fmu.setReal(currents, [law.step(x) for law, x in zip(laws, xs)])
        fmu.doStep(currentCommunicationPoint=k * step, communicationStepSize=step)
        if after_step:
            after_step(k, fmu, vr)
    out = answers(fmu, vr)
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(fmu.unzipDirectory, ignore_errors=True)  # what extract() unpacked
    return out, n


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("fmu")
    p.add_argument("--step", type=float, default=1e-4, help="communication step = sample time, s")
    p.add_argument("--end", type=float, default=0.16, help="s")
    d = PAPER_A_DIGITAL
    p.add_argument("--kp", type=float, default=d["kp"], help="A/m")
    p.add_argument("--kd", type=float, default=d["kd"], help="A s/m")
    p.add_argument("--filter", type=float, default=d["fc"], help="the derivative's filter corner, Hz")
    p.add_argument("--delay", type=int, default=d["delay"], help="samples of computation delay")
    a = p.parse_args()
    out, n = run(a.fmu, a.end, a.step, a.kp, a.kd, a.filter, a.delay)
    print("%d steps of %g s" % (n, a.step))
    for k, v in out.items():
        print("%-20s %s" % (k, "n/a (no contact)" if v is None else "%.9g" % v))


if __name__ == "__main__":
    main()
