/* LCM logs of image_t: the lcm-log source (event headers, sync words,
 * lengths, events cut short, image_t headers, strides and sizes). The
 * first byte chooses how the source is configured: sized (a format and a
 * 64x64 maximum) or not (the first image_t found decides), a channel or
 * every channel; the rest is the log. */
#include "fuzz.h"

#include "rtedge/recorded_source.h"

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
        for (int pass = 0; pass < 2; pass++) {
            for (int i = 0; i < 64; i++) {
                rte_source_frame f;
                st = rte_source_next(&src, &f, 0, msg, sizeof msg);
                fuzz_check_message(msg, sizeof msg);
                if (st == RTE_ERR_END)
                    break;
                if (st == RTE_OK) {
                    FUZZ_ASSERT(rte_frame_check(&f.frame) == RTE_OK);
                    FUZZ_ASSERT(f.frame.width <= src.max_width && f.frame.height <= src.max_height);
                    FUZZ_ASSERT(f.frame.format == src.format);
                    /* Every pixel lies in what was read (ASan): the last byte
                     * of each plane's last row. */
                    const rte_frame *fr = &f.frame;
                    rte_frame packed;
                    uint8_t probe;
                    FUZZ_ASSERT(rte_frame_packed(&packed, fr->format, fr->width, 1, &probe,
                                                 SIZE_MAX) == RTE_OK);
                    for (int p = 0; p < RTE_FRAME_MAX_PLANES && fr->plane[p]; p++) {
                        int32_t rows = p ? (fr->height + 1) / 2 : fr->height;
                        size_t at = (size_t)(rows - 1) * (size_t)fr->stride[p] +
                                    (size_t)packed.stride[p] - 1;
                        volatile uint8_t last = fr->plane[p][at];
                        (void)last;
                    }
                }
            }
            FUZZ_ASSERT(rte_recorded_source_rewind(&src) == RTE_OK);
        }
        rte_source_close(&src);
    } else {
        FUZZ_ASSERT(!src.ops);
    }
    close(fd);
    return 0;
}
