/*
 * The API 617 unbalance response report in the modal files (api617_output.h): the swept orbits
 * (speeds x response nodes), the peaks with their amplification factors and margins, the static
 * reactions, and in /modes the log decrement of every mode and the disc and sensor nodes that the
 * mode-shape plots mark. HDF5 conventions as modal_writer.c: a "units" attribute on every dataset,
 * axes as dimension scales.
 */
#include "io/api617_output.h"
#include "io/h5_util.h"
#include "io/schema.h"
#include "touchdown/assess.h"

#include <stdlib.h>

/* ---- CSV --------------------------------------------------------------------------------- */

/* "# section: NAME" (NULL: none) and the columns' names, without the line's end. */
static void csv_columns(FILE *f, const char *section, const td_out_id *cols, int n)
{
    int i;
    if (section)
        fprintf(f, "# section: %s\n", section);
    for (i = 0; i < n; i++)
        fprintf(f, "%s%s", i ? "," : "", td_schema_csv(cols[i]));
}

static void csv_sweep(FILE *f, const td_sweep *s)
{
    static const td_out_id cols[] = {TD_OUT_UR_SPEED, TD_OUT_UR_NODE,    TD_OUT_UR_X_AMP,   TD_OUT_UR_X_PHASE,
                                     TD_OUT_UR_Y_AMP, TD_OUT_UR_Y_PHASE, TD_OUT_UR_FORWARD, TD_OUT_UR_BACKWARD,
                                     TD_OUT_UR_MAJOR, TD_OUT_UR_MINOR};
    int k, j;
    csv_columns(f, td_out_name(TD_OUT_UNBALANCE_RESPONSE), cols, 10);
    fputc('\n', f);
    for (k = 0; k < td_sweep_speed_count(s); k++)
        for (j = 0; j < td_sweep_node_count(s); j++) {
            td_orbit o;
            td_sweep_orbit(s, k, j, &o);
            fprintf(f, "%.12g,%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", td_sweep_speed(s, k),
                    td_sweep_node(s, j), o.x_amp, o.x_phase, o.y_amp, o.y_phase, o.forward, o.backward, o.major,
                    o.minor);
        }
    fputc('\n', f);
}

static void csv_peaks(FILE *f, const td_sweep *s)
{
    static const td_out_id cols[] = {TD_OUT_PEAK_NODE,      TD_OUT_PEAK_SPEED,           TD_OUT_PEAK_AMPLITUDE,
                                     TD_OUT_PEAK_SPEED_LOW, TD_OUT_PEAK_SPEED_HIGH,      TD_OUT_PEAK_AMPLIFICATION,
                                     TD_OUT_PEAK_MARGIN,    TD_OUT_PEAK_REQUIRED_MARGIN, TD_OUT_PEAK_VERDICT};
    int i;
    double lo, hi;
    td_sweep_operating_range(s, &lo, &hi);
    fprintf(f, "# %s = %.12g\n# %s = %.12g\n", td_out_name(TD_OUT_PEAK_OPERATING_SPEED_MIN), lo,
            td_out_name(TD_OUT_PEAK_OPERATING_SPEED_MAX), hi);
    csv_columns(f, td_out_name(TD_OUT_RESPONSE_PEAKS), cols, 9);
    fputc('\n', f);
    for (i = 0; i < td_sweep_peak_count(s); i++) {
        td_response_peak p;
        td_sweep_get_peak(s, i, &p);
        fprintf(f, "%d,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%d\n", p.node, p.speed, p.amplitude, p.speed_low,
                p.speed_high, p.amplification, p.margin, p.required_margin, p.verdict);
    }
    fputc('\n', f);
}

