/*
 * touchdown/modal.h - eigen-analysis of the contact-free rotor/AMB system: modes, Campbell
 * diagram, critical speeds, steady-state unbalance response and the steady starting orbit.
 *
 * Every function here works on the first-order form of the linear, contact-free system at a
 * rotor speed Omega, with the state vector
 *
 *   z = [q (ndof); v = q' (ndof); w (n_controller_states)]
 *
 * where q follows touchdown/dofs.h and w holds the lagged AMB control forces Fc, N, one per AMB
 * axis with tau > 0, in the order of the system's AMB axis table (filter-state index), then the
 * integrators (kint > 0), then the states of each continuous linear controller (td_model_add_controller)
 * in turn. A sampled controller has no state here: td_modal_solve and td_modal_stability analyse its
 * loop over one sample, exactly at the samples (the plant held by zero-order hold), its states
 * appended to z and each eigenvalue mu reported as s = ln(mu) sample_rate; the other analyses refuse
 * it (TD_ERR_INVALID). AMB axes
 * with tau == 0 enter as their exact spring-damper. Saturation is ignored (linear analysis);
 * contact is absent. The state dimension is td_modal_state_count(sys).
 *
 * Eigenvalues s = sigma + i omega_d. A complex pair is reported once, as a td_mode with
 * omega_d > 0; real eigenvalues (overdamped modes, filter lags) are reported apart.
 * Damping ratio zeta = -sigma / |s|.
 *
 * Whirl: a mode's motion at node i is x = Re(X_i e^{st}), y = Re(Y_i e^{st}). Its orbit turns
 * with the spin (forward, x towards y) where h_i = -2 Im(conj(X_i) Y_i) / (|X_i|^2 + |Y_i|^2) > 0.
 * The mode's whirl index is the amplitude-weighted mean of h_i over the nodes, in [-1, 1];
 * the mode is TD_WHIRL_FORWARD when every node with a visible amplitude whirls forward,
 * TD_WHIRL_BACKWARD when every one whirls backward, and TD_WHIRL_MIXED otherwise (e.g. planar
 * modes of a non-spinning isotropic rotor, where forward and backward are degenerate).
 *
 * GSL: these functions call gsl_set_error_handler_off() (the library's one side effect on GSL)
 * and check every GSL return code. Ownership: the system is borrowed for the duration of the
 * call only; result handles own their data and are freed with their _free function.
 */
#ifndef TOUCHDOWN_MODAL_H
#define TOUCHDOWN_MODAL_H

#include "touchdown/error.h"
#include "touchdown/export.h"
#include "touchdown/model.h"
#include "touchdown/options.h"
#include "touchdown/system.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Whirl direction of a mode (see the header comment). */
typedef enum td_whirl {
    TD_WHIRL_BACKWARD = -1, /**< against the spin */
    TD_WHIRL_MIXED = 0,     /**< some nodes forward, some backward (or planar) */
    TD_WHIRL_FORWARD = 1    /**< with the spin */
} td_whirl;

/** The whirl's name, as every output and the tool write it: "forward", "backward" or "mixed";
 *  NULL for a value that is none of the three. The string is static. */
TD_API const char *td_whirl_name(td_whirl w);

/** One oscillatory mode (the omega_d > 0 member of a complex pair). */
typedef struct td_mode {
    double sigma;       /**< real part of the eigenvalue, 1/s (negative: decaying) */
    double omega_d;     /**< damped natural frequency, rad/s, > 0 */
    double freq_hz;     /**< omega_d / (2 pi), Hz */
    double omega_n;     /**< |s|, rad/s */
    double zeta;        /**< damping ratio -sigma/|s| */
    double whirl_index; /**< amplitude-weighted whirl sense in [-1, 1] (+1: forward circular) */
    td_whirl whirl;
} td_mode;

/**
 * Complex pairs at least this damped are not vibration modes: on an AMB rotor they are the force
 * lags of the two axes of a bearing, split into a pair by gyroscopic coupling (zeta ~ 1,
 * omega_d ~ 0.1-1 rad/s). The Campbell diagram, the critical speeds and the tool's mode tables
 * leave them out; td_modal_get_mode still reports them.
 */
#define TD_MODAL_OVERDAMPED_ZETA 0.99

/** 1 if `m` is a vibration mode (zeta < TD_MODAL_OVERDAMPED_ZETA), 0 for an overdamped pair. */
TD_API int td_mode_is_vibration(const td_mode *m);

/* ---------------------------------------------------------------------------------------- */
/* State-space form                                                                          */

/** Number of first-order states: 2 ndof + number of AMB axes with tau > 0. */
TD_API int td_modal_state_count(const td_system *sys);

