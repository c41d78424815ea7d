/*
 * What the writers share below writer.c and the format back ends (csv_writer.c, hdf5_writer.c),
 * so that each calls down to it: the names of the event kinds, the I/O error, the checked
 * close of a stream and the CSV files' completeness line.
 */
#include "io/schema.h"
#include "io/writer_internal.h"
#include "util/error_internal.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

const char *td_event_kind_name(td_event_kind kind)
{
    switch (kind) {
    case TD_EVENT_CONTACT_ONSET: return "contact_onset";
    case TD_EVENT_RELEASE: return "release";
    case TD_EVENT_FRICTION_REVERSAL: return "friction_reversal";
    case TD_EVENT_SCHEDULE: return "schedule";
    case TD_EVENT_PENALTY_ENTER: return "penalty_enter";
    case TD_EVENT_PENALTY_EXIT: return "penalty_exit";
    case TD_EVENT_ROLL_START: return "roll_start";
    case TD_EVENT_ROLL_END: return "roll_end";
    case TD_EVENT_CONTROLLER_SWITCH: return "controller_switch";
    }
    return "unknown";
}

td_status td_io_fail(td_error *err, const char *path, const char *what)
{
    return td_error_set(err, TD_ERR_IO, "%s: %s: %s", path, what, errno ? strerror(errno) : "write error");
}

int td_io_close_stream(FILE **f)
{
    int rc = 0;
    if (*f) {
        rc |= fflush(*f) != 0;
        rc |= ferror(*f) != 0;
        rc |= fclose(*f) != 0;
        *f = NULL;
    }
    return rc;
}

int td_io_csv_flag(FILE *f, int complete, const char *reason)
{
    int rc;
    if (complete)
        return fprintf(f, "# %s\n", td_out_name(TD_OUT_COMPLETE)) < 0;
    rc = fputs("# incomplete: ", f) < 0;
    for (; reason && *reason; reason++)
        rc |= fputc(*reason == '\n' || *reason == '\r' ? ' ' : *reason, f) == EOF;
    rc |= fputc('\n', f) == EOF;
    return rc;
}
