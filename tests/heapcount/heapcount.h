/* heapcount: counts the process's heap calls, to prove that code makes none
 * (the daemon's "no heap calls after the first frame" test, the publisher's
 * tests).
 *
 * The library defines malloc, calloc, realloc, free, posix_memalign,
 * aligned_alloc, memalign, valloc and pvalloc, counts each call and forwards
 * it to glibc's own allocator (__libc_*), so it interposes whether it is
 * linked into a program (listed before libc, as every shared library is) or
 * preloaded with LD_PRELOAD into one that is not. Under a sanitizer the
 * sanitizer's allocator comes first and nothing is counted:
 * heapcount_active() tells, so tests can skip. Counting is process-wide and
 * atomic (other threads' calls count too).
 *
 * Preloaded into a program that does not call this API, it reports at exit:
 *   LD_PRELOAD=libheapcount.so HEAPCOUNT_REPORT=counts.txt program ...
 * writes "malloc N calloc N realloc N free N bytes N" to counts.txt. */
#ifndef RTEDGE_HEAPCOUNT_H
#define RTEDGE_HEAPCOUNT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct heapcount_counts {
    uint64_t malloc_calls; /* malloc, and the aligned allocators */
    uint64_t calloc_calls;
    uint64_t realloc_calls;
    uint64_t free_calls; /* free(NULL) included: it is still a call */
    uint64_t bytes;      /* requested by malloc/calloc/realloc/aligned */
} heapcount_counts;

/* The process's counts since the last reset. */
void heapcount_get(heapcount_counts *counts);
/* The calling thread's counts since its last reset (other threads, such as
 * liblcm's receive thread, excluded). */
void heapcount_get_thread(heapcount_counts *counts);
/* Resets the process's counts and the calling thread's. */
void heapcount_reset(void);
/* Allocating calls: malloc + calloc + realloc (+ aligned); free excluded. */
uint64_t heapcount_allocations(const heapcount_counts *counts);
/* Every call, free included. */
uint64_t heapcount_calls(const heapcount_counts *counts);
/* 1 when this library's malloc is the one the process uses (checked by
 * making a call and watching the counter). */
int heapcount_active(void);

#ifdef __cplusplus
}
#endif
#endif
