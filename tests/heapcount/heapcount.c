/* The heap-call counter: see heapcount.h. glibc exports its allocator under
 * __libc_* names, so forwarding needs no dlsym (whose own calloc would
 * recurse into ours). */
#include "heapcount.h"

#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

void *__libc_malloc(size_t size);
void *__libc_calloc(size_t n, size_t size);
void *__libc_realloc(void *p, size_t size);
void __libc_free(void *p);
void *__libc_memalign(size_t alignment, size_t size);

/* The interposed allocator (declared here only to satisfy
 * -Wmissing-prototypes; <stdlib.h> would clash on attributes). */
void *malloc(size_t size);
void *calloc(size_t n, size_t size);
void *realloc(void *p, size_t size);
void free(void *p);
int posix_memalign(void **out, size_t alignment, size_t size);
void *aligned_alloc(size_t alignment, size_t size);
void *memalign(size_t alignment, size_t size);
void *valloc(size_t size);
void *pvalloc(size_t size);

static uint64_t n_malloc, n_calloc, n_realloc, n_free, n_bytes;
/* The calling thread's own counts. initial-exec: the general TLS model may
 * allocate on a thread's first access, which would recurse into malloc. */
static __thread heapcount_counts thread_counts __attribute__((tls_model("initial-exec")));

#define COUNT(var, k) __atomic_fetch_add(&(var), (k), __ATOMIC_RELAXED)
#define COUNT_THREAD(field, k) (thread_counts.field += (k))

void *malloc(size_t size)
{
    COUNT(n_malloc, 1);
    COUNT(n_bytes, size);
    COUNT_THREAD(malloc_calls, 1);
    COUNT_THREAD(bytes, size);
    return __libc_malloc(size);
}

void *calloc(size_t n, size_t size)
{
    COUNT(n_calloc, 1);
    COUNT(n_bytes, n * size);
    COUNT_THREAD(calloc_calls, 1);
    COUNT_THREAD(bytes, n * size);
    return __libc_calloc(n, size);
}

void *realloc(void *p, size_t size)
{
    COUNT(n_realloc, 1);
    COUNT(n_bytes, size);
    COUNT_THREAD(realloc_calls, 1);
    COUNT_THREAD(bytes, size);
    return __libc_realloc(p, size);
}

void free(void *p)
{
    COUNT(n_free, 1);
    COUNT_THREAD(free_calls, 1);
    __libc_free(p);
}

void *memalign(size_t alignment, size_t size)
{
    COUNT(n_malloc, 1);
    COUNT(n_bytes, size);
    COUNT_THREAD(malloc_calls, 1);
    COUNT_THREAD(bytes, size);
    return __libc_memalign(alignment, size);
}

int posix_memalign(void **out, size_t alignment, size_t size)
{
    if (alignment < sizeof(void *) || (alignment & (alignment - 1)) != 0)
        return EINVAL;
    void *p = memalign(alignment, size);
    if (!p)
        return ENOMEM;
    *out = p;
    return 0;
}

void *aligned_alloc(size_t alignment, size_t size) { return memalign(alignment, size); }

void *valloc(size_t size) { return memalign(4096, size); }

void *pvalloc(size_t size) { return memalign(4096, (size + 4095) & ~(size_t)4095); }

#define LOAD(var) __atomic_load_n(&(var), __ATOMIC_RELAXED)
#define CLEAR(var) __atomic_store_n(&(var), 0, __ATOMIC_RELAXED)

void heapcount_get(heapcount_counts *c)
{
    c->malloc_calls = LOAD(n_malloc);
    c->calloc_calls = LOAD(n_calloc);
    c->realloc_calls = LOAD(n_realloc);
    c->free_calls = LOAD(n_free);
    c->bytes = LOAD(n_bytes);
}

void heapcount_get_thread(heapcount_counts *c) { *c = thread_counts; }

void heapcount_reset(void)
{
    thread_counts = (heapcount_counts){0, 0, 0, 0, 0};
    CLEAR(n_malloc);
    CLEAR(n_calloc);
    CLEAR(n_realloc);
    CLEAR(n_free);
    CLEAR(n_bytes);
}

uint64_t heapcount_allocations(const heapcount_counts *c)
{
    return c->malloc_calls + c->calloc_calls + c->realloc_calls;
}

uint64_t heapcount_calls(const heapcount_counts *c)
{
    return heapcount_allocations(c) + c->free_calls;
}

int heapcount_active(void)
{
    uint64_t before = LOAD(n_malloc);
    /* volatile: the compiler may not elide a malloc/free pair it can see */
    void *volatile p = malloc(1);
    free(p);
    return LOAD(n_malloc) != before;
}

/* LD_PRELOAD use: with HEAPCOUNT_REPORT=FILE in the environment, the counts
 * are written to FILE when the process exits (with write(2): stdio would
 * allocate). */
__attribute__((destructor)) static void heapcount_report(void)
{
    const char *path = getenv("HEAPCOUNT_REPORT");
    if (!path || !*path)
        return;
    heapcount_counts c;
    heapcount_get(&c);
    char line[256];
    int n =
        snprintf(line, sizeof line, "malloc %llu calloc %llu realloc %llu free %llu bytes %llu\n",
                 (unsigned long long)c.malloc_calls, (unsigned long long)c.calloc_calls,
                 (unsigned long long)c.realloc_calls, (unsigned long long)c.free_calls,
                 (unsigned long long)c.bytes);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        return;
    if (n > 0 && write(fd, line, (size_t)n) < 0)
        n = 0;
    close(fd);
}
