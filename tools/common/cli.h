/* The touchdown command-line tool: shared declarations of its subcommands. No physics here. */
#ifndef TD_TOOLS_CLI_H
#define TD_TOOLS_CLI_H

#include "touchdown/case.h"
#include "touchdown/job.h"
#include "touchdown/touchdown.h"

#include <signal.h>
#include <stdio.h>

/* Exit codes (documented in every command's --help). */
enum {
    TD_EXIT_OK = 0,     /* success */
    TD_EXIT_FAILED = 1, /* the simulation or analysis failed (solver, numerics, interrupted, output) */
    TD_EXIT_USAGE = 2   /* bad input: usage, case file, overrides */
};

/* Largest number of --set overrides on one command line. */
#define TD_CLI_MAX_SETS 64

/* --set KEY=VALUE overrides collected from the command line. */
typedef struct td_cli_sets {
    const char *items[TD_CLI_MAX_SETS];
    int count;
} td_cli_sets;

/* Add one --set argument; prints an error and returns TD_EXIT_USAGE when there are too many. */
int td_cli_add_set(td_cli_sets *sets, const char *kv);

/* Load a case with `count` overrides and judge its sweep group, as every command loads one
 * (td_case_load, td_sweep_check_case); on failure *out is NULL and err says why. Prints nothing. */
td_status td_cli_case_checked(const char *path, const char *const *items, int count, td_case **out, td_error *err);

/* Each plug-in controller of case c (touchdown/plugin.h) tried before the case is used: its init,
 * one step from rest and its free, in a child process (probe.c), so that a crash in the user's code
 * never takes the tool with it. A child that dies of a signal, or an init that refuses, prints
 * "touchdown: FILE:LINE: controllers[i].plugin.library: ..." and returns TD_EXIT_USAGE; else 0. */
int td_cli_probe_plugins(const td_case *c);

/* td_cli_case_checked with the --set overrides, and its plug-ins probed (td_cli_probe_plugins); on
 * failure print "touchdown: MESSAGE" and return TD_EXIT_USAGE. */
int td_cli_load_case(const char *path, const td_cli_sets *sets, td_case **out);

/* The job of a case with overrides (touchdown/job.h); on failure as td_cli_load_case. */
int td_cli_job_create(const char *path, const td_cli_sets *sets, td_job **out);

/* Catch SIGINT, SIGTERM and SIGHUP (a closed terminal, a dropped ssh) from now on: each sets the
 * returned flag (cleared here), which the command reads to stop and keep what it has written. */
volatile sig_atomic_t *td_cli_catch_signals(void);

/* Seconds on the monotonic clock, for the tool's own wall times and progress lines (the library's
 * clock is internal); only differences mean anything. */
double td_cli_now(void);

/* `s` as a JSON string into f, escaped by the library (touchdown/json.h); "" if it cannot be held. */
void td_cli_json_string(FILE *f, const char *s);

/* Map a library status to an exit code: input errors 2, everything else 1. */
int td_cli_exit_code(td_status st);

/* dst (n bytes) = stem + ext; a path that does not fit is an error line naming `from` (the
 * option or file it came from) and TD_EXIT_USAGE, never a shortened path. Returns 0 when it fits. */
int td_cli_path(char *dst, size_t n, const char *stem, const char *ext, const char *cmd, const char *from);

/* 0 when PREFIX (of --output) ends in a file name, as PREFIX.csv and PREFIX.h5 need: else an error
 * line and TD_EXIT_USAGE. An empty prefix, one ending in '/' or in '.' or '..' would name hidden
 * files ('.csv', 'dir/.h5', '..csv') that nobody asked for. */
int td_cli_prefix(const char *prefix, const char *cmd);

/* Print an error line "touchdown CMD: message" to stderr. */
void td_cli_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

int td_cmd_run(int argc, char **argv);
int td_cmd_modal(int argc, char **argv);
int td_cmd_info(int argc, char **argv);
int td_cmd_plot(int argc, char **argv);
int td_cmd_bench(int argc, char **argv);
int td_cmd_sweep(int argc, char **argv);
int td_cmd_fmu(int argc, char **argv);
int td_cmd_report(int argc, char **argv);

#endif
