/*
 * The case-file reader (td_case_load): every documented key lands where it should, the paper
 * cases carry the reference rig's numbers (docs/reference-rig.md), overrides work and bad ones fail,
 * and every broken file under tests/data/bad/ fails with FILE:LINE: KEY in its message.
 */
#include "td_test.h"

#include "case/case_internal.h"
#include "touchdown/case.h"
#include "touchdown/model.h"
#include "touchdown/run.h"
#include "touchdown/sim.h"
#include "touchdown/sweep.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

/* ---- helpers ------------------------------------------------------------------------------ */

static td_case *load_ok(const char *relative, const char *const *ov, int n)
{
    td_case *c = NULL;
    td_error err;
    td_status st = td_case_load(td_source_path(relative), ov, n, &c, &err);
    if (st != TD_OK)
        print_error("td_case_load(%s): %s\n", relative, err.message);
    assert_int_equal(st, TD_OK);
    assert_non_null(c);
    return c;
}

/* A scratch directory in the build tree for files made at test time. */
static const char *scratch(const char *name)
{
    static char buf[4][1024];
    static int slot;
    slot = (slot + 1) % 4;
    mkdir(TD_BINARY_DIR "/tests", 0755);
    mkdir(TD_BINARY_DIR "/tests/case-scratch", 0755);
    snprintf(buf[slot], sizeof buf[slot], "%s/tests/case-scratch/%s", TD_BINARY_DIR, name);
    return buf[slot];
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void assert_contains(const char *haystack, const char *needle)
{
    if (!strstr(haystack, needle)) {
        print_error("expected \"%s\" in \"%s\"\n", needle, haystack);
        fail();
    }
}

/* ---- the reference rig and the paper cases ------------------------------------------------ */

/* Closed-form rig mass (docs/reference-rig.md): shaft rho pi r^2 L + four 10 kg discs + two 14.6 kg
 * AMB journals. */
static double rig_mass(void)
{
    return 7810.0 * TD_PI * 0.025 * 0.025 * 2.0 + 4 * 10.0 + 2 * 14.6;
}

static void check_rig(const td_model *m)
{
    static const int disc_nodes[] = {1, 5, 7, 11};
    td_shaft_element el;
    td_shaft_options so;
    td_disc d;
    td_amb a;
    td_retainer r;
    double gx, gy;
    int i;

    assert_int_equal(td_model_node_count(m), 13);
    assert_int_equal(td_model_shaft_element_count(m), 12);
    for (i = 0; i < 12; i++) {
        assert_int_equal(td_model_get_shaft_element(m, i, &el), TD_OK);
        assert_close(el.length, 1.0 / 6.0, 1e-15, 0.0);
        assert_close(el.outer_diameter, 0.05, 0.0, 0.0);
        assert_close(el.inner_diameter, 0.0, 0.0, 0.0);
        assert_close(el.material.E, 2.11e11, 0.0, 0.0);
        assert_close(el.material.G, 8.1e10, 0.0, 0.0);
        assert_close(el.material.density, 7810.0, 0.0, 0.0);
    }
    assert_close(td_model_node_position(m, 12), 2.0, 1e-14, 0.0);
    td_model_shaft_options(m, &so);
    assert_int_equal(so.beam, TD_BEAM_EULER_BERNOULLI);
    assert_int_equal(so.mass, TD_MASS_CONSISTENT);
    assert_close(so.rayleigh_alpha, 0.0, 0.0, 0.0);
    assert_close(so.rayleigh_beta, 0.0, 0.0, 0.0);

    /* 4 discs then 2 point masses */
    assert_int_equal(td_model_disc_count(m), 6);
    for (i = 0; i < 4; i++) {
        assert_int_equal(td_model_get_disc(m, i, &d), TD_OK);
        assert_int_equal(d.node, disc_nodes[i]);
        assert_close(d.mass, 10.0, 0.0, 0.0);
        assert_close(d.Ip, 10.0 * 0.12 * 0.12 / 2.0, 1e-15, 0.0);
        /* Id = m (3R^2 + t^2)/12 with t = m / (rho pi R^2), exactly (not the rounded 0.036668) */
        assert_close(d.Id, 10.0 * (3 * 0.0144 + pow(10.0 / (7810.0 * TD_PI * 0.0144), 2)) / 12.0, 1e-15, 0.0);
    }
    for (i = 4; i < 6; i++) {
        assert_int_equal(td_model_get_disc(m, i, &d), TD_OK);
        assert_int_equal(d.node, i == 4 ? 3 : 9);
        assert_close(d.mass, 14.6, 0.0, 0.0);
        assert_close(d.Ip, 0.0, 0.0, 0.0);
        assert_close(d.Id, 0.0, 0.0, 0.0);
    }
    assert_close(td_model_total_mass(m), rig_mass(), 1e-13, 0.0);
    assert_close(td_model_total_mass(m), 99.87, 0.0, 0.005); /* "rotor mass 99.87 kg in all" */

    assert_int_equal(td_model_amb_count(m), 2);
    for (i = 0; i < 2; i++) {
        assert_int_equal(td_model_get_amb(m, i, &a), TD_OK);
        assert_int_equal(a.node, i == 0 ? 3 : 9);
        assert_int_equal(a.sensor_node, a.node);
        assert_close(a.ks, 1.0e6, 0.0, 0.0);
        assert_close(a.ki, 200.0, 0.0, 0.0);
        assert_close(a.kp, 1.0e4, 0.0, 0.0);
        assert_close(a.kd, 40.0, 0.0, 0.0);
        assert_close(a.tau, 1.0 / (2.0 * TD_PI * 100.0), 1e-15, 0.0);
        assert_close(a.force_capacity, 1700.0, 0.0, 0.0);
        assert_int_equal(a.saturation, 0);
        assert_close(a.air_gap, 1.2e-3, 0.0, 0.0);
    }
    assert_int_equal(td_model_bearing_count(m), 0);
    assert_int_equal(td_model_retainer_count(m), 2);
    for (i = 0; i < 2; i++) {
        assert_int_equal(td_model_get_retainer(m, i, &r), TD_OK);
        assert_int_equal(r.node, i == 0 ? 2 : 10);
        assert_close(r.clearance, 0.75e-3, 0.0, 0.0);
        assert_close(r.shaft_radius, 0.025, 0.0, 0.0);
        assert_close(r.bore_radius, 0.025 + 0.75e-3, 1e-15, 0.0);
        assert_close(r.friction, 0.1, 0.0, 0.0);
        assert_close(r.bore_speed, 0.0, 0.0, 0.0);
        assert_close(r.restitution, 0.0, 0.0, 0.0);
    }
    td_model_gravity(m, &gx, &gy);
    assert_close(gx, 0.0, 0.0, 0.0);
    assert_close(gy, 0.0, 0.0, 0.0);
    assert_int_equal(td_model_validate(m, NULL), TD_OK);
}

typedef struct paper_case {
    const char *file, *name;
    double speed, u_low, u_high; /* unbalance before 0.1 s and after 1.1 s, and in between */
    td_contact_model contact;
    double kc;
} paper_case;

static const paper_case paper_cases[] = {
    {"cases/paper-a.cfg", "paper-a", 90.0, 0.02, 0.10, TD_CONTACT_CONSTRAINT, 0.0},
    {"cases/paper-b.cfg", "paper-b", 190.0, 0.01, 0.03, TD_CONTACT_CONSTRAINT, 0.0},
    {"cases/paper-c.cfg", "paper-c", 90.0, 0.02, 0.10, TD_CONTACT_PENALTY, 1.25e12},
    {"cases/paper-d-kc1.25e12.cfg", "paper-d-kc1.25e12", 190.0, 0.01, 0.03, TD_CONTACT_PENALTY, 1.25e12},
    {"cases/paper-d-kc1.25e10.cfg", "paper-d-kc1.25e10", 190.0, 0.01, 0.03, TD_CONTACT_PENALTY, 1.25e10},
};

static void test_paper_cases(void **state)
{
    size_t k;
    (void)state;
    for (k = 0; k < sizeof paper_cases / sizeof paper_cases[0]; k++) {
        const paper_case *p = &paper_cases[k];
        td_case *c = load_ok(p->file, NULL, 0);
        const td_model *m = td_case_model(c);
        const td_sim_options *so = td_case_sim_options(c);
        td_unbalance u;
        td_change ch;

        check_rig(m);
        assert_string_equal(td_case_name(c), p->name);
        assert_string_equal(td_case_path(c), td_source_path(p->file));
        assert_close(td_model_speed(m), p->speed, 0.0, 0.0);
        assert_close(td_case_end_time(c), 2.0, 0.0, 0.0);
        assert_int_equal(so->start, TD_START_AUTO);
        assert_int_equal(so->contact.model, p->contact);
        if (p->contact == TD_CONTACT_PENALTY) {
            assert_close(so->contact.stiffness, p->kc, 0.0, 0.0);
            assert_close(so->contact.exponent, 1.0, 0.0, 0.0);
            assert_int_equal(so->contact.damping, TD_DAMPING_NONE);
        }
        /* unbalance at the NDE disc (node 1): U0 at t = 0, stepped at 0.1 s and back at 1.1 s */
        assert_int_equal(td_model_unbalance_count(m), 1);
        assert_int_equal(td_model_get_unbalance(m, 0, &u), TD_OK);
        assert_int_equal(u.node, 1);
        assert_close(u.magnitude, p->u_low, 0.0, 0.0);
        assert_close(u.phase, 0.0, 0.0, 0.0);
        assert_int_equal(td_model_change_count(m), 2);
        assert_int_equal(td_model_get_change(m, 0, &ch), TD_OK);
        assert_close(ch.time, 0.1, 0.0, 0.0);
        assert_int_equal(ch.kind, TD_CHANGE_UNBALANCE);
        assert_int_equal(ch.index, 0);
        assert_close(ch.magnitude, p->u_high, 0.0, 0.0);
        assert_int_equal(td_model_get_change(m, 1, &ch), TD_OK);
        assert_close(ch.time, 1.1, 0.0, 0.0);
        assert_close(ch.magnitude, p->u_low, 0.0, 0.0);
        /* the include is expanded in the text kept with the results */
        assert_contains(td_case_text(c), "# >>> @include \"rig.cfg\"");
        assert_contains(td_case_text(c), "force_capacity = 1700.0");
        assert_contains(td_case_description(c), "Paper case");
        td_case_free(&c);
        assert_null(c);
    }
}

/* The expanded text is a self-contained case that reads back to the same machine. */
static void test_text_is_self_contained(void **state)
{
    td_case *a = load_ok("cases/paper-c.cfg", NULL, 0), *b = NULL;
    const char *copy = scratch("paper-c-expanded.cfg");
    td_error err;
    td_change ca, cb;
    int i;
    (void)state;
    assert_null(strstr(td_case_text(a), "\n@include"));
    write_file(copy, td_case_text(a));
    assert_int_equal(td_case_load(copy, NULL, 0, &b, &err), TD_OK);
    check_rig(td_case_model(b));
    assert_close(td_model_speed(td_case_model(b)), td_model_speed(td_case_model(a)), 0.0, 0.0);
    assert_int_equal(td_model_change_count(td_case_model(b)), td_model_change_count(td_case_model(a)));
    for (i = 0; i < td_model_change_count(td_case_model(a)); i++) {
        td_model_get_change(td_case_model(a), i, &ca);
        td_model_get_change(td_case_model(b), i, &cb);
        assert_memory_equal(&ca, &cb, sizeof ca);
    }
    assert_memory_equal(td_case_sim_options(a), td_case_sim_options(b), sizeof(td_sim_options));
    assert_string_equal(td_case_text(a), td_case_text(b)); /* nothing left to expand */
    td_case_free(&a);
    td_case_free(&b);
}

static void test_other_examples(void **state)
{
    td_case *c = load_ok("cases/rotor-drop.cfg", NULL, 0);
    const td_model *m = td_case_model(c);
    td_change ch;
    td_disc d;
    double gx, gy, mass;
    (void)state;
    assert_close(td_model_total_mass(m), rig_mass(), 1e-13, 0.0);
    td_model_gravity(m, &gx, &gy);
    assert_close(gx, 0.0, 0.0, 0.0);
    assert_close(gy, -9.81, 1e-15, 0.0);
    assert_int_equal(td_model_change_count(m), 2);
    assert_int_equal(td_model_get_change(m, 0, &ch), TD_OK);
    assert_int_equal(ch.kind, TD_CHANGE_AMB_OFF);
    assert_int_equal(ch.index, 0);
    assert_close(ch.time, 0.1, 0.0, 0.0);
    assert_int_equal(td_model_get_change(m, 1, &ch), TD_OK);
    assert_int_equal(ch.kind, TD_CHANGE_AMB_OFF);
    assert_int_equal(ch.index, 1);
    assert_close(td_case_end_time(c), 0.5, 0.0, 0.0);
    assert_string_equal(td_case_output_options(c)->hdf5_path, "rotor-drop.h5");
    td_case_free(&c);

    c = load_ok("cases/jeffcott.cfg", NULL, 0);
    m = td_case_model(c);
    assert_int_equal(td_model_node_count(m), 7);
    assert_int_equal(td_model_bearing_count(m), 2);
    assert_int_equal(td_model_amb_count(m), 0);
    assert_int_equal(td_model_retainer_count(m), 0);
    /* disc from geometry: m = rho pi R^2 t, Ip = m R^2/2, Id = m (3R^2 + t^2)/12 */
    mass = 7810.0 * TD_PI * 0.1 * 0.1 * 0.02;
    assert_int_equal(td_model_get_disc(m, 0, &d), TD_OK);
    assert_close(d.mass, mass, 1e-14, 0.0);
    assert_close(d.Ip, mass * 0.01 / 2.0, 1e-14, 0.0);
    assert_close(d.Id, mass * (3 * 0.01 + 0.02 * 0.02) / 12.0, 1e-14, 0.0);
    assert_int_equal(td_case_modal_options(c)->response_speed_count, 4);
    td_case_free(&c);
}

/* ---- every key ---------------------------------------------------------------------------- */

static void check_element(const td_model *m, int i, double od, double id, double E, double G, double rho)
{
    td_shaft_element el;
    assert_int_equal(td_model_get_shaft_element(m, i, &el), TD_OK);
    assert_close(el.length, 0.2, 1e-15, 0.0);
    assert_close(el.outer_diameter, od, 0.0, 0.0);
    assert_close(el.inner_diameter, id, 0.0, 0.0);
    assert_close(el.material.E, E, 0.0, 0.0);
    assert_close(el.material.G, G, 0.0, 0.0);
    assert_close(el.material.density, rho, 0.0, 0.0);
}

/* heat: retainer 0's network as written, retainer 1 without one */
static void check_all_keys_thermal(const td_model *m)
{
    td_retainer_thermal t;
    assert_int_equal(td_model_get_retainer_thermal(m, 0, &t), 1);
    assert_close(t.race_capacity, 45.0, 0.0, 0.0);
    assert_close(t.housing_capacity, 600.0, 0.0, 0.0);
    assert_close(t.race_housing_conductance, 3.0, 0.0, 0.0);
    assert_close(t.housing_ambient_conductance, 1.2, 0.0, 0.0);
    assert_close(t.expansion, 1.1e-5, 0.0, 0.0);
    assert_int_equal(td_model_get_retainer_thermal(m, 1, &t), 0);
}

/* housing body: the tilting housing on two mounts, the second undamped (damping's default 0). */
static void check_all_keys_housing_body(const td_model *m)
{
    td_housing_body b;
    assert_int_equal(td_model_get_housing_body(m, &b), 1);
    assert_int_equal(td_model_housing_body_dofs(m), 4);
    assert_close(b.mass, 40.0, 0.0, 0.0);
    assert_close(b.inertia, 1.5, 0.0, 0.0);
    assert_close(b.centre, 0.3, 0.0, 0.0);
    assert_int_equal(b.mount_count, 2);
    assert_close(b.mounts[0].position, 0.0, 0.0, 0.0);
    assert_close(b.mounts[0].stiffness, 2.0e7, 0.0, 0.0);
    assert_close(b.mounts[0].damping, 2.0e3, 0.0, 0.0);
    assert_close(b.mounts[1].position, 0.6, 0.0, 0.0);
    assert_close(b.mounts[1].stiffness, 3.0e7, 0.0, 0.0);
    assert_close(b.mounts[1].damping, 0.0, 0.0, 0.0);
}

/* housing motion: the shock (its direction normalised), the record shifted by 0.1 s and doubled, the ramp. */
static void check_all_keys_housing(const td_model *m)
{
    td_housing_pulse p;
    td_housing_motion hm;
    assert_true(td_model_has_housing_motion(m));
    assert_close(td_model_housing_reference(m), 0.25, 0.0, 0.0);
    assert_int_equal(td_model_housing_shock_count(m), 1);
    assert_int_equal(td_model_get_housing_shock(m, 0, &p), TD_OK);
    assert_int_equal(p.shape, TD_PULSE_HALF_SINE);
    assert_close(p.amplitude, 490.0, 0.0, 0.0);
    assert_close(p.duration, 0.011, 0.0, 0.0);
    assert_close(p.start, 0.05, 0.0, 0.0);
    assert_close(p.direction[0], 0.0, 0.0, 0.0);
    assert_close(p.direction[1], 1.0, 0.0, 0.0);
    assert_int_equal(td_model_housing_history_count(m), 3);
    td_model_housing_motion_at(m, 0.11, &hm); /* the record's peak: the shock is over */
    assert_close(hm.acceleration[0], 20.0, 1e-12, 0.0);
    assert_close(hm.acceleration[1], -10.0, 1e-12, 0.0);
    assert_int_equal(td_model_housing_rotation_count(m), 1);
    assert_int_equal(td_model_get_housing_rotation(m, 0, &p), TD_OK);
    assert_int_equal(p.shape, TD_PULSE_RAMP);
    assert_close(p.amplitude, 0.1, 0.0, 0.0);
    assert_close(p.direction[0], 1.0, 0.0, 0.0);
    assert_close(hm.rate[0], 0.1 * 0.01 / 0.5, 1e-15, 0.0);
    check_all_keys_housing_body(m);
}

/* retainers[0].bearing and limits of all-keys.cfg; retainer 1 has no bearing. */
static void check_all_keys_assessment(const td_model *m)
{
    td_retainer_bearing b;
    td_limits l;
    assert_int_equal(td_model_get_retainer_bearing(m, 0, &b), TD_OK);
    assert_close(b.static_rating, 18000.0, 0.0, 0.0);
    assert_close(b.dynamic_rating, 27000.0, 0.0, 0.0);
    assert_close(b.life_exponent, 3.3, 0.0, 0.0);
    assert_int_equal(b.balls, 10);
    assert_close(b.ball_diameter, 0.0111, 0.0, 0.0);
    assert_close(b.pitch_diameter, 0.0775, 0.0, 0.0);
    assert_close(b.groove_conformity, 0.53, 0.0, 0.0);
    assert_close(b.width, 0.018, 0.0, 0.0);
    assert_int_equal(td_model_get_retainer_bearing(m, 1, &b), TD_OK);
    assert_true(b.static_rating == 0.0 && b.balls == 0 && b.width == 0.0);
    assert_close(b.life_exponent, 3.0, 0.0, 0.0);
    assert_close(b.groove_conformity, 0.52, 0.0, 0.0);
    assert_int_equal(td_model_get_retainer_bearing(m, 2, &b), TD_ERR_INVALID);
    td_model_get_limits(m, &l);
    assert_close(l.zones.ab, 0.25, 0.0, 0.0);
    assert_close(l.zones.bc, 0.35, 0.0, 0.0);
    assert_close(l.zones.cd, 0.45, 0.0, 0.0);
    assert_close(l.temperature_rise, 60.0, 0.0, 0.0);
    assert_close(l.drops, 200.0, 0.0, 0.0);
    assert_int_equal(l.zone, TD_ZONE_C);
}
static void check_all_keys_model(const td_model *m)
{
    td_shaft_options so;
    td_disc d;
    td_amb a;
    td_bearing b;
    td_retainer r;
    td_unbalance u;
    td_change ch;
    double gx, gy, disc_m, shaft_m;
    int i;

    assert_close(td_model_speed(m), 150.0, 0.0, 0.0); /* written as the integer 150 */
    assert_int_equal(td_model_shaft_element_count(m), 6);
    check_element(m, 0, 0.06, 0.0, 1.1e11, 4.2e10, 4500.0);
    check_element(m, 1, 0.06, 0.0, 1.1e11, 4.2e10, 4500.0);
    check_element(m, 2, 0.04, 0.01, 2.0e11, 7.7e10, 7800.0);
    check_element(m, 3, 0.04, 0.01, 2.0e11, 7.7e10, 7800.0);
    check_element(m, 4, 0.04, 0.02, 2.0e11, 7.7e10, 2700.0);
    check_element(m, 5, 0.04, 0.01, 2.0e11, 7.7e10, 7800.0);
    td_model_shaft_options(m, &so);
    assert_int_equal(so.beam, TD_BEAM_TIMOSHENKO);
    assert_int_equal(so.shear, TD_SHEAR_COWPER);
    assert_int_equal(so.mass, TD_MASS_LUMPED);
    assert_close(so.rayleigh_alpha, 0.5, 0.0, 0.0);
    assert_close(so.rayleigh_beta, 1.0e-5, 0.0, 0.0);

    assert_int_equal(td_model_disc_count(m), 3);
    td_model_get_disc(m, 0, &d);
    assert_int_equal(d.node, 1);
    assert_close(d.mass, 8.0, 0.0, 0.0);
    assert_close(d.Ip, 0.05, 0.0, 0.0);
    assert_close(d.Id, 0.03, 0.0, 0.0);
    /* bored disc: m = rho pi (R^2 - r^2) t, Ip = m (R^2 + r^2)/2, Id = m (3 (R^2 + r^2) + t^2)/12 */
    disc_m = 7800.0 * TD_PI * (0.01 - 0.0004) * 0.02;
    td_model_get_disc(m, 1, &d);
    assert_int_equal(d.node, 5);
    assert_close(d.mass, disc_m, 1e-14, 0.0);
    assert_close(d.Ip, disc_m * 0.0104 / 2.0, 1e-14, 0.0);
    assert_close(d.Id, disc_m * (3 * 0.0104 + 0.0004) / 12.0, 1e-14, 0.0);
    td_model_get_disc(m, 2, &d);
    assert_int_equal(d.node, 2);
    assert_close(d.mass, 3.5, 0.0, 0.0);
    assert_close(d.Ip + d.Id, 0.0, 0.0, 0.0);
    shaft_m = 0.2 * TD_PI / 4.0 * (2 * 4500.0 * 0.0036 + 3 * 7800.0 * (0.0016 - 0.0001) + 2700.0 * (0.0016 - 0.0004));
    assert_close(td_model_total_mass(m), shaft_m + 8.0 + disc_m + 3.5, 1e-13, 0.0);

    assert_int_equal(td_model_amb_count(m), 2);
    td_model_get_amb(m, 0, &a);
    assert_int_equal(a.node, 2);
    assert_int_equal(a.sensor_node, 1);
    assert_close(a.ks, 5.0e5, 0.0, 0.0);
    assert_close(a.ki, 150.0, 0.0, 0.0);
    assert_close(a.kp, 8.0e3, 0.0, 0.0);
    assert_close(a.kd, 30.0, 0.0, 0.0);
    assert_close(a.tau, 2.0e-3, 0.0, 0.0);
    assert_close(a.force_capacity, 1200.0, 0.0, 0.0);
    assert_int_equal(a.saturation, 1);
    assert_close(a.air_gap, 1.0e-3, 0.0, 0.0);
    assert_close(a.slew_rate, 400.0, 0.0, 0.0);
    td_model_get_amb(m, 1, &a);
    assert_int_equal(a.node, 4);
    assert_int_equal(a.sensor_node, 4);                           /* default: collocated */
    assert_close(a.tau, 1.0 / (2.0 * TD_PI * 200.0), 1e-15, 0.0); /* from the bandwidth */
    assert_int_equal(a.saturation, 0);
    assert_close(a.air_gap, 0.0, 0.0, 0.0);
    assert_close(a.kint, 1.0e5, 0.0, 0.0);
    assert_true(a.slew_rate == 0.0); /* default: no slew limit */

    assert_int_equal(td_model_bearing_count(m), 2);
    td_model_get_bearing(m, 0, &b);
    assert_int_equal(b.node, 0);
    assert_close(b.kxx, 1.0e7, 0.0, 0.0);
    assert_close(b.kyy, 2.0e7, 0.0, 0.0);
    assert_close(b.cxx, 100.0, 0.0, 0.0);
    assert_close(b.cyy, 200.0, 0.0, 0.0);
    td_model_get_bearing(m, 1, &b);
    assert_int_equal(b.node, 6);
    assert_close(b.kyy, 3.0e7, 0.0, 0.0); /* default kxx */
    assert_close(b.cyy, 50.0, 0.0, 0.0);  /* default cxx */

    assert_int_equal(td_model_retainer_count(m), 2);
    td_model_get_retainer(m, 0, &r);
    assert_int_equal(r.node, 1);
    assert_close(r.clearance, 0.5e-3, 0.0, 0.0);
    assert_close(r.shaft_radius, 0.03, 0.0, 0.0);
    assert_close(r.bore_radius, 0.0305, 0.0, 0.0);
    assert_close(r.friction, 0.15, 0.0, 0.0);
    assert_close(r.bore_speed, 10.0, 0.0, 0.0);
    assert_close(r.restitution, 0.3, 0.0, 0.0);
    assert_int_equal(r.stick, 1);
    assert_close(r.race.inertia, 1.0e-4, 0.0, 0.0);
    assert_close(r.race.drag_torque, 0.01, 0.0, 0.0);
    assert_close(r.race.drag_viscous, 1.0e-6, 0.0, 0.0);
    assert_close(r.race.mass, 0.3, 0.0, 0.0);
    assert_close(r.race.mount_stiffness, 1.0e8, 0.0, 0.0);
    assert_close(r.race.mount_damping, 500.0, 0.0, 0.0);
    assert_close(r.contact.stiffness, 1.0e9, 0.0, 0.0);
    assert_close(r.contact.exponent, 1.5, 0.0, 0.0);
    assert_int_equal(r.contact.damping, TD_DAMPING_KELVIN_VOIGT);
    assert_close(r.contact.damping_coefficient, 1000.0, 0.0, 0.0);
    check_all_keys_thermal(m);
    check_all_keys_assessment(m);
    td_model_get_retainer(m, 1, &r);
    assert_int_equal(r.node, 5);
    assert_close(r.bore_radius, 0.0204, 1e-15, 0.0); /* default shaft_radius + clearance */
    assert_close(r.bore_speed, 0.0, 0.0, 0.0);
    assert_close(r.restitution, 0.0, 0.0, 0.0);
    assert_int_equal(r.stick, 0); /* the paper's retainer: no race, mount, own contact or stick */
    assert_false(td_retainer_has_race(&r));
    assert_close(r.contact.stiffness, 0.0, 0.0, 0.0);

    assert_int_equal(td_model_unbalance_count(m), 2);
    td_model_get_unbalance(m, 0, &u);
    assert_int_equal(u.node, 5);
    assert_close(u.magnitude, 0.001, 0.0, 0.0);
    assert_close(u.phase, 0.5, 0.0, 0.0);
    td_model_get_unbalance(m, 1, &u);
    assert_int_equal(u.node, 1);
    assert_close(u.phase, 0.0, 0.0, 0.0);

    /* the schedule comes back sorted by time */
    assert_int_equal(td_model_change_count(m), 4);
    td_model_get_change(m, 0, &ch);
    assert_close(ch.time, 0.05, 0.0, 0.0);
    assert_int_equal(ch.kind, TD_CHANGE_UNBALANCE);
    assert_int_equal(ch.index, 1);
    assert_close(ch.magnitude, 0.004, 0.0, 0.0);
    assert_close(ch.phase, 1.0, 0.0, 0.0);
    td_model_get_change(m, 1, &ch);
    assert_close(ch.time, 0.1, 0.0, 0.0);
    assert_int_equal(ch.index, 0);
    assert_close(ch.magnitude, 0.0, 0.0, 0.0);
    assert_close(ch.phase, 0.5, 0.0, 0.0); /* default: the unbalance's own phase */
    td_model_get_change(m, 2, &ch);
    assert_close(ch.time, 0.15, 0.0, 0.0);
    assert_int_equal(ch.kind, TD_CHANGE_AMB_OFF);
    assert_int_equal(ch.index, 0);
    td_model_get_change(m, 3, &ch);
    assert_close(ch.time, 0.2, 0.0, 0.0);
    assert_int_equal(ch.kind, TD_CHANGE_AMB_ON);

    td_model_gravity(m, &gx, &gy); /* 9.8 along [3, -4]/5 */
    assert_close(gx, 9.8 * 0.6, 1e-15, 0.0);
    assert_close(gy, -9.8 * 0.8, 1e-15, 0.0);
    check_all_keys_housing(m);
    (void)i;
}

static void test_all_keys(void **state)
{
    td_case *c = load_ok("tests/data/case/all-keys.cfg", NULL, 0);
    const td_sim_options *so = td_case_sim_options(c);
    const td_output_options *oo = td_case_output_options(c);
    const td_modal_options *mo = td_case_modal_options(c);
    (void)state;
    check_all_keys_model(td_case_model(c));
    assert_string_equal(td_case_description(c), "every key");
    assert_string_equal(td_case_name(c), "all-keys");
    assert_close(td_case_end_time(c), 0.25, 0.0, 0.0);
    assert_close(td_model_reduction(td_case_model(c)), 2500.0, 0.0, 0.0);
    assert_int_equal(so->start, TD_START_REST);
    assert_int_equal(so->contact.model, TD_CONTACT_PENALTY);
    assert_close(so->contact.stiffness, 2.0e9, 0.0, 0.0);
    assert_close(so->contact.exponent, 1.5, 0.0, 0.0);
    assert_int_equal(so->contact.damping, TD_DAMPING_HUNT_CROSSLEY);
    assert_close(so->contact.damping_coefficient, 0.2, 0.0, 0.0);
    assert_close(so->solver.rtol, 1e-7, 0.0, 0.0);
    assert_close(so->solver.atol, 1e-10, 0.0, 0.0);
    assert_close(so->solver.max_step, 1e-4, 0.0, 0.0);
    assert_close(so->solver.initial_step, 1e-6, 0.0, 0.0);
    assert_int_equal(so->solver.max_order, 3);
    assert_int_equal(so->solver.linear_solver, TD_LINSOL_DENSE);
    assert_int_equal(so->solver.free_flight, 0);
    assert_string_equal(oo->hdf5_path, "out/all.h5");
    assert_string_equal(oo->csv_path, "out/all.csv");
    assert_close(oo->sample_rate, 2000.0, 0.0, 0.0);
    assert_int_equal(oo->compression, 5);
    assert_true(oo->section_after == 0.25);
    assert_true(oo->window == 0.05); /* long runs */
    assert_int_equal(oo->omit_events, 1);
    assert_int_equal(oo->end_at_rest, 1);
    assert_int_equal(oo->node_count, 2);
    assert_int_equal(oo->nodes[0], 1);
    assert_int_equal(oo->nodes[1], 5);
    assert_close(mo->speed_min, 10.0, 0.0, 0.0);
    assert_close(mo->speed_max, 500.0, 0.0, 0.0);
    assert_int_equal(mo->speed_steps, 50);
    assert_int_equal(mo->mode_count, 4);
    assert_int_equal(mo->response_speed_count, 2);
    assert_close(mo->response_speeds[0], 100.0, 0.0, 0.0);
    assert_close(mo->response_speeds[1], 200.0, 0.0, 0.0);
    td_case_free(&c);
}

/* The other forms, and the defaults of everything left out. */
static void test_other_forms_and_defaults(void **state)
{
    td_case *c = load_ok("tests/data/case/all-keys-nodes.cfg", NULL, 0);
    const td_model *m = td_case_model(c);
    td_sim_options sdef;
    td_output_options odef;
    td_modal_options mdef;
    td_shaft_element el;
    td_shaft_options so;
    td_bearing b;
    double gx, gy;
    (void)state;
    /* 3 elements from the node positions, each split in two */
    assert_int_equal(td_model_node_count(m), 7);
    td_model_get_shaft_element(m, 1, &el);
    assert_close(el.length, 0.05, 1e-15, 0.0);
    assert_close(el.inner_diameter, 0.0, 0.0, 0.0);
    td_model_get_shaft_element(m, 2, &el);
    assert_close(el.length, 0.075, 1e-14, 0.0);
    td_model_get_shaft_element(m, 5, &el);
    assert_close(el.length, 0.1, 1e-14, 0.0);
    assert_close(td_model_node_position(m, 6), 0.45, 1e-14, 0.0);
    td_model_shaft_options(m, &so);
    assert_int_equal(so.beam, TD_BEAM_EULER_BERNOULLI);
    assert_int_equal(so.mass, TD_MASS_CONSISTENT);
    /* damping ratio 0.02 at 50 and 500 Hz: the Rayleigh fit through w1 = 100 pi, w2 = 1000 pi */
    assert_close(so.rayleigh_alpha, 2.0 * 0.02 * (100.0 * TD_PI) * (1000.0 * TD_PI) / (1100.0 * TD_PI), 1e-14, 0.0);
    assert_close(so.rayleigh_beta, 2.0 * 0.02 / (1100.0 * TD_PI), 1e-14, 0.0);
    assert_close(so.rayleigh_alpha / (2.0 * 100.0 * TD_PI) + so.rayleigh_beta * 100.0 * TD_PI / 2.0, 0.02, 1e-14, 0.0);
    assert_int_equal(td_model_disc_count(m), 0);
    assert_int_equal(td_model_amb_count(m), 0);
    td_model_get_bearing(m, 1, &b);
    assert_int_equal(b.node, 6); /* node 3 as written */
    assert_close(b.kyy, 1e6, 0.0, 0.0);
    assert_close(b.cxx + b.cyy, 0.0, 0.0, 0.0);
    td_model_gravity(m, &gx, &gy); /* a gravity group is on by default, along -y */
    assert_close(gx, 0.0, 0.0, 0.0);
    assert_close(gy, -9.81, 1e-15, 0.0);
    assert_close(td_model_speed(m), 0.0, 0.0, 0.0);
    assert_string_equal(td_case_description(c), "");
    /* the history from housing-record.csv: ms and g to s and m/s^2; the reference the centre of mass */
    assert_int_equal(td_model_housing_history_count(m), 3);
    {
        td_housing_motion hm;
        td_model_housing_motion_at(m, 0.005, &hm);
        assert_close(hm.acceleration[0], 0.5 * 9.80665, 1e-15, 0.0);
        assert_close(hm.acceleration[1], -9.80665, 1e-15, 0.0);
    }
    assert_close(td_model_housing_reference(m), td_model_mass_centre(m), 0.0, 0.0);

    td_sim_options_default(&sdef);
    sdef.contact.damping = TD_DAMPING_KELVIN_VOIGT;
    sdef.contact.damping_coefficient = 1.0e3;
    assert_memory_equal(td_case_sim_options(c), &sdef, sizeof sdef);
    td_output_options_default(&odef);
    odef.leap_burst = 0.1; /* projective leap: the file's leap group */
    odef.leap_factor = 5.0;
    odef.leap_heal = 0.05;
    odef.leap_start = 0.2;
    assert_memory_equal(td_case_output_options(c), &odef, sizeof odef);
    td_modal_options_default(&mdef);
    assert_memory_equal(td_case_modal_options(c), &mdef, sizeof mdef);
    td_case_free(&c);
}

/* A retainer's own contact stiffness of 0 (documented: "0: the run's contact model") is accepted,
 * with or without the other keys of its group at their defaults; an exponent not written is kept
 * as 0 ("taken as 1", model.h), so the rule that a law needs a stiffness never meets a value the
 * case does not hold. */
static void test_retainer_contact_stiffness_zero(void **state)
{
    const char *ov[2] = {"retainers[0].contact = { stiffness = 0.0; }",
                         "retainers[1].contact = { stiffness = 0.0; damping = \"none\"; }"};
    td_case *c = load_ok("cases/paper-a.cfg", ov, 2);
    td_retainer r;
    (void)state;
    assert_int_equal(td_model_get_retainer(td_case_model(c), 0, &r), TD_OK);
    assert_close(r.contact.stiffness, 0.0, 0.0, 0.0);
    assert_close(r.contact.exponent, 0.0, 0.0, 0.0);
    td_case_free(&c);
}

/* Every key in the tables of docs/case-format.md is used by the all-keys files, and every key the
 * reader accepts is documented (the reader lists the valid keys of a group when it meets an
 * unknown one far from all of them). */
static void test_docs_match_reader(void **state)
{
    static const char *const groups[] = {"",
                                         "shaft.",
                                         "shaft.material.",
                                         "shaft.sections[0].",
                                         "shaft.rayleigh.",
                                         "shaft.damping.",
                                         "discs[0].",
                                         "point_masses[0].",
                                         "ambs[0].",
                                         "bearings[0].",
                                         "retainers[0].",
                                         "retainers[0].race.",
                                         "retainers[0].mount.",
                                         "retainers[0].contact.",
                                         "retainers[0].bearing.",
                                         "unbalances[0].",
                                         "schedule[0].",
                                         "gravity.",
                                         "reduction.",
                                         "contact.",
                                         "solver.",
                                         "output.",
                                         "modal.",
                                         "sweep.",
                                         "controllers[0].",
                                         "controllers[0].law[0].",
                                         "controllers[0].law[0].pid.",
                                         "controllers[0].law[1].leadlag.",
                                         "controllers[0].law[2].lowpass.",
                                         "controllers[0].law[3].notch.",
                                         "controllers[0].law[4].tf.",
                                         "controllers[0].law[5].zpk.",
                                         "controllers[0].law[7].ss.",
                                         "controllers[0].law[8].resonant.",
                                         "recovery.",
                                         "recovery.detect.",
                                         "recovery.release.",
                                         "limits.",
                                         "housing.",
                                         "housing.shocks[0].",
                                         "housing.history.",
                                         "housing.rotation[0]."};
    char *doc = td_test_read_file(td_source_path("docs/case-format.md"));
    char *a = td_test_read_file(td_source_path("tests/data/case/all-keys.cfg"));
    char *b = td_test_read_file(td_source_path("tests/data/case/all-keys-nodes.cfg"));
    char *ctl = td_test_read_file(td_source_path("tests/data/case/all-keys-controllers.cfg"));
    const char *p = doc;
    int documented = 0;
    size_t g;
    (void)state;
    while ((p = strstr(p, "\n| `")) != NULL) {
        char key[128], leaf[160];
        const char *end = strchr(p + 4, '`'), *dot;
        size_t n = (size_t)(end - (p + 4));
        assert_true(n < sizeof key);
        memcpy(key, p + 4, n);
        key[n] = '\0';
        dot = strrchr(key, '.');
        snprintf(leaf, sizeof leaf, "%s =", dot ? dot + 1 : key);
        if (!strstr(a, leaf) && !strstr(b, leaf) && !strstr(ctl, leaf)) {
            print_error("documented key %s is not used by the all-keys files\n", key);
            fail();
        }
        documented++;
        p = end;
    }
    assert_true(documented >= 90);

    for (g = 0; g < sizeof groups / sizeof groups[0]; g++) {
        char ov[160], docprefix[160], *q, *list;
        const char *ovs[1];
        const char *file = strncmp(groups[g], "controllers", 11) == 0 || strncmp(groups[g], "recovery", 8) == 0
                               ? "tests/data/case/all-keys-controllers.cfg"
                               : "tests/data/case/all-keys.cfg";
        td_case *c = NULL;
        td_error err;
        snprintf(ov, sizeof ov, "%szzzzzzzzzz=1", groups[g]);
        ovs[0] = ov;
        assert_int_equal(td_case_load(td_source_path(file), ovs, 1, &c, &err), TD_ERR_PARSE);
        list = strstr(err.message, "(valid here: ");
        if (!list) {
            print_error("%s: %s\n", ov, err.message);
            fail();
        }
        list += strlen("(valid here: ");
        snprintf(docprefix, sizeof docprefix, "%s", groups[g]);
        for (q = strchr(docprefix, '['); q; q = strchr(q + 1, '[')) /* "discs[0]." -> "discs[]." */
            memmove(q + 1, strchr(q, ']'), strlen(strchr(q, ']')) + 1);
        for (q = strtok(list, ", )"); q; q = strtok(NULL, ", )")) {
            char want[200];
            snprintf(want, sizeof want, "| `%s%s` |", docprefix, q);
            if (!strstr(doc, want)) {
                print_error("the reader accepts %s%s but docs/case-format.md has no row for it\n", docprefix, q);
                fail();
            }
        }
    }
    free(doc);
    free(a);
    free(b);
    free(ctl);
}

/* The value a key's documented default gives as a case value: a number or boolean (the first
 * word), a string or an array in backticks (`"orbit"`, `[0.0, -1.0]`); 0 when the default has no
 * value form (required, none, another key's value, a phrase). */
static int default_as_value(const char *def, char *buf, size_t n)
{
    const char *end;
    char *stop;
    if (def[0] == '`') {
        end = strchr(def + 1, '`');
        if (!end || (def[1] != '"' && def[1] != '[') || (size_t)(end - def) > n)
            return 0; /* `node`, `kxx`, `shaft_radius + clearance`: another key's value */
        snprintf(buf, n, "%.*s", (int)(end - def - 1), def + 1);
        return 1;
    }
    end = strchr(def, ' ');
    snprintf(buf, n, "%.*s", end ? (int)(end - def) : (int)strlen(def), def);
    if (strcmp(buf, "true") == 0 || strcmp(buf, "false") == 0)
        return 1;
    strtod(buf, &stop);
    return buf[0] && !*stop;
}

/* Append to a dump (a test-sized buffer; overflowing it fails the test). */
static void dump_add(char *buf, size_t n, const char *fmt, ...)
{
    size_t len = strlen(buf);
    va_list ap;
    int w;
    va_start(ap, fmt);
    w = vsnprintf(buf + len, n - len, fmt, ap);
    va_end(ap);
    assert_true(w >= 0 && (size_t)w < n - len);
}

/* The shaft, the speed and the whole-machine settings of a model, every number exactly (%a). */
static void dump_machine(const td_model *m, char *buf, size_t n)
{
    td_shaft_options so;
    td_spin sp;
    double gx, gy;
    int i;
    td_model_shaft_options(m, &so);
    td_model_spin(m, &sp);
    td_model_gravity(m, &gx, &gy);
    dump_add(buf, n, "nodes %d shaft %d %d %a %a %d %a\n", td_model_node_count(m), so.beam, so.mass, so.rayleigh_alpha,
             so.rayleigh_beta, so.shear, so.shear_value);
    for (i = 0; i < td_model_shaft_element_count(m); i++) {
        td_shaft_element e;
        assert_int_equal(td_model_get_shaft_element(m, i, &e), TD_OK);
        dump_add(buf, n, "element %d %a %a %a %a %a %a at %a\n", i, e.length, e.outer_diameter, e.inner_diameter,
                 e.material.E, e.material.G, e.material.density, td_model_node_position(m, i));
    }
    dump_add(buf, n, "speed %a points %d spin %d %a %a %a %a gravity %a %a reduction %a\n", td_model_speed(m),
             td_model_speed_point_count(m), sp.free, sp.inertia, sp.drive_torque, sp.drag_torque, sp.drag_viscous, gx,
             gy, td_model_reduction(m));
    for (i = 0; i < td_model_speed_point_count(m); i++) {
        td_speed_point p;
        assert_int_equal(td_model_get_speed_point(m, i, &p), TD_OK);
        dump_add(buf, n, "speed point %a %a\n", p.time, p.speed);
    }
}

/* The discs (and point masses), AMBs and bearings of a model. */
/* The retainers' bearings and the limits (the bearing's duty). */
static void dump_assessment(const td_model *m, char *buf, size_t n)
{
    td_limits l;
    int i;
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer_bearing b;
        assert_int_equal(td_model_get_retainer_bearing(m, i, &b), TD_OK);
        dump_add(buf, n, "retainer bearing %a %a %a %d %a %a %a %a\n", b.static_rating, b.dynamic_rating,
                 b.life_exponent, b.balls, b.ball_diameter, b.pitch_diameter, b.groove_conformity, b.width);
    }
    td_model_get_limits(m, &l);
    dump_add(buf, n, "limits %a %a %a %a %a %d\n", l.zones.ab, l.zones.bc, l.zones.cd, l.temperature_rise, l.drops,
             l.zone);
}

