/*
 * touchdown/model.h - a plain description of a rotor/AMB machine: no matrices, no solver.
 *
 * A td_model is built part by part, either in code (embedding) or by the case-file reader
 * (touchdown/case.h). Every td_model_add_* call copies its argument and validates it; node
 * numbers are checked against the shaft once the model is complete (td_model_validate).
 * Units and DOF conventions: touchdown/dofs.h.
 */
#ifndef TOUCHDOWN_MODEL_H
#define TOUCHDOWN_MODEL_H

#include "touchdown/assess.h"
#include "touchdown/controller.h"
#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/housing.h"
#include "touchdown/options.h"
#include "touchdown/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct td_model td_model;

/** Beam theory of the shaft elements. */
typedef enum td_beam_theory {
    TD_BEAM_EULER_BERNOULLI = 0, /**< shear deformation neglected (the reference rig) */
    TD_BEAM_TIMOSHENKO = 1       /**< shear deformation included */
} td_beam_theory;

/** Mass matrix form of the shaft elements. */
typedef enum td_mass_form {
    TD_MASS_CONSISTENT = 0, /**< consistent mass with rotary inertia (the reference rig) */
    TD_MASS_LUMPED = 1      /**< half the element's mass and rotary inertia at each end (the paper) */
} td_mass_form;

/** Isotropic linear-elastic material. */
typedef struct td_material {
    double E;       /**< Young's modulus, Pa */
    double G;       /**< shear modulus, Pa */
    double density; /**< kg/m^3 */
} td_material;

/** One shaft element; element i joins node i and node i + 1. */
typedef struct td_shaft_element {
    double length;         /**< m, > 0 */
    double outer_diameter; /**< m, > 0 */
    double inner_diameter; /**< m, 0 <= inner < outer (hollow shafts) */
    td_material material;
} td_shaft_element;

/** Options that apply to the whole shaft. */
/** Shear coefficient kappa of the Timoshenko elements' hollow circular sections. */
typedef enum td_shear_form {
    TD_SHEAR_HUTCHINSON = 0, /**< Hutchinson (2001), J. Appl. Mech. 68: the default */
    TD_SHEAR_COWPER = 1,     /**< Cowper (1966), J. Appl. Mech. 33, as in Friswell et al. (2010) and ROSS */
    TD_SHEAR_GIVEN = 2       /**< shear_value for every element */
} td_shear_form;

typedef struct td_shaft_options {
    td_beam_theory beam;
    td_mass_form mass;
    double rayleigh_alpha; /**< C += alpha M_shaft, 1/s */
    double rayleigh_beta;  /**< C += beta K_shaft, s */
    td_shear_form shear;   /**< Timoshenko shear coefficient (all zero: Hutchinson) */
    double shear_value;    /**< kappa for TD_SHEAR_GIVEN, in (0, 1]; 0 otherwise */
} td_shaft_options;

/**
 * Rayleigh damping coefficients from a damping ratio `ratio` (0 <= ratio < 1) given at one or two
 * frequencies (Hz, > 0, increasing): with w = 2 pi f, two frequencies give the fit
 * alpha = 2 zeta w1 w2 / (w1 + w2), beta = 2 zeta / (w1 + w2); one gives stiffness-proportional
 * damping alpha = 0, beta = 2 zeta / w1. The modal damping ratio is then
 * zeta(w) = alpha / (2 w) + beta w / 2: exactly `ratio` at the given frequencies, more above the
 * highest (and, with two, below the lowest), less between them. A fault names site part "damping",
 * field "ratio" or "frequencies.[i]".
 */
TD_API td_status td_rayleigh_from_ratio(double ratio, const double *frequencies, int count, double *alpha, double *beta,
                                        td_error *err);

/** A rigid disc (or, with Ip = Id = 0, a point mass) attached to a node. */
typedef struct td_disc {
    int node;
    double mass; /**< kg, > 0 */
    double Ip;   /**< polar moment of inertia, kg m^2, >= 0 */
    double Id;   /**< diametral moment of inertia, kg m^2, >= 0 */
} td_disc;

