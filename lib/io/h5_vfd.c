/*
 * The writer's HDF5 file driver (see h5_vfd.h for why it exists): plain POSIX pread/pwrite on one
 * descriptor, like HDF5's sec2 driver, except that an I/O error is stored in the writer's slot and
 * reported to HDF5 as success. The H5FD_class_t layout is the one of HDF5 1.10 and 1.12 (C99
 * designated initialisers keep unnamed members zero); later versions, where a failed close no
 * longer leaves a dangling identifier, use the default driver and report errors through HDF5.
 */
#include "io/h5_vfd.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#if !H5_VERSION_GE(1, 13, 0)

/* What H5Pset_driver copies into the file access list. */
typedef struct vfd_info {
    int *io_errno;
} vfd_info;

typedef struct vfd_file {
    H5FD_t pub; /* first: HDF5 fills it in */
    int fd;
    haddr_t eoa, eof;
    dev_t dev;
    ino_t ino;
    int *io_errno;
} vfd_file;

/* Largest address: the largest off_t. */
#define VFD_MAXADDR ((haddr_t)(((haddr_t)1 << (8 * sizeof(off_t) - 1)) - 1))

static void keep_error(vfd_file *f, int e)
{
    if (*f->io_errno == 0)
        *f->io_errno = e ? e : EIO;
}

static H5FD_t *vfd_open(const char *name, unsigned flags, hid_t fapl, haddr_t maxaddr)
{
    const vfd_info *info = H5Pget_driver_info(fapl);
    int oflags = (flags & H5F_ACC_RDWR) ? O_RDWR : O_RDONLY;
    struct stat sb;
    vfd_file *f;
    (void)maxaddr;
    if (!info || !info->io_errno)
        return NULL;
    if (flags & H5F_ACC_TRUNC)
        oflags |= O_TRUNC;
    if (flags & H5F_ACC_CREAT)
        oflags |= O_CREAT;
    if (flags & H5F_ACC_EXCL)
        oflags |= O_EXCL;
    f = calloc(1, sizeof *f);
    if (!f)
        return NULL;
    f->io_errno = info->io_errno;
    f->fd = open(name, oflags, 0666);
    /* Not a sticky error: HDF5 probes for an existing file before creating one, and reports a
     * failed open itself. */
    if (f->fd < 0 || fstat(f->fd, &sb) != 0) {
        if (f->fd >= 0)
            close(f->fd);
        free(f);
        return NULL;
    }
    f->eof = (haddr_t)sb.st_size;
    f->dev = sb.st_dev;
    f->ino = sb.st_ino;
    return &f->pub;
}

static herr_t vfd_close(H5FD_t *file)
{
    vfd_file *f = (vfd_file *)file;
    if (close(f->fd) != 0)
        keep_error(f, errno);
    free(f);
    return 0;
}

static int vfd_cmp(const H5FD_t *a, const H5FD_t *b)
{
    const vfd_file *x = (const vfd_file *)a, *y = (const vfd_file *)b;
    if (x->dev != y->dev)
        return x->dev < y->dev ? -1 : 1;
    if (x->ino != y->ino)
        return x->ino < y->ino ? -1 : 1;
    return 0;
}

static herr_t vfd_query(const H5FD_t *file, unsigned long *flags)
{
    (void)file;
    /* The sec2 driver's features: metadata and small raw data aggregated, sieve buffer. */
    *flags = H5FD_FEAT_AGGREGATE_METADATA | H5FD_FEAT_ACCUMULATE_METADATA | H5FD_FEAT_DATA_SIEVE |
             H5FD_FEAT_AGGREGATE_SMALLDATA;
    return 0;
}

static haddr_t vfd_get_eoa(const H5FD_t *file, H5FD_mem_t type)
{
    (void)type;
    return ((const vfd_file *)file)->eoa;
}

static herr_t vfd_set_eoa(H5FD_t *file, H5FD_mem_t type, haddr_t addr)
{
    (void)type;
    ((vfd_file *)file)->eoa = addr;
    return 0;
}

static haddr_t vfd_get_eof(const H5FD_t *file, H5FD_mem_t type)
{
    (void)type;
    return ((const vfd_file *)file)->eof;
}

