/*
 * touchdown/export.h - symbol visibility for the public API.
 */
#ifndef TOUCHDOWN_EXPORT_H
#define TOUCHDOWN_EXPORT_H

#if defined(TD_BUILDING_LIBRARY) && defined(__GNUC__)
#define TD_API __attribute__((visibility("default")))
#else
#define TD_API
#endif

#endif /* TOUCHDOWN_EXPORT_H */
