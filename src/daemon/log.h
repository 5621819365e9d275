/* rtedged's stderr lines ("rtedged: ..."), and a limit for lines that a
 * recording, a failing path or the network could repeat without end: at
 * most `burst` lines of one kind per RTED_LOG_WINDOW_NS, then one line
 * saying how many were left out (the status message counts every case).
 * Nothing here allocates: stderr is unbuffered. */
#ifndef RTEDGED_LOG_H
#define RTEDGED_LOG_H

#include <stddef.h>
#include <stdint.h>

#define RTED_LOG_WINDOW_NS 10000000000LL

typedef struct rted_log_limit {
    const char *what; /* e.g. "bad-frame", for the summary line */
    uint32_t burst;   /* lines per window */
    int64_t window_start_ns;
    uint32_t lines;      /* printed in this window */
    uint64_t suppressed; /* left out in this window */
} rted_log_limit;

/* printf into a caller's message buffer (nothing when size is 0). */
void rted_msgf(char *msg, size_t size, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Priorities (syslog's): when stderr is the journal (JOURNAL_STREAM),
 * each line starts with "<N>" so that the journal files it at N. */
enum { RTED_LOG_ERR = 3, RTED_LOG_WARNING = 4, RTED_LOG_INFO = 6, RTED_LOG_DEBUG = 7 };

/* "rtedged: " and the formatted line ("rtedged: warning: " at
 * RTED_LOG_WARNING). */
void rted_log_at(int priority, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
#define rted_log(...) rted_log_at(RTED_LOG_INFO, __VA_ARGS__)
#define rted_warn(...) rted_log_at(RTED_LOG_WARNING, __VA_ARGS__)
#define rted_error(...) rted_log_at(RTED_LOG_ERR, __VA_ARGS__)

/* As rted_log_at, within l's limit. */
void rted_log_limited(rted_log_limit *l, int priority, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Says how many lines l left out, once its window has passed (called with
 * each status message, so that a burst that stopped is still reported). */
void rted_log_flush(rted_log_limit *l, int64_t now_ns);

#endif
