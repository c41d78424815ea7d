/*
 * Embedding touchdown: build the reference rotor in code (no case file), drive its AMBs with
 * our own sampled PD controller (zero-order hold) through the step API, and print every
 * contact event.
 *
 *   cc embed.c $(pkg-config --cflags --libs touchdown) -o embed      (or find_package(touchdown))
 */
#include <touchdown/touchdown.h>

#include <stdio.h>

#define NODES 13
#define SAMPLE_RATE 10000.0 /* controller sampling, Hz */

/* The rig of docs/reference-rig.md: 12 steel beam elements over 2 m, four discs, two AMB journals. */
static int build_rotor(td_model *m, td_error *err)
{
    const td_shaft_element el = {2.0 / 12, 0.05, 0.0, {2.11e11, 8.1e10, 7810.0}};
    const int disc_nodes[4] = {1, 5, 7, 11};
    const int amb_nodes[2] = {3, 9};
    const int retainer_nodes[2] = {2, 10};
    int i;
    for (i = 0; i < NODES - 1; i++)
        if (td_model_add_shaft_element(m, &el, err))
            return -1;
    for (i = 0; i < 4; i++) {
        /* a solid steel disc of 10 kg and radius 0.12 m: the library computes Ip and Id */
        const td_disc_geometry g = {disc_nodes[i], 0.12, 0.0, 7810.0, 0.0, 10.0};
        td_disc d;
        if (td_disc_from_geometry(&g, &d, err) || td_model_add_disc(m, &d, err))
            return -1;
    }
    for (i = 0; i < 2; i++) {
        /* our own controller replaces the built-in PD, so only ks (the magnet) matters here */
        td_amb a = {amb_nodes[i], amb_nodes[i], 1.0e6, 200.0, 1.0e4, 40.0, 1.0 / (2 * TD_PI * 100), 1700, 0,
                    1.2e-3,       0.0,          0.0};
        td_retainer r = {.node = retainer_nodes[i],
                         .clearance = 0.75e-3,
                         .shaft_radius = 0.025,
                         .bore_radius = 0.02575,
                         .friction = 0.1,
                         .bore_speed = 0.0,
                         .restitution = 0.0};
        if (td_model_add_point_mass(m, amb_nodes[i], 14.6, err) || td_model_add_amb(m, &a, err) ||
            td_model_add_retainer(m, &r, err))
            return -1;
    }
    {
        td_unbalance u = {1, 0.10, 0.0}; /* large enough to reach the retainers */
        if (td_model_add_unbalance(m, &u, err) || td_model_set_speed(m, 90.0, err))
            return -1;
    }
    return td_model_validate(m, err) == TD_OK ? 0 : -1;
}

/* A sampled PD law with a backward-difference derivative: F = -ki (kp x + kd dx/dt). */
typedef struct pd_axis {
    double previous;
} pd_axis;

static double pd_control(pd_axis *s, double x, double dt)
{
    const double ki = 200.0, kp = 1.0e4, kd = 40.0;
    double rate = (x - s->previous) / dt;
    s->previous = x;
    return -ki * (kp * x + kd * rate);
}

int main(void)
{
    td_model *m = NULL;
    td_sim *sim = NULL;
    td_sim_options opt;
    td_error err;
    pd_axis axes[2][2] = {{{0}, {0}}, {{0}, {0}}};
    const int amb_nodes[2] = {3, 9};
    double q[4 * NODES], dt = 1.0 / SAMPLE_RATE, t_end = 0.3;
    long k, onsets = 0;
    int status = 1, a;

    printf("touchdown %s\n", td_version());
    if (td_model_create(&m, &err) || build_rotor(m, &err))
        goto fail;
    td_sim_options_default(&opt);
    opt.start = TD_START_REST;
    if (td_sim_create(m, &opt, &sim, &err))
        goto fail;
    for (a = 0; a < 2; a++)
        td_sim_set_amb_mode(sim, a, TD_AMB_EXTERNAL, NULL);

    for (k = 1; k * dt <= t_end + 1e-12; k++) {
        double t_next = k * dt;
        td_status st;
        /* sample the sensors, compute, hold the control force until the next sample */
        td_sim_get_state(sim, q, NULL);
        for (a = 0; a < 2; a++) { /* the sensors' DOFs in q (a reduced rotor keeps them physical) */
            int ix = td_system_node_dof(td_sim_system(sim), amb_nodes[a], TD_DOF_X);
            int iy = td_system_node_dof(td_sim_system(sim), amb_nodes[a], TD_DOF_Y);
            td_sim_set_amb_control(sim, a, pd_control(&axes[a][0], q[ix], dt), pd_control(&axes[a][1], q[iy], dt),
                                   NULL);
        }
        while ((st = td_sim_step(sim, t_next, NULL, &err)) == TD_EVENT) {
            td_event ev;
            td_sim_last_event(sim, &ev);
            if (ev.kind == TD_EVENT_CONTACT_ONSET)
                onsets++;
            if (ev.kind == TD_EVENT_CONTACT_ONSET || ev.kind == TD_EVENT_RELEASE)
                if (onsets <= 10)
                    printf("t = %.9f s  retainer %d  %-17s  radial velocity %+.6f -> %+.6f m/s  impulse %.4g N s\n",
                           ev.time, ev.retainer, td_event_kind_name(ev.kind), ev.radial_velocity_before,
                           ev.radial_velocity_after, ev.impulse);
        }
        if (st != TD_OK) {
            fprintf(stderr, "embed: step failed at t = %.9f s: %s\n", td_sim_time(sim), err.message);
            goto done;
        }
    }
    printf("%ld contact onsets in %.3f s\n", onsets, t_end);
    status = onsets > 0 ? 0 : 1;
    goto done;
fail:
    fprintf(stderr, "embed: %s\n", err.message);
done:
    td_sim_free(&sim);
    td_model_free(&m);
    return status;
}
