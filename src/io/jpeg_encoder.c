/* The debug stream's JPEG encoder: see jpeg_encoder.h.
 *
 * libjpeg's memory manager is an object of method pointers
 * (jpeglib.h, struct jpeg_memory_mgr). After jpeg_create_compress and
 * jpeg_set_defaults (whose tables go to libjpeg's own permanent pool, once)
 * the methods are pointed here: allocations come from two arenas, one for
 * JPOOL_PERMANENT and one for JPOOL_IMAGE, which free_pool(JPOOL_IMAGE)
 * (jpeg_finish_compress, jpeg_abort) empties again. Blocks and sample rows
 * are aligned and rows padded to ARENA_ALIGN bytes: libjpeg-turbo's SIMD
 * code reads and writes whole vectors. Baseline compression needs no
 * virtual arrays (those serve multi-scan output): asking for one is an
 * error. */
#include "jpeg_encoder.h"

#include <setjmp.h>
#include <stdio.h> /* jpeglib.h needs FILE and size_t first */
#include <stdlib.h>
#include <string.h>

#include <jerror.h>
#include <jpeglib.h>

#define ARENA_ALIGN 64
#define PERMANENT_BYTES (16 << 10)
#define MIN_SIDE 8
#define MAX_SIDE 16384

typedef struct arena {
    uint8_t *base;
    size_t size, used, peak;
} arena;

struct rte_jpeg_encoder {
    struct jpeg_compress_struct cinfo; /* first: libjpeg's callbacks get &cinfo */
    struct jpeg_error_mgr jerr;
    struct jpeg_destination_mgr dest;
    jmp_buf jump;
    char error[JMSG_LENGTH_MAX];
    void (*libjpeg_self_destruct)(j_common_ptr);
    arena permanent, image;
    uint8_t *out;
    size_t out_capacity, out_size;
    int32_t max_width, max_height;
    void *memory; /* the arenas and the output, one allocation */
};

static rte_jpeg_encoder *encoder_of(j_common_ptr c) { return (rte_jpeg_encoder *)(void *)c; }

static size_t align_up(size_t n) { return (n + ARENA_ALIGN - 1) & ~(size_t)(ARENA_ALIGN - 1); }

/* ---- libjpeg's errors: the message kept, back to the caller ---- */

static void on_error(j_common_ptr c)
{
    rte_jpeg_encoder *enc = encoder_of(c);
    (*c->err->format_message)(c, enc->error);
    longjmp(enc->jump, 1);
}

static void on_message(j_common_ptr c) { (void)c; /* warnings: nothing on stderr */ }

/* ---- the memory manager's methods ---- */

static void *arena_alloc(j_common_ptr c, int pool_id, size_t n)
{
    rte_jpeg_encoder *enc = encoder_of(c);
    arena *a = pool_id == JPOOL_PERMANENT ? &enc->permanent : &enc->image;
    size_t at = align_up(a->used);
    if (at > a->size || n > a->size - at)
        ERREXIT1(c, JERR_OUT_OF_MEMORY, pool_id);
    a->used = at + n;
    if (a->used > a->peak)
        a->peak = a->used;
    return a->base + at;
}

static JSAMPARRAY alloc_sarray(j_common_ptr c, int pool_id, JDIMENSION samples, JDIMENSION rows)
{
    size_t row_bytes = align_up((size_t)samples * sizeof(JSAMPLE));
    JSAMPARRAY array = arena_alloc(c, pool_id, (size_t)rows * sizeof(JSAMPROW));
    uint8_t *data = arena_alloc(c, pool_id, (size_t)rows * row_bytes);
    for (JDIMENSION i = 0; i < rows; i++)
        array[i] = (JSAMPROW)(data + (size_t)i * row_bytes);
    return array;
}

static JBLOCKARRAY alloc_barray(j_common_ptr c, int pool_id, JDIMENSION blocks, JDIMENSION rows)
{
    size_t row_bytes = align_up((size_t)blocks * sizeof(JBLOCK));
    JBLOCKARRAY array = arena_alloc(c, pool_id, (size_t)rows * sizeof(JBLOCKROW));
    uint8_t *data = arena_alloc(c, pool_id, (size_t)rows * row_bytes);
    for (JDIMENSION i = 0; i < rows; i++)
        array[i] = (JBLOCKROW)(void *)(data + (size_t)i * row_bytes);
    return array;
}

static jvirt_sarray_ptr request_virt_sarray(j_common_ptr c, int pool_id, boolean pre_zero,
                                            JDIMENSION samples, JDIMENSION rows,
                                            JDIMENSION maxaccess)
{
    (void)pool_id, (void)pre_zero, (void)samples, (void)rows, (void)maxaccess;
    ERREXIT(c, JERR_NOTIMPL);
    return NULL;
}

