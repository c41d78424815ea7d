/* td_model: parts are validated as added, cross-references by td_model_validate. */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <string.h>

static td_model *uniform_shaft(int elements)
{
    td_model *m = NULL;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    int i;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    for (i = 0; i < elements; i++)
        assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    return m;
}

static void test_counts_and_mass(void **state)
{
    td_model *m = uniform_shaft(10);
    (void)state;
    assert_int_equal(td_model_node_count(m), 11);
    assert_int_equal(td_model_dof_count(m), 44);
    /* shaft mass rho pi d^2/4 L, L = 1 m */
    assert_close(td_model_total_mass(m), 7810.0 * TD_PI * 0.05 * 0.05 / 4.0, 1e-14, 0.0);
    assert_int_equal(td_model_add_point_mass(m, 3, 14.6, NULL), TD_OK);
    assert_close(td_model_total_mass(m), 7810.0 * TD_PI * 0.05 * 0.05 / 4.0 + 14.6, 1e-14, 0.0);
    assert_close(td_model_node_position(m, 4), 0.4, 1e-14, 0.0);
    td_model_free(&m);
    assert_null(m);
    td_model_free(&m); /* NULL is accepted */
}

static void test_rejects_bad_parts(void **state)
{
    td_model *m = uniform_shaft(2);
    td_error err;
    td_shaft_element bad = {0.1, 0.05, 0.06, {2.11e11, 8.1e10, 7810.0}};
    td_retainer r = {1, 0.75e-3, 0.025, 0.02575, 0.1, 0.0, 0.0};
    (void)state;
    assert_int_equal(td_model_add_shaft_element(m, &bad, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "inner diameter"));
    assert_int_equal(td_model_add_point_mass(m, 0, -1.0, &err), TD_ERR_INVALID);
    assert_int_equal(td_model_add_point_mass(m, 0, NAN, &err), TD_ERR_INVALID);
    r.bore_radius = 0.03;
    assert_int_equal(td_model_add_retainer(m, &r, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "bore radius"));
    td_model_free(&m);
}

static void test_validate_cross_references(void **state)
{
    td_model *m = uniform_shaft(2);
    td_error err;
    td_amb amb = {1, 1, 1e6, 200, 1e4, 40, 1.0 / (2 * TD_PI * 100), 1700, 0, 0.5e-3};
    td_retainer r = {0, 0.75e-3, 0.025, 0.02575, 0.1, 0.0, 0.0};
    (void)state;
    assert_int_equal(td_model_validate(m, &err), TD_OK);
    assert_int_equal(td_model_add_point_mass(m, 3, 1.0, NULL), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "out of range"));
    td_model_free(&m);

    m = uniform_shaft(2);
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID); /* clearance >= air gap */
    assert_non_null(strstr(err.message, "air gap"));
    td_model_free(&m);
}

static void test_schedule_sorted_and_clone(void **state)
{
    td_model *m = uniform_shaft(2), *c = NULL;
    td_change a = {1.1, TD_CHANGE_UNBALANCE, 0, 0.02, 0.0};
    td_change b = {0.1, TD_CHANGE_UNBALANCE, 0, 0.10, 0.0};
    td_unbalance u = {1, 0.02, 0.0};
    td_change got;
    (void)state;
    assert_int_equal(td_model_add_unbalance(m, &u, NULL), TD_OK);
    assert_int_equal(td_model_add_change(m, &a, NULL), TD_OK);
    assert_int_equal(td_model_add_change(m, &b, NULL), TD_OK);
    assert_int_equal(td_model_clone(m, &c, NULL), TD_OK);
    td_model_free(&m);
    assert_int_equal(td_model_get_change(c, 0, &got), TD_OK);
    assert_close(got.time, 0.1, 0, 0);
    assert_int_equal(td_model_get_change(c, 1, &got), TD_OK);
    assert_close(got.time, 1.1, 0, 0);
    assert_int_equal(td_model_get_change(c, 2, &got), TD_ERR_INVALID);
    assert_int_equal(td_model_validate(c, NULL), TD_OK);
    td_model_free(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts_and_mass),
        cmocka_unit_test(test_rejects_bad_parts),
        cmocka_unit_test(test_validate_cross_references),
        cmocka_unit_test(test_schedule_sorted_and_clone),
    };
    return cmocka_run_group_tests_name("model", tests, NULL, NULL);
}
