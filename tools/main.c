/*
 * touchdown - simulate flexible rotors on active magnetic bearings through retainer contact.
 * This file only dispatches to the subcommands.
 */
#include "common/cli.h"
#include "sweep/sweep_mpi.h"

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

static const char usage[] =
    "usage: touchdown COMMAND [OPTIONS] CASE|FILE\n"
    "\n"
    "Simulate a flexible rotor on active magnetic bearings (AMBs) through contact with its\n"
    "retainer (backup) bearings, after Sahinkaya, Abulrub and Keogh.\n"
    "\n"
    "commands:\n"
    "  run CASE        simulate a case file to HDF5/CSV and print a summary\n"
    "  modal CASE      modes, Campbell diagram, critical speeds, unbalance response\n"
    "  info CASE       what a case describes: nodes, masses, bearings, retainers, DOFs, first modes\n"
    "  plot OUT.h5...  figures (PNG + gnuplot scripts) from output files\n"
    "  sweep CASE      run a case over a grid of key values in parallel: one summary row per point\n"
    "  bench           time the paper's cases with the constrained and penalty models\n"
    "  fmu CASE        pack a case as an FMU (FMI 2.0 co-simulation) for Simulink, OpenModelica, Python\n"
    "  report RUN.h5   the one-page drop report: each quantity beside its limit from the case\n"
    "\n"
    "options for every command:\n"
    "  -h, --help      help for the command (touchdown COMMAND --help)\n"
    "  --version       print the library version and whether touchdown sweep has MPI\n"
    "\n"
    "exit codes: 0 success, 1 the simulation or analysis failed, 2 bad input or usage.\n"
    "Case files: docs/case-format.md. Output files: docs/output-format.md.\n";

typedef int (*td_command_fn)(int argc, char **argv);

static const struct {
    const char *name;
    td_command_fn fn;
} commands[] = {
    {"run", td_cmd_run},     {"modal", td_cmd_modal}, {"info", td_cmd_info}, {"plot", td_cmd_plot},
    {"bench", td_cmd_bench}, {"sweep", td_cmd_sweep}, {"fmu", td_cmd_fmu},   {"report", td_cmd_report},
};

/* One run is one thread. OpenBLAS (which SLICOT loads as the system's libblas) starts a worker
 * thread per core as it loads, and each spins on sched_yield before it sleeps: about 0.1 s of CPU
 * of every run on another core, paid once per point by a sweep and by the other jobs of a busy
 * machine. Its count asked down to one, the workers are ended (blas_thread_shutdown_, the routine
 * OpenBLAS's own fork handler calls); with one thread asked for, no BLAS call starts them again.
 * Asked by name, so that another BLAS (none of these symbols) changes nothing; a user's
 * OPENBLAS_NUM_THREADS is theirs to keep. */
static void blas_on_one_thread(void)
{
    void *self;
    void (*set_threads)(int);
    int (*end_workers)(void);
    if (getenv("OPENBLAS_NUM_THREADS"))
        return;
    self = dlopen(NULL, RTLD_LAZY);
    if (!self)
        return;
    *(void **)&set_threads = dlsym(self, "openblas_set_num_threads");
    *(void **)&end_workers = dlsym(self, "blas_thread_shutdown_");
    if (set_threads && end_workers) {
        set_threads(1);
        end_workers();
    }
    dlclose(self);
}

int main(int argc, char **argv)
{
    size_t i;
    blas_on_one_thread();
    if (argc < 2) {
        fputs(usage, stderr);
        return TD_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        fputs(usage, stdout);
        return TD_EXIT_OK;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version")) {
        char mpi[160];
        sweep_mpi_describe(mpi, sizeof mpi);
        printf("touchdown %s\n%s (for touchdown sweep)\n", td_version(), mpi);
        return TD_EXIT_OK;
    }
    for (i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            /* getopt prefixes its messages with argv[0]: make that "touchdown CMD" */
            char name[64];
            snprintf(name, sizeof name, "touchdown %s", commands[i].name);
            argv[1] = name;
            return commands[i].fn(argc - 1, argv + 1);
        }
    fprintf(stderr, "touchdown: unknown command '%s'\n\n%s", argv[1], usage);
    return TD_EXIT_USAGE;
}