/**
 * A rigid disc by its geometry: a uniform circular cylinder of outer radius R, axial thickness t
 * and an optional central bore of radius r (the shaft through the bore is modelled separately).
 * Give either the thickness or the mass and leave the other 0: a disc of given mass has the
 * thickness t = m / (rho pi (R^2 - r^2)).
 */
typedef struct td_disc_geometry {
    int node;
    double outer_radius; /**< R, m, > 0 */
    double inner_radius; /**< r, m, 0 <= r < R (0: solid) */
    double density;      /**< rho, kg/m^3, > 0 */
    double thickness;    /**< t, m: > 0, or 0 when `mass` is given */
    double mass;         /**< m, kg: > 0 when `thickness` is 0, else 0 */
} td_disc_geometry;

/**
 * An active magnetic bearing, each lateral axis controlled on its own (docs/reference-rig.md,
 * docs/theory.md "AMB control"):
 *   force on the rotor        F  = ks x + Fc                      (x at `node`)
 *   current-controlled force  tau dFc/dt = -Fc - ki (kp xs + kd dxs/dt + kint e)   (xs at `sensor_node`)
 *   integral of the sensor    de/dt = xs                           (only when kint > 0: PID)
 * ks > 0 is the negative-stiffness term of the magnet. With saturation on, F is clipped to
 * +-force_capacity and the integrator stops while the clip holds and xs would drive it deeper
 * (anti-windup by clamping); while the AMB is off (or driven externally) the integrator holds its
 * value, so a restored AMB resumes with the bias it had. With slew_rate > 0 the amplifier's rate is
 * clipped: dFc/dt = clip(r, +-ki slew_rate), r the lag's rate above, and the integrator also stops
 * while the clip holds and xs would drive r deeper into it.
 */
typedef struct td_amb {
    int node;              /**< actuator node */
    int sensor_node;       /**< sensor node (collocated: equal to node) */
    double ks;             /**< negative-stiffness coefficient, N/m */
    double ki;             /**< force/current gain, N/A */
    double kp;             /**< proportional gain, A/m */
    double kd;             /**< derivative gain, A s/m */
    double tau;            /**< force lag time constant, s (1/(2 pi bandwidth)); 0: no lag */
    double force_capacity; /**< N, > 0 */
    int saturation;        /**< nonzero: clip the total axis force at +-force_capacity */
    double air_gap;        /**< radial air gap, m (0: unknown); a retainer must be tighter */
    double kint;           /**< integral gain, A/(m s), >= 0 (0: PD, no integrator state); last, so that
                            *   positional initialisers written for 0.3 keep their meaning */
    double slew_rate;      /**< the amplifier's slew-rate limit, A/s, >= 0 (0: none): |dFc/dt| <= ki slew_rate;
                            *   needs tau > 0 (the current is then a state). Last, as kint */
} td_amb;

/** A plain linear bearing (spring and damper per axis) for non-AMB supports. */
typedef struct td_bearing {
    int node;
    double kxx, kyy; /**< N/m */
    double cxx, cyy; /**< N s/m */
} td_bearing;

/**
 * The inner race of a retainer ball bearing as a body (docs/theory.md, "Retainer bearings as bodies").
 * All zero is the paper's retainer: a rigid bore fixed in the housing, turning at bore_speed.
 *  - inertia > 0: the race speed Omega_b is a state, starting at bore_speed, driven by the friction
 *    torque R_b mu N phi(v_s) at the contact and braked by the bearing's drag
 *    T = drag_torque sgn(Omega_b) + drag_viscous Omega_b;
 *  - mount_stiffness > 0: the race centre moves on an isotropic mount (stiffness, damping) to the
 *    housing, with the race mass (> 0) in translation.
 */
typedef struct td_race {
    double inertia;         /**< polar moment of inertia J of the rotating parts, kg m^2, >= 0 */
    double drag_torque;     /**< constant drag torque, N m, >= 0 (needs inertia > 0) */
    double drag_viscous;    /**< viscous drag, N m s/rad, >= 0 (needs inertia > 0) */
    double mass;            /**< mass moving on the mount, kg: > 0 with a mount, 0 without */
    double mount_stiffness; /**< radial stiffness of the mount, N/m, >= 0 (0: rigid mount) */
    double mount_damping;   /**< radial damping of the mount, N s/m, >= 0 (needs a mount) */
} td_race;

