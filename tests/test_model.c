/* td_model: parts are validated as added, cross-references by td_model_validate. */
#include "td_rig.h"
#include "td_test.h"

#include "touchdown/touchdown.h"

#include <math.h>
#include <stdlib.h>
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
    td_retainer r = {.node = 1,
                     .clearance = 0.75e-3,
                     .shaft_radius = 0.025,
                     .bore_radius = 0.02575,
                     .friction = 0.1,
                     .bore_speed = 0.0,
                     .restitution = 0.0};
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
    td_amb amb = {1, 1, 1e6, 200, 1e4, 40, 1.0 / (2 * TD_PI * 100), 1700, 0, 0.5e-3, 0.0, 0.0};
    td_retainer r = {.node = 0,
                     .clearance = 0.75e-3,
                     .shaft_radius = 0.025,
                     .bore_radius = 0.02575,
                     .friction = 0.1,
                     .bore_speed = 0.0,
                     .restitution = 0.0};
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

/* The model's errors name the part, its index and the field at fault (and, for a cross check,
 * the part compared against); the message is "PART INDEX: FIELD: REASON", REASON at `reason`. */
static void assert_site(const td_error_site *site, const char *part, int index, const char *field)
{
    assert_non_null(site->part);
    assert_string_equal(site->part, part);
    assert_int_equal(site->index, index);
    if (field) {
        assert_non_null(site->field);
        assert_string_equal(site->field, field);
    } else {
        assert_null(site->field);
    }
}

