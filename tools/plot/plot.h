/*
 * touchdown plot: declarations shared by the plot_*.c files (no physics here: the tool only reads
 * result files, writes gnuplot data + scripts, and runs gnuplot).
 *
 *   plot_file.c    a simulation or modal result file loaded into memory (touchdown/result.h)
 *   plot_script.c  output directory, data files, script preamble, running gnuplot
 *   plot_sim.c     figures of one simulation file (orbit, radial displacement + force, AMB forces)
 *   plot_modal.c   figures of one modal file (Campbell diagram, mode shapes)
 *   plot_compare.c overlays of several simulation files
 * The gnuplot text is in the templates tools/plot/gp/NAME.gp (docs/plotting.md): the figure files write
 * the data and the variables a template reads, then the template itself.
 */
#ifndef TD_TOOLS_PLOT_H
#define TD_TOOLS_PLOT_H

#include <stddef.h>
#include <stdio.h>

#include "touchdown/result.h"

/* Exit-code-like results of the plot helpers (see cli.h): 0 ok, 1 failed, 2 bad input. */
enum { PLOT_OK = 0, PLOT_FAILED = 1, PLOT_BAD_INPUT = 2 };

/* Most mode shapes in one figure (--modes). */
#define PLOT_MAX_MODES 16

/* Longest path the tool builds. */
#define PLOT_PATH_SIZE 4096

/* ---- plot_file.c: result files in memory --------------------------------------------------- */

typedef enum plot_kind { PLOT_KIND_SIM, PLOT_KIND_MODAL, PLOT_KIND_SWEEP } plot_kind;

/* Most swept keys a sweep table's figures use (touchdown/sweep.h TD_SWEEP_MAX_KEYS). */
#define PLOT_SWEEP_MAX_KEYS 16

/* A sweep table (touchdown sweep): its swept keys and what the figures read of each point. */
typedef struct plot_sweep {
    size_t n; /* points */
    int nkeys;
    char key[PLOT_SWEEP_MAX_KEYS][128];
    int numeric[PLOT_SWEEP_MAX_KEYS];   /* 1: the key's values are numbers */
    int axis[PLOT_SWEEP_MAX_KEYS];      /* the grid axis of the key (zipped keys share one) */
    double *value[PLOT_SWEEP_MAX_KEYS]; /* n each (numeric keys), else NULL */
    char **text[PLOT_SWEEP_MAX_KEYS];   /* n each: the values as text */
    int *regime;                        /* n: td_regime, -1 when the table has no regime column */
    int *failed;                        /* n: 1 if the point did not run to its end (status not "success") */
    char **status;                      /* n: the points' status, NULL when the table has no status column */
    double *section_count;              /* n: crossings of each point's section (NaN: unknown) */
    size_t m;                           /* section radii per point (0: the table has none) */
    double *section;                    /* n x m, m, NaN-padded */
    double *clearance;                  /* n, m (NaN: unknown) */
} plot_sweep;

/* One event, reduced to what the figures use. */
typedef struct plot_event {
    double time;
    int retainer;
    char kind[32]; /* the file's enum name: contact_onset, release, schedule, ... */
} plot_event;

/* Time window (s) and the samples it keeps. */
typedef struct plot_window {
    double from, to; /* -HUGE_VAL / +HUGE_VAL when not given */
} plot_window;

/* A simulation file: samples inside the time window, SI units as in the file. */
typedef struct plot_sim {
    size_t n;  /* samples kept */
    double *t; /* n */
    int nret, namb;
    double *x, *y, *r, *fn, *contact; /* n x nret, row-major */
    double *amb;                      /* n x namb x 2 */
    double *clearance;                /* nret, NAN when the file has no retainer_clearance */
    long *ret_nodes;                  /* nret, -1 when unknown */
    long *amb_nodes;                  /* namb, -1 when unknown */
    plot_event *ev;                   /* events inside the window */
    size_t nev;
    /* housing motion */
    double *housing;  /* n x 6: the housing's acceleration x, y [m/s^2] and displacement x, y [m], then a housing
                         body's displacement x, y [m] (0 without one); NULL: the file has no housing fields */
    int housing_body; /* the file has a housing body's displacement (/housing/body_displacement) */
    /* projective leap */
    double *leap_time; /* nleap: each leap's start, the time of the row before its gap (leap_time); NULL: none */
    size_t nleap;
} plot_sim;

