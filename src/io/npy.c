/* NumPy .npy writer, format version 1.0: magic, a little-endian 16-bit
 * header length, a Python dict literal padded with spaces and a newline so
 * the pixel data starts at a multiple of 64 bytes, then the elements in C
 * order. Elements are written little-endian whatever the host. */
#include <stdio.h>
#include <string.h>

#include "io_internal.h"

rte_status npy_write(FILE *f, const io_msg *m, const void *buf, size_t stride_bytes, int32_t w,
                     int32_t h, int channels, const char *dtype, size_t elem_size)
{
    char header[256];
    int n = channels == 3
                ? snprintf(header + 10, sizeof header - 10,
                           "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d, 3), }", dtype,
                           (int)h, (int)w)
                : snprintf(header + 10, sizeof header - 10,
                           "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d), }", dtype,
                           (int)h, (int)w);
    size_t total = 10 + (size_t)n + 1; /* magic + version + length, dict, '\n' */
    size_t padded = (total + 63) / 64 * 64;
    memcpy(header, "\x93NUMPY\x01\x00", 8);
    size_t dict_len = padded - 10;
    header[8] = (char)(dict_len & 0xFF);
    header[9] = (char)(dict_len >> 8);
    memset(header + 10 + n, ' ', padded - total);
    header[padded - 1] = '\n';
    if (fwrite(header, 1, padded, f) != padded)
        return io_fail_errno(m, RTE_ERR_IO, "cannot write");

    size_t row_elems = (size_t)w * (size_t)channels;
    uint8_t chunk[4096];
    size_t per_chunk = sizeof chunk / elem_size;
    for (int32_t y = 0; y < h; y++) {
        const uint8_t *row = (const uint8_t *)buf + (size_t)y * stride_bytes;
        for (size_t i0 = 0; i0 < row_elems; i0 += per_chunk) {
            size_t cnt = row_elems - i0 < per_chunk ? row_elems - i0 : per_chunk;
            if (elem_size == 1) {
                memcpy(chunk, row + i0, cnt);
            } else {
                const int16_t *s = (const int16_t *)(const void *)row + i0;
                for (size_t i = 0; i < cnt; i++) {
                    uint16_t v = (uint16_t)s[i];
                    chunk[2 * i] = (uint8_t)(v & 0xFF);
                    chunk[2 * i + 1] = (uint8_t)(v >> 8);
                }
            }
            if (fwrite(chunk, elem_size, cnt, f) != cnt)
                return io_fail_errno(m, RTE_ERR_IO, "cannot write");
        }
    }
    return RTE_OK;
}