/**
 * Dense first-order system matrix A at speed `omega` (z' = A z + b), column-major n x n with
 * n = td_modal_state_count(sys): entry (i, j) at A[i + j n]. Caller allocates n*n doubles.
 * Returns TD_ERR_NUMERIC if M is singular. A is left unspecified on failure.
 */
TD_API td_status td_modal_state_matrix(const td_system *sys, double omega, double *A, td_error *err);

/* ---------------------------------------------------------------------------------------- */
/* Modes at one speed                                                                        */

typedef struct td_modal td_modal;

/**
 * Eigen-analysis at speed `omega` (rad/s; the model's own speed is ignored). On success *out
 * holds every eigenvalue: oscillatory modes sorted by ascending omega_d (ties by sigma), real
 * eigenvalues sorted by descending value (least stable first), with mode shapes.
 * Caller frees with td_modal_free. On failure *out is NULL.
 */
TD_API td_status td_modal_solve(const td_system *sys, double omega, td_modal **out, td_error *err);
/** Free and set *m to NULL; accepts NULL. */
TD_API void td_modal_free(td_modal **m);
/** Speed of the analysis, rad/s. */
TD_API double td_modal_speed(const td_modal *m);
/** Number of oscillatory modes (complex pairs). */
TD_API int td_modal_mode_count(const td_modal *m);
/** Copy oscillatory mode i (0: lowest omega_d) into *out. TD_ERR_INVALID when out of range. */
TD_API td_status td_modal_get_mode(const td_modal *m, int i, td_mode *out);
/** Number of real eigenvalues. */
TD_API int td_modal_real_count(const td_modal *m);
/**
 * Zero roots (td_modal_solve): a motion that no bearing or AMB holds (a free rotor's translation
 * or tilt; the null space of the state matrix, found by its scaled singular values) has a zero root,
 * double when undamped, which the eigen-solver returns at rounding level (about sqrt(eps) times the
 * fastest mode's frequency, as a pair or two real roots). Up to two per such motion, the roots of
 * least |s| within TD_MODAL_ROUNDOFF_ROOT of the spectral radius, are no modes: they are neither
 * among the modes nor the real eigenvalues. td_modal_rounding_count says how many were left out
 * (0 for a rotor held in every direction: then nothing is, however small), td_modal_rounding_bound
 * the bound on their |s| (1/s).
 */
#define TD_MODAL_ROUNDOFF_ROOT 1e-6
TD_API int td_modal_rounding_count(const td_modal *m);
TD_API double td_modal_rounding_bound(const td_modal *m);
/** Real eigenvalue i, 1/s (0: largest, i.e. least stable). NAN when out of range. */
TD_API double td_modal_real_eigenvalue(const td_modal *m, int i);
/** Number of nodes of the mode shapes. */
TD_API int td_modal_node_count(const td_modal *m);
/**
 * Mode shape of oscillatory mode i at the nodes: complex X and Y displacement amplitudes
 * (real and imaginary parts, each array td_modal_node_count long; any pointer may be NULL).
 * Normalised so that the largest |X_k| or |Y_k| is 1 and that component is real and positive.
 */
TD_API td_status td_modal_mode_shape(const td_modal *m, int i, double *x_re, double *x_im, double *y_re, double *y_im);
/**
 * Largest real part over the eigenvalues the analysis holds, 1/s. For td_modal_solve (all of
 * them): < 0 means the contact-free system is stable. For td_modal_solve_lowest on a large
 * system it covers only the roots computed (td_modal_computed_count).
 */
TD_API double td_modal_max_real_part(const td_modal *m);
/** Largest |s| over all eigenvalues, 1/s (the spectral radius). */
TD_API double td_modal_spectral_radius(const td_modal *m);
/** Real parts within this fraction of the spectral radius (td_modal_rounding_scale) are round-off of
 *  zero (undamped modes of an undamped shaft come out at +-1e-12..1e-9 of it). */
#define TD_MODAL_ROUNDOFF_REAL_PART 1e-9
/** Real parts up to this fraction of the spectral radius are rounding of a marginal root, not
 *  growth: 10 sqrt(DBL_EPSILON) = 1.5e-7. For a sampled loop (td_modal_sample_rate > 0) the
 *  fraction is of the sample rate: its roots are s = ln(mu) rate with mu those of the loop over one
 *  sample, which round relative to |mu| ~ 1 (ln |mu| up to 1.5e-7 is marginal), whereas a root
 *  mu ~ 0 (a delay's) makes its spectral radius whatever the rounding of that mu's ln gives. The eigen-solver (the QR
 * algorithm) returns the exact roots of A + E with |E| about eps |A|: a simple root moves by O(eps |A|), but a
 * defective one of multiplicity 2 moves by O(sqrt(eps) |A|), the roots of a 2 x 2 Jordan block perturbed by e being
 * +-sqrt(e) (Golub & Van Loan, Matrix Computations, 4th ed., 7.2 and 7.5). A rotor without bearings (every AMB off,
 * free-free) has such roots at 0, its rigid-body motions x'' = 0: they come out at up to about sqrt(eps) times the
 * spectral radius (3e-9 of it on the rig without its AMBs), where the rounding of simple roots stays within
 *  TD_MODAL_ROUNDOFF_REAL_PART. The factor 10 covers the constant of |E|; a true growth rate this
 *  small (1.5e-7 of the fastest root, e-folding over millions of its periods) is no instability a
 *  run could show. */
