/* The rainflow counter (touchdown/assess.h) as a filter for tests/life/rainflow_reference.py: the
 * history's values on stdin, one a line, after the gate on the first line; on stdout one line per
 * counted cycle, "range mean count" with 17 digits, the cycles closed as the values came and then
 * those of the end (td_rainflow_residue). Exit 1 on a value the counter refuses. */
#include "touchdown/assess.h"

#include <stdio.h>
#include <stdlib.h>

static void print_cycle(void *user, double range, double mean, double count)
{
    (void)user;
    printf("%.17g %.17g %.17g\n", range, mean, count);
}

int main(void)
{
    double gate, x;
    td_error err;
    td_rainflow *rf;
    if (scanf("%lf", &gate) != 1)
        return 1;
    rf = td_rainflow_create(gate, &err);
    if (!rf) {
        fprintf(stderr, "rainflow_probe: %s\n", err.message);
        return 1;
    }
    while (scanf("%lf", &x) == 1)
        if (td_rainflow_add(rf, x, print_cycle, NULL, &err) != TD_OK) {
            fprintf(stderr, "rainflow_probe: %s\n", err.message);
            td_rainflow_free(&rf);
            return 1;
        }
    td_rainflow_residue(rf, print_cycle, NULL);
    td_rainflow_free(&rf);
    return 0;
}
