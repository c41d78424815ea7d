/*
 * Shaft element matrices (Nelson & McVaugh 1976; Friswell et al. 2010, sec. 5.4-5.5).
 *
 * Each bending plane is a Hermite-cubic beam in the "standard" coordinates [w1, w1', w2, w2']
 * (w' = dw/dz). The x-z plane is standard as it stands (phi = +dx/dz); in the y-z plane the
 * rotation is theta = -dy/dz (touchdown/dofs.h), so its slope DOFs change sign on the way in.
 * Shear deformation (Timoshenko) enters through Phi = 12 E I / (kappa G A L^2); Phi = 0 gives
 * the Euler-Bernoulli element exactly. The Timoshenko matrices are the consistent matrices of the
 * interdependent (statically exact) shape functions, as in Przemieniecki, "Theory of Matrix
 * Structural Analysis" (1968) and Friswell et al.; the nodal rotations are the cross-section
 * rotations. The mass matrix always carries rotary inertia, so the Euler-Bernoulli element
 * converges to the Rayleigh beam.
 */
#include "model/elements.h"

#include <string.h>

#include "touchdown/dofs.h"

/* Where the standard plane coordinates [w1, w1', w2, w2'] sit in the 8-DOF element, and the sign
 * that turns a standard slope into the element's rotation. */
static const int x_plane_index[4] = {TD_DOF_X, TD_DOF_PHI, 4 + TD_DOF_X, 4 + TD_DOF_PHI};
static const double x_plane_sign[4] = {1.0, 1.0, 1.0, 1.0};
static const int y_plane_index[4] = {TD_DOF_Y, TD_DOF_THETA, 4 + TD_DOF_Y, 4 + TD_DOF_THETA};
static const double y_plane_sign[4] = {1.0, -1.0, 1.0, -1.0}; /* theta = -dy/dz */

void td_shaft_section(const td_shaft_element *el, double *area, double *inertia)
{
    double ro2 = 0.25 * el->outer_diameter * el->outer_diameter;
    double ri2 = 0.25 * el->inner_diameter * el->inner_diameter;
    if (area)
        *area = TD_PI * (ro2 - ri2);
    if (inertia)
        *inertia = 0.25 * TD_PI * (ro2 * ro2 - ri2 * ri2);
}

double td_shaft_poisson(const td_shaft_element *el)
{
    return el->material.E / (2.0 * el->material.G) - 1.0;
}

double td_shaft_shear_coefficient(const td_shaft_element *el, td_shear_form form, double value)
{
    double nu = td_shaft_poisson(el);
    double m = el->inner_diameter / el->outer_diameter;
    double m2 = m * m, s = (1.0 + m2) * (1.0 + m2);
    if (form == TD_SHEAR_GIVEN)
        return value;
    if (form == TD_SHEAR_COWPER)
        return 6.0 * (1.0 + nu) * s / ((7.0 + 6.0 * nu) * s + (20.0 + 12.0 * nu) * m2);
    return 6.0 * (1.0 + nu) * (1.0 + nu) * s /
           ((7.0 + 12.0 * nu + 4.0 * nu * nu) * s + 4.0 * m2 * (5.0 + 6.0 * nu + 2.0 * nu * nu));
}

double td_shaft_shear_parameter(const td_shaft_element *el, td_beam_theory beam, double kappa)
{
    double A, I, L = el->length;
    if (beam != TD_BEAM_TIMOSHENKO)
        return 0.0;
    td_shaft_section(el, &A, &I);
    return 12.0 * el->material.E * I / (kappa * el->material.G * A * L * L);
}

/* Bending stiffness of one plane, standard coordinates (Friswell eq. 5.74 with shear). */
static void plane_stiffness(double EI, double L, double phi, double k[4][4])
{
    double c = EI / ((1.0 + phi) * L * L * L);
    double a = 12.0 * c, b = 6.0 * L * c;
    double d = (4.0 + phi) * L * L * c, e = (2.0 - phi) * L * L * c;
    double v[4][4] = {{a, b, -a, b}, {b, d, -b, e}, {-a, -b, a, -b}, {b, e, -b, d}};
    memcpy(k, v, sizeof v);
}

/* Consistent translational mass of one plane, rho A L / (840 (1 + Phi)^2) times the polynomial
 * pattern in Phi (Friswell eq. 5.119; Phi = 0 gives the familiar rho A L / 420 [156 22L ...]). */
static void plane_translational_mass(double rhoAL, double L, double phi, double m[4][4])
{
    double c = rhoAL / (840.0 * (1.0 + phi) * (1.0 + phi));
    double p2 = phi * phi;
    double m1 = (312.0 + 588.0 * phi + 280.0 * p2) * c;
    double m2 = (44.0 + 77.0 * phi + 35.0 * p2) * L * c;
    double m3 = (108.0 + 252.0 * phi + 140.0 * p2) * c;
    double m4 = -(26.0 + 63.0 * phi + 35.0 * p2) * L * c;
    double m5 = (8.0 + 14.0 * phi + 7.0 * p2) * L * L * c;
    double m6 = -(6.0 + 14.0 * phi + 7.0 * p2) * L * L * c;
    double v[4][4] = {{m1, m2, m3, m4}, {m2, m5, -m4, m6}, {m3, -m4, m1, -m2}, {m4, m6, -m2, m5}};
    memcpy(m, v, sizeof v);
}

