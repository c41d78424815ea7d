/*
 * libFuzzer target for the sweep journal's reader (tools/sweep/sweep_journal.c): sweep_store_read, and
 * sweep_journal_open, which cuts a torn tail off before appending.
 *
 * An input is a control byte, a byte giving the sweep's number of points (1 .. 64), then the
 * journal's bytes. Control bit 0 puts the valid header of the sweep (the documented layout:
 * magic TDSWJ02, fingerprint, row size, points; docs/output-format.md) in front of them, so that
 * the fuzzer starts past the header; bit 1 also makes every whole record's frame hold (its length
 * and CRC-32 written over the fuzzed ones), so that what comes after the frame (the point, the
 * state, the text fields' bounds) is reached. The file is written as journal, read, opened to
 * append, a row recorded, closed, and read again. TD_FUZZ_MAKE_SEEDS=DIR writes the seed corpus
 * (journals of the writer itself) into DIR and exits (scripts/fuzz.sh).
 *
 * Besides the sanitizers (ASan + UBSan), the target checks the journal's contract and abort()s
 * when it is broken:
 *   - the reader returns 0 or TD_EXIT_USAGE (refused), and the writer's open agrees with it;
 *   - after a read that is not refused, `found` is the number of rows no longer "not run", each
 *     of them done or failed, and every text field of every row ends within its array;
 *   - a row recorded after reopening reads back, found by one more if its point was new, and the
 *     journal then reads whole (the torn tail was cut: no notice the second time).
 * TD_FUZZ_VERBOSE=1 prints the journal's own messages (silenced otherwise).
 * Build and run: FUZZ_TARGET=journal scripts/fuzz.sh SECONDS (fuzz/README.md).
 */
#include "common/cli.h"
#include "fuzz_util.h"
#include "sweep/sweep_journal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#define FP 0x7a11ed5eedULL
#define MAX_POINTS 64
#define HEADER 32                                 /* magic[8], fingerprint, row size, points */
#define FRAME 8                                   /* length (u32), CRC-32 (u32) */
#define RECORD (FRAME + 8 + sizeof(td_sweep_row)) /* the frame, the point (i64), the row */

/* The header of the sweep (FP, points), as the journal writes it. */
static void header(uint8_t *h, long points)
{
    uint64_t fp = FP, row = sizeof(td_sweep_row);
    int64_t n = points;
    memset(h, 0, HEADER);
    memcpy(h, "TDSWJ02", 8);
    memcpy(h + 8, &fp, 8);
    memcpy(h + 16, &row, 8);
    memcpy(h + 24, &n, 8);
}

/* Make the frame of every whole record after the header hold. */
static void fix_frames(uint8_t *j, size_t n)
{
    size_t at;
    uint32_t len = (uint32_t)(RECORD - FRAME), crc;
    for (at = HEADER; at + RECORD <= n; at += RECORD) {
        crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), j + at + FRAME, (uInt)(RECORD - FRAME));
        memcpy(j + at, &len, 4);
        memcpy(j + at + 4, &crc, 4);
    }
}

static void check_rows(const td_sweep_row *rows, long points, long found)
{
    long p, ran = 0;
    for (p = 0; p < points; p++) {
        const td_sweep_row *r = &rows[p];
        if (!sweep_row_texts_end(r))
            fuzz_contract_failed("a text field of a row read does not end in its array", "");
        if (r->state != TD_SWEEP_NOT_RUN && r->state != TD_SWEEP_DONE && r->state != TD_SWEEP_FAILED)
            fuzz_contract_failed("a row read with an unknown state", "");
        ran += r->state != TD_SWEEP_NOT_RUN;
    }
    if (found != ran)
        fuzz_contract_failed("found differs from the rows read", "");
}

static int read_back(const char *path, long points, td_sweep_row *rows, long *found)
{
    long p;
    for (p = 0; p < points; p++)
        td_sweep_row_unknown(&rows[p], TD_SWEEP_NOT_RUN, "not run", "");
    *found = 0;
    return sweep_store_read(path, FP, points, rows, found);
}

/* Reopen the journal to append, record a failed row for the last point, read it all again. */
static void append_and_reread(const char *path, long points, const td_sweep_row *before, long found)
{
    td_sweep_row rows[MAX_POINTS], r;
    sweep_journal *j = NULL;
    long again;
    if (sweep_journal_open(path, FP, points, &j) != 0)
        fuzz_contract_failed("the writer refused a journal the reader took", "");
    td_sweep_row_unknown(&r, TD_SWEEP_FAILED, "fuzz", "recorded by the fuzz target");
    sweep_journal_record(j, points - 1, &r);
    sweep_journal_close(&j);
    if (j)
        fuzz_contract_failed("sweep_journal_close did not clear the pointer", "");
    if (read_back(path, points, rows, &again) != 0)
        fuzz_contract_failed("a journal appended to is refused", "");
    check_rows(rows, points, again);
    if (again != found + (before[points - 1].state == TD_SWEEP_NOT_RUN) || rows[points - 1].state != TD_SWEEP_FAILED ||
        strcmp(rows[points - 1].message, "recorded by the fuzz target") != 0)
        fuzz_contract_failed("the row recorded after reopening does not read back", "");
}