/**
 * A retainer's own compliant contact law between shaft and race (eq. 4 and its generalisations,
 * touchdown/options.h). stiffness 0: the run's contact model (td_contact_options) applies.
 */
typedef struct td_retainer_contact {
    double stiffness;           /**< Kc, N/m^exponent, >= 0 (0: the run's contact model) */
    double exponent;            /**< p >= 1: 1 linear, 1.5 Hertzian (0 is taken as 1) */
    td_contact_damping damping; /**< damping law (touchdown/options.h) */
    double damping_coefficient; /**< s/m (Hunt-Crossley) or N s/m (Kelvin-Voigt), >= 0 */
} td_retainer_contact;

/** A retainer (backup, touchdown) bearing around the shaft at a node. */
typedef struct td_retainer {
    int node;
    double clearance;            /**< radial clearance c = bore_radius - shaft_radius, m, > 0 */
    double shaft_radius;         /**< R_s, m */
    double bore_radius;          /**< R_b, m */
    double friction;             /**< Coulomb coefficient mu, >= 0 */
    double bore_speed;           /**< Omega_b, rotation speed of the bore (rolling-element race), rad/s:
                                  *   fixed, or the start value of a race with inertia */
    double restitution;          /**< e in [0, 1]: radial velocity after impact = -e times before */
    int stick;                   /**< nonzero: Coulomb friction with sticking: rolling without slip
                                  *   (v_s = 0) is a state, held while the friction force it needs stays
                                  *   within mu N; 0: the paper's sliding law (eq. 17), slip band */
    td_race race;                /**< the race as a body (all zero: fixed rigid bore, the paper's model) */
    td_retainer_contact contact; /**< its own compliant contact law (all zero: the run's) */
} td_retainer;

/** 1 if retainer r has states of its own: a spinning race (inertia > 0) or a mount. */
TD_API int td_retainer_has_race(const td_retainer *r);

/** An unbalance: F_x = U Omega^2 cos(Omega t + phase), F_y = U Omega^2 sin(Omega t + phase). */
typedef struct td_unbalance {
    int node;
    double magnitude; /**< U, kg m, >= 0 */
    double phase;     /**< rad */
} td_unbalance;

/** What a timed change does. */
typedef enum td_change_kind {
    TD_CHANGE_UNBALANCE = 0, /**< set unbalance `index` to magnitude/phase */
    TD_CHANGE_AMB_OFF = 1,   /**< AMB `index` fails: its forces drop to zero */
    TD_CHANGE_AMB_ON = 2     /**< AMB `index` is restored */
} td_change_kind;

/** A timed change of the machine during a run. */
typedef struct td_change {
    double time; /**< s */
    td_change_kind kind;
    int index;        /**< unbalance or AMB index, in order of addition */
    double magnitude; /**< TD_CHANGE_UNBALANCE: new U, kg m */
    double phase;     /**< TD_CHANGE_UNBALANCE: new phase, rad */
} td_change;

/**
 * A point of a prescribed speed ramp (docs/theory.md, "Speed transients"): the rotor speed is
 * `speed` at `time`, linear between points, the model's speed before the first point and the last
 * point's speed after it.
 */
typedef struct td_speed_point {
    double time;  /**< s, >= 0, increasing from point to point */
    double speed; /**< rad/s, >= 0 */
} td_speed_point;

/**
 * The rotor's spin as a degree of freedom (docs/theory.md, "Speed transients"). free = 0: the speed
 * is prescribed (constant, or a ramp of td_speed_point). free != 0: the speed is a state starting at
 * the model's speed, J dOmega/dt = drive_torque - drag_torque sgn(Omega) - drag_viscous Omega minus
 * the friction torques R_s F_t of the retainers.
 */
