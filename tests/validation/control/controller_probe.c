/*
 * controller_probe: builds controllers from commands on stdin with the public API and prints
 * their responses, for scipy_reference.py, which writes the commands, builds the same laws with
 * scipy.signal and compares. One command per line (numbers as text, matrices column-major):
 *
 *   law NAME                            start a law (the blocks that follow go in series)
 *   gain G | pid KP KINT KD FILTER | leadlag G ZERO POLE | lowpass F ORDER DAMPING | notch F WIDTH DEPTH
 *   resonant G PHASE F [DAMPING]
 *   tf RATE NNUM NUM... NDEN DEN...     zpk RATE GAIN NZ (RE IM)... NP (RE IM)...
 *   ss RATE N M P A... B... C... D...
 *   discretise RATE tustin|zoh PREWARP  delay SAMPLES  minimal
 *   set KEY=VALUE                       a case-file override (the rest of the line) for the next `case`
 *   case INDEX PATH                     the law: controller INDEX of the case file PATH as the case
 *                                       reader builds it (touchdown/case.h), with the overrides set
 *   append                              the law so far side by side with itself
 *   branch                              keep the law so far aside and start another
 *   sum                                 the law kept aside plus the law so far, in parallel
 *   freq F...        prints  "freq NAME F re im ..." (G column-major)
 *   step INPUT T...  prints  "step NAME T y..."
 *   matrices         prints  "matrices NAME N M P RATE A... B... C... D..."
 *
 * Exit status 1 with the library's message on the first failure.
 */
#include "touchdown/case.h"
#include "touchdown/controller.h"
#include "touchdown/model.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINE (1 << 18)
#define MAX_VALUES 4096
#define MAX_OVERRIDES 8

static char name[128];
static td_controller *law, *aside;
static char *overrides[MAX_OVERRIDES];
static int n_overrides;

static int fail(const char *what, const td_error *err)
{
    fprintf(stderr, "controller_probe: %s: %s: %s\n", name, what, err ? err->message : "bad command");
    exit(1);
}

/* The numbers after the command word, into v; returns their count. */
static int numbers(char *rest, double *v)
{
    int n = 0;
    char *end;
    for (;;) {
        double x = strtod(rest, &end);
        if (end == rest || n == MAX_VALUES)
            return n;
        v[n++] = x;
        rest = end;
    }
}

/* law <- law then k (k alone for the first block). */
static void chain(td_controller *k, const char *what, td_error *err)
{
    td_controller *s;
    if (!k)
        fail(what, err);
    if (!law) {
        law = k;
        return;
    }
    s = td_controller_series(law, k, err);
    if (!s)
        fail(what, err);
    td_controller_free(&law);
    td_controller_free(&k);
    law = s;
}

static void replace(td_controller *k, const char *what, td_error *err)
{
    if (!k)
        fail(what, err);
    td_controller_free(&law);
    law = k;
}

static td_controller *make_zpk(const double *v, int count, td_error *err)
{
    double zr[64], zi[64], pr[64], pi[64];
    int nz = (int)v[2], np, i;
    if (nz < 0 || nz > 64 || 3 + 2 * nz >= count)
        fail("zpk", NULL);
    for (i = 0; i < nz; i++)
        zr[i] = v[3 + 2 * i], zi[i] = v[4 + 2 * i];
    np = (int)v[3 + 2 * nz];
    if (np < 0 || np > 64 || 4 + 2 * nz + 2 * np != count)
        fail("zpk", NULL);
    for (i = 0; i < np; i++)
        pr[i] = v[4 + 2 * nz + 2 * i], pi[i] = v[5 + 2 * nz + 2 * i];
    return td_controller_create_zpk(zr, zi, nz, pr, pi, np, v[1], v[0], err);
}

static td_controller *make_ss(const double *v, int count, td_error *err)
{
    int n = (int)v[1], m = (int)v[2], p = (int)v[3];
    const double *A = v + 4, *B = A + n * n, *C = B + n * m, *D = C + p * n;
    if (n < 0 || m < 1 || p < 1 || 4 + n * n + n * m + p * n + p * m != count)
        fail("ss", NULL);
    return td_controller_create_ss(n, m, p, A, B, C, D, NULL, v[0], err);
}

