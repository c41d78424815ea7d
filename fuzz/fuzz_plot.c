/*
 * libFuzzer target for the reading of result files by `touchdown plot` (tools/plot/plot_file.c,
 * plot_sweep_load.c, through the library's reader lib/io/result.c): the input's bytes are written
 * as result.h5 and loaded with plot_file_load, as the tool loads each file it is given (the reader
 * keeps HDF5's own error printing off). The seed corpus (scripts/fuzz.sh) is small result files of the tool itself: a
 * run, a modal analysis and a sweep table.
 *
 * Besides the sanitizers (ASan + UBSan; the HDF5 library is not instrumented, its reads are
 * checked only where they write into our buffers), the target checks the loader's contract and
 * abort()s when it is broken:
 *   - the result is PLOT_OK, PLOT_FAILED or PLOT_BAD_INPUT;
 *   - a file loaded has a kind, and every array it holds has the length its counts say (each
 *     element is read, so that ASan sees any that is short) and every string ends;
 *   - plot_file_free leaves nothing behind (LeakSanitizer).
 * TD_FUZZ_VERBOSE=1 prints the loader's messages (silenced otherwise).
 * Build and run: FUZZ_TARGET=plot scripts/fuzz.sh SECONDS (fuzz/README.md).
 */
#include "fuzz_util.h"
#include "plot/plot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The sum of a[0 .. n) (NULL: 0): reads every element. */
static double touch(const double *a, size_t n)
{
    double s = 0.0;
    size_t i;
    for (i = 0; a && i < n; i++)
        s += a[i];
    return s;
}

static double touch_sim(const plot_sim *s)
{
    size_t i, nr = (size_t)s->nret, na = (size_t)s->namb;
    double sum = touch(s->t, s->n) + touch(s->x, s->n * nr) + touch(s->y, s->n * nr) + touch(s->r, s->n * nr) +
                 touch(s->fn, s->n * nr) + touch(s->contact, s->n * nr) + touch(s->amb, s->n * na * 2) +
                 touch(s->clearance, nr);
    if (s->nret < 0 || s->namb < 0)
        fuzz_contract_failed("a negative count of retainers or AMBs", "");
    for (i = 0; s->ret_nodes && i < nr; i++)
        sum += (double)s->ret_nodes[i];
    for (i = 0; s->amb_nodes && i < na; i++)
        sum += (double)s->amb_nodes[i];
    for (i = 0; i < s->nev; i++)
        if (!memchr(s->ev[i].kind, '\0', sizeof s->ev[i].kind))
            fuzz_contract_failed("an event kind that does not end", "");
        else
            sum += s->ev[i].time + strlen(s->ev[i].kind);
    return sum;
}

static double touch_modal(const plot_modal *m)
{
    size_t ns = (size_t)m->ns, nb = (size_t)m->nb, nm = (size_t)m->nm, nn = (size_t)m->nn;
    if (m->ns < 0 || m->nb < 0 || m->nm < 0 || m->nn < 0 || m->ncrit < 0)
        fuzz_contract_failed("a negative count in a modal file", "");
    return touch(m->speed, ns) + touch(m->freq, ns * nb) + touch(m->whirl, ns * nb) +
           touch(m->crit_speed, (size_t)m->ncrit) + touch(m->crit_freq, (size_t)m->ncrit) +
           touch(m->crit_whirl, (size_t)m->ncrit) + touch(m->mode_freq, nm) + touch(m->mode_whirl, nm) +
           touch(m->mode_zeta, nm) + touch(m->xr, nm * nn) + touch(m->xi, nm * nn) + touch(m->yr, nm * nn) +
           touch(m->yi, nm * nn) + touch(m->node_z, nn);
}

static double touch_sweep(const plot_sweep *s)
{
    double sum = touch(s->section, s->n * s->m) + touch(s->clearance, s->n);
    size_t i;
    int k;
    if (s->nkeys < 0 || s->nkeys > PLOT_SWEEP_MAX_KEYS)
        fuzz_contract_failed("a sweep table with a bad number of keys", "");
    for (k = 0; k < s->nkeys; k++) {
        if (!memchr(s->key[k], '\0', sizeof s->key[k]))
            fuzz_contract_failed("a swept key that does not end", "");
        sum += touch(s->value[k], s->n);
        for (i = 0; s->text[k] && i < s->n; i++)
            sum += s->text[k][i] ? (double)strlen(s->text[k][i]) : 0.0;
    }
    for (i = 0; s->regime && i < s->n; i++)
        sum += s->regime[i];
    return sum;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int init;
    const char *path = fuzz_path("result.h5");
    plot_window win = {-HUGE_VAL, HUGE_VAL};
    plot_file f;
    volatile double sum = 0.0;
    int rc;
    if (!init) {
        init = 1;
        fuzz_quiet_stderr();
    }
    fuzz_write(path, data, size);
    rc = plot_file_load(path, &win, &f);
    if (fuzz_verbose())
        fprintf(stderr, "fuzz_plot: load %d\n", rc);
    if (rc != PLOT_OK && rc != PLOT_FAILED && rc != PLOT_BAD_INPUT)
        fuzz_contract_failed("plot_file_load returned an unexpected code", "");
    if (rc != PLOT_OK)
        return 0;
    if (!memchr(f.stem, '\0', sizeof f.stem) || !memchr(f.title, '\0', sizeof f.title))
        fuzz_contract_failed("a stem or title that does not end", "");
    if (f.kind == PLOT_KIND_SIM)
        sum = touch_sim(&f.sim);
    else if (f.kind == PLOT_KIND_MODAL)
        sum = touch_modal(&f.modal);
    else if (f.kind == PLOT_KIND_SWEEP)
        sum = touch_sweep(&f.sweep);
    else
        fuzz_contract_failed("a file loaded without a kind", "");
    (void)sum;
    plot_file_free(&f);
    return 0;
}
