/*
 * touchdown/version.h - compile-time and run-time version.
 */
#ifndef TOUCHDOWN_VERSION_H
#define TOUCHDOWN_VERSION_H

#include "touchdown/export.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TD_VERSION_MAJOR 0
#define TD_VERSION_MINOR 20
#define TD_VERSION_PATCH 1
#define TD_VERSION "0.20.1"

/** The library's version string, e.g. "0.2.0"; compare with TD_VERSION to detect a mismatch. */
TD_API const char *td_version(void);

#ifdef __cplusplus
}
#endif

#endif /* TOUCHDOWN_VERSION_H */