#define TD_MODAL_MARGINAL_REAL_PART 1.4901161193847656e-07
/** Sample rate of the loop a sampled analysis holds (td_modal_solve of a system with sampled
 *  controllers: its eigenvalues are s = ln(mu) rate), Hz; 0 for a continuous one. */
TD_API double td_modal_sample_rate(const td_modal *m);
/** The scale, 1/s, that real parts round against (TD_MODAL_ROUNDOFF_REAL_PART and
 *  TD_MODAL_MARGINAL_REAL_PART are fractions of it): the spectral radius; for a sampled loop its
 *  sample rate (ln |mu| rounds against 1). */
TD_API double td_modal_rounding_scale(const td_modal *m);
/** 1 if some eigenvalue grows: max real part > TD_MODAL_MARGINAL_REAL_PART * td_modal_rounding_scale
 *  (the spectral radius; for a sampled loop the sample rate: ln |mu| beyond the rounding). */
TD_API int td_modal_is_unstable(const td_modal *m);
/**
 * Stability of the contact-free system at speed `omega` from its eigenvalues alone (no
 * eigenvectors: several times cheaper than td_modal_solve, still a dense O(states^3) solve).
 * *max_real_part: the largest real part, 1/s; *unstable: as td_modal_is_unstable would say for
 * td_modal_solve's result. Either pointer may be NULL. Errors: TD_ERR_NOMEM, TD_ERR_NUMERIC.
 */
TD_API td_status td_modal_stability(const td_system *sys, double omega, double *max_real_part, int *unstable,
                                    td_error *err);

/**
 * The lowest modes only: at least the `count` lowest-frequency vibration modes
 * (td_mode_is_vibration) at speed `omega`, for tables, Campbell diagrams and critical speeds of
 * large models. Systems of at most a few hundred states get the full dense td_modal_solve (the
 * same results). Larger ones are solved by shift-invert block subspace iteration on the sparse
 * first-order system (one KLU factorisation; the small projected problem on GSL), which costs
 * O(states) per iteration instead of O(states^3): the result
 * then holds every vibration mode with omega_d below td_modal_complete_below (sorted as in
 * td_modal_solve, shapes and whirl alike) and the real roots and overdamped pairs that were
 * computed on the way; roots further from 0 are absent. Fails with TD_ERR_INVALID when `count`
 * is so large that only a dense solve could give it and the system is too large for one.
 */
TD_API td_status td_modal_solve_lowest(const td_system *sys, double omega, int count, td_modal **out, td_error *err);
/** Damped frequency below which every vibration mode is listed, rad/s (INFINITY after a full solve). */
TD_API double td_modal_complete_below(const td_modal *m);
/** Number of eigenvalues the solver computed: the state count for a full solve, fewer for a partial one. */
TD_API int td_modal_computed_count(const td_modal *m);

/* ---------------------------------------------------------------------------------------- */
/* Campbell diagram                                                                          */

typedef struct td_campbell td_campbell;

/**
 * Case files may ask for at most this many speed_steps x mechanical DOFs: every grid speed costs an
 * eigen-solve for the Campbell diagram (more where its branch tracking halves the step) and one for
 * the critical speeds, unless td_campbell_critical_speeds reuses the diagram's (docs/performance.md).
 */
#define TD_MODAL_MAX_GRID_WORK 200000L

/**
 * Branch tracking: a step of td_campbell_compute whose weakest match has a MAC below this is halved;
 * a point whose td_campbell_mac is below it was not followed as one mode. 0.9 is the usual bound for
 * "the same mode" in modal correlation (Allemang, The Modal Assurance Criterion - Twenty Years of Use
 * and Abuse, Sound and Vibration 37(8), 2003); a forward and a backward circular whirl of one shape
 * have MAC 0.
 */
#define TD_CAMPBELL_MAC_REFINE 0.9
/** At most this many halvings of a grid step: the finest step is 1/1024 of the grid's. Where even that
 *  step matches with a low MAC (a mode that left the modes matched, degenerate modes), the match is
 *  taken as found, td_campbell_mac says so, and the rest of that grid step is taken in one: a grid
 *  step costs at most TD_CAMPBELL_MAX_HALVINGS + 2 eigen-solves, one where every match is good. */