static void dump_supports(const td_model *m, char *buf, size_t n)
{
    int i;
    for (i = 0; i < td_model_disc_count(m); i++) {
        td_disc d;
        assert_int_equal(td_model_get_disc(m, i, &d), TD_OK);
        dump_add(buf, n, "disc %d %a %a %a\n", d.node, d.mass, d.Ip, d.Id);
    }
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        assert_int_equal(td_model_get_amb(m, i, &a), TD_OK);
        dump_add(buf, n, "amb %d %d %a %a %a %a %a %a %d %a %a %a\n", a.node, a.sensor_node, a.ks, a.ki, a.kp, a.kd,
                 a.tau, a.force_capacity, a.saturation, a.air_gap, a.kint, a.slew_rate);
    }
    for (i = 0; i < td_model_bearing_count(m); i++) {
        td_bearing b;
        assert_int_equal(td_model_get_bearing(m, i, &b), TD_OK);
        dump_add(buf, n, "bearing %d %a %a %a %a\n", b.node, b.kxx, b.kyy, b.cxx, b.cyy);
    }
    dump_assessment(m, buf, n);
}

/* The controllers of a case: their names, axes, order, timing, the case's account of each and
 * their frequency responses at a few frequencies, every number exactly (%a). */
static void dump_controllers(const td_case *c, char *buf, size_t n)
{
    static const double f[] = {0.0, 3.0, 70.0, 900.0};
    const td_model *m = td_case_model(c);
    int i, j, l;
    for (i = 0; i < td_model_controller_count(m); i++) {
        const char *name;
        const int *in, *out;
        const td_controller *k = td_model_get_controller(m, i, &name, &in, &out);
        td_case_controller_info info;
        double re[64], im[64];
        assert_int_equal(td_case_controller(c, i, &info), TD_OK);
        dump_add(buf, n, "controller \"%s\" %d states %a Hz rigid %d %a delay %d %d %a axes", name,
                 td_controller_order(k), td_controller_sample_rate(k), info.rigid, info.reference_z, info.delay,
                 (int)info.discretisation, info.prewarp);
        for (j = 0; j < td_controller_inputs(k); j++)
            dump_add(buf, n, " %d>%d", in[j], out[j]);
        assert_true(td_controller_inputs(k) * td_controller_outputs(k) <= 64);
        for (j = 0; j < 4; j++) {
            assert_int_equal(td_controller_frequency_response(k, f[j], re, im, NULL), TD_OK);
            for (l = 0; l < td_controller_inputs(k) * td_controller_outputs(k); l++)
                dump_add(buf, n, " %a%+a", re[l], im[l]);
        }
        dump_add(buf, n, "\n");
    }
}

