/* The LCM log file format, read and written without liblcm's allocations
 * (internal to rtedge: the publisher writes it, the lcm-log source reads it).
 *
 * An event is: sync word 0xEDA1DA01, event number (int64), timestamp in
 * microseconds (int64), channel length (int32), data length (int32), all
 * big-endian, then the channel name (no NUL) and the data. This is what
 * lcm-logger writes and lcm_eventlog / lcm-logplayer read. */
#ifndef RTEDGE_LCM_LOG_H
#define RTEDGE_LCM_LOG_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/status.h"

#define RTE_LCM_LOG_SYNC 0xEDA1DA01u
#define RTE_LCM_LOG_HEADER_SIZE 28
/* liblcm refuses longer channel names (LCM_MAX_CHANNEL_NAME_LENGTH). */
#define RTE_LCM_LOG_MAX_CHANNEL 63

typedef struct rte_lcm_log_writer {
    int fd;
    int64_t next_event;
} rte_lcm_log_writer;

/* Creates (append = 0: truncates) or appends to the log at path. */
rte_status rte_lcm_log_writer_open(rte_lcm_log_writer *w, const char *path, int append, char *msg,
                                   size_t msg_size);
/* One event, one writev(); no allocation. */
rte_status rte_lcm_log_write(rte_lcm_log_writer *w, int64_t utime, const char *channel,
                             const void *data, size_t size, char *msg, size_t msg_size);
void rte_lcm_log_writer_close(rte_lcm_log_writer *w);

typedef struct rte_lcm_log_event {
    int64_t eventnum;
    int64_t utime;
    char channel[RTE_LCM_LOG_MAX_CHANNEL + 1];
    const uint8_t *data; /* the reader's buffer, until the next read */
    int32_t size;
} rte_lcm_log_event;

typedef struct rte_lcm_log_reader {
    int fd;
    uint8_t *buf; /* max_event_bytes, allocated at open */
    size_t capacity;
    int64_t offset; /* file offset of the next event */
} rte_lcm_log_reader;

/* Opens a log for reading; events whose data exceed max_event_bytes are
 * skipped (RTE_ERR_TOO_LARGE). */
rte_status rte_lcm_log_reader_open(rte_lcm_log_reader *r, const char *path, size_t max_event_bytes,
                                   char *msg, size_t msg_size);
/* The next event. RTE_ERR_END at the end of the file. A damaged event
 * (no sync word, impossible lengths) gives RTE_ERR_CORRUPT and the reader
 * moves on to the next sync word; an event cut short by the end of the file
 * gives RTE_ERR_TRUNCATED (then RTE_ERR_END); one larger than the buffer
 * RTE_ERR_TOO_LARGE (skipped). No allocation. */
rte_status rte_lcm_log_read(rte_lcm_log_reader *r, rte_lcm_log_event *ev, char *msg,
                            size_t msg_size);
/* As rte_lcm_log_read, but an event larger than the buffer is not skipped:
 * its first max_event_bytes are read (ev->size is still the whole event's
 * size; ev->data holds min(size, max_event_bytes) bytes). For looking at
 * headers without a buffer for the largest event. */
rte_status rte_lcm_log_read_head(rte_lcm_log_reader *r, rte_lcm_log_event *ev, char *msg,
                                 size_t msg_size);
void rte_lcm_log_reader_close(rte_lcm_log_reader *r);

#endif
