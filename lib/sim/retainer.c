/*
 * The retainers of a sim (retainer.h): per-retainer queries of the state and the bookkeeping of
 * their contact and slip modes.
 */
#include "sim/sim_internal.h"

#include <math.h>
#include <string.h>

void td_sim_retainer_init(td_sim_retainer *r, const td_system *sys, int k, const td_contact_options *run)
{
    td_model_get_retainer(td_system_model(sys), k, &r->r);
    /* a retainer's node is a boundary node of a reduced rotor (reduce.c): physical in q */
    r->dx = td_system_node_dof(sys, r->r.node, TD_DOF_X);
    r->dy = td_system_node_dof(sys, r->r.node, TD_DOF_Y);
    r->rx = r->ry = r->rs = r->fi = -1;
    r->rolling = 0;
    r->mode = TD_RMODE_FREE;
    r->armed = 1;
    r->slip = 1;
    if (r->r.contact.stiffness > 0.0) { /* the retainer's own law (model.h td_retainer_contact) */
        r->compliant = 1;
        r->law.stiffness = r->r.contact.stiffness;
        r->law.exponent = r->r.contact.exponent > 0.0 ? r->r.contact.exponent : 1.0;
        r->law.damping = r->r.contact.damping;
        r->law.coefficient = r->r.contact.damping_coefficient;
    } else {
        r->compliant = run->model == TD_CONTACT_PENALTY;
        r->law.stiffness = run->stiffness;
        r->law.exponent = run->exponent;
        r->law.damping = run->damping;
        r->law.coefficient = run->damping_coefficient;
    }
}

void td_sim_node_state(const td_sim *s, int k, const double *y, double *x, double *yy, double *vx, double *vy)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    *x = y[s->dae.oq + r->dx];
    *yy = y[s->dae.oq + r->dy];
    *vx = y[s->dae.ov + r->dx];
    *vy = y[s->dae.ov + r->dy];
    if (r->rx >= 0) {
        *x -= y[s->dae.oq + r->rx];
        *yy -= y[s->dae.oq + r->ry];
        *vx -= y[s->dae.ov + r->rx];
        *vy -= y[s->dae.ov + r->ry];
    }
}

double td_sim_race_speed(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    return r->rs >= 0 ? y[s->dae.ov + r->rs] : r->r.bore_speed;
}

/* Contact through a force law: the force acts whenever the node penetrates, whatever the
 * retainer's mode: the mode only places the enter/exit roots and records the events
 * (td_sim_penalty_mode_wanted), so a crossing that root finding misses (a grazing node) cannot let
 * the rotor pass through the retainer. The force is continuous where it switches on (zero at
 * delta = 0; a Kelvin-Voigt damper's jump is met by the enter event's restart). */
int td_sim_penalty_model(const td_sim *s, int k)
{
    return s->contacts.ret[k].compliant;
}

/* A Kelvin-Voigt contact whose enter root left the node a hair outside (delta <= 0, inside the
 * noise band): its damper d rate acts from the restart on, as it does a hair inside, instead of
 * jumping in within the next step (which failed IDA's error test at h ~ 1e-12 s). */
static double kelvin_voigt_at_touch(const td_penalty_law *law, double rate, double *fd, double *fr)
{
    double f = law->coefficient * rate;
    if (fd)
        *fd = 0.0;
    if (fr)
        *fr = f > 0.0 ? law->coefficient : 0.0;
    return f > 0.0 ? f : 0.0;
}

double td_sim_penalty_force(const td_sim *s, int k, const double *y, double *fd, double *fr)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, delta, rate;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    delta = hypot(x, yy) - r->r.clearance;
    rate = td_contact_radial_velocity(x, yy, vx, vy);
    if (delta <= 0.0 && r->mode == TD_RMODE_PENETRATING && r->law.damping == TD_DAMPING_KELVIN_VOIGT)
        return kelvin_voigt_at_touch(&r->law, rate, fd, fr);
    return td_contact_penalty_force(&r->law, delta, rate, fd, fr);
}

double td_sim_normal_force(const td_sim *s, int k, const double *y)
{
    if (s->contacts.ret[k].mode == TD_RMODE_CONTACT)
        return y[s->dae.ol + k];
    return td_sim_penalty_model(s, k) ? td_sim_penalty_force(s, k, y, NULL, NULL) : 0.0;
}

double td_sim_sliding_velocity(const td_sim *s, int k, const double *y)
{
    double x, yy, vx, vy;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    return td_contact_sliding_velocity(&s->contacts.ret[k].r, td_sim_rotor_speed(s, y), td_sim_race_speed(s, k, y), x,
                                       yy, vx, vy);
}