/* Consistent rotary-inertia pattern of one plane, rho I / (30 L (1 + Phi)^2) times the pattern
 * (Friswell eq. 5.119). With rho I replaced by rho J = 2 rho I it is also the gyroscopic block. */
static void plane_rotary_mass(double rhoI, double L, double phi, double r[4][4])
{
    double c = rhoI / (30.0 * L * (1.0 + phi) * (1.0 + phi));
    double m7 = 36.0 * c;
    double m8 = (3.0 - 15.0 * phi) * L * c;
    double m9 = (4.0 + 5.0 * phi + 10.0 * phi * phi) * L * L * c;
    double m10 = (-1.0 - 5.0 * phi + 5.0 * phi * phi) * L * L * c;
    double v[4][4] = {{m7, m8, -m7, m8}, {m8, m9, -m8, m10}, {-m7, -m8, m7, -m8}, {m8, m10, -m8, m9}};
    memcpy(r, v, sizeof v);
}

/* Add a plane matrix (standard coordinates) to both bending planes of the 8 x 8 element. */
static void scatter_both_planes(double p[4][4], double e[64])
{
    int i, j;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            e[8 * x_plane_index[i] + x_plane_index[j]] += x_plane_sign[i] * x_plane_sign[j] * p[i][j];
            e[8 * y_plane_index[i] + y_plane_index[j]] += y_plane_sign[i] * y_plane_sign[j] * p[i][j];
        }
}

/*
 * Gyroscopic coupling from the polar-inertia pattern P (rho J times the rotary pattern). The
 * virtual work of the gyroscopic moments of a slice dz is Omega rho J (dtheta phi' - dphi theta') dz
 * (the disc's +Ip at (theta, phi), dofs.h). With phi = N' q_x and theta = -N' q_y(standard):
 *   rows x-plane, columns y-plane: +P T;   rows y-plane, columns x-plane: -T P,   T = diag(y_plane_sign)
 * which is skew because P is symmetric.
 */
static void scatter_gyroscopic(double p[4][4], double g[64])
{
    int i, j;
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++) {
            g[8 * x_plane_index[i] + y_plane_index[j]] += p[i][j] * y_plane_sign[j];
            g[8 * y_plane_index[i] + x_plane_index[j]] -= y_plane_sign[i] * p[i][j];
        }
}

/*
 * Lumped form (TD_MASS_LUMPED, the paper's "lumped mass" model): each end node gets half the
 * element mass on x and y, half the element's diametral rotary inertia rho I L on theta and phi,
 * and half its polar inertia rho J L = 2 rho I L as a disc-like gyroscopic term. The m L^2 / 12
 * "segment about its end" inertia is deliberately not added: the lumped model is a chain of thin
 * discs, one per node.
 */
static void lumped_mass_and_gyroscopic(double rhoAL, double rhoIL, double Me[64], double Ge[64])
{
    int end;
    for (end = 0; end < 2; end++) {
        int o = 4 * end;
        if (Me) {
            Me[8 * (o + TD_DOF_X) + o + TD_DOF_X] = 0.5 * rhoAL;
            Me[8 * (o + TD_DOF_Y) + o + TD_DOF_Y] = 0.5 * rhoAL;
            Me[8 * (o + TD_DOF_THETA) + o + TD_DOF_THETA] = 0.5 * rhoIL;
            Me[8 * (o + TD_DOF_PHI) + o + TD_DOF_PHI] = 0.5 * rhoIL;
        }
        if (Ge) {
            Ge[8 * (o + TD_DOF_THETA) + o + TD_DOF_PHI] = rhoIL;  /* + half of rho J L = rho I L */
            Ge[8 * (o + TD_DOF_PHI) + o + TD_DOF_THETA] = -rhoIL; /* - half of rho J L */
        }
    }
}

void td_shaft_element_matrices(const td_shaft_element *el, td_beam_theory beam, td_mass_form mass, double Me[64],
                               double Ke[64], double Ge[64])
{
    td_shaft_element_matrices_kappa(el, beam, td_shaft_shear_coefficient(el, TD_SHEAR_HUTCHINSON, 0.0), mass, Me, Ke,
                                    Ge);
}

void td_shaft_element_matrices_kappa(const td_shaft_element *el, td_beam_theory beam, double kappa, td_mass_form mass,
                                     double Me[64], double Ke[64], double Ge[64])
{
    double A, I, L = el->length, rho = el->material.density;
    double phi = td_shaft_shear_parameter(el, beam, kappa);
    double p[4][4];
    td_shaft_section(el, &A, &I);
    if (Me)
        memset(Me, 0, 64 * sizeof *Me);
    if (Ke)
        memset(Ke, 0, 64 * sizeof *Ke);
    if (Ge)
        memset(Ge, 0, 64 * sizeof *Ge);
    if (Ke) {
        plane_stiffness(el->material.E * I, L, phi, p);
        scatter_both_planes(p, Ke);
    }
    if (mass == TD_MASS_LUMPED) {
        lumped_mass_and_gyroscopic(rho * A * L, rho * I * L, Me, Ge);
        return;
    }
    if (Me) {
        plane_translational_mass(rho * A * L, L, phi, p);
        scatter_both_planes(p, Me);
        plane_rotary_mass(rho * I, L, phi, p);
        scatter_both_planes(p, Me);
    }
    if (Ge) {
        plane_rotary_mass(2.0 * rho * I, L, phi, p); /* polar inertia per length rho J = 2 rho I */
        scatter_gyroscopic(p, Ge);
    }
}