/* One row per support: kind ("amb", "bearing"), its index, node, the force's x and y (N). */
static void csv_reactions(FILE *f, const td_modal_results *r)
{
    static const td_out_id cols[] = {TD_OUT_STATIC_SUPPORT, TD_OUT_MODAL_INDEX, TD_OUT_MODAL_NODE};
    const char *const *comp = td_schema_components();
    int i;
    csv_columns(f, td_out_name(TD_OUT_STATIC_REACTIONS), cols, 3);
    for (i = 0; i < 2; i++) { /* the force's components */
        fputc(',', f);
        fprintf(f, td_schema_csv(TD_OUT_STATIC_AMB_FORCE), comp[i]);
    }
    fputc('\n', f);
    for (i = 0; i < td_model_amb_count(r->model); i++) {
        td_amb a;
        td_model_get_amb(r->model, i, &a);
        fprintf(f, "amb,%d,%d,%.12g,%.12g\n", i, a.node, r->static_amb[2 * i], r->static_amb[2 * i + 1]);
    }
    for (i = 0; i < td_model_bearing_count(r->model); i++) {
        td_bearing b;
        td_model_get_bearing(r->model, i, &b);
        fprintf(f, "bearing,%d,%d,%.12g,%.12g\n", i, b.node, r->static_bearing[2 * i], r->static_bearing[2 * i + 1]);
    }
    fputc('\n', f);
}

/* One row per speed and AMB: the zone's name ("A".."D", "undefined"). */
static void csv_zones(FILE *f, const td_modal_results *r)
{
    static const td_out_id cols[] = {TD_OUT_UR_SPEED, TD_OUT_AMB, TD_OUT_UR_SENSOR_ZONE};
    int k, i, na = td_model_amb_count(r->model);
    fprintf(f, "# section: %s\n# %s = %.12g\n", td_out_name(TD_OUT_UR_SENSOR_ZONE), td_out_name(TD_OUT_UR_C_MIN),
            r->zone_c_min);
    csv_columns(f, NULL, cols, 3);
    fputc('\n', f);
    for (k = 0; k < td_sweep_speed_count(r->sweep); k++)
        for (i = 0; i < na; i++)
            fprintf(f, "%.12g,%d,%s\n", td_sweep_speed(r->sweep, k), i,
                    td_vibration_zone_name(r->sensor_zones[(size_t)k * (size_t)na + (size_t)i]));
    fputc('\n', f);
}

/* API 617's amplitude check, one row per retainer, the limit and the range as comment lines. */
static void csv_clearance(FILE *f, const td_modal_results *r)
{
    static const td_out_id cols[] = {TD_OUT_RETAINER, TD_OUT_RC_NODE,  TD_OUT_RC_CLEARANCE, TD_OUT_RC_AMPLITUDE,
                                     TD_OUT_RC_SPEED, TD_OUT_RC_RATIO, TD_OUT_RC_VERDICT};
    double lo, hi;
    int i;
    td_sweep_clearance_range(r->sweep, &lo, &hi);
    fprintf(f, "# section: %s\n# %s = %.12g\n# %s = %.12g\n# %s = %.12g\n", td_out_name(TD_OUT_RUNNING_CLEARANCE),
            td_out_name(TD_OUT_RC_FRACTION), TD_API617_CLEARANCE_FRACTION, td_out_name(TD_OUT_RC_SPEED_MIN), lo,
            td_out_name(TD_OUT_RC_SPEED_MAX), hi);
    csv_columns(f, NULL, cols, 7);
    fputc('\n', f);
    for (i = 0; i < td_model_retainer_count(r->model); i++) {
        const td_clearance_check *c = &r->clearance[i];
        fprintf(f, "%d,%d,%.12g,%.12g,%.12g,%.12g,%d\n", i, c->node, c->clearance, c->amplitude, c->speed, c->ratio,
                c->verdict);
    }
    fputc('\n', f);
}

void td_api617_write_csv_sections(FILE *f, const td_modal_results *r)
{
    if (r->sweep) {
        csv_sweep(f, r->sweep);
        csv_peaks(f, r->sweep);
    }
    if (r->model && r->static_amb && r->static_bearing)
        csv_reactions(f, r);
    if (r->sweep && r->model && r->sensor_zones && td_model_amb_count(r->model) > 0)
        csv_zones(f, r);
    if (r->sweep && r->model && r->clearance && td_model_retainer_count(r->model) > 0)
        csv_clearance(f, r);
}