typedef struct td_spin {
    int free;            /**< nonzero: the speed is free (a coast-down, a drop) */
    double inertia;      /**< J, kg m^2, >= 0 (0: the rotor's polar inertia, td_model_polar_inertia) */
    double drive_torque; /**< N m along the spin (a motor; 0 once it has tripped) */
    double drag_torque;  /**< N m >= 0, opposing the spin (seals, windage, motor losses) */
    double drag_viscous; /**< N m s/rad >= 0 */
} td_spin;

/** Create an empty model (speed 0, gravity off, Euler-Bernoulli, consistent mass). */
TD_API td_status td_model_create(td_model **out, td_error *err);
/** Free a model and set *model to NULL. Accepts NULL and *model == NULL. */
TD_API void td_model_free(td_model **model);
/** Deep copy. */
TD_API td_status td_model_clone(const td_model *model, td_model **out, td_error *err);
/**
 * A copy of `model` with every shaft element split into `factor` equal elements (factor >= 1), for
 * mesh-convergence checks. Node i becomes node factor * i, so every part (discs, point masses,
 * AMBs and their sensors, bearings, retainers, unbalances) keeps its axial position; schedule,
 * speed, gravity and shaft options are copied unchanged.
 */
TD_API td_status td_model_refine(const td_model *model, int factor, td_model **out, td_error *err);

TD_API td_status td_model_set_shaft_options(td_model *m, const td_shaft_options *opt, td_error *err);
TD_API td_status td_model_add_shaft_element(td_model *m, const td_shaft_element *el, td_error *err);
TD_API td_status td_model_add_disc(td_model *m, const td_disc *disc, td_error *err);
/**
 * The disc (node, mass, Ip, Id) of a uniform cylinder given by its geometry:
 *   m = rho pi (R^2 - r^2) t,  Ip = m (R^2 + r^2) / 2,  Id = m (3 (R^2 + r^2) + t^2) / 12,
 * Id about a diameter through the centre of mass. TD_ERR_INVALID for a value out of range or
 * when both or neither of thickness and mass are given.
 */
TD_API td_status td_disc_from_geometry(const td_disc_geometry *g, td_disc *out, td_error *err);
/** A point mass: a disc without rotary inertia. */
TD_API td_status td_model_add_point_mass(td_model *m, int node, double mass, td_error *err);
TD_API td_status td_model_add_amb(td_model *m, const td_amb *amb, td_error *err);
TD_API td_status td_model_add_bearing(td_model *m, const td_bearing *b, td_error *err);
TD_API td_status td_model_add_retainer(td_model *m, const td_retainer *r, td_error *err);
TD_API td_status td_model_add_unbalance(td_model *m, const td_unbalance *u, td_error *err);
TD_API td_status td_model_add_change(td_model *m, const td_change *c, td_error *err);
/**
 * A linear controller (touchdown/controller.h) driving AMB axes. An AMB axis is numbered
 * 2 * amb + axis (axis 0: x, 1: y), as the system numbers them. Input j of the controller reads the
 * sensor of axis inputs[j] (its error e = -xs), output j is the current command of axis
 * outputs[j]'s amplifier (force ki i, lagged by the AMB's tau, clipped as the AMB says). An axis is
 * driven by at most one controller, and the AMB of a driven axis has kp = kd = kint = 0: its td_amb
 * keeps the magnet (ks, ki) and the amplifier (tau, force_capacity, saturation), the controller
 * replaces the shorthand law. A controller reads its sensors and runs while its AMB is off; the
 * AMB then exerts no force. A sampled controller's rate is within TD_CONTROLLER_RATE_MIN ..
 * TD_CONTROLLER_RATE_MAX. The model keeps copies of k and of the lists. name (may be NULL, at
 * most 63 characters) names it in messages and events. A fault names site part "controller".
 */
/** The sample rates a model's sampled controller may have, Hz: an AMB's DSP runs at a few kHz to a
 *  few tens of kHz; the simulation takes each sample at t0 + k / rate to 1e-14 (1 + |t|) s, so the
 *  period must stay far above that, and below 1 Hz a sampled law is no AMB controller. */
