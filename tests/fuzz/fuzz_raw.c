/* Raw frame dumps: the first three bytes choose the pixel format and a size
 * up to 64x64 (as source.format, width and height would), the rest is the
 * file: whole frames, a last one cut short, a rewind. */
#include "fuzz.h"

#include "rtedge/recorded_source.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const rte_pixel_format formats[] = {RTE_PIXEL_GREY, RTE_PIXEL_BGR24, RTE_PIXEL_RGB24,
                                               RTE_PIXEL_YUYV, RTE_PIXEL_UYVY, RTE_PIXEL_NV12,
                                               (rte_pixel_format)0, (rte_pixel_format)99};
    if (size < 3)
        return 0;
    rte_raw_source_config c = {NULL, formats[data[0] % 8], 1 + data[1] % 64, 1 + data[2] % 64,
                               data[0] & 0x80 ? 0 : 25, data[0] & 0x40 ? 0 : 1};
    char path[64], msg[RTE_SOURCE_MESSAGE_SIZE];
    int fd = fuzz_file(data + 3, size - 3, path, sizeof path);
    c.path = path;
    rte_source src;
    rte_status st = rte_raw_source_open(&src, &c, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (st == RTE_OK) {
        size_t frame_size = rte_frame_packed_size(c.format, c.width, c.height);
        uint64_t good = 0, bad = 0;
        for (int pass = 0; pass < 2; pass++) {
            for (int i = 0; i < 256; i++) {
                rte_source_frame f;
                st = rte_source_next(&src, &f, 0, msg, sizeof msg);
                fuzz_check_message(msg, sizeof msg);
                if (st == RTE_ERR_END)
                    break;
                if (st == RTE_OK) {
                    FUZZ_ASSERT(rte_frame_check(&f.frame) == RTE_OK);
                    good++;
                } else {
                    FUZZ_ASSERT(st == RTE_ERR_TRUNCATED);
                    bad++;
                }
            }
            FUZZ_ASSERT(rte_recorded_source_rewind(&src) == RTE_OK);
        }
        /* Every whole frame was delivered, a cut one counted as bad. */
        size_t whole = (size - 3) / frame_size;
        if (whole < 256)
            FUZZ_ASSERT(good == 2 * whole && bad == ((size - 3) % frame_size ? 2u : 0u));
        rte_source_close(&src);
    } else {
        FUZZ_ASSERT(!src.ops);
    }
    close(fd);
    return 0;
}
