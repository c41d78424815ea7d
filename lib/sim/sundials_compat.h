/*
 * The few places where SUNDIALS 6.x and 7.x differ, behind one small header, so that no other
 * file of the library needs a version test and no SUNDIALS type reaches a public header.
 *
 *  - SUNContext_Create takes a void* communicator in 6.x and a SUNComm (SUN_COMM_NULL) in 7.x.
 *  - realtype/booleantype are gone in 7.x: the library uses sunrealtype/sunbooleantype only.
 *  - IDASetErrHandlerFn is gone in 7.x: errors go to handlers pushed on the SUNContext.
 */
#ifndef TD_SUNDIALS_COMPAT_H
#define TD_SUNDIALS_COMPAT_H

#include <ida/ida.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_types.h>

/* Receives one message of the solver (error or warning): `code` < 0 error, > 0 warning. */
typedef void (*td_sun_message_fn)(int code, const char *function, const char *msg, void *data);

/* A sink and its data, referred to by the adapters below; must outlive the solver. */
typedef struct td_sun_message_sink {
    td_sun_message_fn fn;
    void *data;
} td_sun_message_sink;

static inline int td_sun_context_create(SUNContext *ctx)
{
#if SUNDIALS_VERSION_MAJOR >= 7
    return SUNContext_Create(SUN_COMM_NULL, ctx);
#else
    return SUNContext_Create(NULL, ctx);
#endif
}

#if SUNDIALS_VERSION_MAJOR >= 7
static inline void td_sun_error_adapter(int line, const char *func, const char *file, const char *msg, SUNErrCode code,
                                        void *data, SUNContext ctx)
{
    const td_sun_message_sink *sink = (const td_sun_message_sink *)data;
    (void)line, (void)file, (void)ctx;
    if (sink && sink->fn)
        sink->fn(code < 0 ? (int)code : -1, func, msg, sink->data);
}
#else
static inline void td_sun_error_adapter(int code, const char *module, const char *function, char *msg, void *data)
{
    const td_sun_message_sink *sink = (const td_sun_message_sink *)data;
    (void)module;
    if (sink && sink->fn)
        sink->fn(code, function, msg, sink->data);
}
#endif

/* Route every message of the IDA instance `mem` (6.x) or of the context `ctx` (7.x) to `sink`
 * instead of stderr: the library never prints. Returns 0 on success. */
static inline int td_sun_install_message_sink(SUNContext ctx, void *mem, td_sun_message_sink *sink)
{
#if SUNDIALS_VERSION_MAJOR >= 7
    (void)mem;
    if (SUNContext_ClearErrHandlers(ctx) != 0)
        return -1;
    return SUNContext_PushErrHandler(ctx, td_sun_error_adapter, sink) != 0 ? -1 : 0;
#else
    (void)ctx;
    return IDASetErrHandlerFn(mem, td_sun_error_adapter, sink) != IDA_SUCCESS ? -1 : 0;
#endif
}

#endif
