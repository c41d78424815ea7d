/*
 * What the sweep stage (lib/sweep) sees of the case reader's `sweep` group (case_vary.c): its
 * specs as read, with the places they were written, and the context of an error about one of
 * them, so that lib/sweep judges them and names the setting at fault as the reader names its own,
 * without seeing the reader's internals (case_internal.h).
 */
#ifndef TD_CASE_SWEEP_SPECS_H
#define TD_CASE_SWEEP_SPECS_H

#include <stddef.h>

#include "touchdown/case.h"

/* One swept key of the case's `sweep` group as read (case_vary.c): the spec --vary (an entry of
 * `with`: --with) would take, with the place it was written. The reader checks the group's shape
 * only; the specs are judged by the sweep's rules (lib/sweep), which name the setting at fault as
 * the reader names its own (td_cr_sweep_context). */
typedef struct td_cr_sweep_spec {
    char *spec;  /* "KEY=START:STOP:N[:SPACING]" or "KEY=V1,V2,...", the key as written */
    char *where; /* "FILE:LINE: sweep.vary[i]" (or "...with[j]"): td_case_sweep_spec's, the axis's origin */
    char *at;    /* "FILE:LINE" of the entry, or how an override placed it (td_cr_where) */
    char *key;   /* the entry's setting, "sweep.vary[i]" or "sweep.vary[i].with[j]" (td_cr_key) */
    int with;    /* 1: zipped onto the axis of the spec before */
    int values;  /* 1: written as `values`, 0: as a range (from, to, points, spacing) */
} td_cr_sweep_spec;

/* Spec i (0 <= i < td_case_sweep_specs(c)) of the case's `sweep` group as read, borrowed. */
const td_cr_sweep_spec *td_cr_sweep_entry(const td_case *c, int i);
/* Bytes of an error's context "WHERE: KEY.SETTING" and of its "KEY.SETTING" before they are cut,
 * as in td_cr_fail. */
#define TD_CR_SWEEP_CONTEXT_SIZE 2048
#define TD_CR_SWEEP_KEY_SIZE 512
/* The context of an error about entry s, as td_cr_fail would give it: "WHERE: KEY", or
 * "WHERE: KEY.SETTING" when `setting` (a member of the entry, e.g. "points") is not NULL; into
 * buf (n bytes, TD_CR_SWEEP_CONTEXT_SIZE for the reader's own cut). */
void td_cr_sweep_context(const td_cr_sweep_spec *s, const char *setting, char *buf, size_t n);

#endif
