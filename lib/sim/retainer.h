/*
 * One retainer bearing as the sim sees it: its contact mode, the slip bookkeeping of its friction
 * law, its race (a body with states of its own, or the paper's fixed bore) and the queries of the
 * contact geometry. The DAE (sim_residual.c) and the mode switching (sim_modes.c) ask these; the
 * retainer's own data is the model's, read once when the sim is created.
 *
 * Geometry is relative: the contact sees the node's position and velocity relative to the race
 * centre (x - x_r, ...), which is the housing's origin for a fixed or rigidly mounted race. Forces
 * come in pairs: what pushes the rotor node pulls the race the other way, and the friction force
 * turns the race (torque R_b times the tangential force, eq. 16's Omega_b its speed).
 */
#ifndef TD_SIM_RETAINER_H
#define TD_SIM_RETAINER_H

#include "contact/contact.h"
#include "touchdown/model.h"
#include "touchdown/sim.h"
#include "touchdown/system.h"

/* Contact mode of one retainer. */
typedef enum td_rmode {
    TD_RMODE_FREE = 0,       /* no contact: lambda = eta = 0 */
    TD_RMODE_CONTACT = 1,    /* constrained contact: g = 0, J v = 0, lambda >= 0 */
    TD_RMODE_PENETRATING = 2 /* penalty contact: delta = r - c > 0, force F_n(delta, rate) */
} td_rmode;

/* Root functions, three per retainer (their meaning depends on the mode, see sim_residual.c). */
enum { TD_ROOT_CONTACT = 0, TD_ROOT_SLIP = 1, TD_ROOT_REARM = 2, TD_ROOTS_PER_RETAINER = 3 };

typedef struct td_sim_retainer {
    td_retainer r;      /* the model's data: the sim's one copy, read at creation (td_sim_retainer_init) */
    int dx, dy;         /* global DOFs x, y of its node */
    int rx, ry;         /* DOFs x, y of the race centre on its mount, -1: no mount (centre fixed at 0) */
    int rs;             /* DOF of the race: angle in q, speed Omega_b in v; -1: Omega_b fixed at bore_speed */
    int compliant;      /* 1: contact through a force law (the run's penalty model or the retainer's own) */
    td_penalty_law law; /* that force law */
    int fi;             /* stick retainers (r.stick): index of its friction multiplier F_t in the y block
                         * at s->dae.of; -1 for the others */
    int rolling;        /* stick retainers in contact: 1 while rolling without slip (v_s = 0 held by F_t) */
    td_rmode mode;
    int armed;     /* free, constraint model: onset root at gap = 0 (1) or at gap = -eps (0, after a
                    * release or a rejected/bouncing onset); penalty model: 0 after an exit, the onset
                    * root stays at gap = 0 but the free flight waits (flight.c). Both re-armed when
                    * the gap exceeds +eps. */
    int slip;      /* slip mode of eq. (17): +1 or -1 sliding (|v_s| >= v_reg), 0 inside the
                    * slip-regularised band |v_s| < v_reg (contact.h TD_CONTACT_SLIP_BAND). Only the
                    * roots depend on it: the friction force is phi(v_s) of the state in every mode.
                    * Stick retainers have no band: slip is the sliding direction, +1 or -1, and the
                    * friction force mu N slip until v_s reaches 0 (then rolling, or a reversal) */
    int band_from; /* slip = 0: the sliding sign before the band (a reversal if it leaves the other way) */
} td_sim_retainer;

/* The contact set's record: the retainers, with their DOFs (race.c lays out the races') and their
 * contact and slip modes (retainer.c; sim_modes.c switches them). The layers above read it. */
typedef struct td_sim_contacts {
    td_sim_retainer *ret; /* nr */
    int *roll_tried;      /* nr: stick retainers set rolling at a slip root, not yet confirmed */
    int *touching;        /* nr: retainers touching their circles at the start (start.c) */
} td_sim_contacts;

/* Retainer k of `model`, free and armed, sliding forwards, its contact law from the run's options;
 * its race DOFs unassigned (-1: td_sim_races_layout assigns them). */
void td_sim_retainer_init(td_sim_retainer *r, const td_system *sys, int k, const td_contact_options *run);

