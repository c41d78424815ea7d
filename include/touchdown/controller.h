/*
 * touchdown/controller.h - AMB controllers as linear systems: transfer functions, zeros-poles-gain,
 * state space and blocks in series (PID, lead-lag, low-pass, notch, resonant), continuous or sampled.
 *
 * A td_controller is one state-space realisation (docs/theory.md, "Controllers"):
 *
 *   continuous   x' = A x + B e,            i = C x + D e + D1 e'
 *   sampled      x[k+1] = A x[k] + B e[k],  i[k] = C x[k] + D e[k]     at t_k = t0 + k / sample_rate,
 *                i held (zero-order hold) on [t_k, t_{k+1})
 *
 * with n states, `inputs` error signals e and `outputs` current commands i. Sign convention (one
 * place, with touchdown/dofs.h): a controller acts on the error e = r - y with the reference r = 0,
 * so its input is minus the sensed displacement, e = -xs (m), and its output is the current command
 * i (A) of the amplifier, whose force is ki i. A positive PD kp + kd s therefore gives
 * i = -(kp xs + kd xs'), the td_amb shorthand's law (touchdown/model.h).
 *
 * D1 (outputs x inputs) is the velocity feedthrough of a continuous law that is improper by exactly
 * one (a PD without a derivative filter): it multiplies the exact sensor velocity, the signal the
 * shorthand reads. A sampled controller has D1 = 0. Matrices are column-major (LAPACK's order).
 *
 * Transfer-function coefficients are in descending powers of s (num[0] s^m + ... + num[m]) for a
 * continuous law, and in ascending powers of z^-1 (num[0] + num[1] z^-1 + ...) for a sampled one,
 * as control textbooks and scipy.signal write them. Frequencies given to blocks are in Hz.
 */
#ifndef TOUCHDOWN_CONTROLLER_H
#define TOUCHDOWN_CONTROLLER_H

#include "touchdown/error.h"
#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** An opaque linear controller (one realisation). */
typedef struct td_controller td_controller;

/** PID block  kp + kint / s + kd s / (1 + s / (2 pi derivative_filter)); derivative_filter 0: the
 *  exact derivative kd s (continuous only: it becomes the velocity feedthrough D1). */
typedef struct td_pid_block {
    double kp;                /**< A/m */
    double kint;              /**< A/(m s), >= 0 */
    double kd;                /**< A s/m */
    double derivative_filter; /**< Hz, >= 0 */
} td_pid_block;

/** Lead-lag block  gain (1 + s / (2 pi zero)) / (1 + s / (2 pi pole)). */
typedef struct td_leadlag_block {
    double gain; /**< A/m for a first block, dimensionless after it */
    double zero; /**< Hz, > 0 */
    double pole; /**< Hz, > 0 */
} td_leadlag_block;

/** Low-pass block: order 1  wc / (s + wc); order 2  wc^2 / (s^2 + 2 damping wc s + wc^2), wc = 2 pi frequency. */
typedef struct td_lowpass_block {
    double frequency; /**< Hz, > 0 */
    int order;        /**< 1 or 2 */
    double damping;   /**< order 2 only, > 0 */
} td_lowpass_block;

/** Notch block  (s^2 + 2 zz wn s + wn^2) / (s^2 + 2 zp wn s + wn^2), wn = 2 pi frequency,
 *  zp = width / (2 frequency) (width: the -3 dB band), zz = depth zp (depth: the gain at wn, 0..1). */
typedef struct td_notch_block {
    double frequency; /**< Hz, > 0 */
    double width;     /**< Hz, > 0 */
    double depth;     /**< >= 0, < 1 */
} td_notch_block;

/** Resonant block  gain (s cos phase + w sin phase) / (s^2 + 2 damping w s + w^2), w = 2 pi frequency.
 *  Undamped (damping 0) it is an internal model of a sinusoid at `frequency` (at the spin speed,
 *  Omega / 2 pi, a synchronous compensator: the LTI form of synchronous motion compensation, Su, Gu,
 *  Keogh et al., MSSP 2022): its poles +-jw lie on the imaginary axis and its response at w itself
 *  is infinite. Damped (0 < damping < 1) its poles are -damping w +- j w sqrt(1 - damping^2) and its
 *  response at w is finite, gain / (2 damping w) e^{-j phase}: a synchronous damper whose output
 *  follows the present phase of the motion at w rather than integrating it. */
