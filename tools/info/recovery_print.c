/* `touchdown info`'s account of a case's recovery supervisor (touchdown/model.h td_recovery). */
#include "info/recovery_print.h"
#include "info/controller_print.h"

#include <math.h>

/* The smallest retainer clearance c, m (the model has a retainer: a supervisor's rule). */
static double smallest_clearance(const td_model *m)
{
    double c = INFINITY;
    int i;
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_model_get_retainer(m, i, &r);
        c = fmin(c, r.clearance);
    }
    return c;
}

/* One rule: the threshold as a fraction of c and in m, its dwell in s and in whole samples. */
static void print_rule(FILE *f, const char *what, const char *sign, const td_recovery_rule *u, double c, double rate)
{
    fprintf(f, "             %s when the sensed radius %s %g c = %g m for %g s (%g samples at %g Hz)\n", what, sign,
            u->radius_fraction, u->radius_fraction * c, u->dwell, td_recovery_dwell_samples(u->dwell, rate), rate);
}

void td_print_recovery(FILE *f, const td_model *m)
{
    td_recovery rec;
    double c, rate;
    int p, pairs = td_model_get_recovery(m, &rec);
    if (pairs == 0)
        return;
    c = smallest_clearance(m);
    td_controller_view a, b;
    td_controller_view_get(m, rec.nominal[0], &a);
    rate = a.sample_rate;
    fprintf(f, "recovery     supervisor %s, %d pair%s (c = %g m, the smallest retainer clearance)\n",
            rec.enabled ? "on" : "off (enabled = false: the nominal laws throughout)", pairs, pairs == 1 ? "" : "s", c);
    for (p = 0; p < pairs; p++) {
        td_controller_view_get(m, rec.nominal[p], &a);
        td_controller_view_get(m, rec.controller[p], &b);
        fprintf(f, "             pair %d: controller %d \"%s\" -> controller %d \"%s\" (standing by)\n", p,
                rec.nominal[p], a.name, rec.controller[p], b.name);
    }
    print_rule(f, "detect ", ">", &rec.detect, c, rate);
    print_rule(f, "release", "<", &rec.release, c, rate);
    fprintf(f, "             blend %g s, linear from the old law's current to the new one's\n", rec.blend);
}
