#include "source_msg.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void rte_source_msgf(char *msg, size_t size, const char *fmt, ...)
{
    if (!msg || size == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, size, fmt, ap);
    va_end(ap);
}

void rte_source_msg_append(char *msg, size_t size, const char *fmt, ...)
{
    if (!msg || size == 0)
        return;
    size_t len = strnlen(msg, size);
    if (len + 1 >= size)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg + len, size - len, fmt, ap);
    va_end(ap);
}
