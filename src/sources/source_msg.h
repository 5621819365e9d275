/* Writing the sources' messages (internal to src/sources). */
#ifndef RTEDGE_SOURCE_MSG_H
#define RTEDGE_SOURCE_MSG_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* printf into msg (nothing when msg is NULL or size 0). */
void rte_source_msgf(char *msg, size_t size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* printf after what msg already holds. */
void rte_source_msg_append(char *msg, size_t size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#ifdef __cplusplus
}
#endif
#endif
