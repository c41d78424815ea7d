#include "td_test.h"

#include "touchdown/case.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

void td_assert_close_impl(double actual, double expected, double rtol, double atol, const char *expr, const char *file,
                          int line)
{
    double tol = atol + rtol * fabs(expected);
    if (!(fabs(actual - expected) <= tol)) {
        print_error("%s = %.17g, expected %.17g (|diff| %.3g > tol %.3g)\n", expr, actual, expected,
                    fabs(actual - expected), tol);
        _fail(file, line);
    }
}

double td_rel_diff(double a, double b)
{
    double d = fabs(b) > 1e-300 ? fabs(b) : 1e-300;
    return fabs(a - b) / d;
}

const char *td_source_path(const char *relative)
{
    static char buf[8][1024];
    static int slot;
    slot = (slot + 1) % 8;
    snprintf(buf[slot], sizeof buf[slot], "%s/%s", TD_SOURCE_DIR, relative);
    return buf[slot];
}

td_case *td_test_load_case(const char *relative, const char **overrides, int n)
{
    td_case *c = NULL;
    td_error err;
    if (td_case_load(td_source_path(relative), overrides, n, &c, &err) != TD_OK)
        fail_msg("%s: %s", relative, err.message);
    return c;
}

td_sim *td_test_new_sim(const td_model *m, const td_case *c)
{
    td_sim *s = NULL;
    td_error err;
    if (td_sim_create(m, td_case_sim_options(c), &s, &err) != TD_OK)
        fail_msg("td_sim_create: %s", err.message);
    return s;
}

void td_test_step_to(td_sim *s, double tout)
{
    td_error err;
    td_status st;
    while ((st = td_sim_step(s, tout, NULL, &err)) == TD_EVENT)
        ;
    if (st != TD_OK)
        fail_msg("td_sim_step to %.17g: %s", tout, err.message);
}

double td_test_next_output(double t, double dt, double t_end)
{
    return fmin(t_end, (floor(t / dt + 0.5) + 1.0) * dt);
}

char *td_test_read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    char *buf;
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)n + 1);
    assert_non_null(buf);
    assert_int_equal(fread(buf, 1, (size_t)n, f), (size_t)n);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

double td_test_max_abs(const double *a, int n)
{
    double m = 0.0;
    int i;
    for (i = 0; i < n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

uint64_t td_test_splitmix(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

int td_test_sanitized(void)
{
    const char *v = getenv("TD_TEST_SANITIZED");
    return v != NULL && v[0] == '1' && v[1] == '\0';
}

char *td_test_summary_json(const td_run_summary *s, const td_run_summary *like)
{
    td_run_summary t = *s;
    char *buf;
    int n;
    t.wall_time = like->wall_time;
    t.solver_wall_time = like->solver_wall_time;
    t.wall_time_per_revolution = like->wall_time_per_revolution;
    t.realtime_factor = like->realtime_factor;
    t.stats.wall_time = like->stats.wall_time;
    n = td_run_summary_json(NULL, 0, &t);
    buf = malloc((size_t)n + 1);
    assert_non_null(buf);
    td_run_summary_json(buf, (size_t)n + 1, &t);
    return buf;
}
