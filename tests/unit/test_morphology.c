/* Structuring elements, erosion/dilation/opening/closing against a direct
 * definition (min/max over the set cells inside the image), in place,
 * arena sizing and argument errors. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/morphology.h"

static uint8_t arena_memory[1 << 20];

static rte_morph_element element(rte_morph_shape shape, int32_t w, int32_t h)
{
    rte_morph_element e;
    assert_int_equal(rte_morphology_element_init(&e, shape, w, h), RTE_OK);
    return e;
}

static void elements_match_hand_drawn_masks(void **state)
{
    rte_morph_element e = element(RTE_MORPH_CROSS, 3, 3);
    const uint8_t cross[9] = {0, 1, 0, 1, 1, 1, 0, 1, 0};
    assert_memory_equal(e.mask, cross, 9);
    assert_false(e.full);
    assert_int_equal(e.run_count, 3);

    e = element(RTE_MORPH_ELLIPSE, 5, 5);
    const uint8_t ellipse5[25] = {0, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1,
                                  1, 1, 1, 1, 1, 1, 1, 0, 0, 1, 0, 0};
    assert_memory_equal(e.mask, ellipse5, 25);

    e = element(RTE_MORPH_ELLIPSE, 4, 6); /* OpenCV's lopsided even ellipse */
    const uint8_t ellipse46[24] = {0, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1,
                                   1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1};
    assert_memory_equal(e.mask, ellipse46, 24);

    e = element(RTE_MORPH_CROSS, 4, 6);
    assert_int_equal(e.anchor_x, 2);
    assert_int_equal(e.anchor_y, 3);
    const uint8_t cross46[24] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0,
                                 1, 1, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0};
    assert_memory_equal(e.mask, cross46, 24);

    e = element(RTE_MORPH_RECT, 7, 2);
    assert_true(e.full);
    assert_int_equal(e.max_run, 7);
    e = element(RTE_MORPH_ELLIPSE, 1, 1);
    assert_true(e.full);
    e = element(RTE_MORPH_CROSS, 1, 5); /* a cross one pixel wide is full */
    assert_true(e.full);

    assert_int_equal(rte_morphology_element_init(&e, RTE_MORPH_RECT, 0, 3), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_element_init(&e, RTE_MORPH_RECT, 3, RTE_MORPH_MAX_KSIZE + 1),
                     RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_element_init(&e, (rte_morph_shape)3, 3, 3), RTE_ERR_ARGUMENT);
    const uint8_t empty[4] = {0};
    assert_int_equal(rte_morphology_element_from_mask(&e, empty, 2, 2, -1, -1), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_element_from_mask(&e, cross, 3, 3, 3, 0), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_element_from_mask(&e, cross, 3, 3, -1, -1), RTE_OK);
    assert_int_equal(e.anchor_x, 1);
}

/* Direct definition: one erosion or dilation, border pixels never win. */
static void reference_pass(const uint8_t *in, uint8_t *out, int32_t w, int32_t h,
                           const rte_morph_element *e, int is_max)
{
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            int32_t v = is_max ? 0 : 255;
            for (int32_t j = 0; j < e->height; j++)
                for (int32_t i = 0; i < e->width; i++) {
                    int32_t sy = y + j - e->anchor_y, sx = x + i - e->anchor_x;
                    if (!e->mask[j * e->width + i] || sy < 0 || sy >= h || sx < 0 || sx >= w)
                        continue;
                    int32_t s = in[sy * w + sx];
                    v = is_max ? (s > v ? s : v) : (s < v ? s : v);
                }
            out[y * w + x] = (uint8_t)v;
        }
}

static void reference(const uint8_t *in, uint8_t *out, int32_t w, int32_t h, rte_morph_op op,
                      const rte_morph_element *e, int32_t iterations)
{
    uint8_t *tmp = test_malloc((size_t)w * h);
    memcpy(out, in, (size_t)w * h);
    int first_max = op == RTE_MORPH_DILATE || op == RTE_MORPH_CLOSE;
    int stages = op >= RTE_MORPH_OPEN ? 2 : 1;
    for (int s = 0; s < stages; s++)
        for (int32_t i = 0; i < iterations; i++) {
            reference_pass(out, tmp, w, h, e, s == 0 ? first_max : !first_max);
            memcpy(out, tmp, (size_t)w * h);
        }
    test_free(tmp);
}