static td_controller *make_tf(const double *v, int count, td_error *err)
{
    int nn = (int)v[1], nd;
    if (nn < 1 || 2 + nn >= count)
        fail("tf", NULL);
    nd = (int)v[2 + nn];
    if (nd < 1 || 3 + nn + nd != count)
        fail("tf", NULL);
    return td_controller_create_tf(v + 2, nn, v + 3 + nn, nd, v[0], err);
}

/* The blocks of touchdown/controller.h; returns 0 when word is not one. */
static int block(const char *word, const double *v, int count, td_error *err)
{
    if (!strcmp(word, "gain") && count == 1) {
        chain(td_controller_create_gain(v[0], err), word, err);
    } else if (!strcmp(word, "pid") && count == 4) {
        td_pid_block b = {v[0], v[1], v[2], v[3]};
        chain(td_controller_create_pid(&b, err), word, err);
    } else if (!strcmp(word, "leadlag") && count == 3) {
        td_leadlag_block b = {v[0], v[1], v[2]};
        chain(td_controller_create_leadlag(&b, err), word, err);
    } else if (!strcmp(word, "lowpass") && count == 3) {
        td_lowpass_block b = {v[0], (int)v[1], v[2]};
        chain(td_controller_create_lowpass(&b, err), word, err);
    } else if (!strcmp(word, "notch") && count == 3) {
        td_notch_block b = {v[0], v[1], v[2]};
        chain(td_controller_create_notch(&b, err), word, err);
    } else if (!strcmp(word, "resonant") && (count == 3 || count == 4)) {
        td_resonant_block b = {v[0], v[1], v[2], count == 4 ? v[3] : 0.0};
        chain(td_controller_create_resonant(&b, err), word, err);
    } else if (!strcmp(word, "tf") && count >= 4) {
        chain(make_tf(v, count, err), word, err);
    } else if (!strcmp(word, "zpk") && count >= 4) {
        chain(make_zpk(v, count, err), word, err);
    } else if (!strcmp(word, "ss") && count >= 5) {
        chain(make_ss(v, count, err), word, err);
    } else {
        return 0;
    }
    return 1;
}

static void print_matrix(const double *M, int count)
{
    int i;
    for (i = 0; i < count; i++)
        printf(" %.17g", M[i]);
}

static void print_matrices(void)
{
    int n = td_controller_order(law), m = td_controller_inputs(law), p = td_controller_outputs(law);
    double *w = malloc(((size_t)n * n + (size_t)n * m + (size_t)p * n + (size_t)p * m + 1) * sizeof *w);
    if (!w)
        fail("matrices", NULL);
    td_controller_matrices(law, w, w + n * n, w + n * n + n * m, w + n * n + n * m + p * n, NULL);
    printf("matrices %s %d %d %d %.17g", name, n, m, p, td_controller_sample_rate(law));
    print_matrix(w, n * n + n * m + p * n + p * m);
    printf("\n");
    free(w);
}

static void print_responses(const char *word, const double *v, int count, td_error *err)
{
    int m = td_controller_inputs(law), p = td_controller_outputs(law), i, l;
    double re[64], im[64], y[64];
    if (m * p > 64)
        fail(word, NULL);
    for (i = !strcmp(word, "step"); i < count; i++) {
        if (!strcmp(word, "freq")) {
            if (td_controller_frequency_response(law, v[i], re, im, err) != TD_OK)
                fail(word, err);
            printf("freq %s %.17g", name, v[i]);
            for (l = 0; l < m * p; l++)
                printf(" %.17g %.17g", re[l], im[l]);
        } else {
            if (td_controller_step_response(law, (int)v[0], v + i, 1, y, err) != TD_OK)
                fail(word, err);
            printf("step %s %.17g", name, v[i]);
            print_matrix(y, p);
        }
        printf("\n");
    }
}