#define TD_CAMPBELL_MAX_HALVINGS 10

/**
 * Oscillatory modes over opt->speed_steps speeds evenly spaced from opt->speed_min to
 * opt->speed_max (inclusive), the lowest opt->mode_count vibration modes at each speed, each point
 * labelled with its own whirl. Branches are tracked by mode shape: branch j starts as the j-th
 * lowest mode at speed_min and, from each speed to the next, every branch moves on to the mode whose
 * shape matches its own best, the Modal Assurance Criterion MAC = |a^H b|^2 / ((a^H a)(b^H b)) of the
 * complex nodal displacements (x and y at every node) matched by the optimal assignment (largest
 * total MAC, Hungarian algorithm) among the lowest 2 mode_count modes; where the weakest match of a
 * step has MAC < TD_CAMPBELL_MAC_REFINE the step is halved, down to 2^-TD_CAMPBELL_MAX_HALVINGS of the
 * grid step (a branch whose mode lies above td_modal_complete_below of a partial solve, where it may
 * be absent, asks for no halving). So a branch keeps its mode
 * (and whirl) where it crosses another; the points of a row are the same modes as sorting gives,
 * their columns permuted. A mode that leaves the lowest mode_count hands its branch to the one
 * entering (the lowest no branch followed in), with the low MAC of that link (td_campbell_mac).
 * A speed with fewer modes leaves its missing points with omega_d = NAN.
 * Caller frees with td_campbell_free.
 */
TD_API td_status td_campbell_compute(const td_system *sys, const td_modal_options *opt, td_campbell **out,
                                     td_error *err);
TD_API void td_campbell_free(td_campbell **c);
TD_API int td_campbell_speed_count(const td_campbell *c);
TD_API int td_campbell_branch_count(const td_campbell *c);
/** Speed number k, rad/s (NAN when out of range). */
TD_API double td_campbell_speed(const td_campbell *c, int k);
/** Branch j at speed number k. */
TD_API td_status td_campbell_get(const td_campbell *c, int k, int j, td_mode *out);
/** MAC of branch j at speed number k to its point at speed k - 1: the weakest match of the steps that
 *  carried it there (1: the same shape; near 0: another mode took the branch over). NAN at k = 0, at
 *  a missing point or one whose branch had no point before, and out of range. */
TD_API double td_campbell_mac(const td_campbell *c, int k, int j);

/* ---------------------------------------------------------------------------------------- */
/* Critical speeds                                                                           */

/** A speed where a whirl branch crosses the synchronous (1x) line omega_d = Omega. */
typedef struct td_critical_speed {
    double speed;   /**< rad/s, = omega_d of the mode there (to ~1e-12 relative) */
    double freq_hz; /**< speed / (2 pi) */
    double zeta;    /**< damping ratio of the crossing mode */
    double sigma;   /**< real part of its eigenvalue, 1/s */
    td_whirl whirl; /**< TD_WHIRL_FORWARD or TD_WHIRL_BACKWARD */
    int branch;     /**< index of the branch among the modes of that whirl (0: lowest) */
} td_critical_speed;

/**
 * Critical speeds in [opt->speed_min, opt->speed_max]: each forward branch (k-th lowest
 * forward-whirling mode) and, separately, each backward branch, bracketed on the Campbell grid
 * (opt->speed_steps speeds) and refined by bisection/secant (Illinois) on fresh eigen-solves
 * of omega_d(Omega) - Omega until the bracket is narrower than 1e-12 relative. Crossings
 * closer together than one grid step can be missed: refine the grid. Results are sorted by
 * speed; up to `capacity` go to `out` (may be NULL when capacity is 0) and *count receives
 * the number found (which may exceed capacity).
 */
TD_API td_status td_modal_critical_speeds(const td_system *sys, const td_modal_options *opt, td_critical_speed *out,
                                          int capacity, int *count, td_error *err);
/**
 * td_modal_critical_speeds(sys, opt, ...), its results bit for bit, reusing the eigen-solves of the
 * Campbell diagram c at the grid speeds (one per grid speed) where they are the ones the search makes: c computed by
 * td_campbell_compute on this sys, unchanged since, with the same speed_min, speed_max and speed_steps, and solved in
 * full (a system small enough for the dense solver, td_modal_solve_lowest). Otherwise (c NULL too) it solves as
 * td_modal_critical_speeds does.
 */
TD_API td_status td_campbell_critical_speeds(const td_campbell *c, const td_system *sys, const td_modal_options *opt,
                                             td_critical_speed *out, int capacity, int *count, td_error *err);

