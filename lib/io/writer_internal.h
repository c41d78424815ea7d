/*
 * The td_writer record shared by the format back ends (hdf5_writer.c, csv_writer.c).
 *
 * writer.c owns what both formats share: argument checks, the layout copy, the attribute list,
 * the PATH.XXXXXX.partial -> PATH protocol. A back end implements four operations on its own state.
 */
#ifndef TD_IO_WRITER_INTERNAL_H
#define TD_IO_WRITER_INTERNAL_H

#include "touchdown/output.h"

#include <stdio.h>

/** Ending of every temporary file name (PATH.XXXXXX.partial); outputs may not end with it. */
#define TD_IO_TEMP_SUFFIX ".partial"

/** Longest attribute name, NUL included. */
#define TD_ATTR_NAME_SIZE 64

typedef enum td_attr_type { TD_ATTR_STRING = 0, TD_ATTR_DOUBLE = 1, TD_ATTR_LONG = 2 } td_attr_type;

/** One named attribute, kept until close. */
typedef struct td_attr {
    char name[TD_ATTR_NAME_SIZE];
    td_attr_type type;
    int count;       /**< values (strings: 1) */
    int is_array;    /**< written as a 1-D array even if count == 1 */
    char *text;      /**< TD_ATTR_STRING */
    double *doubles; /**< TD_ATTR_DOUBLE */
    long *longs;     /**< TD_ATTR_LONG */
} td_attr;

typedef struct td_writer_ops td_writer_ops;

struct td_writer {
    td_writer_kind kind;
    char *path;        /**< final path of the main file */
    char *tmp_path;    /**< path + ".XXXXXX.partial", created by td_io_create_temp */
    char *events_path; /**< CSV only: the events file (td_writer_events_path), else NULL */
    char *events_tmp;  /**< CSV only: events_path + ".XXXXXX.partial" */
    int tmp_fd;        /**< the new empty tmp_path, open until the back end takes it over (-1) */
    int events_fd;     /**< likewise for events_tmp */
    int tmp_lock;      /**< holds tmp_path's lock (td_io_create_temp) until the writer is freed */
    int events_lock;   /**< likewise for events_tmp */
    int node_count, retainer_count, amb_count;
    int race_fields;   /**< nonzero: the race columns / datasets too (td_output_layout) */
    int speed_field;   /**< nonzero: the rotor speed column / dataset too (td_output_layout) */
    int whirl_field;   /**< nonzero: the retainers' whirl rate columns / dataset too (td_output_layout) */
    int switch_fields; /**< nonzero: the events' controller and sensed_radius fields too (td_output_layout) */
    int compression;   /**< HDF5 deflate level, 0..9 */
    int *nodes;        /**< node_count numbers (NULL if 0) */
    td_attr *attrs;
    int attr_count, attr_capacity;
    long samples, events;
    int failed; /**< a write failed: the file can only be closed incomplete */
    char failure[TD_ERROR_MESSAGE_SIZE];
    const td_writer_ops *ops;
    void *impl; /**< back end state */

    /* heat */
    int thermal_fields; /**< nonzero: the retainers' temperature rises too (td_output_layout) */
    /* housing motion */
    int housing_fields; /**< nonzero: /housing and the absolute displacement (td_output_layout) */
    /** the next sample's (td_writer_housing; a housing body's after the housing's), NaN until given */
    double housing[TD_WRITER_HOUSING_VALUES + TD_WRITER_HOUSING_BODY_VALUES];
    double *node_abs_xy; /**< 2 node_count: the next sample's absolute displacement */
    /* housing body */
    int housing_body_fields; /**< nonzero: the body's displacement and tilt in /housing too (td_output_layout) */
    /* long runs */
    int window_fields;  /**< nonzero: window summaries too (td_output_layout) */
    char *windows_path; /**< CSV: the window file (td_writer_windows_path); without window_fields only removed */
    char *windows_tmp;  /**< its windows_path + ".XXXXXX.partial" */
    int windows_fd;     /**< as events_fd */
    int windows_lock;   /**< as events_lock */
    long windows;       /**< window summaries written */
    int omit_events;    /**< nonzero: no event table (td_output_layout); events_path is then only removed */
};

