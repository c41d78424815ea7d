/* `touchdown info`'s account of a case's linear controllers: what the case file says of each, and
 * its poles, the eigenvalues of its A (GSL's nonsymmetric eigensolver); a sampled law's z poles
 * are mapped to s = ln(z) * sample_rate (the pole z = 0 of a delay has no s). */
#include "info/controller_print.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TWO_PI 6.283185307179586
/* |z| below which a sampled pole is z = 0, a delay's (a shift register's eigenvalue 0 comes out of
 * the solver at round-off size; a pole of the law there would be far beyond the Nyquist frequency). */
#define Z_ZERO 1e-6

void td_controller_view_get(const td_model *m, int i, td_controller_view *v)
{
    const td_plugin_spec *p = td_model_get_plugin(m, i);
    memset(v, 0, sizeof *v);
    v->name = "";
    v->plugin = p;
    if (p) {
        v->name = p->name ? p->name : "";
        v->sample_rate = p->sample_rate;
        v->n_inputs = p->n_inputs;
        v->n_outputs = p->n_outputs;
        v->inputs = p->inputs;
        v->outputs = p->outputs;
    } else if ((v->law = td_model_get_controller(m, i, &v->name, &v->inputs, &v->outputs)) != NULL) {
        v->sample_rate = td_controller_sample_rate(v->law);
        v->n_inputs = td_controller_inputs(v->law);
        v->n_outputs = td_controller_outputs(v->law);
    }
}

int td_amb_controller(const td_model *m, int amb)
{
    td_recovery rec;
    int i, j, p, standby, pairs = td_model_get_recovery(m, &rec);
    for (i = 0; i < td_model_controller_count(m); i++) {
        td_controller_view v;
        td_controller_view_get(m, i, &v);
        for (p = standby = 0; p < pairs; p++) /* a recovery law stands by on its nominal's AMBs */
            standby |= rec.controller[p] == i;
        for (j = 0; j < v.n_outputs && !standby; j++)
            if (v.outputs[j] / 2 == amb)
                return i;
    }
    return -1;
}

/* The eigenvalues of the n x n column-major A into re, im; 0, or -1 when GSL fails. */
static int eigenvalues(const double *A, int n, double *re, double *im)
{
    gsl_matrix *m = gsl_matrix_alloc((size_t)n, (size_t)n);
    gsl_vector_complex *ev = gsl_vector_complex_alloc((size_t)n);
    gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc((size_t)n);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int i, j, status = -1;
    if (m && ev && w) {
        for (i = 0; i < n; i++)
            for (j = 0; j < n; j++)
                gsl_matrix_set(m, (size_t)i, (size_t)j, A[i + (size_t)j * n]);
        status = gsl_eigen_nonsymm(m, ev, w) == GSL_SUCCESS ? 0 : -1;
        for (i = 0; status == 0 && i < n; i++) {
            re[i] = GSL_REAL(gsl_vector_complex_get(ev, (size_t)i));
            im[i] = GSL_IMAG(gsl_vector_complex_get(ev, (size_t)i));
        }
    }
    gsl_set_error_handler(old);
    gsl_eigen_nonsymm_free(w);
    gsl_vector_complex_free(ev);
    gsl_matrix_free(m);
    return status;
}

/* A pole as "F Hz (zeta Z)", from s (rad/s); "integrator" at s = 0 (|s| below 1e-9 of the
 * largest pole, `scale`: an eigenvalue 0 computed with round-off); after a comma unless first. */
static void print_pole(FILE *f, double re, double im, int count, int first, double scale)
{
    double w = hypot(re, im);
    if (w <= 1e-9 * scale)
        fprintf(f, "%s 0 Hz (integrator)", first ? "" : ",");
    else
        fprintf(f, "%s %.6g Hz (zeta %.3g)", first ? "" : ",", w / TWO_PI, -re / w + 0.0); /* + 0: no "-0" */
    if (count > 1)
        fprintf(f, " x%d", count);
}

/* Whether poles i and j are the same (equal up to round-off of their size). */
static int same_pole(const double *re, const double *im, int i, int j)
{
    double scale = hypot(re[i], im[i]) + hypot(re[j], im[j]);
    return fabs(re[i] - re[j]) + fabs(im[i] - im[j]) <= 1e-9 * scale;
}

/* The poles s (re, im: n of them, NaN re for a delay's z = 0), each conjugate pair once, equal
 * ones counted, in the order of the solver. */
static void print_pole_list(FILE *f, const double *re, const double *im, int n)
{
    double scale = 0.0;
    int i, j, delays = 0, shown = 0;
    for (i = 0; i < n; i++)
        scale = isnan(re[i]) || hypot(re[i], im[i]) < scale ? scale : hypot(re[i], im[i]);
    for (i = 0; i < n; i++) {
        int count = 1, first = 1;
        delays += isnan(re[i]);
        if (isnan(re[i]) || im[i] < 0.0)
            continue; /* a delay's z = 0; a pair's lower half */
        for (j = 0; j < n; j++)
            if (j != i && !isnan(re[j]) && same_pole(re, im, i, j))
                j < i ? (void)(first = 0) : (void)count++;
        if (first)
            print_pole(f, re[i], im[i], count, shown++ == 0, scale);
    }
    if (delays > 0)
        fprintf(f, "%s z = 0 (delay) x%d", shown ? "," : "", delays);
}

