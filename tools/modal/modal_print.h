/* Printing of modal results shared by `touchdown modal` and `touchdown info`. */
#ifndef TD_TOOLS_MODAL_PRINT_H
#define TD_TOOLS_MODAL_PRINT_H

#include "touchdown/modal.h"
#include "touchdown/modal_output.h"
#include "touchdown/options.h"
#include "touchdown/system.h"

#include <stdio.h>

/* Table of the first `count` vibration modes with `digits` significant digits; returns how many
 * near-critically damped pairs (AMB lags) were left out. */
int td_print_modes(FILE *f, const td_modal *modes, int count, int digits);
/* The overdamped roots (near-critically damped pairs and real eigenvalues), one line labelled by
 * what in `model` gives them; then how many roots were rounding of zero, if any. */
void td_print_overdamped(FILE *f, const td_modal *modes, const td_model *model);
/* "stable", "marginally stable (undamped modes)" or "UNSTABLE", judged against round-off. */
const char *td_stability_word(const td_modal *modes);
/* The loop analysis (touchdown/modal.h, td_loop_compute): stability, and per controlled axis the
 * peak sensitivity, its frequency and ISO 14839-3 zone. */
void td_print_loop(FILE *f, const td_loop *l);
/* td_loop_json's object and a newline (l NULL: no analysis, every answer null); 1 when out of memory. */
int td_print_loop_json(FILE *f, const td_loop *l);
/* One line on a reduced system (its boundary DOFs and kept modes); nothing for a full one. */
void td_print_reduction(FILE *f, const td_system *sys);
/* The reduced system's error against the full model of the same machine: the frequencies of the
 * vibration modes below the cut-off at `speed`, and the unbalance response at the retainer and
 * AMB (sensor) nodes at each of the response speeds (none: at `speed`). Said and skipped when the
 * full model is too large for a quick dense solve. Returns 0, or 1 when the comparison failed
 * (said on stderr). */
int td_print_reduction_error(FILE *f, const td_system *red, double speed, const double *response_speeds, int n_speeds);

/* The API 617 unbalance response report of a case (api617_report.c). */
typedef struct td_modal_api617_results {
    td_sweep *sweep;               /* NULL without unbalances */
    double *amb;                   /* static reactions, 2 per AMB */
    double *bearing;               /* 2 per plain bearing */
    int reactions_ok;              /* 0: the static state was refused (a free rotor, sampled controllers) */
    int *zones;                    /* ISO 14839-2 zone per speed and AMB sensor (td_sweep_sensor_zones); NULL: none */
    double c_min;                  /* m, their C_min */
    int gravity;                   /* 0: the case has no gravity (the reactions are NaN, "no gravity in the case") */
    td_clearance_check *clearance; /* API 617's amplitude check, one per retainer; NULL without a sweep */
} td_modal_api617_results;
/* The sweep over modal.speed_min..speed_max at the response nodes and the static reactions. */
td_status td_modal_api617(const td_model *m, const td_system *sys, const td_modal_options *opt, const td_unbalance *u,
                          int n_u, td_modal_api617_results *out, td_error *err);
void td_modal_api617_free(td_modal_api617_results *r);
/* A zeroed td_modal_results holding the report's parts (the static reactions only when computed). */
void td_modal_api617_into(td_modal_results *res, const td_modal_api617_results *r);
/* Its text: the peak table and the static reactions. */
void td_print_api617(FILE *f, const td_model *m, const td_modal_options *opt, const td_modal_api617_results *r);

#endif
