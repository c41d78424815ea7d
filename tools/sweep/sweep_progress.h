/* touchdown sweep: the progress line on stderr (tools/sweep/sweep_progress.c). */
#ifndef TD_TOOLS_SWEEP_PROGRESS_H
#define TD_TOOLS_SWEEP_PROGRESS_H

/* Off, one line rewritten in place on a terminal, or a line every few seconds into a log. */
typedef enum { SWEEP_PROGRESS_OFF, SWEEP_PROGRESS_TERMINAL, SWEEP_PROGRESS_LOG } sweep_progress_mode;

/* Where the sweep stands: points in all, with a row (resumed ones included), running, failed;
 * the seconds left (< 0: not known yet). */
typedef struct sweep_status {
    long points, done, running, failed;
    double eta;
} sweep_status;

typedef struct sweep_progress {
    sweep_progress_mode mode;
    double last; /* when the line was last printed (monotonic s) */
    int width;   /* of the line last printed on the terminal, to blank what it was longer by */
} sweep_progress;

/* The mode for --progress (forced = 1), --no-progress (forced = 0) or neither (-1: on when
 * stderr is a terminal and the sweep prints text). */
sweep_progress_mode sweep_progress_choose(int forced, int quiet_or_json);

/* Print the line if it is due (at most 4 a second on a terminal, one every 5 s into a log); with
 * `final` print it whatever the time and end it with a newline. */
void sweep_progress_show(sweep_progress *p, const sweep_status *s, double now, int final);

/* Blank the line on a terminal, before another line goes to stderr (it is printed again when due). */
void sweep_progress_clear(sweep_progress *p);

#endif