typedef struct td_resonant_block {
    double gain;      /**< A/(m s) for a first block, 1/s after it */
    double phase;     /**< degrees, finite: 0 gives gain s / (s^2 + w^2), 90 gives gain w / (s^2 + w^2) */
    double frequency; /**< Hz, > 0 */
    double damping;   /**< damping ratio of the poles, >= 0 and < 1; 0: undamped (as a zero-initialised block) */
} td_resonant_block;

/** Every frequency a block takes (Hz: leadlag zero and pole, lowpass and notch frequency, notch
 *  width, pid derivative_filter, resonant frequency) lies from TD_CONTROLLER_FREQUENCY_MIN to
 *  TD_CONTROLLER_FREQUENCY_MAX (a derivative_filter may also be 0: none). 1 MHz is far above any
 *  AMB filter (an amplifier's bandwidth is a few kHz), 1e-6 Hz far below (a period of 12 days).
 *  Beyond them a value is a typing error, and the analyses would mislead: a notch at 1e308 Hz made
 *  w = inf and one of 1e-300 Hz a realisation with entries 1e306 apart (`touchdown info` did not
 *  finish on either), and one at 1e8 Hz widened the closed-loop stability test's rounding margin
 *  (TD_MODAL_MARGINAL_REAL_PART of the spectral radius, touchdown/modal.h) enough to call an
 *  unstable loop marginally stable. A block at 1 MHz keeps that radius within the FE rotor's own
 *  (the reference rig refined 8 times reaches 1.9e6 rad/s). Every constructor and combination
 *  also refuses a realisation that overflows (an entry inf or NaN), naming itself. */
#define TD_CONTROLLER_FREQUENCY_MIN 1.0e-6
#define TD_CONTROLLER_FREQUENCY_MAX 1.0e6

/** How a continuous law becomes a sampled one. */
typedef enum td_discretisation {
    TD_DISCRETISE_TUSTIN = 0, /**< bilinear, with optional frequency prewarping */
    TD_DISCRETISE_ZOH = 1     /**< zero-order hold: exact for a held input */
} td_discretisation;

/* --- Creating (each returns a new controller the caller frees; NULL with err set on failure) --- */

TD_API td_controller *td_controller_create_gain(double gain, td_error *err);
TD_API td_controller *td_controller_create_pid(const td_pid_block *b, td_error *err);
TD_API td_controller *td_controller_create_leadlag(const td_leadlag_block *b, td_error *err);
TD_API td_controller *td_controller_create_lowpass(const td_lowpass_block *b, td_error *err);
TD_API td_controller *td_controller_create_notch(const td_notch_block *b, td_error *err);
TD_API td_controller *td_controller_create_resonant(const td_resonant_block *b, td_error *err);
/** SISO transfer function num/den (coefficients as in the header comment). sample_rate 0: in s,
 *  proper or improper by one; > 0 (Hz): in z^-1, proper (den[0] != 0). */
TD_API td_controller *td_controller_create_tf(const double *num, int num_len, const double *den, int den_len,
                                              double sample_rate, td_error *err);
/** SISO zeros-poles-gain, continuous or sampled (as create_tf). A root with a nonzero imaginary
 *  part stands for itself and its conjugate: give each pair once. gain multiplies the monic
 *  polynomials' ratio. */
TD_API td_controller *td_controller_create_zpk(const double *zero_re, const double *zero_im, int n_zeros,
                                               const double *pole_re, const double *pole_im, int n_poles, double gain,
                                               double sample_rate, td_error *err);
/** State space (n >= 0 states, column-major A n x n, B n x inputs, C outputs x n, D outputs x inputs);
 *  D1 may be NULL (zero), and must be for a sampled law. */
TD_API td_controller *td_controller_create_ss(int n, int inputs, int outputs, const double *A, const double *B,
                                              const double *C, const double *D, const double *D1, double sample_rate,
                                              td_error *err);
/** Deep copy. */
TD_API td_controller *td_controller_clone(const td_controller *k, td_error *err);
TD_API void td_controller_free(td_controller **k);

