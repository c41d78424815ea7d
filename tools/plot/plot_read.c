/*
 * The plot's length-checked readers of a result file's arrays: shared by the modal loaders
 * (plot_file.c, plot_loop.c, plot_api617.c), below all of them, so that no call cycle joins them.
 */
#include "plot/plot.h"

double *plot_read_vector(const td_result *r, td_out_id id, const char *sub, size_t n)
{
    td_result_array a;
    if (td_result_read(r, id, sub, &a, NULL) != TD_OK)
        return NULL;
    if (a.n != n) {
        td_result_array_free(&a);
        return NULL;
    }
    return a.v;
}

int plot_read_optional(const td_result *r, td_out_id id, const char *sub, size_t n, double **out)
{
    *out = NULL;
    if (!td_result_has(r, id, sub))
        return 0;
    *out = plot_read_vector(r, id, sub, n);
    return *out ? 0 : -1;
}
