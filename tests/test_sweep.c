/*
 * td_sweep: the grid of points (ranges with exact ends, lists with quoted commas, the first axis
 * slowest, the bounds and the errors) and the table writers (the CSV read back; the HDF5 columns
 * and the completeness flag read back with the HDF5 C API).
 */
#include "td_test.h"

#include "touchdown/sweep.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static td_sweep_grid *grid_of(const char *const *specs, int n)
{
    td_sweep_grid *g = NULL;
    td_error err;
    int i;
    assert_int_equal(td_sweep_grid_create(&g, &err), TD_OK);
    for (i = 0; i < n; i++)
        assert_int_equal(td_sweep_grid_vary(g, specs[i], &err), TD_OK);
    return g;
}

static void test_range_ends_exact(void **state)
{
    const char *specs[] = {"speed=0.1:0.7:7"};
    td_sweep_grid *g = grid_of(specs, 1);
    long p;
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 7);
    assert_true(td_sweep_grid_numeric(g, 0));
    assert_string_equal(td_sweep_grid_value(g, 0, 0), "0.1"); /* the fewest digits that read back */
    /* the last point is STOP itself, not START plus six rounded steps */
    assert_true(strtod(td_sweep_grid_value(g, 6, 0), NULL) == 0.7);
    for (p = 0; p < 7; p++) /* every value reads back to the point's double */
        assert_true(strtod(td_sweep_grid_value(g, p, 0), NULL) == 0.1 + (0.7 - 0.1) * (double)p / 6.0 || p == 6);
    td_sweep_grid_free(&g);
    assert_null(g);
}

static void test_grid_order_and_lists(void **state)
{
    const char *specs[] = {"speed=60:90:2", "contact.model=\"penalty\",constraint", "output.nodes=[1, 2],[3]"};
    td_sweep_grid *g = grid_of(specs, 3);
    char buf[128];
    (void)state;
    assert_int_equal(td_sweep_grid_points(g), 8);
    assert_int_equal(td_sweep_grid_axes(g), 3);
    assert_false(td_sweep_grid_numeric(g, 1));
    /* point 5 = speed 1, model 0, nodes 1: the first axis varies slowest */
    assert_string_equal(td_sweep_grid_value(g, 5, 0), "90");
    assert_string_equal(td_sweep_grid_value(g, 5, 1), "\"penalty\"");
    assert_string_equal(td_sweep_grid_value(g, 5, 2), "[3]");
    assert_string_equal(td_sweep_grid_value(g, 0, 2), "[1, 2]");
    td_sweep_grid_override(g, 3, 1, buf, sizeof buf);
    assert_string_equal(buf, "contact.model=constraint");
    assert_string_equal(td_sweep_grid_key(g, 2), "output.nodes");
    assert_string_equal(td_sweep_grid_spec(g, 0), "speed=60:90:2");
    td_sweep_grid_free(&g);
}

static void test_bad_specs(void **state)
{
    static const char *const bad[] = {"speed",         "speed=",          "=1,2",          "speed=1:2",
                                      "speed=1:2:0",   "speed=a:2:3",     "speed=1:2:3:4", "speed=1,,2",
                                      "speed=1:2:1.5", "speed=1:2:100001"};
    td_sweep_grid *g = NULL;
    td_error err;
    size_t i;
    (void)state;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(td_sweep_grid_vary(g, bad[i], &err), TD_ERR_PARSE);
        assert_non_null(strstr(err.message, bad[i]));
    }
    assert_int_equal(td_sweep_grid_axes(g), 0);
    assert_int_equal(td_sweep_grid_vary(g, "speed=1:2:1000", &err), TD_OK);
    assert_int_equal(td_sweep_grid_vary(g, "speed=3", &err), TD_ERR_PARSE);          /* twice */
    assert_int_equal(td_sweep_grid_vary(g, "end_time=1:2:101", &err), TD_ERR_PARSE); /* 101,000 points */
    assert_non_null(strstr(err.message, "101000 points"));
    assert_int_equal(td_sweep_grid_points(g), 1000);
    td_sweep_grid_free(&g);
    td_sweep_grid_free(&g); /* NULL accepted */
}