/* ---------------------------------------------------------------------------------------- */
/* Harmonic (steady-state) unbalance response                                                */

typedef struct td_harmonic td_harmonic;

/**
 * Steady-state response at speed `omega` to the unbalances u[0..n_u-1] (copied), each
 * F_x = U omega^2 cos(omega t + phase), F_y = U omega^2 sin(omega t + phase) at its node
 * (touchdown/model.h). The state is z(t) = Re(Z e^{i omega t}) with (i omega I - A) Z = F_z
 * (complex LU). n_u may be 0 (zero response). Fails with TD_ERR_NUMERIC when i omega is an
 * eigenvalue of A (undamped resonance). Caller frees with td_harmonic_free.
 */
TD_API td_status td_harmonic_compute(const td_system *sys, double omega, const td_unbalance *u, int n_u,
                                     td_harmonic **out, td_error *err);
TD_API void td_harmonic_free(td_harmonic **h);
TD_API double td_harmonic_speed(const td_harmonic *h);
TD_API int td_harmonic_node_count(const td_harmonic *h);
/** Number of entries of the complex state amplitude (td_modal_state_count of its system). */
TD_API int td_harmonic_state_count(const td_harmonic *h);
/** Complex amplitude of state i (layout of the header comment) into re, im (either may be NULL). */
TD_API td_status td_harmonic_state(const td_harmonic *h, int i, double *re, double *im);

/** Orbit of one node: x = Re(X e^{i omega t}), y = Re(Y e^{i omega t}). */
typedef struct td_orbit {
    double x_re, x_im;     /**< complex X, m */
    double y_re, y_im;     /**< complex Y, m */
    double x_amp, x_phase; /**< |X| m, arg X rad */
    double y_amp, y_phase; /**< |Y| m, arg Y rad */
    double forward;        /**< radius of the forward circular component |X + iY|/2, m */
    double backward;       /**< radius of the backward circular component |X - iY|/2, m */
    double major;          /**< major semi-axis forward + backward, m */
    double minor;          /**< minor semi-axis |forward - backward|, m */
} td_orbit;

/** Orbit of node `node`. */
TD_API td_status td_harmonic_orbit(const td_harmonic *h, int node, td_orbit *out);

/**
 * Steady starting state at time t for the simulation's TD_START_ORBIT:
 *
 *   z(t) = Re(Z e^{i omega t}) + z_s
 *
 * Z the harmonic response to the unbalances u[0..n_u-1] at speed omega (as td_harmonic_compute),
 * z_s the static deflection under the system's gravity load (A z_s = -[0; M^-1 f_g; 0], which has
 * v = 0 and the AMB filter states at their steady values) when `with_gravity` is nonzero, else 0.
 * z has td_modal_state_count(sys) entries in the layout [q (ndof), v (ndof), w (n_controller_states)]
 * (w = the lagged AMB forces Fc, by filter-state index). omega == 0 or n_u == 0 give the static
 * state only. On failure z is left unspecified.
 */
TD_API td_status td_modal_start_state(const td_system *sys, double omega, const td_unbalance *u, int n_u,
                                      int with_gravity, double t, double *z, td_error *err);

/* ---------------------------------------------------------------------------------------- */
/* Loop analysis: sensitivity, open loop and compliance (docs/theory.md, "Sensitivity")     */

typedef struct td_loop td_loop;

/** The frequency grid of td_loop_compute: `points` frequencies evenly spaced in log f from f_min
 *  to f_max (Hz, inclusive). */
typedef struct td_loop_options {
    double f_min; /**< Hz, > 0 */
    double f_max; /**< Hz, > f_min */
    int points;   /**< >= 2 */
} td_loop_options;

/** The largest first-order system (td_modal_state_count) td_loop_compute analyses: its dense
 *  eigen-solve and its O(states^2) per frequency and input grow past seconds beyond this (a
 *  reduction, docs/theory.md "Reduced rotor", brings a large model under it). */
#define TD_LOOP_MAX_STATES 240

/** Defaults: 0.5 Hz to 5 kHz, 800 points. */
TD_API void td_loop_options_default(td_loop_options *opt);

/** The ISO 14839-3:2006 zone ("Evaluation of stability margin") of a peak sensitivity (linear):
 *  'A' below 3, 'B' from 3 below 4, 'C' from 4 below 5, 'D' from 5; 0 for an undefined peak. */
TD_API char td_loop_zone(double peak);

