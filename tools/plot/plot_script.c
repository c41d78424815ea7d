/* touchdown plot: output directory, data and script files, and running gnuplot on the scripts. */
#include "plot/plot.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

const char *plot_ext(const plot_opts *opt)
{
    return opt->svg ? "svg" : "png";
}

void plot_remove_new_dirs(const char *dir, size_t created)
{
    char path[PLOT_PATH_SIZE];
    size_t len;
    if (!created || (len = strlen(dir)) >= sizeof path)
        return;
    memcpy(path, dir, len + 1);
    for (;;) {
        while (len > 1 && path[len - 1] == '/')
            path[--len] = '\0';
        /* rmdir removes only an empty directory: whatever holds a file stays, and so do its parents */
        if (len < created || (rmdir(path) != 0 && errno != ENOENT))
            return;
        while (len > 0 && path[len - 1] != '/')
            len--;
        path[len] = '\0';
    }
}

int plot_make_dir(const char *dir, size_t *created)
{
    char path[PLOT_PATH_SIZE];
    struct stat st;
    size_t i, len = strlen(dir);
    *created = 0;
    if (len == 0 || len >= sizeof path) {
        fprintf(stderr, "touchdown plot: bad output directory '%s'\n", dir);
        return PLOT_BAD_INPUT;
    }
    memcpy(path, dir, len + 1);
    /* mkdir -p: every prefix ending before a '/', then the whole path */
    for (i = 1; i <= len; i++) {
        if (path[i] != '/' && path[i] != '\0')
            continue;
        path[i] = '\0';
        if (mkdir(path, 0777) == 0) {
            if (!*created)
                *created = i;
        } else if (errno != EEXIST) {
            fprintf(stderr, "touchdown plot: cannot create directory %s: %s\n", path, strerror(errno));
            plot_remove_new_dirs(dir, *created);
            *created = 0;
            return PLOT_BAD_INPUT;
        }
        path[i] = i < len ? '/' : '\0';
    }
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "touchdown plot: %s exists and is not a directory\n", dir);
        return PLOT_BAD_INPUT;
    }
    return PLOT_OK;
}

/* buf = dir/name; 0, or -1 (said on stderr) when it does not fit: a path is never shortened. */
static int join(char *buf, size_t n, const char *dir, const char *name)
{
    if (snprintf(buf, n, "%s%s%s", dir, dir[strlen(dir) - 1] == '/' ? "" : "/", name) < (int)n)
        return 0;
    fprintf(stderr, "touchdown plot: %s/%s: the path is longer than %lu characters\n", dir, name, (unsigned long)n - 1);
    return -1;
}

FILE *plot_open(const plot_opts *opt, const char *name)
{
    char path[PLOT_PATH_SIZE];
    FILE *f;
    if (join(path, sizeof path, opt->dir, name))
        return NULL;
    f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "touchdown plot: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

int plot_close(FILE *f, const plot_opts *opt, const char *name)
{
    int failed = ferror(f);
    if (fclose(f) != 0 || failed) {
        char path[PLOT_PATH_SIZE];
        join(path, sizeof path, opt->dir, name);
        fprintf(stderr, "touchdown plot: writing %s failed\n", path);
        return PLOT_FAILED;
    }
    return PLOT_OK;
}

void plot_leaps_begin(plot_leaps *l, const double *time, size_t n)
{
    l->time = time;
    l->n = time ? n : 0;
    l->k = 0;
}

void plot_leap_break(FILE *out, plot_leaps *l, const double *t, size_t i)
{
    if (i == 0)
        return;
    while (l->k < l->n && !(l->time[l->k] >= t[i - 1])) /* passed (or NaN): no row will be at it */
        l->k++;
    if (l->k < l->n && l->time[l->k] == t[i - 1] && t[i] > t[i - 1])
        fputc('\n', out);
}

void plot_gp_string(FILE *f, const char *s)
{
    /* double quotes so that a newline can be written as \n (two-line titles) */
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            fprintf(f, "\\%c", *s);
        else if (*s == '\n')
            fputs("\\n", f);
        else if (*s == '\r' || *s == '\t')
            fputc(' ', f);
        else
            fputc(*s, f);
    }
    fputc('"', f);
}

void plot_var_string(FILE *f, const char *name, const char *value)
{
    fprintf(f, "%s = ", name);
    plot_gp_string(f, value);
    fputc('\n', f);
}

FILE *plot_script_begin(plot_job *job, const char *name, const char *what, const char *source, int width, int height)
{
    char file[256];
    FILE *f;
    if (job->count >= PLOT_MAX_SCRIPTS) {
        fprintf(stderr, "touchdown plot: more than %d figures; plot fewer files at once\n", PLOT_MAX_SCRIPTS);
        return NULL;
    }
    if (snprintf(file, sizeof file, "%s.gp", name) >= (int)sizeof file) {
        fprintf(stderr, "touchdown plot: figure file name %s.gp is longer than %d characters\n", name,
                (int)sizeof file - 1);
        return NULL;
    }
    if (!(f = plot_open(job->opt, file)))
        return NULL;
    snprintf(job->scripts[job->count++], sizeof job->scripts[0], "%s", file);
    fprintf(f,
            "# %s\n# from %s, written by 'touchdown plot'. Edit freely, then rerun in this directory:\n"
            "#     gnuplot %s\n\n",
            what, source, file);
    plot_var_string(f, "figure", name);
    fprintf(f, "format = '%s'    # png or svg\nwidth = %d\nheight = %d    # pixels\n", plot_ext(job->opt), width,
            height);
    return f;
}