/* A modal file. Arrays absent from the file are NULL with zero counts. */
/* The loop analysis of a modal file (/loop; nf = 0 when the file has none). */
typedef struct plot_loop {
    int nf, nc, na;           /* frequencies, controlled axes, AMB axes */
    int stable;               /* 1: S is defined */
    double rate;              /* a sampled loop's sample rate, Hz; 0: continuous */
    double *freq;             /* nf, Hz */
    double *s_re, *s_im;      /* nf x nc */
    double *l_re, *l_im;      /* nf x nc */
    double *c_re, *c_im;      /* nf x na, m/N */
    double *axis, *peak, *fp; /* nc: AMB axis, peak |S|, its frequency (Hz) */
} plot_loop;

/* The API 617 report of a modal file (plot_api617.c): what its figures read. */
#define PLOT_PARTS 4 /* discs, AMBs, AMB sensors, retainers */
typedef struct plot_api617 {
    int ns, nn;                      /* swept speeds x response nodes (0: no sweep in the file) */
    double *speed, *node;            /* ns, nn */
    double *major, *x_amp, *x_phase; /* ns x nn: m, m, rad */
    int np;                          /* peaks */
    double *peak_node, *peak_speed, *peak_amp, *peak_af;
    double op_min, op_max; /* operating range, rad/s (NAN: none) */
    int nparts[PLOT_PARTS];
    double *parts[PLOT_PARTS]; /* node numbers of each kind of part */
} plot_api617;

typedef struct plot_modal {
    int ns, nb;    /* Campbell: speeds x branches */
    double *speed; /* ns, rad/s */
    double *freq;  /* ns x nb, Hz (NAN: missing point) */
    double *whirl; /* ns x nb: 1 forward, -1 backward, 0 mixed */
    double *mac;   /* ns x nb: MAC to the branch's previous point (td_campbell_mac), NULL in older files */
    int ncrit;
    double *crit_speed, *crit_freq, *crit_whirl; /* ncrit */
    int nm, nn;                                  /* modes x nodes of the mode shapes */
    double *mode_freq, *mode_whirl, *mode_zeta;  /* nm */
    double *xr, *xi, *yr, *yi;                   /* nm x nn */
    double *node_z;                              /* nn axial positions (m) when the file has them, else NULL */
    double mode_speed;                           /* rad/s of the mode shapes, NAN when unknown */
    plot_loop loop;
    plot_api617 api; /* the API 617 report: swept response, peaks, the parts' nodes */
} plot_modal;

typedef struct plot_file {
    const char *path; /* as given (borrowed from argv) */
    char stem[256];   /* file name without directories and .h5/.hdf5: the legend label */
    char title[512];  /* case description, else the stem; "(INCOMPLETE ...)" appended */
    plot_kind kind;
    int complete; /* 1, 0, or -1 when the file has no flag */
    plot_sim sim;
    plot_modal modal;
    plot_sweep sweep;
} plot_file;

/* One line "touchdown plot: PATH: BEFORE/NAME-PATH-OF-id AFTER"; PLOT_BAD_INPUT. */
int plot_bad_part(const char *path, const char *before, td_out_id id, const char *after);
/* Load `path` (window applies to simulation files). On failure prints one line
 * "touchdown plot: PATH: why" and returns PLOT_BAD_INPUT (or PLOT_FAILED when out of memory). */
int plot_file_load(const char *path, const plot_window *win, plot_file *f);
void plot_file_free(plot_file *f);

/* ---- plot_read.c: the loaders' checked readers ----------------------------------------------- */

/* Dataset `id` (+ `sub`) as a new array of `n` doubles; NULL when absent or of another size, so
 * that the arrays read together with one whose shape sets n are never read past their end. */
double *plot_read_vector(const td_result *r, td_out_id id, const char *sub, size_t n);
/* An optional dataset `id` (+ `sub`): 0 with *out NULL when absent or the array of `n` doubles,
 * -1 when it is there with another size (a file to refuse: read without it, its figure would
 * be wrong, with no word said). */
