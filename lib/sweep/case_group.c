/*
 * The case file's `sweep` group (touchdown/sweep.h): its specs, kept by the case reader as they
 * were written (td_cr_sweep_spec, case/case_sweep_specs.h), judged here by the grid's rules on a
 * dry grid (counts only, no values), then added to a grid after the caller's own axes. The error names the entry and
 * the setting at fault as the case reader names its own ("FILE:LINE: sweep.vary[i].points: why"), so that a bad group
 * reads the same whichever stage finds it.
 */
#include "case/case_message.h"     /* td_cr_printable, td_cr_fail_file */
#include "case/case_sweep_specs.h" /* the group as read */
#include "sweep/sweep_internal.h"
#include "util/error_internal.h"

#include <string.h>

/* The setting of entry s a failed rule's part names (NULL: the entry itself): the members the
 * case file writes a spec's parts in (docs/case-format.md, "sweep"). */
static const char *part_setting(td_sweep_part part, const td_cr_sweep_spec *s)
{
    static const char *const names[TD_SWEEP_PART_COUNT] = {
        [TD_SWEEP_PART_SPEC] = NULL,      [TD_SWEEP_PART_KEY] = "key",  [TD_SWEEP_PART_START] = "from",
        [TD_SWEEP_PART_STOP] = "to",      [TD_SWEEP_PART_N] = "points", [TD_SWEEP_PART_SPACING] = "spacing",
        [TD_SWEEP_PART_VALUES] = "values"};
    if (part == TD_SWEEP_PART_COUNT)
        return s->values ? "values" : "points";
    return names[part];
}

td_status td_sweep_check_case(const td_case *c, td_error *err)
{
    char reason[TD_ERROR_MESSAGE_SIZE], context[TD_CR_SWEEP_CONTEXT_SIZE], shown[1024];
    const td_cr_sweep_spec *s;
    td_sweep_grid *dry = NULL;
    td_sweep_part part;
    td_status st = TD_OK;
    int i;
    if (!c)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_check_case: NULL argument");
    if (td_case_sweep_specs(c) == 0)
        return TD_OK;
    if (td_sweep_grid_create_dry(&dry, NULL) != TD_OK)
        return td_cr_fail_file(err, TD_ERR_NOMEM, td_cr_printable(td_case_path(c), shown, sizeof shown), 0,
                               "out of memory");
    for (i = 0; st == TD_OK && i < td_case_sweep_specs(c); i++) {
        s = td_cr_sweep_entry(c, i);
        if (td_sweep_grid_add(dry, s->spec, s->with, "", &part, reason, sizeof reason) != TD_OK) {
            td_cr_sweep_context(s, part_setting(part, s), context, sizeof context);
            st = td_error_set_reason(err, TD_ERR_PARSE, context, reason);
        }
    }
    td_sweep_grid_free(&dry);
    return st;
}

/* 1 if `spec` sweeps one of the first `own` keys of g. */
static int spec_is_swept(const td_sweep_grid *g, int own, const char *spec)
{
    int i;
    for (i = 0; i < own; i++) {
        size_t len = strlen(td_sweep_grid_key(g, i));
        if (!strncmp(spec, td_sweep_grid_key(g, i), len) && spec[len] == '=')
            return 1;
    }
    return 0;
}

/* The case's specs [first, *end) of one axis; 1 if the grid's own keys (the first `own`) sweep
 * any of them, which then replaces the whole axis. */
static int case_axis(const td_sweep_grid *g, int own, const td_case *c, int first, int *end)
{
    int i, with = 0, n = td_case_sweep_specs(c), taken = 0;
    for (i = first; i < n; i++) {
        const char *spec = td_case_sweep_spec(c, i, &with, NULL);
        if (i > first && !with)
            break;
        taken = taken || spec_is_swept(g, own, spec);
    }
    *end = i;
    return taken;
}

td_status td_sweep_grid_from_case(td_sweep_grid *g, const td_case *c, td_error *err)
{
    char reason[TD_ERROR_MESSAGE_SIZE];
    int i, j, end, own, with;
    td_sweep_part part;
    const char *where, *spec, *origin = NULL;
    td_status st;
    if (!g || !c)
        return td_error_set(err, TD_ERR_INVALID, "td_sweep_grid_from_case: NULL argument");
    if ((st = td_sweep_check_case(c, err)) != TD_OK)
        return st;
    own = td_sweep_grid_keys(g);
    for (i = 0; i < td_case_sweep_specs(c); i = end) {
        if (case_axis(g, own, c, i, &end))
            continue;
        for (j = i; j < end; j++) {
            spec = td_case_sweep_spec(c, j, &with, &where);
            if (j == i)
                origin = where;
            if (td_sweep_grid_add(g, spec, j > i, origin, &part, reason, sizeof reason) != TD_OK)
                return td_error_set_reason(err, TD_ERR_PARSE, where, reason);
        }
    }
    return TD_OK;
}
