/*
 * The sweep journal (tools/sweep/sweep_journal.c, the tool's) against what a crash or a bad disk leaves
 * behind: a zero-filled tail, a last record of garbage that says "done", a record cut short, text
 * fields without their terminating zero, a damaged record with whole records after it, a
 * journal of the previous format, one of another build (its row layout), and files shorter than a header. Each journal
 * is written by the journal's own writer and then has its bytes changed; what it must read back is what was written,
 * never more: the rows of the whole records, every text field ending in bounds, a torn tail dropped (its point runs
 * again) and damage in the middle refused.
 */
#include "td_test.h"

#include "common/cli.h"
#include "sweep/sweep_journal.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#define FP 0x5eedf00du /* any fingerprint: the sweep the journal belongs to */
#define POINTS 4
#define HEADER 32 /* bytes before the first record (documented in docs/output-format.md) */

static const char journal_path[] = "sweep_journal_test.journal";

/* A journal holding the rows of points 0 and 2 (peak forces 10 N and 30 N); returns a record's size. */
static long write_journal(void)
{
    sweep_journal *j = NULL;
    td_sweep_row r;
    struct stat sb;
    remove(journal_path);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), 0);
    td_sweep_row_unknown(&r, TD_SWEEP_DONE, "success", "");
    r.peak_housing_force = 10.0;
    sweep_journal_record(j, 0, &r);
    r.peak_housing_force = 30.0;
    sweep_journal_record(j, 2, &r);
    sweep_journal_close(&j);
    assert_null(j);
    assert_int_equal(stat(journal_path, &sb), 0);
    assert_true(sb.st_size > HEADER && (sb.st_size - HEADER) % 2 == 0);
    return (long)(sb.st_size - HEADER) / 2;
}

/* n bytes of the journal from offset at (n == 0: to its end), malloc'ed; *len their count. */
static unsigned char *bytes_of(long at, long n, long *len)
{
    FILE *f = fopen(journal_path, "rb");
    unsigned char *b;
    assert_non_null(f);
    if (n == 0) {
        assert_int_equal(fseek(f, 0, SEEK_END), 0);
        n = ftell(f) - at;
    }
    b = malloc((size_t)n + 1);
    assert_non_null(b);
    assert_int_equal(fseek(f, at, SEEK_SET), 0);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = n;
    return b;
}