/* ---- HDF5 -------------------------------------------------------------------------------- */

/* Make dataset `scale` of g a dimension scale, attached to axis `axis` of ids[0 .. n). */
static int h5_scale(hid_t g, td_out_id scale, const td_out_id *ids, int n, unsigned axis)
{
    const char *names[16];
    int i;
    for (i = 0; i < n && i < 15; i++)
        names[i] = td_out_name(ids[i]);
    names[i] = NULL;
    return td_h5_attach(g, td_out_name(scale), names, axis);
}

/* The orbit field c (0 x_amp .. 7 minor, the order of the ids) of o. */
static double orbit_field(const td_orbit *o, int c)
{
    const double v[8] = {o->x_amp, o->x_phase, o->y_amp, o->y_phase, o->forward, o->backward, o->major, o->minor};
    return v[c];
}

/* The zones of the AMB sensors and their C_min in the group g. */
static int h5_zones(hid_t g, const td_modal_results *r)
{
    int ns = td_sweep_speed_count(r->sweep), na = td_model_amb_count(r->model);
    return td_h5_table(g, TD_OUT_UR_SENSOR_ZONE, H5T_NATIVE_INT, r->sensor_zones, (hsize_t)ns, (hsize_t)na) &&
           td_h5_attr_double(g, td_out_name(TD_OUT_UR_C_MIN), r->zone_c_min) >= 0;
}

static int h5_sweep(hid_t file, const td_sweep *s, const td_modal_results *r)
{
    static const td_out_id cols[8] = {TD_OUT_UR_X_AMP,   TD_OUT_UR_X_PHASE,  TD_OUT_UR_Y_AMP, TD_OUT_UR_Y_PHASE,
                                      TD_OUT_UR_FORWARD, TD_OUT_UR_BACKWARD, TD_OUT_UR_MAJOR, TD_OUT_UR_MINOR};
    int ns = td_sweep_speed_count(s), nn = td_sweep_node_count(s), k, j, c, ok;
    double *d = malloc((size_t)ns * (size_t)nn * sizeof *d), *sp = malloc((size_t)ns * sizeof *sp);
    int *nodes = malloc((size_t)nn * sizeof *nodes);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_UNBALANCE_RESPONSE), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = d && sp && nodes && g >= 0;
    for (k = 0; ok && k < ns; k++)
        sp[k] = td_sweep_speed(s, k);
    for (j = 0; ok && j < nn; j++)
        nodes[j] = td_sweep_node(s, j);
    ok = ok && td_h5_table(g, TD_OUT_UR_SPEED, H5T_NATIVE_DOUBLE, sp, (hsize_t)ns, 0) &&
         td_h5_table(g, TD_OUT_UR_NODE, H5T_NATIVE_INT, nodes, (hsize_t)nn, 0);
    for (c = 0; ok && c < 8; c++) {
        for (k = 0; k < ns; k++)
            for (j = 0; j < nn; j++) {
                td_orbit o;
                td_sweep_orbit(s, k, j, &o);
                d[(size_t)k * (size_t)nn + (size_t)j] = orbit_field(&o, c);
            }
        ok = td_h5_table(g, cols[c], H5T_NATIVE_DOUBLE, d, (hsize_t)ns, (hsize_t)nn);
    }
    ok = ok && h5_scale(g, TD_OUT_UR_SPEED, cols, 8, 0) && h5_scale(g, TD_OUT_UR_NODE, cols, 8, 1);
    ok = ok && (!r->model || !r->sensor_zones || td_model_amb_count(r->model) == 0 || h5_zones(g, r));
    if (g >= 0)
        H5Gclose(g);
    free(d);
    free(sp);
    free(nodes);
    return ok;
}