/* The poles of k in s (a sampled law's z mapped to s = ln(z) sample_rate). */
static void print_poles(FILE *f, const td_controller *k)
{
    int n = td_controller_order(k), i, ok;
    double rate = td_controller_sample_rate(k);
    double *A = malloc((size_t)n * n * sizeof *A + 1), *re = malloc((size_t)n * sizeof *re + 1),
           *im = malloc((size_t)n * sizeof *im + 1);
    ok = n > 0 && A && re && im;
    if (ok)
        td_controller_matrices(k, A, NULL, NULL, NULL, NULL);
    ok = ok && eigenvalues(A, n, re, im) == 0; /* GSL takes no empty matrix: a static law has none */
    for (i = 0; ok && i < n && rate > 0.0; i++) {
        double r = hypot(re[i], im[i]), a = atan2(im[i], re[i]);
        re[i] = r < Z_ZERO ? NAN : log(r) * rate;
        im[i] = a * rate;
    }
    fprintf(f, "             poles:");
    if (ok)
        print_pole_list(f, re, im, n);
    else
        fprintf(f, n == 0 ? " none" : " (not computed)");
    fprintf(f, "\n");
    free(A);
    free(re);
    free(im);
}

/* "amb 0" or "ambs 0, 1" of a controller: the AMBs of its n inputs, each once, in their order. */
static void print_ambs(FILE *f, int n, const int *inputs)
{
    int j, l, pass, shown;
    for (pass = 0, shown = 0; pass < 2; pass++) {
        int count = shown;
        shown = 0;
        if (pass == 1)
            fprintf(f, count == 1 ? "amb" : "ambs");
        for (j = 0; j < n; j++) {
            for (l = 0; l < j && inputs[l] / 2 != inputs[j] / 2; l++)
                ;
            if (l == j && pass == 1)
                fprintf(f, "%s%d", shown ? ", " : " ", inputs[j] / 2);
            shown += l == j;
        }
    }
}

/* A plug-in controller's line after its AMBs: its library, ABI and output, timing, parameters. */
static void print_plugin(FILE *f, const td_plugin_spec *p)
{
    int j;
    fprintf(f, " in bearing coordinates, plug-in %s (ABI %d, %s commands), sampled at %.6g Hz, delay %d sample%s\n",
            p->library ? p->library : "(registered by the program)", p->functions ? p->functions->abi_version : 0,
            p->functions && p->functions->output == TD_PLUGIN_FORCE ? "force" : "current", p->sample_rate, p->delay,
            p->delay == 1 ? "" : "s");
    fprintf(f, "             parameters:");
    for (j = 0; j < p->n_parameters; j++)
        fprintf(f, "%s %s = %.9g", j ? "," : "", p->parameter_names[j], p->parameter_values[j]);
    fprintf(f, "%s\n", p->n_parameters ? "" : " none");
}

void td_print_controllers(FILE *f, const td_case *c)
{
    const td_model *m = td_case_model(c);
    int i;
    for (i = 0; i < td_model_controller_count(m); i++) {
        td_controller_view v;
        const td_controller *k;
        td_case_controller_info info;
        double rate;
        td_controller_view_get(m, i, &v);
        k = v.law;
        rate = v.sample_rate;
        td_case_controller(c, i, &info);
        fprintf(f, "controller %-2d \"%s\": ", i, v.name);
        print_ambs(f, v.n_inputs, v.inputs);
        if (v.plugin) {
            print_plugin(f, v.plugin);
            continue;
        }
        if (info.rigid)
            fprintf(f, " in rigid-body coordinates about z = %.6g m", info.reference_z);
        else
            fprintf(f, " in bearing coordinates");
        fprintf(f, ", %d states, ", td_controller_order(k));
        if (rate > 0.0 && !info.discretised) /* no block in s: the law is as written in z */
            fprintf(f, "sampled at %.6g Hz (written in z)", rate);
        else if (rate > 0.0 && info.prewarp > 0.0)
            fprintf(f, "sampled at %.6g Hz (tustin prewarped at %.6g Hz)", rate, info.prewarp);
        else if (rate > 0.0)
            fprintf(f, "sampled at %.6g Hz (%s)", rate, info.discretisation == TD_DISCRETISE_ZOH ? "zoh" : "tustin");
        else
            fprintf(f, "continuous%s", td_controller_has_velocity_feedthrough(k) ? ", exact derivative" : "");
        if (rate > 0.0)
            fprintf(f, ", delay %d sample%s", info.delay, info.delay == 1 ? "" : "s");
        fprintf(f, "\n");
        print_poles(f, k);
    }
}
