/* Image-file source: a directory or glob of PGM/PPM/PNG/JPEG files in name
 * order, read through one rte_image_reader (imageio.h).
 *
 * Memory: open() allocates the name list, the reader and two frame buffers
 * (the decoded file, and the converted frame when grey and colour files
 * meet); next() allocates nothing of its own (the codecs do, per file). */
#include <dirent.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "recorded.h"
#include "rtedge/imageio.h"

typedef struct images_source {
    rte_recording rec; /* first: see recorded.h */
    rte_pixel_format format;
    int32_t fps_num, fps_den;
    char **names;
    size_t count;
    rte_image_reader *reader;
    uint8_t *decoded;   /* max * 3 bytes: what the file holds */
    uint8_t *converted; /* max * channels bytes: the other channel count */
    size_t decoded_size;
} images_source;

static void images_rewind(void *impl) { (void)impl; /* the slot index is all the state */ }

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Appends dir/name (or name alone when dir is NULL) to the list. */
static rte_status add_name(images_source *s, size_t *capacity, const char *dir, const char *name)
{
    if (s->count == *capacity) {
        size_t cap = *capacity ? *capacity * 2 : 64;
        char **names = realloc(s->names, cap * sizeof *names);
        if (!names)
            return RTE_ERR_NO_MEMORY;
        s->names = names;
        *capacity = cap;
    }
    size_t len = (dir ? strlen(dir) + 1 : 0) + strlen(name) + 1;
    char *full = malloc(len);
    if (!full)
        return RTE_ERR_NO_MEMORY;
    if (dir)
        snprintf(full, len, "%s/%s", dir, name);
    else
        snprintf(full, len, "%s", name);
    s->names[s->count++] = full;
    return RTE_OK;
}

static rte_status list_files(images_source *s, const char *path, char *msg, size_t msg_size)
{
    size_t capacity = 0;
    rte_status st = RTE_OK;
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
        DIR *d = opendir(path);
        if (!d) {
            rte_source_msgf(msg, msg_size, "%s: cannot open the directory", path);
            return RTE_ERR_IO;
        }
        struct dirent *e;
        while (st == RTE_OK && (e = readdir(d)) != NULL)
            if (e->d_name[0] != '.' && rte_image_path_has_image_extension(e->d_name))
                st = add_name(s, &capacity, path, e->d_name);
        closedir(d);
    } else {
        glob_t g;
        int r = glob(path, 0, NULL, &g);
        if (r == 0)
            for (size_t i = 0; st == RTE_OK && i < g.gl_pathc; i++)
                if (stat(g.gl_pathv[i], &sb) == 0 && S_ISREG(sb.st_mode))
                    st = add_name(s, &capacity, NULL, g.gl_pathv[i]);
        if (r == 0 || r == GLOB_NOMATCH)
            globfree(&g);
        if (r != 0 && r != GLOB_NOMATCH)
            st = RTE_ERR_NO_MEMORY;
    }
    if (st != RTE_OK) {
        rte_source_msgf(msg, msg_size, "%s: no memory for the file list", path);
        return st;
    }
    if (s->count == 0) {
        rte_source_msgf(msg, msg_size, "%s: no image files", path);
        return RTE_ERR_IO;
    }
    qsort(s->names, s->count, sizeof *s->names, compare_names);
    return RTE_OK;
}

static rte_status images_next(void *impl, rte_source_frame *out, int32_t timeout_ms, char *msg,
                              size_t msg_size)
{
    (void)timeout_ms; /* files are always ready */
    images_source *s = impl;
    if (s->rec.index >= s->count)
        return rte_recording_end(&s->rec, msg, msg_size);
    const char *name = s->names[s->rec.index];
    rte_image_info info;
    rte_status st =
        rte_image_read(s->reader, name, s->decoded, s->decoded_size, &info, msg, msg_size);
    if (st != RTE_OK)
        return rte_recording_bad(&s->rec, st);
    int32_t w = info.width, h = info.height;
    uint8_t *pixels = s->decoded;
    if (s->format == RTE_PIXEL_GREY && info.channels == 3) {
        rte_image_u8c3 bgr = {w, h, w * 3, s->decoded};
        rte_image_u8 gray = {w, h, w, s->converted};
        st = rte_color_bgr_to_gray(&bgr, &gray);
        pixels = s->converted;
    } else if (s->format == RTE_PIXEL_BGR24 && info.channels == 1) {
        size_t n = (size_t)w * (size_t)h;
        for (size_t i = 0; i < n; i++) {
            uint8_t v = s->decoded[i];
            s->converted[3 * i] = s->converted[3 * i + 1] = s->converted[3 * i + 2] = v;
        }
        pixels = s->converted;
    }
    rte_frame frame;
    if (st == RTE_OK)
        st = rte_frame_packed(&frame, s->format, w, h, pixels, s->decoded_size);
    if (st != RTE_OK) {
        rte_source_msgf(msg, msg_size, "%s: %s", name, rte_status_message(st));
        return rte_recording_bad(&s->rec, st);
    }
    rte_recording_deliver(&s->rec, out, &frame,
                          rte_recording_frame_ns(s->rec.index, s->fps_num, s->fps_den));
    return RTE_OK;
}

