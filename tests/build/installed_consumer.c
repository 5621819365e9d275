/* A program built against an installed rtedge (headers and pkg-config file
 * from `meson install`), as a user of librtedge builds one: Canny on a
 * vertical step must mark the step's two columns on every inner row and
 * nothing else. Exit 0 when it does. */
#include <stdio.h>
#include <stdlib.h>

#include <rtedge/arena.h>
#include <rtedge/canny.h>
#include <rtedge/image.h>
#include <rtedge/status.h>

enum { W = 64, H = 48, STEP = 32 };

int main(void)
{
    static uint8_t src_px[W * H], dst_px[W * H];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            src_px[y * W + x] = x < STEP ? 20 : 220;
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
