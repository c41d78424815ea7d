/* touchdown modal: modes, Campbell diagram, critical speeds and unbalance response of a case. */
#include "common/cli.h"
#include "modal/modal_print.h"

#include <getopt.h>
#include <stdlib.h>
#include <string.h>

static const char modal_usage[] =
    "usage: touchdown modal [OPTIONS] CASE\n"
    "\n"
    "Eigen-analysis of the contact-free first-order system (AMB force lags included):\n"
    "damped natural frequencies (rad/s and Hz, 12 significant digits), damping ratios and\n"
    "whirl directions at the case speed; the Campbell diagram over modal.speed_min..speed_max;\n"
    "the critical speeds (forward and backward whirl crossing the 1x line); the steady\n"
    "unbalance response (orbits at the retainer and AMB nodes) at modal.response_speeds; the API 617\n"
    "report (docs/api617.md): the unbalance response over the speed range at modal.response_nodes,\n"
    "each peak's amplification factor and separation margin from modal.operating_speed_min/max with\n"
    "its verdict, the log decrement of every mode, the ISO 14839-2 zone of each AMB sensor along the\n"
    "response and the static reactions under gravity; and the\n"
    "loop analysis at the case speed (ISO 14839-3): per controlled AMB axis the sensitivity with\n"
    "every loop closed, its peak and zone, the open loop (Bode, Nyquist) and the compliance at the\n"
    "AMBs, 0.5 Hz to 5 kHz (with sampled controllers: their axes' sampled loop at the sample\n"
    "instants, up to the Nyquist frequency).\n"
    "Writes everything, mode shapes included, to CSV and HDF5. Large models (over 240 states) get\n"
    "their lowest modes only (docs/case-format.md); speed_steps x DOFs is limited to 200000.\n"
    "\n"
    "options:\n"
    "  -s, --set KEY=VALUE  override a case key (repeatable), e.g. --set modal.speed_max=500\n"
    "  -w, --speed W        analyse at W rad/s instead of the case speed\n"
    "  -o, --output PREFIX  write PREFIX.csv and PREFIX.h5 (default CASENAME-modal.*)\n"
    "      --csv PATH       CSV path ('' for none)\n"
    "      --hdf5 PATH      HDF5 path ('' for none)\n"
    "  -q, --quiet          print nothing but errors\n"
    "      --json           print only the loop analysis as one JSON object (stable, max_real_part,\n"
    "                       sample_rate, sensitivity_peak, sensitivity_peak_frequency,\n"
    "                       sensitivity_zones, sensitivity_zone; docs/output-format.md); the files\n"
    "                       are written as usual\n"
    "  -h, --help           this help\n"
    "\n"
    "Refused before the analysis (exit 2): CSV and HDF5 outputs that are the same file, an output\n"
    "that is the case file or one of its @include files, an output named *.partial, an output\n"
    "that exists and is not a regular file, an output directory that does not exist or is not\n"
    "writable, an --output PREFIX that names no file ('', 'dir/', '.').\n"
    "\n"
    "exit codes: 0 success, 1 the analysis failed or was interrupted (SIGINT/SIGTERM/SIGHUP, checked\n"
    "between its stages), 2 bad input or usage.\n";

static void print_modes(const td_modal *modes, int count, const td_model *model)
{
    printf("modes at %.12g rad/s (%s):\n", td_modal_speed(modes), td_stability_word(modes));
    td_print_modes(stdout, modes, count, 12);
    td_print_overdamped(stdout, modes, model);
}

static void print_critical(const td_critical_speed *cs, int n, const td_modal_options *opt)
{
    int i;
    printf("critical speeds in %.6g..%.6g rad/s:\n", opt->speed_min, opt->speed_max);
    if (n == 0)
        printf("  none\n");
    for (i = 0; i < n; i++)
        printf("  %-9s %20.12g rad/s %20.12g Hz %12.2f rpm  zeta %.6g\n", td_whirl_name(cs[i].whirl), cs[i].speed,
               cs[i].freq_hz, TD_RPM_FROM_RAD_S(cs[i].speed), cs[i].zeta);
}

/* One orbit line, if `node` is in the response. */
static void print_orbit(const td_harmonic *h, const char *what, int node, double clearance)
{
    td_orbit o;
    if (td_harmonic_orbit(h, node, &o) != TD_OK)
        return;
    printf("  %s, node %d: major %.9g m, minor %.9g m", what, node, o.major, o.minor);
    if (clearance > 0.0)
        printf(" (%.4g of the clearance)", o.major / clearance);
    putchar('\n');
}

