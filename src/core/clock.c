#include "core/clock.h"

#include <time.h>

int64_t rte_clock_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int64_t rte_clock_wall_us(int64_t mono_ns)
{
    struct timespec wall, mono;
    clock_gettime(CLOCK_REALTIME, &wall);
    clock_gettime(CLOCK_MONOTONIC, &mono);
    const int64_t now_ns = (int64_t)mono.tv_sec * 1000000000 + mono.tv_nsec;
    return (int64_t)wall.tv_sec * 1000000 + wall.tv_nsec / 1000 - (now_ns - mono_ns) / 1000;
}
