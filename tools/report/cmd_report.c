/* touchdown report: the one-page drop report of a run file (docs/report.md): PREFIX.txt,
 * PREFIX.json and PREFIX.png, written into a temporary directory and renamed into place only when
 * all three are whole. The work is in report_*.c (report.h). */
#define _DEFAULT_SOURCE /* mkdtemp */
#include "common/cli.h"
#include "report/report.h"

#include "touchdown/output.h"

#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char report_usage[] =
    "usage: touchdown report [OPTIONS] RUN.h5\n"
    "\n"
    "The one-page drop report of a run file (touchdown run): each quantity the file holds (the\n"
    "drop's peak forces, impulse, friction work, ending and final speed; whether the rotor touched\n"
    "and its smallest clearance margin; the ISO 14839-2 zone at each AMB sensor; per retainer its\n"
    "loads, clearance margin, the bearing's duty, heat and life) beside its limit\n"
    "from the case stored in the file (`limits`, `retainers[].bearing`) and a verdict: within,\n"
    "exceeds, or '-' (no limit given). Totals over the run (heat, damage, drops to failure) are\n"
    "judged within their limit only for a run that ended at rest: a run that ended before the rotor\n"
    "came to rest holds part of the drop. A quantity the file does not hold (an older file, a part not\n"
    "modelled) is 'not in this file' (null in JSON), one it holds as NaN 'not computed'; a quantity\n"
    "the file says does not converge with the mesh is flagged. A run that did not complete is said\n"
    "so on the first line, and none of its numbers is given as an answer.\n"
    "Writes PREFIX.txt (the text, also printed), PREFIX.json and PREFIX.png (normal forces, rotor\n"
    "and race speeds, race temperatures, the orbits at the retainers; by gnuplot). The three are\n"
    "written under a temporary directory PREFIX.partial-XXXXXX and renamed into place together:\n"
    "either all three are there, whole, or none is.\n"
    "\n"
    "options:\n"
    "  -o, --output PREFIX  write PREFIX.txt, PREFIX.json, PREFIX.png (default: the run file's name\n"
    "                       without .h5 plus '-report', in the current directory)\n"
    "      --json           print the JSON form instead of the text (the files are written as usual)\n"
    "  -h, --help           this help\n"
    "\n"
    "Refused (exit 2): a run file that is missing, not HDF5, or not a run file (a modal file, a sweep\n"
    "table); an output that is the run file; an output that exists and is not a regular file; an\n"
    "--output PREFIX that names no file ('', 'dir/', '.'); an output directory that does not exist or\n"
    "is not writable.\n"
    "\n"
    "environment: TOUCHDOWN_GNUPLOT names the gnuplot program (default: gnuplot on PATH).\n"
    "\n"
    "exit codes: 0 success (also for the report of a run that did not complete, which says so);\n"
    "1 gnuplot missing or failed, or a file could not be written (then none is left); 2 bad input\n"
    "or usage.\n";

static const char *const exts[3] = {".txt", ".json", ".png"};

typedef struct report_paths {
    char out[3][TD_OUTPUT_PATH_SIZE]; /* PREFIX.txt, .json, .png */
    char tmp[TD_OUTPUT_PATH_SIZE];    /* the temporary directory */
} report_paths;

static int usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "touchdown report: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, " (see touchdown report --help)\n");
    return TD_EXIT_USAGE;
}

/* Options into *prefix and *json; -1 to go on with argv[optind] the run file, else the exit code. */
static int parse(int argc, char **argv, const char **prefix, int *json)
{
    static const struct option longopts[] = {{"output", required_argument, NULL, 'o'},
                                             {"json", no_argument, NULL, 'j'},
                                             {"help", no_argument, NULL, 'h'},
                                             {NULL, 0, NULL, 0}};
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":o:h", longopts, NULL)) != -1) {
        switch (c) {
        case 'o': *prefix = optarg; break;
        case 'j': *json = 1; break;
        case 'h': fputs(report_usage, stdout); return TD_EXIT_OK;
        case ':': return usage_error("option '%s' needs a value", argv[optind - 1]);
        default: return usage_error("unknown option '%s'", argv[optind - 1]);
        }
    }
    if (optind >= argc)
        return usage_error("%s", "no run file given");
    if (argc - optind > 1)
        return usage_error("one run file at a time, not '%s' as well", argv[optind + 1]);
    return -1;
}

/* The default prefix: the run file's base name without .h5/.hdf5, plus "-report". */
static void default_prefix(const char *run, char *buf, size_t n)
{
    const char *base = strrchr(run, '/');
    size_t len;
    base = base ? base + 1 : run;
    len = strlen(base);
    if (len > 3 && !strcmp(base + len - 3, ".h5"))
        len -= 3;
    else if (len > 5 && !strcmp(base + len - 5, ".hdf5"))
        len -= 5;
    snprintf(buf, n, "%.*s-report", (int)(len < 200 ? len : 200), base);
}

