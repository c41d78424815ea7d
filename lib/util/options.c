/* Defaults of every option struct: the one statement of them. The case reader's tables take them from
 * here (TD_CS_PRESET, lib/case/case_schema.h), and docs/case-format.md's key tables print them. */
#include "touchdown/options.h"

#include <math.h>
#include <string.h>

void td_contact_options_default(td_contact_options *o)
{
    memset(o, 0, sizeof *o);
    o->model = TD_CONTACT_CONSTRAINT;
    o->stiffness = 1.25e12;
    o->exponent = 1.0;
    o->damping = TD_DAMPING_NONE;
    o->damping_coefficient = 0.0;
}

void td_solver_options_default(td_solver_options *o)
{
    memset(o, 0, sizeof *o);
    o->rtol = 1e-6;
    o->atol = 1e-9;
    o->max_step = 0.0;
    o->initial_step = 0.0;
    o->free_flight = 1;
    o->max_order = 2; /* BDF2 is the highest A-stable order: the undamped shaft modes need it (docs/theory.md) */
    o->linear_solver = TD_LINSOL_KLU;
}

void td_sim_options_default(td_sim_options *o)
{
    memset(o, 0, sizeof *o);
    td_contact_options_default(&o->contact);
    td_solver_options_default(&o->solver);
    o->start = TD_START_ORBIT;
    o->t0 = 0.0;
}

void td_output_options_default(td_output_options *o)
{
    memset(o, 0, sizeof *o);
    o->sample_rate = 10000.0;
    o->node_count = 0;
    o->section_after = 0.5;
}

void td_modal_options_default(td_modal_options *o)
{
    memset(o, 0, sizeof *o);
    o->speed_min = 0.0;
    o->speed_max = 400.0;
    o->speed_steps = 41;
    o->mode_count = 8;
    o->response_speed_count = 0;
    o->operating_speed_min = NAN;
    o->operating_speed_max = NAN;
    o->response_node_count = 0;
}
