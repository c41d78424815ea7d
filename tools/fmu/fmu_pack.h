/* touchdown fmu: the unpacked FMU (a directory) packed into its zip archive, written under a
 * temporary name and renamed; the staging directory removed. No physics here. */
#ifndef TD_TOOLS_FMU_PACK_H
#define TD_TOOLS_FMU_PACK_H

#include <signal.h>
#include <stddef.h>

/* Zip every file under the directory `stage` (its paths relative to it, in byte order) plus the file
 * `binary` as binaries/linux64/MODEL_ID.so into `out`: written to OUT.XXXXXX.partial in out's
 * directory, then renamed to `out`, so that `out` is either as it was or complete. The archive is the
 * same bits for the same files (fixed entry times and modes). Stops, removing the temporary file,
 * when *cancel becomes nonzero. Returns 0, or -1 with a one-line reason in msg (n bytes). */
int fmu_pack(const char *stage, const char *binary, const char *model_id, const char *out,
             volatile sig_atomic_t *cancel, char *msg, size_t n);

/* Remove the directory `dir` and everything under it (not following symbolic links); 0 or -1. */
int fmu_remove_tree(const char *dir);

#endif
