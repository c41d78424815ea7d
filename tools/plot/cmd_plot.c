/* touchdown plot: figures (PNG or SVG, through gnuplot scripts kept for editing) from the HDF5
 * files of 'touchdown run' and 'touchdown modal'. The work is in plot_*.c (plot.h). */
#include "common/cli.h"
#include "plot/plot.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PLOT_MAX_FILES 32

static const char plot_usage[] =
    "usage: touchdown plot [OPTIONS] FILE.h5 [FILE2.h5 ...]\n"
    "\n"
    "Figures from result files: for each file, plain-text data files (.dat) and gnuplot scripts\n"
    "(.gp) are written to the output directory, then gnuplot turns each script into an image.\n"
    "The scripts stay there: restyle one and rerun it in that directory with 'gnuplot NAME.gp'.\n"
    "\n"
    "A simulation file (touchdown run) gives, for each retainer N:\n"
    "  orbit-rN          the orbit at the retainer: x against y in mm, equal scales, the clearance\n"
    "                    circle, samples in contact in red (the paper's figures 3, 5, 7)\n"
    "  radial-force-rN   radial displacement (mm, clearance as a dotted line) over normal contact\n"
    "                    force (N) against time, contact intervals shaded (figures 4, 6, 8)\n"
    "and amb-forces, the x and y force of each AMB against time; with housing motion or a\n"
    "housing body also housing, the housing's acceleration (g) and displacement (mm) against\n"
    "time (a body's own displacement dotted). Scheduled changes (e.g. the unbalance steps) are\n"
    "dashed vertical lines.\n"
    "A modal file (touchdown modal) gives:\n"
    "  campbell          damped natural frequencies (Hz) against speed (rad/s), forward and\n"
    "                    backward whirl apart, the 1x line, the critical speeds circled\n"
    "  mode-shapes       the first modes' lateral shapes, the bearings and discs marked\n"
    "  bode, polar       the unbalance response over the speed range (docs/api617.md)\n"
    "A sweep table (touchdown sweep, its .h5) gives:\n"
    "  sweep-QUANTITY    a summary quantity (--quantity, default peak_housing_force) against the x\n"
    "                    key, one line per value of the other swept keys\n"
    "  regime-map        each point's regime (free, rub, bounce, backward whirl, failed: the\n"
    "                    table's regime column) as a coloured tile over the x and y keys\n"
    "  bifurcation       the bifurcation diagram: every point's once-per-revolution radius at\n"
    "                    the retainer (after the transient) against the x key, clearance dashed\n"
    "The x key is --x, else speed when swept, else the first swept key with numeric values.\n"
    "Several simulation files also give compare-rN: radial displacement and normal force at\n"
    "retainer N of every file overlaid, the legend from the file names. With several files\n"
    "every name is prefixed with the file's name (out.h5 -> out-orbit-r0.png).\n"
    "Titles come from the case's description; an incomplete run says so in its titles.\n"
    "\n"
    "options:\n"
    "  -d, --dir DIR      output directory (created; default: the first file's name without\n"
    "                     .h5 plus '-plots', in the current directory: out.h5 -> out-plots/)\n"
    "      --retainer N   only retainer N (default: every retainer)\n"
    "      --from T       start of the time window, s (default: the first sample)\n"
    "      --to T         end of the time window, s (default: the last sample)\n"
    "      --format F     png (default; pngcairo when gnuplot has it, else png) or svg\n"
    "      --modes N      mode shapes to draw (default 6, at most 16)\n"
    "      --quantity NAME  sweep tables: the column plotted against the x key (default\n"
    "                     peak_housing_force; any numeric column: total_impulse, contacts, ...)\n"
    "      --x KEY        sweep tables: the swept key on the x axis\n"
    "      --y KEY        sweep tables: the regime map's y key (default: the first numeric key on another axis)\n"
    "      --log-x        sweep tables: a logarithmic x axis (the x key's values must be > 0)\n"
    "      --log-y        sweep tables: a logarithmic y axis for the quantity and the regime map's y key\n"
    "      --no-run       write the data and scripts only, do not run gnuplot\n"
    "  -q, --quiet        print nothing but errors (default: one 'wrote' line per figure)\n"
    "  -h, --help         this help\n"
    "\n"
    "environment: TOUCHDOWN_GNUPLOT names the gnuplot program (default: gnuplot on PATH).\n"
    "When gnuplot fails its messages are kept in DIR/NAME.log.\n"
    "\n"
    "exit codes: 0 success; 1 gnuplot missing or failed, or a file could not be written;\n"
    "2 bad input or usage (missing or unreadable file, not a touchdown result file, bad option,\n"
    "a --quantity, --x or --y the sweep table does not have).\n";

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "touchdown plot: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see touchdown plot --help)\n");
    return TD_EXIT_USAGE;
}