/* The recovery supervisor (td_model_get_recovery). */
static void dump_recovery(const td_model *m, char *buf, size_t n)
{
    td_recovery r;
    int i, pairs = td_model_get_recovery(m, &r);
    dump_add(buf, n, "recovery %d pairs %d detect %a %a release %a %a blend %a\n", r.enabled, pairs,
             r.detect.radius_fraction, r.detect.dwell, r.release.radius_fraction, r.release.dwell, r.blend);
    for (i = 0; i < pairs; i++)
        dump_add(buf, n, "  pair %d: %d -> %d\n", i, r.nominal[i], r.controller[i]);
}
/* The retainers, unbalances and timed changes of a model. */
/* housing motion: the pulses, the reference and the motion at a few times (the history's shift and scale). */
/* housing body */
static void dump_housing_body(const td_model *m, char *buf, size_t n)
{
    td_housing_body b;
    int has = td_model_get_housing_body(m, &b), k;
    dump_add(buf, n, "body %d %a %a %a %d\n", has, b.mass, b.inertia, b.centre, b.mount_count);
    for (k = 0; k < b.mount_count; k++)
        dump_add(buf, n, "  mount %a %a %a\n", b.mounts[k].position, b.mounts[k].stiffness, b.mounts[k].damping);
}

static void dump_housing(const td_model *m, char *buf, size_t n)
{
    static const double times[] = {0.0, 0.004, 0.013, 0.3, 1.0};
    size_t k;
    int i;
    for (i = 0; i < td_model_housing_shock_count(m) + td_model_housing_rotation_count(m); i++) {
        td_housing_pulse p;
        int shock = i < td_model_housing_shock_count(m);
        assert_int_equal(shock ? td_model_get_housing_shock(m, i, &p)
                               : td_model_get_housing_rotation(m, i - td_model_housing_shock_count(m), &p),
                         TD_OK);
        dump_add(buf, n, "%s %d %a %a %a %a %a\n", shock ? "shock" : "rotation", (int)p.shape, p.amplitude, p.duration,
                 p.start, p.direction[0], p.direction[1]);
    }
    dump_add(buf, n, "housing %a %d\n", td_model_housing_reference(m), td_model_housing_history_count(m));
    for (k = 0; k < sizeof times / sizeof times[0]; k++) {
        td_housing_motion hm;
        td_model_housing_motion_at(m, times[k], &hm);
        dump_add(buf, n, "  at %a: %a %a %a %a %a %a\n", times[k], hm.acceleration[0], hm.acceleration[1],
                 hm.displacement[0], hm.displacement[1], hm.angle[0], hm.angle[1]);
    }
    dump_housing_body(m, buf, n);
}

static void dump_events(const td_model *m, char *buf, size_t n)
{
    int i;
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        assert_int_equal(td_model_get_retainer(m, i, &r), TD_OK);
        dump_add(buf, n, "retainer %d %a %a %a %a %a %a %d\n", r.node, r.clearance, r.shaft_radius, r.bore_radius,
                 r.friction, r.bore_speed, r.restitution, r.stick);
        dump_add(buf, n, "  race %a %a %a %a %a %a contact %a %a %d %a\n", r.race.inertia, r.race.drag_torque,
                 r.race.drag_viscous, r.race.mass, r.race.mount_stiffness, r.race.mount_damping, r.contact.stiffness,
                 r.contact.exponent, r.contact.damping, r.contact.damping_coefficient);
    }
    for (i = 0; i < td_model_unbalance_count(m); i++) {
        td_unbalance u;
        assert_int_equal(td_model_get_unbalance(m, i, &u), TD_OK);
        dump_add(buf, n, "unbalance %d %a %a\n", u.node, u.magnitude, u.phase);
    }
    for (i = 0; i < td_model_change_count(m); i++) {
        td_change ch;
        assert_int_equal(td_model_get_change(m, i, &ch), TD_OK);
        dump_add(buf, n, "change %a %d %d %a %a entry %d\n", ch.time, ch.kind, ch.index, ch.magnitude, ch.phase,
                 td_model_change_entry(m, i));
    }
    dump_recovery(m, buf, n);
    dump_housing(m, buf, n);
}

/* Everything a case gives, as text: the model through its getters, the end time, the description
 * and the option records (their bytes: each is a plain record set field by field from its
 * td_*_options_default). */
/* The sweep group as the grid it makes (td_sweep_grid_from_case): every point's overrides, not the
 * specs' text, which keeps what was written (an explicit `spacing = "linear"`). */
static void dump_sweep(const td_case *c, char *buf, size_t n)
{
    td_sweep_grid *g;
    char ov[TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE];
    long p;
    int k;
    assert_int_equal(td_sweep_grid_create(&g, NULL), TD_OK);
    assert_int_equal(td_sweep_grid_from_case(g, c, NULL), TD_OK);
    for (p = 0; p < td_sweep_grid_points(g); p++)
        for (k = 0; k < td_sweep_grid_keys(g); k++) {
            td_sweep_grid_override(g, p, k, ov, sizeof ov);
            dump_add(buf, n, "sweep point %ld axis %d %s\n", p, td_sweep_grid_axis(g, k), ov);
        }
    td_sweep_grid_free(&g);
}

static void dump_case(const td_case *c, char *buf, size_t n)
{
    const unsigned char *rec[3];
    size_t size[3], i, j;
    rec[0] = (const void *)td_case_sim_options(c);
    size[0] = sizeof(td_sim_options);
    rec[1] = (const void *)td_case_output_options(c);
    size[1] = sizeof(td_output_options);
    rec[2] = (const void *)td_case_modal_options(c);
    size[2] = sizeof(td_modal_options);
    buf[0] = '\0';
    dump_machine(td_case_model(c), buf, n);
    dump_supports(td_case_model(c), buf, n);
    dump_events(td_case_model(c), buf, n);
    dump_controllers(c, buf, n);
    dump_add(buf, n, "end %a description \"%s\"\n", td_case_end_time(c), td_case_description(c));
    dump_sweep(c, buf, n);
    for (i = 0; i < 3; i++) {
        dump_add(buf, n, "options %zu:", i);
        for (j = 0; j < size[i]; j++)
            dump_add(buf, n, "%02x", rec[i][j]);
        dump_add(buf, n, "\n");
    }
}

/* The base of test_documented_defaults: every group and list with a key that has a default, with
 * one entry (the retainers two: the second on a mount, which needs a race mass; the controller's
 * law a block of each kind but gain, in the order of the blocks' table), each holding its
 * required keys only (radii of exact binary sums), and a sweep axis with a key zipped onto it.
 * Point masses, the speed ramp and the reduction have no key with a default. */
