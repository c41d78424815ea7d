/*
 * The plug-in probe (cli.h, td_cli_probe_plugins): a plug-in controller is the user's own code,
 * loaded into this process; a crash in it would take the tool with it, and the library may not fork
 * or catch signals. So before a case is used, each plug-in's init, one step and free run in a child
 * process, which reports through a pipe which call it entered and why init refused; a child that
 * dies of a signal is the one-line error naming the case's file, line and key and the signal,
 * exit 2, and nothing is run.
 */
#include "common/cli.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

/* Seconds a child may take before it is stopped (SIGALRM): an init that never returns would
 * otherwise hang the tool before its run. */
#define PROBE_SECONDS 60
/* The most axes a plug-in is handed (a controller drives at most 16 AMBs). */
#define PROBE_MAX_AXES 64

/* The signals that end a process, by name (the messages name the signal as a user looks it up). */
static const char *signal_name(int sig)
{
    static const struct {
        int sig;
        const char *name;
    } names[] = {{SIGSEGV, "SIGSEGV"}, {SIGBUS, "SIGBUS"},   {SIGFPE, "SIGFPE"},   {SIGILL, "SIGILL"},
                 {SIGABRT, "SIGABRT"}, {SIGALRM, "SIGALRM"}, {SIGKILL, "SIGKILL"}, {SIGTRAP, "SIGTRAP"},
                 {SIGTERM, "SIGTERM"}, {SIGSYS, "SIGSYS"},   {SIGPIPE, "SIGPIPE"}, {SIGXCPU, "SIGXCPU"}};
    size_t i;
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        if (names[i].sig == sig)
            return names[i].name;
    return "a signal";
}

