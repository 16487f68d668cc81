// Heap allocation counter for a whole process, loaded with LD_PRELOAD (test_netns.py
// runs build/bin/sva_node under it). It replaces the malloc family, forwards to glibc's
// allocator and counts every call in a shared file the test reads while the process runs:
//
//   SVA_ALLOC_COUNT_FILE=/tmp/x LD_PRELOAD=build/tests/lcm/libsva_alloc_count.so sva_node ...
//
// The file (made by this library, sizeof(sva_alloc_shared_t) bytes, see the layout below)
// holds one counter per function, the bytes requested, and a ring of the last
// SVA_ALLOC_RING calls: function, size, thread and the caller's return address, so a
// test can name what allocates (resolve the address with /proc/PID/maps + addr2line).
// free() is not counted: only new allocations matter for "zero per message".
//
// DEVIATION(C99, no extensions): interposing glibc's allocator needs glibc's __libc_*
// entry points, a constructor, GCC atomics and __builtin_return_address; this is test
// instrumentation for Linux/glibc only and never part of the node.
#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

extern void* __libc_malloc(size_t size);
extern void* __libc_calloc(size_t n, size_t size);
extern void* __libc_realloc(void* p, size_t size);
extern void* __libc_memalign(size_t align, size_t size);

#define SVA_ALLOC_MAGIC 0x5356414c4c4f4331ULL  // "SVALLOC1"
#define SVA_ALLOC_RING  256

enum { K_MALLOC, K_CALLOC, K_REALLOC, K_MEMALIGN, K_COUNT };

typedef struct {
    uint64_t kind;    // K_*
    uint64_t size;    // bytes requested
    uint64_t tid;     // Linux thread id
    uint64_t caller;  // return address in the caller of the allocation function
} sva_alloc_event_t;

// Layout read by tests/lcm/test_netns.py (little-endian uint64 fields, in order).
typedef struct {
    uint64_t magic;
    uint64_t calls[K_COUNT];  // malloc, calloc, realloc, memalign family
    uint64_t bytes;
    uint64_t seq;  // total calls; event i is ring[i % SVA_ALLOC_RING]
    sva_alloc_event_t ring[SVA_ALLOC_RING];
} sva_alloc_shared_t;

static sva_alloc_shared_t* shared = NULL;

__attribute__((constructor)) static void sva_alloc_open(void)
{
    const char* path = getenv("SVA_ALLOC_COUNT_FILE");
    if (path == NULL) {
        return;
    }
    const int fd = open(path, O_RDWR | O_CREAT | O_TRUNC, 0600);
    if (fd < 0) {
        return;
    }
    if (ftruncate(fd, (off_t)sizeof(sva_alloc_shared_t)) == 0) {
        void* m = mmap(NULL, sizeof(sva_alloc_shared_t), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        if (m != MAP_FAILED) {
            shared = (sva_alloc_shared_t*)m;
            __atomic_store_n(&shared->magic, SVA_ALLOC_MAGIC, __ATOMIC_RELEASE);
        }
    }
    (void)close(fd);
}

static void record(int kind, size_t size, void* caller)
{
    sva_alloc_shared_t* s = shared;
    if (s == NULL) {
        return;
    }
    __atomic_fetch_add(&s->calls[kind], 1, __ATOMIC_RELAXED);
    __atomic_fetch_add(&s->bytes, (uint64_t)size, __ATOMIC_RELAXED);
    const uint64_t i = __atomic_fetch_add(&s->seq, 1, __ATOMIC_ACQ_REL) % SVA_ALLOC_RING;
    s->ring[i].kind = (uint64_t)kind;
    s->ring[i].size = (uint64_t)size;
    s->ring[i].tid = (uint64_t)syscall(SYS_gettid);
    s->ring[i].caller = (uint64_t)(uintptr_t)caller;
}

void* malloc(size_t size)
{
    record(K_MALLOC, size, __builtin_return_address(0));
    return __libc_malloc(size);
}

void* calloc(size_t n, size_t size)
{
    record(K_CALLOC, n * size, __builtin_return_address(0));
    return __libc_calloc(n, size);
}

void* realloc(void* p, size_t size)
{
    record(K_REALLOC, size, __builtin_return_address(0));
    return __libc_realloc(p, size);
}

void* memalign(size_t align, size_t size)
{
    record(K_MEMALIGN, size, __builtin_return_address(0));
    return __libc_memalign(align, size);
}

void* aligned_alloc(size_t align, size_t size)
{
    record(K_MEMALIGN, size, __builtin_return_address(0));
    return __libc_memalign(align, size);
}

int posix_memalign(void** out, size_t align, size_t size)
{
    record(K_MEMALIGN, size, __builtin_return_address(0));
    void* p = __libc_memalign(align, size);
    if (p == NULL) {
        return ENOMEM;
    }
    *out = p;
    return 0;
}
