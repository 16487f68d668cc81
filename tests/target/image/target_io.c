// target_io.c -- the C library's system calls in the Cortex-M test images
// (tests/target), over Arm semihosting: Unity's output (UNITY_OUTPUT_CHAR) and the
// tests' printf both reach sva_target_putchar(), which hands whole lines to
// examples/cortex-m/semihost.c (SYS_WRITE0); _exit ends qemu with the status
// (SYS_EXIT_EXTENDED). The heap is a fixed array (SVA_TARGET_HEAP_SIZE), so that a
// runaway allocation fails instead of growing into the stack. Every other call fails
// cleanly: there is no file system and no environment (getenv() finds nothing, so the
// model-based tests run their default seeds, as on the host without SVA_TEST_SEED).
//
// Test images only: firmware keeps to the example's rules (no heap, no stdio).
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/stat.h>

#include "semihost.h"
#include "target.h"

#ifndef SVA_TARGET_HEAP_SIZE
#    define SVA_TARGET_HEAP_SIZE 8192
#endif

// semihost.c keeps a line of at most 511 characters; longer ones are cut here.
#define TARGET_LINE_MAX 500u

static uint32_t pending;  // characters of the current line handed to semihost.c

void sva_target_putchar(int c)
{
    if (c == '\n') {
        sh_end_line();
        pending = 0u;
        return;
    }
    const char s[2] = {(char)c, '\0'};
    if (s[0] == '\0') {
        return;
    }
    sh_put_str(s);
    pending++;
    if (pending == TARGET_LINE_MAX) {
        sh_end_line();
        pending = 0u;
    }
}

void sva_target_flush(void)
{
    if (pending > 0u) {
        sva_target_putchar('\n');
    }
}

static uint8_t heap[SVA_TARGET_HEAP_SIZE] __attribute__((aligned(8)));
static size_t heap_used;

size_t sva_target_heap_used(void)
{
    return heap_used;
}

size_t sva_target_heap_size(void)
{
    return sizeof heap;
}

// The system calls newlib's stdio, malloc, abort and getenv reach. The prototypes are
// newlib's (sys/unistd.h has most of them only under __rtems__ and the like).
int _write(int fd, const char* buf, int len);
int _read(int fd, char* buf, int len);
int _close(int fd);
int _lseek(int fd, int offset, int whence);
int _fstat(int fd, struct stat* st);
int _isatty(int fd);
void* _sbrk(ptrdiff_t increment);
int _kill(int pid, int sig);
int _getpid(void);
void _exit(int status);

int _write(int fd, const char* buf, int len)
{
    if (fd != 1 && fd != 2) {
        errno = EBADF;
        return -1;
    }
    for (int i = 0; i < len; i++) {
        sva_target_putchar((unsigned char)buf[i]);
    }
    return len;
}

int _read(int fd, char* buf, int len)
{
    (void)fd;
    (void)buf;
    (void)len;
    errno = EBADF;
    return -1;
}

int _close(int fd)
{
    (void)fd;
    return 0;
}

int _lseek(int fd, int offset, int whence)
{
    (void)fd;
    (void)offset;
    (void)whence;
    errno = ESPIPE;
    return -1;
}

// stdout and stderr are character devices (a terminal), so stdio buffers them by line.
int _fstat(int fd, struct stat* st)
{
    (void)fd;
    st->st_mode = S_IFCHR;
    return 0;
}

int _isatty(int fd)
{
    return (fd >= 0 && fd <= 2) ? 1 : 0;
}

void* _sbrk(ptrdiff_t increment)
{
    if (increment < 0 || (size_t)increment > sizeof heap - heap_used) {
        errno = ENOMEM;
        return (void*)-1;
    }
    void* block = &heap[heap_used];
    heap_used += (size_t)increment;
    return block;
}

int _kill(int pid, int sig)
{
    (void)pid;
    (void)sig;
    errno = EINVAL;
    return -1;
}

int _getpid(void)
{
    return 1;
}

// abort() (a failed assert) ends here with status 1, after raise() found no handler.
void _exit(int status)
{
    sva_target_flush();
    sh_put_str("sva target: exit ");
    sh_put_int(status);
    sh_end_line();
    sh_exit((uint32_t)status);
}