/* --- Combining --- */

/** first then second: e -> first -> second -> i (second's inputs = first's outputs). Both continuous,
 *  or both sampled at the same rate. The result may be improper by at most one. */
TD_API td_controller *td_controller_series(const td_controller *first, const td_controller *second, td_error *err);
/** In parallel: the same inputs into a and b, their outputs added (i = a(e) + b(e)); same timing,
 *  same numbers of inputs and outputs. */
TD_API td_controller *td_controller_parallel(const td_controller *a, const td_controller *b, td_error *err);
/** Side by side: inputs and outputs stacked (block-diagonal), same timing. */
TD_API td_controller *td_controller_append(const td_controller *a, const td_controller *b, td_error *err);
/** Static pre- and post-multiplication  i = Tout K(Tin e): Tin is (k inputs x new inputs), Tout
 *  (new outputs x k outputs), both column-major; the coordinate transforms of a rigid-body law. */
TD_API td_controller *td_controller_transform(const td_controller *k, int new_inputs, const double *Tin,
                                              int new_outputs, const double *Tout, td_error *err);
/** The sampled law of a continuous one at sample_rate (Hz). prewarp (Hz, Tustin only, 0: none)
 *  is the frequency where the sampled law's response matches the continuous one exactly. A law
 *  with D1 != 0 is refused (give the derivative a filter). */
TD_API td_controller *td_controller_discretise(const td_controller *k, double sample_rate, td_discretisation method,
                                               double prewarp, td_error *err);
/** A sampled law followed by a delay of `samples` whole samples on every output (z^-samples). */
TD_API td_controller *td_controller_delay(const td_controller *k, int samples, td_error *err);
/** A minimal realisation (uncontrollable and unobservable states removed, then balanced). */
TD_API td_controller *td_controller_minimal(const td_controller *k, td_error *err);

/* --- Reading --- */

TD_API int td_controller_order(const td_controller *k);   /**< n, the number of states */
TD_API int td_controller_inputs(const td_controller *k);  /**< error signals */
TD_API int td_controller_outputs(const td_controller *k); /**< current commands */
/** Hz; 0 for a continuous law. */
TD_API double td_controller_sample_rate(const td_controller *k);
/** 1 if D1 != 0 (continuous, improper by one). */
TD_API int td_controller_has_velocity_feedthrough(const td_controller *k);
/** Copy the matrices (column-major; any pointer may be NULL). */
TD_API void td_controller_matrices(const td_controller *k, double *A, double *B, double *C, double *D, double *D1);
/** Frequency response at f (Hz): G (outputs x inputs, column-major) as real and imaginary parts,
 *  G = C (jw I - A)^-1 B + D + jw D1 (continuous) or C (z I - A)^-1 B + D at z = exp(jw/sample_rate). */
TD_API td_status td_controller_frequency_response(const td_controller *k, double f, double *re, double *im,
                                                  td_error *err);
/** Response y (outputs x n_times, column-major) to a unit step on input `input` at t = 0 from rest,
 *  at the times t (>= 0, s): exact for a continuous law (matrix exponential), the sample sequence
 *  held for a sampled one. A law with D1 != 0 is refused (its step response has an impulse). */
TD_API td_status td_controller_step_response(const td_controller *k, int input, const double *t, int n_times, double *y,
                                             td_error *err);

/* --- Rigid-body coordinates (docs/theory.md, "Rigid-body coordinates") ---
 * For two bearing planes a and b at axial positions za != zb and a reference position zr, in each
 * lateral plane (x-z and y-z alike, the tilt being the slope dx/dz or dy/dz, m/m):
 *
 *   [x_r; tilt] = T [x_a; x_b],   T = 1/(zb - za) [ zb - zr   zr - za ; -1   1 ]
 *   [F_a; F_b]  = T^T [F_r; M]    (virtual work: F_a dx_a + F_b dx_b = F_r dx_r + M dtilt)
 */
/** T (2 x 2, column-major) of the transform above; TD_ERR_INVALID when za == zb or a value is not finite. */
TD_API td_status td_rigid_transform(double za, double zb, double zr, double T[4], td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_CONTROLLER_H */
