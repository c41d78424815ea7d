/*
 * touchdown sweep: the journal that makes a sweep resumable.
 *
 * While a sweep runs, every row a point's own run produced is appended to PREFIX.journal as it
 * arrives, one write per row. Re-running the same sweep (same case, overrides, grid and library)
 * reads the rows back and runs only the points that have none, so a study killed half way (Ctrl-C,
 * SIGKILL, a lost machine) loses at most the points that were running, and no point is computed
 * twice. The file is a work file, not a result: binary rows of this build (the row layout and the
 * library version are in the fingerprint), removed once the table of a finished sweep is written.
 *
 * Layout: a header (magic, fingerprint, row size, points) and then records (point, row). A record
 * torn by a kill is cut off on resume.
 *
 * Under MPI each rank appends to a part of its own, PREFIX.journal.rank-K, in the same layout, so
 * that no rank waits for another to record a row; rank 0 merges the parts into the table at the
 * end. A resume, with any number of ranks or none, reads the journal and every part of the sweep.
 */
#include "sweep_journal.h"

#include "cli.h"
#include "touchdown/output.h"
#include "touchdown/version.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#define JOURNAL_MAGIC "TDSWJ01"
/* PREFIX.journal.rank-K: the part of rank K of a sweep run under MPI */
#define PART_TAG ".rank-"

typedef struct journal_header {
    char magic[8];
    uint64_t fingerprint;
    uint64_t row_size;
    int64_t points;
} journal_header;

typedef struct journal_record {
    int64_t point;
    td_sweep_row row;
} journal_record;

struct sweep_journal {
    FILE *f;
    char path[SWEEP_PART_PATH_SIZE];
    int failed; /* a write failed: the journal was given up */
};

/* FNV-1a, 64 bits, over a string and its terminating zero (so that "ab","c" differs from "a","bc"). */
static uint64_t fnv_string(uint64_t h, const char *s)
{
    do {
        h ^= (unsigned char)*s;
        h *= 1099511628211u;
    } while (*s++);
    return h;
}

uint64_t sweep_fingerprint(const td_case *base, const td_sweep_grid *grid)
{
    char layout[64], axis[16];
    uint64_t h = 14695981039346656037u;
    long p, n = td_sweep_grid_points(grid);
    int k, keys = td_sweep_grid_keys(grid);
    snprintf(layout, sizeof layout, "%s %lu %ld %d %d", td_version(), (unsigned long)sizeof(journal_record), n,
             td_sweep_grid_axes(grid), keys);
    h = fnv_string(h, layout);
    h = fnv_string(h, td_case_text(base)); /* the case with its --set overrides */
    for (k = 0; k < keys; k++) {           /* every key with its axis: a zip is not a grid */
        snprintf(axis, sizeof axis, "%d", td_sweep_grid_axis(grid, k));
        h = fnv_string(h, axis);
        h = fnv_string(h, td_sweep_grid_key(grid, k));
        for (p = 0; p < n; p++)
            h = fnv_string(h, td_sweep_grid_value(grid, p, k));
    }
    return h;
}

static journal_header header_of(uint64_t fp, long points)
{
    journal_header hd;
    memset(&hd, 0, sizeof hd);
    memcpy(hd.magic, JOURNAL_MAGIC, sizeof JOURNAL_MAGIC);
    hd.fingerprint = fp;
    hd.row_size = sizeof(td_sweep_row);
    hd.points = points;
    return hd;
}

/* Read the records of an open journal into rows[] (NULL: only count them); returns the number of
 * rows that were "not run" before and sets *end to the offset after the last whole record (a torn
 * one, cut by a kill, ends the reading there). */
static long read_records(FILE *f, long points, td_sweep_row *rows, off_t *end)
{
    journal_record rec;
    long got = 0;
    *end = (off_t)sizeof(journal_header);
    while (fread(&rec, sizeof rec, 1, f) == 1) {
        if (rec.point < 0 || rec.point >= points)
            break; /* not a record of this sweep: keep what came before */
        if (!rows || rows[rec.point].state == TD_SWEEP_NOT_RUN)
            got++;
        if (rows)
            rows[rec.point] = rec.row;
        *end += (off_t)sizeof rec;
    }
    return got;
}

/* 1 if f starts with the header `want`, 0 if it has no whole header (cut before it was written:
 * as good as none), -1 if it is the header of another sweep. */
static int header_matches(FILE *f, const journal_header *want)
{
    journal_header have;
    if (fread(&have, sizeof have, 1, f) != 1)
        return 0;
    return memcmp(&have, want, sizeof have) == 0 ? 1 : -1;
}

static int refuse_foreign(const char *path)
{
    td_cli_error("sweep",
                 "%s is the journal of another sweep (its case, --set, grid or touchdown version "
                 "differ): remove it to start afresh, or write to another --output",
                 path);
    return TD_EXIT_USAGE;
}

/* The rows of one journal or part at path into rows[], *found counting the new ones; a missing
 * file is none. Returns 0 or TD_EXIT_USAGE (another sweep's, after an error line). */
static int read_file(const char *path, uint64_t fp, long points, td_sweep_row *rows, long *found)
{
    journal_header want = header_of(fp, points);
    FILE *f = fopen(path, "rb");
    off_t end;
    int m;
    if (!f)
        return 0;
    m = header_matches(f, &want);
    if (m > 0)
        *found += read_records(f, points, rows, &end);
    fclose(f);
    return m < 0 ? refuse_foreign(path) : 0;
}

