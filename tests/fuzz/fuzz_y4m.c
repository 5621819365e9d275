/* YUV4MPEG2: the daemon's Y4M source (header, FRAME lines, frames cut short
 * or damaged, a rewind) and rtedge_io's reader on the same bytes. */
#include "fuzz_source.h"

#include "rtedge/y4m.h"

#define FUZZ_MAX 64

static void source(const char *path)
{
    rte_source src;
    char msg[RTE_SOURCE_MESSAGE_SIZE];
    rte_status st = rte_y4m_source_open(&src, path, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    if (st != RTE_OK) {
        FUZZ_ASSERT(!src.ops);
        return;
    }
    /* A rewind gives the same frames again. */
    fuzz_passes passes;
    fuzz_read_passes(&src, 64, &passes);
    if (!passes.capped[0] && !passes.capped[1])
        FUZZ_ASSERT(passes.good[0] == passes.good[1] && passes.bad[0] == passes.bad[1]);
    rte_source_close(&src);
}

static void reader(const char *path)
{
    static uint8_t y[FUZZ_MAX * FUZZ_MAX];
    rte_y4m_reader *r;
    rte_y4m_info info;
    char msg[256];
    if (rte_y4m_open(path, FUZZ_MAX, FUZZ_MAX, &r, &info, msg, sizeof msg) != RTE_OK) {
        fuzz_check_message(msg, sizeof msg);
        return;
    }
    FUZZ_ASSERT(info.width >= 1 && info.width <= FUZZ_MAX && info.height >= 1 &&
                info.height <= FUZZ_MAX && info.chroma_bytes >= 0);
    rte_image_u8 dst = {info.width, info.height, info.width, y};
    for (int i = 0; i < 16 && rte_y4m_read_gray(r, &dst, msg, sizeof msg) == RTE_OK; i++)
        ;
    rte_y4m_close(r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[64];
    int fd = fuzz_file(data, size, path, sizeof path);
    source(path);
    reader(path);
    close(fd);
    return 0;
}
