/* A text buffer for building strings piece by piece: growable (data from realloc, freed by its
 * owner, also after a failure) or over the caller's fixed array with snprintf semantics (what does
 * not fit is only counted). */
#ifndef TD_UTIL_TEXT_H
#define TD_UTIL_TEXT_H

#include <stddef.h>

#include "util/error_internal.h"

/* An empty growable text is {NULL, 0, 0, 0, 0}. */
typedef struct td_text {
    char *data; /* NUL-terminated once anything was written (NULL: empty growable text) */
    size_t len; /* length of the whole text, including what did not fit a fixed array */
    size_t cap; /* bytes at data */
    int fixed;  /* data is the caller's array: never grown, the text is cut to fit it */
    int failed; /* a growable text whose allocation failed: it stays as it was */
} td_text;

/** An empty text in the caller's `buf` of `n` bytes (n may be 0 to measure only). */
void td_text_fixed(td_text *t, char *buf, size_t n);
/** Append `n` bytes of `s`. */
void td_text_append(td_text *t, const char *s, size_t n);
/** Append printf-style. */
void td_text_printf(td_text *t, const char *fmt, ...) TD_PRINTF(2, 3);
/** Append `s` as a JSON string: quoted, with the escapes RFC 8259 requires. */
void td_text_json_string(td_text *t, const char *s);
/** Append x as a JSON number with 17 significant digits (it reads back exactly), or null for a
 *  value JSON cannot hold (TD_UNDEFINED, any NaN or infinity): a failure is never a number. */
void td_text_json_real(td_text *t, double x);

/** x into buf (n bytes) with the fewest significant digits (15, 16 or 17) that read back to x:
 *  short, and exact (a sweep's range values, a case file's numbers as sweep specs). */
void td_text_shortest_number(char *buf, size_t n, double x);

#endif
