/* Image views, the scratch arena and status messages. */
#include "unit.h"

#include "rtedge/arena.h"
#include "rtedge/image.h"
#include "rtedge/status.h"

static void image_checks_reject_bad_views(void **state)
{
    uint8_t px[16];
    rte_image_u8 ok = rte_image_u8_view(px, 4, 4, 0);
    assert_int_equal(ok.stride, 4);
    assert_int_equal(rte_image_u8_check(&ok), RTE_OK);

    rte_image_u8 bad = ok;
    bad.width = 0;
    assert_int_equal(rte_image_u8_check(&bad), RTE_ERR_SIZE);
    bad = ok;
    bad.stride = 3;
    assert_int_equal(rte_image_u8_check(&bad), RTE_ERR_SIZE);
    bad = ok;
    bad.buf = NULL;
    assert_int_equal(rte_image_u8_check(&bad), RTE_ERR_ARGUMENT);
    bad = ok;
    bad.height = RTE_MAX_SIDE + 1;
    assert_int_equal(rte_image_u8_check(&bad), RTE_ERR_SIZE);
    assert_int_equal(rte_image_u8_check(NULL), RTE_ERR_ARGUMENT);

    rte_image_u8 other = rte_image_u8_view(px, 4, 3, 0);
    assert_int_equal(rte_image_u8_check_pair(&ok, &other), RTE_ERR_SIZE);
    assert_int_equal(rte_image_u8_check_pair(&ok, &ok), RTE_OK);

    rte_image_u8c3 c3 = {2, 2, 5, px};
    assert_int_equal(rte_image_u8c3_check(&c3), RTE_ERR_SIZE);
    c3.stride = 6;
    assert_int_equal(rte_image_u8c3_check(&c3), RTE_OK);
}

static void arena_hands_out_aligned_pieces_until_full(void **state)
{
    static uint8_t memory[1000];
    rte_arena arena;
    rte_arena_init(&arena, memory, sizeof memory);

    void *a = rte_arena_alloc(&arena, 10);
    void *b = rte_arena_alloc(&arena, 100);
    assert_non_null(a);
    assert_non_null(b);
    assert_int_equal((uintptr_t)a % RTE_ARENA_ALIGN, 0);
    assert_int_equal((uintptr_t)b % RTE_ARENA_ALIGN, 0);
    assert_true((uint8_t *)b >= (uint8_t *)a + 10);

    size_t mark = rte_arena_mark(&arena);
    assert_null(rte_arena_alloc(&arena, sizeof memory)); /* too big: nothing taken */
    assert_int_equal(rte_arena_mark(&arena), mark);
    void *c = rte_arena_alloc(&arena, 200);
    assert_non_null(c);
    rte_arena_reset(&arena, mark);
    assert_ptr_equal(rte_arena_alloc(&arena, 200), c);
    assert_true(arena.high_water >= mark + 200);
    assert_true(arena.high_water <= sizeof memory);
}

static void arena_piece_size_covers_any_alignment(void **state)
{
    static uint8_t memory[4096];
    for (size_t offset = 0; offset < RTE_ARENA_ALIGN; offset++) {
        for (size_t bytes = 1; bytes < 300; bytes += 37) {
            rte_arena arena;
            size_t need = rte_arena_piece_size(bytes) + rte_arena_piece_size(7);
            rte_arena_init(&arena, memory + offset, need);
            assert_non_null(rte_arena_alloc(&arena, bytes));
            assert_non_null(rte_arena_alloc(&arena, 7));
        }
    }
}

static void arena_without_memory_gives_nothing(void **state)
{
    rte_arena arena;
    rte_arena_init(&arena, NULL, 100);
    assert_null(rte_arena_alloc(&arena, 1));
}

static void every_status_has_a_message(void **state)
{
    for (int s = RTE_OK; s <= RTE_STATUS_LAST; s++) {
        const char *m = rte_status_message((rte_status)s);
        assert_non_null(m);
        assert_string_not_equal(m, "unknown status");
    }
    assert_string_equal(rte_status_message((rte_status)999), "unknown status");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(image_checks_reject_bad_views),
        cmocka_unit_test(arena_hands_out_aligned_pieces_until_full),
        cmocka_unit_test(arena_piece_size_covers_any_alignment),
        cmocka_unit_test(arena_without_memory_gives_nothing),
        cmocka_unit_test(every_status_has_a_message),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
