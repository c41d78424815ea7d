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
 * Layout: a header (magic, fingerprint, row size, points) and then records, each framed by its
 * length and a CRC-32 (zlib's, ISO 3309 / ITU-T V.42) of its point and row. A crash or a bad disk
 * leaves a torn tail (a record cut short, or blocks of zeros the file system allocated but never
 * wrote): a record that fails its frame with no whole record after it is dropped, with a notice,
 * and its point runs again; one with whole records after it is corruption, and the journal is
 * refused. A record whose frame holds is still checked for a point of this sweep, a known state
 * and text fields that end within their arrays, so that nothing read from the file is trusted
 * beyond its bounds. Format 02 (this framing) refuses journals of format 01 by their magic.
 *
 * Under MPI each rank appends to a part of its own, PREFIX.journal.rank-K, in the same layout, so
 * that no rank waits for another to record a row; rank 0 merges the parts into the table at the
 * end. A resume, with any number of ranks or none, reads the journal and every part of the sweep.
 */
#include "sweep/sweep_journal.h"

#include "common/cli.h"
#include "touchdown/output.h"
#include "touchdown/version.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>
#include <zlib.h>

/* "TDSWJ" and the format: 02 frames every record by its length and CRC-32 */
#define JOURNAL_MAGIC_STEM "TDSWJ"
#define JOURNAL_MAGIC JOURNAL_MAGIC_STEM "02"
/* PREFIX.journal.rank-K: the part of rank K of a sweep run under MPI */
#define PART_TAG ".rank-"

typedef struct journal_header {
    char magic[8];
    uint64_t fingerprint;
    uint64_t row_size;
    int64_t points;
} journal_header;

/* A record: its frame (the length and CRC-32 of what follows it), then the point and its row. */
typedef struct journal_record {
    uint32_t length; /* bytes after the frame: RECORD_BODY */
    uint32_t crc;    /* CRC-32 of those bytes */
    int64_t point;
    td_sweep_row row;
} journal_record;

#define RECORD_BODY (sizeof(journal_record) - offsetof(journal_record, point))

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

/* CRC-32 of a record's point and row (zlib: ISO 3309, ITU-T V.42), the bytes its frame covers. */
static uint32_t record_crc(const journal_record *rec)
{
    return (uint32_t)crc32(crc32(0L, Z_NULL, 0), (const Bytef *)&rec->point, (uInt)RECORD_BODY);
}

/* 1 if the text field s[0 .. n) holds its terminating zero. */
static int text_ends(const char *s, size_t n)
{
    return memchr(s, '\0', n) != NULL;
}

int sweep_row_texts_end(const td_sweep_row *r)
{
    /* every char array of td_sweep_row (touchdown/sweep.h): a text field added there is added here */
    return text_ends(r->status, sizeof r->status) && text_ends(r->message, sizeof r->message) &&
           text_ends(r->ending, sizeof r->ending) && text_ends(r->warnings, sizeof r->warnings) &&
           text_ends(r->regime, sizeof r->regime) &&
           text_ends(r->shock_outcome, sizeof r->shock_outcome); /* clearance margin */
}

/* 1 if rec is a whole record of a sweep of `points` points: its frame holds, its point is one of
 * the sweep's, its state is one a run leaves (done or failed), its text fields end in bounds. */
static int record_whole(const journal_record *rec, long points)
{
    const td_sweep_row *r = &rec->row;
    return rec->length == RECORD_BODY && rec->crc == record_crc(rec) && rec->point >= 0 && rec->point < points &&
           (r->state == TD_SWEEP_DONE || r->state == TD_SWEEP_FAILED) && sweep_row_texts_end(r);
}

/* What the records of a journal held. */
typedef struct journal_read {
    long got;    /* rows that were "not run" before */
    off_t end;   /* the offset after the last whole record */
    int torn;    /* a record that is not whole ends the reading at `end` */
    int corrupt; /* ... and whole records follow it: not a torn tail but damage */
} journal_read;

/* Read the records of an open journal, just past its header, into rows[] (NULL: only count them).
 * Only one record is ever being written, so a crash tears the last one (or leaves zeros the file
 * system allocated): a record that is not whole is the torn tail when no whole record follows it. */
static void read_records(FILE *f, long points, td_sweep_row *rows, journal_read *r)
{
    journal_record rec;
    size_t k;
    memset(r, 0, sizeof *r);
    r->end = (off_t)sizeof(journal_header);
    while ((k = fread(&rec, 1, sizeof rec, f)) == sizeof rec && record_whole(&rec, points)) {
        if (!rows || rows[rec.point].state == TD_SWEEP_NOT_RUN)
            r->got++;
        if (rows)
            rows[rec.point] = rec.row;
        r->end += (off_t)sizeof rec;
    }
    if (k == 0)
        return; /* the end of the file, after whole records */
    r->torn = 1;
    while (!r->corrupt && fread(&rec, sizeof rec, 1, f) == 1)
        r->corrupt = record_whole(&rec, points);
}

/* What a journal's first bytes say: the header wanted, none (the file was cut before its header
 * was whole, a prefix of it, or only zeros reached the disk: as good as no journal), or a refusal. */
enum {
    HEADER_OTHER_SWEEP = -1,
    HEADER_OTHER_FORMAT = -2,
    HEADER_NOT_JOURNAL = -3,
    HEADER_OTHER_BUILD = -4,
    HEADER_NONE = 0,
    HEADER_OURS = 1
};

/* 1 if the rest of f is zeros. */
static int rest_is_zero(FILE *f)
{
    int c;
    while ((c = getc(f)) == 0)
        ;
    return c == EOF;
}

static int header_matches(FILE *f, const journal_header *want)
{
    static const journal_header zero;
    journal_header have;
    size_t k = fread(&have, 1, sizeof have, f);
    /* shorter than a header: a journal cut while its header was written holds a prefix of it (or
     * zeros); anything else is a file of the user's, never taken for none and overwritten */
    if (k < sizeof have)
        return !memcmp(&have, want, k) || !memcmp(&have, &zero, k) ? HEADER_NONE : HEADER_NOT_JOURNAL;
    if (memcmp(&have, want, sizeof have) == 0)
        return HEADER_OURS;
    if (memcmp(&have, &zero, sizeof have) == 0 && rest_is_zero(f))
        return HEADER_NONE;
    if (memcmp(have.magic, JOURNAL_MAGIC_STEM, strlen(JOURNAL_MAGIC_STEM)) != 0)
        return HEADER_NOT_JOURNAL;
    if (memcmp(have.magic, want->magic, sizeof have.magic))
        return HEADER_OTHER_FORMAT;
    /* the row size first: the fingerprint holds it too, but a journal whose rows are not this
     * build's is refused for that, not taken for another sweep's */
    return have.row_size != want->row_size ? HEADER_OTHER_BUILD : HEADER_OTHER_SWEEP;
}

/* The error line of a journal refused by its header (m < 0); returns TD_EXIT_USAGE. */
static int refuse_foreign(const char *path, int m)
{
    if (m == HEADER_NOT_JOURNAL)
        td_cli_error("sweep", "%s is not a sweep journal: choose another -o prefix, the sweep would overwrite it",
                     path);
    else if (m == HEADER_OTHER_FORMAT)
        td_cli_error("sweep",
                     "%s is a sweep journal of another format (not " JOURNAL_MAGIC
                     ", written by another touchdown version): remove it to start afresh, or choose another -o "
                     "prefix",
                     path);
    else if (m == HEADER_OTHER_BUILD)
        td_cli_error("sweep",
                     "%s is a sweep journal written by another build of touchdown (its row layout differs): "
                     "remove it to start afresh, or choose another -o prefix",
                     path);
    else
        td_cli_error("sweep",
                     "%s is the journal of another sweep (its case, --set, grid or touchdown version "
                     "differ): remove it to start afresh, or choose another -o prefix",
                     path);
    return TD_EXIT_USAGE;
}

static int refuse_corrupt(const char *path, off_t at)
{
    td_cli_error("sweep",
                 "%s: the record at byte %lld is damaged and whole records follow it (a bad disk, or the file was "
                 "changed): the journal cannot be trusted; remove it to run the sweep afresh",
                 path, (long long)at);
    return TD_EXIT_USAGE;
}

/* The rows of one journal or part at path into rows[], *found counting the new ones; a missing
 * file is none, a torn tail is dropped with a notice (its point runs again). Returns 0 or
 * TD_EXIT_USAGE (another sweep's, damaged; after an error line). */
static int read_file(const char *path, uint64_t fp, long points, td_sweep_row *rows, long *found)
{
    journal_header want = header_of(fp, points);
    journal_read r;
    FILE *f = fopen(path, "rb");
    int m;
    if (!f)
        return 0;
    m = header_matches(f, &want);
    if (m == HEADER_OURS)
        read_records(f, points, rows, &r);
    fclose(f);
    if (m != HEADER_OURS)
        return m < 0 ? refuse_foreign(path, m) : 0;
    if (r.corrupt)
        return refuse_corrupt(path, r.end);
    if (r.torn)
        td_cli_error("sweep", "%s: a torn record at byte %lld (what a crash leaves) is dropped: its point runs again",
                     path, (long long)r.end);
    *found += r.got;
    return 0;
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

/* The inputs of a sweep, for check_part. */
typedef struct input_list {
    const char *journal;
    const char *const *paths;
    int n;
} input_list;

/* The index of the input that `path` is (the same device and inode), or -1: none, or no file. */
static int input_index(const char *path, const input_list *in)
{
    struct stat a, b;
    int i;
    if (stat(path, &a) != 0)
        return -1;
    for (i = 0; i < in->n; i++)
        if (stat(in->paths[i], &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino)
            return i;
    return -1;
}

/* 0, or TD_EXIT_USAGE after an error line if the journal or part at path is an input. */
static int check_part(const char *path, void *arg)
{
    const input_list *in = arg;
    int i = input_index(path, in);
    if (i < 0)
        return 0;
    td_cli_error("sweep",
                 "%s: the sweep's journal%s is the same file as the %s (%s): an input is never overwritten; "
                 "choose another -o prefix",
                 path, strcmp(path, in->journal) ? " part" : "", i == 0 ? "case file" : "@include file", in->paths[i]);
    return TD_EXIT_USAGE;
}

int sweep_store_check_inputs(const char *journal, const char *const *inputs, int n)
{
    input_list in;
    int code;
    in.journal = journal;
    in.paths = inputs;
    in.n = n;
    code = check_part(journal, &in);
    return code ? code : each_part(journal, check_part, &in);
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

/* The journal j->path of this sweep, opened to append after its last whole record (a torn tail is
 * cut off), or created when missing or cut before its header was whole. */
static int journal_reopen(sweep_journal *j, uint64_t fp, long points)
{
    journal_header want = header_of(fp, points);
    journal_read r;
    int m;
    j->f = fopen(j->path, "r+b");
    m = j->f ? header_matches(j->f, &want) : HEADER_NONE;
    if (m < 0)
        return refuse_foreign(j->path, m);
    if (m == HEADER_NONE) {
        if (j->f)
            fclose(j->f);
        return journal_create(j, fp, points);
    }
    read_records(j->f, points, NULL, &r);
    if (r.corrupt)
        return refuse_corrupt(j->path, r.end);
    /* the position set before the stream turns from reading to writing, the torn tail cut */
    if (fseeko(j->f, r.end, SEEK_SET) == 0 && ftruncate(fileno(j->f), r.end) != 0)
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
    rec.length = (uint32_t)RECORD_BODY;
    rec.point = point;
    memcpy(&rec.row, row, sizeof rec.row); /* every byte, padding too, as the CRC covers them */
    rec.crc = record_crc(&rec);
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
