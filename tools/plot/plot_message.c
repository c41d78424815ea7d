/*
 * The plot's message about a part of a result file it cannot use, naming the part by the output
 * schema (touchdown/result.h): shared by the run, modal and sweep loaders (plot_file.c,
 * plot_sweep_load.c), below both.
 */
#include "plot/plot.h"

#include <stdio.h>

int plot_bad_part(const char *path, const char *before, td_out_id id, const char *after)
{
    char where[256] = "/";
    if (td_out_place_of(id) == TD_OUT_ATTRIBUTE) /* an attribute by its name, an object by its path */
        snprintf(where, sizeof where, "%s", td_out_name(id));
    else
        td_out_path(id, NULL, where + 1, sizeof where - 1);
    fprintf(stderr, "touchdown plot: %s: %s%s%s\n", path, before, where, after);
    return PLOT_BAD_INPUT;
}