void td_sim_sliding_gradient(const td_sim *s, int k, const double *y, double g[4])
{
    double x, yy, vx, vy;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    td_contact_sliding_velocity_gradient(&s->contacts.ret[k].r, x, yy, vx, vy, g);
}

double td_sim_slip_factor(const td_sim *s, int k, const double *y, double *dphi)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    if (r->r.stick) { /* rolling: F_t carries the friction; sliding: full mu N in its direction */
        if (dphi)
            *dphi = 0.0;
        return r->rolling ? 0.0 : (double)r->slip;
    }
    return td_contact_slip_factor(td_sim_sliding_velocity(s, k, y), TD_CONTACT_SLIP_BAND, dphi);
}

double td_sim_friction_force(const td_sim *s, int k, const double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    if (r->rolling)
        return y[s->dae.of + r->fi];
    return td_sim_slip_factor(s, k, y, NULL) * r->r.friction * td_sim_normal_force(s, k, y);
}

void td_sim_roll_row(const td_sim *s, int k, const double *y, td_contact_row *row, double *h)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, g[4];
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    td_sim_sliding_gradient(s, k, y, g);
    *h = g[0] * vx + g[1] * vy;
    row->count = 2;
    row->dof[0] = r->dx;
    row->dof[1] = r->dy;
    row->j[0] = g[2];
    row->j[1] = g[3];
    if (r->rx >= 0) {
        row->dof[row->count] = r->rx;
        row->j[row->count++] = -g[2];
        row->dof[row->count] = r->ry;
        row->j[row->count++] = -g[3];
    }
    if (r->rs >= 0) { /* eq. (16): d v_s / d Omega_b = -R_b */
        row->dof[row->count] = r->rs;
        row->j[row->count++] = -r->r.bore_radius;
    }
    if (s->machine.spin >= 0) { /* eq. (16): d v_s / d Omega = R_s */
        row->dof[row->count] = s->machine.spin;
        row->j[row->count++] = r->r.shaft_radius;
    }
}

void td_sim_roll_column(const td_sim *s, int k, const double *y, double *col)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, n[2], t[2];
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    td_contact_frame(x, yy, n, t);
    memset(col, 0, sizeof(double) * (size_t)s->dae.n);
    col[r->dx] = t[0];
    col[r->dy] = t[1];
    if (r->rx >= 0) {
        col[r->rx] = -t[0];
        col[r->ry] = -t[1];
    }
    if (r->rs >= 0)
        col[r->rs] = -r->r.bore_radius;
    if (s->machine.spin_free) /* F_t brakes a free spin: torque -R_s F_t */
        col[s->machine.spin] = r->r.shaft_radius;
}

double td_sim_race_drag(const td_sim *s, int k, const double *y, double *dT)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double band, phi, dphi = 0.0;
    if (r->rs < 0 || !(r->r.race.drag_torque > 0.0)) {
        if (dT)
            *dT = 0.0;
        return 0.0;
    }
    band = TD_CONTACT_SLIP_BAND / r->r.bore_radius; /* the race surface creeps at v_reg */
    phi = td_contact_slip_factor(y[s->dae.ov + r->rs], band, &dphi);
    if (dT)
        *dT = r->r.race.drag_torque * dphi;
    return r->r.race.drag_torque * phi;
}

void td_sim_contact_row(const td_sim *s, int k, const double *y, td_contact_row *row)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    row->count = 2;
    row->dof[0] = r->dx;
    row->dof[1] = r->dy;
    td_contact_constraint_jacobian(x, yy, r->r.clearance, row->j);
    if (r->rx >= 0) { /* g depends on node minus race */
        row->count = 4;
        row->dof[2] = r->rx;
        row->dof[3] = r->ry;
        row->j[2] = -row->j[0];
        row->j[3] = -row->j[1];
    }
}

void td_sim_contact_column(const td_sim *s, int k, const double *y, double *col)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, c = r->r.clearance, rad;
    double sm = td_sim_slip_factor(s, k, y, NULL) * r->r.friction;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    memset(col, 0, sizeof(double) * (size_t)s->dae.n);
    col[r->dx] = x / c - sm * yy / rad;
    col[r->dy] = yy / c + sm * x / rad;
    if (r->rx >= 0) {
        col[r->rx] = -col[r->dx];
        col[r->ry] = -col[r->dy];
    }
    if (r->rs >= 0) /* the friction force s mu lambda turns the race: torque R_b s mu lambda */
        col[r->rs] = -r->r.bore_radius * sm;
    if (s->machine.spin_free) /* and brakes a free rotor: torque -R_s s mu lambda */
        col[s->machine.spin] = r->r.shaft_radius * sm;
}

