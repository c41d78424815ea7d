/*
 * The compliant housing (touchdown/housing.h td_housing_body): its rules, the coupled system's mass
 * against the rig's masses and inertias in closed form, and the simulation's body state at the
 * static equilibrium on the mounts against the machine's weight over the mounts' stiffness.
 */
#include "support/td_rig.h"
#include "support/td_test.h"
#include "touchdown/options.h"
#include "touchdown/sim.h"
#include "touchdown/system.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The body of the tests: 60 kg, 2 kg m^2 about z = 0.9 m, mounts at 0.2 m and 1.8 m. */
static td_housing_body body(double inertia)
{
    td_housing_body b;
    memset(&b, 0, sizeof b);
    b.mass = 60.0;
    b.inertia = inertia;
    b.centre = 0.9;
    b.mount_count = 2;
    b.mounts[0] = (td_housing_mount){0.2, 2.0e7, 1.0e3};
    b.mounts[1] = (td_housing_mount){1.8, 3.0e7, 1.0e3};
    return b;
}

/* Each rule names its field; a valid body is kept (and copied with the model), 0, 2 or 4 DOFs. */
static void test_rules(void **state)
{
    td_model *m = td_test_rig_create(100.0, 0.0, TD_RIG_NO_RETAINERS), *c = NULL;
    td_housing_body b = body(2.0), got;
    td_error err;
    (void)state;
    assert_int_equal(td_model_housing_body_dofs(m), 0);
    assert_int_equal(td_model_get_housing_body(m, &got), 0);
    b.mass = 0.0;
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "mass");
    b = body(-1.0);
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "inertia");
    b = body(2.0);
    b.mounts[1].position = b.mounts[0].position; /* no tilt stiffness */
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.field, "mounts");
    b.inertia = 0.0; /* a translating body: the positions do not matter */
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_OK);
    assert_int_equal(td_model_housing_body_dofs(m), 2);
    b = body(2.0);
    b.mounts[1].damping = -1.0;
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_ERR_INVALID);
    assert_string_equal(err.site.part, "housing.body.mounts");
    assert_int_equal(err.site.index, 1);
    assert_string_equal(err.site.field, "damping");
    b = body(2.0);
    b.mount_count = TD_HOUSING_MAX_MOUNTS + 1;
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_ERR_INVALID);
    b = body(2.0);
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_OK);
    assert_int_equal(td_model_clone(m, &c, &err), TD_OK);
    assert_int_equal(td_model_get_housing_body(c, &got), 1);
    assert_int_equal(td_model_housing_body_dofs(c), 4);
    assert_int_equal(memcmp(&got, &b, sizeof b), 0);
    td_model_free(&c);
    td_model_free(&m);
}

/* The shaft's mass and its inertia about z (transverse): each element a uniform tube, its section's
 * rotary inertia rho I L included (elements.c: the mass always carries it). */
static void shaft_inertia(const td_model *m, double z, double *mass, double *inertia)
{
    double z0 = 0.0;
    int i;
    *mass = *inertia = 0.0;
    for (i = 0; i < td_model_shaft_element_count(m); i++) {
        td_shaft_element e;
        double ro, ri, A, I, me, d;
        assert_int_equal(td_model_get_shaft_element(m, i, &e), TD_OK);
        ro = 0.5 * e.outer_diameter, ri = 0.5 * e.inner_diameter;
        A = TD_PI * (ro * ro - ri * ri), I = TD_PI * (ro * ro * ro * ro - ri * ri * ri * ri) / 4.0;
        me = e.material.density * A * e.length, d = z0 + 0.5 * e.length - z;
        *mass += me;
        *inertia += me * (e.length * e.length / 12.0 + d * d) + e.material.density * I * e.length;
        z0 += e.length;
    }
}

/* The coupled M over a unit body translation is the whole machine's mass (rotor + body), over a
 * unit tilt the machine's inertia about the body's centre: the rotor's about that point (its rigid
 * motion is exact in the consistent mass), from the rig's parts in closed form. */
