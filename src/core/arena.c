#include "rtedge/arena.h"

void rte_arena_init(rte_arena *arena, void *memory, size_t size)
{
    arena->base = (uint8_t *)memory;
    arena->size = memory ? size : 0;
    arena->used = 0;
    arena->high_water = 0;
}

size_t rte_arena_piece_size(size_t bytes)
{
    /* Worst case: the piece needs padding before it to reach alignment. */
    return (bytes + 2 * RTE_ARENA_ALIGN - 1) & ~(size_t)(RTE_ARENA_ALIGN - 1);
}

void *rte_arena_alloc(rte_arena *arena, size_t bytes)
{
    uintptr_t start = (uintptr_t)arena->base + arena->used;
    size_t pad =
        (size_t)((RTE_ARENA_ALIGN - (start & (RTE_ARENA_ALIGN - 1))) & (RTE_ARENA_ALIGN - 1));
    if (!arena->base || pad > arena->size - arena->used || bytes > arena->size - arena->used - pad)
        return NULL;
    arena->used += pad + bytes;
    if (arena->used > arena->high_water)
        arena->high_water = arena->used;
    return (void *)(start + pad);
}
