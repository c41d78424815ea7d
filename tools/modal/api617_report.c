/* touchdown modal: the API 617 unbalance response report (docs/api617.md): the swept response at
 * the response nodes, its peaks with amplification factors and separation margins, and the static
 * reactions under gravity. */
#include "modal/modal_print.h"
#include "touchdown/assess.h"
#include "touchdown/dofs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The response nodes of the case: modal.response_nodes, else the default ones. */
static int response_nodes(const td_model *m, const td_modal_options *opt, int *nodes)
{
    int i, n;
    if (opt->response_node_count > 0) {
        for (i = 0; i < opt->response_node_count; i++)
            nodes[i] = opt->response_nodes[i];
        return opt->response_node_count;
    }
    n = td_modal_default_response_nodes(m, nodes, TD_SWEEP_MAX_NODES);
    return n < TD_SWEEP_MAX_NODES ? n : TD_SWEEP_MAX_NODES;
}

/* The zones of the AMB sensors along the sweep, or none (said on stderr) when a sensor is not a
 * response node. */
static void sensor_zones(const td_model *m, td_modal_api617_results *out)
{
    td_error e;
    size_t n = (size_t)td_sweep_speed_count(out->sweep) * (size_t)td_model_amb_count(m);
    if (n == 0 || !(out->zones = malloc(n * sizeof *out->zones)))
        return;
    if (td_sweep_sensor_zones(out->sweep, m, out->zones, &out->c_min, &e) != TD_OK) {
        fprintf(stderr, "touchdown modal: no ISO 14839-2 zones along the unbalance response: %s\n", e.message);
        free(out->zones);
        out->zones = NULL;
    }
}

/* API 617's amplitude check at the retainers (none when the machine has no retainer). */
static void clearance_check(const td_model *m, td_modal_api617_results *out)
{
    size_t n = (size_t)td_model_retainer_count(m);
    if (n == 0 || !(out->clearance = malloc(n * sizeof *out->clearance)))
        return;
    if (td_sweep_clearance_check(out->sweep, m, out->clearance, NULL) != TD_OK) {
        free(out->clearance);
        out->clearance = NULL;
    }
}

/* Without gravity the static reactions are no quantity: NaN in the files, said in the text. */
static void no_gravity(const td_model *m, td_modal_api617_results *out)
{
    double gx, gy;
    int i;
    td_model_gravity(m, &gx, &gy);
    out->gravity = gx != 0.0 || gy != 0.0;
    for (i = 0; !out->gravity && i < 2 * td_model_amb_count(m); i++)
        out->amb[i] = TD_UNDEFINED;
    for (i = 0; !out->gravity && i < 2 * td_model_bearing_count(m); i++)
        out->bearing[i] = TD_UNDEFINED;
}

td_status td_modal_api617(const td_model *m, const td_system *sys, const td_modal_options *opt, const td_unbalance *u,
                          int n_u, td_modal_api617_results *out, td_error *err)
{
    int nodes[TD_SWEEP_MAX_NODES];
    td_sweep_options so;
    size_t na = 2u * (size_t)td_model_amb_count(m) + 1u, nb = 2u * (size_t)td_model_bearing_count(m) + 1u;
    td_status st = TD_OK;
    out->sweep = NULL;
    out->zones = NULL;
    out->clearance = NULL;
    out->amb = calloc(na, sizeof *out->amb);
    out->bearing = calloc(nb, sizeof *out->bearing);
    if (!out->amb || !out->bearing)
        return TD_ERR_NOMEM;
    so.speed_min = opt->speed_min;
    so.speed_max = opt->speed_max;
    so.operating_min = opt->operating_speed_min;
    so.operating_max = opt->operating_speed_max;
    so.nodes = nodes;
    so.node_count = response_nodes(m, opt, nodes);
    if (n_u > 0 && so.node_count > 0)
        st = td_unbalance_sweep(sys, u, n_u, &so, &out->sweep, err);
    if (st == TD_ERR_INVALID) { /* a machine the harmonic solve refuses (sampled or plug-in controllers) */
        fprintf(stderr, "touchdown modal: no unbalance response over the speed range: %s\n", err->message);
        td_error_clear(err);
        st = TD_OK;
    }
    if (st == TD_OK && out->sweep) {
        sensor_zones(m, out);
        clearance_check(m, out);
    }
    out->reactions_ok = st == TD_OK && td_static_reactions(sys, out->amb, out->bearing, NULL) == TD_OK;
    no_gravity(m, out);
    return st;
}

void td_modal_api617_into(td_modal_results *res, const td_modal_api617_results *r)
{
    memset(res, 0, sizeof *res);
    res->sweep = r->sweep;
    res->static_amb = r->reactions_ok ? r->amb : NULL;
    res->static_bearing = r->reactions_ok ? r->bearing : NULL;
    res->sensor_zones = r->zones;
    res->zone_c_min = r->c_min;
    res->clearance = r->clearance;
}

void td_modal_api617_free(td_modal_api617_results *r)
{
    td_sweep_free(&r->sweep);
    free(r->amb);
    free(r->bearing);
    free(r->zones);
    free(r->clearance);
    r->amb = r->bearing = NULL;
    r->zones = NULL;
    r->clearance = NULL;
}

static const char *verdict_word(int v)
{
    return v == 1 ? "pass" : v == 0 ? "FAIL" : "undefined";
}

/* x with format fmt into buf, or "n/a" when it is undefined (the files keep the NaN). */
static const char *number(char *buf, size_t n, const char *fmt, double x)
{
    if (td_is_undefined(x))
        return "n/a";
    snprintf(buf, n, fmt, x);
    return buf;
}