static const char documented_defaults_base[] =
    "shaft = { length = 2.0; elements = 12; outer_diameter = 0.05; rayleigh = {}; sections = ( { element = 2; } );\n"
    "  material = { E = 2.11e11; G = 8.1e10; density = 7810.0; }; };\n"
    "speed = 100.0;\nend_time = 0.1;\n"
    "discs = ( { node = 3; radius = 0.1; thickness = 0.02; density = 7810.0; } );\n"
    "ambs = ( { node = 2; ks = 1.0e5; ki = 50.0; kp = 1.0e4; kd = 10.0; tau = 1.0e-4; force_capacity = 1000.0; },\n"
    "  { node = 8; ks = 1.0e5; ki = 50.0; tau = 1.0e-4; force_capacity = 1000.0; },\n"
    "  { node = 6; ks = 1.0e5; ki = 50.0; tau = 1.0e-4; force_capacity = 1000.0; } );\n"
    "controllers = ( { name = \"k\"; ambs = [1]; law = ( { pid = {}; }, { leadlag = { gain = 2.0; zero = 10.0;\n"
    "  pole = 100.0; }; }, { lowpass = { frequency = 500.0; }; }, { notch = { frequency = 50.0; width = 5.0; }; },\n"
    "  { tf = { num = [1.0]; den = [1.0, 100.0]; }; }, { zpk = {}; }, { ss = { D = ([1.0]); }; },\n"
    "  { resonant = { gain = 1.0; }; } ); },\n"
    "  { name = \"n\"; ambs = [2]; law = ( { gain = 1.0; } ); sample_rate = 1000.0; },\n"
    "  { name = \"r\"; ambs = [2]; law = ( { gain = 2.0; } ); sample_rate = 1000.0; } );\n"
    "recovery = { nominal = \"n\"; controller = \"r\"; detect = { radius_fraction = 0.8; dwell = 0.0; };\n"
    "  release = { radius_fraction = 0.3; dwell = 0.0; }; blend = 0.0; };\n"
    "bearings = ( { node = 10; kxx = 1.0e6; } );\n"
    "retainers = ( { node = 1; clearance = 0.000244140625; shaft_radius = 0.03125; friction = 0.1; race = {};\n"
    "    contact = { stiffness = 1.0e9; }; },\n"
    "  { node = 11; clearance = 0.000244140625; shaft_radius = 0.03125; friction = 0.1; race = { mass = 1.0; };\n"
    "    mount = { stiffness = 1.0e7; }; } );\n"
    "unbalances = ( { node = 5; magnitude = 1.0e-4; } );\n"
    "schedule = ( { time = 0.05; unbalance = 0; magnitude = 2.0e-4; } );\n"
    "gravity = {};\nspin = {};\n"
    "contact = {};\nsolver = {};\noutput = {};\nmodal = {};\n"
    "sweep = { vary = ( { key = \"speed\"; from = 100.0; to = 200.0; points = 3;\n"
    "  with = ( { key = \"end_time\"; from = 0.1; to = 0.2; points = 3; } ); } ); };\n"
    /* housing motion */
    "housing = { shocks = ( { amplitude = 1.0; duration = 0.01; direction = [0.0, 1.0]; } );\n"
    "  history = { time = [0.0, 0.01]; x = [0.0, 1.0]; y = [0.0, 0.0]; };\n"
    "  rotation = ( { rate = 0.1; duration = 0.5; axis = [1.0, 0.0]; } );\n"
    /* housing body */
    "  body = { mass = 40.0; centre = 1.0; mounts = ( { position = 0.5; stiffness = 1.0e7; } ); }; };\n";

/* Keys whose documented default is another key's value (of their entry, the unbalance they set, the
 * shaft), and that value in the base. */
static const struct {
    const char *key, *documented, *value;
} documented_same_as[] = {
    {"ambs[].sensor_node", "`node`", "2"},
    {"bearings[].kyy", "`kxx`", "1.0e6"},
    {"bearings[].cyy", "`cxx`", "0.0"}, /* cxx's own default */
    {"retainers[].bore_radius", "`shaft_radius + clearance`", "0.031494140625"},
    {"schedule[].phase", "the unbalance's `phase`", "0.0"}, /* phase's own default */
    {"shaft.sections[].outer_diameter", "the shaft's", "0.05"},
    {"shaft.sections[].inner_diameter", "the shaft's", "0.0"},
    {"shaft.sections[].material.E", "the shaft's", "2.11e11"},
    {"shaft.sections[].material.G", "the shaft's", "8.1e10"},
    {"shaft.sections[].material.density", "the shaft's", "7810.0"},
};

/* Why a key's documented default is not checked; NULL when it is (its value into buf). */
static const char *documented_default_value(const td_case_key_info *k, char *buf, size_t n)
{
    size_t i;
    for (i = 0; i < sizeof documented_same_as / sizeof documented_same_as[0]; i++)
        if (strcmp(k->key, documented_same_as[i].key) == 0) {
            assert_string_equal(k->default_value, documented_same_as[i].documented);
            snprintf(buf, n, "%s", documented_same_as[i].value);
            return NULL;
        }
    if (default_as_value(k->default_value, buf, n))
        return NULL;
    if (strcmp(k->type, "group") == 0 || strcmp(k->type, "list") == 0)
        return "part"; /* its presence is a setting of its own; its keys are checked */
    if (strstr(k->default_value, "required"))
        return "required";
    return "other"; /* a phrase: "-" (an alternative), "none", "the rotor's", "unknown" */
}

/* The override that writes `value` into the key of the base: a key of a list entry into the
 * entry (the first; a mount's, the second retainer's; a zipped key's, the first of the first). */
static void documented_default_override(const char *key, const char *value, char *buf, size_t n)
{
    static const char *const blocks[] = {"law[].pid.", "law[].leadlag.", "law[].lowpass.", "law[].notch.",
                                         "law[].tf.",  "law[].zpk.",     "law[].ss.",      "law[].resonant."};
    const char *entry = strncmp(key, "retainers[].mount.", 18) == 0 ? "[1]" : "[0]";
    const char *q;
    char block[8] = "[0]";
    size_t used = 0, b;
    for (b = 0; b < sizeof blocks / sizeof blocks[0]; b++)
        if (strstr(key, blocks[b]))
            snprintf(block, sizeof block, "[%d]", (int)b); /* the base's law: a block of each kind */
    while ((q = strstr(key, "[]")) != NULL && used < n) {
        used += (size_t)snprintf(buf + used, n - used, "%.*s%s", (int)(q - key), key,
                                 strncmp(q - 3, "law", 3) == 0 ? block : entry);
        key = q + 2;
    }
    if (used < n)
        snprintf(buf + used, n - used, "%s=%s", key, value);
}

/* Fail at the first line where two dumps differ. */
static void assert_same_dump(const char *ov, const char *want, const char *got)
{
    size_t line = 0, j;
    if (strcmp(want, got) == 0)
        return;
    for (j = 0; want[j] == got[j]; j++)
        if (want[j] == '\n')
            line = j + 1;
    print_error("%s: the documented default is not the reader's:\n absent: %.*s\nwritten: %.*s\n", ov,
                (int)strcspn(want + line, "\n"), want + line, (int)strcspn(got + line, "\n"), got + line);
    fail();
}

/* Every default the reader's tables document (td_case_key: docs/case-format.md's tables) that has a
 * value form, or names another key of its entry, is the value the reader gives an absent key:
 * writing it into the base case, which omits the key, changes nothing the case gives (dump_case:
 * the whole model, through its getters, and the options). A key inside a list entry is written
 * into the base's entry. The keys skipped, by why (documented_default_value), are counted, so that
 * a key added with a default the test cannot write fails here until it is looked at. */
static void test_documented_defaults(void **state)
{
    enum { DUMP = 1 << 15 };
    const char *path = scratch("defaults.cfg");
    char *want = malloc(DUMP), *got = malloc(DUMP);
    td_case *base, *set;
    td_case_key_info k;
    td_error err;
    int i, tried = 0, part = 0, required = 0, other = 0;
    (void)state;
    assert_true(want && got);
    write_file(path, documented_defaults_base);
    assert_int_equal(td_case_load(path, NULL, 0, &base, &err), TD_OK);
    dump_case(base, want, DUMP);
    for (i = 0; i < td_case_key_count(); i++) {
        char value[128], ov[320];
        const char *ovs[1], *skip;
        assert_int_equal(td_case_key(i, &k, &err), TD_OK);
        if ((skip = documented_default_value(&k, value, sizeof value)) != NULL) {
            part += strcmp(skip, "part") == 0;
            required += strcmp(skip, "required") == 0;
            other += strcmp(skip, "other") == 0;
            continue;
        }
        documented_default_override(k.key, value, ov, sizeof ov);
        ovs[0] = ov;
        if (td_case_load(path, ovs, 1, &set, &err) != TD_OK) {
            print_error("%s (the documented default): %s\n", ov, err.message);
            fail();
        }
        dump_case(set, got, DUMP);
        assert_same_dump(ov, want, got);
        td_case_free(&set);
        tried++;
    }
    print_message("documented defaults: %d keys checked; skipped: %d groups and lists, %d required, %d other\n", tried,
                  part, required, other);
    assert_int_equal(tried + part + required + other, td_case_key_count());
    assert_int_equal(tried, 98);    /* long runs: end_at_rest, output.window */
    assert_int_equal(part, 53);     /* their keys are checked (projective leap: leap) */
    assert_int_equal(required, 92); /* required, or one form's required key (a sweep entry's range or values);
                                       projective leap: leap's four */
    /* an alternative with no default ("-": shaft.nodes, sections' element, schedule's unbalance,
     * amb_off, amb_on, a law's gain block), "unknown" (an AMB's air gap), "all nodes", "none"
     * (response speeds, overrides, a zpk's zeros and poles, an ss block's A, B and C), "the rotor's"
     * (spin.inertia, kept as 0: td_spin; a controller's reference_z, its mass centre),
     * "continuous" (a controller's sample_rate), "1/sqrt(2)" (a low-pass's damping), "the case's
     * `speed` / (2 pi)" (a resonant's frequency), "-" (a parallel block), "none" (a plug-in's
     * parameters), "none" (a retainer bearing's ratings, geometry and width; the limits on temperature and
     * drops), "the defaults below" (limits), "none" (modal.operating_speed_min and _max), "every disc, AMB
     * sensor and retainer node" (modal.response_nodes), "none (no growth reported)" (a thermal network's
     * expansion), "the rotor's centre of mass" (housing.reference), "none" (a housing history's file, time, x
     * and y: alternatives), "`true`" (long runs: output.events, read by hand as the opposite it is stored as) */
    assert_int_equal(other, 40);
    td_case_free(&base);
    free(want);
    free(got);
}

/* td_case_key: every key once, each after its group; out of range and NULL refused. */
static void test_case_key_api(void **state)
{
    td_case_key_info k;
    td_error err;
    int i, j, n = td_case_key_count();
    char(*keys)[128];
    (void)state;
    assert_true(n > 100);
    keys = calloc((size_t)n, sizeof *keys);
    assert_non_null(keys);
    for (i = 0; i < n; i++) {
        const char *dot;
        assert_int_equal(td_case_key(i, &k, &err), TD_OK);
        assert_true(k.key[0] && k.type[0] && k.default_value[0] && k.doc[0] && k.section[0]);
        for (j = 0; j < i; j++)
            assert_string_not_equal(keys[j], k.key);
        /* a key in a group comes after the group's own row ("shaft.material.E" after "shaft.material") */
        if ((dot = strrchr(k.key, '.')) != NULL) {
            char group[128];
            snprintf(group, sizeof group, "%.*s", (int)(dot - k.key), k.key);
            if (strlen(group) > 2 && strcmp(group + strlen(group) - 2, "[]") == 0)
                group[strlen(group) - 2] = '\0';
            for (j = 0; j < i && strcmp(keys[j], group) != 0; j++)
                ;
            if (j == i) {
                print_error("%s comes before its group %s\n", k.key, group);
                fail();
            }
        }
        snprintf(keys[i], sizeof keys[i], "%s", k.key);
    }
    free(keys);
    assert_int_equal(td_case_key(n, &k, &err), TD_ERR_INVALID);
    assert_int_equal(td_case_key(-1, &k, &err), TD_ERR_INVALID);
    assert_int_equal(td_case_key(0, NULL, &err), TD_ERR_INVALID);
}

/* shaft.refine: node numbers in the case are those of the shaft as written; every part and output
 * node keeps its axial position on the refined shaft (the model itself: test_model.c). */
static void test_refine(void **state)
{
    static const char *const ov[] = {"shaft.refine=4", "output.nodes=[2, 10, 12]"};
    td_case *coarse = load_ok("cases/paper-a.cfg", ov + 1, 1);
    td_case *fine = load_ok("cases/paper-a.cfg", ov, 2);
    const td_model *mc = td_case_model(coarse), *mf = td_case_model(fine);
    const td_output_options *oc = td_case_output_options(coarse), *of = td_case_output_options(fine);
    td_retainer rc, rf;
    td_amb ac, af;
    int i;
    (void)state;
    assert_int_equal(td_model_node_count(mf), 49);
    assert_close(td_model_total_mass(mf), td_model_total_mass(mc), 1e-14, 0.0);
    for (i = 0; i < 2; i++) {
        td_model_get_retainer(mc, i, &rc);
        td_model_get_retainer(mf, i, &rf);
        assert_int_equal(rf.node, 4 * rc.node);
        assert_close(td_model_node_position(mf, rf.node), td_model_node_position(mc, rc.node), 1e-14, 0.0);
        td_model_get_amb(mc, i, &ac);
        td_model_get_amb(mf, i, &af);
        assert_close(td_model_node_position(mf, af.sensor_node), td_model_node_position(mc, ac.sensor_node), 1e-14,
                     0.0);
    }
    assert_int_equal(of->node_count, 3);
    for (i = 0; i < 3; i++)
        assert_close(td_model_node_position(mf, of->nodes[i]), td_model_node_position(mc, oc->nodes[i]), 1e-14, 0.0);
    td_case_free(&coarse);
    td_case_free(&fine);
}

/* ---- overrides ---------------------------------------------------------------------------- */

static void test_overrides(void **state)
{
    static const char *const ov[] = {"speed=100",
                                     "speed=190", /* a later override wins */
                                     "contact.model=penalty",
                                     "contact.stiffness=1.25e10",
                                     "solver.rtol=1e-8",
                                     " solver.max_order = 4 ",
                                     "retainers[1].friction=0.2",
                                     "ambs[0].saturation=true",
                                     "output.nodes=[2, 10]",
                                     "output.hdf5=runs/a.h5",
                                     "gravity.g=9.5",
                                     "gravity.enabled=true",
                                     "modal.response_speeds=[150.0]",
                                     "unbalances=({ node = 5; magnitude = 0.05; })",
                                     "schedule.[1].magnitude=0.07"};
    td_case *c = load_ok("cases/paper-a.cfg", ov, (int)(sizeof ov / sizeof ov[0]));
    const td_model *m = td_case_model(c);
    const td_sim_options *so = td_case_sim_options(c);
    td_retainer r;
    td_amb a;
    td_unbalance u;
    td_change ch;
    double gx, gy;
    (void)state;
    assert_close(td_model_speed(m), 190.0, 0.0, 0.0);
    assert_int_equal(so->contact.model, TD_CONTACT_PENALTY);
    assert_close(so->contact.stiffness, 1.25e10, 0.0, 0.0);
    assert_close(so->solver.rtol, 1e-8, 0.0, 0.0);
    assert_int_equal(so->solver.max_order, 4);
    td_model_get_retainer(m, 1, &r);
    assert_close(r.friction, 0.2, 0.0, 0.0);
    td_model_get_retainer(m, 0, &r);
    assert_close(r.friction, 0.1, 0.0, 0.0);
    td_model_get_amb(m, 0, &a);
    assert_int_equal(a.saturation, 1);
    assert_int_equal(td_case_output_options(c)->node_count, 2);
    assert_int_equal(td_case_output_options(c)->nodes[1], 10);
    assert_string_equal(td_case_output_options(c)->hdf5_path, "runs/a.h5");
    td_model_gravity(m, &gx, &gy);
    assert_close(gy, -9.5, 0.0, 0.0);
    assert_int_equal(td_case_modal_options(c)->response_speed_count, 1);
    td_model_get_unbalance(m, 0, &u);
    assert_int_equal(u.node, 5);
    assert_close(u.magnitude, 0.05, 0.0, 0.0);
    td_model_get_change(m, 1, &ch);
    assert_close(ch.magnitude, 0.07, 0.0, 0.0);
    assert_close(td_model_total_mass(m), rig_mass(), 1e-13, 0.0);
    /* the overrides are kept with the text, as comments */
    assert_contains(td_case_text(c), "\n# --set speed=190\n");
    assert_contains(td_case_text(c), "\n# --set output.nodes=[2, 10]\n");
    td_case_free(&c);
}

/* A message is one line of printable text: no newline, no ESC or other control character. */
static void assert_printable(const char *message)
{
    const unsigned char *p;
    for (p = (const unsigned char *)message; *p; p++)
        if (*p < 0x20 || *p == 0x7f) {
            print_error("message \"%s\" holds the control character 0x%02x\n", message, *p);
            fail();
        }
}

typedef struct bad_override {
    const char *ov;
    const char *expect; /* in the message, after "FILE: --set 'OV': " */
} bad_override;

