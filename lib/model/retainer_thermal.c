/*
 * The retainers' thermal networks (touchdown/model.h td_retainer_thermal), kept by retainer beside
 * the retainers themselves: a retainer without one has no entry.
 */
#include "model/model_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const td_error_site no_site = {NULL, 0, NULL};

/* Fail naming retainer i's thermal field at fault. */
static td_status bad(td_error *err, int i, const char *field, const char *rule, double v)
{
    return td_error_set_site(err, TD_ERR_INVALID, &(td_error_site){"retainer", i, field}, &no_site, "must %s (got %g)",
                             rule, v);
}

static td_status check_thermal(const td_retainer_thermal *t, int i, td_error *err)
{
    if (!(isfinite(t->race_capacity) && t->race_capacity > 0.0))
        return bad(err, i, "thermal.race_capacity", "be > 0", t->race_capacity);
    if (!(isfinite(t->housing_capacity) && t->housing_capacity > 0.0))
        return bad(err, i, "thermal.housing_capacity", "be > 0", t->housing_capacity);
    if (!(isfinite(t->race_housing_conductance) && t->race_housing_conductance > 0.0))
        return bad(err, i, "thermal.race_housing_conductance", "be > 0", t->race_housing_conductance);
    if (!(isfinite(t->housing_ambient_conductance) && t->housing_ambient_conductance >= 0.0))
        return bad(err, i, "thermal.housing_ambient_conductance", "be >= 0", t->housing_ambient_conductance);
    if (!td_is_undefined(t->expansion) && !(isfinite(t->expansion) && t->expansion >= 0.0))
        return bad(err, i, "thermal.expansion", "be >= 0 (or undefined: not given)", t->expansion);
    return TD_OK;
}

/* The entry of retainer i, NULL if it has none. */
static td_model_thermal *entry_of(const td_model *m, int i)
{
    int j;
    for (j = 0; j < m->thermals.count; j++)
        if (m->thermals.items[j].retainer == i)
            return &m->thermals.items[j];
    return NULL;
}

td_status td_model_set_retainer_thermal(td_model *m, int i, const td_retainer_thermal *t, td_error *err)
{
    td_model_thermal *e;
    td_status st;
    if (!m || !t)
        return td_error_set(err, TD_ERR_INVALID, "retainer thermal: NULL argument");
    if (i < 0 || i >= m->retainers.count)
        return td_error_set(err, TD_ERR_INVALID, "retainer thermal: retainer %d out of range (there are %d)", i,
                            m->retainers.count);
    if ((st = check_thermal(t, i, err)) != TD_OK)
        return st;
    e = entry_of(m, i);
    if (!e) {
        if (m->thermals.count == m->thermals.capacity) {
            int cap = m->thermals.capacity ? 2 * m->thermals.capacity : 4;
            td_model_thermal *p = realloc(m->thermals.items, (size_t)cap * sizeof *p);
            if (!p)
                return td_error_set(err, TD_ERR_NOMEM, "out of memory adding a retainer's thermal network");
            m->thermals.items = p;
            m->thermals.capacity = cap;
        }
        e = &m->thermals.items[m->thermals.count++];
        e->retainer = i;
    }
    e->t = *t;
    td_error_clear(err);
    return TD_OK;
}

int td_model_get_retainer_thermal(const td_model *m, int i, td_retainer_thermal *out)
{
    const td_model_thermal *e = m ? entry_of(m, i) : NULL;
    if (out) {
        if (e)
            *out = e->t;
        else
            memset(out, 0, sizeof *out);
    }
    return e != NULL;
}
