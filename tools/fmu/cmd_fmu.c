/* touchdown fmu: a case packed as an FMU for co-simulation (FMI 2.0), for an importer that closes the
 * loop around it (Simulink, OpenModelica, Dymola, fmpy). The library stages the FMU's files
 * (td_fmu_stage); this command adds the binary and writes the archive. */
#include "common/cli.h"
#include "fmu/fmu_pack.h"
#include "touchdown/fmu.h"
#include "touchdown/output.h"

#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef TD_FMU_FROM_BIN
#define TD_FMU_FROM_BIN "../lib/touchdown" /* an install's FMU binary, relative to the tool's directory */
#endif

/* The generic FMU binary (fmu/ of the source tree), renamed to the model identifier in each FMU. */
#define FMU_BINARY "touchdown-fmu.so"

static const char fmu_usage[] =
    "usage: touchdown fmu [OPTIONS] CASE -o NAME.fmu\n"
    "\n"
    "Pack CASE as a Functional Mock-up Unit for co-simulation (FMI 2.0) that Simulink, OpenModelica,\n"
    "Dymola or Python (fmpy) import to close a loop around the rotor, its AMBs and its retainers\n"
    "(docs/fmu.md): modelDescription.xml (model identifier NAME), the case and its settings in\n"
    "resources/, and the binary for 64-bit Linux in binaries/linux64/NAME.so. The FMU needs none of\n"
    "the files it was made from: it runs on any 64-bit Linux machine with the libraries touchdown\n"
    "links (Debian: the runtime packages of those scripts/setup.sh installs).\n"
    "\n"
    "options:\n"
    "  -o, --output NAME.fmu  the FMU to write (required); NAME, its model identifier, is a C\n"
    "                         identifier: a letter or '_', then letters, digits or '_', at\n"
    "                         most 63 characters\n"
    "  -i, --inputs KIND      what the FMU's inputs drive: \"current\" (default), a current command\n"
    "                         per AMB axis (A) into the amplifier; \"force\", a control force per AMB\n"
    "                         axis (N); \"none\", no inputs: the case's own AMB laws and controllers\n"
    "  -s, --set KEY=VALUE    override a case key (repeatable; keys as in docs/case-format.md)\n"
    "  -q, --quiet            print nothing on success\n"
    "  -h, --help             this help\n"
    "\n"
    "The FMU is written under a temporary name, NAME.fmu.XXXXXX.partial, and renamed to NAME.fmu\n"
    "when complete: a failed or interrupted command leaves NAME.fmu as it was. The same case and\n"
    "options give the same bits. Refused (exit 2): an output that does not end in .fmu or whose\n"
    "NAME is no C identifier, an output that is the case file or one of its @include files, an\n"
    "output that exists and is not an FMU (a zip archive), an output directory that does not exist.\n"
    "\n"
    "exit codes: 0 written, 1 it could not be written (the FMU binary missing, a full disk,\n"
    "interrupted), 2 bad input or usage.\n";

typedef struct fmu_args {
    const char *case_path, *out;
    td_fmu_inputs inputs;
    td_cli_sets sets;
    int quiet;
} fmu_args;

/* NAME of dir/NAME.fmu into id (n bytes): the model identifier, which td_fmu_stage judges. 0, or an
 * error line and 2. */
static int model_identifier(const char *out, char *id, size_t n)
{
    const char *slash = strrchr(out, '/'), *name = slash ? slash + 1 : out;
    size_t len = strlen(name);
    if (len < 4 || strcmp(name + len - 4, ".fmu") != 0) {
        td_cli_error("fmu", "--output '%s': an FMU's name ends in .fmu (FMI 2.0, 2.3)", out);
        return TD_EXIT_USAGE;
    }
    snprintf(id, n, "%.*s", (int)(len - 4 < n ? len - 4 : n - 1), name);
    return 0;
}

/* 1 if the file at path begins as a zip archive does (a local file header, or the end record of an
 * empty archive): what a previous FMU is, and what an input (a case file) never is. */