/* 1 if `name` is the file name of a part of the journal whose file name is `base`: base, ".rank-",
 * then digits alone. */
static int is_part_name(const char *name, const char *base)
{
    size_t n = strlen(base);
    const char *d;
    if (strncmp(name, base, n) || strncmp(name + n, PART_TAG, strlen(PART_TAG)))
        return 0;
    d = name + n + strlen(PART_TAG);
    if (!*d)
        return 0;
    while (*d >= '0' && *d <= '9')
        d++;
    return *d == '\0';
}

/* Call fn(path, ...) for every part of the journal at `journal` in its directory; stops at the
 * first nonzero return, which it returns. */
static int each_part(const char *journal, int (*fn)(const char *path, void *arg), void *arg)
{
    char dir[TD_OUTPUT_PATH_SIZE], path[TD_OUTPUT_PATH_SIZE + 256]; /* the directory and a file name */
    const char *slash = strrchr(journal, '/'), *base = slash ? slash + 1 : journal;
    struct dirent *e;
    DIR *d;
    int code = 0;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - journal + 1) : 1, slash ? journal : ".");
    if (!(d = opendir(dir)))
        return 0;
    while (!code && (e = readdir(d)))
        if (is_part_name(e->d_name, base)) {
            snprintf(path, sizeof path, "%s%s", slash ? dir : "", e->d_name);
            code = fn(path, arg);
        }
    closedir(d);
    return code;
}

typedef struct read_args {
    uint64_t fp;
    long points, *found;
    td_sweep_row *rows;
} read_args;

static int read_part(const char *path, void *arg)
{
    read_args *a = arg;
    return read_file(path, a->fp, a->points, a->rows, a->found);
}

int sweep_store_read(const char *journal, uint64_t fp, long points, td_sweep_row *rows, long *found)
{
    read_args a;
    int code;
    *found = 0;
    a.fp = fp;
    a.points = points;
    a.rows = rows;
    a.found = found;
    code = read_file(journal, fp, points, rows, found);
    return code ? code : each_part(journal, read_part, &a);
}

static int remove_part(const char *path, void *arg)
{
    (void)arg;
    remove(path);
    return 0;
}

void sweep_store_remove(const char *journal)
{
    remove(journal);
    each_part(journal, remove_part, NULL);
}

void sweep_part_path(char *dst, const char *journal, int rank)
{
    snprintf(dst, SWEEP_PART_PATH_SIZE, "%s%s%d", journal, PART_TAG, rank);
}

/* A fresh journal at path; 0 or TD_EXIT_FAILED after an error line. */
static int journal_create(sweep_journal *j, uint64_t fp, long points)
{
    journal_header hd = header_of(fp, points);
    j->f = fopen(j->path, "w+b");
    if (!j->f || fwrite(&hd, sizeof hd, 1, j->f) != 1 || fflush(j->f)) {
        td_cli_error("sweep", "cannot write the journal %s: %s", j->path, strerror(errno));
        return TD_EXIT_FAILED;
    }
    return 0;
}

/* The journal j->path of this sweep, opened to append after its last whole record (a torn one is
 * cut off), or created when missing or cut before its header was whole. */
static int journal_reopen(sweep_journal *j, uint64_t fp, long points)
{
    journal_header want = header_of(fp, points);
    off_t end;
    int m;
    j->f = fopen(j->path, "r+b");
    m = j->f ? header_matches(j->f, &want) : 0;
    if (m < 0)
        return refuse_foreign(j->path);
    if (m == 0) {
        if (j->f)
            fclose(j->f);
        return journal_create(j, fp, points);
    }
    read_records(j->f, points, NULL, &end);
    /* the position set before the stream turns from reading to writing, the torn tail cut */
    if (fseeko(j->f, end, SEEK_SET) == 0 && ftruncate(fileno(j->f), end) != 0)
        clearerr(j->f); /* not cut: the next record overwrites it all the same */
    return 0;
}

int sweep_journal_open(const char *path, uint64_t fp, long points, sweep_journal **out)
{
    sweep_journal *j = calloc(1, sizeof *j);
    int code;
    *out = NULL;
    if (!j) {
        td_cli_error("sweep", "out of memory");
        return TD_EXIT_FAILED;
    }
    snprintf(j->path, sizeof j->path, "%s", path);
    code = journal_reopen(j, fp, points);
    if (code) {
        if (j->f)
            fclose(j->f);
        free(j);
        return code;
    }
    *out = j;
    return 0;
}

void sweep_journal_record(sweep_journal *j, long point, const td_sweep_row *row)
{
    journal_record rec;
    if (!j || j->failed)
        return;
    memset(&rec, 0, sizeof rec);
    rec.point = point;
    rec.row = *row;
    /* one fwrite and a flush per row: what is on disk is whole records, at most one torn */
    if (fwrite(&rec, sizeof rec, 1, j->f) != 1 || fflush(j->f)) {
        td_cli_error("sweep",
                     "cannot write the journal %s (%s): the sweep goes on, but a resume would repeat "
                     "the points from here",
                     j->path, strerror(errno));
        j->failed = 1;
    }
}

void sweep_journal_close(sweep_journal **j)
{
    if (!j || !*j)
        return;
    if ((*j)->f)
        fclose((*j)->f);
    free(*j);
    *j = NULL;
}
