/*
 * The Hertz contact of touchdown/assess.h as a command, for hertz_reference.py. Reads lines from
 * stdin and prints one line of results for each, %.17g:
 *   point LOAD RX RY MODULUS                           -> a b p_max  (td_hertz_point; "invalid" if refused)
 *   ball LOAD BALLS BALL_DIAMETER PITCH_DIAMETER FI    -> p_max      (td_ball_inner_contact_stress)
 */
#include "touchdown/assess.h"

#include <stdio.h>
#include <string.h>

int main(void)
{
    char line[512], kind[16];
    while (fgets(line, sizeof line, stdin)) {
        double v[5];
        int z;
        if (sscanf(line, "%15s", kind) != 1)
            continue;
        if (strcmp(kind, "point") == 0 && sscanf(line, "%*s %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3]) == 4) {
            td_hertz_contact h;
            if (td_hertz_point(v[0], v[1], v[2], v[3], &h) == TD_OK)
                printf("%.17g %.17g %.17g\n", h.a, h.b, h.p_max);
            else
                printf("invalid\n");
        } else if (strcmp(kind, "ball") == 0 &&
                   sscanf(line, "%*s %lf %d %lf %lf %lf", &v[0], &z, &v[1], &v[2], &v[3]) == 5) {
            printf("%.17g\n", td_ball_inner_contact_stress(v[0], z, v[1], v[2], v[3]));
        } else {
            printf("bad line\n");
        }
        fflush(stdout);
    }
    return 0;
}
