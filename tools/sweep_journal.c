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
 */
#include "sweep_journal.h"

#include "cli.h"
#include "touchdown/output.h"
#include "touchdown/version.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#define JOURNAL_MAGIC "TDSWJ01"

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
    char path[TD_OUTPUT_PATH_SIZE];
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

/* Read the records of an open journal into rows[]; returns the number of rows read and leaves the
 * file positioned after the last whole record (a torn one is cut off there). */
static long read_records(FILE *f, long points, td_sweep_row *rows)
{
    journal_record rec;
    long got = 0;
    off_t end = (off_t)sizeof(journal_header);
    while (fread(&rec, sizeof rec, 1, f) == 1) {
        if (rec.point < 0 || rec.point >= points)
            break; /* not a record of this sweep: keep what came before */
        if (rows[rec.point].state == TD_SWEEP_NOT_RUN)
            got++;
        rows[rec.point] = rec.row;
        end += (off_t)sizeof rec;
    }
    /* the position set before the stream turns from reading to writing, the torn tail cut */
    if (fseeko(f, end, SEEK_SET) == 0 && ftruncate(fileno(f), end) != 0)
        clearerr(f); /* not cut: the next record overwrites it all the same */
    return got;
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

int sweep_journal_open(const char *path, uint64_t fp, long points, td_sweep_row *rows, long *resumed,
                       sweep_journal **out)
{
    sweep_journal *j = calloc(1, sizeof *j);
    journal_header want = header_of(fp, points), have;
    int code = 0;
    *resumed = 0;
    *out = NULL;
    if (!j) {
        td_cli_error("sweep", "out of memory");
        return TD_EXIT_FAILED;
    }
    snprintf(j->path, sizeof j->path, "%s", path);
    j->f = fopen(path, "r+b");
    if (j->f && fread(&have, sizeof have, 1, j->f) == 1) {
        if (memcmp(&have, &want, sizeof have) != 0) {
            td_cli_error("sweep",
                         "%s is the journal of another sweep (its case, --set, grid or touchdown version "
                         "differ): remove it to start afresh, or write to another --output",
                         path);
            code = TD_EXIT_USAGE;
        } else
            *resumed = read_records(j->f, points, rows);
    } else { /* none, or cut before its header was whole: start one */
        if (j->f)
            fclose(j->f);
        code = journal_create(j, fp, points);
    }
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

void sweep_journal_close(sweep_journal **j, int finished)
{
    if (!j || !*j)
        return;
    if ((*j)->f)
        fclose((*j)->f);
    if (finished)
        remove((*j)->path);
    free(*j);
    *j = NULL;
}
