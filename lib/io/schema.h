/*
 * The output schema as data (touchdown/result.h lists the ids): one entry per dataset, group,
 * attribute and event field of the files touchdown writes, with its name, units, shape and type,
 * and for the run's CSV files its column. Every writer takes its names from here.
 */
#ifndef TD_IO_SCHEMA_H
#define TD_IO_SCHEMA_H

#include "touchdown/result.h"

typedef struct td_schema_entry {
    const char *name;      /**< link or attribute name ("" for the root) */
    td_out_id parent;      /**< the group it is in, the object it is on (TD_OUT_ID_COUNT: several) */
    td_out_place place;    /**< group, dataset, attribute, event field, CSV only */
    unsigned files;        /**< TD_OUT_IN_* bits */
    td_out_type type;      /**< in the HDF5 file */
    const char *units;     /**< a dataset's `units` attribute as written; the unit of the others */
    const char *shape;     /**< in the words of docs/output-format.md */
    const char *csv;       /**< CSV column: a printf format of the component and/or index; NULL: name */
    const char *csv_units; /**< the unit in the CSV header's brackets; NULL: units */
} td_schema_entry;

/** The entry of `id`; NULL for an id out of range. */
const td_schema_entry *td_schema(td_out_id id);

/** The CSV column name (format) of `id`: its csv, else its name. */
const char *td_schema_csv(td_out_id id);

/** The unit in the CSV header of `id`: its csv_units, else its units. */
const char *td_schema_csv_units(td_out_id id);

/** The two lateral components of every x-y pair written, in order ("x", "y"): the values of
 *  /component, the last axis of /nodes/displacement and /ambs/force, and the component in the
 *  names of their CSV columns. */
const char *const *td_schema_components(void);
/** The same names joined by ',' ("x,y"): the `components` attribute of those datasets. */
const char *td_schema_components_list(void);

#endif