static int parse_time(const char *s, double *out)
{
    char *end;
    *out = strtod(s, &end);
    return end != s && !*end && isfinite(*out);
}

static int parse_count(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi)
        return 0;
    *out = (int)v;
    return 1;
}

/* Once the options are read (optind past them): the files given and the window. Returns -1 to go
 * on, else the exit code. */
static int check_operands(int argc, const plot_opts *opt)
{
    if (optind >= argc)
        return usage_error("%s", "no result file given");
    if (argc - optind > PLOT_MAX_FILES) {
        fprintf(stderr, "touchdown plot: at most %d files at once\n", PLOT_MAX_FILES);
        return TD_EXIT_USAGE;
    }
    if (!(opt->win.from < opt->win.to)) {
        fprintf(stderr, "touchdown plot: --from %g is not before --to %g\n", opt->win.from, opt->win.to);
        return TD_EXIT_USAGE;
    }
    return -1;
}

/* Parse the options into `opt`; returns -1 to go on, else the exit code. */
static int parse(int argc, char **argv, plot_opts *opt)
{
    enum {
        OPT_RETAINER = 256,
        OPT_FROM,
        OPT_TO,
        OPT_FORMAT,
        OPT_NO_RUN,
        OPT_MODES,
        OPT_QUANTITY,
        OPT_X,
        OPT_Y,
        OPT_LOG_X,
        OPT_LOG_Y
    };
    static const struct option longopts[] = {{"dir", required_argument, NULL, 'd'},
                                             {"retainer", required_argument, NULL, OPT_RETAINER},
                                             {"from", required_argument, NULL, OPT_FROM},
                                             {"to", required_argument, NULL, OPT_TO},
                                             {"format", required_argument, NULL, OPT_FORMAT},
                                             {"no-run", no_argument, NULL, OPT_NO_RUN},
                                             {"modes", required_argument, NULL, OPT_MODES},
                                             {"quantity", required_argument, NULL, OPT_QUANTITY},
                                             {"x", required_argument, NULL, OPT_X},
                                             {"y", required_argument, NULL, OPT_Y},
                                             {"log-x", no_argument, NULL, OPT_LOG_X},
                                             {"log-y", no_argument, NULL, OPT_LOG_Y},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    int c;
    optind = 1;
    opterr = 0; /* our own one-line messages */
    while ((c = getopt_long(argc, argv, ":d:qh", longopts, NULL)) != -1) {
        switch (c) {
        case 'd': opt->dir = optarg; break;
        case OPT_RETAINER:
            if (!parse_count(optarg, 0, 1000000, &opt->retainer))
                return usage_error("--retainer wants a retainer number >= 0, not '%s'", optarg);
            break;
        case OPT_FROM:
            if (!parse_time(optarg, &opt->win.from))
                return usage_error("--from wants a time in s, not '%s'", optarg);
            break;
        case OPT_TO:
            if (!parse_time(optarg, &opt->win.to))
                return usage_error("--to wants a time in s, not '%s'", optarg);
            break;
        case OPT_FORMAT:
            if (strcmp(optarg, "png") && strcmp(optarg, "svg"))
                return usage_error("--format is png or svg, not '%s'", optarg);
            opt->svg = !strcmp(optarg, "svg");
            break;
        case OPT_NO_RUN: opt->run = 0; break;
        case OPT_MODES:
            if (!parse_count(optarg, 1, PLOT_MAX_MODES, &opt->modes))
                return usage_error("--modes wants a number from 1 to 16, not '%s'", optarg);
            break;
        case OPT_QUANTITY: opt->quantity = optarg; break;
        case OPT_X: opt->xkey = optarg; break;
        case OPT_Y: opt->ykey = optarg; break;
        case OPT_LOG_X: opt->log_x = 1; break;
        case OPT_LOG_Y: opt->log_y = 1; break;
        case 'q': opt->quiet = 1; break;
        case 'h': fputs(plot_usage, stdout); return TD_EXIT_OK;
        case ':': return usage_error("option '%s' needs a value", argv[optind - 1]);
        default: return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    return check_operands(argc, opt);
}

/* --retainer must exist in every simulation file. */
static int check_retainer(const plot_opts *opt, const plot_file *files, int count)
{
    int i;
    for (i = 0; i < count && opt->retainer >= 0; i++)
        if (files[i].kind == PLOT_KIND_SIM && opt->retainer >= files[i].sim.nret) {
            fprintf(stderr, "touchdown plot: %s: no retainer %d (the file has %d)\n", files[i].path, opt->retainer,
                    files[i].sim.nret);
            return TD_EXIT_USAGE;
        }
    return TD_EXIT_OK;
}

/* File-name prefixes: none for one file, else "STEM-" ("K-STEM-" when two stems are equal). */
static void make_prefixes(const plot_file *files, int count, char (*prefix)[300])
{
    int i, j;
    for (i = 0; i < count; i++) {
        int dup = 0;
        for (j = 0; j < count; j++)
            dup |= j != i && !strcmp(files[i].stem, files[j].stem);
        if (count == 1)
            prefix[i][0] = '\0';
        else if (dup)
            snprintf(prefix[i], sizeof prefix[i], "%d-%s-", i + 1, files[i].stem);
        else
            snprintf(prefix[i], sizeof prefix[i], "%s-", files[i].stem);
    }
}

static int make_figures(plot_job *job, const plot_file *files, int count)
{
    static char prefix[PLOT_MAX_FILES][300];
    const plot_file *sims[PLOT_MAX_FILES];
    const char *sim_prefix[PLOT_MAX_FILES];
    int i, nsim = 0, rc = PLOT_OK;
    make_prefixes(files, count, prefix);
    for (i = 0; i < count && rc == PLOT_OK; i++) {
        if (files[i].kind == PLOT_KIND_SIM) {
            rc = plot_sim_figures(job, &files[i], prefix[i]);
            sims[nsim] = &files[i];
            sim_prefix[nsim++] = prefix[i];
        } else if (files[i].kind == PLOT_KIND_SWEEP) {
            rc = plot_sweep_figures(job, &files[i], prefix[i]);
        } else {
            rc = plot_modal_figures(job, &files[i], prefix[i]);
        }
    }
    if (rc == PLOT_OK && nsim >= 2)
        rc = plot_compare_figures(job, sims, sim_prefix, nsim);
    return rc;
}

int td_cmd_plot(int argc, char **argv)
{
    static plot_file files[PLOT_MAX_FILES];
    static plot_job job;
    char dir[PLOT_PATH_SIZE];
    size_t created = 0; /* what plot_make_dir made, removed again if the call gives up */
    plot_opts opt;
    int code, count = 0, i;
    memset(&opt, 0, sizeof opt);
    opt.retainer = -1;
    opt.win.from = -HUGE_VAL;
    opt.win.to = HUGE_VAL;
    opt.run = 1;
    opt.modes = 6;
    if ((code = parse(argc, argv, &opt)) >= 0)
        return code;
    for (i = optind; i < argc; i++, count++)
        if ((code = plot_file_load(argv[i], &opt.win, &files[count])) != PLOT_OK)
            goto done;
    if ((code = check_retainer(&opt, files, count)) != TD_EXIT_OK)
        goto done;
    if (td_cli_path(dir, sizeof dir, opt.dir ? opt.dir : files[0].stem, opt.dir ? "" : "-plots", "plot",
                    opt.dir ? "--dir" : argv[optind])) {
        code = TD_EXIT_USAGE;
        goto done;
    }
    for (i = (int)strlen(dir) - 1; i > 0 && dir[i] == '/'; i--)
        dir[i] = '\0';
    opt.dir = dir;
    if ((code = plot_make_dir(dir, &created)) != PLOT_OK)
        goto done;
    memset(&job, 0, sizeof job);
    job.opt = &opt;
    if ((code = make_figures(&job, files, count)) != PLOT_OK)
        goto done;
    if (!opt.run) {
        if (!opt.quiet)
            printf("wrote %d gnuplot scripts and their data to %s (run 'gnuplot NAME.gp' there)\n", job.count, dir);
    } else {
        code = plot_run_all(&job);
    }
done:
    if (code != TD_EXIT_OK)
        plot_remove_new_dirs(dir, created);
    for (i = 0; i < count; i++)
        plot_file_free(&files[i]);
    return code;
}