/* The peak field c (0 speed .. 6 required margin, the order of the ids) of p. */
static double peak_field(const td_response_peak *p, int c)
{
    const double v[7] = {p->speed,         p->amplitude, p->speed_low,      p->speed_high,
                         p->amplification, p->margin,    p->required_margin};
    return v[c];
}

static int h5_peaks(hid_t file, const td_sweep *s)
{
    static const td_out_id cols[7] = {TD_OUT_PEAK_SPEED,          TD_OUT_PEAK_AMPLITUDE,     TD_OUT_PEAK_SPEED_LOW,
                                      TD_OUT_PEAK_SPEED_HIGH,     TD_OUT_PEAK_AMPLIFICATION, TD_OUT_PEAK_MARGIN,
                                      TD_OUT_PEAK_REQUIRED_MARGIN};
    int np = td_sweep_peak_count(s), i, c, ok;
    td_response_peak *p = malloc((size_t)(np ? np : 1) * sizeof *p);
    double *d = malloc((size_t)(np ? np : 1) * sizeof *d);
    int *n = malloc(2u * (size_t)(np ? np : 1) * sizeof *n);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_RESPONSE_PEAKS), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    double lo, hi;
    td_sweep_operating_range(s, &lo, &hi);
    ok = p && d && n && g >= 0 && td_h5_attr_double(g, td_out_name(TD_OUT_PEAK_OPERATING_SPEED_MIN), lo) >= 0 &&
         td_h5_attr_double(g, td_out_name(TD_OUT_PEAK_OPERATING_SPEED_MAX), hi) >= 0;
    for (i = 0; ok && i < np; i++) {
        td_sweep_get_peak(s, i, &p[i]);
        n[i] = p[i].node;
        n[np + i] = p[i].verdict;
    }
    for (c = 0; ok && c < 7; c++) {
        for (i = 0; i < np; i++)
            d[i] = peak_field(&p[i], c);
        ok = td_h5_table(g, cols[c], H5T_NATIVE_DOUBLE, d, (hsize_t)np, 0);
    }
    ok = ok && td_h5_table(g, TD_OUT_PEAK_NODE, H5T_NATIVE_INT, n, (hsize_t)np, 0) &&
         td_h5_table(g, TD_OUT_PEAK_VERDICT, H5T_NATIVE_INT, n + np, (hsize_t)np, 0);
    if (g >= 0)
        H5Gclose(g);
    free(p);
    free(d);
    free(n);
    return ok;
}

static int h5_reactions(hid_t file, const td_modal_results *r)
{
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_STATIC_REACTIONS), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int na = td_model_amb_count(r->model), nb = td_model_bearing_count(r->model);
    int ok = g >= 0 && td_h5_table(g, TD_OUT_STATIC_AMB_FORCE, H5T_NATIVE_DOUBLE, r->static_amb, (hsize_t)na, 2) &&
             td_h5_table(g, TD_OUT_STATIC_BEARING_FORCE, H5T_NATIVE_DOUBLE, r->static_bearing, (hsize_t)nb, 2) &&
             td_h5_attr_string(g, "components", td_schema_components_list()) >= 0;
    if (g >= 0)
        H5Gclose(g);
    return ok;
}

