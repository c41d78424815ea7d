/*
 * touchdown report: the one-page drop report of a run file (docs/report.md). No physics here: the
 * quantities are the run's own (its HDF5 attributes, touchdown/result.h), the limits the case's
 * (the case text stored in the file); the report puts them side by side and judges each.
 *
 *   report_read.c    the run file's quantities (by their output names), the limits of its case
 *   report_write.c   the text and JSON forms
 *   report_figure.c  the figure (gnuplot, through the plot tool's script helpers)
 *   cmd_report.c     the command: options, paths, writing the three files whole or not at all
 */
#ifndef TD_TOOLS_REPORT_H
#define TD_TOOLS_REPORT_H

#include <stdio.h>

#include "touchdown/result.h"

/* Most retainers and AMB sensors a report lists (more: the first ones, said in the report). */
#define REPORT_MAX_PARTS 16

/* What the report has of one quantity. */
typedef enum report_state {
    REPORT_VALUE = 0,      /* a number, an answer */
    REPORT_ABSENT = 1,     /* the file has no such name: an older file, or not modelled ("not in this file") */
    REPORT_UNDEFINED = 2,  /* the file has it as NaN: not computed (e.g. no rating given) */
    REPORT_NOT_ANSWER = 3, /* the run did not complete: its numbers are not answers */
    REPORT_NO_RATING = 4   /* life, not written: the case gives the bearing no dynamic rating C */
} report_state;

/* How a quantity is judged against the case's limits. */
typedef enum report_limit {
    REPORT_LIMIT_NONE = 0,        /* no limit applies */
    REPORT_LIMIT_RATIO = 1,       /* a load over its rating: within while <= 1 */
    REPORT_LIMIT_TEMPERATURE = 2, /* limits.temperature_rise, K: within while <= */
    REPORT_LIMIT_DROPS = 3,       /* limits.drops: within while drops to failure >= */
    REPORT_LIMIT_ZONE = 4,        /* an ISO 14839-2 zone (0 A .. 3 D): within up to limits.zone */
    REPORT_LIMIT_STRESS = 5       /* a ball bearing's contact stress: within up to ISO 76's 4200 MPa */
} report_limit;

typedef enum report_verdict {
    REPORT_NOT_JUDGED = 0, /* no value to judge */
    REPORT_NO_LIMIT = 1,   /* a value, no limit given */
    REPORT_WITHIN = 2,
    REPORT_EXCEEDS = 3,
    REPORT_NOT_AT_REST = 4 /* a total of the run within its limit, but the run ended before the rotor came to
                              rest: the drop's total would be larger (td_run_at_rest), so not judged */
} report_verdict;

/* One quantity of the report, as the table in report_read.c declares it. */
typedef struct report_def {
    td_out_id id;      /* its output (lib/io/schema.c declares the name) */
    const char *label; /* in the text */
    int per;           /* 0 the run, 1 each retainer, 2 each AMB sensor */
    report_limit limit;
    td_out_id flag; /* the attribute that says whether it converges (0: flagged); TD_OUT_ID_COUNT: none */
    int run_total;  /* 1: a total over the simulated run that only grows with time (heat, damage) */
} report_def;

/* One line of the report. */
typedef struct report_item {
    const report_def *def;
    int part; /* retainer or sensor number, -1 for the run */
    report_state state;
    double value; /* when state is REPORT_VALUE */
    char units[128];
    int converges; /* 1, 0 (flagged: the file's NAME_converges is 0), -1 not stated */
    double limit;  /* the limit applied, NaN when none */
    report_verdict verdict;
} report_item;

/* The limits of the case (case keys `limits`, `retainers[].bearing`), NaN when not given. */
typedef struct report_limits {
    int read;      /* 1: the case text was read; 0: see why */
    char why[700]; /* why the case text gave no limits */
    double temperature_rise;
    double drops;
    double zones[3]; /* A/B, B/C, C/D as fractions of C_min */
    double zone;     /* the largest acceptable zone (limits.zone), 0 A .. 3 D */
    double static_rating[REPORT_MAX_PARTS];
    double dynamic_rating[REPORT_MAX_PARTS];
} report_limits;

#define REPORT_MAX_ITEMS 512

typedef struct report {
    const char *path;      /* the run file, as given */
    int complete;          /* td_result_complete */
    int flag;              /* td_result_flag */
    char reason[300];      /* incomplete_reason, else "" */
    char description[300]; /* the case's description, else "" */
    char version[64];      /* library_version of the file, else "" */
    char ending[128];      /* summary_ending, else "" */
    double t_start, t_end, t_reached;
    double speed, final_speed; /* the rotor's at the start and at the end, rad/s (NaN: not in the file) */
    int at_rest;               /* td_run_at_rest(speed, final_speed): the totals are those of the whole drop */
    int settled;               /* summary_settled: 1, 0, -1 not in the file or not applicable */
    int nret, namb;            /* in the file (the report lists at most REPORT_MAX_PARTS of each) */
    report_limits lim;
    int n;
    report_item items[REPORT_MAX_ITEMS];
} report;

/* ---- report_read.c ---- */

/* Fill *rep from the open run file r (path as given). Returns 0, or 2 with a line printed for a
 * file that is no run file. */
int report_read(const td_result *r, const char *path, report *rep);
/* The state's words in the text: "not in this file", "not computed", "not an answer". */
const char *report_state_words(report_state s);
/* The verdict's words: "within", "exceeds", "-" (no limit given or nothing to judge), "not judged: ...". */
const char *report_verdict_words(report_verdict v);

/* ---- report_limits.c ---- */

/* The limits of the case whose text (TD_OUT_CASE_TEXT, NULL when the file has none) is given, and
 * its description into desc (n bytes, "" when none): the text read as the case reader reads a case
 * file, with the --set overrides it records. Never fails: a text that cannot be read leaves every
 * limit NaN, lim->read 0 and lim->why saying why. */
void report_case_limits(const char *case_text, int nret, report_limits *lim, char *desc, size_t n);

/* ---- report_write.c ---- */

void report_write_text(FILE *f, const report *rep);
void report_write_json(FILE *f, const report *rep);

/* ---- report_figure.c ---- */

/* Write the figure's data and script into dir and run gnuplot there, giving dir/NAME.png.
 * Returns 0, or 1 with a line printed (gnuplot missing or failed, a file not written). */
int report_figure(const td_result *r, const report *rep, const char *dir, const char *name);

#endif