static void put_bytes(long at, const void *b, long n)
{
    FILE *f = fopen(journal_path, "r+b");
    assert_non_null(f);
    assert_int_equal(fseek(f, at, at < 0 ? SEEK_END : SEEK_SET), 0);
    assert_int_equal(fwrite(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
}

/* A new file at the journal's path holding the n bytes b. */
static void put_bytes_new(const void *b, long n)
{
    FILE *f = fopen(journal_path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
}

/* Read the journal back into rows[] (all "not run" first); returns the code, *found the rows. */
static int read_back(td_sweep_row *rows, long *found)
{
    int p;
    for (p = 0; p < POINTS; p++)
        td_sweep_row_unknown(&rows[p], TD_SWEEP_NOT_RUN, "not run", "");
    *found = -1;
    return sweep_store_read(journal_path, FP, POINTS, rows, found);
}

/* The rows of the two records written, and nothing else; every text field ends in bounds. */
static void assert_written_rows(const td_sweep_row *rows, long found)
{
    int p;
    assert_int_equal(found, 2);
    assert_int_equal(rows[0].state, TD_SWEEP_DONE);
    assert_true(rows[0].peak_housing_force == 10.0);
    assert_int_equal(rows[2].state, TD_SWEEP_DONE);
    assert_true(rows[2].peak_housing_force == 30.0);
    assert_int_equal(rows[1].state, TD_SWEEP_NOT_RUN);
    assert_int_equal(rows[3].state, TD_SWEEP_NOT_RUN);
    for (p = 0; p < POINTS; p++)
        assert_true(memchr(rows[p].status, '\0', sizeof rows[p].status) &&
                    memchr(rows[p].message, '\0', sizeof rows[p].message) &&
                    memchr(rows[p].ending, '\0', sizeof rows[p].ending) &&
                    memchr(rows[p].warnings, '\0', sizeof rows[p].warnings) &&
                    memchr(rows[p].regime, '\0', sizeof rows[p].regime));
}

static void test_whole_journal(void **state)
{
    td_sweep_row rows[POINTS];
    long found;
    (void)state;
    write_journal();
    assert_int_equal(read_back(rows, &found), 0);
    assert_written_rows(rows, found);
    remove(journal_path);
}

/* Blocks the file system allocated but the crash kept from being written read as zeros: more
 * than two records' worth of them. */
static void test_zero_filled_tail(void **state)
{
    td_sweep_row rows[POINTS];
    long found, rec = write_journal();
    unsigned char *zeros = calloc((size_t)(2 * rec + rec / 3), 1);
    (void)state;
    assert_non_null(zeros);
    put_bytes(HEADER + 2 * rec, zeros, 2 * rec + rec / 3);
    free(zeros);
    assert_int_equal(read_back(rows, &found), 0);
    assert_written_rows(rows, found);
    remove(journal_path);
}

/* Offset, within a record, of byte `off` of its row (the row ends the record). */
static long row_byte(long rec, size_t off)
{
    return rec - (long)sizeof(td_sweep_row) + (long)off;
}

/* A last record of garbage whose row says "done": a copy of the last record (point 2) with a
 * byte of its peak force changed, as a bad disk leaves it. */
static void test_garbage_last_record(void **state)
{
    td_sweep_row rows[POINTS];
    long n, found, rec = write_journal();
    unsigned char *last = bytes_of(HEADER + rec, rec, &n);
    (void)state;
    last[row_byte(rec, offsetof(td_sweep_row, peak_housing_force) + 3)] ^= 0x5a;
    put_bytes(HEADER + 2 * rec, last, rec);
    free(last);
    assert_int_equal(read_back(rows, &found), 0);
    assert_written_rows(rows, found);
    remove(journal_path);
}

/* A last record whose text field at `off` (n bytes) has no terminating zero, its frame (length,
 * CRC-32) made whole again so that only the bounds of its text can refuse it: it is dropped as a
 * torn tail and the rows of the whole records read back. */
static void assert_unterminated_dropped(size_t off, size_t n)
{
    td_sweep_row rows[POINTS];
    long len, found, rec = write_journal();
    unsigned char *last = bytes_of(HEADER + rec, rec, &len);
    uint32_t crc;
    memset(last + row_byte(rec, off), 'A', n);
    assert_int_equal(rec - (long)sizeof(td_sweep_row), 16); /* framed: u32 length, u32 CRC, i64 point, row */
    crc = (uint32_t)crc32(crc32(0L, Z_NULL, 0), last + 8, (uInt)(rec - 8));
    memcpy(last + 4, &crc, 4);
    put_bytes(HEADER + 2 * rec, last, rec);
    free(last);
    assert_int_equal(read_back(rows, &found), 0);
    assert_written_rows(rows, found);
    remove(journal_path);
}

/* Each text field of a row in turn, the others whole. */
static void test_unterminated_text(void **state)
{
    td_sweep_row r;
    (void)state;
    assert_unterminated_dropped(offsetof(td_sweep_row, status), sizeof r.status);
    assert_unterminated_dropped(offsetof(td_sweep_row, message), sizeof r.message);
    assert_unterminated_dropped(offsetof(td_sweep_row, ending), sizeof r.ending);
    assert_unterminated_dropped(offsetof(td_sweep_row, warnings), sizeof r.warnings);
    assert_unterminated_dropped(offsetof(td_sweep_row, regime), sizeof r.regime);
}

/* A record cut short (the kill came during its write) is cut off when the journal is reopened:
 * the next record follows the last whole one. */
static void test_torn_record_cut(void **state)
{
    td_sweep_row rows[POINTS], r;
    sweep_journal *j = NULL;
    long n, found, rec = write_journal();
    unsigned char *half = bytes_of(HEADER, rec / 2, &n);
    struct stat sb;
    (void)state;
    put_bytes(HEADER + 2 * rec, half, n);
    free(half);
    assert_int_equal(read_back(rows, &found), 0);
    assert_written_rows(rows, found);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), 0);
    td_sweep_row_unknown(&r, TD_SWEEP_FAILED, "solver failure", "a message");
    sweep_journal_record(j, 3, &r);
    sweep_journal_close(&j);
    assert_int_equal(stat(journal_path, &sb), 0);
    assert_int_equal((long)sb.st_size, HEADER + 3 * rec);
    assert_int_equal(read_back(rows, &found), 0);
    assert_int_equal(found, 3);
    assert_int_equal(rows[3].state, TD_SWEEP_FAILED);
    assert_string_equal(rows[3].message, "a message");
    remove(journal_path);
}

/* A damaged record with a whole record after it is not a torn tail: the journal is refused, by
 * the reader and by the writer that would append to it. */
static void test_damage_in_the_middle(void **state)
{
    td_sweep_row rows[POINTS];
    sweep_journal *j = NULL;
    long found, rec = write_journal();
    unsigned char bad = 0x77;
    (void)state;
    put_bytes(HEADER + row_byte(rec, offsetof(td_sweep_row, total_impulse) + 2), &bad, 1);
    assert_int_equal(read_back(rows, &found), TD_EXIT_USAGE);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), TD_EXIT_USAGE);
    assert_null(j);
    remove(journal_path);
}

