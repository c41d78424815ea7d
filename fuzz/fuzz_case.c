/*
 * libFuzzer target for the case-file reader, td_case_load (lib/case/case*.c, on libconfig 1.5).
 *
 * One fuzz input holds up to three parts separated by a line "@@@":
 *     MAIN TEXT \n@@@\n INCLUDED TEXT \n@@@\n OVERRIDES
 * MAIN is written to case.cfg and INCLUDED to part.cfg in a private temporary directory, so a
 * main file that says @include "part.cfg" pulls in the second fuzzed file (the seed corpus made by
 * scripts/fuzz.sh does so for every case that includes rig.cfg); every further line is one
 * --set override (at most 8). Then td_case_load runs on case.cfg with the overrides, and on a
 * case it loads td_sweep_check_case judges the `sweep` group (lib/sweep), as every command does.
 *
 * Besides the sanitizers (ASan + UBSan, -fno-sanitize-recover), the target checks the reader's
 * contract and abort()s when it is broken, so libFuzzer saves the input:
 *   - the status is one of TD_OK, TD_ERR_PARSE, TD_ERR_IO, TD_ERR_NOMEM;
 *   - on failure: no case is returned, and the message is one non-empty line with no control
 *     characters (what the tool prints on stderr);
 *   - on success: every accessor answers, the case text and name are strings, the model has
 *     nodes, the end time is finite and positive; the sweep group's judge returns TD_OK,
 *     TD_ERR_PARSE or TD_ERR_NOMEM, a failure with one such message line.
 *
 * The known findings K1-K3 (fuzz/README.md) are fixed, so the harness checks them like anything
 * else. TD_FUZZ_STRICT=0 brings back the filters that stepped round them (to fuzz an old reader):
 *   K1  an @include name not closed on its line: the error message spans lines -> not checked
 *       for being one line when it says "cannot open include file";
 *   K2  include bombs (a file including itself several times expands exponentially) -> inputs
 *       with more than 3 "@include" are not run;
 *   K3  messages quote user text (overrides, string values) raw, control characters included ->
 *       control characters in override lines become '?', and a message quoting a string value
 *       (got "...") is not checked for control characters or line breaks.
 * TD_FUZZ_VERBOSE=1 prints each status and message (to replay a finding).
 * Build and run: scripts/fuzz.sh SECONDS (see fuzz/README.md).
 */
#include "touchdown/case.h"
#include "touchdown/model.h"
#include "touchdown/sweep.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_OVERRIDES 8
#define MAX_OVERRIDE_LEN 256

/* The harness's private directory and its two file names (per process; removed at exit). */
static char dir[256];
static char main_path[300];
static char part_path[300];

static void remove_files(void)
{
    unlink(main_path);
    unlink(part_path);
    rmdir(dir);
}

static void setup_dir(void)
{
    const char *tmp = getenv("TMPDIR");
    if (dir[0])
        return;
    snprintf(dir, sizeof dir, "%s/td-fuzz.XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        perror("fuzz_case: mkdtemp");
        abort();
    }
    snprintf(main_path, sizeof main_path, "%s/case.cfg", dir);
    snprintf(part_path, sizeof part_path, "%s/part.cfg", dir);
    atexit(remove_files);
}

static void write_file(const char *path, const uint8_t *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || (n && fwrite(data, 1, n, f) != n) || fclose(f) != 0) {
        perror("fuzz_case: writing the input");
        abort();
    }
}

/* Find "\n@@@\n" (or "@@@\n" at the very start) in data[0..n): the part before it ends at
 * *part_end (its last newline kept); returns the index of the part after it, or n. */
static size_t split(const uint8_t *data, size_t n, size_t *part_end)
{
    static const char sep[] = "\n@@@\n";
    size_t i;
    if (n >= 4 && memcmp(data, "@@@\n", 4) == 0) {
        *part_end = 0;
        return 4;
    }
    for (i = 0; i + 5 <= n; i++)
        if (memcmp(data + i, sep, 5) == 0) {
            *part_end = i + 1;
            return i + 5;
        }
    *part_end = n;
    return n;
}

static void contract_failed(const char *what, const char *message)
{
    fprintf(stderr, "fuzz_case: contract broken: %s (message: \"%s\")\n", what, message ? message : "(null)");
    abort();
}

static int strict(void)
{
    const char *s = getenv("TD_FUZZ_STRICT");
    return !(s && s[0] == '0');
}

