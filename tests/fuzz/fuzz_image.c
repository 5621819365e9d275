/* The image readers (rtedge_io: PGM/PPM, PNG through libspng, JPEG through
 * libjpeg-turbo, chosen by content): probe, then decode into a reader sized
 * for FUZZ_MAX x FUZZ_MAX, as grey, BGR and interleaved. A header that
 * declares more is refused before anything large is allocated. */
#include "fuzz.h"

#include "rtedge/imageio.h"

#define FUZZ_MAX 256

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static rte_image_reader *reader;
    static uint8_t pixels[FUZZ_MAX * FUZZ_MAX * 3];
    if (!reader && !(reader = rte_image_reader_create(FUZZ_MAX, FUZZ_MAX)))
        abort();
    char path[64], msg[RTE_IO_MESSAGE_SIZE];
    int fd = fuzz_file(data, size, path, sizeof path);

    rte_image_info probed, info;
    rte_status probe = rte_image_probe(path, &probed, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (probe == RTE_OK)
        FUZZ_ASSERT(probed.width >= 1 && probed.height >= 1 &&
                    (probed.channels == 1 || probed.channels == 3));

    rte_status st = rte_image_read(reader, path, pixels, sizeof pixels, &info, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (st == RTE_OK) {
        FUZZ_ASSERT(info.width >= 1 && info.width <= FUZZ_MAX && info.height >= 1 &&
                    info.height <= FUZZ_MAX && (info.channels == 1 || info.channels == 3));
        /* The probe said the same (EXIF orientation included). */
        FUZZ_ASSERT(probe == RTE_OK && probed.width == info.width && probed.height == info.height &&
                    probed.channels == info.channels);
        /* The other entry points on an image of the size found, with padding. */
        int32_t w = info.width, h = info.height;
        if ((w + 3) * h * 3 <= (int32_t)sizeof pixels) {
            rte_image_u8c3 bgr = {w, h, 3 * w + 5, pixels};
            st = rte_image_read_bgr(reader, path, &bgr, msg, sizeof msg);
            FUZZ_ASSERT(st == RTE_OK);
            rte_image_u8 gray = {w, h, w + 3, pixels};
            st = rte_image_read_gray(reader, path, &gray, msg, sizeof msg);
            FUZZ_ASSERT(info.channels == 1 ? st == RTE_OK : st == RTE_ERR_UNSUPPORTED);
        }
    }
    close(fd);
    return 0;
}
