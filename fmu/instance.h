/*
 * One instance of touchdown's FMU (FMI 2.0 co-simulation): the case of its resources, the values of
 * its variables, the simulation and the state machine of FMI 2.0, 4.2.4. fmi2.c holds the entry
 * points, which check the state and hand over to the functions here; every failure is one line
 * through the importer's logger and fmi2Error, never a crash.
 */
#ifndef TD_FMU_INSTANCE_H
#define TD_FMU_INSTANCE_H

#include "fmi2Functions.h"
#include "fmu/fmu_internal.h"
#include "touchdown/touchdown.h"

/* FMI 2.0's states of a co-simulation slave (4.2.4), as far as they change what a call may do. */
typedef enum td_fmu_state {
    TD_FMU_INSTANTIATED = 0, /* parameters and inputs may be set */
    TD_FMU_INITIALISING = 1, /* between fmi2EnterInitializationMode and fmi2ExitInitializationMode */
    TD_FMU_STEPPING = 2,     /* inputs may be set, fmi2DoStep runs */
    TD_FMU_TERMINATED = 3,   /* values may be read */
    TD_FMU_FAILED = 4        /* an fmi2Error: values may be read, then fmi2Reset or fmi2FreeInstance */
} td_fmu_state;

typedef struct td_fmu_instance {
    fmi2CallbackLogger logger; /* may be NULL */
    fmi2ComponentEnvironment env;
    char *name;
    int logging;       /* fmi2Instantiate's or fmi2SetDebugLogging's loggingOn */
    unsigned log_mask; /* the categories logged when logging is on (a bit per td_fmu_log_category) */
    td_fmu_state state;
    td_fmu_settings settings;
    td_fmu_var *var; /* n_var, vr = index */
    int n_var;
    double *value;                  /* per variable: a parameter's or an input's value now */
    int inputs_held;                /* the input values are those the simulation holds */
    double t_start, t_stop, t_comm; /* t_comm: the next doStep's communication point */
    int has_stop;
    td_sim *sim; /* NULL until it is made at initialisation */
    double *q;   /* the simulation's displacements, td_sim_dof_count of them: made with the simulation */
} td_fmu_instance;

/* One line through the logger in the category of its status (td_fmu_log_category_of): an error's
 * line always, the others when logging is on and their category is chosen; returns status. */
fmi2Status td_fmu_log(const td_fmu_instance *in, fmi2Status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* fmi2SetDebugLogging: logging on or off, and the categories logged (none named: all of them); an
 * unknown category is fmi2Error, logged, and changes nothing. */
fmi2Status td_fmu_instance_set_logging(td_fmu_instance *in, int on, size_t n, const fmi2String categories[]);

/* A new instance from the resources at the URI `resources` (file:///...) after checking the guid;
 * NULL (logged) on failure. */
td_fmu_instance *td_fmu_instance_create(const char *name, const char *guid, const char *resources,
                                        fmi2CallbackLogger logger, fmi2ComponentEnvironment env, int logging);
void td_fmu_instance_free(td_fmu_instance *in);
/* Back to the instantiated state with the start values (fmi2Reset). */
void td_fmu_instance_reset(td_fmu_instance *in);
/* The simulation made from the case with the parameters set, at t_start, the inputs applied; `what`
 * (the FMI function that asks for it) opens a failure's line. */
fmi2Status td_fmu_instance_start(td_fmu_instance *in, const char *what);
fmi2Status td_fmu_instance_step(td_fmu_instance *in, double t, double h);
fmi2Status td_fmu_instance_set_real(td_fmu_instance *in, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]);
/* Variable vr's value now as a double (Integer and Boolean ones as 0/1/counts): *out. */
fmi2Status td_fmu_instance_get(td_fmu_instance *in, fmi2ValueReference vr, td_fmu_type type, double *out);

#endif
