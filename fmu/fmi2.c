/*
 * The FMI 2.0 co-simulation entry points of touchdown's FMU (fmi2Functions.h, the standard's own
 * header): each checks that its call is allowed in the instance's state (FMI 2.0, 4.2.4) and hands
 * over to instance.c. What this FMU does not offer (FMU states, directional derivatives, input
 * derivatives, asynchronous steps; modelDescription.xml says so) is fmi2Error with its reason.
 */
#include "fmu/instance.h"

#include <math.h>
#include <stdlib.h>

/* The instance, when the call `what` is allowed in its state (a bit per td_fmu_state in `allowed`);
 * else NULL, logged. */
static td_fmu_instance *allowed(fmi2Component c, unsigned allowed_states, const char *what)
{
    td_fmu_instance *in = c;
    if (!in)
        return NULL;
    if (!(allowed_states & (1u << in->state))) {
        td_fmu_log(in, fmi2Error, "%s: not allowed in this state of the FMU", what);
        return NULL;
    }
    return in;
}

#define S(x) (1u << (x))
#define ANY                                                                                                            \
    (S(TD_FMU_INSTANTIATED) | S(TD_FMU_INITIALISING) | S(TD_FMU_STEPPING) | S(TD_FMU_TERMINATED) | S(TD_FMU_FAILED))

const char *fmi2GetTypesPlatform(void)
{
    return fmi2TypesPlatform;
}

const char *fmi2GetVersion(void)
{
    return fmi2Version;
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    td_fmu_instance *in = allowed(c, ANY, "fmi2SetDebugLogging");
    if (!in)
        return fmi2Error;
    return td_fmu_instance_set_logging(in, loggingOn != fmi2False, nCategories, categories);
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation, const fmi2CallbackFunctions *functions,
                              fmi2Boolean visible, fmi2Boolean loggingOn)
{
    fmi2CallbackLogger logger = functions ? functions->logger : NULL;
    fmi2ComponentEnvironment env = functions ? functions->componentEnvironment : NULL;
    (void)visible;
    if (fmuType != fmi2CoSimulation) {
        if (logger)
            logger(env, instanceName, fmi2Error, "logStatusError", "%s",
                   "fmi2Instantiate: this FMU is for co-simulation only");
        return NULL;
    }
    return td_fmu_instance_create(instanceName, fmuGUID, fmuResourceLocation, logger, env, loggingOn != fmi2False);
}

void fmi2FreeInstance(fmi2Component c)
{
    td_fmu_instance_free(c);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    td_fmu_instance *in = allowed(c, S(TD_FMU_INSTANTIATED), "fmi2SetupExperiment");
    (void)toleranceDefined, (void)tolerance; /* the case's solver tolerances hold */
    if (!in)
        return fmi2Error;
    if (!isfinite(startTime) || (stopTimeDefined && !(stopTime > startTime)))
        return td_fmu_log(in, fmi2Error,
                          "fmi2SetupExperiment: start %g and stop %g: need a finite start before the stop", startTime,
                          stopTime);
    in->t_start = in->t_comm = startTime;
    in->has_stop = stopTimeDefined != fmi2False;
    in->t_stop = stopTime;
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    td_fmu_instance *in = allowed(c, S(TD_FMU_INSTANTIATED), "fmi2EnterInitializationMode");
    if (!in)
        return fmi2Error;
    in->state = TD_FMU_INITIALISING;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    td_fmu_instance *in = allowed(c, S(TD_FMU_INITIALISING), "fmi2ExitInitializationMode");
    if (!in)
        return fmi2Error;
    if (!in->sim && td_fmu_instance_start(in, "fmi2ExitInitializationMode") != fmi2OK) {
        in->state = TD_FMU_FAILED;
        return fmi2Error;
    }
    in->state = TD_FMU_STEPPING;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    td_fmu_instance *in = allowed(c, S(TD_FMU_STEPPING) | S(TD_FMU_FAILED), "fmi2Terminate");
    if (!in)
        return fmi2Error;
    in->state = TD_FMU_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    td_fmu_instance *in = allowed(c, ANY, "fmi2Reset");
    if (!in)
        return fmi2Error;
    td_fmu_instance_reset(in);
    return fmi2OK;
}

/* Get values of one type; a failure leaves the rest unread. */
static fmi2Status get_values(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, td_fmu_type type, fmi2Real *r,
                             fmi2Integer *n, fmi2Boolean *b)
{
    td_fmu_instance *in = allowed(c, ANY, "fmi2Get");
    size_t i;
    if (!in)
        return fmi2Error;
    for (i = 0; i < nvr; i++) {
        double x;
        if (td_fmu_instance_get(in, vr[i], type, &x) != fmi2OK)
            return fmi2Error;
        if (r)
            r[i] = x;
        else if (n)
            n[i] = (fmi2Integer)x;
        else
            b[i] = x != 0.0 ? fmi2True : fmi2False;
    }
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[])
{
    return get_values(c, vr, nvr, TD_FMU_REAL, value, NULL, NULL);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Integer value[])
{
    return get_values(c, vr, nvr, TD_FMU_INTEGER, NULL, value, NULL);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Boolean value[])
{
    return get_values(c, vr, nvr, TD_FMU_BOOLEAN, NULL, NULL, value);
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2String value[])
{
    td_fmu_instance *in = allowed(c, ANY, "fmi2GetString");
    (void)vr, (void)value;
    if (!in)
        return fmi2Error;
    return nvr == 0 ? fmi2OK : td_fmu_log(in, fmi2Error, "fmi2GetString: the FMU has no String variable");
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[])
{
    td_fmu_instance *in =
        allowed(c, S(TD_FMU_INSTANTIATED) | S(TD_FMU_INITIALISING) | S(TD_FMU_STEPPING), "fmi2SetReal");
    if (!in)
        return fmi2Error;
    return td_fmu_instance_set_real(in, vr, nvr, value);
}

