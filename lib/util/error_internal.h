/* Internal error helpers. */
#ifndef TD_UTIL_ERROR_INTERNAL_H
#define TD_UTIL_ERROR_INTERNAL_H

#include "touchdown/error.h"

#if defined(__GNUC__)
#define TD_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define TD_PRINTF(f, a)
#endif

/** Fill `err` (may be NULL) with `code` and a printf-style message; returns `code`. */
td_status td_error_set(td_error *err, td_status code, const char *fmt, ...) TD_PRINTF(3, 4);

#endif