/** housing motion: the number of td_writer_housing's values a sample of `w` holds (the body's with a body). */
#define TD_WRITER_HOUSING_COUNT(w)                                                                                     \
    (TD_WRITER_HOUSING_VALUES + ((w)->housing_body_fields ? TD_WRITER_HOUSING_BODY_VALUES : 0))

/** Back-end operations. Each returns a status and fills err; finish and destroy release impl. */
struct td_writer_ops {
    /* Open the created, empty w->tmp_path (and w->events_tmp); an fd taken over is set to -1.
     * On failure release impl; the caller removes the files. */
    td_status (*open)(td_writer *w, td_error *err);
    td_status (*sample)(td_writer *w, double t, double speed, const double *node_xy, const td_retainer_state *ret,
                        const double *amb_f, td_error *err);
    td_status (*event)(td_writer *w, const td_event *ev, long sample, td_error *err);
    /* Write the buffered data, every attribute, then complete/incomplete_reason last, flush and
     * close the file(s) (not renamed yet), release impl and set it to NULL, even on failure.
     * `reason` is NULL when complete. */
    td_status (*finish)(td_writer *w, int complete, const char *reason, td_error *err);
    /* Release impl (may be NULL) without finishing; the caller removes the files. */
    void (*destroy)(td_writer *w);
    /* long runs: one window summary (only with window_fields) */
    td_status (*window)(td_writer *w, const td_window_summary *win, td_error *err);
};

extern const td_writer_ops td_hdf5_writer_ops;
extern const td_writer_ops td_csv_writer_ops;

/**
 * Create a new empty file PATH.XXXXXX.partial (XXXXXX: letters and digits) with O_CREAT|O_EXCL,
 * so it never is another run's file; *tmp (malloc'ed name) and *fd (open for writing) are set.
 * The same directory as PATH keeps the final rename atomic. The file is locked (flock, exclusive)
 * for as long as *lock stays open: close it only once the file is renamed or removed. First the
 * leftovers of earlier writers of PATH are removed: temporary files nobody holds the lock of
 * (their writer was killed), never a live writer's.
 */
td_status td_io_create_temp(const char *path, char **tmp, int *fd, int *lock, td_error *err);

/** Flush a closed temporary file to disk and rename it to `path`; on failure remove it. */
td_status td_io_commit_temp(const char *tmp, const char *path, td_error *err);

/** A whole text file at `path` by the completeness rule: written by write_all(f, ctx) under
 *  PATH.XXXXXX.partial, flushed and renamed to path, removed on any failure. */
td_status td_io_write_text_file(const char *path, void (*write_all)(FILE *f, const void *ctx), const void *ctx,
                                td_error *err);

/** The same for a writer that opens the file by name (HDF5): write_all(tmp, ctx, err) writes the
 *  temporary file tmp. */
td_status td_io_write_named_file(const char *path,
                                 td_status (*write_all)(const char *tmp, const void *ctx, td_error *err),
                                 const void *ctx, td_error *err);

/** Flush a closed file's data to disk (fsync); TD_ERR_IO on failure. */
td_status td_io_fsync_path(const char *path, td_error *err);

/* ---- io_common.c, below writer.c and the back ends ---- */
/** TD_ERR_IO "PATH: WHAT: CAUSE", the cause strerror(errno) ("write error" when errno is 0). */
td_status td_io_fail(td_error *err, const char *path, const char *what);

/** Flush, check and close a stream (*f set to NULL; NULL accepted); nonzero if anything failed,
 *  an earlier buffered write included. */
int td_io_close_stream(FILE **f);

/** The completeness line of a CSV file, its last line (docs/output-format.md, "Completeness
 *  rule"): "# complete", or "# incomplete: REASON" with each line break of the reason written as
 *  a space, so that the flag stays one line. Nonzero if a write failed. */
int td_io_csv_flag(FILE *f, int complete, const char *reason);

#endif