/* Steady orbits where they matter: retainers, AMBs, and the unbalanced nodes. */
static void print_orbits(const td_model *m, const td_harmonic *h)
{
    int i;
    char what[32];
    printf("unbalance response at %.12g rad/s (semi-axes of the steady orbit):\n", td_harmonic_speed(h));
    for (i = 0; i < td_model_retainer_count(m); i++) {
        td_retainer r;
        td_model_get_retainer(m, i, &r);
        snprintf(what, sizeof what, "retainer %d", i);
        print_orbit(h, what, r.node, r.clearance);
    }
    for (i = 0; i < td_model_amb_count(m); i++) {
        td_amb a;
        td_model_get_amb(m, i, &a);
        snprintf(what, sizeof what, "amb %d", i);
        print_orbit(h, what, a.node, 0.0);
    }
    for (i = 0; i < td_model_unbalance_count(m); i++) {
        td_unbalance u;
        td_model_get_unbalance(m, i, &u);
        snprintf(what, sizeof what, "unbalance %d", i);
        print_orbit(h, what, u.node, 0.0);
    }
}

/* Unbalances of the model as defined at t = 0. */
static td_unbalance *model_unbalances(const td_model *m, int *n)
{
    int i;
    td_unbalance *u;
    *n = td_model_unbalance_count(m);
    u = calloc((size_t)(*n > 0 ? *n : 1), sizeof *u);
    for (i = 0; u && i < *n; i++)
        td_model_get_unbalance(m, i, &u[i]);
    return u;
}

typedef struct modal_outputs {
    char csv[TD_OUTPUT_PATH_SIZE];
    char hdf5[TD_OUTPUT_PATH_SIZE];
} modal_outputs;

/* A stage boundary: TD_ERR_INTERRUPTED once a signal came (td_cli_catch_signals). */
static td_status stage(td_status st, volatile sig_atomic_t *cancel, td_error *err)
{
    if (st == TD_OK && *cancel) {
        err->code = TD_ERR_INTERRUPTED;
        snprintf(err->message, sizeof err->message, "interrupted by a signal before every file was written");
        return TD_ERR_INTERRUPTED;
    }
    return st;
}

/* Output paths: --csv/--hdf5, else PREFIX.csv/.h5, else CASENAME-modal.csv/.h5. A path too long
 * is an error (td_cli_path), never cut short. Returns 0 or an exit code. */
static int choose_paths(modal_outputs *paths, const td_case *c, const char *prefix, const char *csv, const char *hdf5)
{
    const char *stem = prefix ? prefix : td_case_name(c);
    const char *from = prefix ? "--output" : td_case_path(c);
    int code = prefix ? td_cli_prefix(prefix, "modal") : 0;
    if (code)
        return code;
    code = csv ? td_cli_path(paths->csv, sizeof paths->csv, csv, "", "modal", "--csv")
               : td_cli_path(paths->csv, sizeof paths->csv, stem, prefix ? ".csv" : "-modal.csv", "modal", from);
    if (!code)
        code = hdf5 ? td_cli_path(paths->hdf5, sizeof paths->hdf5, hdf5, "", "modal", "--hdf5")
                    : td_cli_path(paths->hdf5, sizeof paths->hdf5, stem, prefix ? ".h5" : "-modal.h5", "modal", from);
    return code;
}

/* Refuse, before the analysis, outputs that collide with each other or with the case's files, or
 * that cannot be written (td_modal_check_paths). Returns 0 or an exit code. */
static int check_outputs(const modal_outputs *paths, const td_case *c)
{
    int n = 0;
    const char *const *files = td_case_files(c, &n);
    td_error err;
    td_status st;
    td_error_clear(&err);
    st = td_modal_check_paths(paths->csv, paths->hdf5, files, n, &err);
    if (st == TD_OK)
        return 0;
    fprintf(stderr, "touchdown modal: %s\n", err.message[0] ? err.message : td_strerror(st));
    return td_cli_exit_code(st);
}

/* 1 (said on stderr) when the Campbell grid, speed_steps x DOFs, is past TD_MODAL_MAX_GRID_WORK.
 * The case reader checks the key where it is written; this catches the default on a large model. */