void td_sim_project_onto_circle(const td_sim *s, int k, double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, rad;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = hypot(x, yy);
    if (!(rad > 0.0))
        return;
    /* the node moves, the race stays: node = race centre + relative position scaled onto c */
    y[s->dae.oq + r->dx] = x * (r->r.clearance / rad);
    y[s->dae.oq + r->dy] = yy * (r->r.clearance / rad);
    if (r->rx >= 0) {
        y[s->dae.oq + r->dx] += y[s->dae.oq + r->rx];
        y[s->dae.oq + r->dy] += y[s->dae.oq + r->ry];
    }
}

void td_sim_init_slip(td_sim *s, int k, const double *y)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    double vs = td_sim_sliding_velocity(s, k, y);
    int sg = vs < 0.0 ? -1 : 1;
    r->band_from = sg;
    r->slip = fabs(vs) < TD_CONTACT_SLIP_BAND && !r->r.stick ? 0 : sg;
    r->rolling = 0;
    if (r->r.stick && fabs(vs) < TD_CONTACT_SLIP_BAND) { /* no slip to speak of: try rolling */
        r->rolling = 1;
        s->contacts.roll_tried[k] = 1;
    }
}

void td_sim_project_rolling(const td_sim *s, int k, double *y)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double vs = td_sim_sliding_velocity(s, k, y), x, yy, vx, vy, rad, n[2], t[2], dv;
    if (r->rs >= 0) { /* the race turns by what its surface lags: v_s = 0 */
        y[s->dae.ov + r->rs] += vs / r->r.bore_radius;
        return;
    }
    /* a fixed bore: the node's whirl rate moves, v_s = ... + (R_b - R_s) dtheta/dt (eq. 16) */
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    rad = td_contact_frame(x, yy, n, t);
    dv = -vs * rad / (r->r.bore_radius - r->r.shaft_radius);
    y[s->dae.ov + r->dx] += dv * t[0];
    y[s->dae.ov + r->dy] += dv * t[1];
}

void td_sim_unroll(td_sim *s, int k, double *y, int slip)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    r->rolling = 0;
    r->slip = slip;
    if (r->fi >= 0)
        y[s->dae.of + r->fi] = 0.0;
}

/* +1 or -1: the sign of v, or `otherwise` at v == 0. */
static int sign_or(double v, int otherwise)
{
    return v > 0.0 ? 1 : (v < 0.0 ? -1 : otherwise);
}

int td_sim_slip_root(td_sim *s, int k, const double *y)
{
    td_sim_retainer *r = &s->contacts.ret[k];
    if (r->slip != 0) { /* into the band: no event */
        r->band_from = r->slip;
        r->slip = 0;
        return 0;
    }
    /* out of the band: a reversal if on the other side */
    r->slip = sign_or(td_sim_sliding_velocity(s, k, y), -r->band_from);
    return r->slip != r->band_from;
}

void td_sim_release(td_sim *s, int k, double *y)
{
    td_sim_unroll(s, k, y, s->contacts.ret[k].slip);
    s->contacts.ret[k].mode = TD_RMODE_FREE;
    s->contacts.ret[k].armed = 0; /* left at r = c: no onset until the gap has opened (grazing guard) */
    y[s->dae.ol + k] = 0.0;
}

/*
 * Penalty model: the mode of retainer k follows its state. The penalty force itself is a function
 * of the state (it acts whenever delta = r - c > 0, whatever the mode), so the mode only places
 * the roots (the enter root waits for the gap to fall through zero, the exit root for it to rise)
 * and records the events. Outside a band |delta| <= penalty_band the state decides; inside it,
 * where a restart's Newton correction can move delta either way, `in_band` does (the flip a root
 * asks for, or the current mode). Without the state check a mode could disagree with the state
 * for good: a grazing node's gap crosses zero several times within a step, IDA reports one
 * crossing, and a free retainer whose node is already outside never sees its enter root again
 * (case C lost a contact that way and its node flew 1.7 mm past the clearance, force-free).
 */
static double penalty_band(const td_sim *s)
{
    return s->machine.constraint_tol;
}

td_rmode td_sim_penalty_mode_wanted(const td_sim *s, int k, const double *y, td_rmode in_band)
{
    const td_sim_retainer *r = &s->contacts.ret[k];
    double x, yy, vx, vy, delta;
    td_sim_node_state(s, k, y, &x, &yy, &vx, &vy);
    delta = hypot(x, yy) - r->r.clearance;
    if (delta > penalty_band(s))
        return TD_RMODE_PENETRATING;
    if (delta < -penalty_band(s))
        return TD_RMODE_FREE;
    return in_band;
}