static void test_errors_name_part_index_field(void **state)
{
    td_model *m = uniform_shaft(2), *fine = NULL;
    td_error err;
    td_amb amb = {1, 1, 1e6, 200, 1e4, 40, 1.0 / (2 * TD_PI * 100), 1700, 0, 0.5e-3, 0.0, 0.0};
    td_retainer r = {.node = 0,
                     .clearance = 0.25e-3,
                     .shaft_radius = 0.025,
                     .bore_radius = 0.02525,
                     .friction = 0.1,
                     .bore_speed = 0.0,
                     .restitution = 0.0};
    td_change c = {0.5, TD_CHANGE_AMB_OFF, 3, 0.0, 0.0};
    td_change early = {0.1, TD_CHANGE_AMB_OFF, 0, 0.0, 0.0};
    (void)state;
    /* a value check of td_model_add_*: the index the part would have had */
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    r.bore_radius = 0.03;
    assert_int_equal(td_model_add_retainer(m, &r, &err), TD_ERR_INVALID);
    assert_site(&err.site, "retainer", 1, "bore_radius");
    assert_null(err.other.part);
    assert_true(strncmp(err.message, "retainer 1: bore_radius: ", 25) == 0);
    assert_int_equal(err.reason, 25);
    assert_non_null(strstr(err.message + err.reason, "shaft_radius + clearance"));
    assert_int_equal(td_model_add_shaft_element(m, &(td_shaft_element){0.1, 0.05, 0.0, {-1.0, 8.1e10, 7810.0}}, &err),
                     TD_ERR_INVALID);
    assert_site(&err.site, "element", 2, "material.E");

    /* cross checks of td_model_validate: the part at fault and the one it was compared with */
    r.bore_radius = 0.02525; /* a second retainer on node 0 */
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_site(&err.site, "retainer", 1, "node");
    assert_site(&err.other, "retainer", 0, "node");
    assert_string_equal(err.message + err.reason, "node 0 already has a retainer (retainer 0)");
    td_model_free(&m);

    m = uniform_shaft(2);
    amb.air_gap = 0.2e-3;
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    assert_int_equal(td_model_add_retainer(m, &r, NULL), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_site(&err.site, "retainer", 0, "clearance");
    assert_site(&err.other, "amb", 0, "air_gap");
    assert_true(strncmp(err.message, "retainer 0: clearance: ", 23) == 0);

    /* a change is numbered as td_model_get_change numbers it: in time order */
    amb.air_gap = 0.0;
    td_model_free(&m);
    m = uniform_shaft(2);
    assert_int_equal(td_model_add_amb(m, &amb, NULL), TD_OK);
    assert_int_equal(td_model_add_change(m, &c, NULL), TD_OK);
    assert_int_equal(td_model_add_change(m, &early, NULL), TD_OK);
    assert_int_equal(td_model_validate(m, &err), TD_ERR_INVALID);
    assert_site(&err.site, "change", 1, "index");
    assert_non_null(strstr(err.message, "AMB 3 does not exist"));

    /* an error about no part leaves the sites empty */
    assert_int_equal(td_model_refine(m, 0, &fine, &err), TD_ERR_INVALID);
    assert_null(err.site.part);
    assert_null(err.other.part);
    assert_int_equal(err.reason, 0);
    td_error_clear(&err);
    assert_null(err.site.part);
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

/* Node nc of `coarse` and node nf of `fine` are at the same axial position. */
static void assert_same_z(const td_model *coarse, int nc, const td_model *fine, int nf)
{
    assert_close(td_model_node_position(fine, nf), td_model_node_position(coarse, nc), 1e-14, 1e-15);
}

/* Every part of the machine is where it was before refinement, and unchanged otherwise. */
static void check_parts_in_place(const td_model *coarse, const td_model *fine)
{
    td_disc dc, df;
    td_amb ac, af;
    td_retainer rc, rf;
    td_unbalance uc, uf;
    int i;
    for (i = 0; td_model_get_disc(coarse, i, &dc) == TD_OK; i++) {
        assert_int_equal(td_model_get_disc(fine, i, &df), TD_OK);
        assert_same_z(coarse, dc.node, fine, df.node);
        assert_true(dc.mass == df.mass && dc.Ip == df.Ip && dc.Id == df.Id);
    }
    for (i = 0; td_model_get_amb(coarse, i, &ac) == TD_OK; i++) {
        assert_int_equal(td_model_get_amb(fine, i, &af), TD_OK);
        assert_same_z(coarse, ac.node, fine, af.node);
        assert_same_z(coarse, ac.sensor_node, fine, af.sensor_node);
        assert_true(ac.kp == af.kp && ac.kd == af.kd && ac.tau == af.tau);
    }
    for (i = 0; td_model_get_retainer(coarse, i, &rc) == TD_OK; i++) {
        assert_int_equal(td_model_get_retainer(fine, i, &rf), TD_OK);
        assert_same_z(coarse, rc.node, fine, rf.node);
        assert_true(rc.clearance == rf.clearance);
    }
    for (i = 0; td_model_get_unbalance(coarse, i, &uc) == TD_OK; i++) {
        assert_int_equal(td_model_get_unbalance(fine, i, &uf), TD_OK);
        assert_same_z(coarse, uc.node, fine, uf.node);
    }
}

static void test_refine_keeps_the_machine(void **state)
{
    td_model *rig = NULL, *fine = NULL;
    td_unbalance u = {1, 0.02, 0.3};
    td_change c = {0.1, TD_CHANGE_UNBALANCE, 0, 0.10, 0.0};
    td_change got;
    td_error err;
    (void)state;
    assert_int_equal(td_model_create(&rig, NULL), TD_OK);
    td_test_build_rig(rig, 90.0, TD_RIG_TAU, TD_RIG_WITH_RETAINERS);
    assert_int_equal(td_model_add_unbalance(rig, &u, NULL), TD_OK);
    assert_int_equal(td_model_add_change(rig, &c, NULL), TD_OK);

    assert_int_equal(td_model_refine(rig, 4, &fine, &err), TD_OK);
    assert_int_equal(td_model_shaft_element_count(fine), 48);
    assert_int_equal(td_model_node_count(fine), 49);
    assert_int_equal(td_model_dof_count(fine), 196);
    assert_close(td_model_node_position(fine, 48), 2.0, 1e-14, 0.0);
    /* mass is conserved: the same shaft cut into more pieces, the same parts */
    assert_close(td_model_total_mass(fine), td_model_total_mass(rig), 1e-14, 0.0);
    check_parts_in_place(rig, fine);
    assert_int_equal(td_model_get_change(fine, 0, &got), TD_OK);
    assert_true(got.time == c.time && got.magnitude == c.magnitude);
    assert_close(td_model_speed(fine), 90.0, 0.0, 0.0);
    assert_int_equal(td_model_validate(fine, &err), TD_OK);
    td_model_free(&fine);

    assert_int_equal(td_model_refine(rig, 1, &fine, &err), TD_OK); /* a plain copy */
    assert_int_equal(td_model_node_count(fine), 13);
    check_parts_in_place(rig, fine);
    td_model_free(&fine);

    assert_int_equal(td_model_refine(rig, 0, &fine, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "factor 0"));
    assert_null(fine);
    assert_int_equal(td_model_refine(rig, 1 << 28, &fine, &err), TD_ERR_INVALID);
    assert_null(fine);
    assert_int_equal(td_model_add_point_mass(rig, 13, 1.0, NULL), TD_OK); /* off the shaft */
    assert_int_equal(td_model_refine(rig, 2, &fine, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "out of range"));
    assert_null(fine);
    td_model_free(&rig);
}

/* td_disc_from_geometry against the closed forms evaluated in 40-digit decimal arithmetic
 * (Python's decimal module): the rig's solid disc given by its mass (docs/reference-rig.md,
 * thickness m/(rho pi R^2) = 0.028303269151354270837 m) and a bored disc given by its thickness. */
static void test_disc_from_geometry(void **state)
{
    td_disc_geometry rig = {5, 0.12, 0.0, 7810.0, 0.0, 10.0};
    td_disc_geometry bored = {2, 0.1, 0.02, 7800.0, 0.02, 0.0};
    td_disc d;
    td_error err;
    (void)state;
    assert_int_equal(td_disc_from_geometry(&rig, &d, &err), TD_OK);
    assert_int_equal(d.node, 5);
    assert_close(d.mass, 10.0, 0.0, 0.0);
    assert_close(d.Ip, 0.072, 1e-15, 0.0);
    assert_close(d.Id, 0.036667562537211668589, 1e-15, 0.0); /* not the rounded 0.036668 */
    assert_int_equal(td_disc_from_geometry(&bored, &d, &err), TD_OK);
    assert_int_equal(d.node, 2);
    assert_close(d.mass, 4.7048491580160743539, 1e-15, 0.0);
    assert_close(d.Ip, 0.024465215621683586640, 1e-15, 0.0);
    assert_close(d.Id, 0.012389436116108995799, 1e-15, 0.0);
    /* the same disc given by the mass it has: the same inertias */
    bored.mass = 4.7048491580160743539;
    bored.thickness = 0.0;
    assert_int_equal(td_disc_from_geometry(&bored, &d, &err), TD_OK);
    assert_close(d.Id, 0.012389436116108995799, 1e-14, 0.0);
    /* both or neither of thickness and mass; bore not inside; bad numbers */
    bored.thickness = 0.02;
    assert_int_equal(td_disc_from_geometry(&bored, &d, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "not both"));
    bored.thickness = bored.mass = 0.0;
    assert_int_equal(td_disc_from_geometry(&bored, &d, &err), TD_ERR_INVALID);
    rig.inner_radius = 0.12;
    assert_int_equal(td_disc_from_geometry(&rig, &d, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, "inner radius"));
    assert_string_equal(err.site.field, "inner_radius"); /* a disc in no model: index -1 */
    assert_int_equal(err.site.index, -1);
    rig.inner_radius = 0.0;
    rig.density = NAN;
    assert_int_equal(td_disc_from_geometry(&rig, &d, &err), TD_ERR_INVALID);
    rig.density = 7810.0;
    rig.mass = -1.0;
    assert_int_equal(td_disc_from_geometry(&rig, &d, &err), TD_ERR_INVALID);
    assert_int_equal(td_disc_from_geometry(NULL, &d, &err), TD_ERR_INVALID);
}

/* Second method: refining a coarse stepped shaft gives the matrices of the fine shaft built directly. */
static void test_refine_is_the_fine_mesh(void **state)
{
    const td_material steel = {2.11e11, 8.1e10, 7810.0};
    td_shaft_element thick = {0.3, 0.08, 0.02, steel}, thin = {0.2, 0.05, 0.0, steel};
    td_disc disc = {1, 10.0, 0.072, 0.036668};
    td_model *coarse = NULL, *refined = NULL, *direct = NULL;
    td_system *sr = NULL, *sd = NULL;
    td_matrix_kind kinds[] = {TD_MATRIX_MASS, TD_MATRIX_STIFFNESS, TD_MATRIX_GYROSCOPIC};
    double *a, *b;
    int i, k, n;
    (void)state;
    assert_int_equal(td_model_create(&coarse, NULL), TD_OK);
    assert_int_equal(td_model_create(&direct, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(coarse, &thick, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(coarse, &thin, NULL), TD_OK);
    assert_int_equal(td_model_add_disc(coarse, &disc, NULL), TD_OK);
    thick.length /= 3;
    thin.length /= 3;
    for (i = 0; i < 3; i++)
        assert_int_equal(td_model_add_shaft_element(direct, &thick, NULL), TD_OK);
    for (i = 0; i < 3; i++)
        assert_int_equal(td_model_add_shaft_element(direct, &thin, NULL), TD_OK);
    disc.node = 3;
    assert_int_equal(td_model_add_disc(direct, &disc, NULL), TD_OK);

    assert_int_equal(td_model_refine(coarse, 3, &refined, NULL), TD_OK);
    assert_int_equal(td_system_create(refined, &sr, NULL), TD_OK);
    assert_int_equal(td_system_create(direct, &sd, NULL), TD_OK);
    n = td_system_dof_count(sd);
    assert_int_equal(td_system_dof_count(sr), n);
    a = malloc(sizeof *a * (size_t)(n * n));
    b = malloc(sizeof *b * (size_t)(n * n));
    assert_non_null(a);
    assert_non_null(b);
    for (k = 0; k < 3; k++) {
        assert_int_equal(td_system_dense(sr, kinds[k], a, NULL), TD_OK);
        assert_int_equal(td_system_dense(sd, kinds[k], b, NULL), TD_OK);
        for (i = 0; i < n * n; i++)
            assert_close(a[i], b[i], 1e-14, 1e-14 * fabs(b[0]));
    }
    free(a);
    free(b);
    td_system_free(&sr);
    td_system_free(&sd);
    td_model_free(&coarse);
    td_model_free(&refined);
    td_model_free(&direct);
}

/* A negative speed is refused wherever the library takes a speed (touchdown/dofs.h: the spin is
 * about +z, whirl directions are counted from it), as the case file refuses it. */
static void test_negative_speed_refused(void **state)
{
    td_model *m = uniform_shaft(4);
    td_system *sys = NULL;
    td_modal *modes = NULL;
    td_sim *sim = NULL;
    td_sim_options o;
    td_error err;
    int unstable = 0;
    (void)state;
    assert_int_equal(td_model_set_speed(m, -10.0, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, ">= 0"));
    assert_int_equal(td_model_set_speed(m, NAN, NULL), TD_ERR_INVALID);
    assert_int_equal(td_model_set_speed(m, 10.0, NULL), TD_OK);
    assert_int_equal(td_system_create(m, &sys, NULL), TD_OK);
    assert_int_equal(td_modal_solve(sys, -10.0, &modes, NULL), TD_ERR_INVALID);
    assert_null(modes);
    assert_int_equal(td_modal_solve_lowest(sys, -10.0, 2, &modes, NULL), TD_ERR_INVALID);
    assert_null(modes);
    assert_int_equal(td_modal_stability(sys, -10.0, NULL, &unstable, NULL), TD_ERR_INVALID);
    td_sim_options_default(&o);
    o.start = TD_START_REST;
    assert_int_equal(td_sim_create(m, &o, &sim, NULL), TD_OK);
    assert_int_equal(td_sim_set_speed(sim, -10.0, &err), TD_ERR_INVALID);
    assert_non_null(strstr(err.message, ">= 0"));
    assert_int_equal(td_sim_set_speed(sim, 20.0, NULL), TD_OK);
    td_sim_free(&sim);
    td_system_free(&sys);
    td_model_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_negative_speed_refused),
        cmocka_unit_test(test_counts_and_mass),
        cmocka_unit_test(test_rejects_bad_parts),
        cmocka_unit_test(test_validate_cross_references),
        cmocka_unit_test(test_schedule_sorted_and_clone),
        cmocka_unit_test(test_refine_keeps_the_machine),
        cmocka_unit_test(test_refine_is_the_fine_mesh),
        cmocka_unit_test(test_disc_from_geometry),
        cmocka_unit_test(test_errors_name_part_index_field),
    };
    return cmocka_run_group_tests_name("model", tests, NULL, NULL);
}
