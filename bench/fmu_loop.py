"""One FMU loop of bench/fmu.sh, timed: the FMU at PATH stepped every STEP s to END by fmpy, either
closed by the Python PD of examples/fmu_pd_loop.py (MODE pd: inputs AMB currents) or with the
FMU's own controllers inside (MODE none: no inputs). Prints one JSON object: the CPU seconds of
this process from instantiation to freeing the instance (not Python's start nor fmpy's import),
the steps and the FMU's answers.

    fmu_loop.py PATH pd|none END STEP      (run by the fmpy environment's python)
"""
import json
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))
import fmu_pd_loop  # noqa: E402

path, mode, end, step = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
t0 = time.process_time()
if mode == "pd":
    d = fmu_pd_loop.PAPER_A_DIGITAL
    answers, n = fmu_pd_loop.run(path, end, step, d["kp"], d["kd"], d["fc"], d["delay"])
else:
    fmu, md, vr = fmu_pd_loop.open_fmu(path)
    fmu.setupExperiment(startTime=0.0, stopTime=end)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    n = int(round(end / step))
    for k in range(n):
        fmu.doStep(currentCommunicationPoint=k * step, communicationStepSize=step)
    answers = fmu_pd_loop.answers(fmu, vr)
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(fmu.unzipDirectory, ignore_errors=True)
print(json.dumps({"cpu": time.process_time() - t0, "steps": n, "answers": answers}))