/* `set KEY=VALUE`: the rest of the line, without its surrounding blanks, kept for the next `case`. */
static void keep_override(const char *rest)
{
    size_t n;
    while (*rest == ' ' || *rest == '\t')
        rest++;
    n = strcspn(rest, "\r\n");
    while (n > 0 && (rest[n - 1] == ' ' || rest[n - 1] == '\t'))
        n--;
    if (n_overrides == MAX_OVERRIDES || n == 0 || !(overrides[n_overrides] = malloc(n + 1)))
        fail("set", NULL);
    memcpy(overrides[n_overrides], rest, n);
    overrides[n_overrides++][n] = '\0';
}

/* `case INDEX PATH`: law <- a copy of the case's controller INDEX; the overrides are used up. */
static void load_case(const char *rest, td_error *err)
{
    char path[4096];
    int index, i;
    td_case *c = NULL;
    const td_controller *k;
    if (sscanf(rest, "%d %4095s", &index, path) != 2)
        fail("case", NULL);
    if (td_case_load(path, (const char *const *)overrides, n_overrides, &c, err) != TD_OK)
        fail("case", err);
    for (i = 0; i < n_overrides; i++)
        free(overrides[i]);
    n_overrides = 0;
    k = index >= 0 && index < td_model_controller_count(td_case_model(c))
            ? td_model_get_controller(td_case_model(c), index, NULL, NULL, NULL)
            : NULL;
    if (!k)
        fail("case: no such controller", NULL);
    replace(td_controller_clone(k, err), "case", err);
    td_case_free(&c);
}

/* The commands that transform the law so far or print it; returns 0 when word is not one. */
static int operation(const char *word, char *rest, const double *v, int count, td_error *err)
{
    char method[16] = "";
    if (!strcmp(word, "discretise") && sscanf(rest, "%*s %15s", method) == 1) {
        double prewarp = strtod(strstr(rest, method) + strlen(method), NULL);
        td_discretisation d = !strcmp(method, "zoh") ? TD_DISCRETISE_ZOH : TD_DISCRETISE_TUSTIN;
        replace(td_controller_discretise(law, strtod(rest, NULL), d, prewarp, err), word, err);
    } else if (!strcmp(word, "delay") && count == 1) {
        replace(td_controller_delay(law, (int)v[0], err), word, err);
    } else if (!strcmp(word, "minimal")) {
        replace(td_controller_minimal(law, err), word, err);
    } else if (!strcmp(word, "append")) {
        replace(td_controller_append(law, law, err), word, err);
    } else if (!strcmp(word, "branch")) {
        td_controller_free(&aside);
        aside = law;
        law = NULL;
    } else if (!strcmp(word, "sum")) {
        replace(td_controller_parallel(aside, law, err), word, err);
    } else if (!strcmp(word, "set")) {
        keep_override(rest);
    } else if (!strcmp(word, "case")) {
        load_case(rest, err);
    } else if (!strcmp(word, "freq") || !strcmp(word, "step")) {
        print_responses(word, v, count, err);
    } else if (!strcmp(word, "matrices")) {
        print_matrices();
    } else {
        return 0;
    }
    return 1;
}

int main(void)
{
    static char line[MAX_LINE];
    static double v[MAX_VALUES];
    td_error err;
    while (fgets(line, sizeof line, stdin)) {
        char word[32] = "", *rest;
        int count;
        if (sscanf(line, "%31s", word) != 1 || word[0] == '#')
            continue;
        rest = strstr(line, word) + strlen(word);
        if (!strcmp(word, "law")) {
            td_controller_free(&law);
            if (sscanf(rest, "%127s", name) != 1)
                fail(word, NULL);
            continue;
        }
        count = numbers(rest, v);
        if (!block(word, v, count, &err) && !operation(word, rest, v, count, &err))
            fail(word, NULL);
        fflush(stdout);
    }
    td_controller_free(&law);
    td_controller_free(&aside);
    return 0;
}