static void images_close(void *impl)
{
    images_source *s = impl;
    if (!s)
        return;
    for (size_t i = 0; i < s->count; i++)
        free(s->names[i]);
    free(s->names);
    rte_image_reader_destroy(s->reader);
    free(s->decoded);
    free(s->converted);
    free(s);
}

const rte_source_ops rte_images_source_ops = {"images", images_next, rte_recording_get_stats,
                                              images_close};

/* The largest width and height among the files' headers. */
static void probe_maxima(const images_source *s, int32_t *max_w, int32_t *max_h)
{
    *max_w = *max_h = 0;
    for (size_t i = 0; i < s->count; i++) {
        rte_image_info info;
        if (rte_image_probe(s->names[i], &info, NULL, 0) != RTE_OK)
            continue;
        if (info.width > *max_w)
            *max_w = info.width;
        if (info.height > *max_h)
            *max_h = info.height;
    }
}

rte_status rte_images_source_open(rte_source *source, const rte_images_source_config *config,
                                  char *msg, size_t msg_size)
{
    if (!source || !config || !config->path) {
        rte_source_msgf(msg, msg_size, "images: missing argument");
        return RTE_ERR_ARGUMENT;
    }
    memset(source, 0, sizeof *source);
    if (config->format != RTE_PIXEL_GREY && config->format != RTE_PIXEL_BGR24) {
        rte_source_msgf(msg, msg_size, "images: the format must be grey or bgr24");
        return RTE_ERR_ARGUMENT;
    }
    int32_t fps_num = config->fps_num, fps_den = config->fps_den;
    rte_status st = rte_recording_check_fps(&fps_num, &fps_den, msg, msg_size);
    if (st != RTE_OK)
        return st;
    images_source *s = calloc(1, sizeof *s);
    if (!s) {
        rte_source_msgf(msg, msg_size, "images: no memory");
        return RTE_ERR_NO_MEMORY;
    }
    rte_recording_init(&s->rec, rte_recording_frame_ns(1, fps_num, fps_den), images_rewind);
    s->format = config->format;
    s->fps_num = fps_num;
    s->fps_den = fps_den;
    st = list_files(s, config->path, msg, msg_size);
    int32_t max_w = config->max_width, max_h = config->max_height;
    if (st == RTE_OK && max_w == 0 && max_h == 0) {
        probe_maxima(s, &max_w, &max_h);
        if (max_w == 0) {
            rte_source_msgf(msg, msg_size, "%s: none of the files is a readable image",
                            config->path);
            st = RTE_ERR_FORMAT;
        }
    }
    if (st == RTE_OK && (max_w < 1 || max_h < 1 || max_w > RTE_MAX_SIDE || max_h > RTE_MAX_SIDE)) {
        rte_source_msgf(msg, msg_size, "images: bad maximum size %dx%d", max_w, max_h);
        st = RTE_ERR_ARGUMENT;
    }
    if (st == RTE_OK) {
        s->decoded_size = (size_t)max_w * (size_t)max_h * 3;
        s->reader = rte_image_reader_create(max_w, max_h);
        s->decoded = malloc(s->decoded_size);
        s->converted = malloc(s->decoded_size);
        if (!s->reader || !s->decoded || !s->converted) {
            rte_source_msgf(msg, msg_size, "images: no memory for %dx%d frames", max_w, max_h);
            st = RTE_ERR_NO_MEMORY;
        }
    }
    if (st != RTE_OK) {
        images_close(s);
        return st;
    }
    rte_recording_attach(source, &rte_images_source_ops, s, max_w, max_h, config->format);
    rte_source_msgf(msg, msg_size, "%zu image files, up to %dx%d", s->count, max_w, max_h);
    return RTE_OK;
}
