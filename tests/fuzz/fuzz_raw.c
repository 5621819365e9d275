/* Raw frame dumps: the first three bytes choose the pixel format and a size
 * up to 64x64 (as source.format, width and height would), the rest is the
 * file: whole frames, a last one cut short, a rewind. */
#include "fuzz_source.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const rte_pixel_format formats[] = {
        RTE_PIXEL_GREY, RTE_PIXEL_BGR24, RTE_PIXEL_RGB24,     RTE_PIXEL_YUYV,
        RTE_PIXEL_UYVY, RTE_PIXEL_NV12,  (rte_pixel_format)0, (rte_pixel_format)99};
    if (size < 3)
        return 0;
    rte_raw_source_config c = {NULL,
                               formats[data[0] % 8],
                               1 + data[1] % 64,
                               1 + data[2] % 64,
                               data[0] & 0x80 ? 0 : 25,
                               data[0] & 0x40 ? 0 : 1};
    char path[64], msg[RTE_SOURCE_MESSAGE_SIZE];
    int fd = fuzz_file(data + 3, size - 3, path, sizeof path);
    c.path = path;
    rte_source src;
    rte_status st = rte_raw_source_open(&src, &c, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (st == RTE_OK) {
        fuzz_passes passes;
        fuzz_read_passes(&src, 256, &passes);
        /* Every whole frame delivered, in each pass; a cut one refused as such. */
        size_t frame_size = rte_frame_packed_size(c.format, c.width, c.height);
        size_t whole = (size - 3) / frame_size, cut = (size - 3) % frame_size ? 1 : 0;
        if (!passes.capped[0] && !passes.capped[1])
            for (int pass = 0; pass < 2; pass++)
                FUZZ_ASSERT(passes.good[pass] == whole && passes.bad[pass] == cut);
        FUZZ_ASSERT(!passes.bad_kinds || passes.bad_kinds == 1u << RTE_ERR_TRUNCATED);
        rte_source_close(&src);
    } else {
        FUZZ_ASSERT(!src.ops);
    }
    close(fd);
    return 0;
}
