/*
 * touchdown/error.h - status codes and the error record every fallible call fills.
 */
#ifndef TOUCHDOWN_ERROR_H
#define TOUCHDOWN_ERROR_H

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Status of a library call: 0 success, positive information, negative failure
 * (the convention of ida.h, where IDA_ROOT_RETURN = 2).
 */
typedef enum td_status {
    TD_OK = 0,              /**< success */
    TD_EVENT = 1,           /**< td_sim_step stopped at an event before the output time */
    TD_ERR_NOMEM = -1,      /**< an allocation failed */
    TD_ERR_INVALID = -2,    /**< an argument or model value is invalid */
    TD_ERR_PARSE = -3,      /**< a case file is malformed */
    TD_ERR_IO = -4,         /**< a file could not be read or written */
    TD_ERR_SOLVER = -5,     /**< the DAE solver failed */
    TD_ERR_NUMERIC = -6,    /**< a linear-algebra or eigenvalue computation failed */
    TD_ERR_STATE = -7,      /**< the call is not allowed in the object's current state */
    TD_ERR_INTERRUPTED = -8 /**< stopped on request (e.g. a signal) */
} td_status;

/** Longest message an error record holds, terminating NUL included. */
#define TD_ERROR_MESSAGE_SIZE 512

/**
 * A place in a model: a part, its index and one of its fields. `part` and `field` are static
 * strings: the part as td_model_add_* names it ("element", "disc", "amb", "bearing", "retainer",
 * "unbalance", "change") and the member of its struct ("clearance", "bore_radius",
 * "material.E", ...). `index` numbers the part as td_model_get_* does; a td_model_add_* call
 * that fails gives the index the part would have had (the number of such parts before it);
 * td_disc_from_geometry, whose disc is in no model yet, gives -1 and the message "disc: FIELD: ...".
 */
typedef struct td_error_site {
    const char *part;  /**< NULL: the error is not about one part */
    int index;         /**< index of the part, in the numbering of td_model_get_*; -1: in no model */
    const char *field; /**< NULL: the part as a whole */
} td_error_site;

/**
 * Error record: the status and a one-line message saying what went wrong and where
 * (for case files: "FILE:LINE: KEY: what is wrong"). Owned by the caller; a NULL
 * td_error pointer is accepted everywhere and means "not interested".
 *
 * The model's checks (td_model_add_*, td_model_validate) also say where the fault is: `site`
 * names the part, index and field at fault, and the message reads "PART INDEX: FIELD: REASON"
 * ("PART INDEX: REASON" without a field), REASON starting at message + reason. A cross check
 * names the part it compared against in `other` (the AMB whose air gap a retainer's clearance
 * reaches, the retainer already on a node, the shaft's nodes, a list of parts with index -1).
 * The case reader's errors ("FILE:LINE: KEY: REASON", the sweep's too) put REASON at message +
 * reason as well; when the value at fault was written by one of td_case_load's overrides, `site`
 * names that override: part "override", index its position in the list, field NULL.
 * Every other error leaves both parts NULL and reason 0.
 */
typedef struct td_error {
    td_status code;
    char message[TD_ERROR_MESSAGE_SIZE];
    td_error_site site;  /**< the part, index and field at fault; part NULL when none */
    td_error_site other; /**< the part a cross check compared against; part NULL when none */
    int reason;          /**< offset in message of the reason, past "PART INDEX: FIELD: " */
} td_error;

/** Static, never-NULL description of a status code. */
TD_API const char *td_strerror(td_status code);

/** Reset an error record to TD_OK with an empty message. Accepts NULL. */
TD_API void td_error_clear(td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_ERROR_H */
