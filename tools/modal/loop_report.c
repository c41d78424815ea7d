/* The loop analysis part of `touchdown modal`: the text table and the --json object. */
#include "modal/modal_print.h"
#include "touchdown/modal_output.h"

#include <stdlib.h>

/* "stable", "marginally stable (undamped modes)" (no eigenvalue grows, some real part is zero to
 * rounding: an undamped shaft's mode the AMBs do not see) or "NOT STABLE: no sensitivity". */
static const char *loop_word(const td_loop *l)
{
    if (!td_loop_stable(l))
        return "NOT STABLE: no sensitivity";
    return td_loop_max_real_part(l) < 0.0 ? "stable" : "marginally stable (undamped modes)";
}

void td_print_loop(FILE *f, const td_loop *l)
{
    int j;
    fprintf(f,
            "loop analysis at %.12g rad/s (ISO 14839-3: sensitivity at each amplifier input, every loop closed): %s, "
            "largest real part %.6g 1/s\n",
            td_loop_speed(l), loop_word(l), td_loop_max_real_part(l));
    if (td_loop_sample_rate(l) > 0.0)
        fprintf(f,
                "  sampled at %.12g Hz: the sampled axes' loop at the sample instants (zero-order hold), up to the "
                "Nyquist frequency %.12g Hz\n",
                td_loop_sample_rate(l), 0.5 * td_loop_sample_rate(l));
    if (!td_loop_stable(l))
        return;
    fprintf(f, "  %-6s %-4s %14s %16s  %s\n", "axis", "amb", "peak |S|", "at f [Hz]", "zone");
    for (j = 0; j < td_loop_axis_count(l); j++) {
        int a = td_loop_axis(l, j);
        fprintf(f, "  %-6d %-2d %c  %14.6g %16.6g  %c\n", a, a / 2, a % 2 ? 'y' : 'x', td_loop_sensitivity_peak(l, j),
                td_loop_sensitivity_peak_frequency(l, j), td_loop_sensitivity_zone(l, j));
    }
    fprintf(f, "  worst zone %c (A < 3 <= B < 4 <= C < 5 <= D, ISO 14839-3:2006 \"Evaluation of stability margin\")\n",
            td_loop_worst_zone(l));
}

int td_print_loop_json(FILE *f, const td_loop *l)
{
    int n = td_loop_json(NULL, 0, l);
    char *buf = malloc((size_t)n + 1u);
    if (!buf)
        return 1;
    td_loop_json(buf, (size_t)n + 1u, l);
    fprintf(f, "%s\n", buf);
    free(buf);
    return 0;
}