/* The three outputs and the temporary directory beside them; refusals as the help says. */
static int choose_paths(const char *run, const char *prefix, report_paths *p)
{
    char stem[256];
    const char *from = prefix ? "--output" : run;
    int i, code;
    struct stat st;
    if (!prefix)
        default_prefix(run, stem, sizeof stem);
    else if ((code = td_cli_prefix(prefix, "report")) != 0)
        return code;
    for (i = 0; i < 3; i++) {
        if ((code = td_cli_path(p->out[i], sizeof p->out[i], prefix ? prefix : stem, exts[i], "report", from)))
            return code;
        if (td_output_same_file(p->out[i], run)) {
            td_cli_error("report", "%s: the output would overwrite the run file", p->out[i]);
            return TD_EXIT_USAGE;
        }
        if (stat(p->out[i], &st) == 0 && !S_ISREG(st.st_mode)) {
            td_cli_error("report", "%s: exists and is not a regular file", p->out[i]);
            return TD_EXIT_USAGE;
        }
    }
    return td_cli_path(p->tmp, sizeof p->tmp, prefix ? prefix : stem, ".partial-XXXXXX", "report", from);
}

/* dst = the temporary directory's NAME. */
static void inside(char *dst, size_t n, const report_paths *p, const char *name)
{
    snprintf(dst, n, "%s/%s", p->tmp, name);
}

/* Remove the temporary directory and what the report put in it. */
static void remove_tmp(const report_paths *p)
{
    static const char *const names[] = {"report.txt", "report.json", "report.png",
                                        "report.dat", "report.gp",   "report.log"};
    char path[TD_OUTPUT_PATH_SIZE + 32];
    size_t i;
    for (i = 0; i < sizeof names / sizeof names[0]; i++) {
        inside(path, sizeof path, p, names[i]);
        remove(path);
    }
    rmdir(p->tmp);
}

/* Write one form of the report into the temporary directory; 0 or 1 with a line printed. */
static int write_form(const report_paths *p, const char *name, const report *rep, void (*fn)(FILE *, const report *))
{
    char path[TD_OUTPUT_PATH_SIZE + 32];
    FILE *f;
    int failed;
    inside(path, sizeof path, p, name);
    if (!(f = fopen(path, "w"))) {
        td_cli_error("report", "cannot write %s: %s", path, strerror(errno));
        return TD_EXIT_FAILED;
    }
    fn(f, rep);
    failed = ferror(f);
    if (fclose(f) != 0 || failed) {
        td_cli_error("report", "writing %s failed", path);
        return TD_EXIT_FAILED;
    }
    return TD_EXIT_OK;
}

/* Rename the three into place (the figure first, the text last); on a failure take back those
 * already renamed: 0 or 1 with a line printed. */
static int publish(const report_paths *p)
{
    static const char *const names[3] = {"report.txt", "report.json", "report.png"};
    char path[TD_OUTPUT_PATH_SIZE + 32];
    int i, j;
    for (i = 2; i >= 0; i--) {
        inside(path, sizeof path, p, names[i]);
        if (rename(path, p->out[i]) != 0) {
            td_cli_error("report", "cannot rename %s to %s: %s", path, p->out[i], strerror(errno));
            for (j = 2; j > i; j--)
                remove(p->out[j]);
            return TD_EXIT_FAILED;
        }
    }
    return TD_EXIT_OK;
}

/* Write the three forms into the temporary directory and rename them into place. */
static int write_all(const td_result *r, const report *rep, const report_paths *p)
{
    int code = write_form(p, "report.txt", rep, report_write_text);
    if (!code)
        code = write_form(p, "report.json", rep, report_write_json);
    if (!code && report_figure(r, rep, p->tmp, "report") != 0)
        code = TD_EXIT_FAILED;
    if (!code)
        code = publish(p);
    remove_tmp(p);
    return code;
}

int td_cmd_report(int argc, char **argv)
{
    const char *prefix = NULL, *run;
    int json = 0, code;
    report_paths paths;
    td_result *r = NULL;
    td_error err;
    report *rep;
    if ((code = parse(argc, argv, &prefix, &json)) >= 0)
        return code;
    run = argv[optind];
    if ((code = choose_paths(run, prefix, &paths)))
        return code;
    if (td_result_open(run, &r, &err) != TD_OK) {
        td_cli_error("report", "%s", err.message);
        return TD_EXIT_USAGE;
    }
    if (!(rep = calloc(1, sizeof *rep))) {
        td_result_free(&r);
        td_cli_error("report", "out of memory");
        return TD_EXIT_FAILED;
    }
    code = report_read(r, run, rep);
    if (!code && !mkdtemp(paths.tmp)) {
        td_cli_error("report", "cannot create %s: %s", paths.tmp, strerror(errno));
        code = TD_EXIT_USAGE;
    }
    if (!code)
        code = write_all(r, rep, &paths);
    if (!code)
        (json ? report_write_json : report_write_text)(stdout, rep);
    free(rep);
    td_result_free(&r);
    return code;
}
