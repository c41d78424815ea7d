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
 * Error record: the status and a one-line message saying what went wrong and where
 * (for case files: "FILE:LINE: KEY: what is wrong"). Owned by the caller; a NULL
 * td_error pointer is accepted everywhere and means "not interested".
 */
typedef struct td_error {
    td_status code;
    char message[TD_ERROR_MESSAGE_SIZE];
} td_error;

/** Static, never-NULL description of a status code. */
TD_API const char *td_strerror(td_status code);

/** Reset an error record to TD_OK with an empty message. Accepts NULL. */
TD_API void td_error_clear(td_error *err);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_ERROR_H */
