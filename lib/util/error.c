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

/* No part, no field: the site of every error that is not about a model part. */
static void clear_sites(td_error *err)
{
    static const td_error_site none = {NULL, 0, NULL};
    err->site = none;
    err->other = none;
    err->reason = 0;
}

void td_error_clear(td_error *err)
{
    if (err) {
        err->code = TD_OK;
        err->message[0] = '\0';
        clear_sites(err);
    }
}

td_status td_error_set(td_error *err, td_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        err->code = code;
        clear_sites(err);
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return code;
}

td_status td_error_set_site(td_error *err, td_status code, const td_error_site *site, const td_error_site *other,
                            const char *fmt, ...)
{
    if (err) {
        va_list ap;
        char part[64];
        int n;
        err->code = code;
        err->site = *site;
        err->other = *other;
        if (site->index >= 0)
            snprintf(part, sizeof part, "%s %d", site->part, site->index);
        else
            snprintf(part, sizeof part, "%s", site->part); /* not in a model */
        n = site->field ? snprintf(err->message, sizeof err->message, "%s: %s: ", part, site->field)
                        : snprintf(err->message, sizeof err->message, "%s: ", part);
        err->reason = n > 0 && n < (int)sizeof err->message ? n : 0;
        va_start(ap, fmt);
        vsnprintf(err->message + err->reason, sizeof err->message - (size_t)err->reason, fmt, ap);
        va_end(ap);
    }
    return code;
}

/* Append at most `max` bytes of s to buf (length *len); a longer s loses its middle to "...". */
static void append_cut(char *buf, size_t *len, const char *s, size_t max)
{
    size_t n = strlen(s), head;
    if (n <= max) {
        memcpy(buf + *len, s, n);
        *len += n;
        return;
    }
    if (max < 3) {
        return;
    }
    head = (max - 3) / 2;
    memcpy(buf + *len, s, head);
    memcpy(buf + *len + head, "...", 3);
    memcpy(buf + *len + head + 3, s + n - (max - 3 - head), max - 3 - head);
    *len += max;
}

td_status td_error_set_reason(td_error *err, td_status code, const char *context, const char *reason)
{
    const size_t room = TD_ERROR_MESSAGE_SIZE - 1;
    size_t len = 0, rlen, clen;
    if (!err)
        return code;
    rlen = strlen(reason);
    if (rlen > room * 3 / 4)
        rlen = room * 3 / 4;
    clen = context[0] ? room - rlen - 2 : 0;
    if (context[0]) {
        append_cut(err->message, &len, context, clen);
        memcpy(err->message + len, ": ", 2);
        len += 2;
    }
    err->code = code;
    clear_sites(err);
    err->reason = (int)len; /* the reason starts past "CONTEXT: " */
    append_cut(err->message, &len, reason, room - len);
    err->message[len] = '\0';
    return code;
}
