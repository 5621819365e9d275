/* LCM log files: see lcm_log.h. */
#include "lcm_log.h"
#include "lcm_wire.h"

#include "sources/source_msg.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>

/* ---- writing ---- */

rte_status rte_lcm_log_writer_open(rte_lcm_log_writer *w, const char *path, int append, char *msg,
                                   size_t msg_size)
{
    w->fd = -1;
    w->next_event = 0;
    int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC);
    w->fd = open(path, flags, 0644);
    if (w->fd < 0) {
        rte_source_msgf(msg, msg_size, "%s: %s", path, strerror(errno));
        return RTE_ERR_IO;
    }
    rte_source_msgf(msg, msg_size, "%s", "");
    return RTE_OK;
}

rte_status rte_lcm_log_write(rte_lcm_log_writer *w, int64_t utime, const char *channel,
                             const void *data, size_t size, char *msg, size_t msg_size)
{
    size_t channel_len = strlen(channel);
    if (channel_len == 0 || channel_len > RTE_LCM_LOG_MAX_CHANNEL || size > INT32_MAX) {
        rte_source_msgf(msg, msg_size, "log event: channel of %zu bytes or data of %zu bytes",
                        channel_len, size);
        return RTE_ERR_ARGUMENT;
    }
    uint8_t header[RTE_LCM_LOG_HEADER_SIZE];
    rte_lcm_put_u32(header, RTE_LCM_LOG_SYNC);
    rte_lcm_put_u64(header + 4, (uint64_t)w->next_event);
    rte_lcm_put_u64(header + 12, (uint64_t)utime);
    rte_lcm_put_u32(header + 20, (uint32_t)channel_len);
    rte_lcm_put_u32(header + 24, (uint32_t)size);
    struct iovec iov[3] = {
        {header, sizeof header},
        {(void *)(uintptr_t)channel, channel_len},
        {(void *)(uintptr_t)data, size},
    };
    size_t total = sizeof header + channel_len + size;
    /* A short write to a regular file means the disk is full: finish it, so
     * the log stays readable up to here. */
    size_t done = 0;
    int i = 0;
    while (done < total) {
        ssize_t n = writev(w->fd, iov + i, 3 - i);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            rte_source_msgf(msg, msg_size, "log write: %s", strerror(errno));
            return RTE_ERR_IO;
        }
        done += (size_t)n;
        while (i < 3 && (size_t)n >= iov[i].iov_len) {
            n -= (ssize_t)iov[i].iov_len;
            i++;
        }
        if (i < 3) {
            iov[i].iov_base = (uint8_t *)iov[i].iov_base + n;
            iov[i].iov_len -= (size_t)n;
        }
    }
    w->next_event++;
    rte_source_msgf(msg, msg_size, "%s", "");
    return RTE_OK;
}

void rte_lcm_log_writer_close(rte_lcm_log_writer *w)
{
    if (w->fd >= 0)
        close(w->fd);
    w->fd = -1;
}

/* ---- reading ---- */

rte_status rte_lcm_log_reader_open(rte_lcm_log_reader *r, const char *path, size_t max_event_bytes,
                                   char *msg, size_t msg_size)
{
    memset(r, 0, sizeof *r);
    r->fd = -1;
    if (max_event_bytes == 0 || max_event_bytes > INT32_MAX) {
        rte_source_msgf(msg, msg_size, "%s: bad maximum event size %zu", path, max_event_bytes);
        return RTE_ERR_ARGUMENT;
    }
    r->buf = malloc(max_event_bytes);
    if (!r->buf) {
        rte_source_msgf(msg, msg_size, "%s: no memory for %zu bytes", path, max_event_bytes);
        return RTE_ERR_NO_MEMORY;
    }
    r->capacity = max_event_bytes;
    r->fd = open(path, O_RDONLY | O_CLOEXEC);
    if (r->fd < 0) {
        rte_source_msgf(msg, msg_size, "%s: %s", path, strerror(errno));
        free(r->buf);
        r->buf = NULL;
        return RTE_ERR_IO;
    }
    rte_source_msgf(msg, msg_size, "%s", "");
    return RTE_OK;
}

/* Reads exactly n bytes at off; returns the count read (short at EOF), -1
 * on an error. */
static ssize_t read_at(int fd, void *buf, size_t n, int64_t off)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = pread(fd, (uint8_t *)buf + got, n - got, (off_t)(off + (int64_t)got));
        if (k < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        if (k == 0)
            break;
        got += (size_t)k;
    }
    return (ssize_t)got;
}

/* The offset of the next sync word after `from`, or -1 at the end. */
static int64_t find_sync(int fd, int64_t from)
{
    uint8_t chunk[4096];
    for (int64_t off = from;;) {
        ssize_t n = read_at(fd, chunk, sizeof chunk, off);
        if (n < 4)
            return -1;
        for (ssize_t i = 0; i + 4 <= n; i++)
            if (rte_lcm_get_u32(chunk + i) == RTE_LCM_LOG_SYNC)
                return off + i;
        off += n - 3;
    }
}

