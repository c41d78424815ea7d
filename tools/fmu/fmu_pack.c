/* touchdown fmu: pack the unpacked FMU into its zip archive (libzip) and put it in place. The FMI 2.0
 * standard, section 2.3: an FMU is a zip file with modelDescription.xml at its root, the binaries
 * in binaries/<platform>/<modelIdentifier>.so and the files the binary reads in resources/. */
#define _DEFAULT_SOURCE /* mkstemps: the temporary name ends in ".partial", as the library's writers' do */
#include "fmu/fmu_pack.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zip.h>

/* Every entry gets this time (MS-DOS date 1980-01-01, 00:00) and a fixed mode: the same files give the
 * same archive, whoever packs them and whenever. */
#define FMU_DOS_DATE ((0u << 9) | (1u << 5) | 1u)
#define FMU_DOS_TIME 0u
#define FMU_MODE_FILE 0100644u
#define FMU_MODE_PROGRAM 0100755u

static void say(char *msg, size_t n, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void say(char *msg, size_t n, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, n, fmt, ap);
    va_end(ap);
}

/* Add the file at `path` as the archive's `name` with `mode`. 0, or -1 with msg. */
static int add_file(zip_t *za, const char *path, const char *name, unsigned mode, char *msg, size_t n)
{
    zip_source_t *src = zip_source_file(za, path, 0, -1);
    zip_int64_t idx;
    if (!src || (idx = zip_file_add(za, name, src, ZIP_FL_ENC_UTF_8)) < 0) {
        if (src)
            zip_source_free(src);
        say(msg, n, "cannot add %s to the archive: %s", path, zip_strerror(za));
        return -1;
    }
    if (zip_file_set_dostime(za, (zip_uint64_t)idx, FMU_DOS_TIME, FMU_DOS_DATE, 0) < 0 ||
        zip_file_set_external_attributes(za, (zip_uint64_t)idx, 0, ZIP_OPSYS_UNIX, (zip_uint32_t)mode << 16) < 0) {
        say(msg, n, "cannot set the attributes of %s in the archive: %s", name, zip_strerror(za));
        return -1;
    }
    return 0;
}

/* Add the files under dir/rel (rel "" for dir itself), each named by its path relative to dir, in
 * byte order of the names (scandir's alphasort in the C locale the tool runs in). */
static int add_tree(zip_t *za, const char *dir, const char *rel, char *msg, size_t n)
{
    struct dirent **names = NULL;
    char path[8200], name[4096];
    int i, count, status = 0;
    snprintf(path, sizeof path, "%s%s%s", dir, *rel ? "/" : "", rel);
    if ((count = scandir(path, &names, NULL, alphasort)) < 0) {
        say(msg, n, "cannot read the directory %s: %s", path, strerror(errno));
        return -1;
    }
    for (i = 0; i < count; i++) {
        struct stat sb;
        const char *d = names[i]->d_name;
        if (status || !strcmp(d, ".") || !strcmp(d, ".."))
            continue;
        if ((size_t)snprintf(name, sizeof name, "%s%s%s", rel, *rel ? "/" : "", d) >= sizeof name ||
            (size_t)snprintf(path, sizeof path, "%s/%s", dir, name) >= sizeof path) {
            say(msg, n, "%s/%s: the path is too long", dir, name);
            status = -1;
        } else if (lstat(path, &sb) != 0) {
            say(msg, n, "cannot read %s: %s", path, strerror(errno));
            status = -1;
        } else if (S_ISDIR(sb.st_mode)) {
            status = add_tree(za, dir, name, msg, n);
        } else if (S_ISREG(sb.st_mode)) {
            status = add_file(za, path, name, FMU_MODE_FILE, msg, n);
        } else {
            say(msg, n, "%s: not a regular file nor a directory", path);
            status = -1;
        }
    }
    for (i = 0; i < count; i++)
        free(names[i]);
    free(names);
    return status;
}