static void put(int fd, const char *text, size_t n)
{
    while (n > 0) {
        ssize_t w = write(fd, text, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return;
        text += w;
        n -= (size_t)w;
    }
}

/* stdout and stderr to /dev/null (left as they are when it cannot be opened). */
static void quiet(void)
{
    int null = open("/dev/null", O_WRONLY);
    if (null < 0)
        return;
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
    close(null);
}

/* The child: the signals a crash raises back to their default action (a sanitiser's handler would
 * turn the crash into an exit status), no core file, its output to /dev/null (the parent's one line
 * says what happened; the run calls init again, with its output); then init, one step from rest and
 * free, each announced on fd before it is called ('i', 's', 'f'), and 'd' once free has returned;
 * init's refusal is 'R' and its reason. A plug-in that ends the process itself (exit(0) in its init)
 * never writes the 'd': only the whole sequence is a success. */
static void child(const td_plugin_spec *p, int fd)
{
    static const int crashes[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
    const td_plugin_controller *f = p->functions;
    struct rlimit no_core = {0, 0};
    char message[TD_ERROR_MESSAGE_SIZE] = "";
    double sensed[PROBE_MAX_AXES] = {0.0}, command[PROBE_MAX_AXES];
    td_plugin_setup setup;
    void *instance;
    size_t i;
    for (i = 0; i < sizeof crashes / sizeof crashes[0]; i++)
        signal(crashes[i], SIG_DFL);
    setrlimit(RLIMIT_CORE, &no_core);
    quiet();
    alarm(PROBE_SECONDS);
    td_plugin_spec_setup(p, &setup);
    put(fd, "i", 1);
    if (!(instance = f->init(&setup, message, (int)sizeof message))) {
        message[sizeof message - 1] = '\0';
        put(fd, "R", 1);
        put(fd, message, strlen(message));
        _exit(3);
    }
    put(fd, "s", 1);
    (void)f->step(instance, 0, 0.0, sensed, command, message, (int)sizeof message); /* the run judges its outputs */
    put(fd, "f", 1);
    f->free(instance);
    put(fd, "d", 1);
    _exit(0);
}

/* What the child wrote, NUL-terminated; returns its length. */
static size_t drain(int fd, char *buf, size_t n)
{
    size_t got = 0;
    for (;;) {
        ssize_t r = read(fd, buf + got, n - 1 - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0 || (got += (size_t)r) == n - 1)
            break;
    }
    buf[got] = '\0';
    return got;
}

/* The call the child was in when it stopped: the last it announced before any refusal. */
static const char *phase(const char *said)
{
    const char *p = "init";
    for (; *said && *said != 'R'; said++)
        p = *said == 's' ? "step" : *said == 'f' || *said == 'd' ? "free" : "init";
    return p;
}

/* The child's end as the one-line error (exit 2), or 0 when init, step and free all returned (it
 * said "isfd" and exited 0: an exit status 0 alone may be the plug-in's own exit(0)). A refusal's
 * reason is the plug-in's text: its control characters (a stray newline) become spaces. */
static int judge(const char *where, const td_plugin_spec *p, int status, char *said)
{
    char *refused = strchr(said, 'R'), *q;
    for (q = refused; q && *q; q++)
        *q = (unsigned char)*q < 0x20 || *q == 0x7f ? ' ' : *q;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && strcmp(said, "isfd") == 0)
        return TD_EXIT_OK;
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
        fprintf(stderr, "touchdown: %s: the plug-in \"%s\" did not return from its %s within %d s\n", where, p->name,
                phase(said), PROBE_SECONDS);
    else if (WIFSIGNALED(status))
        fprintf(stderr, "touchdown: %s: the plug-in \"%s\" crashed in its %s (%s, %s); nothing was run\n", where,
                p->name, phase(said), signal_name(WTERMSIG(status)), strsignal(WTERMSIG(status)));
    else if (refused && WEXITSTATUS(status) == 3)
        fprintf(stderr, "touchdown: %s: the plug-in \"%s\" refused to start: %s\n", where, p->name,
                refused[1] ? refused + 1 : "(it gave no reason)");
    else
        fprintf(stderr, "touchdown: %s: the plug-in \"%s\" ended the process in its %s (exit status %d)\n", where,
                p->name, phase(said), WEXITSTATUS(status));
    return TD_EXIT_USAGE;
}

/* Plug-in i of case c tried in a child; 0 or the exit code, its error printed. */
static int probe(const td_case *c, int i, const td_plugin_spec *p)
{
    td_case_controller_info info;
    char said[TD_ERROR_MESSAGE_SIZE + 8];
    int fds[2], status = 0;
    pid_t pid;
    if (td_case_controller(c, i, &info) != TD_OK || !info.where)
        info.where = td_case_path(c);
    if (p->n_inputs > PROBE_MAX_AXES || p->n_outputs > PROBE_MAX_AXES)
        return TD_EXIT_OK; /* the model bounds them below this; nothing to try it with */
    fflush(NULL);          /* the child's copies of unwritten output would be written twice */
    if (pipe(fds) != 0)
        fds[0] = fds[1] = -1;
    if (fds[0] < 0 || (pid = fork()) < 0) {
        fprintf(stderr, "touchdown: %s: cannot try the plug-in \"%s\" in a child process first: %s\n", info.where,
                p->name, strerror(errno));
        if (fds[0] >= 0) {
            close(fds[0]);
            close(fds[1]);
        }
        return TD_EXIT_FAILED;
    }
    if (pid == 0) {
        close(fds[0]);
        child(p, fds[1]);
    }
    close(fds[1]);
    drain(fds[0], said, sizeof said);
    close(fds[0]);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    return judge(info.where, p, status, said);
}

int td_cli_probe_plugins(const td_case *c)
{
    const td_model *m = td_case_model(c);
    int i, code = TD_EXIT_OK;
    for (i = 0; code == TD_EXIT_OK && i < td_model_controller_count(m); i++) {
        const td_plugin_spec *p = td_model_get_plugin(m, i);
        if (p && p->functions)
            code = probe(c, i, p);
    }
    return code;
}