static jvirt_barray_ptr request_virt_barray(j_common_ptr c, int pool_id, boolean pre_zero,
                                            JDIMENSION blocks, JDIMENSION rows,
                                            JDIMENSION maxaccess)
{
    (void)pool_id, (void)pre_zero, (void)blocks, (void)rows, (void)maxaccess;
    ERREXIT(c, JERR_NOTIMPL);
    return NULL;
}

/* Called on every image whether or not arrays were requested: none were. */
static void realize_virt_arrays(j_common_ptr c) { (void)c; }

static JSAMPARRAY access_virt_sarray(j_common_ptr c, jvirt_sarray_ptr p, JDIMENSION start,
                                     JDIMENSION rows, boolean writable)
{
    (void)p, (void)start, (void)rows, (void)writable;
    ERREXIT(c, JERR_NOTIMPL);
    return NULL;
}

static JBLOCKARRAY access_virt_barray(j_common_ptr c, jvirt_barray_ptr p, JDIMENSION start,
                                      JDIMENSION rows, boolean writable)
{
    (void)p, (void)start, (void)rows, (void)writable;
    ERREXIT(c, JERR_NOTIMPL);
    return NULL;
}

static void free_pool(j_common_ptr c, int pool_id)
{
    rte_jpeg_encoder *enc = encoder_of(c);
    if (pool_id == JPOOL_IMAGE)
        enc->image.used = 0;
}

/* jpeg_destroy: libjpeg frees what it allocated before the switch. */
static void self_destruct(j_common_ptr c) { encoder_of(c)->libjpeg_self_destruct(c); }

/* ---- the destination: the encoder's buffer ---- */

static void dest_init(j_compress_ptr c)
{
    rte_jpeg_encoder *enc = encoder_of((j_common_ptr)c);
    c->dest->next_output_byte = enc->out;
    c->dest->free_in_buffer = enc->out_capacity;
}

/* The buffer holds any image of the maximum size: never reached. */
static boolean dest_full(j_compress_ptr c)
{
    ERREXIT(c, JERR_BUFFER_SIZE);
    return FALSE;
}

static void dest_term(j_compress_ptr c)
{
    rte_jpeg_encoder *enc = encoder_of((j_common_ptr)c);
    enc->out_size = enc->out_capacity - c->dest->free_in_buffer;
}

/* ---- the encoder ---- */

/* Bytes of the per-image arena for a width: libjpeg-turbo 2.1 asks for
 * about 30 bytes a column and 9 KiB at 4:2:0 (colour conversion,
 * downsampling and context rows, one MCU row of coefficients; measured
 * from 640 to 4096 columns); twice that and a margin. */
static size_t image_arena_bytes(int32_t max_width)
{
    return (size_t)(max_width + 64) * 64 + (64 << 10);
}

/* libjpeg-turbo's worst case for a 4:2:0 image (tjBufSize(TJSAMP_420)):
 * 3 bytes a pixel of the image padded to whole MCUs, and the headers. */
static size_t output_bytes(int32_t w, int32_t h)
{
    return (size_t)((w + 15) & ~15) * (size_t)((h + 15) & ~15) * 3 + 2048;
}

rte_status rte_jpeg_encoder_set_quality(rte_jpeg_encoder *enc, int32_t quality)
{
    if (!enc || quality < 1 || quality > 100)
        return RTE_ERR_ARGUMENT;
    if (setjmp(enc->jump))
        return RTE_ERR_IO;
    /* The tables exist (jpeg_set_defaults): they are refilled, not allocated. */
    jpeg_set_quality(&enc->cinfo, quality, TRUE);
    return RTE_OK;
}

rte_status rte_jpeg_encode_bgr(rte_jpeg_encoder *enc, const rte_image_u8c3 *img,
                               const uint8_t **data, size_t *size, char *msg, size_t msg_size)
{
    if (!enc || !img || !img->buf || !data || !size)
        return RTE_ERR_ARGUMENT;
    if (img->width < 1 || img->height < 1 || img->width > enc->max_width ||
        img->height > enc->max_height || img->stride < img->width * 3) {
        snprintf(msg, msg_size, "a %dx%d image (stride %d) for an encoder of at most %dx%d",
                 img->width, img->height, img->stride, enc->max_width, enc->max_height);
        return RTE_ERR_SIZE;
    }
    struct jpeg_compress_struct *c = &enc->cinfo;
    if (setjmp(enc->jump)) {
        jpeg_abort_compress(c);
        snprintf(msg, msg_size, "libjpeg: %s", enc->error);
        return RTE_ERR_IO;
    }
    c->image_width = (JDIMENSION)img->width;
    c->image_height = (JDIMENSION)img->height;
    jpeg_start_compress(c, TRUE);
    JSAMPROW rows[16];
    while (c->next_scanline < c->image_height) {
        JDIMENSION n = 0;
        for (; n < 16 && c->next_scanline + n < c->image_height; n++)
            rows[n] = img->buf + (size_t)(c->next_scanline + n) * (size_t)img->stride;
        jpeg_write_scanlines(c, rows, n);
    }
    jpeg_finish_compress(c);
    *data = enc->out;
    *size = enc->out_size;
    return RTE_OK;
}

