/* The heap-call counter counts every kind of call, and nothing else. */
#include <malloc.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "heapcount.h"

/* Opaque to the optimiser, so no call below is elided or merged. */
static void *volatile sink;

static void test_counts_each_call(void **state)
{
    (void)state;
    if (!heapcount_active()) {
        print_message("heapcount is not interposed (sanitizer build?)\n");
        skip();
    }
    heapcount_counts c;
    heapcount_reset();
    heapcount_get(&c);
    assert_int_equal(heapcount_calls(&c), 0);

    sink = malloc(100);
    free(sink);
    sink = calloc(3, 10);
    sink = realloc(sink, 200);
    free(sink);
    void *p = NULL;
    assert_int_equal(posix_memalign(&p, 64, 128), 0);
    assert_int_equal((uintptr_t)p % 64, 0);
    free(p);
    sink = aligned_alloc(32, 64);
    free(sink);
    sink = memalign(16, 48);
    free(sink);
    sink = NULL;
    free(sink); /* free(NULL) is a call too */
    heapcount_get(&c);
    assert_int_equal(c.malloc_calls, 4);
    assert_int_equal(c.calloc_calls, 1);
    assert_int_equal(c.realloc_calls, 1);
    assert_int_equal(c.free_calls, 6);
    assert_int_equal(c.bytes, 100 + 30 + 200 + 128 + 64 + 48);
    assert_int_equal(heapcount_allocations(&c), 6);
    assert_int_equal(heapcount_calls(&c), 12);

    /* Code that does not touch the heap counts nothing; strdup does. */
    heapcount_reset();
    char buf[64];
    snprintf(buf, sizeof buf, "%d", 42);
    memset(buf, 0, sizeof buf);
    heapcount_get(&c);
    assert_int_equal(heapcount_calls(&c), 0);
    sink = strdup("x");
    free(sink);
    heapcount_get(&c);
    assert_int_equal(heapcount_allocations(&c), 1);
    assert_int_equal(posix_memalign(&p, 3, 8), 22 /* EINVAL */);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts_each_call),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