static int grid_too_big(const td_case *c)
{
    const td_model *m = td_case_model(c);
    const td_modal_options *opt = td_case_modal_options(c);
    if ((long)opt->speed_steps * td_model_dof_count(m) <= TD_MODAL_MAX_GRID_WORK)
        return 0;
    fprintf(stderr,
            "touchdown modal: %s: modal.speed_steps: the default %d speeds are too many for %d DOFs "
            "(speed_steps x DOFs at most %ld): set modal.speed_steps to at most %ld\n",
            td_case_path(c), opt->speed_steps, td_model_dof_count(m), (long)TD_MODAL_MAX_GRID_WORK,
            (long)TD_MODAL_MAX_GRID_WORK / (td_model_dof_count(m)));
    return 1;
}

/* The text report: modes, critical speeds, unbalance orbits and, of a reduced model, the reduction. */
static void print_results(const td_case *c, const td_system *sys, double speed, const td_modal *modes,
                          const td_critical_speed *cs, int n_cs, td_harmonic *const *h, int n_h, const td_loop *loop,
                          const td_modal_api617_results *api)
{
    const td_model *m = td_case_model(c);
    const td_modal_options *opt = td_case_modal_options(c);
    int i;
    print_modes(modes, opt->mode_count, m);
    print_critical(cs, n_cs, opt);
    for (i = 0; i < n_h; i++)
        print_orbits(m, h[i]);
    td_print_api617(stdout, m, opt, api);
    if (loop)
        td_print_loop(stdout, loop);
    if (td_system_is_reduced(sys)) {
        td_print_reduction(stdout, sys);
        td_print_reduction_error(stdout, sys, speed, opt->response_speeds, n_h);
    }
}

/* The loop analysis, or NULL (said on stderr) for a machine it does not apply to or refuses: a
 * machine without a controlled AMB axis, sampled controllers at different rates. That fails
 * nothing else. */
static td_loop *loop_analysis(const td_case *c, const td_system *sys, double speed)
{
    td_loop *l = NULL;
    td_error err;
    td_error_clear(&err);
    if (td_loop_compute(sys, speed, NULL, &l, &err) != TD_OK)
        fprintf(stderr, "touchdown modal: %s: %s\n", td_case_path(c),
                err.message[0] ? err.message : td_strerror(err.code));
    return l;
}

/* quiet: 1 prints nothing, 2 (--json) only the loop analysis as JSON. */
static int analyse(const td_case *c, double speed, const modal_outputs *paths, int quiet)
{
    volatile sig_atomic_t *cancel = td_cli_catch_signals();
    const td_model *m = td_case_model(c);
    const td_modal_options *opt = td_case_modal_options(c);
    td_system *sys = NULL;
    td_modal *modes = NULL;
    td_campbell *camp = NULL;
    td_critical_speed cs[64];
    td_harmonic *h[64];
    td_unbalance *u = NULL;
    td_loop *loop = NULL;
    int n_cs = 0, n_h = 0, n_u = 0, i, code = TD_EXIT_FAILED;
    td_modal_results res;
    td_modal_api617_results api = {NULL, NULL, NULL, 0, NULL, 0.0, 0, NULL};
    td_error err;
    td_status st;

    memset(h, 0, sizeof h);
    td_error_clear(&err);
    if (grid_too_big(c))
        return TD_EXIT_USAGE;
    if ((st = stage(td_system_create(m, &sys, &err), cancel, &err)) != TD_OK)
        goto done;
    if ((st = stage(td_modal_solve_lowest(sys, speed, opt->mode_count, &modes, &err), cancel, &err)) != TD_OK)
        goto done;
    if ((st = stage(td_campbell_compute(sys, opt, &camp, &err), cancel, &err)) != TD_OK)
        goto done;
    if ((st = stage(td_campbell_critical_speeds(camp, sys, opt, cs, 64, &n_cs, &err), cancel, &err)) != TD_OK)
        goto done;
    if (!(u = model_unbalances(m, &n_u))) {
        st = TD_ERR_NOMEM;
        goto done;
    }
    for (i = 0; i < opt->response_speed_count && i < 64; i++, n_h++)
        if ((st = stage(td_harmonic_compute(sys, opt->response_speeds[i], u, n_u, &h[i], &err), cancel, &err)) != TD_OK)
            goto done;
    if ((st = stage(td_modal_api617(m, sys, opt, u, n_u, &api, &err), cancel, &err)) != TD_OK)
        goto done;
    loop = loop_analysis(c, sys, speed);
    if (!quiet)
        print_results(c, sys, speed, modes, cs, n_cs, h, n_h, loop, &api);
    td_modal_api617_into(&res, &api);
    res.loop = loop;
    res.modes = modes;
    res.campbell = camp;
    res.critical = cs;
    res.n_critical = n_cs;
    res.harmonics = (const td_harmonic *const *)h;
    res.n_harmonics = n_h;
    res.model = m;
    res.case_text = td_case_text(c);
    if ((st = stage(TD_OK, cancel, &err)) != TD_OK)
        goto done;
    if (paths->csv[0] && (st = stage(td_modal_write_csv(paths->csv, &res, &err), cancel, &err)) != TD_OK)
        goto done;
    if (paths->hdf5[0] && (st = td_modal_write_hdf5(paths->hdf5, &res, &err)) != TD_OK)
        goto done;
    if (quiet == 2 && td_print_loop_json(stdout, loop)) {
        st = TD_ERR_NOMEM;
        goto done;
    }
    if (!quiet && (paths->csv[0] || paths->hdf5[0]))
        printf("wrote%s%s%s%s\n", paths->csv[0] ? " " : "", paths->csv, paths->hdf5[0] ? " " : "", paths->hdf5);
    code = TD_EXIT_OK;
done:
    if (code != TD_EXIT_OK) {
        fprintf(stderr, "touchdown modal: %s: %s\n", td_case_path(c), err.message[0] ? err.message : td_strerror(st));
        code = td_cli_exit_code(st);
    }
    for (i = 0; i < 64; i++)
        td_harmonic_free(&h[i]);
    free(u);
    td_modal_api617_free(&api);
    td_campbell_free(&camp);
    td_loop_free(&loop);
    td_modal_free(&modes);
    td_system_free(&sys);
    return code;
}

