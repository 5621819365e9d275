/* Error codes shared by every rtedge function. */
#ifndef RTEDGE_STATUS_H
#define RTEDGE_STATUS_H

/* What the shared librtedge exports: the functions and objects declared in
 * include/rtedge carry RTE_API; everything else is hidden (the library is
 * built with -fvisibility=hidden), so internal helpers are not ABI. */
#if defined(__GNUC__) && !defined(RTE_STATIC_ONLY)
#define RTE_API __attribute__((visibility("default")))
#else
#define RTE_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rte_status {
    RTE_OK = 0,
    RTE_ERR_ARGUMENT = 1,    /* a parameter is out of its documented range */
    RTE_ERR_SIZE = 2,        /* image sizes or strides do not fit together */
    RTE_ERR_NO_MEMORY = 3,   /* the caller's arena or buffer is too small */
    RTE_ERR_IO = 4,          /* a read or write failed (errno has the cause) */
    RTE_ERR_FORMAT = 5,      /* the file is not in the format it claims */
    RTE_ERR_TRUNCATED = 6,   /* the data ends before the header says it should */
    RTE_ERR_UNSUPPORTED = 7, /* valid, but a variant rtedge does not handle */
    RTE_ERR_TOO_LARGE = 8,   /* sizes beyond the configured or absolute maxima */
    RTE_ERR_CORRUPT = 9,     /* the data fails its own checks (CRC, markers) */
    RTE_ERR_TIMEOUT = 10,    /* nothing arrived within the time allowed */
    RTE_ERR_END = 11,        /* a recording or stream has no more frames */
    RTE_ERR_DEVICE = 12,     /* a device failed or disappeared (errno has the cause) */
} rte_status;

/* The last code, for tables and tests. */
#define RTE_STATUS_LAST RTE_ERR_DEVICE

/* A short English description of the status, never NULL. */
RTE_API const char *rte_status_message(rte_status status);

#ifdef __cplusplus
}
#endif
#endif