/* Three rows: one done, one failed, one not run. */
static void three_rows(td_sweep_row rows[3])
{
    td_run_summary s;
    memset(&s, 0, sizeof s);
    s.status = TD_OK;
    s.peak_housing_force = 1234.5678901234567;
    s.contacts = 7;
    s.first_contact_time = 0.1;
    s.returned_to_free_orbit = 1;
    s.stats.peak_amb = -1;
    snprintf(s.ending, sizeof s.ending, "forward rub at 9 Hz, rolling");
    td_sweep_row_from_summary(&rows[0], &s);
    s.status = TD_ERR_SOLVER;
    snprintf(s.message, sizeof s.message, "failed at t = 0.2, \"badly\"");
    td_sweep_row_from_summary(&rows[1], &s);
    td_sweep_row_unknown(&rows[2], TD_SWEEP_NOT_RUN, "not run", NULL);
}

static void test_csv_table(void **state)
{
    const char *specs[] = {"speed=1,2,3"};
    const char *sets[] = {"end_time=0.2"};
    td_sweep_grid *g = grid_of(specs, 1);
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "speed = 1.0;\n", sets, 1, 0, "interrupted: 1 of 3 points not run"};
    char path[] = "sweep-test.csv";
    char *text;
    (void)state;
    three_rows(rows);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_csv(path, &t, NULL), TD_OK);
    text = td_test_read_file(path);
    assert_non_null(strstr(text, "point [-],speed,status,message,peak_housing_force [N],"));
    assert_non_null(strstr(text, "\n0,1,success,,1234.5678901234567,"));
    assert_non_null(strstr(text, ",\"forward rub at 9 Hz, rolling\","));
    assert_non_null(strstr(text, "\n1,2,solver failure,\"failed at t = 0.2, \"\"badly\"\"\","));
    assert_non_null(strstr(text, "\n2,3,not run,,nan,"));
    assert_non_null(strstr(text, "# vary = speed=1,2,3\n# set = end_time=0.2\n# case_text:\n#| speed = 1.0;\n"));
    assert_non_null(strstr(text, "# incomplete: interrupted: 1 of 3 points not run\n"));
    assert_int_equal(text[strlen(text) - 1], '\n');
    free(text);
    remove(path);
    td_sweep_grid_free(&g);
}

static double read_double(hid_t f, const char *name, int i)
{
    double v[3];
    hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
    assert_true(d >= 0);
    assert_true(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) >= 0);
    H5Dclose(d);
    return v[i];
}

static int read_flag(hid_t f)
{
    int v = -1;
    hid_t a = H5Aopen(f, "complete", H5P_DEFAULT);
    assert_true(a >= 0);
    assert_true(H5Aread(a, H5T_NATIVE_INT, &v) >= 0);
    H5Aclose(a);
    return v;
}

static void test_hdf5_table(void **state)
{
    const char *specs[] = {"speed=1:3:3"};
    td_sweep_grid *g = grid_of(specs, 1);
    td_sweep_row rows[3];
    td_sweep_table t = {NULL, NULL, "", NULL, 0, 1, NULL};
    const char *path = "sweep-test.h5";
    hid_t f;
    (void)state;
    three_rows(rows);
    t.grid = g;
    t.rows = rows;
    assert_int_equal(td_sweep_write_hdf5(path, &t, NULL), TD_OK);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_int_equal(read_flag(f), 1);
    assert_true(read_double(f, "vary/speed", 2) == 3.0);
    assert_true(read_double(f, "peak_housing_force", 0) == 1234.5678901234567);
    assert_true(read_double(f, "contacts", 1) == 7.0);
    assert_true(isnan(read_double(f, "wall_time", 2)));
    H5Fclose(f);
    remove(path);
    assert_int_equal(access(path, F_OK), -1);
    td_sweep_grid_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_range_ends_exact), cmocka_unit_test(test_grid_order_and_lists),
        cmocka_unit_test(test_bad_specs),        cmocka_unit_test(test_csv_table),
        cmocka_unit_test(test_hdf5_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
