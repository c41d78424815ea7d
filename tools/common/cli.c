/* Helpers shared by the subcommands: overrides, case loading, error lines, exit codes. */
#include "common/cli.h"

#include "touchdown/json.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Set by on_signal; a signal handler can reach nothing else. */
static volatile sig_atomic_t cli_signalled;

static void on_signal(int sig)
{
    (void)sig;
    cli_signalled = 1;
}

volatile sig_atomic_t *td_cli_catch_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    struct sigaction sa;
    size_t i;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    cli_signalled = 0;
    for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++)
        sigaction(sigs[i], &sa, NULL);
    return &cli_signalled;
}

int td_cli_add_set(td_cli_sets *sets, const char *kv)
{
    if (sets->count >= TD_CLI_MAX_SETS) {
        td_cli_error("--set", "at most %d overrides", TD_CLI_MAX_SETS);
        return TD_EXIT_USAGE;
    }
    sets->items[sets->count++] = kv;
    return TD_EXIT_OK;
}

/* A case that cannot be loaded: "touchdown: MESSAGE", exit 2. */
static int load_failed(td_status st, const td_error *err)
{
    fprintf(stderr, "touchdown: %s\n", err->message[0] ? err->message : td_strerror(st));
    return TD_EXIT_USAGE;
}

td_status td_cli_case_checked(const char *path, const char *const *items, int count, td_case **out, td_error *err)
{
    td_status st = td_case_load(path, items, count, out, err);
    /* the sweep group is judged whichever command loads the case (docs/case-format.md, "sweep") */
    if (st == TD_OK && (st = td_sweep_check_case(*out, err)) != TD_OK)
        td_case_free(out);
    return st;
}

int td_cli_load_case(const char *path, const td_cli_sets *sets, td_case **out)
{
    td_error err;
    td_status st;
    int code;
    td_error_clear(&err);
    st = td_cli_case_checked(path, sets ? sets->items : NULL, sets ? sets->count : 0, out, &err);
    if (st != TD_OK)
        return load_failed(st, &err);
    if ((code = td_cli_probe_plugins(*out)) != TD_EXIT_OK)
        td_case_free(out);
    return code;
}

int td_cli_job_create(const char *path, const td_cli_sets *sets, td_job **out)
{
    td_error err;
    td_status st;
    int code;
    td_error_clear(&err);
    st = td_job_create(path, sets ? sets->items : NULL, sets ? sets->count : 0, out, &err);
    /* as td_cli_case_checked: the sweep group is judged whichever command loads the case */
    if (st == TD_OK && (st = td_sweep_check_case(td_job_case(*out), &err)) != TD_OK)
        td_job_free(out);
    if (st != TD_OK)
        return load_failed(st, &err);
    if ((code = td_cli_probe_plugins(td_job_case(*out))) != TD_EXIT_OK)
        td_job_free(out);
    return code;
}

int td_cli_exit_code(td_status st)
{
    switch (st) {
    case TD_OK:
    case TD_EVENT: return TD_EXIT_OK;
    case TD_ERR_PARSE:
    case TD_ERR_INVALID: return TD_EXIT_USAGE;
    default: return TD_EXIT_FAILED;
    }
}

int td_cli_path(char *dst, size_t n, const char *stem, const char *ext, const char *cmd, const char *from)
{
    size_t a = strlen(stem), b = strlen(ext);
    if (a + b >= n) {
        td_cli_error(cmd, "%s: the path '%.40s...%s' is %lu characters long, at most %lu are supported", from, stem,
                     ext, (unsigned long)(a + b), (unsigned long)(n - 1));
        return TD_EXIT_USAGE;
    }
    memcpy(dst, stem, a);
    memcpy(dst + a, ext, b + 1);
    return 0;
}

int td_cli_prefix(const char *prefix, const char *cmd)
{
    const char *slash = strrchr(prefix, '/'), *name = slash ? slash + 1 : prefix;
    if (*name && strcmp(name, ".") && strcmp(name, ".."))
        return 0;
    td_cli_error(
        cmd, "--output '%s' names no file (it would write '%s.csv'): give the outputs a name, e.g. --output %s%sresult",
        prefix, prefix, prefix, *name ? "/" : "");
    return TD_EXIT_USAGE;
}

void td_cli_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "touchdown %s: ", cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

void td_cli_json_string(FILE *f, const char *s)
{
    char small[1024], *big;
    int n = td_json_string(small, sizeof small, s);
    if (n < (int)sizeof small) {
        fputs(small, f);
        return;
    }
    big = malloc((size_t)n + 1);
    if (big)
        td_json_string(big, (size_t)n + 1, s);
    fputs(big ? big : "\"\"", f);
    free(big);
}

double td_cli_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