int plot_read_optional(const td_result *r, td_out_id id, const char *sub, size_t n, double **out);

/* ---- plot_loop.c: the loop analysis of a modal file ------------------------------------------ */

/* Read /loop into *l when the file has it (0; nothing read: l->nf = 0), -1 when unreadable. */
int plot_loop_load(const td_result *r, plot_loop *l);
void plot_loop_free(plot_loop *l);

/* ---- plot_script.c: output and gnuplot ----------------------------------------------------- */

typedef struct plot_opts {
    const char *dir; /* output directory */
    int retainer;    /* -1: all */
    plot_window win;
    int svg; /* 0: png, 1: svg */
    int run; /* run gnuplot */
    int quiet;
    int modes; /* mode shapes to draw */
    /* sweep tables */
    const char *quantity; /* column plotted against the x key (NULL: peak_housing_force) */
    const char *xkey;     /* swept key on the x axis (NULL: speed when swept, else the first numeric one) */
    const char *ykey;     /* the regime map's y key (NULL: the first other numeric one) */
    int log_x, log_y;     /* logarithmic x axis (every sweep figure), y axis (the quantity, the map's y key) */
} plot_opts;

/* The scripts written so far, run at the end. */
#define PLOT_MAX_SCRIPTS 256
typedef struct plot_job {
    const plot_opts *opt;
    int count;
    char scripts[PLOT_MAX_SCRIPTS][256]; /* names relative to opt->dir */
} plot_job;

/* Create `dir` and its parents; PLOT_OK or PLOT_BAD_INPUT with a line printed (and nothing left
 * created). *created: the length of the shallowest prefix of `dir` this call created, 0 if none. */
int plot_make_dir(const char *dir, size_t *created);
/* Undo plot_make_dir when the call that made the directories gives up: remove `dir` and its
 * parents down to that prefix, each only while it is empty. */
void plot_remove_new_dirs(const char *dir, size_t created);
/* Open DIR/NAME for writing; NULL with a line printed on failure. */
FILE *plot_open(const plot_opts *opt, const char *name);
/* Close a file opened by plot_open; PLOT_OK or PLOT_FAILED with a line printed. */
int plot_close(FILE *f, const plot_opts *opt, const char *name);
/* projective leap: no line across a leap. A data file written in time order gets a blank line (a
 * break in gnuplot's line) between the row at a leap's start and the next row, the leap's gap.
 * The leaps' starts (the file's leap_time: the time of the row before each gap, in order) are
 * walked with a moving index, O(rows + leaps) over a data file. */
typedef struct plot_leaps {
    const double *time; /* each leap's start, in order (NULL: none) */
    size_t n, k;        /* leaps; the first one not yet passed */
} plot_leaps;
/* The leaps `time` (n, NULL: none) from the first row of a data file on. */
void plot_leaps_begin(plot_leaps *l, const double *time, size_t n);
/* A blank line before row i of the rows at times t[] (called for i = 0, 1, ... in order) when a
 * leap's gap lies between rows i - 1 and i: row i - 1 is at a leap's start and row i after it.
 * Rows that share the leap's start (an event's row and the grid's) have no gap between them. */
void plot_leap_break(FILE *out, plot_leaps *l, const double *t, size_t i);
/* Start the script NAME.gp for the figure NAME.png/.svg (width x height pixels): header comment
 * `what` and the variables figure, format, width and height that tools/plot/gp/common.gp uses.
 * Returns the open file (NULL with a line printed) and records the script in the job. The caller
 * then writes the figure's own variables and ends with plot_script_end. */
FILE *plot_script_begin(plot_job *job, const char *name, const char *what, const char *source, int width, int height);
/* Append tools/plot/gp/common.gp (terminal and style), the template `pre` (NULL: none) and the
 * figure's template `body`, then close. */
int plot_script_end(FILE *f, const plot_job *job, const char *name, const char *pre, const char *body);
/* name = "value" */
void plot_var_string(FILE *f, const char *name, const char *value);
/* Print `s` as a gnuplot double-quoted string (a newline becomes \n: two-line titles). */
void plot_gp_string(FILE *f, const char *s);
/* Run gnuplot on every recorded script in opt->dir; PLOT_OK or PLOT_FAILED with a line printed. */
int plot_run_all(const plot_job *job);
/* Image file extension for the options: "png" or "svg". */
const char *plot_ext(const plot_opts *opt);