static void test_bad_overrides(void **state)
{
    static const bad_override bad[] = {
        {"speed", "expected KEY=VALUE"},
        {"=190", "non-empty key"},
        {"speed=", "value after '=' is empty"},
        {"speed=abc", "speed: expected a number"},
        {"speed=nan", "speed: expected a number, got \"nan\" (NaN"},
        {"speed=-inf", "speed: expected a number, got \"-inf\" (NaN"},
        {"speed=1e999", "speed: must be finite"},
        {"speed=-5", "speed: must be >= 0"},
        {"sped=190", "sped: unknown key; did you mean 'speed'?"},
        {"contact.model=hertz", "contact.model: must be one of"},
        {"contact.modle=penalty", "contact.modle: unknown key; did you mean 'model'?"},
        {"retainers[7].friction=0.1", "index [7] is out of range (the list has 2 entries)"},
        {"retainers[x].friction=0.1", "malformed key"},
        {"retainers..friction=0.1", "malformed key"},
        {"speed.x=1", "its parent is not a group"},
        {"shaft.elements=4294967297", "integer 4294967297 is out of range"},
        {"shaft.elements=100000000", "shaft.elements: must lie in [1, 10000]"},
        {"solver.rtol=-1", "solver.rtol: must lie in (0, 1)"},
        {"solver.rtol=0", "solver.rtol: must lie in (0, 1)"},
        {"output.nodes=[1, 2", "cannot parse the value"},
        {"output.nodes=[1, 2.0]", "cannot parse the value"},
        {"output.nodes=[1, 13]", "output.nodes[1]: node 13 is out of range"},
        {"speed=1; end_time=5", "more than one value"},
        {"ambs[1].node=3", "ambs[1].node: node 3 already has an AMB"},
        {"retainers[0].clearance=1.5e-3", "retainers[0].clearance: clearance 0.0015 m is not smaller than the air gap"},
        {"retainers[0].node=13", "retainers[0].node: node 13 is out of range"},
        {"schedule[0].unbalance=3", "schedule[0].unbalance: unbalance 3 does not exist"},
        {"discs[0].mass=0", "discs[0].mass: must be > 0"},
        {"shaft.elements=12.5", "shaft.elements: expected an integer"},
        {"1bad=3", "'1bad' is not a valid key name"},
        /* fuzz finding K3: control characters are quoted escaped, the message stays one line */
        {"speed\n=1", "--set 'speed\\n=1': expected KEY=VALUE on one line"},
        {"speed=\x1b[31m", "speed: expected a number, got the string \"\\x1b[31m\""},
        {"spe\x1b"
         "ed=1",
         "'spe\\x1bed' is not a valid key name"},
        {"speed=\"a\tb", "cannot parse the value '\"a\\tb'"},
        {"end_time=\"2\"", "end_time: expected a number, got the string \"2\""},
        {"gravity.direction=[0.0, 0.0]", "gravity.direction: must not be the zero vector"},
        {"reduction.cutoff=-5.0", "reduction.cutoff: must be > 0"},
        {"reduction.cutoff=\"high\"", "reduction.cutoff: expected a number"},
        {"discs[0]=3", "must have the type of the entry it replaces"},
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const char *ovs[1];
        char prefix[256];
        td_case *c = (td_case *)&prefix; /* must come back NULL */
        td_error err;
        td_status st;
        ovs[0] = bad[k].ov;
        st = td_case_load(td_source_path("cases/paper-a.cfg"), ovs, 1, &c, &err);
        if (st != TD_ERR_PARSE || !strstr(err.message, bad[k].expect)) {
            print_error("--set '%s': status %d, message \"%s\"; expected \"%s\"\n", bad[k].ov, (int)st, err.message,
                        bad[k].expect);
            fail();
        }
        assert_null(c);
        snprintf(prefix, sizeof prefix, "paper-a.cfg: --set '");
        assert_contains(err.message, prefix);
        assert_printable(err.message);
        assert_string_equal(err.site.part, "override"); /* the override named in the record, its reason after */
        assert_int_equal(err.site.index, 0);
        assert_null(err.site.field);
        assert_true(err.reason > (int)strlen(prefix) && !strstr(err.message + err.reason, prefix));
    }
}

/* The model's rules are checked by the model alone; its error names part, index and field, and
 * the reader reports the setting they came from: "FILE:LINE: KEY: reason", and for a cross check
 * where the other part is. */
static void expect_located(const char *relative, const char *const *ov, int n, const char *where, const char *tail)
{
    td_case *c = NULL;
    td_error err;
    size_t len;
    assert_int_equal(td_case_load(td_source_path(relative), ov, n, &c, &err), TD_ERR_PARSE);
    assert_null(c);
    assert_contains(err.message, where);
    len = strlen(err.message);
    if (len < strlen(tail) || strcmp(err.message + len - strlen(tail), tail) != 0) {
        print_error("message \"%s\" does not end with \"%s\"\n", err.message, tail);
        fail();
    }
}

static void test_model_rules_located(void **state)
{
    static const char *const late_bad[] = {"schedule[1].time=0.05", "schedule[1].unbalance=4"};
    static const char *const mass_node[] = {"point_masses[1].node=40"};
    (void)state;
    expect_located("tests/data/bad/retainer-bore-mismatch.cfg", NULL, 0,
                   "retainer-bore-mismatch.cfg:6: retainers[0].bore_radius: ",
                   ": the bore radius must equal shaft_radius + clearance = 0.02575 m (got 0.026 m)");
    expect_located("tests/data/bad/retainer-clearance-ge-airgap.cfg", NULL, 0,
                   "retainer-clearance-ge-airgap.cfg:8: retainers[0].clearance: clearance 0.0012 m is not smaller "
                   "than the air gap 0.0012 m of amb 0; see ambs[0].air_gap at ",
                   "retainer-clearance-ge-airgap.cfg:5");
    expect_located("tests/data/bad/retainer-duplicate-node.cfg", NULL, 0,
                   "retainer-duplicate-node.cfg:6: retainers[1].node: node 2 already has a retainer (retainer 0); "
                   "see retainers[0].node at ",
                   "retainer-duplicate-node.cfg:5");
    expect_located("tests/data/bad/amb-duplicate-node.cfg", NULL, 0,
                   "amb-duplicate-node.cfg:6: ambs[1].node: node 3 already has an AMB (amb 0); see ambs[0].node at ",
                   "amb-duplicate-node.cfg:5");
    /* the model keeps its changes in time order: change 0 is the schedule's second entry */
    expect_located("cases/paper-a.cfg", late_bad, 2,
                   "--set 'schedule[1].unbalance=4': schedule[1].unbalance: unbalance 4 does not exist (1 defined, "
                   "indices start at 0; the change at t = 0.05 s); see unbalances at ",
                   "cases/paper-a.cfg:9");
    /* the model's discs are the discs, then the point masses */
    expect_located("cases/paper-a.cfg", mass_node, 1,
                   "--set 'point_masses[1].node=40': point_masses[1].node: node 40 is out of range (the shaft has "
                   "nodes 0..12); see shaft.elements at ",
                   "cases/rig.cfg:10");
}

/* An error on a value an override wrote names that override in err.site (its index among
 * td_case_load's), the reason at err.reason; one on a value of the file, or of the case's own
 * overrides list, names none, although a --set may be what it was compared with. */
static void test_override_named_in_site(void **state)
{
    static const char *const late_bad[] = {"schedule[1].time=0.05", "schedule[1].unbalance=4"};
    static const char *const elements[] = {"shaft.elements=2"};
    td_case *c = NULL;
    td_error err;
    (void)state;
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), late_bad, 2, &c, &err), TD_ERR_PARSE);
    assert_string_equal(err.site.part, "override");
    assert_int_equal(err.site.index, 1);
    assert_contains(err.message, "--set 'schedule[1].unbalance=4': schedule[1].unbalance: unbalance 4 does not");
    assert_true(strncmp(err.message + err.reason, "unbalance 4 does not exist", 26) == 0);
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), elements, 1, &c, &err), TD_ERR_PARSE);
    assert_null(err.site.part);
    assert_true(strncmp(err.message + err.reason, "node 5 is out of range", 22) == 0);
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/retainer-clearance-ge-airgap.cfg"), NULL, 0, &c, &err),
                     TD_ERR_PARSE);
    assert_null(err.site.part);
    assert_true(strncmp(err.message + err.reason, "clearance 0.0012 m is not smaller", 33) == 0);
    assert_null(c);
}

/* A rule that compares a key in the file with one a --set changed names the key where it is and
 * says where the other value was written: the --set (it used to name the file's line alone, as if
 * the value there were wrong). */
static void test_rules_name_the_set_they_compare_with(void **state)
{
    static const char *const elements[] = {"shaft.elements=2"};
    static const char *const one_amb[] = {"ambs=({ node = 3; ks = 1.0e6; ki = 200.0; kp = 1.0e4; kd = 40.0; "
                                          "bandwidth = 100.0; force_capacity = 1700.0; air_gap = 1.2e-3; })"};
    static const char *const renamed[] = {"controllers[0].name=\"x\""};
    static const char *const fast[] = {"end_time=1e-3", "speed=1e7"};
    char tail[512];
    (void)state;
    expect_located("cases/paper-a.cfg", elements, 1,
                   "cases/rig.cfg:28: discs[1].node: node 5 is out of range (the shaft has nodes 0..2); see "
                   "shaft.elements at ",
                   "cases/paper-a.cfg: --set 'shaft.elements=2'");
    snprintf(tail, sizeof tail, "cases/drop.cfg: --set '%s'", one_amb[0]);
    expect_located(
        "cases/drop.cfg", one_amb, 1,
        "cases/include/drop-rig.cfg:39: schedule[1].amb_off: AMB 1 does not exist (1 defined, indices start at 0; the "
        "change at t = 0.05 s); see ambs at ",
        tail);
    expect_located("cases/recovery.cfg", renamed, 1,
                   "cases/recovery.cfg:66: recovery.nominal: no controller is named \"pd\" (the controllers table "
                   "names \"x\", \"pd-sync\"; see controllers at ",
                   "cases/recovery.cfg: --set 'controllers[0].name=\"x\"')");
    expect_located("cases/paper-a.cfg", fast, 2,
                   "cases/paper-a.cfg:9: unbalances[0].magnitude: the unbalance force U Omega^2 = 0.02 kg m x (1e+07 "
                   "rad/s)^2 = 2e+12 N exceeds 1e+12 N; see speed at ",
                   "cases/paper-a.cfg: --set 'speed=1e7'");
}

/* ---- controllers ---------------------------------------------------------------------------- */

/* The frequency responses of a and b (same shape and timing) agree to tol of their largest entry
 * at frequencies from 0.3 Hz to 3 kHz (below the Nyquist frequency of the sampled laws here). */
static void assert_same_response(const td_controller *a, const td_controller *b, double tol)
{
    static const double f[] = {0.3, 7.0, 34.4, 60.0, 333.0, 2999.0};
    double are[64], aim[64], bre[64], bim[64];
    int ni = td_controller_inputs(a), no = td_controller_outputs(a), j, l;
    assert_int_equal(ni, td_controller_inputs(b));
    assert_int_equal(no, td_controller_outputs(b));
    assert_int_equal(td_controller_order(a), td_controller_order(b));
    assert_true(td_controller_sample_rate(a) == td_controller_sample_rate(b));
    assert_true(ni * no <= 64);
    for (j = 0; j < 6; j++) {
        double scale = 0.0;
        assert_int_equal(td_controller_frequency_response(a, f[j], are, aim, NULL), TD_OK);
        assert_int_equal(td_controller_frequency_response(b, f[j], bre, bim, NULL), TD_OK);
        for (l = 0; l < ni * no; l++)
            scale = fmax(scale, hypot(are[l], aim[l]));
        for (l = 0; l < ni * no; l++)
            if (!(hypot(are[l] - bre[l], aim[l] - bim[l]) <= tol * scale)) {
                print_error("at %g Hz entry %d: %g%+gj, expected %g%+gj\n", f[j], l, are[l], aim[l], bre[l], bim[l]);
                fail();
            }
    }
}

/* first, then second (both freed); second may be the result of a call that failed (test fails). */
static td_controller *then(td_controller *first, td_controller *second)
{
    td_controller *k;
    assert_non_null(second);
    if (!first)
        return second;
    k = td_controller_series(first, second, NULL);
    assert_non_null(k);
    td_controller_free(&first);
    td_controller_free(&second);
    return k;
}

static td_controller *side_by_side(td_controller *a, const td_controller *b)
{
    td_controller *k = td_controller_append(a, b, NULL);
    assert_non_null(k);
    td_controller_free(&a);
    return k;
}

static td_controller *sampled(td_controller *k, double rate, double prewarp)
{
    td_controller *d = td_controller_discretise(k, rate, TD_DISCRETISE_TUSTIN, prewarp, NULL);
    assert_non_null(d);
    td_controller_free(&k);
    return d;
}

/* tests/data/case/all-keys-controllers.cfg's "decentralised" law, through the API, at the case's
 * speed (rad/s: its resonant block's frequency). */
static td_controller *decentralised_law(double speed)
{
    const td_pid_block pid = {8.0e3, 2.0e4, 30.0, 0.0};
    const td_leadlag_block ll = {1.5, 20.0, 200.0};
    const td_lowpass_block lp = {800.0, 2, 0.6};
    const td_notch_block nb = {60.0, 8.0, 0.1};
    const td_resonant_block res = {0.8, 30.0, speed / (2.0 * TD_PI), 0.05};
    const double num[] = {1.0, 300.0}, den[] = {1.0, 400.0}, zr[] = {-50.0}, zi[] = {0.0}, pr[] = {-100.0},
                 pi[] = {200.0};
    const double A[] = {-500.0, 1.0, 0.0, -700.0}, B[] = {500.0, 0.0}, C[] = {0.0, 700.0}, D[] = {0.0};
    td_controller *k = then(NULL, td_controller_create_pid(&pid, NULL));
    k = then(k, td_controller_create_leadlag(&ll, NULL));
    k = then(k, td_controller_create_lowpass(&lp, NULL));
    k = then(k, td_controller_create_notch(&nb, NULL));
    k = then(k, td_controller_create_tf(num, 2, den, 2, 0.0, NULL));
    k = then(k, td_controller_create_zpk(zr, zi, 1, pr, pi, 1, 900.0, 0.0, NULL));
    k = then(k, td_controller_create_gain(0.5, NULL));
    k = then(k, td_controller_create_ss(2, 1, 1, A, B, C, D, NULL, 0.0, NULL));
    k = then(k, td_controller_create_resonant(&res, NULL));
    return then(k, td_controller_create_gain(0.5 * 0.2 + 1.0, NULL)); /* the parallel block */
}

/* Its "rigid" controller's translation and tilt laws in one plane, [x_r, tilt] in and out. */
static td_controller *rigid_plane(void)
{
    const double rate = 8000.0, tn[] = {0.2, 0.2}, td[] = {1.0, -0.6}, zr[] = {0.5}, zi[] = {0.0}, pr[] = {0.3},
                 pi[] = {0.4}, A[] = {0.5}, B[] = {0.5}, C[] = {1.0}, D[] = {0.0};
    const td_pid_block pid = {6.0e3, 0.0, 20.0, 1500.0};
    const td_lowpass_block lp = {900.0, 1, 0.0};
    td_controller *t = sampled(td_controller_create_pid(&pid, NULL), rate, 60.0), *tilt;
    t = then(t, td_controller_create_tf(tn, 2, td, 2, rate, NULL));
    tilt = sampled(td_controller_create_lowpass(&lp, NULL), rate, 60.0);
    tilt = then(tilt, td_controller_create_zpk(zr, zi, 1, pr, pi, 1, 2.0e3, rate, NULL));
    tilt = then(tilt, td_controller_create_ss(1, 1, 1, A, B, C, D, NULL, rate, NULL));
    t = side_by_side(t, tilt);
    td_controller_free(&tilt);
    return t;
}

/* The recovery table of the all-keys file lands in the model as written: the pair by the names'
 * indices, the rules and the blend. */
static void check_recovery_all_keys(const td_model *m)
{
    td_recovery r;
    assert_int_equal(td_model_get_recovery(m, &r), 1);
    assert_int_equal(r.enabled, 1);
    assert_int_equal(r.nominal[0], 2);
    assert_int_equal(r.controller[0], 3);
    assert_true(r.detect.radius_fraction == 0.8 && r.detect.dwell == 0.02);
    assert_true(r.release.radius_fraction == 0.3 && r.release.dwell == 0.2);
    assert_true(r.blend == 0.01);
}

/* Every key of the controllers table lands in the model's controllers: each law as the controller
 * API builds it from the same numbers (its frequency response), on the axes in the documented
 * order, with the case's account of what the realisation does not say. */
