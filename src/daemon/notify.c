/* sd_notify's datagram protocol: see notify.h. */
#define _GNU_SOURCE
#include "notify.h"

#include <errno.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "log.h"

/* A decimal number of at most 19 digits, nothing else. */
static bool parse_u64(const char *s, uint64_t *v)
{
    if (!s || !*s || strlen(s) > 19)
        return false;
    uint64_t x = 0;
    for (; *s; s++) {
        if (*s < '0' || *s > '9')
            return false;
        x = x * 10 + (uint64_t)(*s - '0');
    }
    *v = x;
    return true;
}

/* WATCHDOG_USEC, when WATCHDOG_PID is unset or ours: ping at half of it. */
static void watchdog_period(rted_notify *n)
{
    uint64_t usec, pid;
    const char *p = getenv("WATCHDOG_PID");
    if (p && (!parse_u64(p, &pid) || pid != (uint64_t)getpid()))
        return;
    if (!parse_u64(getenv("WATCHDOG_USEC"), &usec) || usec == 0 || usec > INT64_MAX / 1000)
        return;
    n->ping_every_ns = (int64_t)usec * 1000 / 2;
}

bool rted_notify_open(rted_notify *n, char *msg, size_t msg_size)
{
    memset(n, 0, sizeof *n);
    n->fd = -1;
    const char *path = getenv("NOTIFY_SOCKET");
    if (!path || !*path)
        return true;
    size_t len = strlen(path);
    if ((path[0] != '/' && path[0] != '@') || len >= sizeof n->addr.sun_path || len < 2) {
        rted_msgf(msg, msg_size, "NOTIFY_SOCKET=%s: not a socket path or @abstract address", path);
        return false;
    }
    n->addr.sun_family = AF_UNIX;
    memcpy(n->addr.sun_path, path, len);
    if (path[0] == '@')
        n->addr.sun_path[0] = 0; /* abstract: no terminating NUL in the length */
    n->addr_len = (socklen_t)(offsetof(struct sockaddr_un, sun_path) + len);
    /* Non-blocking: a full socket drops a message rather than the frame loop waiting. */
    n->fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (n->fd < 0) {
        rted_msgf(msg, msg_size, "NOTIFY_SOCKET: socket: %s", strerror(errno));
        return false;
    }
    watchdog_period(n);
    return true;
}

void rted_notify_close(rted_notify *n)
{
    if (n->fd >= 0)
        close(n->fd);
    n->fd = -1;
}

static void send_text(rted_notify *n, const char *text, size_t len)
{
    ssize_t r;
    do
        r = sendto(n->fd, text, len, MSG_NOSIGNAL, (const struct sockaddr *)&n->addr, n->addr_len);
    while (r < 0 && errno == EINTR);
    if (r == (ssize_t)len)
        n->sent++;
    else
        n->failed++;
}

void rted_notify_send(rted_notify *n, const char *text)
{
    if (n->fd >= 0)
        send_text(n, text, strlen(text));
}

void rted_notify_status(rted_notify *n, const char *head, const char *fmt, ...)
{
    if (n->fd < 0)
        return;
    char text[320];
    int k = snprintf(text, 96, "%s%sSTATUS=", head ? head : "", head ? "\n" : "");
    if (k < 0 || k >= 96)
        return;
    va_list ap;
    va_start(ap, fmt);
    int m = vsnprintf(text + k, 201, fmt, ap);
    va_end(ap);
    if (m < 0)
        return;
    send_text(n, text, strlen(text));
}

void rted_notify_watchdog(rted_notify *n, int64_t now_ns)
{
    if (n->fd < 0 || !n->ping_every_ns || now_ns < n->next_ping_ns)
        return;
    send_text(n, "WATCHDOG=1", 10);
    n->next_ping_ns = now_ns + n->ping_every_ns;
}
