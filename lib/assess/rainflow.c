/*
 * Rainflow counting, online (touchdown/assess.h td_rainflow): ASTM E1049-85 (2017) 5.4.4, its
 * steps 1-6 on a stack of reversals, with a hysteresis gate in front of the peak-valley step.
 *
 * The stack holds the reversals not yet discarded, the history's first point at the bottom (the
 * standard's starting point S, moved up by step 5). After every push the three-point rule runs
 * (steps 2-5), so the ranges along the stack always shrink from bottom to top: X < Y for every
 * three neighbours. The last extreme since the last reversal is held apart (`cand`): it is not a
 * reversal until the history has moved back from it by more than the gate, and at the end of the
 * history it is the last point (step 1, "out of data": the standard reads the last point as a
 * peak or valley too).
 */
#include "touchdown/assess.h"
#include "util/error_internal.h"

#include <math.h>
#include <stdlib.h>

struct td_rainflow {
    double gate;
    double *stack; /* the reversals kept, stack[0] the starting point */
    size_t len, cap;
    double cand; /* the extreme reached since the last reversal (the last value while dir == 0) */
    int dir;     /* +1 rising towards cand, -1 falling, 0: not yet moved from the start by more than the gate */
    long values;
};

#define TD_RAINFLOW_START_CAP 16

td_rainflow *td_rainflow_create(double gate, td_error *err)
{
    td_rainflow *rf;
    if (!isfinite(gate) || gate < 0.0) {
        td_error_set(err, TD_ERR_INVALID, "rainflow: the hysteresis gate must be a finite number >= 0");
        return NULL;
    }
    rf = calloc(1, sizeof *rf);
    if (rf)
        rf->stack = malloc(TD_RAINFLOW_START_CAP * sizeof *rf->stack);
    if (!rf || !rf->stack) {
        if (rf)
            free(rf);
        td_error_set(err, TD_ERR_NOMEM, "rainflow: out of memory");
        return NULL;
    }
    rf->cap = TD_RAINFLOW_START_CAP;
    rf->gate = gate;
    return rf;
}

void td_rainflow_free(td_rainflow **rf)
{
    if (!rf || !*rf)
        return;
    free((*rf)->stack);
    free(*rf);
    *rf = NULL;
}

long td_rainflow_values(const td_rainflow *rf)
{
    return rf ? rf->values : 0;
}

/* Steps 2-5 on the stack after a push: while the latest range X is not smaller than the one before
 * it, Y, Y closes: a half cycle when it holds the starting point (discarded, the start moves up),
 * else a full cycle (its two points discarded). */
static void three_point(td_rainflow *rf, td_rainflow_cycle_fn fn, void *user)
{
    double *s = rf->stack;
    while (rf->len >= 3) {
        size_t n = rf->len;
        double x = fabs(s[n - 1] - s[n - 2]), y = fabs(s[n - 2] - s[n - 3]);
        if (x < y)
            break;
        if (n == 3) {
            if (fn)
                fn(user, y, 0.5 * (s[0] + s[1]), 0.5);
            s[0] = s[1];
            s[1] = s[2];
            rf->len = 2;
        } else {
            if (fn)
                fn(user, y, 0.5 * (s[n - 2] + s[n - 3]), 1.0);
            s[n - 3] = s[n - 1];
            rf->len = n - 2;
        }
    }
}

/* Room for one more reversal; 0 when the stack cannot grow. */
static int room(td_rainflow *rf)
{
    double *grown;
    if (rf->len < rf->cap)
        return 1;
    grown = realloc(rf->stack, 2 * rf->cap * sizeof *grown);
    if (!grown)
        return 0;
    rf->stack = grown;
    rf->cap *= 2;
    return 1;
}

td_status td_rainflow_add(td_rainflow *rf, double value, td_rainflow_cycle_fn fn, void *user, td_error *err)
{
    if (!rf || !isfinite(value))
        return td_error_set(err, TD_ERR_INVALID, "rainflow: a value of the history is not a finite number");
    if (rf->values == 0) { /* the starting point (capacity from td_rainflow_create) */
        rf->stack[rf->len++] = value;
        rf->cand = value;
    } else if (rf->dir == 0) {
        if (fabs(value - rf->stack[0]) > rf->gate) {
            rf->dir = value > rf->stack[0] ? 1 : -1;
            rf->cand = value;
        }
    } else if ((value - rf->cand) * rf->dir > 0.0) {
        rf->cand = value; /* further the same way: the extreme moves on */
    } else if (fabs(rf->cand - value) > rf->gate) {
        if (!room(rf))
            return td_error_set(err, TD_ERR_NOMEM, "rainflow: out of memory (%zu reversals kept)", rf->len);
        rf->stack[rf->len++] = rf->cand; /* step 1: a reversal */
        three_point(rf, fn, user);
        rf->dir = -rf->dir;
        rf->cand = value;
    }
    rf->values++;
    return TD_OK;
}

/* Step 1 at the end of the data (the last extreme read as a reversal) and steps 2-5 on a view of
 * the stack, s[lo..hi-1] followed by that extreme e, which the rule never discards (the full
 * cycles it closes are the two points below it, a half cycle is the bottom one); then step 6. */
void td_rainflow_residue(const td_rainflow *rf, td_rainflow_cycle_fn fn, void *user)
{
    const double *s;
    size_t lo = 0, hi, i;
    double e;
    if (!rf || rf->len == 0 || !fn)
        return;
    s = rf->stack;
    hi = rf->len;
    if (rf->dir != 0) {
        e = rf->cand;
        while (hi - lo >= 2) {
            double x = fabs(e - s[hi - 1]), y = fabs(s[hi - 1] - s[hi - 2]);
            if (x < y)
                break;
            if (hi - lo == 2) {
                fn(user, y, 0.5 * (s[lo] + s[lo + 1]), 0.5);
                lo++;
            } else {
                fn(user, y, 0.5 * (s[hi - 1] + s[hi - 2]), 1.0);
                hi -= 2;
            }
        }
    }
    for (i = lo; i + 1 < hi; i++) /* step 6: every range left, a half cycle */
        fn(user, fabs(s[i + 1] - s[i]), 0.5 * (s[i + 1] + s[i]), 0.5);
    if (rf->dir != 0)
        fn(user, fabs(rf->cand - s[hi - 1]), 0.5 * (rf->cand + s[hi - 1]), 0.5);
}
