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

/** Fill `err` (may be NULL) with `code`, the place `site` (part and field static strings) and
 *  `other` (part NULL: none), and the message "PART INDEX: FIELD: REASON" ("PART INDEX: REASON"
 *  when site->field is NULL), REASON printf-style; returns `code`. */
td_status td_error_set_site(td_error *err, td_status code, const td_error_site *site, const td_error_site *other,
                            const char *fmt, ...) TD_PRINTF(5, 6);

/** Fill `err` with "CONTEXT: REASON" (REASON alone when CONTEXT is empty), REASON at
 *  err->message + err->reason, no site. When the two do not fit in TD_ERROR_MESSAGE_SIZE, CONTEXT
 *  (where: a file, an echoed override, a key) is cut in its middle with "...", keeping its start
 *  and end, so that the reason always survives; REASON is cut only beyond 3/4 of the record.
 *  Returns `code`. */
td_status td_error_set_reason(td_error *err, td_status code, const char *context, const char *reason);

#endif