static void run_case(const rte_morph_element *e, rte_morph_op op, int32_t iterations, int32_t w,
                     int32_t h, uint32_t *rng, int in_place)
{
    rte_image_u8 src = unit_image_u8(w, h, (int32_t)(unit_rand(rng) % 7), 0);
    rte_image_u8 dst = in_place ? src : unit_image_u8(w, h, (int32_t)(unit_rand(rng) % 7), 0);
    uint8_t *packed = test_malloc((size_t)w * h), *want = test_malloc((size_t)w * h);
    int sparse = unit_rand(rng) % 2;
    for (int32_t y = 0; y < h; y++)
        for (int32_t x = 0; x < w; x++) {
            uint8_t v = (uint8_t)unit_rand(rng);
            if (sparse)
                v = (unit_rand(rng) % 5 == 0) ? 255 : 0;
            src.buf[y * src.stride + x] = packed[y * w + x] = v;
        }
    reference(packed, want, w, h, op, e, iterations);

    size_t need = rte_morphology_scratch_size(w, h, e, iterations);
    assert_true(need > 0 && need <= sizeof arena_memory);
    rte_arena arena;
    rte_arena_init(&arena, arena_memory, need);
    assert_int_equal(rte_morphology_u8(&src, &dst, op, e, iterations, &arena), RTE_OK);
    assert_int_equal(arena.used, 0);
    for (int32_t y = 0; y < h; y++)
        assert_memory_equal(dst.buf + y * dst.stride, want + y * w, (size_t)w);
    unit_assert_padding_u8(&dst);
    if (!in_place) {
        unit_assert_padding_u8(&src);
        for (int32_t y = 0; y < h; y++) /* the source is untouched */
            assert_memory_equal(src.buf + y * src.stride, packed + y * w, (size_t)w);
        test_free(dst.buf);
    }
    test_free(src.buf);
    test_free(packed);
    test_free(want);
}

static void single_bright_pixel_grows_and_vanishes(void **state)
{
    rte_image_u8 img = unit_image_u8(5, 5, 2, 0), out = unit_image_u8(5, 5, 3, 0);
    img.buf[2 * img.stride + 2] = 200;
    rte_morph_element e = element(RTE_MORPH_RECT, 3, 3);
    rte_arena arena;
    rte_arena_init(&arena, arena_memory, sizeof arena_memory);
    assert_int_equal(rte_morphology_dilate_u8(&img, &out, &e, 1, &arena), RTE_OK);
    for (int32_t y = 0; y < 5; y++)
        for (int32_t x = 0; x < 5; x++)
            assert_int_equal(out.buf[y * out.stride + x],
                             (x >= 1 && x <= 3 && y >= 1 && y <= 3) ? 200 : 0);
    assert_int_equal(rte_morphology_erode_u8(&img, &out, &e, 1, &arena), RTE_OK);
    for (int32_t y = 0; y < 5; y++)
        for (int32_t x = 0; x < 5; x++)
            assert_int_equal(out.buf[y * out.stride + x], 0);
    /* opening removes the dot, closing keeps it */
    assert_int_equal(rte_morphology_u8(&img, &out, RTE_MORPH_OPEN, &e, 1, &arena), RTE_OK);
    assert_int_equal(out.buf[2 * out.stride + 2], 0);
    assert_int_equal(rte_morphology_u8(&img, &out, RTE_MORPH_CLOSE, &e, 1, &arena), RTE_OK);
    assert_int_equal(out.buf[2 * out.stride + 2], 200);
    assert_int_equal(out.buf[1 * out.stride + 2], 0);
    unit_assert_padding_u8(&out);
    assert_int_equal(arena.used, 0);
    test_free(img.buf);
    test_free(out.buf);
}

