/*
 * Finite-element matrices of the rotor parts, inside the library only.
 *
 * Shaft element: Nelson & McVaugh (1976), "The dynamics of rotor-bearing systems using finite
 * elements", J. Eng. Ind. 98(2), and Friswell et al., "Dynamics of Rotating Machines" (2010),
 * ch. 5, with the DOF and sign conventions of touchdown/dofs.h.
 *
 * Element matrices are 8 x 8, row-major (entry (i, j) at e[8 * i + j]), in the local order
 *
 *   [x1, y1, theta1, phi1, x2, y2, theta2, phi2]
 *
 * i.e. node 1's block then node 2's, each in the nodal order of dofs.h, so local index
 * 4 * end + TD_DOF_* maps onto global TD_DOF(node + end, TD_DOF_*).
 */
#ifndef TD_MODEL_ELEMENTS_H
#define TD_MODEL_ELEMENTS_H

#include "touchdown/model.h"

/* Number of DOFs of a shaft element (two nodes). */
#define TD_ELEMENT_DOFS 8

/* Cross-section of a (hollow) circular shaft element: area A (m^2) and second moment of
 * area I about a diameter (m^4); the polar second moment is 2 I. */
void td_shaft_section(const td_shaft_element *el, double *area, double *inertia);

/* Poisson's ratio nu = E / (2 G) - 1 of the element's material. */
double td_shaft_poisson(const td_shaft_element *el);

/* Timoshenko shear coefficient kappa of the hollow circular section, m = inner / outer diameter:
 *   Hutchinson (2001), "Shear coefficients for Timoshenko beam theory", J. Appl. Mech. 68, 87-92:
 *     kappa = 6 (1 + nu)^2 (1 + m^2)^2 / ((7 + 12 nu + 4 nu^2)(1 + m^2)^2 + 4 m^2 (5 + 6 nu + 2 nu^2))
 *     (solid: 6 (1 + nu)^2 / (7 + 12 nu + 4 nu^2));
 *   Cowper (1966), "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33, 335-340,
 *   as in Friswell et al. (2010) and ROSS:
 *     kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu)(1 + m^2)^2 + (20 + 12 nu) m^2)
 *     (solid: 6 (1 + nu) / (7 + 6 nu));
 *   TD_SHEAR_GIVEN: `value`. */
double td_shaft_shear_coefficient(const td_shaft_element *el, td_shear_form form, double value);

/* Shear parameter Phi = 12 E I / (kappa G A L^2) for TD_BEAM_TIMOSHENKO, 0 for Euler-Bernoulli. */
double td_shaft_shear_parameter(const td_shaft_element *el, td_beam_theory beam, double kappa);

/* The three matrices of one shaft element (any of the outputs may be NULL):
 *   Me  mass: translational + rotary inertia (consistent), or lumped (see elements.c)
 *   Ke  stiffness (bending, with shear deformation for Timoshenko)
 *   Ge  gyroscopic per unit speed, skew-symmetric, the sign of dofs.h
 * The element is assumed valid (td_model_add_shaft_element checked it). */
void td_shaft_element_matrices(const td_shaft_element *el, td_beam_theory beam, td_mass_form mass, double Me[64],
                               double Ke[64], double Ge[64]);
/* The same with a shear coefficient of the caller's choice (td_shaft_element_matrices: Hutchinson). */
void td_shaft_element_matrices_kappa(const td_shaft_element *el, td_beam_theory beam, double kappa, td_mass_form mass,
                                     double Me[64], double Ke[64], double Ge[64]);

#endif
