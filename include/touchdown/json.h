/*
 * touchdown/json.h - the JSON string escape shared by the library's JSON output
 * (td_run_summary_json) and programs that write their own JSON around it.
 */
#ifndef TOUCHDOWN_JSON_H
#define TOUCHDOWN_JSON_H

#include <stddef.h>

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/** `s` as a JSON string: in double quotes, with '"' and '\\' escaped by a backslash and the
 *  control characters below 0x20 as \\u00XX (RFC 8259); other bytes, UTF-8 included, unchanged.
 *  NULL is written as "". Returns the length needed, like snprintf; buf is always NUL-terminated
 *  when n > 0 (n may be 0 to measure). */
TD_API int td_json_string(char *buf, size_t n, const char *s);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_JSON_H */