#define TD_CONTROLLER_RATE_MIN 1.0
#define TD_CONTROLLER_RATE_MAX 1.0e7
TD_API td_status td_model_add_controller(td_model *m, const char *name, const td_controller *k, const int *inputs,
                                         const int *outputs, td_error *err);
/**
 * A plug-in controller (touchdown/plugin.h): the user's own code driving AMB axes, sampled at
 * sample_rate. It is one of the model's controllers (td_model_controller_count counts it, in the
 * order of addition; a recovery pair may name it) under the axis rules of td_model_add_controller,
 * but no linear system: td_model_get_controller returns NULL for it and td_model_get_plugin its
 * spec, and the analyses that need a linear law (touchdown/modal.h, an orbit start) refuse a model
 * with one, naming it. Either `functions` is a program's own table, or `library` (functions NULL)
 * the path of a shared library exporting TD_PLUGIN_ENTRY_NAME, opened here: a file that cannot be
 * opened, a missing symbol or an abi_version other than TD_PLUGIN_ABI_VERSION is TD_ERR_INVALID
 * naming the library. The model keeps copies of every string and list. A fault names site part
 * "controller".
 */
typedef struct td_plugin_spec {
    const char *name;                      /**< as td_model_add_controller's (may be NULL) */
    const td_plugin_controller *functions; /**< a program's table, or NULL: load `library` */
    const char *library;                   /**< shared library path (when functions is NULL; a name without '/'
                                            *   is the file in the current directory, not a library search) */
    double sample_rate;                    /**< Hz, TD_CONTROLLER_RATE_MIN .. TD_CONTROLLER_RATE_MAX */
    int delay;                             /**< whole samples of computation delay on every output, >= 0 */
    int n_inputs;                          /**< sensors read, >= 1 */
    const int *inputs;                     /**< n_inputs AMB axes (2 amb + axis) */
    int n_outputs;                         /**< amplifiers commanded, >= 1 */
    const int *outputs;                    /**< n_outputs AMB axes */
    int n_parameters;                      /**< >= 0 */
    const char *const *parameter_names;    /**< n_parameters names */
    const double *parameter_values;        /**< n_parameters values */
} td_plugin_spec;
TD_API td_status td_model_add_plugin_controller(td_model *m, const td_plugin_spec *spec, td_error *err);
/** Controller i's plug-in spec (borrowed, valid while the model lives unchanged; `functions` is
 *  then always set, from the library when it named one), or NULL for a linear controller or an i
 *  out of range. */
TD_API const td_plugin_spec *td_model_get_plugin(const td_model *m, int i);
/** The setup (touchdown/plugin.h) a simulation gives a new instance of the plug-in `spec`: its
 *  name ("" for none), rate, axes and parameters, borrowed from spec. For a program that creates
 *  an instance itself, as the tool's probe of a plug-in does. */
TD_API void td_plugin_spec_setup(const td_plugin_spec *spec, td_plugin_setup *setup);
/** The most controller pairs one recovery supervisor switches (td_recovery). */
#define TD_RECOVERY_MAX_PAIRS 16

/** A rule of the recovery supervisor on the sensed radius (td_recovery). */
typedef struct td_recovery_rule {
    double radius_fraction; /**< f > 0: the sensed radius against f c, c the smallest retainer clearance */
    double dwell;           /**< s >= 0: how long the condition must hold, counted in samples of the pair */
} td_recovery_rule;

/**
 * The contact-aware recovery supervisor (docs/theory.md, "Recovery supervisor"): pair i switches the
 * AMB axes of controller nominal[i] over to controller controller[i] when the rotor stays near its
 * retainers, and back when it has left them. Evaluated at each sample of the pair, with the sensed
 * radius r_k = the largest over the AMBs the pair drives of hypot(xs_x, xs_y) at the AMB's sensor:
 *   detect  (on nominal):  r > detect.radius_fraction c  at every sample for at least detect.dwell
 *   release (on recovery): r < release.radius_fraction c at every sample for at least release.dwell
 * (a dwell of d s is ceil(d rate) samples after the first that meets the condition). A switch at t_s
 * starts the incoming law from rest and blends the held current linearly over `blend` s,
 * i = (1 - b) i_old + b i_new, b = min(1, (t_k - t_s) / blend) (blend 0: a step), both laws running
 * while they weigh; no switch is taken while one blends. Model rules (td_model_validate): both
 * controllers of a pair exist, are sampled at the same rate and have the same inputs and outputs
 * (continuous supervised laws are not supported yet); no controller is in two pairs; the model has a
 * retainer; 0 < release.radius_fraction < detect.radius_fraction (hysteresis). The pairs' recovery
 * controllers share their nominal's axes and stand by (they drive nothing until a switch); the
 * analyses (touchdown/modal.h) are of the nominal laws. pair_count 0: no supervisor (the default).
 * A fault names site part "recovery", field "nominal", "controller", "detect.radius_fraction",
 * "detect.dwell", "release.radius_fraction", "release.dwell" or "blend".
 */