/**
 * The linear loop analysis of the contact-free machine at speed `omega` (rad/s), as ISO 14839-3
 * measures it: a signal injected at one axis's controller output (amplifier input) with every
 * loop closed. The plant P(s) runs from the amplifier commands (current, A) of the controlled AMB
 * axes to their sensors' displacements (m): rotor, ks, ki and the amplifier lag tau. The
 * controller K(s) runs from the errors e = -xs to the currents: kp + kd s + kint / s for an axis
 * under the td_amb shorthand, the model's linear controller (td_model_add_controller) for an
 * axis it drives. Per controlled axis j:
 *
 *   S_j(jw) = [(I + K(jw) P(jw))^-1]_jj    (the input sensitivity's diagonal),
 *   L_j     = 1 / S_j - 1                   (the open loop seen at that point),
 *
 * the peak of |S_j| over the grid, refined by Brent's method between the grid neighbours, with its
 * frequency and zone (td_loop_zone); and per AMB axis the dynamic compliance, the displacement
 * per unit force at its actuator node with every loop closed (m/N). Stability: the largest real
 * part of the closed-loop eigenvalues (td_modal_solve). The loop is stable unless an eigenvalue
 * grows (td_modal_is_unstable: an undamped mode that no AMB sees, rounding-level real part, keeps
 * it stable); when not stable, S, its peaks and zones and the compliance are TD_UNDEFINED (0 for
 * a zone), and L is still given.
 *
 * With sampled controllers (td_loop_sample_rate > 0) the loop is the sampled-data one, at the
 * sample instants: its axes are the sampled laws' (every continuous law and shorthand stays closed
 * inside the plant), P is the plant's zero-order hold over one sample period T (held currents in,
 * sensor values at the samples out), and S_j = [(I + K(z) P_zoh(z))^-1]_jj at z = e^{jwT}, the
 * grid ending at the Nyquist frequency (rate / 2) if f_max is beyond it. The compliance is the
 * displacement at the sample instants per unit sinusoidal force. Stable iff every eigenvalue mu of
 * the loop over one sample has |mu| < 1 (ln |mu| at most TD_MODAL_MARGINAL_REAL_PART: the rounding
 * of a marginal root; td_modal_is_unstable's rule for a sampled loop). What happens between the
 * samples is not included (docs/theory.md).
 *
 * opt may be NULL (td_loop_options_default). Errors: TD_ERR_INVALID (NULL argument, bad options
 * or speed, no controlled axis, f_min not below a sampled loop's Nyquist frequency, sampled laws
 * at different rates, more than TD_LOOP_MAX_STATES states), TD_ERR_NUMERIC, TD_ERR_NOMEM. Caller
 * frees *out with td_loop_free; NULL on failure.
 */
TD_API td_status td_loop_compute(const td_system *sys, double omega, const td_loop_options *opt, td_loop **out,
                                 td_error *err);
/** Free and set *l to NULL; accepts NULL. */
TD_API void td_loop_free(td_loop **l);
/** Speed of the analysis, rad/s. */
TD_API double td_loop_speed(const td_loop *l);
/** The sampled loop's sample rate, Hz; 0 for a continuous loop (NAN for NULL). */
TD_API double td_loop_sample_rate(const td_loop *l);
/** 1 when the closed loop is stable (see td_loop_compute), else 0. */
TD_API int td_loop_stable(const td_loop *l);
/** Largest real part of the closed-loop eigenvalues, 1/s. */
TD_API double td_loop_max_real_part(const td_loop *l);
/** Number of controlled axes (the columns of the sensitivity), in AMB-axis order. */
TD_API int td_loop_axis_count(const td_loop *l);
/** The AMB axis (2 amb + (0: x, 1: y)) of controlled axis j; -1 out of range. */
TD_API int td_loop_axis(const td_loop *l, int j);
/** Number of AMB axes (the columns of the compliance): 2 per AMB. */
TD_API int td_loop_amb_axis_count(const td_loop *l);
/** Number of grid frequencies. */
TD_API int td_loop_frequency_count(const td_loop *l);
/** Grid frequency k, Hz (NAN out of range). */
TD_API double td_loop_frequency(const td_loop *l, int k);
/** S_j at grid frequency k into re, im (TD_UNDEFINED when unstable). TD_ERR_INVALID out of range. */
TD_API td_status td_loop_sensitivity(const td_loop *l, int j, int k, double *re, double *im);
/** L_j at grid frequency k. TD_ERR_INVALID out of range. */
TD_API td_status td_loop_open_loop(const td_loop *l, int j, int k, double *re, double *im);
/** Compliance of AMB axis a at grid frequency k, m/N (TD_UNDEFINED when unstable). */
TD_API td_status td_loop_compliance(const td_loop *l, int a, int k, double *re, double *im);
/** Peak of |S_j| (linear) and its frequency (Hz); TD_UNDEFINED when unstable or out of range. */
TD_API double td_loop_sensitivity_peak(const td_loop *l, int j);
TD_API double td_loop_sensitivity_peak_frequency(const td_loop *l, int j);
/** Zone of axis j's peak (td_loop_zone); 0 when unstable or out of range. */
TD_API char td_loop_sensitivity_zone(const td_loop *l, int j);
/** The worst zone over the axes; 0 when unstable. */
TD_API char td_loop_worst_zone(const td_loop *l);
/** S_j and L_j at any frequency f (Hz), computed afresh (the grid's values at grid frequencies);
 *  either pointer pair may be NULL. TD_ERR_INVALID for j or f out of range (f > 0, a sampled loop's
 *  at most the Nyquist frequency). */
