// journal_file.c -- a journal's POSIX storage: one file in a folder, appended and
// fsync'd; replaced through a temporary file, fsync, rename and an fsync of the folder
// (contract in sva_journal.h). sva_node and sva_can_node use it with their own names.
#include "sva/sva_journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int fail(sva_journal_file_t* f, const char* call, const char* path)
{
    f->err = errno;
    (void)snprintf(f->what, sizeof f->what, "%s %s: %s", call, path, strerror(f->err));
    return -1;
}

// write() until every byte is out (a signal or a short write is not a failure).
static int write_all(int fd, const uint8_t* p, uint32_t len)
{
    while (len > 0U) {
        const ssize_t n = write(fd, p, len);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return -1;
        }
        p += n;
        len -= (uint32_t)n;
    }
    return 0;
}

static int file_open(void* ctx, uint32_t* size)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    f->lock_fd = open(f->lock, O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (f->lock_fd < 0) {
        return fail(f, "open", f->lock);
    }
    struct flock fl;
    memset(&fl, 0, sizeof fl);
    fl.l_type = F_WRLCK;
    fl.l_whence = SEEK_SET;
    if (fcntl(f->lock_fd, F_SETLK, &fl) != 0) {
        const int e = errno;
        (void)close(f->lock_fd);
        f->lock_fd = -1;
        errno = e;
        if ((e == EACCES) || (e == EAGAIN)) {
            f->err = e;
            (void)snprintf(f->what, sizeof f->what,
                           "%.200s is in use: another process holds its lock (%s)", f->dir,
                           f->lock_name);
            return -1;
        }
        return fail(f, "lock", f->lock);
    }
    // A compaction that a crash interrupted leaves its temporary file: never the journal.
    if ((unlink(f->temp) != 0) && (errno != ENOENT)) {
        return fail(f, "unlink", f->temp);
    }
    f->fd = open(f->path, O_RDWR | O_APPEND | O_CLOEXEC);
    if (f->fd < 0) {
        if (errno == ENOENT) {
            *size = 0U;
            return 0;
        }
        return fail(f, "open", f->path);
    }
    struct stat st;
    if (fstat(f->fd, &st) != 0) {
        return fail(f, "fstat", f->path);
    }
    if ((st.st_size < 0) || ((uint64_t)st.st_size > (uint64_t)UINT32_MAX)) {
        errno = EFBIG;
        return fail(f, "size of", f->path);
    }
    *size = (uint32_t)st.st_size;
    return 0;
}

static int file_read(void* ctx, uint32_t offset, void* buf, uint32_t len)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    uint8_t* p = (uint8_t*)buf;
    while (len > 0U) {
        const ssize_t n = pread(f->fd, p, len, (off_t)offset);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            return fail(f, "read", f->path);
        }
        if (n == 0) {
            errno = EIO;
            return fail(f, "read (the file ended early)", f->path);
        }
        p += n;
        offset += (uint32_t)n;
        len -= (uint32_t)n;
    }
    return 0;
}

static int file_append(void* ctx, const void* data, uint32_t len)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    if (f->fd < 0) {
        errno = ENOENT;
        return fail(f, "append", f->path);
    }
    return (write_all(f->fd, (const uint8_t*)data, len) != 0) ? fail(f, "write", f->path) : 0;
}

static int file_sync(void* ctx)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    return (fsync(f->fd) != 0) ? fail(f, "fsync", f->path) : 0;
}

static int file_truncate(void* ctx, uint32_t size)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    if (ftruncate(f->fd, (off_t)size) != 0) {
        return fail(f, "truncate", f->path);
    }
    return (fsync(f->fd) != 0) ? fail(f, "fsync", f->path) : 0;
}

static int file_replace(void* ctx, const void* data, uint32_t len)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    const int t = open(f->temp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (t < 0) {
        return fail(f, "open", f->temp);
    }
    if ((write_all(t, (const uint8_t*)data, len) != 0) || (fsync(t) != 0)) {
        const int e = errno;
        (void)close(t);
        errno = e;
        return fail(f, "write", f->temp);
    }
    if (close(t) != 0) {
        return fail(f, "close", f->temp);
    }
    if (rename(f->temp, f->path) != 0) {
        return fail(f, "rename", f->temp);
    }
    // The rename is durable once the folder is.
    const int d = open(f->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (d < 0) {
        return fail(f, "open", f->dir);
    }
    if (fsync(d) != 0) {
        const int e = errno;
        (void)close(d);
        errno = e;
        return fail(f, "fsync", f->dir);
    }
    (void)close(d);
    if (f->fd >= 0) {
        (void)close(f->fd);
    }
    f->fd = open(f->path, O_RDWR | O_APPEND | O_CLOEXEC);
    return (f->fd < 0) ? fail(f, "open", f->path) : 0;
}

static void file_close(void* ctx)
{
    sva_journal_file_t* f = (sva_journal_file_t*)ctx;
    if (f->fd >= 0) {
        (void)close(f->fd);
        f->fd = -1;
    }
    if (f->lock_fd >= 0) {
        (void)close(f->lock_fd);  // releases the lock
        f->lock_fd = -1;
    }
}

static const char* file_error(void* ctx)
{
    const sva_journal_file_t* f = (const sva_journal_file_t*)ctx;
    return f->what;
}

static bool name_ok(const char* name)
{
    return (name != NULL) && (name[0] != '\0') && (strlen(name) <= (size_t)SVA_JOURNAL_NAME_MAX);
}

bool sva_journal_file_init(sva_journal_file_t* self, const char* dir, const char* file,
                           const char* temp, const char* lock, sva_journal_storage_t* storage)
{
    if ((self == NULL) || (dir == NULL) || (storage == NULL) || (dir[0] == '\0') ||
        (strlen(dir) > (size_t)SVA_JOURNAL_DIR_MAX) || !name_ok(file) || !name_ok(temp) ||
        !name_ok(lock)) {
        return false;
    }
    memset(self, 0, sizeof(*self));
    self->fd = -1;
    self->lock_fd = -1;
    (void)snprintf(self->dir, sizeof self->dir, "%s", dir);
    (void)snprintf(self->path, sizeof self->path, "%s/%s", dir, file);
    (void)snprintf(self->temp, sizeof self->temp, "%s/%s", dir, temp);
    (void)snprintf(self->lock, sizeof self->lock, "%s/%s", dir, lock);
    (void)snprintf(self->lock_name, sizeof self->lock_name, "%s", lock);
    memset(storage, 0, sizeof(*storage));
    storage->ctx = self;
    storage->open = file_open;
    storage->read = file_read;
    storage->append = file_append;
    storage->sync = file_sync;
    storage->truncate = file_truncate;
    storage->replace = file_replace;
    storage->close = file_close;
    storage->error = file_error;
    return true;
}
