/*
 * libFuzzer target for the `--vary` / `--with` parser (td_sweep_grid_vary, td_sweep_grid_with in
 * lib/sweep/grid.c): the grid of a sweep's points from the specs of its command line.
 *
 * An input is up to 20 lines, one spec each: a line that starts with '+' is a --with (the rest of
 * the line), any other a --vary (a NUL byte ends a line too). Each spec is added in turn, the
 * grid checked after each.
 *
 * Besides the sanitizers (ASan + UBSan), the target checks the parser's contract and abort()s
 * when it is broken:
 *   - the status is TD_OK, TD_ERR_PARSE or TD_ERR_NOMEM, and err.code agrees;
 *   - on failure the message is one non-empty line without control characters (what the tool
 *     prints on stderr), and the grid is unchanged (its points, keys and axes);
 *   - the grid stays within its limits (points 1 .. TD_SWEEP_MAX_POINTS, keys, axes), each key's
 *     axis is one of them, and at the first, the last and a middle point every key has a value
 *     shorter than TD_SWEEP_VALUE_SIZE, a number that reads back whole and finite when the key is
 *     numeric, and "KEY=VALUE" as its override.
 * TD_FUZZ_VERBOSE=1 prints each status and message.
 * Build and run: FUZZ_TARGET=vary scripts/fuzz.sh SECONDS (fuzz/README.md).
 */
#include "fuzz_util.h"
#include "touchdown/sweep.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SPECS 20
#define MAX_SPEC_LEN 512

static void check_value(const td_sweep_grid *g, long p, int k)
{
    const char *v = td_sweep_grid_value(g, p, k), *key = td_sweep_grid_key(g, k);
    char buf[TD_SWEEP_KEY_SIZE + TD_SWEEP_VALUE_SIZE + 2], *end;
    double x;
    int len;
    if (!v || !key || strlen(v) >= TD_SWEEP_VALUE_SIZE || strlen(key) >= TD_SWEEP_KEY_SIZE)
        fuzz_contract_failed("a key or value missing or too long", v);
    if (td_sweep_grid_numeric(g, k)) {
        x = strtod(v, &end);
        if (end == v || *end || !isfinite(x))
            fuzz_contract_failed("a value of a numeric key that is not a finite number", v);
    }
    len = td_sweep_grid_override(g, p, k, buf, sizeof buf);
    if (len != (int)(strlen(key) + 1 + strlen(v)) || strncmp(buf, key, strlen(key)) || buf[strlen(key)] != '=' ||
        strcmp(buf + strlen(key) + 1, v))
        fuzz_contract_failed("the override is not KEY=VALUE", buf);
}

static void check_grid(const td_sweep_grid *g)
{
    long n = td_sweep_grid_points(g), at[3];
    int k, i, keys = td_sweep_grid_keys(g), axes = td_sweep_grid_axes(g);
    if (n < 1 || n > TD_SWEEP_MAX_POINTS || keys < axes || keys > TD_SWEEP_MAX_KEYS || axes < 0 ||
        axes > TD_SWEEP_MAX_AXES)
        fuzz_contract_failed("a grid beyond its limits", "");
    at[0] = 0;
    at[1] = n / 2;
    at[2] = n - 1;
    for (k = 0; k < keys; k++) {
        if (td_sweep_grid_axis(g, k) < 0 || td_sweep_grid_axis(g, k) >= axes)
            fuzz_contract_failed("a key on an axis that does not exist", td_sweep_grid_key(g, k));
        if (!td_sweep_grid_spec(g, k) || !td_sweep_grid_origin(g, k))
            fuzz_contract_failed("a key without its spec or origin", td_sweep_grid_key(g, k));
        for (i = 0; i < 3; i++)
            check_value(g, at[i], k);
    }
}

/* Add one spec; checks the status, the message and that a failure left the grid as it was. */
static void add_spec(td_sweep_grid *g, const char *spec, int with)
{
    long n = td_sweep_grid_points(g);
    int keys = td_sweep_grid_keys(g), axes = td_sweep_grid_axes(g);
    const char *fault;
    td_error err;
    td_status st;
    td_error_clear(&err);
    st = with ? td_sweep_grid_with(g, spec, &err) : td_sweep_grid_vary(g, spec, &err);
    if (fuzz_verbose())
        fprintf(stderr, "fuzz_vary: %s '%s': status %d, message \"%s\"\n", with ? "--with" : "--vary", spec, (int)st,
                err.message);
    if (st == TD_OK)
        return;
    if (st != TD_ERR_PARSE && st != TD_ERR_NOMEM)
        fuzz_contract_failed("unexpected status", err.message);
    if (err.code != st)
        fuzz_contract_failed("err.code differs from the status returned", err.message);
    if ((fault = fuzz_message_fault(err.message)))
        fuzz_contract_failed(fault, err.message);
    if (td_sweep_grid_points(g) != n || td_sweep_grid_keys(g) != keys || td_sweep_grid_axes(g) != axes)
        fuzz_contract_failed("a failed spec changed the grid", err.message);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char spec[MAX_SPEC_LEN];
    td_sweep_grid *g = NULL;
    size_t i = 0;
    int n = 0;
    if (td_sweep_grid_create(&g, NULL) != TD_OK)
        abort();
    while (i < size && n++ < MAX_SPECS) {
        size_t k = 0;
        while (i < size && data[i] != '\n' && data[i] != '\0') {
            if (k + 1 < sizeof spec)
                spec[k++] = (char)data[i];
            i++;
        }
        spec[k] = '\0';
        i++;
        add_spec(g, spec[0] == '+' ? spec + 1 : spec, spec[0] == '+');
        check_grid(g);
    }
    td_sweep_grid_free(&g);
    if (g)
        fuzz_contract_failed("td_sweep_grid_free did not clear the pointer", "");
    return 0;
}