TD_API td_status td_loop_evaluate(const td_loop *l, int j, double f, double *s_re, double *s_im, double *l_re,
                                  double *l_im, td_error *err);

/* ---------------------------------------------------------------------------------------- */
/* API 617 unbalance response report (lib/modal/api617.c; docs/api617.md)                  */

/** Logarithmic decrement of a mode of damping ratio zeta: delta = 2 pi zeta / sqrt(1 - zeta^2)
 *  (the decay of successive peaks, ln(x_k / x_k+1)); TD_UNDEFINED for zeta >= 1 or not finite. */
TD_API double td_log_decrement(double zeta);

/**
 * The separation margin API 617 (7th ed., 2002, 2.6.2.10; the clause moved in the 8th ed.: docs/api617.md) requires of
 * a response peak of amplification factor af, in % of the operating speed it is counted from: 0 when af < 2.5
 * (critically damped); else below the minimum operating speed min(16, 17 (1 - 1 / (af - 1.5))), above the maximum
 * continuous speed (above != 0) min(26, 10 + 17 (1 - 1 / (af - 1.5))). TD_UNDEFINED for af not a finite positive
 * number.
 */
TD_API double td_api617_required_margin(double af, int above);

/** The options of td_unbalance_sweep. */
typedef struct td_sweep_options {
    double speed_min;     /**< rad/s, >= 0 */
    double speed_max;     /**< rad/s, > speed_min */
    double operating_min; /**< minimum operating speed, rad/s; TD_UNDEFINED: no operating range */
    double operating_max; /**< maximum continuous speed, rad/s; TD_UNDEFINED: no operating range */
    const int *nodes;     /**< the response nodes */
    int node_count;       /**< 1..TD_SWEEP_MAX_NODES */
} td_sweep_options;

/** At most this many response nodes, and at most TD_SWEEP_MAX_SPEEDS speeds on the adaptive grid. */
#define TD_SWEEP_MAX_NODES 64
#define TD_SWEEP_MAX_SPEEDS 4000

/** A peak of the unbalance response at one node, with its API 617 assessment. */
typedef struct td_response_peak {
    int node;               /**< the response node */
    double speed;           /**< N_c, rad/s: the amplitude's local maximum (Brent's method on the curve) */
    double amplitude;       /**< m, the orbit's major semi-axis there (0-peak, the largest probe reading) */
    double speed_low;       /**< N_1, rad/s: amplitude / sqrt(2) below the peak (root of the curve); TD_UNDEFINED
                             *   when the curve does not fall that far inside the sweep */
    double speed_high;      /**< N_2, rad/s: the same above the peak */
    double amplification;   /**< AF = N_c / (N_2 - N_1) (half-power method); TD_UNDEFINED without N_1 or N_2 */
    double margin;          /**< separation margin, %: 100 (N_min - N_c) / N_min below the operating range,
                             *   100 (N_c - N_max) / N_max above it, the larger of the two (negative) inside;
                             *   TD_UNDEFINED without an operating range */
    double required_margin; /**< %, td_api617_required_margin (the side of the nearer end inside the range) */
    int verdict;            /**< 1: margin >= required (or AF < 2.5), 0: not, -1: undefined */
} td_response_peak;

typedef struct td_sweep td_sweep;

/**
 * The steady unbalance response (td_harmonic_compute's, to u[0..n_u-1], solved in second-order
 * form, docs/api617.md) over the speed range of `opt` on an adaptive grid: 101 even speeds, then
 * every interval bisected where the orbit's major semi-axis at a response node changes by more than 5 % (amplitudes
 * above 1e-6 of that node's largest), until none does, the interval is 1e-7 of the range or the grid holds
 * TD_SWEEP_MAX_SPEEDS speeds. Each local maximum of a node's amplitude of at least 1 % of that
 * node's largest over the sweep is a peak (smaller ones are not assessed), located by Brent's minimiser between its
 * grid neighbours, its half-power speeds by Brent's root finder on the curve (never read off the grid), and assessed by
 * API 617 against the operating range. A speed where the solve fails (an undamped resonance) holds TD_UNDEFINED orbits.
 * Errors: TD_ERR_INVALID (arguments), TD_ERR_NOMEM, and those of the harmonic solve.
 */