typedef struct td_recovery {
    int enabled;                           /**< 0: the nominal laws throughout (the recovery laws never run) */
    int pair_count;                        /**< 0 .. TD_RECOVERY_MAX_PAIRS */
    int nominal[TD_RECOVERY_MAX_PAIRS];    /**< controller index (td_model_get_controller) of each nominal law */
    int controller[TD_RECOVERY_MAX_PAIRS]; /**< controller index of the recovery law it switches to */
    td_recovery_rule detect;               /**< nominal -> recovery */
    td_recovery_rule release;              /**< recovery -> nominal */
    double blend;                          /**< s >= 0: the linear blend of the held current */
} td_recovery;

/** Set (copy) the recovery supervisor; its values are checked here, its controllers at validation. */
TD_API td_status td_model_set_recovery(td_model *m, const td_recovery *r, td_error *err);
/** The recovery supervisor into *out (all zero when none); returns its pair count (0: none). */
TD_API int td_model_get_recovery(const td_model *m, td_recovery *out);
/** The samples beyond the first that a rule of `dwell` s holds for at `rate` Hz: ceil(dwell rate),
 *  a product within 1e-9 (relative) of an integer taken as that integer (0.02 s at 10 kHz: 200). */
TD_API double td_recovery_dwell_samples(double dwell, double rate);
/** Rotor speed Omega, rad/s (constant between changes). */
TD_API td_status td_model_set_speed(td_model *m, double omega, td_error *err);
/** Append a point of the speed ramp (time after the previous point's). */
TD_API td_status td_model_add_speed_point(td_model *m, const td_speed_point *p, td_error *err);
/** Set the spin (all zero: prescribed speed, the default). */
TD_API td_status td_model_set_spin(td_model *m, const td_spin *spin, td_error *err);
/** Gravity acceleration vector in the x-y plane, m/s^2 (e.g. 0, -9.81); both 0: off. */
TD_API td_status td_model_set_gravity(td_model *m, double gx, double gy, td_error *err);
/**
 * Ask for a Craig-Bampton reduction of the assembled rotor (docs/theory.md, "Reduced rotor"):
 * every node carrying a part keeps its four DOFs, the other nodes are replaced by the
 * fixed-interface modes below `cutoff` Hz. cutoff >= 0 and finite; 0 (the default): the full model.
 * A fault names site part "reduction", field "cutoff".
 */
TD_API td_status td_model_set_reduction(td_model *m, double cutoff, td_error *err);
/** The reduction cut-off frequency, Hz (0: the full model). */
TD_API double td_model_reduction(const td_model *m);

/**
 * Check cross-references (nodes in range, one AMB and one retainer per node, retainers tighter
 * than every AMB air gap, schedule indices). Like every td_model_add_* check, a failure names the
 * part, index and field at fault in err->site, and the part compared against in err->other
 * (touchdown/error.h); a model with no shaft element at all names no part.
 */
TD_API td_status td_model_validate(const td_model *m, td_error *err);

