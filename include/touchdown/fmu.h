/*
 * touchdown/fmu.h - touchdown as a Functional Mock-up Unit for co-simulation (FMI 2.0): the case's
 * rotor, AMBs and retainers stepped by an importer (Simulink, OpenModelica, Dymola, fmpy) that may
 * close the loop with its own controller. `touchdown fmu CASE -o NAME.fmu` packs one
 * (docs/fmu.md); the FMU's binary reads at instantiation what td_fmu_stage wrote.
 */
#ifndef TOUCHDOWN_FMU_H
#define TOUCHDOWN_FMU_H

#include "touchdown/error.h"
#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What the FMU's inputs drive. */
typedef enum td_fmu_inputs {
    TD_FMU_INPUTS_NONE = 0,    /**< none: the case's own AMB laws and controllers run inside */
    TD_FMU_INPUTS_CURRENT = 1, /**< a current command per AMB axis (A), through the amplifier */
    TD_FMU_INPUTS_FORCE = 2    /**< a control force per AMB axis (N), held (td_sim_set_amb_control) */
} td_fmu_inputs;

/** Write the unpacked FMU of the case at case_path (with td_case_load's overrides) into the
 *  existing empty directory dir: modelDescription.xml (modelIdentifier model_identifier, a C
 *  identifier) and resources/ with all the binary reads at instantiation; everything but
 *  binaries/. TD_ERR_PARSE for a bad case, TD_ERR_IO for a directory that cannot be written. */
TD_API td_status td_fmu_stage(const char *case_path, const char *const *overrides, int n_overrides,
                              td_fmu_inputs inputs, const char *model_identifier, const char *dir, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_FMU_H */