static void every_shape_size_op_and_iteration_against_the_definition(void **state)
{
    uint32_t rng = 2026;
    const int32_t sizes[][2] = {{1, 1}, {3, 3}, {2, 2}, {5, 5}, {4, 6},
                                {7, 3}, {1, 5}, {6, 1}, {9, 9}, {15, 15}};
    for (int shape = 0; shape <= 2; shape++)
        for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
            rte_morph_element e = element((rte_morph_shape)shape, sizes[s][0], sizes[s][1]);
            for (int op = 0; op <= 3; op++)
                for (int32_t it = 1; it <= 3; it++) {
                    int32_t w = 1 + (int32_t)(unit_rand(&rng) % 40),
                            h = 1 + (int32_t)(unit_rand(&rng) % 20);
                    run_case(&e, (rte_morph_op)op, it, w, h, &rng, (int)(unit_rand(&rng) % 3 == 0));
                }
        }
}

static void all_widths_thin_and_tiny_images(void **state)
{
    uint32_t rng = 31337;
    rte_morph_element rect = element(RTE_MORPH_RECT, 3, 3), ell = element(RTE_MORPH_ELLIPSE, 5, 7);
    for (int32_t w = 1; w <= 67; w++) {
        run_case(&rect, (rte_morph_op)(w % 4), 1 + w % 3, w, 1 + w % 4, &rng, w % 5 == 0);
        run_case(&ell, (rte_morph_op)((w + 1) % 4), 1 + w % 2, w, 1 + w % 9, &rng, w % 7 == 0);
    }
    run_case(&rect, RTE_MORPH_ERODE, 1, 1, 1, &rng, 0);
    run_case(&ell, RTE_MORPH_DILATE, 2, 1, 30, &rng, 0);
    run_case(&ell, RTE_MORPH_CLOSE, 1, 30, 1, &rng, 1);
}

static void custom_masks_with_anchors(void **state)
{
    uint32_t rng = 5;
    for (int n = 0; n < 200; n++) {
        int32_t kw = 1 + (int32_t)(unit_rand(&rng) % 7), kh = 1 + (int32_t)(unit_rand(&rng) % 7);
        uint8_t mask[49];
        for (int32_t i = 0; i < kw * kh; i++)
            mask[i] = (uint8_t)(unit_rand(&rng) % 3 == 0);
        mask[unit_rand(&rng) % (uint32_t)(kw * kh)] = 7; /* any non-zero is set */
        rte_morph_element e;
        assert_int_equal(rte_morphology_element_from_mask(&e, mask, kw, kh,
                                                          (int32_t)(unit_rand(&rng) % kw),
                                                          (int32_t)(unit_rand(&rng) % kh)),
                         RTE_OK);
        run_case(&e, (rte_morph_op)(n % 4), 1 + n % 3, 1 + (int32_t)(unit_rand(&rng) % 30),
                 1 + (int32_t)(unit_rand(&rng) % 12), &rng, n % 4 == 0);
    }
}

static void constant_images_stay_constant(void **state)
{
    const uint8_t levels[3] = {0, 255, 93};
    rte_morph_element e = element(RTE_MORPH_ELLIPSE, 7, 7), r = element(RTE_MORPH_RECT, 4, 4);
    rte_arena arena;
    rte_arena_init(&arena, arena_memory, sizeof arena_memory);
    for (int l = 0; l < 3; l++)
        for (int op = 0; op <= 3; op++) {
            rte_image_u8 img = unit_image_u8(9, 6, 3, levels[l]), out = unit_image_u8(9, 6, 1, 1);
            assert_int_equal(
                rte_morphology_u8(&img, &out, (rte_morph_op)op, op % 2 ? &e : &r, 2, &arena),
                RTE_OK);
            for (int32_t y = 0; y < 6; y++)
                for (int32_t x = 0; x < 9; x++)
                    assert_int_equal(out.buf[y * out.stride + x], levels[l]);
            unit_assert_padding_u8(&out);
            test_free(img.buf);
            test_free(out.buf);
        }
}

/* An element whose only set cell lies above every image row: OpenCV gives
 * the border value itself (255 for erode, 0 for dilate). */