int plot_script_end(FILE *f, const plot_job *job, const char *name, const char *pre, const char *body)
{
    char file[256];
    fputc('\n', f);
    fputs(plot_tpl_common, f);
    fputs(pre ? pre : "", f);
    fputs(body, f);
    snprintf(file, sizeof file, "%s.gp", name);
    return plot_close(f, job->opt, file);
}

/* The gnuplot program: $TOUCHDOWN_GNUPLOT if set, else "gnuplot" on PATH. */
static const char *gnuplot_program(void)
{
    const char *g = getenv("TOUCHDOWN_GNUPLOT");
    return g && *g ? g : "gnuplot";
}

/* 1 if `prog` can be executed (a path, or a name found on PATH). */
static int find_program(const char *prog)
{
    const char *path = getenv("PATH"), *p;
    char buf[PLOT_PATH_SIZE];
    if (strchr(prog, '/'))
        return access(prog, X_OK) == 0;
    for (p = path ? path : "/usr/bin:/bin"; *p;) {
        const char *colon = strchr(p, ':');
        size_t len = colon ? (size_t)(colon - p) : strlen(p);
        /* a PATH entry too long for the buffer cannot be tried: skipped, never shortened */
        if (snprintf(buf, sizeof buf, "%.*s/%s", (int)len, len ? p : ".", prog) < (int)sizeof buf &&
            access(buf, X_OK) == 0)
            return 1;
        p += len + (colon ? 1 : 0);
    }
    return 0;
}

/* Gnuplot's own error, for one line: the "FILE" line N: message line, else the last line. */
static void log_message(const char *log, char *msg, size_t n)
{
    FILE *f = fopen(log, "r");
    char line[512];
    msg[0] = '\0';
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        if (!line[0])
            continue;
        if (line[0] == '"' && strstr(line, " line ")) {
            snprintf(msg, n, "%s", line);
            break;
        }
        snprintf(msg, n, "%s", line);
    }
    fclose(f);
}

/* Run gnuplot on one script inside opt->dir, its messages going to SCRIPT.log (removed when
 * empty). Returns the child's exit status, or -1 if it could not be started. */
static int run_one(const char *prog, const char *dir, const char *script, const char *log)
{
    pid_t pid = fork();
    int status;
    if (pid < 0)
        return -1;
    if (pid == 0) {
        int fd;
        if (chdir(dir) != 0)
            _exit(126);
        fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (fd >= 0) {
            dup2(fd, STDOUT_FILENO);
            dup2(fd, STDERR_FILENO);
            close(fd);
        }
        execlp(prog, prog, script, (char *)NULL);
        _exit(127);
    }
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    if (WIFEXITED(status))
        return WEXITSTATUS(status);
    return -1;
}

int plot_run_all(const plot_job *job)
{
    const plot_opts *opt = job->opt;
    const char *prog = gnuplot_program();
    int i;
    if (!find_program(prog)) {
        fprintf(stderr,
                "touchdown plot: gnuplot not found ('%s'; install gnuplot-nox or set TOUCHDOWN_GNUPLOT); "
                "the scripts and data are in %s\n",
                prog, opt->dir);
        return PLOT_FAILED;
    }
    for (i = 0; i < job->count; i++) {
        char log[300], log_path[PLOT_PATH_SIZE], msg[600];
        struct stat st;
        int rc;
        /* fits: scripts[i] is shorter than log, and dir/script fitted in plot_open */
        snprintf(log, sizeof log, "%.*s.log", (int)(strlen(job->scripts[i]) - 3), job->scripts[i]);
        if (join(log_path, sizeof log_path, opt->dir, log))
            return PLOT_FAILED;
        rc = run_one(prog, opt->dir, job->scripts[i], log);
        if (rc != 0) {
            log_message(log_path, msg, sizeof msg);
            fprintf(stderr, "touchdown plot: gnuplot failed on %s/%s: %s (see %s)\n", opt->dir, job->scripts[i],
                    msg[0]   ? msg
                    : rc < 0 ? "could not be run"
                             : "no message",
                    log_path);
            return PLOT_FAILED;
        }
        if (stat(log_path, &st) == 0 && st.st_size == 0)
            remove(log_path);
        if (!opt->quiet)
            printf("wrote %s/%.*s.%s\n", opt->dir, (int)(strlen(job->scripts[i]) - 3), job->scripts[i], plot_ext(opt));
    }
    return PLOT_OK;
}
