/* rtedged's stderr lines: see log.h. */
#include "log.h"
#include "core/clock.h"

#include <stdarg.h>
#include <stdio.h>
#include <time.h>

void rted_msgf(char *msg, size_t size, const char *fmt, ...)
{
    if (!size)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
}

__attribute__((format(printf, 1, 0))) static void vlog(const char *fmt, va_list ap)
{
    char line[1024];
    vsnprintf(line, sizeof line, fmt, ap);
    fprintf(stderr, "rtedged: %s\n", line);
}

void rted_log(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
}

void rted_log_flush(rted_log_limit *l, int64_t now_ns)
{
    if (now_ns - l->window_start_ns < RTED_LOG_WINDOW_NS)
        return;
    if (l->suppressed)
        rted_log("(%llu more %s messages in %lld s left out; status_t counts them)",
                 (unsigned long long)l->suppressed, l->what,
                 (long long)((now_ns - l->window_start_ns) / 1000000000));
    l->window_start_ns = now_ns;
    l->lines = 0;
    l->suppressed = 0;
}

void rted_log_limited(rted_log_limit *l, const char *fmt, ...)
{
    rted_log_flush(l, rte_clock_now_ns());
    if (l->lines >= l->burst) {
        l->suppressed++;
        return;
    }
    l->lines++;
    va_list ap;
    va_start(ap, fmt);
    vlog(fmt, ap);
    va_end(ap);
}