static void test_controllers_all_keys(void **state)
{
    td_case *c = load_ok("tests/data/case/all-keys-controllers.cfg", NULL, 0);
    const td_model *m = td_case_model(c);
    const int bearing_axes[] = {0, 1}, rigid_axes[] = {2, 4, 3, 5}; /* AMBs 1 and 2: x of each, then y */
    const char *name;
    const int *in, *out;
    td_controller *law = decentralised_law(100.0), *want, *plane, *both;
    td_case_controller_info info;
    double Ts[4], Ta[4], Tin[16] = {0}, Tout[16] = {0};
    int i, j;
    (void)state;
    /* the mass centre (the rigid reference when none is given): the shaft's at its middle, the disc's at node 1 */
    assert_close(td_model_mass_centre(m),
                 (7800.0 * TD_PI * 0.02 * 0.02 * 1.2 * 0.6 + 8.0 * 0.2) / (7800.0 * TD_PI * 0.02 * 0.02 * 1.2 + 8.0),
                 1e-14, 0.0);
    assert_int_equal(td_model_controller_count(m), 4);
    want = side_by_side(td_controller_clone(law, NULL), law);
    assert_non_null(td_model_get_controller(m, 0, &name, &in, &out));
    assert_memory_equal(in, bearing_axes, sizeof bearing_axes);
    assert_memory_equal(out, bearing_axes, sizeof bearing_axes);
    assert_string_equal(name, "decentralised");
    assert_same_response(td_model_get_controller(m, 0, NULL, NULL, NULL), want, 1e-12);
    assert_int_equal(td_case_controller(c, 0, &info), TD_OK);
    assert_int_equal(info.rigid, 0);
    assert_int_equal(info.discretised, 0); /* continuous */
    td_controller_free(&want);
    td_controller_free(&law);

    /* sensors at nodes 4 and 6 (z = 0.8, 1.2 m), actuators at nodes 4 and 5 (0.8, 1.0 m) */
    assert_int_equal(td_rigid_transform(0.8, 1.2, 0.75, Ts, NULL), TD_OK);
    assert_int_equal(td_rigid_transform(0.8, 1.0, 0.75, Ta, NULL), TD_OK);
    for (i = 0; i < 2; i++)
        for (j = 0; j < 2; j++) {
            Tin[i + 4 * j] = Tin[i + 2 + 4 * (j + 2)] = Ts[i + 2 * j];
            Tout[i + 4 * j] = Tout[i + 2 + 4 * (j + 2)] = Ta[j + 2 * i];
        }
    plane = rigid_plane();
    both = side_by_side(td_controller_clone(plane, NULL), plane);
    law = td_controller_transform(both, 4, Tin, 4, Tout, NULL);
    want = td_controller_delay(law, 1, NULL);
    assert_non_null(want);
    assert_non_null(td_model_get_controller(m, 1, &name, &in, &out));
    assert_string_equal(name, "rigid");
    assert_memory_equal(in, rigid_axes, sizeof rigid_axes);
    assert_memory_equal(out, rigid_axes, sizeof rigid_axes);
    assert_same_response(td_model_get_controller(m, 1, NULL, NULL, NULL), want, 1e-12);
    assert_int_equal(td_case_controller(c, 1, &info), TD_OK);
    assert_int_equal(info.rigid, 1);
    assert_close(info.reference_z, 0.75, 0.0, 0.0);
    assert_int_equal(info.delay, 1);
    assert_int_equal(info.discretisation, TD_DISCRETISE_TUSTIN);
    assert_close(info.prewarp, 60.0, 0.0, 0.0);
    assert_int_equal(info.discretised, 1); /* its pid and lowpass, in s */
    assert_int_equal(td_case_controller(c, 4, &info), TD_ERR_INVALID);
    td_controller_free(&want);
    td_controller_free(&law);
    td_controller_free(&both);
    td_controller_free(&plane);
    check_recovery_all_keys(m);
    td_case_free(&c);
}

/* A resonant block without a frequency resonates at the case's speed, the speed as overridden
 * (a sweep of the speed moves it along). */
static void test_resonant_default_follows_speed(void **state)
{
    const char *ovs[] = {"speed=320"};
    td_case *c = load_ok("tests/data/case/all-keys-controllers.cfg", ovs, 1);
    td_controller *law = decentralised_law(320.0), *want = side_by_side(td_controller_clone(law, NULL), law);
    (void)state;
    assert_same_response(td_model_get_controller(td_case_model(c), 0, NULL, NULL, NULL), want, 1e-12);
    td_controller_free(&want);
    td_controller_free(&law);
    td_case_free(&c);
}

/* A machine for controller cases: a 1.2 m shaft of 6 elements (node i at z = 0.2 i m), AMB 0 at
 * node 1 sensing at node 2, AMB 1 at node 4 sensing at node 5, neither with gains, and AMB 2 at
 * node 6 with the shorthand PD; the controllers are on line 7 (CONTROL_LINE). */
static const char control_base[] =
    "speed = 100.0;\nend_time = 0.1;\n"
    "shaft = { length = 1.2; elements = 6; outer_diameter = 0.04; material = { E = 2.0e11; G = 7.7e10; density = "
    "7800.0; }; };\n"
    "ambs = ( { node = 1; sensor_node = 2; ks = 5.0e5; ki = 150.0; tau = 2.0e-3; force_capacity = 1200.0; },\n"
    "  { node = 4; sensor_node = 5; ks = 5.0e5; ki = 150.0; tau = 2.0e-3; force_capacity = 1200.0; },\n"
    "  { node = 6; ks = 5.0e5; ki = 150.0; kp = 8.0e3; kd = 30.0; tau = 2.0e-3; force_capacity = 1200.0; } );\n";
#define CONTROL_LINE 7

/* Load control_base + `controllers` (one line) from a scratch file; *c NULL on failure. */
static td_status load_controllers(const char *controllers, td_case **c, td_error *err)
{
    const char *path = scratch("controllers.cfg");
    char text[4096];
    snprintf(text, sizeof text, "%s%s\n", control_base, controllers);
    assert_true(strlen(text) < sizeof text - 1);
    write_file(path, text);
    return td_case_load(path, NULL, 0, c, err);
}

/* A PD block with the exact derivative is the shorthand's law i = kp e + kd de/dt (e = -xs): its
 * response is kp + j w kd (closed form); a notch's at its frequency is its depth. */
static void test_controller_closed_forms(void **state)
{
    td_case *c = NULL;
    td_error err;
    int i;
    double re[16], im[16], w = 2.0 * TD_PI * 25.0;
    (void)state;
    assert_int_equal(load_controllers("controllers = ( { name = \"pd\"; ambs = [0, 1]; law = ( { pid = { kp = 8.0e3; "
                                      "kd = 30.0; }; } ); }, { name = \"n\"; ambs = [2]; law = ( { notch = { "
                                      "frequency = 50.0; width = 5.0; depth = 0.25; }; } ); } );",
                                      &c, &err),
                     TD_ERR_PARSE); /* AMB 2 keeps its kp */
    assert_contains(err.message, "ambs[2].kp: this AMB is driven by controller controllers[1] at ");
    assert_int_equal(load_controllers("controllers = ( { name = \"pd\"; ambs = [1, 0]; law = ( { pid = { kp = 8.0e3; "
                                      "kd = 30.0; }; } ); } );",
                                      &c, &err),
                     TD_OK);
    assert_int_equal(td_controller_order(td_model_get_controller(td_case_model(c), 0, NULL, NULL, NULL)), 0);
    assert_int_equal(td_controller_frequency_response(td_model_get_controller(td_case_model(c), 0, NULL, NULL, NULL),
                                                      25.0, re, im, NULL),
                     TD_OK);
    assert_close(re[0], 8.0e3, 1e-15, 0.0);
    assert_close(im[0], 30.0 * w, 1e-15, 0.0);
    for (i = 1; i < 16; i++) /* each axis on its own, the same law */
        assert_close(hypot(re[i], im[i]), i % 5 == 0 ? hypot(8.0e3, 30.0 * w) : 0.0, 1e-15, 0.0);
    td_case_free(&c);
}

/* Rigid-body coordinates, by hand: translation gain gt and tilt gain gr about z_r = 0.3 m, AMB a
 * sensing at z = 0.4 m and pushing at 0.2 m, AMB b sensing at 1.0 m and pushing at 0.8 m. In each
 * plane the bearing currents are Ta^T diag(gt, gr) Ts [e_a; e_b] with
 * T = 1/(z_b - z_a) [z_b - z_r, z_r - z_a; -1, 1] (docs/case-format.md, controllers); the axes
 * are plane x (a, b) then plane y (a, b), and the planes do not couple. */
static void test_controller_rigid_by_hand(void **state)
{
    const double gt = 3.0, gr = 5.0, s[2][2] = {{0.7 / 0.6, -0.1 / 0.6}, {-1.0 / 0.6, 1.0 / 0.6}},
                 a[2][2] = {{0.5 / 0.6, 0.1 / 0.6}, {-1.0 / 0.6, 1.0 / 0.6}};
    const int axes[] = {0, 2, 1, 3};
    const int *in, *out;
    td_case_controller_info info;
    td_case *c = NULL;
    td_error err;
    double re[16], im[16];
    int i, j;
    (void)state;
    assert_int_equal(load_controllers("controllers = ( { name = \"rb\"; ambs = [0, 1]; coordinates = \"rigid\"; "
                                      "reference_z = 0.3; translation = ( { gain = 3.0; } ); tilt = ( { gain = 5.0; "
                                      "} ); } );",
                                      &c, &err),
                     TD_OK);
    assert_int_equal(td_controller_frequency_response(td_model_get_controller(td_case_model(c), 0, NULL, &in, &out),
                                                      10.0, re, im, NULL),
                     TD_OK);
    assert_memory_equal(in, axes, sizeof axes);
    assert_memory_equal(out, axes, sizeof axes);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            /* output i (bearing i % 2 of plane i / 2) from input j */
            double want = i / 2 != j / 2 ? 0.0 : a[0][i % 2] * gt * s[0][j % 2] + a[1][i % 2] * gr * s[1][j % 2];
            assert_close(re[i + 4 * j], want, 1e-14, 1e-14);
            assert_close(im[i + 4 * j], 0.0, 0.0, 1e-14);
        }
    td_case_free(&c);
    /* without reference_z: the uniform shaft's middle */
    assert_int_equal(load_controllers("controllers = ( { name = \"rb\"; ambs = [0, 1]; coordinates = \"rigid\"; "
                                      "translation = ( { gain = 3.0; } ); tilt = ( { gain = 5.0; } ); } );",
                                      &c, &err),
                     TD_OK);
    assert_int_equal(td_case_controller(c, 0, &info), TD_OK);
    assert_close(info.reference_z, 0.6, 1e-15, 0.0);
    td_case_free(&c);
}

/* cases/rig-notch.cfg's rigid-body PD without its notch and filters is the rig's per-bearing PD
 * (kp = 1e4 A/m, kd = 40 A s/m on each axis, docs/reference-rig.md): for collocated AMBs 1 m apart
 * about their midpoint T^T diag(2 kp, kp / 2) T = kp I, each axis on its own. */
static void test_controller_rigid_is_the_shorthand(void **state)
{
    const char *ov[2] = {"controllers[0].translation = ( { pid = { kp = 2.0e4; kd = 80.0; }; } )",
                         "controllers[0].tilt = ( { pid = { kp = 5.0e3; kd = 20.0; }; } )"};
    td_case *c = load_ok("cases/rig-notch.cfg", ov, 2);
    double re[16], im[16], w = 2.0 * TD_PI * 34.4;
    int i;
    (void)state;
    assert_int_equal(td_controller_frequency_response(td_model_get_controller(td_case_model(c), 0, NULL, NULL, NULL),
                                                      34.4, re, im, NULL),
                     TD_OK);
    for (i = 0; i < 16; i++) {
        assert_close(re[i], i % 5 == 0 ? 1.0e4 : 0.0, 1e-14, 1e-10);
        assert_close(im[i], i % 5 == 0 ? 40.0 * w : 0.0, 1e-14, 1e-10);
    }
    td_case_free(&c);
}