/* One seed: control byte ctl, the points, then the journal at path from byte `from` (n bytes). */
static void write_seed(const char *dir, int i, int ctl, long points, const char *path, long from, long n)
{
    char name[512];
    uint8_t *b = malloc((size_t)n + 2);
    FILE *f = fopen(path, "rb");
    if (!b || !f || fseek(f, from, SEEK_SET) || fread(b + 2, 1, (size_t)n, f) != (size_t)n)
        abort();
    fclose(f);
    b[0] = (uint8_t)ctl;
    b[1] = (uint8_t)(points - 1);
    snprintf(name, sizeof name, "%s/journal-%02d", dir, i);
    fuzz_write(name, b, (size_t)n + 2);
    free(b);
}

/* TD_FUZZ_MAKE_SEEDS=DIR: write the seed corpus into DIR and exit: journals of the writer itself,
 * of 4 and 64 points with 0 .. 3 rows, each as a whole file (control 0) and as records alone
 * (control 3: header and frames made by the target), and one torn, one zero-filled. */
static void make_seeds(const char *dir)
{
    static const long points[2] = {4, 64};
    const char *path = fuzz_path("seed.journal");
    static const uint8_t zeros[600];
    sweep_journal *j = NULL;
    td_sweep_row r;
    FILE *f;
    int i = 0, k, rows;
    for (k = 0; k < 2; k++)
        for (rows = 0; rows <= 3; rows++) {
            long n = HEADER + rows * (long)RECORD, p;
            remove(path);
            if (sweep_journal_open(path, FP, points[k], &j))
                abort();
            for (p = 0; p < rows; p++) {
                td_sweep_row_unknown(&r, p == 1 ? TD_SWEEP_FAILED : TD_SWEEP_DONE,
                                     p == 1 ? "solver failure" : "success",
                                     p == 1 ? "the step size fell below its minimum" : "");
                r.peak_housing_force = 1000.0 * (double)p;
                sweep_journal_record(j, p * 2 % points[k], &r);
            }
            sweep_journal_close(&j);
            write_seed(dir, i++, 0, points[k], path, 0, n);
            write_seed(dir, i++, 3, points[k], path, HEADER, n - HEADER);
            if (rows == 3) {
                write_seed(dir, i++, 0, points[k], path, 0, n - (long)RECORD / 2); /* torn */
                f = fopen(path, "ab");
                if (!f || fwrite(zeros, 1, sizeof zeros, f) != sizeof zeros || fclose(f))
                    abort();
                write_seed(dir, i++, 0, points[k], path, 0, n + (long)sizeof zeros); /* zero-filled tail */
            }
        }
    remove(path);
    exit(0);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    const char *dir = getenv("TD_FUZZ_MAKE_SEEDS");
    (void)argc;
    (void)argv;
    if (dir && dir[0])
        make_seeds(dir);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    td_sweep_row rows[MAX_POINTS];
    const char *path;
    uint8_t *j;
    size_t n;
    long points, found;
    int code, ctl;
    sweep_journal *w = NULL;
    if (size < 2)
        return 0;
    fuzz_quiet_stderr();
    path = fuzz_path("sweep.journal");
    ctl = data[0];
    points = 1 + data[1] % MAX_POINTS;
    n = size - 2 + ((ctl & 1) ? HEADER : 0);
    if (!(j = malloc(n + 1)))
        abort();
    if (ctl & 1)
        header(j, points);
    memcpy(j + ((ctl & 1) ? HEADER : 0), data + 2, size - 2);
    if (ctl & 2)
        fix_frames(j, n);
    fuzz_write(path, j, n);
    free(j);
    code = read_back(path, points, rows, &found);
    if (fuzz_verbose())
        fprintf(stderr, "fuzz_journal: %ld points, read: code %d, %ld rows\n", points, code, found);
    if (code != 0 && code != TD_EXIT_USAGE)
        fuzz_contract_failed("the reader returned an unexpected code", "");
    if (code == 0) {
        check_rows(rows, points, found);
        append_and_reread(path, points, rows, found);
    } else if (sweep_journal_open(path, FP, points, &w) != TD_EXIT_USAGE || w) {
        fuzz_contract_failed("the writer took a journal the reader refused", "");
    }
    return 0;
}
