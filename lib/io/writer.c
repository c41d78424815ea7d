/*
 * The format-independent half of td_writer: argument checks, the attribute list and the
 * PATH.XXXXXX.partial -> PATH protocol that keeps an unfinished file from ever looking finished.
 */
#include "io/schema.h"
#include "io/writer_internal.h"
#include "touchdown/dofs.h"
#include "util/error_internal.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "touchdown/dofs.h"
#include "touchdown/version.h"

static const char partial_suffix[] = TD_IO_TEMP_SUFFIX;
/* Characters of the unique part of a temporary name, and names tried before giving up. */
#define TEMP_TAG_LEN 6
#define TEMP_ATTEMPTS 100

/* The path of a CSV file that goes with `csv_path`: its name without ".csv", then `suffix`. */
static int companion_path(const char *csv_path, const char *suffix, char *buf, size_t n)
{
    static const char ext[] = ".csv";
    size_t len = csv_path ? strlen(csv_path) : 0;
    size_t ext_len = sizeof ext - 1;
    if (len >= ext_len && strcmp(csv_path + len - ext_len, ext) == 0)
        len -= ext_len;
    return snprintf(buf, n, "%.*s%s", (int)len, csv_path ? csv_path : "", suffix);
}

int td_writer_events_path(const char *csv_path, char *buf, size_t n)
{
    return companion_path(csv_path, ".events.csv", buf, n);
}

/* long runs */
int td_writer_windows_path(const char *csv_path, char *buf, size_t n)
{
    return companion_path(csv_path, ".windows.csv", buf, n);
}

/* SplitMix64 finaliser: spreads a few changing bits over all 64. */
static uint64_t mix64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9u;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebu;
    return x ^ (x >> 31);
}

/* A name tag that differs between processes, calls and attempts. It need not be unpredictable:
 * O_EXCL makes the file ours, the tag only keeps retries rare. */