/* Each bad controller (one line of control_base) fails with FILE:LINE: KEY: and says what. */
static void test_controller_errors(void **state)
{
    static const struct {
        const char *text, *key, *what;
        int line; /* 0: CONTROL_LINE */
    } bad[] = {
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { pidd = { kp = 1.0; }; } ); } );",
         "controllers[0].law[0].pidd", "unknown key; did you mean 'pid'?", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { pid = { kp = 1.0; }; notch = { frequency = 9.0; "
         "width = 1.0; }; } ); } );",
         "controllers[0].law[0].notch", "a block has exactly one member", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { } ); } );", "controllers[0].law[0]",
         "an empty block", 0},
        {"controllers = ( { ambs = [0, 1]; law = ( { gain = 1.0; } ); } );", "controllers[0].name",
         "missing required key", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; } );", "controllers[0].law", "missing required key", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { notch = { frequency = 9.0; }; } ); } );",
         "controllers[0].law[0].notch.width", "missing required key", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1, 7]; law = ( { gain = 1.0; } ); } );", "controllers[0].ambs[2]",
         "AMB 7 does not exist (3 defined", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1, 2]; law = ( { gain = 1.0; } ); } );", "ambs[2].kp",
         "driven by controller controllers[0] at", 6},
        {"controllers = ( { name = \"a\"; ambs = [0]; coordinates = \"rigid\"; translation = ( { gain = 1.0; } ); "
         "tilt = ( { gain = 1.0; } ); }, { name = \"b\"; ambs = [1]; law = ( { gain = 1.0; } ); } );",
         "controllers[0].coordinates", "exactly two AMBs", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; coordinates = \"rigid\"; law = ( { gain = 1.0; } ); } );",
         "controllers[0].law", "rigid coordinates take `translation` and `tilt`, not `law`", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; coordinates = \"rigid\"; tilt = ( { gain = 1.0; } ); } );",
         "controllers[0].translation", "missing required key", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); tilt = ( { gain = 1.0; } ); } );",
         "controllers[0].tilt", "need coordinates = \"rigid\"", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); reference_z = 0.5; } );",
         "controllers[0].reference_z", "needs coordinates = \"rigid\"", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { tf = { num = [1.0]; den = [1.0, -0.5]; domain = "
         "\"z\"; }; } ); } );",
         "controllers[0].law[0].tf.domain", "needs the controller's sample_rate", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); delay = 1; } );",
         "controllers[0].delay", "applies to a sampled controller", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); discretisation = \"zoh\"; } );",
         "controllers[0].discretisation", "applies to a sampled controller", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); sample_rate = 0.0; } );",
         "controllers[0].sample_rate", "must be > 0", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); sample_rate = 1.0e4; "
         "discretisation = \"zoh\"; prewarp = 50.0; } );",
         "controllers[0].prewarp", "tustin", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { tf = { num = [1.0, 2.0, 3.0]; den = [1.0]; }; } ); "
         "} );",
         "controllers[0].law[0].tf.num", "improper", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { pid = { kp = 1.0; kd = 1.0; }; }, { pid = { kp = "
         "1.0; kd = 1.0; }; } ); } );",
         "controllers[0].law[1]", "improper", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { pid = { kp = 1.0; kd = 1.0; }; } ); sample_rate = "
         "1.0e4; } );",
         "controllers[0].law[0]", "cannot be sampled", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { ss = { A = ([-1.0, 0.0], [0.0, -2.0]); B = ([1.0, "
         "1.0]); C = ([1.0, 1.0]); D = ([0.0]); }; } ); } );",
         "controllers[0].law[0].ss.B", "is 1 x 2; B must be n x 1", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { ss = { A = ([-1.0, 0.0], [0.0]); B = ([1.0], "
         "[1.0]); C = ([1.0, 1.0]); D = ([0.0]); }; } ); } );",
         "controllers[0].law[0].ss.A[1]", "row 1 has 1 entries, row 0 has 2", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { zpk = { poles = ([-1.0, 2.0, 3.0]); }; } ); } );",
         "controllers[0].law[0].zpk.poles[0]", "expected a root [re, im]", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { lowpass = { frequency = 9.0; order = 1; damping = "
         "0.5; }; } ); } );",
         "controllers[0].law[0].lowpass.damping", "no damping", 0},
        {"controllers = ( { name = \"a\"; ambs = [0]; law = ( { gain = 1.0; } ); }, { name = \"a\"; ambs = [1]; law "
         "= ( { gain = 1.0; } ); } );",
         "controllers[1].name", "already names controller 0; see controllers[0].name at ", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { gain = 1.0; } ); }, { name = \"b\"; ambs = [1]; "
         "law = ( { gain = 1.0; } ); } );",
         "controllers[1].ambs", "already driven by controller 0", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { notch = { frequency = 9.0; width = 1.0; depth = "
         "1.5; }; } ); } );",
         "controllers[0].law[0].notch.depth", "must be >= 0 and < 1 (got 1.5)", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { resonant = { gain = 1.0; damping = 1.0; }; } ); } "
         ");",
         "controllers[0].law[0].resonant.damping", "must be >= 0 and < 1 (got 1)", 0},
        {"controllers = ( { name = \"a\"; ambs = [0, 1]; law = ( { lowpass = { frequency = 100.0; }; } ); sample_rate "
         "= 8000.0; prewarp = 5000.0; } );",
         "controllers[0].prewarp", "below the Nyquist frequency 4000 Hz", 0},
    };
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        td_case *c = (td_case *)&k; /* must come back NULL */
        td_error err;
        char where[256];
        snprintf(where, sizeof where, "controllers.cfg:%d: %s: ", bad[k].line ? bad[k].line : CONTROL_LINE, bad[k].key);
        if (load_controllers(bad[k].text, &c, &err) != TD_ERR_PARSE) {
            print_error("%s: loaded, expected \"%s\"\n", bad[k].text, where);
            fail();
        }
        assert_null(c);
        assert_contains(err.message, where);
        assert_contains(err.message, bad[k].what);
        assert_null(strchr(err.message, '\n'));
    }
}

/* ---- broken files ------------------------------------------------------------------------- */

typedef struct bad_file {
    const char *file;  /* under tests/data/bad/ */
    int line;          /* line the message must name */
    const char *key;   /* key the message must name (NULL: file-level or syntax error) */
    const char *shown; /* file the message names, when not `file` (an included file) */
} bad_file;

static const bad_file bad_files[] = {
    {"amb-bandwidth-tiny.cfg", 5, "ambs[0].bandwidth", NULL},
    {"amb-duplicate-node.cfg", 6, "ambs[1].node", NULL},
    {"amb-missing-ki.cfg", 5, "ambs[0].ki", NULL},
    {"amb-saturation-int.cfg", 6, "ambs[0].saturation", NULL},
    {"amb-kint-negative.cfg", 6, "ambs[0].kint", NULL},
    {"speed-ramp-backwards.cfg", 5, "speed_ramp[1].time", NULL},
    {"speed-ramp-step.cfg", 5, "speed_ramp[0].speed", NULL},
    {"speed-ramp-too-fast.cfg", 6, "speed_ramp[1].speed", NULL},
    {"spin-free-and-ramp.cfg", 5, "spin.free", NULL},
    {"spin-torque-not-free.cfg", 4, "spin", NULL},
    {"amb-tau-and-bandwidth.cfg", 6, "ambs[0].bandwidth", NULL},
    {"amb-zero-capacity.cfg", 6, "ambs[0].force_capacity", NULL},
    {"controller-driven-amb-gain.cfg", 5, "ambs[1].kd", NULL},
    {"controller-duplicate-name.cfg", 7, "controllers[1].name", NULL},
    {"controller-rigid-three-ambs.cfg", 8, "controllers[0].coordinates", NULL},
    {"controller-rate-too-high.cfg", 8, "controllers[0].sample_rate", NULL},
    {"controller-notch-frequency-huge.cfg", 8, "controllers[0].law[1].notch.frequency", NULL},
    {"controller-resonant-no-speed.cfg", 9, "controllers[0].law[1].resonant.frequency", NULL},
    {"controller-parallel-mixed.cfg", 8, "controllers[0].law[0].parallel[1]", NULL},
    {"controller-prewarp-all-z.cfg", 8, "controllers[0].prewarp", NULL},
    {"controller-reference-off-shaft.cfg", 8, "controllers[0].reference_z", NULL},
    {"controller-ss-shape.cfg", 8, "controllers[0].law[0].ss.B", NULL},
    {"controller-two-members.cfg", 8, "controllers[0].law[0].notch", NULL},
    {"controller-unknown-block.cfg", 7, "controllers[0].law[0].pidd", NULL},
    {"controller-z-block-continuous.cfg", 8, "controllers[0].law[0].tf.domain", NULL},
    {"recovery-continuous.cfg", 8, "recovery.nominal", NULL},
    {"recovery-different-axes.cfg", 8, "recovery.controller", NULL},
    {"recovery-list-lengths.cfg", 9, "recovery.controller", NULL},
    {"recovery-missing-detect.cfg", 7, "recovery.detect", NULL},
    {"recovery-negative-dwell.cfg", 9, "recovery.detect.dwell", NULL},
    {"recovery-no-hysteresis.cfg", 8, "recovery.release.radius_fraction", NULL},
    {"recovery-no-retainer.cfg", 7, "recovery", NULL},
    {"recovery-rate-mismatch.cfg", 8, "recovery.controller", NULL},
    {"recovery-self.cfg", 7, "recovery.controller", NULL},
    {"recovery-unknown-name.cfg", 6, "recovery.controller", NULL},
    {"binary.cfg", 2, NULL, NULL},
    {"comments-only.cfg", 1, NULL, NULL},
    {"contact-bad-model.cfg", 5, "contact.model", NULL},
    {"contact-exponent-below-one.cfg", 6, "contact.exponent", NULL},
    {"contact-zero-stiffness.cfg", 6, "contact.stiffness", NULL},
    {"disc-bore-too-big.cfg", 5, "discs[0].bore_radius", NULL},
    {"disc-inertia-overflow.cfg", 5, "discs[0].radius", NULL},
    {"disc-mixed-forms.cfg", 5, "discs[0].radius", NULL},
    {"disc-thickness-and-mass.cfg", 6, "discs[0].mass", NULL},
    {"disc-geometry-no-thickness.cfg", 5, "discs[0].thickness", NULL},
    {"disc-negative-node.cfg", 5, "discs[0].node", NULL},
    {"disc-node-out-of-range.cfg", 6, "discs[1].node", NULL},
    {"disc-zero-mass.cfg", 5, "discs[0].mass", NULL},
    {"discs-not-list.cfg", 4, "discs", NULL},
    {"duplicate-key.cfg", 4, NULL, NULL},
    {"empty.cfg", 1, NULL, NULL},
    {"end-time-unbounded.cfg", 4, "end_time", NULL},
    {"end-time-zero.cfg", 4, "end_time", NULL},
    {"gravity-enabled-string.cfg", 5, "gravity.enabled", NULL},
    {"gravity-zero-direction.cfg", 6, "gravity.direction", NULL},
    {"reduction-cutoff-zero.cfg", 5, "reduction.cutoff", NULL},
    {"reduction-missing-cutoff.cfg", 4, "reduction.cutoff", NULL},
    {"include-comment-at-eof.cfg", 3, NULL, "fragments/comment-at-eof.cfg"},
    {"include-fan.cfg", 8, NULL, "fragments/fan-1.cfg"},
    {"include-missing.cfg", 3, NULL, NULL},
    {"include-name-unclosed.cfg", 4, NULL, NULL},
    {"include-self.cfg", 3, NULL, NULL},
    {"junk-bytes.cfg", 1, NULL, NULL},
    {"line-endings-cr.cfg", 5, NULL, NULL},
    {"material-missing-E.cfg", 7, "shaft.material.E", NULL},
    {"material-string-density.cfg", 8, "shaft.material.density", NULL},
    {"missing-end-time.cfg", 1, "end_time", NULL},
    {"missing-shaft.cfg", 1, "shaft", NULL},
    {"missing-speed.cfg", 1, "speed", NULL},
    {"modal-speed-range.cfg", 6, "modal.speed_max", NULL},
    {"modal-grid-work.cfg", 5, "modal.speed_steps", NULL},
    {"output-node-out-of-range.cfg", 6, "output.nodes[1]", NULL},
    {"output-sample-absurd.cfg", 5, "output.sample_rate", NULL},
    {"point-mass-negative.cfg", 5, "point_masses[0].mass", NULL},
    {"retainer-bore-mismatch.cfg", 6, "retainers[0].bore_radius", NULL},
    /* the bearing's duty */
    {"retainer-bearing-raceway-in-bore.cfg", 7, "retainers[0].bearing.pitch_diameter", NULL},
    {"retainer-bearing-balls-missing.cfg", 6, "retainers[0].bearing.ball_diameter", NULL},
    {"retainer-bearing-negative-rating.cfg", 7, "retainers[0].bearing.static_rating", NULL},
    {"limits-zones-order.cfg", 5, "limits.zones", NULL},
    {"limits-zones-two.cfg", 5, "limits.zones", NULL},
    {"retainer-clearance-ge-airgap.cfg", 8, "retainers[0].clearance", NULL},
    {"retainer-duplicate-node.cfg", 6, "retainers[1].node", NULL},
    {"shaft-shear-above-one.cfg", 5, "shaft.shear_coefficient", NULL},
    {"shaft-shear-unknown.cfg", 5, "shaft.shear_coefficient", NULL},
    {"race-negative-inertia.cfg", 6, "retainers[0].race.inertia", NULL},
    {"race-drag-without-inertia.cfg", 6, "retainers[0].race.drag_torque", NULL},
    {"race-mass-without-mount.cfg", 6, "retainers[0].race.mass", NULL},
    {"race-mount-without-mass.cfg", 6, "retainers[0].mount.stiffness", NULL},
    {"race-unknown-key.cfg", 6, "retainers[0].race.intertia", NULL},
    {"race-string-inertia.cfg", 6, "retainers[0].race.inertia", NULL},
    {"retainer-contact-bad-damping.cfg", 6, "retainers[0].contact.damping", NULL},
    {"retainer-contact-exponent.cfg", 6, "retainers[0].contact.exponent", NULL},
    {"retainer-stick-no-friction.cfg", 6, "retainers[0].stick", NULL},
    {"override-bad-index.cfg", 5, "overrides[0]", NULL},
    {"retainer-restitution.cfg", 6, "retainers[0].restitution", NULL},
    {"retainer-zero-clearance.cfg", 5, "retainers[0].clearance", NULL},
    {"schedule-bad-index.cfg", 6, "schedule[0].unbalance", NULL},
    {"schedule-negative-time.cfg", 8, "schedule[0].time", NULL},
    {"schedule-two-kinds.cfg", 10, "schedule[0].amb_off", NULL},
    {"shaft-bad-beam.cfg", 8, "shaft.beam", NULL},
    {"shaft-damping-and-rayleigh.cfg", 9, "shaft.damping", NULL},
    {"shaft-damping-frequencies-decreasing.cfg", 8, "shaft.damping.frequencies[1]", NULL},
    {"shaft-damping-frequency-zero.cfg", 8, "shaft.damping.frequencies[0]", NULL},
    {"shaft-damping-ratio-negative.cfg", 8, "shaft.damping.ratio", NULL},
    {"shaft-damping-ratio-one.cfg", 8, "shaft.damping.ratio", NULL},
    {"shaft-diameter-overflow.cfg", 7, "shaft.outer_diameter", NULL},
    {"shaft-elements-absurd.cfg", 5, "shaft.elements", NULL},
    {"shaft-elements-float.cfg", 5, "shaft.elements", NULL},
    {"shaft-elements-wrap.cfg", 5, "shaft.elements", NULL},
    {"shaft-hollow-too-thick.cfg", 7, "shaft.inner_diameter", NULL},
    {"shaft-length-and-nodes.cfg", 6, "shaft.nodes", NULL},
    {"shaft-negative-diameter.cfg", 6, "shaft.outer_diameter", NULL},
    {"shaft-nodes-decreasing.cfg", 5, "shaft.nodes[2]", NULL},
    {"shaft-refine-too-fine.cfg", 8, "shaft.refine", NULL},
    {"shaft-refine-zero.cfg", 8, "shaft.refine", NULL},
    {"shaft-nodes-too-close.cfg", 4, "shaft.nodes", NULL},
    {"shaft-nodes-overflow.cfg", 4, "shaft.nodes[1]", NULL},
    {"shaft-section-smaller-than-bore.cfg", 8, "shaft.sections[0].outer_diameter", NULL},
    {"shaft-damping-overflow.cfg", 8, "shaft.damping.frequencies", NULL},
    {"shaft-not-group.cfg", 3, "shaft", NULL},
    {"shaft-section-out-of-range.cfg", 10, "shaft.sections[0].to", NULL},
    {"shaft-section-overlap.cfg", 10, "shaft.sections[1]", NULL},
    {"shaft-zero-length.cfg", 4, "shaft.length", NULL},
    {"solver-atol-negative.cfg", 6, "solver.atol", NULL},
    {"solver-atol-above-clearance.cfg", 6, "solver.atol", NULL},
    {"retainer-clearance-below-atol.cfg", 5, "retainers[0].clearance", NULL},
    {"solver-max-step-tiny.cfg", 5, "solver.max_step", NULL},
    {"solver-max-order.cfg", 5, "solver.max_order", NULL},
    {"solver-rtol-zero.cfg", 5, "solver.rtol", NULL},
    {"solver-unknown-linsol.cfg", 5, "solver.linear_solver", NULL},
    {"speed-inf.cfg", 3, "speed", NULL},
    {"speed-negative.cfg", 3, "speed", NULL},
    {"speed-overflow-orbit.cfg", 3, "speed", NULL},
    {"speed-string.cfg", 3, "speed", NULL},
    {"speed-unbounded.cfg", 3, "speed", NULL},
    {"start-control-chars.cfg", 5, "start", NULL},
    {"start-unknown.cfg", 4, "start", NULL},
    {"syntax-error.cfg", 4, NULL, NULL},
    {"syntax-mixed-array.cfg", 4, NULL, NULL},
    {"syntax-nan.cfg", 3, NULL, NULL},
    {"syntax-unclosed-group.cfg", 6, NULL, NULL},
    {"unbalance-force-overflow.cfg", 6, "unbalances[0].magnitude", NULL},
    {"unbalance-negative.cfg", 5, "unbalances[0].magnitude", NULL},
    {"unbalance-wrap-same-line.cfg", 5, "unbalances[0].magnitude", NULL},
    {"unknown-nested-key.cfg", 5, "retainers[0].clearence", NULL},
    {"unknown-top-key.cfg", 4, "strat", NULL},
    {"unterminated-comment.cfg", 4, NULL, NULL},
    {"include-error.cfg", 4, "point_masses[0].mass", "bad-fragment.cfg"},
    /* heat */
    {"retainer-thermal-zero-capacity.cfg", 6, "retainers[0].thermal.race_capacity", NULL},
    {"retainer-thermal-missing-conductance.cfg", 6, "retainers[0].thermal.housing_ambient_conductance", NULL},
    {"retainer-thermal-negative-expansion.cfg", 7, "retainers[0].thermal.expansion", NULL},
    {"retainer-thermal-unknown-key.cfg", 7, "retainers[0].thermal.expansoin", NULL},
    /* housing motion (a CSV history's fault is also located in the CSV file: test_housing.c) */
    {"housing-shock-zero-amplitude.cfg", 5, "housing.shocks[0].amplitude", NULL},
    {"housing-rotation-zero-axis.cfg", 5, "housing.rotation[0].axis", NULL},
    {"housing-rotation-sawtooth.cfg", 5, "housing.rotation[0].shape", NULL},
    {"housing-history-backwards.cfg", 5, "housing.history.time[2]", NULL},
    {"housing-history-both.cfg", 5, "housing.history.file", NULL},
    {"housing-history-start.cfg", 5, "housing.history.start", NULL},
    {"housing-history-scale-zero.cfg", 5, "housing.history.scale", NULL},
    {"housing-csv-unit.cfg", 5, "housing.history.file", NULL},
    {"housing-csv-number.cfg", 5, "housing.history.file", NULL},
    {"housing-csv-missing.cfg", 5, "housing.history.file", NULL},
    {"housing-csv-name.cfg", 5, "housing.history.file", NULL},
    {"housing-csv-twice.cfg", 5, "housing.history.file", NULL},
    {"housing-csv-cr.cfg", 5, "housing.history.file", NULL},
    /* housing body */
    {"housing-body-one-mount.cfg", 5, "housing.body.mounts", NULL},
    {"housing-body-mount-negative.cfg", 6, "housing.body.mounts[1].stiffness", NULL},
    {"housing-body-free-spin.cfg", 5, "housing.body", NULL},
};

static void check_bad_file(const bad_file *b)
{
    char rel[256], where[320];
    td_case *c = (td_case *)&where; /* must come back NULL */
    td_error err;
    td_status st;
    snprintf(rel, sizeof rel, "tests/data/bad/%s", b->file);
    st = td_case_load(td_source_path(rel), NULL, 0, &c, &err);
    if (st != TD_ERR_PARSE) {
        print_error("%s: status %d (%s), expected TD_ERR_PARSE\n", b->file, (int)st, err.message);
        fail();
    }
    assert_null(c);
    /* "FILE:LINE: KEY: what" with FILE ending in the file's name */
    if (b->key)
        snprintf(where, sizeof where, "%s:%d: %s: ", b->shown ? b->shown : b->file, b->line, b->key);
    else
        snprintf(where, sizeof where, "%s:%d: ", b->shown ? b->shown : b->file, b->line);
    if (!strstr(err.message, where)) {
        print_error("%s: message \"%s\" lacks \"%s\"\n", b->file, err.message, where);
        fail();
    }
    assert_printable(err.message);
    assert_true(strlen(err.message) > strlen(where) + 5); /* says what is wrong, too */
}

static void test_bad_files(void **state)
{
    size_t k, n = sizeof bad_files / sizeof bad_files[0], seen = 0;
    DIR *dir;
    struct dirent *e;
    (void)state;
    assert_true(n >= 40);
    for (k = 0; k < n; k++)
        check_bad_file(&bad_files[k]);
    /* every file in the corpus is in the table */
    dir = opendir(td_source_path("tests/data/bad"));
    assert_non_null(dir);
    while ((e = readdir(dir)) != NULL) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".cfg") != 0)
            continue;
        for (k = 0; k < n && strcmp(bad_files[k].file, e->d_name) != 0; k++)
            ;
        if (k == n) {
            print_error("tests/data/bad/%s is not in the table of test_case.c\n", e->d_name);
            fail();
        }
        seen++;
    }
    closedir(dir);
    assert_int_equal(seen, n);
}

/* The run's work is judged by the speed it reaches up to its end time: a ramp point far beyond it
 * at a speed that would be too many revolutions over the whole ramp does not make the case bad. */
static void test_ramp_judged_to_end_time(void **state)
{
    td_case *c = NULL;
    td_error err;
    (void)state;
    if (td_case_load(td_source_path("tests/data/case/ramp-past-end.cfg"), NULL, 0, &c, &err) != TD_OK)
        fail_msg("%s", err.message);
    assert_close(td_model_speed_at(td_case_model(c), td_case_end_time(c), NULL, NULL), 1e7 + 100.0 * (1.0 - 1e-5),
                 1e-12, 0.0);
    td_case_free(&c);
}

/* Paths that cannot be read as a case file: TD_ERR_IO naming the path, never a hang. */
static void test_unreadable_paths(void **state)
{
    const char *fifo = scratch("fifo.cfg"), *locked = scratch("locked.cfg");
    const char *paths[5];
    td_case *c = NULL;
    td_error err;
    size_t k;
    int fd;
    (void)state;
    paths[0] = td_source_path("tests/data/bad");                     /* a directory */
    paths[1] = td_source_path("tests/data/no-such-case.cfg");        /* missing */
    paths[2] = td_source_path("tests/data/case/run.cfg/inside.cfg"); /* through a file */
    paths[3] = fifo;                                                 /* would block a reader */
    paths[4] = locked;
    unlink(fifo);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    write_file(locked, "speed = 1;\n");
    assert_int_equal(chmod(locked, 0), 0);
    for (k = 0; k < 5; k++) {
        td_status st = td_case_load(paths[k], NULL, 0, &c, &err);
        if (k == 4 && (fd = open(locked, O_RDONLY)) >= 0) {
            close(fd); /* running as root: permissions do not apply, the file is readable */
            assert_int_equal(st, TD_ERR_PARSE);
            continue;
        }
        if (st != TD_ERR_IO) {
            print_error("%s: status %d (%s), expected TD_ERR_IO\n", paths[k], (int)st, err.message);
            fail();
        }
        assert_null(c);
        assert_contains(err.message, paths[k]);
        assert_contains(err.message, "cannot read the case file");
    }
    assert_contains(td_case_load(paths[0], NULL, 0, &c, &err) == TD_ERR_IO ? err.message : "", "directory");
    unlink(fifo);
    chmod(locked, 0600);
    unlink(locked);
}

/* Includes that cannot be read: binary data, a FIFO (libconfig would block opening it), a
 * directory, an absolute path; each names the including file and line, or the included file. */
