/* rtedged's stderr lines: see log.h. */
#include "log.h"
#include "core/clock.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

void rted_msgf(char *msg, size_t size, const char *fmt, ...)
{
    if (!size)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
}

/* stderr is the journal's stream when JOURNAL_STREAM names its device and
 * inode (systemd.exec(5)); looked at for each line rather than kept, so
 * that nothing here is global state (lines are few: see the limits). */
static bool stderr_is_journal(void)
{
    const char *v = getenv("JOURNAL_STREAM");
    unsigned long long dev, ino;
    struct stat st;
    return v && sscanf(v, "%llu:%llu", &dev, &ino) == 2 && fstat(2, &st) == 0 &&
           (unsigned long long)st.st_dev == dev && (unsigned long long)st.st_ino == ino;
}

__attribute__((format(printf, 2, 0))) static void vlog(int priority, const char *fmt, va_list ap)
{
    char line[1024];
    vsnprintf(line, sizeof line, fmt, ap);
    const char *what = priority == RTED_LOG_WARNING ? "warning: " : "";
    /* The journal takes the priority from sd-daemon(3)'s "<N>" prefix and
     * stamps the time itself. */
    if (stderr_is_journal())
        fprintf(stderr, "<%d>rtedged: %s%s\n", priority, what, line);
    else
        fprintf(stderr, "rtedged: %s%s\n", what, line);
}

void rted_log_at(int priority, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vlog(priority, fmt, ap);
    va_end(ap);
}

void rted_log_flush(rted_log_limit *l, int64_t now_ns)
{
    if (now_ns - l->window_start_ns < RTED_LOG_WINDOW_NS)
        return;
    if (l->suppressed)
        rted_log_at(RTED_LOG_INFO,
                    "(%llu more %s messages in %lld s left out; status_t counts them)",
                    (unsigned long long)l->suppressed, l->what,
                    (long long)((now_ns - l->window_start_ns) / 1000000000));
    l->window_start_ns = now_ns;
    l->lines = 0;
    l->suppressed = 0;
}

void rted_log_limited(rted_log_limit *l, int priority, const char *fmt, ...)
{
    rted_log_flush(l, rte_clock_now_ns());
    if (l->lines >= l->burst) {
        l->suppressed++;
        return;
    }
    l->lines++;
    va_list ap;
    va_start(ap, fmt);
    vlog(priority, fmt, ap);
    va_end(ap);
}
