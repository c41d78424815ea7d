/*
 * touchdown/plugin.h - the plug-in controller ABI: an AMB controller in the user's own C code (the
 * code that will run on the DSP), run by the simulation at its sample instants exactly as a built-in
 * sampled controller (touchdown/controller.h): at sample k, t_k = t0 + k / sample_rate, it reads the
 * sensed displacements at t_k and returns the commands the amplifiers hold until t_{k+1}.
 *
 * A plug-in includes this header only and links nothing of touchdown. As a shared library it exports
 * one function, named TD_PLUGIN_ENTRY_NAME,
 *
 *     const td_plugin_controller *td_plugin_controller_entry(void);
 *
 * returning a table that lives as long as the library; a program linked with touchdown may instead
 * pass such a table to td_model_add_plugin_controller (touchdown/model.h). A case file names the
 * library (docs/case-format.md, `controllers[].plugin`).
 *
 * Versioning: TD_PLUGIN_ABI_VERSION rises whenever this header's types or calls change meaning; the
 * simulation refuses a table whose abi_version differs from its own, naming both, before it calls
 * any of its functions (abi_version stays the table's first member in every version). A plug-in
 * built against this header sets abi_version = TD_PLUGIN_ABI_VERSION.
 *
 * Life of an instance: td_sim_create makes two. A probe, stepped at k = 0 with xs = 0 and then,
 * reset before each, with xs = -2^-20 m on one input at a time, then freed: its commands per metre
 * (a linear law's direct gain) scale the integrator's tolerances, never the dynamics. Then the run's
 * own, stepped once per sample until td_sim_free frees it; reset when the recovery supervisor
 * switches to the controller (the incoming law starts from rest). k is the sample's index on the
 * run's grid, t = t0 + k / sample_rate, not a count of the calls: sample 0 at the start, but a
 * recovery pair's standby plug-in is first stepped at the switch's sample K > 0, and after a reset
 * k goes on from the grid, never back to 0 (it jumps over the samples the controller stood by). A
 * delay of d samples (td_plugin_spec) holds the command of step k from t_{k+d} on, 0 before.
 *
 * Signs and units (touchdown/dofs.h): sensed[j] is the displacement xs (m) of the sensor of input
 * axis j (positive along +x or +y); command[j] is the current command i (A) of the amplifier of
 * output axis j, whose force on the rotor is ki i, or, with TD_PLUGIN_FORCE, that force f = ki i
 * (N) itself. A PD plug-in that centres the rotor therefore returns i = -(kp xs + kd vs) with vs its
 * own estimate of the velocity. The amplifier lags, clips and slews the command as the case says,
 * as it does a built-in controller's. An AMB axis is numbered 2 amb + axis (axis 0: x, 1: y).
 *
 * Every call that can fail returns 0 on success, or nonzero with a one-line reason (no newline)
 * written into `message` (message_size bytes, NUL-terminated); the simulation stops with that
 * reason and the controller's name, and writes no result from that sample on. A command that is not
 * finite (NaN, inf) is a failure of the plug-in too. The calls are made from one thread per
 * instance; instances share nothing unless the plug-in makes them (two simulations of the same case,
 * as a sweep runs them, each create their own).
 */
#ifndef TOUCHDOWN_PLUGIN_H
#define TOUCHDOWN_PLUGIN_H

#ifdef __cplusplus
extern "C" {
#endif

/** The ABI this header describes. */
#define TD_PLUGIN_ABI_VERSION 1

/** The name of the function a plug-in library exports (a td_plugin_entry). */
#define TD_PLUGIN_ENTRY_NAME "td_plugin_controller_entry"

/** What a plug-in's step returns: the values of td_plugin_controller.output. */
enum td_plugin_output {
    TD_PLUGIN_CURRENT = 0, /**< current commands i, A (the force is ki i) */
    TD_PLUGIN_FORCE = 1    /**< force commands ki i, N (the simulation divides by ki) */
};

/** What the simulation tells a new instance (borrowed: valid during init only; copy what you keep). */
typedef struct td_plugin_setup {
    int abi_version;                    /**< the simulation's TD_PLUGIN_ABI_VERSION */
    const char *name;                   /**< the controller's name in the case (messages, events) */
    double sample_rate;                 /**< Hz: step is called at t0 + k / sample_rate */
    int n_inputs;                       /**< sensed displacements per sample */
    int n_outputs;                      /**< commands per sample */
    const int *input_axes;              /**< n_inputs AMB axes (2 amb + axis) whose sensors it reads */
    const int *output_axes;             /**< n_outputs AMB axes whose amplifiers it commands */
    int n_parameters;                   /**< the case's `parameters` (may be 0) */
    const char *const *parameter_names; /**< n_parameters names, as the case wrote them */
    const double *parameter_values;     /**< n_parameters values */
} td_plugin_setup;

/** The functions of a plug-in controller. */
typedef struct td_plugin_controller {
    int abi_version; /**< TD_PLUGIN_ABI_VERSION of the header the plug-in was built with */
    /** What step writes into command: TD_PLUGIN_CURRENT or TD_PLUGIN_FORCE. An int, not the enum:
     *  an enum's size is the compiler's choice (1 byte with -fshort-enums), a table's layout is not. */
    int output;
    /** A new instance at rest for `setup`; NULL on failure, with the reason in message (e.g. a
     *  missing or bad parameter, a number of axes it does not handle). */
    void *(*init)(const td_plugin_setup *setup, char *message, int message_size);
    /** Sample k at time t (s): sensed (n_inputs, m) in, command (n_outputs) out; every command
     *  must be written (one left unwritten is not finite: a failure). */
    int (*step)(void *instance, long k, double t, const double *sensed, double *command, char *message,
                int message_size);
    /** Back to the state init left it in (the probe between its steps; a switch of the recovery
     *  supervisor to this controller). */
    int (*reset)(void *instance, char *message, int message_size);
    /** Release the instance; accepts NULL. */
    void (*free)(void *instance);
} td_plugin_controller;

/** The type of the exported entry function TD_PLUGIN_ENTRY_NAME. */
typedef const td_plugin_controller *(*td_plugin_entry)(void);

/** Exports a plug-in's entry also when it is compiled with -fvisibility=hidden. */
#if defined(__GNUC__) || defined(__clang__)
#define TD_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define TD_PLUGIN_EXPORT
#endif

/** The entry a plug-in library defines (touchdown itself defines none: it looks it up with dlsym). */
TD_PLUGIN_EXPORT const td_plugin_controller *td_plugin_controller_entry(void);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_PLUGIN_H */
