/* systemd's readiness protocol (sd_notify(3)) spoken by hand: READY=1,
 * STATUS=, WATCHDOG=1, RELOADING=1, STOPPING=1 as datagrams to the
 * AF_UNIX socket named by NOTIFY_SOCKET.
 *
 * Not libsystemd: the watchdog pings go out from the per-frame loop, and
 * sd_notify() opens a socket and builds its message on every call; here
 * the address is parsed and one socket opened once at start, and a
 * message is a sendto() of a caller's buffer, with no heap call (the
 * daemon suite counts them). Without NOTIFY_SOCKET every call is a no-op. */
#ifndef RTEDGED_NOTIFY_H
#define RTEDGED_NOTIFY_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/socket.h>
#include <sys/un.h>

typedef struct rted_notify {
    int fd; /* -1: no NOTIFY_SOCKET (or it could not be used): nothing is sent */
    struct sockaddr_un addr;
    socklen_t addr_len;
    int64_t ping_every_ns; /* half of WATCHDOG_USEC; 0: no watchdog for this process */
    int64_t next_ping_ns;
    uint64_t sent, failed; /* datagrams sent, and not sent (a full socket, ...) */
} rted_notify;

/* Reads NOTIFY_SOCKET (a path, or '@' for an abstract address),
 * WATCHDOG_USEC and WATCHDOG_PID (the watchdog is this process's only when
 * it is unset or our pid) and opens the socket. false and *msg when the
 * variable is set but unusable (the notifier is then off). */
bool rted_notify_open(rted_notify *n, char *msg, size_t msg_size);
void rted_notify_close(rted_notify *n);
/* Sends one message: "READY=1", "STOPPING=1", several lines. */
void rted_notify_send(rted_notify *n, const char *text);
/* "STATUS=" and the formatted text (cut at 200 bytes), in one datagram
 * with the lines of `head` before it ("READY=1", or NULL). */
void rted_notify_status(rted_notify *n, const char *head, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* WATCHDOG=1 when half the watchdog period has passed since the last one.
 * Called from the frame loop only, so that a stalled loop stops the pings. */
void rted_notify_watchdog(rted_notify *n, int64_t now_ns);
static inline bool rted_notify_on(const rted_notify *n) { return n->fd >= 0; }

#endif