/* /running_clearance: API 617's amplitude check, one row per retainer. */
static int h5_clearance(hid_t file, const td_modal_results *r)
{
    static const td_out_id cols[4] = {TD_OUT_RC_CLEARANCE, TD_OUT_RC_AMPLITUDE, TD_OUT_RC_SPEED, TD_OUT_RC_RATIO};
    int n = td_model_retainer_count(r->model), i, c, ok;
    double *d = malloc((size_t)n * sizeof *d), lo, hi;
    int *k = malloc(2u * (size_t)n * sizeof *k);
    hid_t g = H5Gcreate2(file, td_out_name(TD_OUT_RUNNING_CLEARANCE), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    td_sweep_clearance_range(r->sweep, &lo, &hi);
    ok = d && k && g >= 0 && td_h5_attr_double(g, td_out_name(TD_OUT_RC_FRACTION), TD_API617_CLEARANCE_FRACTION) >= 0 &&
         td_h5_attr_double(g, td_out_name(TD_OUT_RC_SPEED_MIN), lo) >= 0 &&
         td_h5_attr_double(g, td_out_name(TD_OUT_RC_SPEED_MAX), hi) >= 0;
    for (i = 0; ok && i < n; i++) {
        k[i] = r->clearance[i].node;
        k[n + i] = r->clearance[i].verdict;
    }
    for (c = 0; ok && c < 4; c++) {
        for (i = 0; i < n; i++) {
            const td_clearance_check *q = &r->clearance[i];
            const double v[4] = {q->clearance, q->amplitude, q->speed, q->ratio};
            d[i] = v[c];
        }
        ok = td_h5_table(g, cols[c], H5T_NATIVE_DOUBLE, d, (hsize_t)n, 0);
    }
    ok = ok && td_h5_table(g, TD_OUT_RC_NODE, H5T_NATIVE_INT, k, (hsize_t)n, 0) &&
         td_h5_table(g, TD_OUT_RC_VERDICT, H5T_NATIVE_INT, k + n, (hsize_t)n, 0);
    if (g >= 0)
        H5Gclose(g);
    free(d);
    free(k);
    return ok;
}

/* In /modes: the log decrement of every mode, and the disc and AMB sensor nodes. */
static int h5_modes_extra(hid_t file, const td_modal_results *r)
{
    int nm = td_modal_mode_count(r->modes), nd = r->model ? td_model_disc_count(r->model) : 0;
    int na = r->model ? td_model_amb_count(r->model) : 0, i, ok;
    double *ld = malloc((size_t)(nm ? nm : 1) * sizeof *ld);
    int *nodes = malloc((size_t)(nd + na ? nd + na : 1) * sizeof *nodes);
    hid_t g = H5Gopen2(file, td_out_name(TD_OUT_MODES), H5P_DEFAULT);
    ok = ld && nodes && g >= 0;
    for (i = 0; ok && i < nm; i++) {
        td_mode m;
        td_modal_get_mode(r->modes, i, &m);
        ld[i] = td_log_decrement(m.zeta);
    }
    for (i = 0; ok && i < nd; i++) {
        td_disc d;
        td_model_get_disc(r->model, i, &d);
        nodes[i] = d.node;
    }
    for (i = 0; ok && i < na; i++) {
        td_amb a;
        td_model_get_amb(r->model, i, &a);
        nodes[nd + i] = a.sensor_node;
    }
    ok = ok && td_h5_table(g, TD_OUT_MODES_LOG_DECREMENT, H5T_NATIVE_DOUBLE, ld, (hsize_t)nm, 0);
    ok = ok && (nd == 0 || td_h5_table(g, TD_OUT_MODES_DISC_NODES, H5T_NATIVE_INT, nodes, (hsize_t)nd, 0));
    ok = ok && (na == 0 || td_h5_table(g, TD_OUT_MODES_SENSOR_NODES, H5T_NATIVE_INT, nodes + nd, (hsize_t)na, 0));
    if (g >= 0)
        H5Gclose(g);
    free(ld);
    free(nodes);
    return ok;
}

const char *td_api617_write_h5(hid_t file, const td_modal_results *r)
{
    if (r->modes && !h5_modes_extra(file, r))
        return "the log decrements in /modes";
    if (r->sweep && !h5_sweep(file, r->sweep, r))
        return "/unbalance_response";
    if (r->sweep && !h5_peaks(file, r->sweep))
        return "/response_peaks";
    if (r->model && r->static_amb && r->static_bearing && !h5_reactions(file, r))
        return "/static_reactions";
    if (r->sweep && r->model && r->clearance && td_model_retainer_count(r->model) > 0 && !h5_clearance(file, r))
        return "/running_clearance";
    return NULL;
}