static herr_t vfd_get_handle(H5FD_t *file, hid_t fapl, void **handle)
{
    (void)fapl;
    *handle = &((vfd_file *)file)->fd;
    return 0;
}

static herr_t vfd_read(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size, void *buf)
{
    vfd_file *f = (vfd_file *)file;
    unsigned char *p = buf;
    (void)type;
    (void)dxpl;
    if (addr > VFD_MAXADDR || size > VFD_MAXADDR - addr)
        return -1;
    while (size > 0) {
        ssize_t n = pread(f->fd, p, size, (off_t)addr);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            keep_error(f, errno);
            return -1; /* a failed read is an ordinary HDF5 error, not one at close */
        }
        if (n == 0) { /* past the end of the file: zeros, like sec2 */
            memset(p, 0, size);
            break;
        }
        p += n;
        addr += (haddr_t)n;
        size -= (size_t)n;
    }
    return 0;
}

static herr_t vfd_write(H5FD_t *file, H5FD_mem_t type, hid_t dxpl, haddr_t addr, size_t size, const void *buf)
{
    vfd_file *f = (vfd_file *)file;
    const unsigned char *p = buf;
    haddr_t end;
    (void)type;
    (void)dxpl;
    if (addr > VFD_MAXADDR || size > VFD_MAXADDR - addr)
        return -1;
    end = addr + size;
    /* After the first failure nothing more is written: the file is already lost. */
    while (size > 0 && *f->io_errno == 0) {
        ssize_t n = pwrite(f->fd, p, size, (off_t)addr);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            keep_error(f, n < 0 ? errno : EIO);
            break;
        }
        p += n;
        addr += (haddr_t)n;
        size -= (size_t)n;
    }
    if (end > f->eof)
        f->eof = end;
    return 0;
}

static herr_t vfd_truncate(H5FD_t *file, hid_t dxpl, hbool_t closing)
{
    vfd_file *f = (vfd_file *)file;
    (void)dxpl;
    (void)closing;
    if (f->eoa != f->eof) {
        if (*f->io_errno == 0 && ftruncate(f->fd, (off_t)f->eoa) != 0)
            keep_error(f, errno);
        f->eof = f->eoa;
    }
    return 0;
}

/* No lock: the writer creates each temporary file under a unique name that no one else opens. */
static const H5FD_class_t vfd_class = {
    .name = "touchdown_writer",
    .maxaddr = VFD_MAXADDR,
    .fc_degree = H5F_CLOSE_WEAK,
    .fapl_size = sizeof(vfd_info),
    .open = vfd_open,
    .close = vfd_close,
    .cmp = vfd_cmp,
    .query = vfd_query,
    .get_eoa = vfd_get_eoa,
    .set_eoa = vfd_set_eoa,
    .get_eof = vfd_get_eof,
    .get_handle = vfd_get_handle,
    .read = vfd_read,
    .write = vfd_write,
    .truncate = vfd_truncate,
    .fl_map = H5FD_FLMAP_DICHOTOMY,
};

hid_t td_h5_vfd_use(hid_t fapl, int *io_errno)
{
    vfd_info info;
    hid_t driver = H5FDregister(&vfd_class);
    if (driver < 0)
        return -1;
    info.io_errno = io_errno;
    if (H5Pset_driver(fapl, driver, &info) < 0) {
        H5FDunregister(driver);
        return -1;
    }
    return driver;
}

void td_h5_vfd_release(hid_t driver)
{
    if (driver >= 0)
        H5FDunregister(driver);
}

#else /* HDF5 >= 1.13: failed closes are safe; keep the default driver */

hid_t td_h5_vfd_use(hid_t fapl, int *io_errno)
{
    (void)io_errno;
    /* no HDF5 file lock: the writer holds its own lock on the file (writer.c, td_io_create_temp),
     * which the sec2 driver's flock on a second descriptor would collide with */
    return H5Pset_fapl_sec2(fapl) < 0 || H5Pset_file_locking(fapl, 0, 1) < 0 ? -1 : 0;
}

void td_h5_vfd_release(hid_t driver)
{
    (void)driver;
}

#endif
