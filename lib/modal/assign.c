/*
 * The optimal assignment (linear sum assignment problem) by the Hungarian algorithm with row and
 * column potentials (Kuhn 1955, Munkres 1957; the O(n^2 m) shortest augmenting path form, Jonker &
 * Volgenant 1987): the Campbell diagram's branch tracking matches the modes of one speed to those of
 * the next by it (lib/modal/campbell.c).
 */
#include "modal/modal_internal.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>

/* Work arrays, 1-based as in the textbook form (index 0 is the virtual start row/column). */
typedef struct assign_work {
    double *u, *v, *minv; /* row and column potentials, least reduced cost to each column */
    int *p, *way;         /* p[j]: row assigned to column j (0: none); way[j]: previous column on the path */
    char *used;
} assign_work;

/* Add row i to the assignment: grow the alternating tree from it by Dijkstra on the reduced costs
 * cost(i, j) - u[i] - v[j] >= 0 until a free column is reached, then flip the path. */
static void augment(const double *cost, int m, int i, assign_work *w)
{
    int j, j0 = 0, j1 = 0;
    w->p[0] = i;
    for (j = 0; j <= m; j++) {
        w->minv[j] = INFINITY;
        w->used[j] = 0;
    }
    do {
        int i0 = w->p[j0];
        double delta = INFINITY;
        w->used[j0] = 1;
        for (j = 1; j <= m; j++) {
            double cur;
            if (w->used[j])
                continue;
            cur = cost[(size_t)(i0 - 1) * (size_t)m + (size_t)(j - 1)] - w->u[i0] - w->v[j];
            if (cur < w->minv[j]) {
                w->minv[j] = cur;
                w->way[j] = j0;
            }
            if (w->minv[j] < delta) {
                delta = w->minv[j];
                j1 = j;
            }
        }
        for (j = 0; j <= m; j++) {
            if (w->used[j]) {
                w->u[w->p[j]] += delta;
                w->v[j] -= delta;
            } else {
                w->minv[j] -= delta;
            }
        }
        j0 = j1;
    } while (w->p[j0] != 0);
    do {
        j1 = w->way[j0];
        w->p[j0] = w->p[j1];
        j0 = j1;
    } while (j0 != 0);
}

td_status td_assign_min_cost(const double *cost, int n, int m, int *row_to_col, td_error *err)
{
    assign_work w;
    int i, j;
    td_status st = TD_OK;
    if (!cost || !row_to_col || n < 0 || m < n)
        return td_error_set(err, TD_ERR_INVALID, "td_assign_min_cost: needs rows <= columns");
    for (i = 0; i < n * m; i++)
        if (!isfinite(cost[i]))
            return td_error_set(err, TD_ERR_INVALID, "td_assign_min_cost: cost not finite");
    w.u = calloc((size_t)n + 1, sizeof *w.u);
    w.v = calloc((size_t)m + 1, sizeof *w.v);
    w.minv = calloc((size_t)m + 1, sizeof *w.minv);
    w.p = calloc((size_t)m + 1, sizeof *w.p);
    w.way = calloc((size_t)m + 1, sizeof *w.way);
    w.used = calloc((size_t)m + 1, 1);
    if (!w.u || !w.v || !w.minv || !w.p || !w.way || !w.used)
        st = td_error_set(err, TD_ERR_NOMEM, "td_assign_min_cost: out of memory");
    for (i = 1; st == TD_OK && i <= n; i++)
        augment(cost, m, i, &w);
    for (j = 1; st == TD_OK && j <= m; j++)
        if (w.p[j] > 0)
            row_to_col[w.p[j] - 1] = j - 1;
    free(w.u);
    free(w.v);
    free(w.minv);
    free(w.p);
    free(w.way);
    free(w.used);
    return st;
}