/* K2: more than 3 "@include" in the whole input. */
static int include_bomb(const uint8_t *data, size_t n)
{
    size_t i, count = 0;
    for (i = 0; i + 8 <= n; i++)
        if (data[i] == '@' && memcmp(data + i, "@include", 8) == 0)
            count++;
    return count > 3;
}

static void check_message(const char *m)
{
    const unsigned char *p;
    if (!strict() && (strstr(m, "cannot open include file") || strstr(m, "(got \""))) /* K1, K3 */
        return;
    if (!m[0])
        contract_failed("failure with an empty message", m);
    for (p = (const unsigned char *)m; *p; p++)
        if (*p == '\n' || *p == '\r')
            contract_failed("message of more than one line", m);
        else if (*p < 0x20 && *p != '\t')
            contract_failed("control character in the message", m);
}

static void check_case(const td_case *c)
{
    const td_model *m = td_case_model(c);
    const char *text = td_case_text(c), *name = td_case_name(c), *desc = td_case_description(c);
    double t_end = td_case_end_time(c);
    if (!m || !text || !name || !desc || !td_case_path(c) || !td_case_sim_options(c) || !td_case_output_options(c) ||
        !td_case_modal_options(c))
        contract_failed("an accessor returned NULL on a loaded case", "");
    if (strlen(text) == (size_t)-1 || strlen(name) == (size_t)-1 || strlen(desc) == (size_t)-1)
        abort(); /* touches every byte (ASan checks them) */
    if (td_model_node_count(m) < 2)
        contract_failed("a loaded case with fewer than 2 nodes", "");
    if (!(t_end > 0.0) || !isfinite(t_end))
        contract_failed("a loaded case with a bad end time", "");
}

/* The sweep group's specs judged by the sweep's rules, as every command judges a case it loads. */
static void check_sweep_group(const td_case *c)
{
    td_error err;
    td_status st;
    td_error_clear(&err);
    st = td_sweep_check_case(c, &err);
    if (st == TD_OK)
        return;
    if (st != TD_ERR_PARSE && st != TD_ERR_NOMEM)
        contract_failed("the sweep group's judge returned an unexpected status", err.message);
    if (err.code != st)
        contract_failed("the sweep group's judge: err.code differs from the status returned", err.message);
    check_message(err.message);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char ov_buf[MAX_OVERRIDES][MAX_OVERRIDE_LEN];
    const char *ov[MAX_OVERRIDES];
    size_t main_end, part_start, part_end, rest, i;
    int n_ov = 0;
    td_case *c = NULL;
    td_error err;
    td_status st;

    if (!strict() && include_bomb(data, size)) /* K2 */
        return 0;
    setup_dir();
    part_start = split(data, size, &main_end);
    write_file(main_path, data, main_end);
    rest = part_start < size ? part_start + split(data + part_start, size - part_start, &part_end) : size;
    if (part_start < size)
        part_end += part_start;
    else
        part_end = size;
    write_file(part_path, data + part_start, part_end - part_start);

    /* overrides: the lines of the third part (a NUL byte ends a line too) */
    for (i = rest; i < size && n_ov < MAX_OVERRIDES;) {
        size_t k = 0;
        while (i < size && data[i] != '\n' && data[i] != '\0') {
            if (k + 1 < MAX_OVERRIDE_LEN)
                ov_buf[n_ov][k++] = (!strict() && data[i] < 0x20) ? '?' : (char)data[i]; /* K3 */
            i++;
        }
        ov_buf[n_ov][k] = '\0';
        ov[n_ov] = ov_buf[n_ov];
        n_ov++;
        i++;
    }

    td_error_clear(&err);
    st = td_case_load(main_path, ov, n_ov, &c, &err);
    if (getenv("TD_FUZZ_VERBOSE")) /* for replaying a finding: what the reader said */
        fprintf(stderr, "fuzz_case: status %d, %d override(s), message \"%s\"\n", (int)st, n_ov, err.message);
    switch (st) {
    case TD_OK:
        if (!c)
            contract_failed("TD_OK without a case", err.message);
        check_case(c);
        check_sweep_group(c);
        break;
    case TD_ERR_PARSE:
    case TD_ERR_IO:
    case TD_ERR_NOMEM:
        if (c)
            contract_failed("a failure that returned a case", err.message);
        if (err.code != st)
            contract_failed("err.code differs from the status returned", err.message);
        check_message(err.message);
        break;
    default: contract_failed("unexpected status", err.message);
    }
    td_case_free(&c);
    if (c)
        contract_failed("td_case_free did not clear the pointer", "");
    return 0;
}
