#include "rtedge/status.h"

const char *rte_status_message(rte_status status)
{
    switch (status) {
    case RTE_OK: return "success";
    case RTE_ERR_ARGUMENT: return "invalid argument";
    case RTE_ERR_SIZE: return "image sizes or strides do not match";
    case RTE_ERR_NO_MEMORY: return "buffer or arena too small";
    case RTE_ERR_IO: return "input/output error";
    case RTE_ERR_FORMAT: return "not a valid file of this format";
    case RTE_ERR_TRUNCATED: return "data ends early (truncated)";
    case RTE_ERR_UNSUPPORTED: return "unsupported variant";
    case RTE_ERR_TOO_LARGE: return "size exceeds the allowed maximum";
    case RTE_ERR_CORRUPT: return "data is corrupt";
    case RTE_ERR_TIMEOUT: return "timed out";
    case RTE_ERR_END: return "end of stream";
    case RTE_ERR_DEVICE: return "device failed or disappeared";
    }
    return "unknown status";
}
