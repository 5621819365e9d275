/* A fixed scratch arena: one block of caller memory handed out in aligned
 * pieces. Kernels that need scratch take an arena, take what they need and
 * give it back with rte_arena_reset() before returning, so the arena's size
 * (computed once from the maximum image size) bounds all working memory. */
#ifndef RTEDGE_ARENA_H
#define RTEDGE_ARENA_H

#include <stddef.h>
#include <stdint.h>

#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rte_arena {
    uint8_t *base;
    size_t size;
    size_t used;
    size_t high_water; /* the most ever in use: lets callers size arenas from a run */
} rte_arena;

/* Alignment of every piece; enough for any SIMD row kernel. */
#define RTE_ARENA_ALIGN 64

RTE_API void rte_arena_init(rte_arena *arena, void *memory, size_t size);

/* A piece of `bytes` bytes aligned to RTE_ARENA_ALIGN, or NULL when the
 * arena cannot hold it (nothing is taken then). */
RTE_API void *rte_arena_alloc(rte_arena *arena, size_t bytes);

/* Bytes that rte_arena_alloc(bytes) uses, padding included: add these up to
 * size an arena. */
RTE_API size_t rte_arena_piece_size(size_t bytes);

static inline size_t rte_arena_mark(const rte_arena *arena) { return arena->used; }
static inline void rte_arena_reset(rte_arena *arena, size_t mark) { arena->used = mark; }

#ifdef __cplusplus
}
#endif
#endif