static void temp_tag(char tag[TEMP_TAG_LEN + 1], const void *salt, unsigned attempt)
{
    static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    struct timespec ts;
    uint64_t x;
    int i;
    clock_gettime(CLOCK_REALTIME, &ts);
    x = mix64((uint64_t)getpid()) ^ mix64((uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec) ^
        mix64((uint64_t)(uintptr_t)salt + attempt);
    for (i = 0; i < TEMP_TAG_LEN; i++) {
        tag[i] = alphabet[x % (sizeof alphabet - 1)];
        x /= sizeof alphabet - 1;
    }
    tag[TEMP_TAG_LEN] = '\0';
}

/* 1 if `name` is a temporary name of the file `base` (base_len bytes): BASE.XXXXXX.partial. */
static int is_temp_of(const char *name, const char *base, size_t base_len)
{
    size_t i;
    if (strncmp(name, base, base_len) != 0 || name[base_len] != '.')
        return 0;
    for (i = 0; i < TEMP_TAG_LEN; i++) {
        char c = name[base_len + 1 + i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')))
            return 0;
    }
    return strcmp(name + base_len + 1 + TEMP_TAG_LEN, partial_suffix) == 0;
}

/* 1 if the open file `fd` is still the one at `name` (not removed or replaced meanwhile). */
static int is_file_at(int fd, const char *name)
{
    struct stat a, b;
    return fstat(fd, &a) == 0 && lstat(name, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/* Remove the temporary file `name` if its writer is gone: nobody holds its lock (a live writer
 * holds it until the file is renamed or removed, td_io_create_temp), and it is still the file
 * opened (not replaced meanwhile). A file created but not yet locked may go too: its writer finds
 * it gone once it holds the lock, and creates another (td_io_create_temp). */
static void remove_if_orphan(const char *name)
{
    struct stat a;
    int fd = open(name, O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0)
        return;
    if (fstat(fd, &a) == 0 && S_ISREG(a.st_mode) && flock(fd, LOCK_EX | LOCK_NB) == 0 && is_file_at(fd, name))
        unlink(name);
    close(fd); /* and its lock */
}

/* The leftovers of earlier writers of `path` (PATH.XXXXXX.partial whose writer was killed: SIGKILL,
 * power loss) are removed; a live writer's, locked, are not. Best effort: what cannot be read or
 * removed stays, and the run goes on. */
static void remove_leftovers(const char *path)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0, base_len = strlen(base);
    char *dir = malloc(dir_len + 2), *name = NULL;
    DIR *d;
    struct dirent *e;
    if (!dir)
        return;
    memcpy(dir, slash ? path : ".", slash ? dir_len : 1);
    dir[slash ? dir_len : 1] = '\0';
    d = opendir(dir);
    while (d && (e = readdir(d)) != NULL) {
        if (!is_temp_of(e->d_name, base, base_len) || !(name = malloc(dir_len + strlen(e->d_name) + 1)))
            continue;
        memcpy(name, path, dir_len);
        strcpy(name + dir_len, e->d_name);
        remove_if_orphan(name);
        free(name);
    }
    if (d)
        closedir(d);
    free(dir);
}

/* Lock the temporary file `fd` just created at `tmp`: 0 if it is locked and still at `tmp`, 1 if a
 * concurrent writer's remove_leftovers took it for a leftover between its creation and the lock
 * (it is closed: try another name), -1 (errno set, fd closed) on an error. The lock waits: the
 * leftover scan holds a lock only while it checks and unlinks. */
static int lock_temp(int fd, const char *tmp)
{
    int r, e;
    while ((r = flock(fd, LOCK_EX)) != 0 && errno == EINTR)
        continue;
    if (r == 0 && is_file_at(fd, tmp))
        return 0;
    e = r == 0 ? 0 : errno;
    close(fd);
    errno = e;
    return r == 0 ? 1 : -1;
}

td_status td_io_create_temp(const char *path, char **tmp_out, int *fd_out, int *lock_out, td_error *err)
{
    size_t len = strlen(path);
    char *tmp = malloc(len + 1 + TEMP_TAG_LEN + sizeof partial_suffix);
    char tag[TEMP_TAG_LEN + 1];
    unsigned attempt;
    int fd = -1, e = EEXIST, lock;
    *tmp_out = NULL;
    *fd_out = *lock_out = -1;
    if (!tmp)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", path);
    remove_leftovers(path);
    for (attempt = 0; attempt < TEMP_ATTEMPTS && fd < 0 && e == EEXIST; attempt++) {
        temp_tag(tag, tmp, attempt);
        memcpy(tmp, path, len);
        tmp[len] = '.';
        memcpy(tmp + len + 1, tag, TEMP_TAG_LEN);
        memcpy(tmp + len + 1 + TEMP_TAG_LEN, partial_suffix, sizeof partial_suffix);
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        e = fd < 0 ? errno : 0;
        if (fd >= 0 && (lock = lock_temp(fd, tmp)) != 0) { /* 1: removed meanwhile, another name */
            e = lock > 0 ? EEXIST : errno;
            fd = -1;
        }
    }
    if (fd < 0) {
        free(tmp);
        return td_error_set(err, TD_ERR_IO, "%s: cannot create its temporary file: %s", path, strerror(e));
    }
    /* The lock says a writer is alive (remove_leftovers): held on a duplicate of the descriptor, so
     * it outlives fd (closed by the writer before the rename) until the caller closes *lock_out. Not
     * inherited by a child process: one that outlived the writer would keep its leftovers alive. */
    if ((*lock_out = fcntl(fd, F_DUPFD_CLOEXEC, 0)) < 0) {
        e = errno;
        close(fd);
        remove(tmp);
        free(tmp);
        return td_error_set(err, TD_ERR_IO, "%s: cannot lock its temporary file: %s", path, strerror(e));
    }
    *tmp_out = tmp;
    *fd_out = fd;
    return TD_OK;
}

td_status td_io_commit_temp(const char *tmp, const char *path, td_error *err)
{
    td_status st = td_io_fsync_path(tmp, err);
    if (st == TD_OK && rename(tmp, path) != 0)
        st = td_error_set(err, TD_ERR_IO, "%s: cannot rename to %s: %s", tmp, path, strerror(errno));
    if (st != TD_OK)
        remove(tmp);
    return st;
}

/* The end of a whole-file write: tmp renamed to path if st is TD_OK, else removed; tmp freed and
 * its lock released (after: the name is gone by then). */
static td_status finish_temp(td_status st, char *tmp, int lock, const char *path, td_error *err)
{
    if (st == TD_OK)
        st = td_io_commit_temp(tmp, path, err);
    else
        remove(tmp);
    free(tmp);
    close(lock);
    return st;
}

td_status td_io_write_text_file(const char *path, void (*write_all)(FILE *f, const void *ctx), const void *ctx,
                                td_error *err)
{
    char *tmp = NULL;
    FILE *f;
    int fd, lock;
    td_status st = td_io_create_temp(path, &tmp, &fd, &lock, err);
    if (st != TD_OK)
        return st;
    errno = 0;
    if (!(f = fdopen(fd, "w"))) {
        st = td_io_fail(err, tmp, "cannot open");
        close(fd);
    } else {
        write_all(f, ctx);
        if (td_io_close_stream(&f))
            st = td_io_fail(err, tmp, "cannot write");
    }
    return finish_temp(st, tmp, lock, path, err);
}

td_status td_io_write_named_file(const char *path,
                                 td_status (*write_all)(const char *tmp, const void *ctx, td_error *err),
                                 const void *ctx, td_error *err)
{
    char *tmp = NULL;
    int fd, lock;
    td_status st = td_io_create_temp(path, &tmp, &fd, &lock, err);
    if (st != TD_OK)
        return st;
    close(fd); /* the writer opens the file by name (HDF5) */
    return finish_temp(write_all(tmp, ctx, err), tmp, lock, path, err);
}

td_status td_io_fsync_path(const char *path, td_error *err)
{
    int fd = open(path, O_RDONLY);
    int rc;
    if (fd < 0)
        return td_error_set(err, TD_ERR_IO, "%s: cannot reopen to flush: %s", path, strerror(errno));
    rc = fsync(fd);
    if (close(fd) != 0 || rc != 0)
        return td_error_set(err, TD_ERR_IO, "%s: flush to disk failed: %s", path, strerror(errno));
    return TD_OK;
}

/* ---- open / free ------------------------------------------------------------------------- */

static td_status check_layout(const td_output_layout *layout, td_error *err)
{
    int i;
    if (!layout)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: NULL layout");
    if (layout->node_count < 0 || layout->retainer_count < 0 || layout->amb_count < 0)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: negative count in the output layout");
    if (layout->compression < 0 || layout->compression > 9)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: compression %d is not a deflate level 0..9",
                            layout->compression);
    if (layout->node_count > 0 && !layout->nodes)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: %d nodes but no node list", layout->node_count);
    for (i = 0; i < layout->node_count; i++)
        if (layout->nodes[i] < 0)
            return td_error_set(err, TD_ERR_INVALID, "td_writer_open: node number %d is negative", layout->nodes[i]);
    return TD_OK;
}

static void attr_release(td_attr *a)
{
    free(a->text);
    free(a->doubles);
    free(a->longs);
    a->text = NULL;
    a->doubles = NULL;
    a->longs = NULL;
}

static void writer_free(td_writer *w)
{
    int i;
    if (!w)
        return;
    for (i = 0; i < w->attr_count; i++)
        attr_release(&w->attrs[i]);
    free(w->attrs);
    free(w->nodes);
    free(w->node_abs_xy); /* housing motion */
    free(w->path);
    free(w->tmp_path);
    free(w->events_path);
    free(w->events_tmp);
    if (w->tmp_fd >= 0)
        close(w->tmp_fd);
    if (w->events_fd >= 0)
        close(w->events_fd);
    if (w->tmp_lock >= 0) /* last: the temporary files are renamed or removed by now */
        close(w->tmp_lock);
    if (w->events_lock >= 0)
        close(w->events_lock);
    free(w->windows_path); /* long runs */
    free(w->windows_tmp);
    if (w->windows_fd >= 0)
        close(w->windows_fd);
    if (w->windows_lock >= 0)
        close(w->windows_lock);
    free(w);
}

static char *string_copy(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = suffix ? strlen(suffix) : 0;
    char *p = malloc(a + b + 1);
    if (p) {
        memcpy(p, s, a);
        if (b)
            memcpy(p + a, suffix, b);
        p[a + b] = '\0';
    }
    return p;
}

/* CSV: the final names of the files that go with it, the events file and (long runs) the window
 * file, named whether or not this run writes them: a file at either name is removed when the writer
 * opens (td_writer_open), so that one left by an earlier run is never read as this run's. */
static td_status events_path(td_writer *w)
{
    int n = td_writer_events_path(w->path, NULL, 0);
    w->events_path = malloc((size_t)n + 1);
    if (!w->events_path)
        return TD_ERR_NOMEM;
    td_writer_events_path(w->path, w->events_path, (size_t)n + 1);
    n = td_writer_windows_path(w->path, NULL, 0);
    if (!(w->windows_path = malloc((size_t)n + 1)))
        return TD_ERR_NOMEM;
    td_writer_windows_path(w->path, w->windows_path, (size_t)n + 1);
    return TD_OK;
}

/* Create the temporary file(s) under fresh unique names; on failure none is left. */
static td_status create_temps(td_writer *w, td_error *err)
{
    td_status st = td_io_create_temp(w->path, &w->tmp_path, &w->tmp_fd, &w->tmp_lock, err);
    if (st == TD_OK && w->events_path && !w->omit_events &&
        (st = td_io_create_temp(w->events_path, &w->events_tmp, &w->events_fd, &w->events_lock, err)) != TD_OK) {
        remove(w->tmp_path);
        free(w->tmp_path);
        w->tmp_path = NULL;
    }
    if (st == TD_OK && w->windows_path && w->window_fields && /* long runs: a CSV file's */
        (st = td_io_create_temp(w->windows_path, &w->windows_tmp, &w->windows_fd, &w->windows_lock, err)) != TD_OK) {
        remove(w->tmp_path);
        if (w->events_tmp)
            remove(w->events_tmp);
        free(w->tmp_path);
        free(w->events_tmp);
        w->tmp_path = w->events_tmp = NULL;
    }
    return st;
}

/* Remove a stale result at `path` (absent is fine): a file at PATH must belong to this run. */
static td_status remove_stale(const char *path, td_error *err)
{
    if (unlink(path) != 0 && errno != ENOENT)
        return td_error_set(err, TD_ERR_IO, "%s: cannot remove the old file: %s", path, strerror(errno));
    return TD_OK;
}

/* housing motion: the layout's flag and the next sample's values, NaN until td_writer_housing gives them. */
static td_status housing_open(td_writer *w, const td_output_layout *layout)
{
    int i;
    w->housing_fields = layout->housing_fields != 0;
    w->housing_body_fields = w->housing_fields && layout->housing_body_fields; /* housing body */
    for (i = 0; i < TD_WRITER_HOUSING_VALUES + TD_WRITER_HOUSING_BODY_VALUES; i++)
        w->housing[i] = TD_UNDEFINED;
    if (!w->housing_fields)
        return TD_OK;
    w->node_abs_xy = malloc((size_t)(2 * layout->node_count + 1) * sizeof *w->node_abs_xy);
    if (!w->node_abs_xy)
        return TD_ERR_NOMEM;
    for (i = 0; i < 2 * layout->node_count; i++)
        w->node_abs_xy[i] = TD_UNDEFINED;
    return TD_OK;
}

td_status td_writer_open(td_writer_kind kind, const char *path, const td_output_layout *layout, td_writer **out,
                         td_error *err)
{
    td_writer *w;
    td_status st;
    if (!out)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: NULL output pointer");
    *out = NULL;
    if (!path || !path[0])
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: empty path");
    if (kind != TD_WRITER_HDF5 && kind != TD_WRITER_CSV)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_open: unknown writer kind %d", (int)kind);
    if ((st = check_layout(layout, err)) != TD_OK)
        return st;
    w = calloc(1, sizeof *w);
    if (!w)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", path);
    w->kind = kind;
    w->tmp_fd = w->events_fd = w->tmp_lock = w->events_lock = w->windows_fd = w->windows_lock = -1;
    w->window_fields = layout->window_fields != 0; /* long runs */
    w->omit_events = layout->omit_events != 0;
    w->ops = kind == TD_WRITER_HDF5 ? &td_hdf5_writer_ops : &td_csv_writer_ops;
    w->path = string_copy(path, NULL);
    if (!w->path || (kind == TD_WRITER_CSV && (st = events_path(w)) != TD_OK)) {
        writer_free(w);
        return td_error_set(err, st, "out of memory opening %s", path);
    }
    w->node_count = layout->node_count;
    w->retainer_count = layout->retainer_count;
    w->race_fields = layout->race_fields != 0;
    w->speed_field = layout->speed_field != 0;
    w->whirl_field = layout->whirl_field != 0;
    w->switch_fields = layout->switch_fields != 0;
    w->thermal_fields = layout->thermal_fields != 0; /* heat */
    if ((st = housing_open(w, layout)) != TD_OK) {   /* housing motion */
        writer_free(w);
        return td_error_set(err, st, "out of memory opening %s", path);
    }
    w->amb_count = layout->amb_count;
    w->compression = layout->compression;
    if (layout->node_count > 0) {
        w->nodes = malloc((size_t)layout->node_count * sizeof *w->nodes);
        if (w->nodes)
            memcpy(w->nodes, layout->nodes, (size_t)layout->node_count * sizeof *w->nodes);
    }
    if (layout->node_count > 0 && !w->nodes) {
        writer_free(w);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory opening %s", path);
    }
    if ((st = create_temps(w, err)) != TD_OK) {
        writer_free(w);
        return st;
    }
    if ((st = w->ops->open(w, err)) != TD_OK) {
        td_writer_discard(&w);
        return st;
    }
    if ((st = remove_stale(w->path, err)) != TD_OK ||
        (w->events_path && (st = remove_stale(w->events_path, err)) != TD_OK) ||
        (w->windows_path && (st = remove_stale(w->windows_path, err)) != TD_OK)) {
        td_writer_discard(&w);
        return st;
    }
    *out = w;
    return TD_OK;
}

/* ---- samples and events ------------------------------------------------------------------ */

static td_status usable(const td_writer *w, const char *what, td_error *err)
{
    if (!w)
        return td_error_set(err, TD_ERR_INVALID, "%s: NULL writer", what);
    if (w->failed)
        return td_error_set(err, TD_ERR_STATE, "%s: an earlier write to %s failed (%s)", what, w->path, w->failure);
    return TD_OK;
}

/* Remember the first failure; the file can then only be closed incomplete. */
static td_status mark_failed(td_writer *w, td_status st, const td_error *local, td_error *err)
{
    w->failed = 1;
    snprintf(w->failure, sizeof w->failure, "%s", local->message);
    return td_error_set(err, st, "%s", local->message);
}

td_status td_writer_sample(td_writer *w, double t, double speed, const double *node_xy, const td_retainer_state *ret,
                           const double *amb_f, td_error *err)
{
    td_status st = usable(w, "td_writer_sample", err);
    td_error local;
    if (st != TD_OK)
        return st;
    if ((w->node_count > 0 && !node_xy) || (w->retainer_count > 0 && !ret) || (w->amb_count > 0 && !amb_f))
        return td_error_set(err, TD_ERR_INVALID, "td_writer_sample: NULL array for a non-empty part of the layout");
    td_error_clear(&local);
    st = w->ops->sample(w, t, speed, node_xy, ret, amb_f, &local);
    if (st != TD_OK)
        return mark_failed(w, st, &local, err);
    w->samples++;
    return TD_OK;
}

td_status td_writer_housing(td_writer *w, const double *motion, const double *node_abs_xy, td_error *err)
{
    td_status st = usable(w, "td_writer_housing", err);
    if (st != TD_OK)
        return st;
    if (!w->housing_fields)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_housing: the layout has no housing fields");
    if (!motion || (w->node_count > 0 && !node_abs_xy))
        return td_error_set(err, TD_ERR_INVALID, "td_writer_housing: NULL array");
    memcpy(w->housing, motion, (size_t)TD_WRITER_HOUSING_COUNT(w) * sizeof *motion);
    if (w->node_count > 0)
        memcpy(w->node_abs_xy, node_abs_xy, 2 * (size_t)w->node_count * sizeof *w->node_abs_xy);
    return TD_OK;
}

td_status td_writer_event(td_writer *w, const td_event *ev, long sample, td_error *err)
{
    td_status st = usable(w, "td_writer_event", err);
    td_error local;
    if (st != TD_OK)
        return st;
    if (!ev)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_event: NULL event");
    if (w->omit_events)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_event: %s was opened without an event table", w->path);
    if (sample < -1 || sample >= w->samples)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_event: sample %ld is not a written row (0..%ld)", sample,
                            w->samples - 1);
    td_error_clear(&local);
    st = w->ops->event(w, ev, sample, &local);
    if (st != TD_OK)
        return mark_failed(w, st, &local, err);
    w->events++;
    return TD_OK;
}

/* long runs */
td_status td_writer_window(td_writer *w, const td_window_summary *win, td_error *err)
{
    td_status st = usable(w, "td_writer_window", err);
    td_error local;
    if (st != TD_OK)
        return st;
    if (!w->window_fields)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_window: the layout has no window fields");
    if (!win || (w->retainer_count > 0 && (!win->contacts || !win->contact_fraction || !win->peak_normal_force ||
                                           !win->friction_work || !win->race_temperature)))
        return td_error_set(err, TD_ERR_INVALID, "td_writer_window: NULL summary or array");
    td_error_clear(&local);
    st = w->ops->window(w, win, &local);
    if (st != TD_OK)
        return mark_failed(w, st, &local, err);
    w->windows++;
    return TD_OK;
}

long td_writer_sample_count(const td_writer *w)
{
    return w ? w->samples : 0;
}
long td_writer_event_count(const td_writer *w)
{
    return w ? w->events : 0;
}

/* ---- attributes -------------------------------------------------------------------------- */

static int name_char_ok(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '.' ||
           c == '-';
}

static td_status check_name(const td_writer *w, const char *name, td_error *err)
{
    size_t i, len;
    if (!w)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_set_*: NULL writer");
    if (!name || !name[0])
        return td_error_set(err, TD_ERR_INVALID, "td_writer_set_*: empty attribute name");
    len = strlen(name);
    if (len >= TD_ATTR_NAME_SIZE)
        return td_error_set(err, TD_ERR_INVALID, "attribute name '%.20s...' longer than %d characters", name,
                            TD_ATTR_NAME_SIZE - 1);
    for (i = 0; i < len; i++)
        if (!name_char_ok(name[i]))
            return td_error_set(err, TD_ERR_INVALID, "attribute name '%s': only letters, digits, '_', '.', '-'", name);
    if (strcmp(name, td_out_name(TD_OUT_COMPLETE)) == 0 || strcmp(name, td_out_name(TD_OUT_INCOMPLETE_REASON)) == 0)
        return td_error_set(err, TD_ERR_INVALID, "attribute name '%s' is reserved for the writer", name);
    return TD_OK;
}

/* The slot for `name`: the existing one (its old value released) or a new one. */
static td_attr *attr_slot(td_writer *w, const char *name)
{
    int i;
    for (i = 0; i < w->attr_count; i++)
        if (strcmp(w->attrs[i].name, name) == 0) {
            attr_release(&w->attrs[i]);
            return &w->attrs[i];
        }
    if (w->attr_count == w->attr_capacity) {
        int cap = w->attr_capacity ? 2 * w->attr_capacity : 32;
        td_attr *p = realloc(w->attrs, (size_t)cap * sizeof *p);
        if (!p)
            return NULL;
        w->attrs = p;
        w->attr_capacity = cap;
    }
    memset(&w->attrs[w->attr_count], 0, sizeof w->attrs[0]);
    snprintf(w->attrs[w->attr_count].name, TD_ATTR_NAME_SIZE, "%s", name);
    return &w->attrs[w->attr_count++];
}

/* Store a copy of `values`: n items of `size` bytes. Strings: n = strlen + 1. */
static td_status attr_store(td_writer *w, const char *name, td_attr_type type, const void *values, int n, int is_array,
                            td_error *err)
{
    td_status st = check_name(w, name, err);
    size_t size = type == TD_ATTR_STRING ? 1 : type == TD_ATTR_DOUBLE ? sizeof(double) : sizeof(long);
    void *copy;
    td_attr *a;
    if (st != TD_OK)
        return st;
    if (!values || n < 1)
        return td_error_set(err, TD_ERR_INVALID, "attribute '%s': no values", name);
    copy = malloc((size_t)n * size);
    if (!copy)
        return td_error_set(err, TD_ERR_NOMEM, "out of memory storing attribute '%s'", name);
    memcpy(copy, values, (size_t)n * size);
    a = attr_slot(w, name);
    if (!a) {
        free(copy);
        return td_error_set(err, TD_ERR_NOMEM, "out of memory storing attribute '%s'", name);
    }
    a->type = type;
    a->count = type == TD_ATTR_STRING ? 1 : n;
    a->is_array = is_array;
    if (type == TD_ATTR_STRING)
        a->text = copy;
    else if (type == TD_ATTR_DOUBLE)
        a->doubles = copy;
    else
        a->longs = copy;
    return TD_OK;
}

td_status td_writer_set_string(td_writer *w, const char *name, const char *value, td_error *err)
{
    if (!value)
        value = "";
    if (strlen(value) >= 0x7fffffff)
        return td_error_set(err, TD_ERR_INVALID, "attribute '%s': string too long", name ? name : "");
    return attr_store(w, name, TD_ATTR_STRING, value, (int)strlen(value) + 1, 0, err);
}

td_status td_writer_set_double(td_writer *w, const char *name, double value, td_error *err)
{
    return attr_store(w, name, TD_ATTR_DOUBLE, &value, 1, 0, err);
}

td_status td_writer_set_long(td_writer *w, const char *name, long value, td_error *err)
{
    return attr_store(w, name, TD_ATTR_LONG, &value, 1, 0, err);
}

td_status td_writer_set_doubles(td_writer *w, const char *name, const double *values, int n, td_error *err)
{
    return attr_store(w, name, TD_ATTR_DOUBLE, values, n, 1, err);
}

td_status td_writer_set_longs(td_writer *w, const char *name, const long *values, int n, td_error *err)
{
    return attr_store(w, name, TD_ATTR_LONG, values, n, 1, err);
}

td_status td_writer_set_stats(td_writer *w, const td_sim_stats *s, td_error *err)
{
    const struct {
        td_out_id id;
        long value;
    } counts[] = {{TD_OUT_STAT_STEPS, s ? s->steps : 0},
                  {TD_OUT_STAT_RESIDUAL_EVALS, s ? s->residual_evals : 0},
                  {TD_OUT_STAT_JACOBIAN_EVALS, s ? s->jacobian_evals : 0},
                  {TD_OUT_STAT_LINEAR_SETUPS, s ? s->linear_setups : 0},
                  {TD_OUT_STAT_NONLINEAR_ITERS, s ? s->nonlinear_iters : 0},
                  {TD_OUT_STAT_ERROR_TEST_FAILS, s ? s->error_test_fails : 0},
                  {TD_OUT_STAT_NONLINEAR_FAILS, s ? s->nonlinear_fails : 0},
                  {TD_OUT_STAT_RESTARTS, s ? s->restarts : 0},
                  {TD_OUT_STAT_EVENTS, s ? s->events : 0},
                  {TD_OUT_STAT_CONTACT_ONSETS, s ? s->contact_onsets : 0},
                  {TD_OUT_STAT_RELEASES, s ? s->releases : 0},
                  {TD_OUT_STAT_PEAK_AMB, s ? s->peak_amb : 0},
                  {TD_OUT_STAT_FLIGHT_STEPS, s ? s->flight_steps : 0},
                  {TD_OUT_STAT_CONTROLLER_SAMPLES, s ? s->controller_samples : 0}};
    const struct {
        td_out_id id;
        double value;
    } reals[] = {{TD_OUT_STAT_WORST_DRIFT, s ? s->worst_drift : 0.0},
                 {TD_OUT_STAT_PEAK_NORMAL_FORCE, s ? s->peak_normal_force : 0.0},
                 {TD_OUT_STAT_TIME_IN_CONTACT, s ? s->time_in_contact : 0.0},
                 {TD_OUT_STAT_FIRST_CONTACT_TIME, s ? s->first_contact_time : 0.0},
                 {TD_OUT_STAT_WALL_TIME, s ? s->wall_time : 0.0},
                 /* no working AMB: no peak AMB force (touchdown/dofs.h, "Undefined values") */
                 {TD_OUT_STAT_PEAK_AMB_FORCE, s && s->peak_amb >= 0 ? s->peak_amb_force : TD_UNDEFINED},
                 {TD_OUT_STAT_PEAK_AMB_LOAD, s && s->peak_amb >= 0 ? s->peak_amb_load : TD_UNDEFINED},
                 {TD_OUT_STAT_PEAK_AMB_TIME, s && s->peak_amb >= 0 ? s->peak_amb_time : TD_UNDEFINED},
                 {TD_OUT_STAT_FLIGHT_TIME, s ? s->flight_time : 0.0},
                 {TD_OUT_STAT_TIME_SLEWING, s ? s->time_slewing : 0.0}};
    size_t i;
    td_status st;
    if (!s)
        return td_error_set(err, TD_ERR_INVALID, "td_writer_set_stats: NULL statistics");
    for (i = 0; i < sizeof counts / sizeof counts[0]; i++)
        if ((st = td_writer_set_long(w, td_out_name(counts[i].id), counts[i].value, err)) != TD_OK)
            return st;
    for (i = 0; i < sizeof reals / sizeof reals[0]; i++)
        if ((st = td_writer_set_double(w, td_out_name(reals[i].id), reals[i].value, err)) != TD_OK)
            return st;
    return td_writer_set_string(w, td_out_name(TD_OUT_LIBRARY_VERSION), td_version(), err);
}

/* ---- close ------------------------------------------------------------------------------- */

void td_writer_discard(td_writer **wp)
{
    td_writer *w;
    if (!wp || !*wp)
        return;
    w = *wp;
    w->ops->destroy(w);
    if (w->tmp_path)
        remove(w->tmp_path);
    if (w->events_tmp)
        remove(w->events_tmp);
    if (w->windows_tmp) /* long runs */
        remove(w->windows_tmp);
    writer_free(w);
    *wp = NULL;
}

td_status td_writer_close(td_writer **wp, int complete, const char *reason, td_error *err)
{
    td_writer *w;
    td_status st;
    td_error local;
    char why[TD_ERROR_MESSAGE_SIZE];
    if (!wp || !*wp)
        return TD_OK;
    w = *wp;
    td_error_clear(&local);
    /* library_version always goes in, whoever set it before. */
    st = td_writer_set_string(w, td_out_name(TD_OUT_LIBRARY_VERSION), td_version(), &local);
    if (st != TD_OK && !w->failed)
        mark_failed(w, st, &local, NULL);
    if (w->failed) {
        complete = 0;
        snprintf(why, sizeof why, "write failed: %.400s", w->failure);
    } else {
        snprintf(why, sizeof why, "%s", reason && reason[0] ? reason : "unspecified");
    }
    st = w->ops->finish(w, complete, complete ? NULL : why, &local);
    if (st == TD_OK)
        st = td_io_fsync_path(w->tmp_path, &local);
    if (st == TD_OK && w->events_tmp)
        st = td_io_fsync_path(w->events_tmp, &local);
    if (st == TD_OK && w->windows_tmp) /* long runs: the window file first, as the events file */
        st = td_io_commit_temp(w->windows_tmp, w->windows_path, &local);
    if (st == TD_OK && w->windows_tmp) {
        free(w->windows_tmp); /* renamed: nothing left to remove */
        w->windows_tmp = NULL;
    }
    /* The events file first: the samples file carries the authoritative flag. */
    if (st == TD_OK && w->events_tmp && rename(w->events_tmp, w->events_path) != 0)
        st = td_error_set(&local, TD_ERR_IO, "%s: cannot rename to %s: %s", w->events_tmp, w->events_path,
                          strerror(errno));
    if (st == TD_OK && rename(w->tmp_path, w->path) != 0) {
        st = td_error_set(&local, TD_ERR_IO, "%s: cannot rename to %s: %s", w->tmp_path, w->path, strerror(errno));
        if (w->events_path)
            remove(w->events_path);
        if (w->windows_path)
            remove(w->windows_path);
    }
    if (st != TD_OK) {
        td_error_set(err, st, "%s", local.message);
        td_writer_discard(wp);
        return st;
    }
    writer_free(w);
    *wp = NULL;
    return TD_OK;
}