rte_status rte_jpeg_encoder_create(rte_jpeg_encoder **out, int32_t max_width, int32_t max_height,
                                   int32_t quality, char *msg, size_t msg_size)
{
    *out = NULL;
    if (max_width < MIN_SIDE || max_height < MIN_SIDE || max_width > MAX_SIDE ||
        max_height > MAX_SIDE || quality < 1 || quality > 100) {
        snprintf(msg, msg_size, "a JPEG encoder for %dx%d at quality %d (%d..%d px, 1..100)",
                 max_width, max_height, quality, MIN_SIDE, MAX_SIDE);
        return RTE_ERR_ARGUMENT;
    }
    rte_jpeg_encoder *enc = calloc(1, sizeof *enc);
    size_t image_bytes = image_arena_bytes(max_width);
    size_t out_bytes = output_bytes(max_width, max_height);
    if (enc)
        enc->memory = malloc(PERMANENT_BYTES + image_bytes + out_bytes);
    if (!enc || !enc->memory) {
        free(enc);
        snprintf(msg, msg_size, "out of memory for a %dx%d JPEG encoder", max_width, max_height);
        return RTE_ERR_NO_MEMORY;
    }
    uint8_t *m = enc->memory;
    enc->permanent = (arena){m, PERMANENT_BYTES, 0, 0};
    enc->image = (arena){m + PERMANENT_BYTES, image_bytes, 0, 0};
    enc->out = m + PERMANENT_BYTES + image_bytes;
    enc->out_capacity = out_bytes;
    enc->max_width = max_width;
    enc->max_height = max_height;

    struct jpeg_compress_struct *c = &enc->cinfo;
    c->err = jpeg_std_error(&enc->jerr);
    enc->jerr.error_exit = on_error;
    enc->jerr.output_message = on_message;
    if (setjmp(enc->jump)) {
        snprintf(msg, msg_size, "libjpeg: %s", enc->error);
        rte_jpeg_encoder_destroy(enc);
        return RTE_ERR_NO_MEMORY;
    }
    jpeg_create_compress(c);
    c->in_color_space = JCS_EXT_BGR;
    c->input_components = 3;
    jpeg_set_defaults(c);
    jpeg_set_quality(c, quality, TRUE);
    enc->dest = (struct jpeg_destination_mgr){NULL, 0, dest_init, dest_full, dest_term};
    c->dest = &enc->dest;
    struct jpeg_memory_mgr *mem = c->mem;
    enc->libjpeg_self_destruct = mem->self_destruct;
    mem->alloc_small = arena_alloc;
    mem->alloc_large = arena_alloc;
    mem->alloc_sarray = alloc_sarray;
    mem->alloc_barray = alloc_barray;
    mem->request_virt_sarray = request_virt_sarray;
    mem->request_virt_barray = request_virt_barray;
    mem->realize_virt_arrays = realize_virt_arrays;
    mem->access_virt_sarray = access_virt_sarray;
    mem->access_virt_barray = access_virt_barray;
    mem->free_pool = free_pool;
    mem->self_destruct = self_destruct;

    /* The largest image once: the arenas hold it, or the encoder is refused. */
    size_t trial_bytes = (size_t)max_width * (size_t)max_height * 3;
    uint8_t *trial = calloc(trial_bytes, 1);
    rte_image_u8c3 img = {max_width, max_height, max_width * 3, trial};
    const uint8_t *data;
    size_t size;
    rte_status st =
        trial ? rte_jpeg_encode_bgr(enc, &img, &data, &size, msg, msg_size) : RTE_ERR_NO_MEMORY;
    free(trial);
    if (st != RTE_OK) {
        rte_jpeg_encoder_destroy(enc);
        return RTE_ERR_NO_MEMORY;
    }
    *out = enc;
    return RTE_OK;
}

void rte_jpeg_encoder_destroy(rte_jpeg_encoder *enc)
{
    if (!enc)
        return;
    if (enc->cinfo.mem)
        jpeg_destroy_compress(&enc->cinfo);
    free(enc->memory);
    free(enc);
}

void rte_jpeg_encoder_get_stats(const rte_jpeg_encoder *enc, rte_jpeg_encoder_stats *stats)
{
    *stats = (rte_jpeg_encoder_stats){enc->permanent.size + enc->image.size,
                                      enc->permanent.peak + enc->image.peak, enc->permanent.used,
                                      enc->out_capacity};
}