/* Create OUT.XXXXXX.partial (in tmp, n bytes) with the mode a new file gets (mkstemps gives 0600,
 * and libzip keeps the mode of the file it replaces). Returns 0 or -1 with msg. */
static int create_temp(const char *out, char *tmp, size_t tn, char *msg, size_t n)
{
    mode_t mask = umask(0);
    int fd;
    umask(mask);
    if ((size_t)snprintf(tmp, tn, "%s.XXXXXX.partial", out) >= tn) {
        say(msg, n, "%s: the path is too long", out);
        return -1;
    }
    if ((fd = mkstemps(tmp, (int)strlen(".partial"))) < 0) {
        say(msg, n, "cannot create a file beside %s: %s", out, strerror(errno));
        return -1;
    }
    if (fchmod(fd, 0666 & ~mask) != 0) {
        say(msg, n, "cannot set the mode of %s: %s", tmp, strerror(errno));
        close(fd);
        unlink(tmp);
        return -1;
    }
    close(fd);
    return 0;
}

/* Flush the file at path to the disk (what rename then publishes is on it). */
static int sync_file(const char *path)
{
    int fd = open(path, O_RDONLY), status;
    if (fd < 0)
        return -1;
    status = fsync(fd);
    close(fd);
    return status;
}

/* Write the archive into tmp: the staged tree, then the binary. 0 or -1 with msg. */
static int write_archive(const char *tmp, const char *stage, const char *binary, const char *model_id,
                         volatile sig_atomic_t *cancel, char *msg, size_t n)
{
    char so[512];
    int zerr = 0;
    zip_t *za = zip_open(tmp, ZIP_CREATE | ZIP_TRUNCATE, &zerr);
    if (!za) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, zerr);
        say(msg, n, "cannot write %s: %s", tmp, zip_error_strerror(&ze));
        zip_error_fini(&ze);
        return -1;
    }
    snprintf(so, sizeof so, "binaries/linux64/%s.so", model_id);
    if (add_tree(za, stage, "", msg, n) != 0 || add_file(za, binary, so, FMU_MODE_PROGRAM, msg, n) != 0 || *cancel) {
        if (*cancel)
            say(msg, n, "interrupted");
        zip_discard(za);
        return -1;
    }
    if (zip_close(za) != 0) {
        say(msg, n, "cannot write %s: %s", tmp, zip_strerror(za));
        zip_discard(za);
        return -1;
    }
    return 0;
}

int fmu_pack(const char *stage, const char *binary, const char *model_id, const char *out,
             volatile sig_atomic_t *cancel, char *msg, size_t n)
{
    char tmp[4200];
    if (create_temp(out, tmp, sizeof tmp, msg, n) != 0)
        return -1;
    if (write_archive(tmp, stage, binary, model_id, cancel, msg, n) != 0) {
        unlink(tmp);
        return -1;
    }
    if (*cancel) {
        say(msg, n, "interrupted");
        unlink(tmp);
        return -1;
    }
    if (sync_file(tmp) != 0 || rename(tmp, out) != 0) {
        say(msg, n, "cannot write %s: %s", out, strerror(errno));
        unlink(tmp);
        return -1;
    }
    return 0;
}

int fmu_remove_tree(const char *dir)
{
    struct dirent **names = NULL;
    char path[4096];
    int i, count, status = 0;
    if (strlen(dir) + 258 > sizeof path || (count = scandir(dir, &names, NULL, NULL)) < 0)
        return -1;
    for (i = 0; i < count; i++) {
        struct stat sb;
        const char *d = names[i]->d_name;
        if (strcmp(d, ".") && strcmp(d, "..")) {
            snprintf(path, sizeof path, "%s/%s", dir, d);
            if (lstat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
                status |= fmu_remove_tree(path);
            else
                status |= unlink(path);
        }
        free(names[i]);
    }
    free(names);
    return status | rmdir(dir);
}