static void test_coupled_mass(void **state)
{
    td_model *m = td_test_rig_create(100.0, 0.0, TD_RIG_NO_RETAINERS);
    td_housing_body b = body(2.0);
    td_system *s = NULL;
    td_error err;
    double *M, rotor, tilt, zc = b.centre;
    int n, h, i;
    (void)state;
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_OK);
    assert_int_equal(td_system_create(m, &s, &err), TD_OK);
    n = td_system_dof_count(s);
    h = n - 4;
    assert_int_equal(n, 4 * td_model_node_count(m) + 4);
    M = malloc(sizeof *M * (size_t)n * (size_t)n);
    assert_non_null(M);
    assert_int_equal(td_system_dense(s, TD_MATRIX_MASS, M, &err), TD_OK);
    shaft_inertia(m, zc, &rotor, &tilt);
    for (i = 0; i < td_model_disc_count(m); i++) {
        td_disc d;
        double dz;
        assert_int_equal(td_model_get_disc(m, i, &d), TD_OK);
        dz = td_model_node_position(m, d.node) - zc;
        rotor += d.mass;
        tilt += d.Id + d.mass * dz * dz;
    }
    assert_close(rotor, td_model_total_mass(m), 1e-12, 0.0);
    assert_close(M[h + (size_t)h * n], b.mass + rotor, 1e-12, 0.0);
    assert_close(M[(h + 1) + (size_t)(h + 1) * n], b.mass + rotor, 1e-12, 0.0);
    assert_close(M[(h + 2) + (size_t)(h + 2) * n], b.inertia + tilt, 1e-12, 0.0);
    assert_close(M[(h + 3) + (size_t)(h + 3) * n], b.inertia + tilt, 1e-12, 0.0);
    free(M);
    td_system_free(&s);
    td_model_free(&m);
}

/* From the orbit start without unbalance, under gravity along -y, the machine rests on its mounts:
 * the body's y is -(m_body + m_rotor) g / sum k for a translating body, and the rest of its state 0;
 * without a body the accessor says so. */
static void test_static_state(void **state)
{
    td_model *m = td_test_rig_create(100.0, 0.0, TD_RIG_NO_RETAINERS);
    td_housing_body b = body(0.0);
    td_sim_options o;
    td_sim *sim = NULL;
    td_error err;
    double q[4], v[4], g = 9.81, weight;
    int k;
    (void)state;
    assert_int_equal(td_model_set_gravity(m, 0.0, -g, &err), TD_OK);
    td_sim_options_default(&o);
    o.start = TD_START_ORBIT;
    assert_int_equal(td_sim_create(m, &o, &sim, &err), TD_OK);
    assert_int_equal(td_sim_housing_body_state(sim, q, v), 0);
    for (k = 0; k < 4; k++)
        assert_true(q[k] == 0.0 && v[k] == 0.0);
    td_sim_free(&sim);
    assert_int_equal(td_model_set_housing_body(m, &b, &err), TD_OK);
    assert_int_equal(td_sim_create(m, &o, &sim, &err), TD_OK);
    td_test_step_to(sim, 0.01);
    assert_int_equal(td_sim_housing_body_state(sim, q, v), 1);
    weight = (b.mass + td_model_total_mass(m)) * g;
    assert_close(q[1], -weight / (b.mounts[0].stiffness + b.mounts[1].stiffness), 1e-9, 0.0);
    assert_close(q[0], 0.0, 0.0, 1e-15);
    assert_close(q[2], 0.0, 0.0, 0.0); /* no tilt DOF */
    assert_close(q[3], 0.0, 0.0, 0.0);
    for (k = 0; k < 4; k++)
        assert_close(v[k], 0.0, 0.0, 1e-12);
    td_sim_free(&sim);
    td_model_free(&m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rules),
        cmocka_unit_test(test_coupled_mass),
        cmocka_unit_test(test_static_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
