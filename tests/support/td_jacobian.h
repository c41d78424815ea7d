/* The simulation's Jacobian against central differences of its residual (test support). */
#ifndef TD_TEST_JACOBIAN_H
#define TD_TEST_JACOBIAN_H

struct td_sim;

/* dF/dy + cj dF/dy' of td_sim_jacobian at the state (y, yp) against central differences of
 * td_sim_residual, entry by entry, relative to the largest entry of its row (1e-6 of it, + 1e-9);
 * every entry found by differences must lie in the fixed pattern. Each unknown j is stepped by
 * rel_step |y[j]| (rel_step 1e-6 where y[j] is 0); y and yp are left as given. Fails the test
 * with `what`, the entry and both values. */
void td_test_check_jacobian(struct td_sim *s, double *y, double *yp, double rel_step, const char *what);

#endif