int td_cmd_modal(int argc, char **argv)
{
    enum { OPT_CSV = 256, OPT_HDF5, OPT_JSON };
    static const struct option longopts[] = {{"set", required_argument, NULL, 's'},
                                             {"speed", required_argument, NULL, 'w'},
                                             {"output", required_argument, NULL, 'o'},
                                             {"csv", required_argument, NULL, OPT_CSV},
                                             {"hdf5", required_argument, NULL, OPT_HDF5},
                                             {"quiet", no_argument, NULL, 'q'},
                                             {"json", no_argument, NULL, OPT_JSON},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    td_cli_sets sets = {{0}, 0};
    const char *prefix = NULL, *csv = NULL, *hdf5 = NULL, *speed_arg = NULL;
    int opt, code, quiet = 0;
    double speed;
    char *end;
    td_case *c = NULL;
    modal_outputs paths;

    optind = 1;
    while ((opt = getopt_long(argc, argv, "s:w:o:qh", longopts, NULL)) != -1) {
        switch (opt) {
        case 's':
            if (td_cli_add_set(&sets, optarg))
                return TD_EXIT_USAGE;
            break;
        case 'w': speed_arg = optarg; break;
        case 'o': prefix = optarg; break;
        case OPT_CSV: csv = optarg; break;
        case OPT_HDF5: hdf5 = optarg; break;
        case 'q': quiet = quiet ? quiet : 1; break;
        case OPT_JSON: quiet = 2; break;
        case 'h': fputs(modal_usage, stdout); return TD_EXIT_OK;
        default: fputs(modal_usage, stderr); return TD_EXIT_USAGE;
        }
    }
    if (optind != argc - 1) {
        td_cli_error("modal", "expected exactly one case file (see touchdown modal --help)");
        return TD_EXIT_USAGE;
    }
    if ((code = td_cli_load_case(argv[optind], &sets, &c)))
        return code;
    speed = td_model_speed(td_case_model(c));
    if (speed_arg) {
        speed = strtod(speed_arg, &end);
        if (*end || end == speed_arg || !TD_SPEED_VALID(speed)) {
            /* the rule of every speed (touchdown/dofs.h): whirl directions are counted from a spin about +z */
            td_cli_error("modal",
                         "--speed wants a speed >= 0 in rad/s, not '%s' (the spin is about +z: a machine turning the "
                         "other way is described from its other end)",
                         speed_arg);
            td_case_free(&c);
            return TD_EXIT_USAGE;
        }
    }
    code = choose_paths(&paths, c, prefix, csv, hdf5);
    if (!code)
        code = check_outputs(&paths, c);
    if (!code)
        code = analyse(c, speed, &paths, quiet);
    td_case_free(&c);
    return code;
}
