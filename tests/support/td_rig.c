/* The reference rig in code (td_rig.h). */
#include "td_rig.h"

#include "td_test.h"

#include "touchdown/touchdown.h"

void td_test_build_rig(td_model *m, double speed, double amb_tau, int retainers)
{
    static const int disc_nodes[4] = {1, 5, 7, 11}, amb_nodes[2] = {3, 9}, retainer_nodes[2] = {2, 10};
    const td_shaft_element el = {2.0 / 12.0, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    td_error err;
    int i;
    assert_non_null(m);
    for (i = 0; i < 12; i++)
        if (td_model_add_shaft_element(m, &el, &err) != TD_OK)
            fail_msg("rig shaft: %s", err.message);
    for (i = 0; i < 4; i++) {
        /* the rig table's solid steel disc, as cases/rig.cfg gives it: m, R, rho */
        const td_disc_geometry g = {disc_nodes[i], 0.12, 0.0, 7810.0, 0.0, 10.0};
        td_disc d;
        if (td_disc_from_geometry(&g, &d, &err) != TD_OK || td_model_add_disc(m, &d, &err) != TD_OK)
            fail_msg("rig disc: %s", err.message);
    }
    for (i = 0; i < 2; i++) {
        td_amb a = {amb_nodes[i], amb_nodes[i], 1.0e6, 200.0, 1.0e4, 40.0, amb_tau, 1700.0, 0, 1.2e-3, 0.0, 0.0};
        if (td_model_add_point_mass(m, amb_nodes[i], 14.6, &err) != TD_OK || td_model_add_amb(m, &a, &err) != TD_OK)
            fail_msg("rig AMB: %s", err.message);
    }
    if (retainers == TD_RIG_WITH_RETAINERS)
        for (i = 0; i < 2; i++) {
            td_retainer r = {.node = retainer_nodes[i],
                             .clearance = TD_RIG_CLEARANCE,
                             .shaft_radius = 0.025,
                             .bore_radius = 0.025 + TD_RIG_CLEARANCE,
                             .friction = 0.1,
                             .bore_speed = 0.0,
                             .restitution = 0.0};
            if (td_model_add_retainer(m, &r, &err) != TD_OK)
                fail_msg("rig retainer: %s", err.message);
        }
    if (td_model_set_speed(m, speed, &err) != TD_OK || td_model_validate(m, &err) != TD_OK)
        fail_msg("rig: %s", err.message);
}

td_model *td_test_rig_create(double speed, double amb_tau, int retainers)
{
    td_model *m = NULL;
    assert_int_equal(td_model_create(&m, NULL), TD_OK);
    td_test_build_rig(m, speed, amb_tau, retainers);
    return m;
}
