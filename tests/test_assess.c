/*
 * The assessment (touchdown/assess.h): ISO 14839-2 zones at and around their boundaries, and the
 * model's retainer bearings and limits (touchdown/model.h): checks, defaults, copies.
 */
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <string.h>

/* Each zone's interval, its boundaries in the better zone, and what has no zone. */
static void test_zones(void **state)
{
    td_zone_limits z;
    const double c = 2.5e-4;
    (void)state;
    td_zone_limits_default(&z);
    assert_true(z.ab == 0.3 && z.bc == 0.4 && z.cd == 0.5);
    assert_int_equal(td_vibration_zone_of(0.0, c, &z), TD_ZONE_A);
    assert_int_equal(td_vibration_zone_of(0.3 * c, c, &z), TD_ZONE_A);
    assert_int_equal(td_vibration_zone_of(nextafter(0.3 * c, 1.0), c, &z), TD_ZONE_B);
    assert_int_equal(td_vibration_zone_of(0.4 * c, c, &z), TD_ZONE_B);
    assert_int_equal(td_vibration_zone_of(0.45 * c, c, &z), TD_ZONE_C);
    assert_int_equal(td_vibration_zone_of(0.5 * c, c, &z), TD_ZONE_C);
    assert_int_equal(td_vibration_zone_of(nextafter(0.5 * c, 1.0), c, &z), TD_ZONE_D);
    assert_int_equal(td_vibration_zone_of(3.0 * c, c, &z), TD_ZONE_D);
    assert_int_equal(td_vibration_zone_of(TD_UNDEFINED, c, &z), -1);
    assert_int_equal(td_vibration_zone_of(-1e-9, c, &z), -1);
    assert_int_equal(td_vibration_zone_of(INFINITY, c, &z), -1);
    assert_int_equal(td_vibration_zone_of(1e-5, 0.0, &z), -1);
    assert_int_equal(td_vibration_zone_of(1e-5, TD_UNDEFINED, &z), -1);
    assert_int_equal(td_vibration_zone_of(1e-5, c, NULL), -1);
    assert_string_equal(td_vibration_zone_name(TD_ZONE_A), "A");
    assert_string_equal(td_vibration_zone_name(TD_ZONE_D), "D");
    assert_string_equal(td_vibration_zone_name(-1), "undefined");
    assert_string_equal(td_vibration_zone_name(4), "undefined");
}