/* Read access. Getters return counts; td_model_get_* copy item i into *out (TD_ERR_INVALID if out of range). */
TD_API int td_model_node_count(const td_model *m);
TD_API int td_model_dof_count(const td_model *m);
TD_API int td_model_shaft_element_count(const td_model *m);
TD_API int td_model_disc_count(const td_model *m);
TD_API int td_model_amb_count(const td_model *m);
TD_API int td_model_bearing_count(const td_model *m);
TD_API int td_model_retainer_count(const td_model *m);
TD_API int td_model_unbalance_count(const td_model *m);
TD_API int td_model_change_count(const td_model *m);
TD_API int td_model_controller_count(const td_model *m);
/** The order of addition (from 0) of change i, i counted in time order as td_model_get_change
 *  counts it: the schedule entry as written, which events report (td_event.change); -1 when i is
 *  out of range. */
TD_API int td_model_change_entry(const td_model *m, int i);
TD_API double td_model_speed(const td_model *m);
TD_API int td_model_speed_point_count(const td_model *m);
TD_API td_status td_model_get_speed_point(const td_model *m, int i, td_speed_point *out);
TD_API void td_model_spin(const td_model *m, td_spin *out);
/** 1 if the speed changes by itself during a run: a ramp, or a free spin. */
TD_API int td_model_speed_varies(const td_model *m);
/**
 * The prescribed speed at time t (rad/s): the model's speed, or the ramp's; *rate receives
 * dOmega/dt and *angle the spin angle, the integral of Omega from time 0 (either may be NULL).
 */
TD_API double td_model_speed_at(const td_model *m, double t, double *rate, double *angle);
/** Polar moment of inertia of the rotor about its axis, kg m^2: shaft elements and discs. */
TD_API double td_model_polar_inertia(const td_model *m);
TD_API void td_model_gravity(const td_model *m, double *gx, double *gy);
TD_API void td_model_shaft_options(const td_model *m, td_shaft_options *out);
/** Axial position of a node, m (node 0 at z = 0). */
TD_API double td_model_node_position(const td_model *m, int node);
/** Total rotor mass, kg: shaft, discs and point masses. */
TD_API double td_model_total_mass(const td_model *m);
/** Axial position of the rotor's mass centre, m (node 0 at z = 0): shaft elements (each a uniform
 *  cylinder, its mass at its middle), discs and point masses; 0 for a model without mass. */
TD_API double td_model_mass_centre(const td_model *m);
TD_API td_status td_model_get_shaft_element(const td_model *m, int i, td_shaft_element *out);
TD_API td_status td_model_get_disc(const td_model *m, int i, td_disc *out);
TD_API td_status td_model_get_amb(const td_model *m, int i, td_amb *out);
TD_API td_status td_model_get_bearing(const td_model *m, int i, td_bearing *out);
TD_API td_status td_model_get_retainer(const td_model *m, int i, td_retainer *out);
/** C_min: the smallest retainer clearance, m (the touchdown clearance of ISO 14839-2 and the
 *  close clearance of API 617's amplitude check); TD_UNDEFINED without a retainer. */
TD_API double td_model_min_retainer_clearance(const td_model *m);
TD_API td_status td_model_get_unbalance(const td_model *m, int i, td_unbalance *out);
TD_API td_status td_model_get_change(const td_model *m, int i, td_change *out);
/** Controller i as the model keeps it (NULL when i is out of range, and for a plug-in controller,
 *  td_model_get_plugin); *name, *inputs and *outputs (each may be NULL) receive the model's name
 *  (never NULL: "" when none) and axis lists, td_controller_inputs(k) and td_controller_outputs(k)
 *  long (a plug-in's: its spec's n_inputs and n_outputs). Valid while the model lives unchanged. */
TD_API const td_controller *td_model_get_controller(const td_model *m, int i, const char **name, const int **inputs,
                                                    const int **outputs);

/* the bearing's duty: the touchdown bearing and the limits a run is assessed against */

/**
 * A retainer's rolling bearing as the assessment sees it (docs/theory.md, "The bearing's duty"):
 * its ratings, and the geometry of its balls for the Hertz contact stress. It changes nothing in
 * the run. 0 in a field means "not given" (the quantity that needs it is TD_UNDEFINED), except
 * life_exponent and groove_conformity, whose 0 is their default (3 and 0.52), filled in by
 * td_model_set_retainer_bearing. The ball geometry is all three of balls, ball_diameter and
 * pitch_diameter, or none; its inner raceway (pitch_diameter - ball_diameter) must lie outside
 * the bore (2 bore_radius). A fault names site part "retainer", field "bearing.KEY".
 */
