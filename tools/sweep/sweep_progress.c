/*
 * touchdown sweep: the progress line. On a terminal one line is rewritten in place ('\r') at most
 * four times a second, so that it costs nothing beside the points and leaves the terminal as it
 * was; into a log (--progress with stderr not a terminal) a whole line every five seconds, which
 * a log keeps readable, and always a last line with the final counts.
 *
 *   sweep: 37/100 points, 4 running, 1 failed, ETA 1m20s
 */
#include "sweep/sweep_progress.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

sweep_progress_mode sweep_progress_choose(int forced, int quiet_or_json)
{
    int tty = isatty(STDERR_FILENO);
    if (forced == 0 || (forced < 0 && (quiet_or_json || !tty)))
        return SWEEP_PROGRESS_OFF;
    return tty ? SWEEP_PROGRESS_TERMINAL : SWEEP_PROGRESS_LOG;
}

/* "1h02m", "3m20s", "45s", "--" (not known yet). */
static void format_eta(char *buf, size_t n, double eta)
{
    long s = (long)(eta + 0.5);
    if (eta < 0.0)
        snprintf(buf, n, "--");
    else if (s >= 3600)
        snprintf(buf, n, "%ldh%02ldm", s / 3600, s / 60 % 60);
    else if (s >= 60)
        snprintf(buf, n, "%ldm%02lds", s / 60, s % 60);
    else
        snprintf(buf, n, "%lds", s);
}

void sweep_progress_show(sweep_progress *p, const sweep_status *s, double now, int final)
{
    char eta[32], line[160];
    int n;
    if (p->mode == SWEEP_PROGRESS_OFF)
        return;
    if (!final && now - p->last < (p->mode == SWEEP_PROGRESS_TERMINAL ? 0.25 : 5.0))
        return;
    p->last = now;
    format_eta(eta, sizeof eta, s->eta);
    n = snprintf(line, sizeof line, "sweep: %ld/%ld points, %ld running, %ld failed, ETA %s", s->done, s->points,
                 s->running, s->failed, eta);
    if (p->mode == SWEEP_PROGRESS_LOG) {
        fprintf(stderr, "%s\n", line);
        return;
    }
    /* blank the rest of a longer line printed before */
    fprintf(stderr, "\r%s%*s%s", line, p->width > n ? p->width - n : 0, "", final ? "\n" : "");
    fflush(stderr);
    p->width = final ? 0 : n;
}

void sweep_progress_clear(sweep_progress *p)
{
    if (p->mode != SWEEP_PROGRESS_TERMINAL || p->width == 0)
        return;
    fprintf(stderr, "\r%*s\r", p->width, "");
    p->width = 0;
    p->last = 0.0;
}