static int looks_like_zip(const char *path)
{
    unsigned char head[4] = {0, 0, 0, 0};
    FILE *f = fopen(path, "rb");
    size_t got = f ? fread(head, 1, sizeof head, f) : 0;
    if (f)
        fclose(f);
    return got == 4 && head[0] == 'P' && head[1] == 'K' &&
           ((head[2] == 3 && head[3] == 4) || (head[2] == 5 && head[3] == 6));
}

/* The output: not a directory nor any other non-file, not a file that is not an FMU, in a directory
 * that exists, not one of the case's files. 0, or an error line and 2. */
static int check_output(const char *out, const td_case *c)
{
    const char *const *files;
    int i, n = 0;
    struct stat sb;
    char dir[4096];
    const char *slash = strrchr(out, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - out + 1) : 1, slash ? out : ".");
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        td_cli_error("fmu", "--output '%s': the directory %s does not exist", out, dir);
        return TD_EXIT_USAGE;
    }
    files = td_case_files(c, &n);
    for (i = 0; i < n; i++)
        if (td_output_same_file(out, files[i])) {
            td_cli_error("fmu", "--output '%s' is the same file as the %s (%s): an input is never overwritten", out,
                         i == 0 ? "case file" : "@include file", files[i]);
            return TD_EXIT_USAGE;
        }
    if (stat(out, &sb) == 0 && (!S_ISREG(sb.st_mode) || (sb.st_size > 0 && !looks_like_zip(out)))) {
        td_cli_error("fmu", "--output '%s' exists and is not an FMU (%s): it is not overwritten", out,
                     S_ISREG(sb.st_mode) ? "not a zip archive" : "not a regular file");
        return TD_EXIT_USAGE;
    }
    return 0;
}

/* The FMU binary: beside the tool (the build tree), else where an install puts it
 * (TD_FMU_FROM_BIN from the tool's directory). 0 with its path in path, or an error line and 1. */
static int find_binary(char *path, size_t n)
{
    char exe[4096], tried[4200];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash;
    if (len <= 0) {
        td_cli_error("fmu", "cannot find the tool's own directory (/proc/self/exe): %s", strerror(errno));
        return TD_EXIT_FAILED;
    }
    exe[len] = '\0';
    slash = strrchr(exe, '/');
    *slash = '\0';
    snprintf(path, n, "%s/%s", exe, FMU_BINARY);
    if (access(path, R_OK) == 0)
        return 0;
    snprintf(tried, sizeof tried, "%s", path);
    snprintf(path, n, "%s/%s/%s", exe, TD_FMU_FROM_BIN, FMU_BINARY);
    if (access(path, R_OK) == 0)
        return 0;
    td_cli_error("fmu", "the FMU binary %s is missing: not at %s nor at %s (build or install touchdown whole)",
                 FMU_BINARY, tried, path);
    return TD_EXIT_FAILED;
}

static int parse_inputs(const char *s, td_fmu_inputs *inputs)
{
    if (!strcmp(s, "current"))
        *inputs = TD_FMU_INPUTS_CURRENT;
    else if (!strcmp(s, "force"))
        *inputs = TD_FMU_INPUTS_FORCE;
    else if (!strcmp(s, "none"))
        *inputs = TD_FMU_INPUTS_NONE;
    else {
        td_cli_error("fmu", "--inputs is \"current\", \"force\" or \"none\", not '%s'", s);
        return TD_EXIT_USAGE;
    }
    return 0;
}

