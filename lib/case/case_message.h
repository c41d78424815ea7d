/*
 * The case reader's message helpers that need no reader (case_message.c, the bottom layer of
 * lib/case): user text made fit to quote, and a failure at a file's line. The sweep stage
 * (lib/sweep) words its errors about the case and the command line with them, as the reader
 * words its own, without seeing the reader's internals (case_internal.h).
 */
#ifndef TD_CASE_MESSAGE_H
#define TD_CASE_MESSAGE_H

#include <stddef.h>

#include "touchdown/error.h"

/* User text (a string value, an override, a file name) made fit to quote in a one-line message:
 * control characters become \n, \t, \r or \xHH (so no raw ESC reaches a terminal), and text
 * longer than the buffer is cut with "...". Writes at most n bytes (n >= 8) to buf; returns buf.
 * Every message that quotes user text passes it through here. */
const char *td_cr_printable(const char *s, char *buf, size_t n);
/* td_cr_printable into a new string (caller frees); NULL when out of memory. */
char *td_cr_printable_dup(const char *s);
/* Fail with "SHOWN:LINE: message" ("SHOWN: message" when line is 0), SHOWN (a file as shown in
 * messages) cut in its middle if needed so that the message survives; returns code. */
td_status td_cr_fail_file(td_error *err, td_status code, const char *shown, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

#endif
