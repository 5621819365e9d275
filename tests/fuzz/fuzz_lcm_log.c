/* LCM logs of image_t: the lcm-log source (event headers, sync words,
 * lengths, events cut short, image_t headers, strides, sizes and times).
 * The first byte chooses how the source is configured: sized (a format and
 * a 64x64 maximum) or not (the first image_t found decides), a channel or
 * every channel; the rest is the log. */
#include "fuzz_source.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const rte_pixel_format formats[] = {RTE_PIXEL_GREY, RTE_PIXEL_BGR24, RTE_PIXEL_NV12,
                                               RTE_PIXEL_YUYV};
    if (size < 1)
        return 0;
    char path[64], msg[RTE_SOURCE_MESSAGE_SIZE];
    int fd = fuzz_file(data + 1, size - 1, path, sizeof path);
    bool sized = data[0] & 1;
    rte_lcm_source_config c = {path, data[0] & 2 ? "CAMERA" : NULL,
                               sized ? formats[(data[0] >> 2) % 4] : (rte_pixel_format)0,
                               sized ? 64 : 0, sized ? 64 : 0};
    rte_source src;
    rte_status st = rte_lcm_log_source_open(&src, &c, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (st == RTE_OK) {
        FUZZ_ASSERT(src.max_width >= 1 && src.max_height >= 1);
        fuzz_passes passes;
        fuzz_read_passes(&src, 64, &passes);
        rte_source_close(&src);
    } else {
        FUZZ_ASSERT(!src.ops);
    }
    close(fd);
    return 0;
}