TD_API td_status td_unbalance_sweep(const td_system *sys, const td_unbalance *u, int n_u, const td_sweep_options *opt,
                                    td_sweep **out, td_error *err);
TD_API void td_sweep_free(td_sweep **s);
TD_API int td_sweep_speed_count(const td_sweep *s);
/** Speed number k of the grid (ascending), rad/s; NAN out of range. */
TD_API double td_sweep_speed(const td_sweep *s, int k);
TD_API int td_sweep_node_count(const td_sweep *s);
/** Response node j; -1 out of range. */
TD_API int td_sweep_node(const td_sweep *s, int j);
/** The orbit of response node j at speed number k. TD_ERR_INVALID out of range. */
TD_API td_status td_sweep_orbit(const td_sweep *s, int k, int j, td_orbit *out);
TD_API int td_sweep_peak_count(const td_sweep *s);
/** The operating range the peaks were assessed against, rad/s (TD_UNDEFINED: none). */
TD_API void td_sweep_operating_range(const td_sweep *s, double *lo, double *hi);
/** Peak i (by node, then speed). TD_ERR_INVALID out of range. */
TD_API td_status td_sweep_get_peak(const td_sweep *s, int i, td_response_peak *out);

/**
 * ISO 14839-2 zone (touchdown/assess.h, td_vibration_zone_of) of each AMB's sensor along the swept
 * response: zones[k n_amb + i] for speed number k and AMB i of `m` (the model the sweep was made
 * of), from the orbit's major semi-axis at the AMB's sensor node against C_min, the smallest
 * retainer clearance of `m`, with the boundaries of its limits (td_model_get_limits); *c_min gets
 * C_min (TD_UNDEFINED without retainers: every zone -1). TD_ERR_INVALID when a sensor node is not
 * a response node of the sweep (zones left unspecified).
 */
TD_API td_status td_sweep_sensor_zones(const td_sweep *s, const td_model *m, int *zones, double *c_min, td_error *err);

/** API 617's limit on the unbalance response at the close clearances, as a fraction of the running
 *  clearance (7th ed., 2002, 2.6.2.10 as recalled, "75 % of the minimum design diametral running
 *  clearances": peak-to-peak against diametral is major semi-axis against radial; docs/api617.md). */
#define TD_API617_CLEARANCE_FRACTION 0.75

/** The unbalance response at one retainer against its clearance (td_sweep_clearance_check). */
typedef struct td_clearance_check {
    int node;         /**< the retainer's node */
    double clearance; /**< m, its radial clearance */
    double amplitude; /**< m, the largest major semi-axis at the node over the range (grid speeds and located
                       *   peaks); TD_UNDEFINED when the node is not a response node or the response is
                       *   undefined (an undamped resonance) somewhere in the range */
    double speed;     /**< rad/s, where it is largest */
    double ratio;     /**< amplitude / clearance */
    int verdict;      /**< 1: ratio <= TD_API617_CLEARANCE_FRACTION, 0: above, -1: undefined */
} td_clearance_check;

/**
 * API 617's amplitude check at the close clearances, here the retainers: out[i] for retainer i of
 * `m` (the model the sweep was made of; td_model_retainer_count(m) entries), the largest major
 * semi-axis at its node over the sweep's operating range (td_sweep_operating_range; the whole sweep
 * when none is given), against TD_API617_CLEARANCE_FRACTION of its clearance. TD_ERR_INVALID for a
 * NULL argument.
 */
TD_API td_status td_sweep_clearance_check(const td_sweep *s, const td_model *m, td_clearance_check *out, td_error *err);
/** The speed range td_sweep_clearance_check looks at, rad/s: the operating range, else the sweep's. */
TD_API void td_sweep_clearance_range(const td_sweep *s, double *lo, double *hi);

/**
 * The default response nodes of a model: every disc's, AMB sensor's and retainer's node, ascending,
 * each once; at most `capacity` go to nodes. Returns how many there are.
 */
TD_API int td_modal_default_response_nodes(const td_model *m, int *nodes, int capacity);

/**
 * Static reactions under the model's gravity: the force (N, x and y) each support exerts on the
 * rotor in the closed-loop static equilibrium (td_modal_start_state's z_s): amb[2 i + c] of AMB i
 * (ks x + Fc at its node, the lagged Fc or the control law's static command), bearing[2 i + c] of
 * plain bearing i (-k x). Either array may be NULL. An AMB axis driven by a linear controller
 * without a lag state is TD_UNDEFINED (its static command is not a state). Errors as
 * td_modal_start_state.
 */
TD_API td_status td_static_reactions(const td_system *sys, double *amb, double *bearing, td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_MODAL_H */