/* A journal whose header is of the format before records were framed (magic TDSWJ01) is refused,
 * never read as records of this format. */
static void test_previous_format(void **state)
{
    td_sweep_row rows[POINTS];
    long found;
    (void)state;
    write_journal();
    put_bytes(0, "TDSWJ01", 8);
    assert_int_equal(read_back(rows, &found), TD_EXIT_USAGE);
    remove(journal_path);
}

/* What f printed on stderr (malloc'ed), *rc what it returned. */
static char *stderr_of(int (*f)(td_sweep_row *, long *), td_sweep_row *rows, long *found, int *rc)
{
    const char *path = "sweep_journal_test.err";
    int saved, fd;
    char *text;
    fflush(stderr);
    saved = dup(STDERR_FILENO);
    fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    assert_true(saved >= 0 && fd >= 0);
    dup2(fd, STDERR_FILENO);
    close(fd);
    *rc = f(rows, found);
    fflush(stderr);
    dup2(saved, STDERR_FILENO);
    close(saved);
    text = td_test_read_file(path);
    remove(path);
    return text;
}

/* A journal of another build (a different row layout: its header's row size, bytes 16 to 23,
 * changed and nothing else, so that the fingerprint still matches) is refused for that, by the
 * reader and the writer, and the line says so rather than "another sweep". */
static void test_other_build(void **state)
{
    td_sweep_row rows[POINTS];
    sweep_journal *j = NULL;
    long n, found;
    unsigned char *head;
    uint64_t size;
    char *text;
    int rc;
    (void)state;
    write_journal();
    head = bytes_of(16, 8, &n);
    memcpy(&size, head, sizeof size);
    free(head);
    assert_true(size == sizeof(td_sweep_row)); /* the field is where the layout says */
    size += 8;
    put_bytes(16, &size, sizeof size);
    text = stderr_of(read_back, rows, &found, &rc);
    assert_int_equal(rc, TD_EXIT_USAGE);
    assert_non_null(strstr(text, "sweep_journal_test.journal is a sweep journal written by another build of "
                                 "touchdown (its row layout differs)"));
    assert_null(strstr(text, "another sweep"));
    free(text);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), TD_EXIT_USAGE);
    assert_null(j);
    remove(journal_path);
}

/* A file shorter than the header: the first 20 bytes of the journal's own header (a crash while
 * the header was written) are no journal, started afresh; 10 bytes of text are not a journal,
 * refused by the reader and the writer and left as they were. */
static void test_short_file(void **state)
{
    td_sweep_row rows[POINTS];
    sweep_journal *j = NULL;
    long n, found;
    unsigned char *head;
    struct stat sb;
    (void)state;
    write_journal();
    head = bytes_of(0, 20, &n);
    remove(journal_path);
    put_bytes_new(head, n);
    free(head);
    assert_int_equal(read_back(rows, &found), 0);
    assert_int_equal(found, 0);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), 0);
    sweep_journal_close(&j);
    assert_int_equal(stat(journal_path, &sb), 0);
    assert_int_equal((long)sb.st_size, HEADER);
    remove(journal_path);
    put_bytes_new("my notes\n\n", 10);
    assert_int_equal(read_back(rows, &found), TD_EXIT_USAGE);
    assert_int_equal(sweep_journal_open(journal_path, FP, POINTS, &j), TD_EXIT_USAGE);
    assert_null(j);
    head = bytes_of(0, 0, &n);
    assert_int_equal(n, 10);
    assert_memory_equal(head, "my notes\n\n", 10);
    free(head);
    remove(journal_path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_whole_journal),       cmocka_unit_test(test_zero_filled_tail),
        cmocka_unit_test(test_garbage_last_record), cmocka_unit_test(test_unterminated_text),
        cmocka_unit_test(test_torn_record_cut),     cmocka_unit_test(test_damage_in_the_middle),
        cmocka_unit_test(test_previous_format),     cmocka_unit_test(test_short_file),
        cmocka_unit_test(test_other_build),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