/* The FMU has no Integer, Boolean or String variable that may be set. */
static fmi2Status set_none(fmi2Component c, size_t nvr, const char *what)
{
    td_fmu_instance *in = allowed(c, ANY, what);
    if (!in)
        return fmi2Error;
    return nvr == 0 ? fmi2OK : td_fmu_log(in, fmi2Error, "%s: the FMU has no such variable that may be set", what);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Integer value[])
{
    (void)vr, (void)value;
    return set_none(c, nvr, "fmi2SetInteger");
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Boolean value[])
{
    (void)vr, (void)value;
    return set_none(c, nvr, "fmi2SetBoolean");
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2String value[])
{
    (void)vr, (void)value;
    return set_none(c, nvr, "fmi2SetString");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint, fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    td_fmu_instance *in = allowed(c, S(TD_FMU_STEPPING), "fmi2DoStep");
    (void)noSetFMUStatePriorToCurrentPoint;
    if (!in)
        return fmi2Error;
    if (td_fmu_instance_step(in, currentCommunicationPoint, communicationStepSize) != fmi2OK) {
        in->state = TD_FMU_FAILED;
        return fmi2Error;
    }
    return fmi2OK;
}

/* A capability modelDescription.xml says the FMU lacks. */
static fmi2Status unsupported(fmi2Component c, const char *what)
{
    td_fmu_instance *in = c;
    if (in)
        td_fmu_log(in, fmi2Error, "%s: not supported by this FMU (see its modelDescription.xml)", what);
    return fmi2Error;
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2GetFMUstate");
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2SetFMUstate");
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2FreeFMUstate");
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)FMUstate, (void)size;
    return unsupported(c, "fmi2SerializedFMUstateSize");
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte serializedState[], size_t size)
{
    (void)FMUstate, (void)serializedState, (void)size;
    return unsupported(c, "fmi2SerializeFMUstate");
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[], size_t size,
                                   fmi2FMUstate *FMUstate)
{
    (void)FMUstate, (void)serializedState, (void)size;
    return unsupported(c, "fmi2DeSerializeFMUstate");
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown, (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr, (void)nvr, (void)order, (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives");
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    return unsupported(c, "fmi2CancelStep");
}

/* A status query of kind s (FMI 2.0, 4.2.3): the instance when the call is allowed and value is
 * there; NULL, logged, otherwise. */
static td_fmu_instance *status_query(fmi2Component c, const void *value, const char *what)
{
    td_fmu_instance *in = allowed(c, ANY, what);
    if (in && !value) {
        td_fmu_log(in, fmi2Error, "%s: value is NULL", what);
        return NULL;
    }
    return in;
}

/* A status this FMU cannot give: fmi2Discard, as 4.2.3 says ("If a status is required which cannot
 * be retrieved by the slave it returns fmi2Discard"). Its steps are synchronous (no fmi2Pending, so
 * no fmi2DoStepStatus nor fmi2PendingStatus) and the kinds of another type have no value here. */
static fmi2Status no_such_status(td_fmu_instance *in, const char *what, fmi2StatusKind s)
{
    return td_fmu_log(in, fmi2Discard, "%s: status kind %d has no value in this FMU (its steps never pend)", what,
                      (int)s);
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    td_fmu_instance *in = status_query(c, value, "fmi2GetStatus");
    return in ? no_such_status(in, "fmi2GetStatus", s) : fmi2Error;
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    td_fmu_instance *in = status_query(c, value, "fmi2GetRealStatus");
    if (!in)
        return fmi2Error;
    if (s != fmi2LastSuccessfulTime)
        return no_such_status(in, "fmi2GetRealStatus", s);
    *value = in->sim ? in->t_comm : in->t_start; /* the end of the last completed communication step */
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    td_fmu_instance *in = status_query(c, value, "fmi2GetIntegerStatus");
    return in ? no_such_status(in, "fmi2GetIntegerStatus", s) : fmi2Error;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    td_fmu_instance *in = status_query(c, value, "fmi2GetBooleanStatus");
    if (!in)
        return fmi2Error;
    if (s != fmi2Terminated)
        return no_such_status(in, "fmi2GetBooleanStatus", s);
    *value = fmi2False; /* the FMU never asks to end the run: its doStep gives fmi2OK or fmi2Error */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    td_fmu_instance *in = status_query(c, value, "fmi2GetStringStatus");
    return in ? no_such_status(in, "fmi2GetStringStatus", s) : fmi2Error;
}
