/* Status strings and the error-record helpers every module uses. */
#include "util/error_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *td_strerror(td_status code)
{
    switch (code) {
    case TD_OK: return "success";
    case TD_EVENT: return "stopped at an event";
    case TD_ERR_NOMEM: return "out of memory";
    case TD_ERR_INVALID: return "invalid argument";
    case TD_ERR_PARSE: return "malformed case file";
    case TD_ERR_IO: return "input/output error";
    case TD_ERR_SOLVER: return "solver failure";
    case TD_ERR_NUMERIC: return "numerical failure";
    case TD_ERR_STATE: return "call not allowed in this state";
    case TD_ERR_INTERRUPTED: return "interrupted";
    }
    return "unknown status";
}

void td_error_clear(td_error *err)
{
    if (err) {
        err->code = TD_OK;
        err->message[0] = '\0';
    }
}

td_status td_error_set(td_error *err, td_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        err->code = code;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return code;
}
