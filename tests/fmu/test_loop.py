"""The closed loop through an independent importer: cases/paper-a-digital.cfg (case A, its AMBs' PD
sampled at 10 kHz with one sample of delay) packed as an FMU whose inputs are the AMB currents,
stepped by fmpy every 0.1 ms with the same PD written in Python (examples/fmu_pd_loop.py, from the
textbook's Tustin rule), against the built-in run of the case (touchdown run). To END = 0.16 s
(first contact at 0.105 s, then some 200 contact events) they agree on the first contact time, the
peak contact force and the event count within TOL below. The two compute the same law in another
order, so their currents differ in the last bits; the bouncing amplifies that until, some time
after END, one of them has a brief lift-off and return the other has not, and from there their
event counts differ: the test finds that time (from the built-in run's events file) and checks that
it comes after END.
The FMU with no inputs (the case's own PD inside), stepped by the same importer, agrees too.
Further, to LONG = 0.3 s, the sequences of impacts part, but not what bounds them: the peak contact
force stays within LONG_TOL of the built-in run's (the built-in run's own peak moves by less than 1e-5
relative with kp changed by 1e-10 to 1e-8 relative, by 2e-3 with atol 1000 times larger).

    test_loop.py TOOL SOURCE_DIR BUILD_DIR FMU_BINARY [--json FILE]    (the numbers as one JSON object into FILE, for docs/fmu.md)
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fmu_common import check, close, event_times, finish, free_run, native, pack, pd_loop  # noqa: E402

# The tolerances. The first contact comes before the two PDs' last-bit differences can move it (it
# is the same to the bit); the peak contact force moves by about 1e-6 relative (from the PDs'
# rounding, and from the communication points where the integrator stops): the tolerance is ten
# times that, a fifth of what it moves by over atol +-1 % (touchdown run --spread 5 of the case to
# 0.15 s: 4.5e-5); the contact events are counted exactly.
TOL = {"first_contact_time": 1e-9, "peak_normal_force": 1e-5, "events": 0}
END, H = 0.16, 1e-4
LONG, LONG_TOL = 0.3, 0.01

tool, src = sys.argv[1:3]
as_json = sys.argv[6] if len(sys.argv) > 6 and sys.argv[5] == "--json" else None
case = os.path.join(src, "cases", "paper-a-digital.cfg")
sets = ["end_time=%g" % END]
ref = native(tool, case, sets)
ref = {k: ref[k] for k in ("first_contact_time", "peak_normal_force", "events")}

with tempfile.TemporaryDirectory() as tmp:
    fmu = pack(tool, case, os.path.join(tmp, "PaperA.fmu"), "current", sets)
    loop, steps = pd_loop(fmu, END, H)
    inner = pack(tool, case, os.path.join(tmp, "PaperAInner.fmu"), "none", sets)
    own = free_run(inner, END, H)


def compare(name, got):
    for k, tol in TOL.items():
        ok = close(got[k], ref[k], atol=tol) if k == "first_contact_time" else \
            close(got[k], ref[k], rtol=tol) if k == "peak_normal_force" else got[k] == ref[k]
        check("%s: %s %r, built-in run %r (tolerance %g)" % (name, k, got[k], ref[k], tol), ok)


with tempfile.TemporaryDirectory() as tmp:
    fmu = pack(tool, case, os.path.join(tmp, "PaperALong.fmu"), "current", ["end_time=%g" % LONG])
    counts = []
    long_loop, _ = pd_loop(fmu, LONG, H, counts)
    long_ref = native(tool, case, ["end_time=%g" % LONG], os.path.join(tmp, "long.csv"))
    times = event_times(os.path.join(tmp, "long.events.csv"))
# the first communication point where the loop's event count is not the built-in run's
parting = next(((k + 1) * H for k, c in enumerate(counts) if c != sum(1 for t in times if t <= (k + 1) * H)), None)
check("the event counts part after END = %g s (at %s s)" % (END, parting), parting is None or parting > END)
check("to %g s: the peak contact force %r within %g of the built-in run's %r" % (
    LONG, long_loop["peak_normal_force"], LONG_TOL, long_ref["peak_normal_force"]),
    close(long_loop["peak_normal_force"], long_ref["peak_normal_force"], rtol=LONG_TOL))
compare("fmpy loop with the Python PD", loop)
compare("fmpy stepping the FMU with the case's own PD", own)
if as_json:
    with open(as_json, "w") as f:
        json.dump({"case": "cases/paper-a-digital.cfg", "end_time": END, "communication_step": H,
                   "steps": steps, "tolerance": TOL, "native": ref, "fmpy_python_pd": loop,
                   "fmpy_inputs_none": own, "long": {"end_time": LONG, "tolerance": LONG_TOL, "events_part_at": parting,
                                                     "native_peak": long_ref["peak_normal_force"],
                                                     "fmpy_python_pd_peak": long_loop["peak_normal_force"]}},
                  f, indent=1, sort_keys=True)
finish()
