/* Printing of modal results shared by `touchdown modal` and `touchdown info`. */
#ifndef TD_TOOLS_MODAL_PRINT_H
#define TD_TOOLS_MODAL_PRINT_H

#include "touchdown/modal.h"

#include <stdio.h>

const char *td_whirl_name(td_whirl w);
/* Table of the first `count` vibration modes with `digits` significant digits; returns how many
 * near-critically damped pairs (AMB lags) were left out. */
int td_print_modes(FILE *f, const td_modal *modes, int count, int digits);
/* The AMB-lag roots: near-critically damped pairs and real eigenvalues, one line. */
void td_print_overdamped(FILE *f, const td_modal *modes);
/* "stable", "marginally stable (undamped modes)" or "UNSTABLE", judged against round-off. */
const char *td_stability_word(const td_modal *modes);

#endif