/* A two-element shaft with a retainer of bore radius 0.02575 m at node 1. */
static td_model *with_retainer(void)
{
    td_model *m = NULL;
    td_shaft_element el = {0.1, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_retainer r;
    memset(&r, 0, sizeof r);
    r.node = 1;
    r.clearance = 0.75e-3;
    r.shaft_radius = 0.025;
    r.bore_radius = r.shaft_radius + r.clearance;
    r.friction = 0.1;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    return m;
}

static void expect_bearing_fault(td_model *m, const td_retainer_bearing *b, const char *field)
{
    td_error err;
    assert_int_equal(td_model_set_retainer_bearing(m, 0, b, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "retainer");
    assert_int_equal(err.site.index, 0);
    assert_string_equal(err.site.field, field);
}

static void test_retainer_bearing(void **state)
{
    td_model *m = with_retainer(), *copy = NULL;
    td_retainer_bearing b, got, bad;
    td_error err;
    (void)state;
    assert_int_equal(td_model_get_retainer_bearing(m, 0, &got), TD_OK); /* none set: the defaults */
    assert_true(got.static_rating == 0.0 && got.balls == 0 && got.life_exponent == 3.0);
    assert_true(got.groove_conformity == 0.52);
    memset(&b, 0, sizeof b);
    b.static_rating = 18000.0;
    b.balls = 10;
    b.ball_diameter = 0.0111;
    b.pitch_diameter = 0.0775;
    assert_int_equal(td_model_set_retainer_bearing(m, 0, &b, &err), TD_OK);
    assert_int_equal(td_model_set_retainer_bearing(m, 1, &b, &err), TD_ERR_INVALID);
    assert_int_equal(td_model_get_retainer_bearing(m, 0, &got), TD_OK);
    assert_true(got.static_rating == 18000.0 && got.balls == 10 && got.life_exponent == 3.0);
    assert_true(got.groove_conformity == 0.52);
    assert_int_equal(td_model_get_retainer_bearing(m, 1, &got), TD_ERR_INVALID);
    /* copies and refined copies keep it */
    assert_int_equal(td_model_refine(m, 2, &copy, &err), TD_OK);
    assert_int_equal(td_model_get_retainer_bearing(copy, 0, &got), TD_OK);
    assert_true(got.pitch_diameter == 0.0775 && got.static_rating == 18000.0);
    td_model_free(&copy);
    bad = b;
    bad.static_rating = -1.0;
    expect_bearing_fault(m, &bad, "bearing.static_rating");
    bad = b;
    bad.life_exponent = 0.5;
    expect_bearing_fault(m, &bad, "bearing.life_exponent");
    bad = b;
    bad.groove_conformity = 0.5;
    expect_bearing_fault(m, &bad, "bearing.groove_conformity");
    bad = b;
    bad.balls = 2;
    expect_bearing_fault(m, &bad, "bearing.balls");
    bad = b;
    bad.balls = 0;
    expect_bearing_fault(m, &bad, "bearing.ball_diameter");
    bad = b;
    bad.pitch_diameter = 0.01;
    expect_bearing_fault(m, &bad, "bearing.pitch_diameter");
    bad = b;
    bad.pitch_diameter = 0.0111 + 2.0 * 0.02575; /* the raceway exactly on the bore */
    expect_bearing_fault(m, &bad, "bearing.pitch_diameter");
    bad = b;
    bad.width = NAN;
    expect_bearing_fault(m, &bad, "bearing.width");
    td_model_free(&m);
}

static void test_limits(void **state)
{
    td_model *m = with_retainer(), *copy = NULL;
    td_limits l, got;
    td_error err;
    (void)state;
    td_model_get_limits(m, &got);
    assert_true(got.zones.ab == 0.3 && got.zones.bc == 0.4 && got.zones.cd == 0.5);
    assert_true(td_is_undefined(got.temperature_rise) && td_is_undefined(got.drops));
    assert_int_equal(got.zone, TD_ZONE_B); /* ISO 14839-2: B, unrestricted long-term operation */
    l = got;
    l.zones.ab = 0.2;
    l.drops = 100.0;
    assert_int_equal(td_model_set_limits(m, &l, &err), TD_OK);
    assert_int_equal(td_model_clone(m, &copy, &err), TD_OK);
    td_model_get_limits(copy, &got);
    assert_true(got.zones.ab == 0.2 && got.drops == 100.0 && td_is_undefined(got.temperature_rise));
    td_model_free(&copy);
    l.zones.bc = 0.6; /* above C/D */
    assert_int_equal(td_model_set_limits(m, &l, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "limits");
    assert_string_equal(err.site.field, "zones");
    l.zones.bc = 0.4;
    l.temperature_rise = 0.0;
    assert_int_equal(td_model_set_limits(m, &l, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "temperature_rise");
    l.temperature_rise = TD_UNDEFINED;
    l.zone = 4; /* no such zone */
    assert_int_equal(td_model_set_limits(m, &l, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "zone");
    l.zone = TD_ZONE_B;
    l.drops = -3.0;
    assert_int_equal(td_model_set_limits(m, &l, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "drops");
    td_model_get_limits(m, &got); /* a refused set changes nothing */
    assert_true(got.zones.ab == 0.2 && got.drops == 100.0);
    td_model_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zones),
        cmocka_unit_test(test_retainer_bearing),
        cmocka_unit_test(test_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