typedef struct td_retainer_bearing {
    double static_rating;     /**< C0, N (ISO 76), >= 0 */
    double dynamic_rating;    /**< C, N (ISO 281), >= 0 */
    double life_exponent;     /**< p: 3 ball bearings, 10/3 roller bearings (ISO 281); 0: 3; else in [1, 10] */
    int balls;                /**< Z, >= 3 (0: no geometry) */
    double ball_diameter;     /**< D, m, > 0 with balls */
    double pitch_diameter;    /**< d_m, m, > ball_diameter with balls */
    double groove_conformity; /**< f_i = inner raceway groove radius / D, in (0.5, 1); 0: 0.52 */
    double width;             /**< race width b, m, >= 0: PV = N / (2 R_s b) |v_s| */
} td_retainer_bearing;

/** Set (copy) retainer k's bearing (k an added retainer); checked here. */
TD_API td_status td_model_set_retainer_bearing(td_model *m, int k, const td_retainer_bearing *b, td_error *err);
/** Retainer k's bearing into *out (all zero but the defaults when none was set); TD_ERR_INVALID
 *  when k is out of range. */
TD_API td_status td_model_get_retainer_bearing(const td_model *m, int k, td_retainer_bearing *out);

/**
 * The limits a run is assessed against (the case's top-level `limits`). Not set: the zones of
 * td_zone_limits_default and no temperature or drop limit (TD_UNDEFINED). A fault names site part
 * "limits", field "zones", "temperature_rise" or "drops".
 */
typedef struct td_limits {
    td_zone_limits zones;    /**< ISO 14839-2 boundaries, fractions of C_min, 0 < ab < bc < cd */
    double temperature_rise; /**< K allowed race temperature rise, > 0 (TD_UNDEFINED: none) */
    double drops;            /**< drops the touchdown bearing must survive, > 0 (TD_UNDEFINED: none) */
    int zone; /**< the largest acceptable ISO 14839-2 zone, TD_ZONE_A..TD_ZONE_D (default TD_ZONE_ACCEPTABLE) */
} td_limits;

/** Set (copy) the limits, checked here. */
TD_API td_status td_model_set_limits(td_model *m, const td_limits *l, td_error *err);
/** The limits into *out (the defaults above when none were set). */
TD_API void td_model_get_limits(const td_model *m, td_limits *out);
/* heat */
/**
 * A retainer's lumped thermal network (docs/theory.md, "Thermal retainers"): the race node (capacity
 * C_r) joined to the housing node (C_h) by G_rh, the housing to the ambient (temperature rise 0) by
 * G_ha, the race heated by the retainer's friction power F_t v_s and its race's drag power. The
 * temperatures are rises above the ambient, K. The race bore's radial thermal growth alpha R_b dT_r
 * is an output only: it does not change the clearance.
 */
typedef struct td_retainer_thermal {
    double race_capacity;               /**< C_r, J/K, > 0 */
    double housing_capacity;            /**< C_h, J/K, > 0 */
    double race_housing_conductance;    /**< G_rh, W/K, > 0 */
    double housing_ambient_conductance; /**< G_ha, W/K, >= 0 (0: an insulated housing, no steady state) */
    double expansion;                   /**< alpha, 1/K, >= 0 (TD_UNDEFINED: not given, no growth reported) */
} td_retainer_thermal;

/** Give retainer i (already added) a thermal network, replacing any it had. Errors: TD_ERR_INVALID
 *  (NULL model or t, i out of range, a value out of its range: the field named), TD_ERR_NOMEM. */
TD_API td_status td_model_set_retainer_thermal(td_model *m, int i, const td_retainer_thermal *t, td_error *err);
/** 1 if retainer i has a thermal network (*out filled, out may be NULL), else 0 (*out zeroed). */
TD_API int td_model_get_retainer_thermal(const td_model *m, int i, td_retainer_thermal *out);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_MODEL_H */