/* ---- the templates tools/plot/gp/NAME.gp, built into the binary (cmake/EmbedText.cmake) ----- */

extern const char plot_tpl_common[], plot_tpl_markers[], plot_tpl_orbit[], plot_tpl_radial_force[],
    plot_tpl_amb_forces[], plot_tpl_palette[], plot_tpl_compare[], plot_tpl_campbell[], plot_tpl_mode_shapes[],
    plot_tpl_sweep_quantity[], plot_tpl_regime_map[], plot_tpl_bifurcation[], plot_tpl_sensitivity[],
    plot_tpl_open_loop[], plot_tpl_nyquist[], plot_tpl_compliance[], plot_tpl_bode[], plot_tpl_polar[],
    plot_tpl_report[], plot_tpl_housing[];

/* ---- plot_sweep_load.c: sweep tables --------------------------------------------------------- */

/* Read the column `name` --quantity can plot: a numeric dataset at the table's root with one value
 * per point (n), other than the index /point; 0 ok, -1 when it is not one (a freed). */
int plot_sweep_read_column(const td_result *r, const char *name, size_t n, td_result_array *a);
/* The table's columns that plot_sweep_read_column accepts, in name order, ", "-separated into buf
 * (", ..." when they do not fit; "(none)" when there are none). */
void plot_sweep_columns(const td_result *r, size_t n, char *buf, size_t size);
/* Load the table's keys, regimes and section; PLOT_OK, else a line printed and PLOT_BAD_INPUT. */
int plot_sweep_load(const td_result *r, plot_file *f);
void plot_sweep_free(plot_sweep *s);

/* ---- figures -------------------------------------------------------------------------------- */

/* Every figure of one simulation file; prefix ("" or "STEM-") starts every file name. */
int plot_sim_figures(plot_job *job, const plot_file *f, const char *prefix);
/* Every figure of one modal file. */
int plot_modal_figures(plot_job *job, const plot_file *f, const char *prefix);
/* The loop figures of a modal file with /loop (plot_loop.c): PREFIXsensitivity (|S| per axis with
 * the ISO 14839-3 zone bands), PREFIXopen-loop (Bode of L), PREFIXnyquist (L with the circles of
 * radius 1/3, 1/4, 1/5 around -1), PREFIXcompliance; nothing for a file without it. */
int plot_loop_figures(plot_job *job, const plot_file *f, const char *prefix);

/* ---- plot_api617.c: the API 617 report of a modal file --------------------------------------- */

/* Read /unbalance_response, /response_peaks and the parts' nodes in /modes (absent parts stay
 * empty); 0, or -1 when a part is there but unreadable, the group that is into *unreadable. */
int plot_api617_load(const td_result *r, plot_api617 *a, td_out_id *unreadable);
void plot_api617_free(plot_api617 *a);
/* PREFIXbode (amplitude and phase against speed at the response nodes, the peaks and the operating
 * range marked) and PREFIXpolar (the x response in the complex plane), when the file has a sweep. */
int plot_api617_figures(plot_job *job, const plot_file *f, const char *prefix);
/* gnuplot lines marking the parts (discs, AMBs, sensors, retainers) at their axial positions
 * node_z (nn nodes; NULL: node numbers) on the mode-shape figure. */
void plot_api617_mark_parts(FILE *out, const plot_api617 *a, const double *node_z, int nn);
/* The figures of one sweep table: the quantity against the x key, the regime map, the bifurcation
 * diagram (plot_sweep.c). PLOT_BAD_INPUT with a line printed for an option the table cannot take. */
int plot_sweep_figures(plot_job *job, const plot_file *f, const char *prefix);
/* Overlays of several simulation files (whose data files plot_sim_figures has written with the
 * given prefixes). */
int plot_compare_figures(plot_job *job, const plot_file *const *files, const char *const *prefixes, int count);

/* Data file of retainer `r` of a simulation file (columns documented in its header). */
void plot_retainer_data_name(char *buf, size_t n, const char *prefix, int r);

#endif