static void element_reaching_only_outside_gives_the_neutral_value(void **state)
{
    const uint8_t mask[7] = {1, 0, 0, 0, 0, 0, 0};
    rte_morph_element e;
    assert_int_equal(rte_morphology_element_from_mask(&e, mask, 1, 7, 0, 6), RTE_OK);
    rte_image_u8 img = unit_image_u8(2, 3, 1, 50), out = unit_image_u8(2, 3, 2, 1);
    rte_arena arena;
    rte_arena_init(&arena, arena_memory, sizeof arena_memory);
    assert_int_equal(rte_morphology_erode_u8(&img, &out, &e, 1, &arena), RTE_OK);
    for (int32_t y = 0; y < 3; y++)
        assert_true(out.buf[y * out.stride] == 255 && out.buf[y * out.stride + 1] == 255);
    assert_int_equal(rte_morphology_dilate_u8(&img, &out, &e, 1, &arena), RTE_OK);
    for (int32_t y = 0; y < 3; y++)
        assert_true(out.buf[y * out.stride] == 0 && out.buf[y * out.stride + 1] == 0);
    unit_assert_padding_u8(&out);
    test_free(img.buf);
    test_free(out.buf);
}

static void arena_and_argument_errors(void **state)
{
    rte_morph_element e = element(RTE_MORPH_ELLIPSE, 5, 5), r = element(RTE_MORPH_RECT, 5, 5);
    rte_image_u8 a = unit_image_u8(40, 30, 0, 1), b = unit_image_u8(40, 29, 0, 1);
    rte_arena arena;
    size_t need = rte_morphology_scratch_size(40, 30, &e, 1);
    assert_true(need > 0);
    assert_true(rte_morphology_scratch_size(40, 30, &r, 3) >
                rte_morphology_scratch_size(40, 30, &r, 1));
    /* Every arena smaller than the bound either holds the pieces (the
     * bound allows for the worst alignment) or fails whole: the mark is
     * back where it was, also when the first piece fitted and a later one
     * did not. The bound itself always holds them. */
    int failed = 0;
    for (size_t size = 1; size <= need + 1; size++) {
        rte_arena_init(&arena, arena_memory, size);
        (void)rte_arena_alloc(&arena, 1); /* the pieces start unaligned */
        size_t mark = rte_arena_mark(&arena);
        rte_status st = rte_morphology_erode_u8(&a, &a, &e, 1, &arena);
        assert_true(st == RTE_OK || st == RTE_ERR_NO_MEMORY);
        assert_int_equal(rte_arena_mark(&arena), mark);
        if (size == need + 1)
            assert_int_equal(st, RTE_OK);
        failed += st == RTE_ERR_NO_MEMORY;
    }
    assert_true(failed > 64);
    rte_arena_init(&arena, arena_memory, sizeof arena_memory);
    assert_int_equal(rte_morphology_erode_u8(&a, &b, &e, 1, &arena), RTE_ERR_SIZE);
    assert_int_equal(rte_morphology_erode_u8(&a, &a, &e, 0, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_erode_u8(&a, &a, NULL, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_erode_u8(&a, &a, &e, 1, NULL), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_u8(&a, &a, (rte_morph_op)4, &e, 1, &arena), RTE_ERR_ARGUMENT);
    rte_morph_element bad = e;
    bad.anchor_x = 5;
    assert_int_equal(rte_morphology_dilate_u8(&a, &a, &bad, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_scratch_size(40, 30, &bad, 1), 0);
    bad = e;
    bad.runs[1].len = 6; /* wider than the element */
    assert_int_equal(rte_morphology_dilate_u8(&a, &a, &bad, 1, &arena), RTE_ERR_ARGUMENT);
    bad = e;
    bad.runs[0].dy = -1;
    assert_int_equal(rte_morphology_erode_u8(&a, &a, &bad, 1, &arena), RTE_ERR_ARGUMENT);
    assert_int_equal(rte_morphology_scratch_size(0, 30, &e, 1), 0);
    test_free(a.buf);
    test_free(b.buf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(elements_match_hand_drawn_masks),
        cmocka_unit_test(single_bright_pixel_grows_and_vanishes),
        cmocka_unit_test(every_shape_size_op_and_iteration_against_the_definition),
        cmocka_unit_test(all_widths_thin_and_tiny_images),
        cmocka_unit_test(custom_masks_with_anchors),
        cmocka_unit_test(constant_images_stay_constant),
        cmocka_unit_test(element_reaching_only_outside_gives_the_neutral_value),
        cmocka_unit_test(arena_and_argument_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