/* Where to go on after a damaged event at `at`: the next sync word, or
 * the end of the file. */
static int64_t resync(int fd, int64_t at)
{
    int64_t next = find_sync(fd, at + 1);
    return next >= 0 ? next : (int64_t)lseek(fd, 0, SEEK_END);
}

static rte_status read_event(rte_lcm_log_reader *r, rte_lcm_log_event *ev, int head_only, char *msg,
                             size_t msg_size)
{
    uint8_t h[RTE_LCM_LOG_HEADER_SIZE];
    ssize_t n = read_at(r->fd, h, sizeof h, r->offset);
    if (n < 0) {
        rte_source_msgf(msg, msg_size, "log read: %s", strerror(errno));
        return RTE_ERR_IO;
    }
    if (n == 0) {
        rte_source_msgf(msg, msg_size, "end of log");
        return RTE_ERR_END;
    }
    int64_t at = r->offset;
    if (n >= 4 && rte_lcm_get_u32(h) != RTE_LCM_LOG_SYNC) {
        r->offset = resync(r->fd, at);
        rte_source_msgf(msg, msg_size, "log offset %lld: no sync word, skipped to %lld",
                        (long long)at, (long long)r->offset);
        return RTE_ERR_CORRUPT;
    }
    if (n < (ssize_t)sizeof h) {
        r->offset = at + n;
        rte_source_msgf(msg, msg_size, "log offset %lld: event header cut short", (long long)at);
        return RTE_ERR_TRUNCATED;
    }
    uint32_t channel_len = rte_lcm_get_u32(h + 20), size = rte_lcm_get_u32(h + 24);
    if (channel_len == 0 || channel_len > RTE_LCM_LOG_MAX_CHANNEL || size > INT32_MAX) {
        r->offset = resync(r->fd, at);
        rte_source_msgf(msg, msg_size, "log offset %lld: impossible lengths (channel %u, data %u)",
                        (long long)at, channel_len, size);
        return RTE_ERR_CORRUPT;
    }
    int64_t end = at + (int64_t)sizeof h + channel_len + size;
    n = read_at(r->fd, ev->channel, channel_len, at + (int64_t)sizeof h);
    if (n != (ssize_t)channel_len) {
        r->offset = (int64_t)lseek(r->fd, 0, SEEK_END);
        rte_source_msgf(msg, msg_size, "log offset %lld: event cut short", (long long)at);
        return n < 0 ? RTE_ERR_IO : RTE_ERR_TRUNCATED;
    }
    ev->channel[channel_len] = '\0';
    ev->eventnum = (int64_t)rte_lcm_get_u64(h + 4);
    ev->utime = (int64_t)rte_lcm_get_u64(h + 12);
    if (size > r->capacity) {
        /* Skip it (or read its head), but only if it is all there. */
        uint8_t last;
        if (read_at(r->fd, &last, 1, end - 1) != 1) {
            r->offset = (int64_t)lseek(r->fd, 0, SEEK_END);
            rte_source_msgf(msg, msg_size, "log offset %lld: event cut short", (long long)at);
            return RTE_ERR_TRUNCATED;
        }
        if (!head_only) {
            r->offset = end;
            rte_source_msgf(msg, msg_size, "log event %lld on %s: %u bytes, more than %zu",
                            (long long)ev->eventnum, ev->channel, size, r->capacity);
            return RTE_ERR_TOO_LARGE;
        }
    }
    size_t want = size < r->capacity ? size : r->capacity;
    n = read_at(r->fd, r->buf, want, at + (int64_t)sizeof h + channel_len);
    if (n != (ssize_t)want) {
        r->offset = (int64_t)lseek(r->fd, 0, SEEK_END);
        rte_source_msgf(msg, msg_size, "log event %lld on %s: data cut short (%zd of %u bytes)",
                        (long long)ev->eventnum, ev->channel, n, size);
        return n < 0 ? RTE_ERR_IO : RTE_ERR_TRUNCATED;
    }
    r->offset = end;
    ev->data = r->buf;
    ev->size = (int32_t)size;
    rte_source_msgf(msg, msg_size, "%s", "");
    return RTE_OK;
}

rte_status rte_lcm_log_read(rte_lcm_log_reader *r, rte_lcm_log_event *ev, char *msg,
                            size_t msg_size)
{
    return read_event(r, ev, 0, msg, msg_size);
}

rte_status rte_lcm_log_read_head(rte_lcm_log_reader *r, rte_lcm_log_event *ev, char *msg,
                                 size_t msg_size)
{
    return read_event(r, ev, 1, msg, msg_size);
}

void rte_lcm_log_reader_close(rte_lcm_log_reader *r)
{
    if (r->fd >= 0)
        close(r->fd);
    free(r->buf);
    memset(r, 0, sizeof *r);
    r->fd = -1;
}