/* The peak table: node, N_c, amplitude, N_1, N_2, AF, SM, required SM, verdict. */
static void print_peaks(FILE *f, const td_sweep *s)
{
    int i;
    fprintf(f, "  %-4s %14s %12s %14s %14s %8s %9s %9s  %s\n", "node", "N_c [rad/s]", "amp [m]", "N_1 [rad/s]",
            "N_2 [rad/s]", "AF", "SM [%]", "req [%]", "verdict");
    if (td_sweep_peak_count(s) == 0)
        fprintf(f, "  none\n");
    for (i = 0; i < td_sweep_peak_count(s); i++) {
        td_response_peak p;
        char n1[24], n2[24], af[24], sm[24], req[24];
        td_sweep_get_peak(s, i, &p);
        fprintf(f, "  %-4d %14.8g %12.5g %14s %14s %8s %9s %9s  %s\n", p.node, p.speed, p.amplitude,
                number(n1, sizeof n1, "%.8g", p.speed_low), number(n2, sizeof n2, "%.8g", p.speed_high),
                number(af, sizeof af, "%.4g", p.amplification), number(sm, sizeof sm, "%.4g", p.margin),
                number(req, sizeof req, "%.4g", p.required_margin), verdict_word(p.verdict));
    }
}

/* API 617's amplitude check at the retainers: the largest major semi-axis over the range against
 * TD_API617_CLEARANCE_FRACTION of the radial clearance. */
static void print_clearance(FILE *f, const td_model *m, const td_modal_options *opt, const td_clearance_check *c)
{
    int i;
    char a[24], w[24], q[24];
    fprintf(f, "API 617 amplitude at the retainers (close clearances) ");
    if (isfinite(opt->operating_speed_min))
        fprintf(f, "over the operating range");
    else
        fprintf(f, "over the whole sweep (no operating range)");
    fprintf(f, ", limit %g %% of the clearance:\n", 100.0 * TD_API617_CLEARANCE_FRACTION);
    fprintf(f, "  %-8s %-4s %14s %12s %14s %12s  %s\n", "retainer", "node", "clearance [m]", "amp [m]", "at [rad/s]",
            "amp/clear.", "verdict");
    for (i = 0; i < td_model_retainer_count(m); i++)
        fprintf(f, "  %-8d %-4d %14.6g %12s %14s %12s  %s\n", i, c[i].node, c[i].clearance,
                number(a, sizeof a, "%.5g", c[i].amplitude), number(w, sizeof w, "%.8g", c[i].speed),
                number(q, sizeof q, "%.4g", c[i].ratio), verdict_word(c[i].verdict));
}

/* Per AMB sensor: the worst zone along the sweep, and inside the operating range when one is given. */
static void print_zones(FILE *f, const td_model *m, const td_modal_options *opt, const td_modal_api617_results *r)
{
    int i, k, na = td_model_amb_count(m), ns = td_sweep_speed_count(r->sweep);
    fprintf(f, "ISO 14839-2 zones at the AMB sensors along the unbalance response (C_min %.6g m):\n", r->c_min);
    for (i = 0; i < na; i++) {
        int worst = -1, in_range = -1;
        for (k = 0; k < ns; k++) {
            int z = r->zones[(size_t)k * (size_t)na + (size_t)i];
            double w = td_sweep_speed(r->sweep, k);
            worst = z > worst ? z : worst;
            if (w >= opt->operating_speed_min && w <= opt->operating_speed_max && z > in_range)
                in_range = z;
        }
        fprintf(f, "  amb %d: worst zone %s over the sweep", i, td_vibration_zone_name(worst));
        if (isfinite(opt->operating_speed_min))
            fprintf(f, ", %s in the operating range", td_vibration_zone_name(in_range));
        fputc('\n', f);
    }
}

void td_print_api617(FILE *f, const td_model *m, const td_modal_options *opt, const td_modal_api617_results *r)
{
    int i;
    if (r->sweep) {
        fprintf(f, "unbalance response over %.6g..%.6g rad/s (%d speeds, adaptive) at nodes", opt->speed_min,
                opt->speed_max, td_sweep_speed_count(r->sweep));
        for (i = 0; i < td_sweep_node_count(r->sweep); i++)
            fprintf(f, " %d", td_sweep_node(r->sweep, i));
        fputc('\n', f);
        if (isfinite(opt->operating_speed_min))
            fprintf(f, "API 617 peaks (operating range %.6g..%.6g rad/s):\n", opt->operating_speed_min,
                    opt->operating_speed_max);
        else
            fprintf(f, "API 617 peaks (no operating range: modal.operating_speed_min/max not given):\n");
        print_peaks(f, r->sweep);
        if (r->clearance)
            print_clearance(f, m, opt, r->clearance);
        if (r->zones)
            print_zones(f, m, opt, r);
    }
    if (!r->reactions_ok)
        return;
    if (!r->gravity) {
        fprintf(f, "static reactions: none, no gravity in the case\n");
        return;
    }
    fprintf(f, "static reactions under gravity (force on the rotor, N):\n");
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        td_model_get_amb(m, i, &a);
        fprintf(f, "  amb %d, node %d: x %.9g, y %.9g\n", i, a.node, r->amb[2 * i], r->amb[2 * i + 1]);
    }
    for (i = 0; i < td_model_bearing_count(m); i++) {
        td_bearing b;
        td_model_get_bearing(m, i, &b);
        fprintf(f, "  bearing %d, node %d: x %.9g, y %.9g\n", i, b.node, r->bearing[2 * i], r->bearing[2 * i + 1]);
    }
}
