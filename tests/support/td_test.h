/* Shared test helpers: double comparisons (cmocka 1.1.5's assert_float_equal casts to float). */
#ifndef TD_TEST_H
#define TD_TEST_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "touchdown/dofs.h" /* TD_PI */

/* Fails the test unless |actual - expected| <= atol + rtol |expected|; prints both with 17 digits. */
void td_assert_close_impl(double actual, double expected, double rtol, double atol, const char *expr, const char *file,
                          int line);
#define assert_close(actual, expected, rtol, atol)                                                                     \
    td_assert_close_impl((actual), (expected), (rtol), (atol), #actual, __FILE__, __LINE__)

/* Relative difference |a - b| / max(|b|, tiny). */
double td_rel_diff(double a, double b);

/* max |a[i]| over n entries (0 for n = 0). */
double td_test_max_abs(const double *a, int n);

struct td_case;
struct td_model;
struct td_run_summary;
struct td_sim;

/* The summary as JSON (every field the tool prints; caller frees), with the wall-clock fields of
 * `like`, which differ from run to run: two summaries of the same run compare equal as text. */
char *td_test_summary_json(const struct td_run_summary *s, const struct td_run_summary *like);

/* Load a case file of the source tree (relative path) with overrides; fails the test on error. */
struct td_case *td_test_load_case(const char *relative, const char **overrides, int n);

/* A simulation of model m with case c's options (td_sim_free it); fails the test on error. */
struct td_sim *td_test_new_sim(const struct td_model *m, const struct td_case *c);

/* Step s to tout through its events; fails the test on an error. */
void td_test_step_to(struct td_sim *s, double tout);

/* The output grid point after t: k dt with k dt >= t + dt/2, capped at t_end. */
double td_test_next_output(double t, double dt, double t_end);

/* A whole file as a NUL-terminated buffer (caller frees); fails the test if it cannot be read. */
char *td_test_read_file(const char *path);

/* Path of a file in the source tree (tests/..., cases/...), in a static buffer per call slot. */
const char *td_source_path(const char *relative);

/* The next of a reproducible stream of 64 random bits from the state *s (SplitMix64, Steele, Lea
 * and Flood 2014): synthetic data that any seed reproduces. */
uint64_t td_test_splitmix(uint64_t *s);

/* 1 when the test runs in the sanitizer pass (TD_TEST_SANITIZED=1, set by tests/CMakeLists.txt on
 * every test of that build), else 0. That pass looks for memory errors and undefined behaviour, so
 * a test may then take the same code paths in a shorter run (fewer repeats, shorter simulations);
 * each test that does says what it still covers there and what only the plain pass checks. */
int td_test_sanitized(void);

#endif
