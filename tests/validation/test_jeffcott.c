/*
 * Jeffcott rotor: critical speed = sqrt(k/m).
 *
 * Model (assembled by td_system_create): a disc of mass m = 10 kg without rotary inertia
 * (Ip = Id = 0, so no gyroscopic coupling) at the middle node of a 2-element Euler-Bernoulli
 * shaft of length L = 1 m, diameter 50 mm, E = 2.11e11 Pa, whose density is negligible
 * (1e-4 kg/m^3: shaft mass 2e-7 kg), on undamped isotropic bearings kb = 1e6 N/m at both ends
 * (pinned: no moment restraint). With a massless shaft the disc sees the static stiffness
 *   1/k = L^3/(48 E I) + 1/(2 kb)
 * exactly (cubic beam elements are exact for nodal loads), so omega_n = sqrt(k/m) at every speed,
 * and the forward and backward whirl branches both cross the 1x line there.
 * Error budget: the shaft mass (2e-8 of m) lowers the frequency by about 7e-9 relative (measured:
 * 7.3e-5 per kg/m^3 of density); round-off grows with the span of the spectrum (the nearly massless
 * shaft DOFs reach 1.6e8 rad/s), measured about 70 eps omega_max/omega_min ~ 1e-8. Asserted: 5e-8 on
 * the frequency, and the required 1e-6 on the critical speed. With no gyroscopic coupling the forward
 * and backward whirls are degenerate; the modal code splits the pair into pure circular whirls.
 */
#include "td_test.h"

#include "touchdown/modal.h"
#include "touchdown/touchdown.h"

#include <math.h>

#define L_SHAFT 1.0
#define D_SHAFT 0.05
#define E_SHAFT 2.11e11
#define KB 1.0e6
#define M_DISC 10.0

static double jeffcott_k(void)
{
    double I = TD_PI * pow(D_SHAFT, 4) / 64.0;
    return 1.0 / (pow(L_SHAFT, 3) / (48.0 * E_SHAFT * I) + 1.0 / (2.0 * KB));
}

static td_system *jeffcott(void)
{
    td_model *m = NULL;
    td_system *s = NULL;
    td_shaft_element el = {L_SHAFT / 2.0, D_SHAFT, 0.0, {E_SHAFT, 8.1e10, 1e-4}};
    td_bearing b0 = {0, KB, KB, 0.0, 0.0}, b2 = {2, KB, KB, 0.0, 0.0};
    td_error err;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_shaft_element(m, &el, NULL), TD_OK);
    assert_int_equal(td_model_add_point_mass(m, 1, M_DISC, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b0, NULL), TD_OK);
    assert_int_equal(td_model_add_bearing(m, &b2, NULL), TD_OK);
    if (td_system_create(m, &s, &err) != TD_OK)
        fail_msg("%s", err.message);
    td_model_free(&m);
    return s;
}

static void test_natural_frequency(void **state)
{
    td_system *s = jeffcott();
    td_modal *md = NULL;
    td_mode a, b;
    double wn = sqrt(jeffcott_k() / M_DISC);
    (void)state;
    assert_int_equal(td_modal_solve(s, 300.0, &md, NULL), TD_OK);
    assert_int_equal(td_modal_get_mode(md, 0, &a), TD_OK);
    assert_int_equal(td_modal_get_mode(md, 1, &b), TD_OK);
    assert_close(a.omega_d, wn, 5e-8, 0.0);
    assert_close(b.omega_d, wn, 5e-8, 0.0);
    /* the degenerate pair comes back as one backward and one forward circular whirl */
    assert_int_equal(a.whirl, TD_WHIRL_BACKWARD);
    assert_int_equal(b.whirl, TD_WHIRL_FORWARD);
    assert_close(b.whirl_index, 1.0, 0.0, 1e-6);
    assert_close(a.zeta, 0.0, 0.0, 1e-10);
    print_message("Jeffcott omega_n = %.12g rad/s, modes %.12g / %.12g (rel err %.2e)\n", wn, a.omega_d, b.omega_d,
                  td_rel_diff(a.omega_d, wn));
    td_modal_free(&md);
    td_system_free(&s);
}

static void test_critical_speed(void **state)
{
    td_system *s = jeffcott();
    td_modal_options opt;
    td_critical_speed cs[8];
    double wn = sqrt(jeffcott_k() / M_DISC);
    int n = 0, i, nf = 0, nb = 0;
    (void)state;
    td_modal_options_default(&opt);
    opt.speed_min = 0.5 * wn;
    opt.speed_max = 1.5 * wn;
    opt.speed_steps = 7;
    assert_int_equal(td_modal_critical_speeds(s, &opt, cs, 8, &n, NULL), TD_OK);
    assert_int_equal(n, 2);
    for (i = 0; i < n; i++) {
        assert_close(cs[i].speed, wn, 1e-6, 0.0);
        assert_int_equal(cs[i].branch, 0);
        nf += cs[i].whirl == TD_WHIRL_FORWARD;
        nb += cs[i].whirl == TD_WHIRL_BACKWARD;
        print_message("Jeffcott critical speed (%s) %.12g rad/s vs sqrt(k/m) = %.12g: rel err %.2e\n",
                      cs[i].whirl == TD_WHIRL_FORWARD ? "forward" : "backward", cs[i].speed, wn,
                      td_rel_diff(cs[i].speed, wn));
    }
    assert_int_equal(nf, 1);
    assert_int_equal(nb, 1);
    td_system_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_natural_frequency),
        cmocka_unit_test(test_critical_speed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