/* The command line into a; -1 when it asked for the help (printed), else 0 or an exit code. */
static int parse_args(int argc, char **argv, fmu_args *a)
{
    static const struct option longopts[] = {
        {"output", required_argument, NULL, 'o'}, {"inputs", required_argument, NULL, 'i'},
        {"set", required_argument, NULL, 's'},    {"quiet", no_argument, NULL, 'q'},
        {"help", no_argument, NULL, 'h'},         {NULL, 0, NULL, 0}};
    int opt;
    optind = 1;
    while ((opt = getopt_long(argc, argv, "o:i:s:qh", longopts, NULL)) != -1) {
        switch (opt) {
        case 'o': a->out = optarg; break;
        case 'i':
            if (parse_inputs(optarg, &a->inputs))
                return TD_EXIT_USAGE;
            break;
        case 's':
            if (td_cli_add_set(&a->sets, optarg))
                return TD_EXIT_USAGE;
            break;
        case 'q': a->quiet = 1; break;
        case 'h': fputs(fmu_usage, stdout); return -1;
        default: fputs(fmu_usage, stderr); return TD_EXIT_USAGE;
        }
    }
    if (optind != argc - 1) {
        td_cli_error("fmu", "expected exactly one case file (see touchdown fmu --help)");
        return TD_EXIT_USAGE;
    }
    a->case_path = argv[optind];
    if (!a->out) {
        td_cli_error("fmu", "no output: give the FMU's name with -o NAME.fmu");
        return TD_EXIT_USAGE;
    }
    return 0;
}

/* Stage the FMU's files into a new temporary directory (stage, n bytes), then pack them with the
 * binary into a->out; the directory removed whatever happens. 0 or an exit code. */
static int stage_and_pack(const fmu_args *a, const char *id, const char *binary, char *stage, size_t n)
{
    const char *tmpdir = getenv("TMPDIR");
    volatile sig_atomic_t *cancel = td_cli_catch_signals();
    char msg[1200];
    td_error err;
    td_status st;
    int code = 0;
    snprintf(stage, n, "%s/touchdown-fmu.XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
    if (!mkdtemp(stage)) {
        td_cli_error("fmu", "cannot create a temporary directory %s: %s", stage, strerror(errno));
        return TD_EXIT_FAILED;
    }
    td_error_clear(&err);
    st = td_fmu_stage(a->case_path, a->sets.items, a->sets.count, a->inputs, id, stage, &err);
    if (st != TD_OK) {
        /* TD_ERR_INVALID: the model identifier, which is the output's name (the case's errors are
         * TD_ERR_PARSE or TD_ERR_IO) */
        td_cli_error("fmu", "%s%s%s%s", st == TD_ERR_INVALID ? "--output '" : "", st == TD_ERR_INVALID ? a->out : "",
                     st == TD_ERR_INVALID ? "': " : "", err.message[0] ? err.message : td_strerror(st));
        code = td_cli_exit_code(st);
    } else if (*cancel || fmu_pack(stage, binary, id, a->out, cancel, msg, sizeof msg) != 0) {
        td_cli_error("fmu", "%s: %s", a->out, *cancel ? "interrupted" : msg);
        code = TD_EXIT_FAILED;
    }
    if (fmu_remove_tree(stage) != 0 && code == 0) {
        td_cli_error("fmu", "cannot remove the temporary directory %s: %s", stage, strerror(errno));
        code = TD_EXIT_FAILED;
    }
    return code;
}

int td_cmd_fmu(int argc, char **argv)
{
    fmu_args a;
    td_case *c = NULL;
    char id[4096], binary[4200], stage[4200];
    int code;
    memset(&a, 0, sizeof a);
    a.inputs = TD_FMU_INPUTS_CURRENT;
    if ((code = parse_args(argc, argv, &a)))
        return code < 0 ? TD_EXIT_OK : code;
    if ((code = model_identifier(a.out, id, sizeof id)))
        return code;
    /* the case read as the FMU will read it, for its errors and its files (never overwritten) */
    if ((code = td_cli_load_case(a.case_path, &a.sets, &c)))
        return code;
    code = check_output(a.out, c);
    td_case_free(&c);
    if (code || (code = find_binary(binary, sizeof binary)))
        return code;
    if ((code = stage_and_pack(&a, id, binary, stage, sizeof stage)))
        return code;
    if (!a.quiet)
        printf("%s: FMI 2.0 co-simulation, model identifier %s, inputs %s\n", a.out, id,
               a.inputs == TD_FMU_INPUTS_CURRENT ? "AMB currents"
               : a.inputs == TD_FMU_INPUTS_FORCE ? "AMB forces"
                                                 : "none (the case's own controllers)");
    return TD_EXIT_OK;
}