/* Position x, y and velocity vx, vy of retainer k's node relative to its race centre at state y. */
void td_sim_node_state(const td_sim *s, int k, const double *y, double *x, double *yy, double *vx, double *vy);
/* Race speed Omega_b of retainer k at state y, rad/s: its state, or the fixed bore_speed. */
double td_sim_race_speed(const td_sim *s, int k, const double *y);
/* 1 if retainer k's contact is a force law (the force acts whenever the node penetrates, whatever
 * the mode), 0 for the constraint. */
int td_sim_penalty_model(const td_sim *s, int k);
/* Penalty normal force of retainer k at y and its partials by delta and its rate (either may be NULL). */
double td_sim_penalty_force(const td_sim *s, int k, const double *y, double *fd, double *fr);
/* Normal force of retainer k at state y: lambda (contact), F_n (penetrating) or 0. */
double td_sim_normal_force(const td_sim *s, int k, const double *y);
/* Sliding velocity eq. (16) of retainer k at state y. */
double td_sim_sliding_velocity(const td_sim *s, int k, const double *y);
/* d v_s / d(x, y, vx, vy) of retainer k at y (relative coordinates); d v_s / d Omega_b = -R_b. */
void td_sim_sliding_gradient(const td_sim *s, int k, const double *y, double g[4]);
/* Slip factor phi of retainer k at state y: phi(v_s) of contact.h, the sliding direction of a stick
 * retainer, 0 while it rolls (its friction is then F_t); *dphi = d phi / d v_s (may be NULL). */
double td_sim_slip_factor(const td_sim *s, int k, const double *y, double *dphi);
/* Friction force of retainer k at y on the race along the whirl tangent t, N (the rotor feels the
 * opposite): phi mu N sliding, the multiplier F_t rolling. */
double td_sim_friction_force(const td_sim *s, int k, const double *y);
/* Rolling constraint of retainer k (d v_s / dv as a row over the node, race and race speed) and
 * its velocity term h = (d v_s / dq) v, so that d v_s / dt = row v' + h (the speed held). */
void td_sim_roll_row(const td_sim *s, int k, const double *y, td_contact_row *row, double *h);
/* Column of F_t in the v rows (length n): t on the node, -t on the race, -R_b on the race speed. */
void td_sim_roll_column(const td_sim *s, int k, const double *y, double *col);

/* Contact row of retainer k at the state y (J_k = (x, y)/c on its node, minus that on its race). */
void td_sim_contact_row(const td_sim *s, int k, const double *y, td_contact_row *row);
/* Column B_k = J_k^T + s mu t_k (normal force plus its friction) of retainer k, length n, with the
 * race's opposite share and the friction torque -R_b s mu on its speed. */
void td_sim_contact_column(const td_sim *s, int k, const double *y, double *col);
/* Project retainer k's node radially onto its clearance circle around the race centre. */
void td_sim_project_onto_circle(const td_sim *s, int k, double *y);
/* Constant part of the drag torque of retainer k's race at state y, N m, braking: drag_torque
 * sgn(Omega_b), regularised over the slip band as friction is (|Omega_b| R_b < v_reg, contact.h);
 * *dT = dT / d Omega_b (may be NULL). The viscous part is a damper on the race speed (race.c). */
double td_sim_race_drag(const td_sim *s, int k, const double *y, double *dT);

/* Set retainer k's slip mode (and band_from) from its sliding velocity at y, entering contact; a
 * stick retainer with no slip to speak of tries rolling (s->contacts.roll_tried). */
void td_sim_init_slip(td_sim *s, int k, const double *y);
/* Retainer k's slip root fired (|v_s| reached v_reg): into the band, or out of it with the slip
 * mode of the state. Returns 1 if it left the band on the other side (a friction reversal).
 * Not for stick retainers (sim_modes.c switches them between sliding and rolling). */
int td_sim_slip_root(td_sim *s, int k, const double *y);
/* Rolling retainer k: v_s = 0 at y (restarts remove the root location's residual slip): the race
 * speed adjusted, or for a fixed bore the node's tangential velocity. */
void td_sim_project_rolling(const td_sim *s, int k, double *y);
/* Retainer k stops rolling: sliding in direction `slip`, F_t = 0. */
void td_sim_unroll(td_sim *s, int k, double *y, int slip);
/* Constraint model: retainer k leaves contact (free, disarmed until the gap opens, lambda = 0). */
void td_sim_release(td_sim *s, int k, double *y);
/* Penalty model: the mode retainer k's state y asks for; `in_band` inside the noise band. */
td_rmode td_sim_penalty_mode_wanted(const td_sim *s, int k, const double *y, td_rmode in_band);

#endif
