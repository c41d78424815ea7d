/*
 * The once-per-revolution (stroboscopic, Poincare) section of a simulation: the radial position
 * of every retainer's node each time the rotor's spin angle passes a multiple of 2 pi, at the
 * exact crossing time, from the same interpolant that gives td_run its output samples (IDA's, or
 * the closed-form flight's). Sampling never moves the simulation: its steps, events and totals
 * are those of a run without the section. Its start and its crossings' times are the run's clock
 * (the simulation's plus the time leapt, td_sim_monitor.leapt). Inside the library only (td_run, run.h).
 */
#ifndef TD_SIM_SECTION_H
#define TD_SIM_SECTION_H

#include "touchdown/error.h"
#include "touchdown/sim.h"

/* Take the section from time t_from on, keeping the last `capacity` (> 0) crossings. Replaces a
 * section begun before. TD_ERR_INVALID, TD_ERR_NOMEM. */
td_status td_sim_section_begin(td_sim *sim, double t_from, int capacity, td_error *err);
/* Stop taking the section and free it; accepts a sim without one. */
void td_sim_section_end(td_sim *sim);
/* Crossings since t_from (also those no longer kept); 0 without a section. */
long td_sim_section_count(const td_sim *sim);
/* The kept crossings, oldest first, at most `max`: their times into t and the radius
 * sqrt(x^2 + y^2) of retainer `retainer`'s node relative to its retainer (m) into r (either may be
 * NULL). Returns how many were written. */
int td_sim_section_read(const td_sim *sim, int retainer, double *t, double *r, int max);

#endif /* TD_SIM_SECTION_H */