static void test_bad_includes(void **state)
{
    static const struct {
        const char *text, *expect;
    } cases[] = {
        {"# a file with a NUL byte\n@include \"binary-part.cfg\"\n", "binary-part.cfg:2: binary data (byte 0x00)"},
        {"speed = 1.0;\n@include \"fifo-part.cfg\"\n",
         "with-include.cfg:2: cannot open include file \"fifo-part.cfg\""},
        {"speed = 1.0;\n\n@include \"..\"\n", "with-include.cfg:3: cannot open include file \"..\""},
        {"@include \"/etc/hostname\"\n", "with-include.cfg:1: cannot open include file \"/etc/hostname\" (absolute"},
    };
    const char *main_file = scratch("with-include.cfg");
    const char *bin = scratch("binary-part.cfg"), *fifo = scratch("fifo-part.cfg");
    FILE *f = fopen(bin, "wb");
    td_case *c = NULL;
    td_error err;
    size_t k;
    (void)state;
    assert_non_null(f);
    fputs("speed = 1;\nend_time", f);
    fputc('\0', f);
    fputs(" = 1;\n", f);
    fclose(f);
    unlink(fifo);
    assert_int_equal(mkfifo(fifo, 0600), 0);
    for (k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        write_file(main_file, cases[k].text);
        assert_int_equal(td_case_load(main_file, NULL, 0, &c, &err), TD_ERR_PARSE);
        assert_null(c);
        assert_contains(err.message, cases[k].expect);
    }
    unlink(fifo);
}

/* Fuzz finding K2: a file that includes itself 8 times, or includes that fan out 8 x 8 x 8, used
 * to be expanded 8^10 times (minutes, gigabytes). The bounds of case.h stop them at once; the
 * byte bound stops a few large files included again and again. */
static void test_include_bounds(void **state)
{
    static const struct {
        const char *file, *expect;
    } bombs[] = {
        {"tests/data/bad/include-self.cfg", "include-self.cfg:3: @include nested more than 8 deep"},
        {"tests/data/bad/include-fan.cfg", "fragments/fan-1.cfg:8: more than 64 @include files"},
    };
    const char *big = scratch("big-part.cfg"), *zeros = scratch("big-zeros.cfg"), *main_file = scratch("big-main.cfg");
    td_case *c = NULL;
    td_error err;
    size_t k;
    FILE *f;
    long bytes = 0;
    (void)state;
    /* the messages name the bound that stopped the expansion: depth 8, 64 files */
    for (k = 0; k < sizeof bombs / sizeof bombs[0]; k++) {
        assert_int_equal(td_case_load(td_source_path(bombs[k].file), NULL, 0, &c, &err), TD_ERR_PARSE);
        assert_null(c);
        assert_contains(err.message, bombs[k].expect);
    }
    /* 2 inclusions of a file of 12 MiB of comments, then a 12 MiB file of NUL bytes: each under
     * TD_CASE_MAX_FILE_SIZE, the three over TD_CASE_MAX_TOTAL_SIZE (32 MiB). The third is refused
     * from its size before a byte of it is read: had it been read, its NUL bytes would be reported
     * as binary data instead. */
    f = fopen(big, "w");
    assert_non_null(f);
    while (bytes < 12L * 1024L * 1024L) {
        fputs("# padding padding padding padding padding padding padding padding padding padding pad\n", f);
        bytes += 88;
    }
    fclose(f);
    assert_true(bytes < TD_CASE_MAX_FILE_SIZE && 3 * bytes > TD_CASE_MAX_TOTAL_SIZE &&
                2 * bytes < TD_CASE_MAX_TOTAL_SIZE);
    f = fopen(zeros, "w");
    assert_non_null(f);
    assert_int_equal(ftruncate(fileno(f), (off_t)bytes), 0); /* sparse: reads as NUL bytes */
    fclose(f);
    write_file(main_file, "@include \"big-part.cfg\"\n@include \"big-part.cfg\"\n@include \"big-zeros.cfg\"\n");
    assert_int_equal(td_case_load(main_file, NULL, 0, &c, &err), TD_ERR_PARSE);
    assert_null(c);
    assert_contains(err.message, "big-main.cfg:3: the case and its @include files exceed 33554432 bytes");
    unlink(big);
    unlink(zeros);
}

/* The key comparisons libconfig 1.5 will make on `text` (td_cr_expand counts them before it is
 * parsed): each new key is compared with every earlier key of its group. */
static unsigned long long name_compares(const char *text, td_status *st, td_error *err)
{
    td_case_reader r;
    td_text out = {NULL, 0, 0, 0, 0};
    memset(&r, 0, sizeof r);
    r.path_shown = (char *)"generated.cfg";
    r.err = err;
    *st = td_cr_expand(&r, text, NULL, 0, &out);
    free(out.data);
    free(r.wraps);
    return r.shape.name_compares;
}

/* n lines "k<i> = <i>;" inside one group, or n groups of three keys in a list. */
static char *many_keys(int n, int in_list)
{
    char *text = malloc((size_t)n * 64 + 64), *p = text;
    int i;
    assert_non_null(text);
    p += sprintf(p, in_list ? "unbalances = (\n" : "extra = {\n");
    for (i = 0; i < n; i++)
        p += in_list ? sprintf(p, "{ node = 1; magnitude = 0.0; phase = %d.0; },\n", i)
                     : sprintf(p, "k%d = %d;\n", i, i);
    sprintf(p, in_list ? "{ node = 1; } );\n" : "};\n");
    return text;
}

/* libconfig 1.5's duplicate-key search made parsing quadratic in the keys of a group (20000 keys:
 * 15.6 s). A group holds at most TD_CASE_MAX_GROUP_KEYS keys, refused before parsing, so the
 * comparisons grow linearly with the case: exactly 3 per entry of a list of 3-key groups. */
static void test_many_keys(void **state)
{
    char *small = many_keys(10000, 1), *large = many_keys(20000, 1), *group = many_keys(20000, 0);
    const char *path = scratch("many-keys.cfg");
    td_case *c = NULL;
    td_error err;
    td_status st;
    unsigned long long a, b;
    (void)state;
    a = name_compares(small, &st, &err);
    assert_int_equal(st, TD_OK);
    b = name_compares(large, &st, &err);
    assert_int_equal(st, TD_OK);
    assert_true(a == 3ULL * 10000 && b == 3ULL * 20000); /* the last entry, one key, compares none */
    /* one group of 20000 keys: refused at the 65th, having counted 64 * 63 / 2 comparisons */
    assert_int_equal(name_compares(group, &st, &err), 64ULL * 63 / 2);
    assert_int_equal(st, TD_ERR_PARSE);
    assert_contains(err.message, "generated.cfg:66: k64: more than 64 keys in one group");
    write_file(path, group);
    assert_int_equal(td_case_load(path, NULL, 0, &c, &err), TD_ERR_PARSE);
    assert_contains(err.message, "many-keys.cfg:66: k64: more than 64 keys in one group");
    free(small);
    free(large);
    free(group);
    unlink(path);
}

/* Overrides add to the same bounds: a value with more entries than TD_CASE_MAX_SETTINGS is
 * refused before libconfig parses it, and no group grows past TD_CASE_MAX_GROUP_KEYS. */
static void test_override_bounds(void **state)
{
    char *big = malloc(2 * (TD_CASE_MAX_SETTINGS + 1) + 16), names[70][16];
    const char *ovs[70];
    td_case *c = NULL;
    td_error err;
    int i;
    (void)state;
    assert_non_null(big);
    strcpy(big, "x=[1");
    for (i = 0; i < TD_CASE_MAX_SETTINGS; i++)
        memcpy(big + 4 + 2 * i, ",1", 2);
    strcpy(big + 4 + 2 * TD_CASE_MAX_SETTINGS, "]");
    ovs[0] = big;
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), ovs, 1, &c, &err), TD_ERR_PARSE);
    assert_contains(err.message, "paper-a.cfg: --set 'x=[1,1,1");
    assert_contains(err.message, "': more than 200000 settings and list or array entries in one case");
    free(big);
    for (i = 0; i < 70; i++) {
        snprintf(names[i], sizeof names[i], "x%d=1", i);
        ovs[i] = names[i];
    }
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), ovs, 70, &c, &err), TD_ERR_PARSE);
    assert_contains(err.message, "the group would hold more than 64 keys");
    assert_null(c);
}

/* CRLF line endings read as LF ones (the bare-CR file is in the bad_files table). */
static void test_crlf(void **state)
{
    td_case *c = load_ok("tests/data/case/line-endings-crlf.cfg", NULL, 0);
    (void)state;
    assert_close(td_model_speed(td_case_model(c)), 123.0, 0.0, 0.0);
    assert_close(td_case_end_time(c), 0.25, 0.0, 0.0);
    assert_close(td_case_output_options(c)->sample_rate, 2000.0, 0.0, 0.0);
    td_case_free(&c);
}

/* gravity.direction = [1.7e308, 1.7e308] is a direction like any other: its norm overflowed and
 * 0 / inf turned gravity off. */
static void test_gravity_direction_huge(void **state)
{
    static const char *const ov[] = {"gravity.direction=[1.7e308, 1.7e308]", "gravity.enabled=true"};
    td_case *c = load_ok("cases/paper-a.cfg", ov, 2);
    double gx, gy;
    (void)state;
    td_model_gravity(td_case_model(c), &gx, &gy);
    assert_close(gx, 9.81 / sqrt(2.0), 1e-15, 0.0);
    assert_close(gy, 9.81 / sqrt(2.0), 1e-15, 0.0);
    td_case_free(&c);
}

/* The message record holds 512 bytes: a long override or path echoed in front of the reason used
 * to push the reason out. The echo is shortened now, never the reason. */
static void test_long_messages(void **state)
{
    static const char expect[] = "long.cfg:1: description: expected a string \"...\", got an integer";
    char ov[700], dir[1024], path[1200];
    const char *ovs[1] = {ov};
    td_case *c = NULL;
    td_error err;
    size_t n;
    (void)state;
    memset(ov, 0, sizeof ov);
    memcpy(ov, "speed=\"", 7);
    memset(ov + 7, 'a', 600);
    ov[607] = '"';
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), ovs, 1, &c, &err), TD_ERR_PARSE);
    n = strlen(err.message);
    assert_true(n < TD_ERROR_MESSAGE_SIZE);
    assert_contains(err.message, "paper-a.cfg: --set 'speed=\"aaa");
    assert_contains(err.message, "\"': speed: expected a number, got the string \"aaa");
    assert_string_equal(err.message + n - 6, "aa...\""); /* the reason's own quote, cut at 64 */
    /* a path of 460 characters: the message still ends with the key and the reason */
    snprintf(dir, sizeof dir, "%s", scratch(""));
    n = strlen(dir);
    memset(dir + n, 'd', 200);
    dir[n + 200] = '\0';
    mkdir(dir, 0755);
    strcat(dir, "/");
    n = strlen(dir);
    memset(dir + n, 'e', 200);
    dir[n + 200] = '\0';
    mkdir(dir, 0755);
    snprintf(path, sizeof path, "%s/long.cfg", dir);
    write_file(path, "description = 5;\n");
    assert_int_equal(td_case_load(path, NULL, 0, &c, &err), TD_ERR_PARSE);
    n = strlen(err.message);
    assert_true(n > strlen(expect));
    assert_string_equal(err.message + n - strlen(expect), expect);
    unlink(path);
    rmdir(dir);
    dir[strlen(dir) - 201] = '\0';
    rmdir(dir);
}

/* td_run bounds a run given through the API as the case reader bounds a case (touchdown/limits.h):
 * each bound broken alone is refused before a step is taken, leaving the simulation at t = 0. */
static void test_run_limits_api(void **state)
{
    td_case *c = load_ok("cases/jeffcott.cfg", NULL, 0);
    td_sim_options so = *td_case_sim_options(c);
    td_output_options out = *td_case_output_options(c);
    td_sim *sim = NULL;
    td_error err;
    (void)state;
    out.csv_path[0] = '\0';
    out.hdf5_path[0] = '\0';
    assert_int_equal(td_sim_create(td_case_model(c), &so, &sim, &err), TD_OK);
    /* 5000 Hz x 1e12 s = 5e15 samples */
    assert_int_equal(td_run(sim, 1e12, &out, NULL, NULL, NULL, &err), TD_ERR_INVALID);
    assert_contains(err.message, "output samples (at most 1e+08)");
    /* 200 rad/s x 1e5 s / 2 pi = 3.2e6 revolutions (1e5 samples at 1 Hz) */
    out.sample_rate = 1.0;
    assert_int_equal(td_run(sim, 1e5, &out, NULL, NULL, NULL, &err), TD_ERR_INVALID);
    assert_contains(err.message, "shaft revolutions (at most 1e+06)");
    assert_close(td_sim_time(sim), 0.0, 0.0, 0.0);
    td_sim_free(&sim);
    so.solver.max_step = 1e-300;
    assert_int_equal(td_sim_create(td_case_model(c), &so, &sim, &err), TD_OK);
    assert_int_equal(td_run(sim, 0.1, &out, NULL, NULL, NULL, &err), TD_ERR_INVALID);
    assert_contains(err.message, "solver steps (at most 1e+08)");
    assert_close(td_sim_time(sim), 0.0, 0.0, 0.0);
    td_sim_free(&sim);
    td_case_free(&c);
}

/* Fuzz finding K4: libconfig 1.5 rejects a last-line comment without a final newline ("syntax
 * error"); the reader appends the newline to the main file, so these load. */
static void test_comment_at_eof(void **state)
{
    static const char *const endings[] = {"# a comment", "// a comment", "end_time = 0.1; # a comment",
                                          "end_time = 0.1; // a comment", "end_time = 0.1;"};
    const char *main_file = scratch("comment-at-eof.cfg");
    char text[512];
    td_case *c = load_ok("tests/data/case/comment-at-eof.cfg", NULL, 0);
    size_t k;
    (void)state;
    assert_close(td_model_speed(td_case_model(c)), 100.0, 0.0, 0.0);
    assert_close(td_case_end_time(c), 0.1, 0.0, 0.0);
    assert_int_equal(td_model_node_count(td_case_model(c)), 13);
    td_case_free(&c);
    for (k = 0; k < sizeof endings / sizeof endings[0]; k++) {
        td_error err;
        snprintf(text, sizeof text,
                 "shaft = { length = 2.0; elements = 4; outer_diameter = 0.05;\n"
                 "  material = { E = 2.11e11; G = 8.1e10; density = 7810.0; }; };\n"
                 "speed = 100.0;\n%s%s",
                 k < 2 ? "end_time = 0.1;\n" : "", endings[k]); /* no final newline */
        write_file(main_file, text);
        if (td_case_load(main_file, NULL, 0, &c, &err) != TD_OK) {
            print_error("ending \"%s\": %s\n", endings[k], err.message);
            fail();
        }
        assert_close(td_case_end_time(c), 0.1, 0.0, 0.0);
        /* the case text ends with the comment and one newline */
        assert_int_equal(td_case_text(c)[strlen(td_case_text(c)) - 1], '\n');
        assert_contains(td_case_text(c), endings[k]);
        td_case_free(&c);
    }
}

static void test_api_misuse(void **state)
{
    td_case *c = NULL;
    td_error err;
    const char *ov[1] = {"speed=1"};
    (void)state;
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), NULL, 0, NULL, &err), TD_ERR_INVALID);
    assert_int_equal(td_case_load(NULL, NULL, 0, &c, &err), TD_ERR_INVALID);
    assert_null(c);
    /* an empty path says so (it used to read ": cannot read the case file") */
    assert_int_equal(td_case_load("", NULL, 0, &c, &err), TD_ERR_IO);
    assert_null(c);
    assert_int_equal(strncmp(err.message, "case file path is empty", 23), 0);
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), NULL, 1, &c, &err), TD_ERR_INVALID);
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), ov, -1, &c, &err), TD_ERR_INVALID);
    assert_int_equal(td_case_load(td_source_path("cases/paper-a.cfg"), NULL, 0, &c, NULL), TD_OK); /* err optional */
    td_case_free(&c);
    assert_int_equal(td_case_load(td_source_path("tests/data/bad/empty.cfg"), NULL, 0, &c, NULL), TD_ERR_PARSE);
    td_case_free(&c);
    td_case_free(NULL);
    assert_null(td_case_model(NULL));
    assert_null(td_case_text(NULL));
    assert_string_equal(td_case_description(NULL), "");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paper_cases),
        cmocka_unit_test(test_text_is_self_contained),
        cmocka_unit_test(test_other_examples),
        cmocka_unit_test(test_all_keys),
        cmocka_unit_test(test_other_forms_and_defaults),
        cmocka_unit_test(test_retainer_contact_stiffness_zero),
        cmocka_unit_test(test_docs_match_reader),
        cmocka_unit_test(test_documented_defaults),
        cmocka_unit_test(test_case_key_api),
        cmocka_unit_test(test_refine),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_bad_overrides),
        cmocka_unit_test(test_bad_files),
        cmocka_unit_test(test_ramp_judged_to_end_time),
        cmocka_unit_test(test_model_rules_located),
        cmocka_unit_test(test_rules_name_the_set_they_compare_with),
        cmocka_unit_test(test_override_named_in_site),
        cmocka_unit_test(test_unreadable_paths),
        cmocka_unit_test(test_bad_includes),
        cmocka_unit_test(test_include_bounds),
        cmocka_unit_test(test_run_limits_api),
        cmocka_unit_test(test_many_keys),
        cmocka_unit_test(test_override_bounds),
        cmocka_unit_test(test_crlf),
        cmocka_unit_test(test_long_messages),
        cmocka_unit_test(test_gravity_direction_huge),
        cmocka_unit_test(test_comment_at_eof),
        cmocka_unit_test(test_api_misuse),
        cmocka_unit_test(test_controllers_all_keys),
        cmocka_unit_test(test_resonant_default_follows_speed),
        cmocka_unit_test(test_controller_closed_forms),
        cmocka_unit_test(test_controller_rigid_by_hand),
        cmocka_unit_test(test_controller_rigid_is_the_shorthand),
        cmocka_unit_test(test_controller_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
