/* A program built against an installed rtedge (headers and pkg-config file
 * from `meson install`), as a user of librtedge builds one: a vertical step
 * written to PATH (a PNG) and read back must be the same pixels, and Canny
 * on it must mark the step's two columns on every inner row and nothing
 * else. Exit 0 when both hold.
 *   installed_consumer PATH */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <rtedge/arena.h>
#include <rtedge/canny.h>
#include <rtedge/image.h>
#include <rtedge/imageio.h>
#include <rtedge/status.h>

enum { W = 64, H = 48, STEP = 32 };

/* The step through a PNG file: written, read back into src. */
static int step_through_file(const char *path, uint8_t *src_px)
{
    static uint8_t step_px[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            step_px[y * W + x] = x < STEP ? 20 : 220;
    rte_image_u8 step = rte_image_u8_view(step_px, W, H, W),
                 src = rte_image_u8_view(src_px, W, H, W);
    char msg[RTE_IO_MESSAGE_SIZE];
    rte_image_reader *reader = rte_image_reader_create(W, H);
    rte_status st = reader ? rte_image_write_gray(path, &step, msg, sizeof msg) : RTE_ERR_NO_MEMORY;
    if (st == RTE_OK)
        st = rte_image_read_gray(reader, path, &src, msg, sizeof msg);
    rte_image_reader_destroy(reader);
    if (st != RTE_OK) {
        fprintf(stderr, "%s: %s\n", rte_status_message(st), reader ? msg : "");
        return 1;
    }
    return memcmp(step_px, src_px, sizeof step_px) != 0;
}

int main(int argc, char **argv)
{
    static uint8_t src_px[W * H], dst_px[W * H];
    if (argc != 2 || step_through_file(argv[1], src_px) != 0) {
        fprintf(stderr, "the step did not come back through %s\n", argc == 2 ? argv[1] : "PATH");
        return 1;
    }
    rte_image_u8 src = rte_image_u8_view(src_px, W, H, W), dst = rte_image_u8_view(dst_px, W, H, W);
    rte_canny_params params;
    rte_status st = rte_canny_params_init(&params, 50, 150, 3, false);
    size_t bytes = rte_canny_scratch_size(W, H, 3);
    void *memory = malloc(bytes);
    rte_arena arena;
    rte_arena_init(&arena, memory, bytes);
    if (st == RTE_OK)
        st = rte_canny_u8(&src, &dst, &params, &arena);
    free(memory);
    if (st != RTE_OK) {
        fprintf(stderr, "rte_canny_u8: %s\n", rte_status_message(st));
        return 1;
    }
    int on_step = 0, elsewhere = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (dst_px[y * W + x])
                *(x == STEP - 1 || x == STEP ? &on_step : &elsewhere) += 1;
    printf("installed librtedge: %d edge pixels on the step, %d elsewhere\n", on_step, elsewhere);
    return on_step >= H && elsewhere == 0 ? 0 : 1;
}
