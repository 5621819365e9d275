/* What the daemon's in-process tests share: a synthetic objects sequence
 * (two bright rectangles moving on a dark table) written as a mono Y4M, the
 * test configuration and opening a daemon on it. Include after cmocka.h. */
#ifndef RTEDGE_TEST_DAEMON_FIXTURES_H
#define RTEDGE_TEST_DAEMON_FIXTURES_H

#include <stdio.h>
#include <string.h>

#include "config.h"
#include "daemon.h"

/* ---- the objects sequence: two bright rectangles moving on a dark table ---- */

#define OW 160
#define OH 120
typedef struct rect {
    int x0, y0, w, h;
} rect;

static inline void objects_at(int k, rect r[2])
{
    r[0] = (rect){20 + k, 20, 40, 24};
    r[1] = (rect){100, 50 + k, 30, 30};
}

static inline void objects_frame(int k, uint8_t *img)
{
    rect r[2];
    objects_at(k, r);
    memset(img, 40, OW * OH);
    for (int i = 0; i < 2; i++)
        for (int y = r[i].y0; y < r[i].y0 + r[i].h; y++)
            memset(img + y * OW + r[i].x0, 200, (size_t)r[i].w);
}

/* damage: 0 none; 1 a corrupt FRAME header at frame 3 and a truncated last frame. */
static inline void write_objects_y4m(const char *file, int frames, int damage)
{
    FILE *f = fopen(file, "wb");
    assert_non_null(f);
    fprintf(f, "YUV4MPEG2 W%d H%d F30:1 Ip A1:1 Cmono\n", OW, OH);
    static uint8_t img[OW * OH];
    for (int k = 0; k < frames; k++) {
        objects_frame(k, img);
        fputs(damage && k == 3 ? "FRAMX\n" : "FRAME\n", f);
        fwrite(img, 1, damage && k == frames - 1 ? OW * OH / 2 : OW * OH, f);
    }
    fclose(f);
}

static inline void base_config(rted_config *c, const char *source, const char *url)
{
    rted_config_defaults(c);
    assert_true(strlen(source) < sizeof c->source_path && strlen(url) < sizeof c->lcm_url);
    memcpy(c->source_path, source, strlen(source) + 1);
    memcpy(c->lcm_url, url, strlen(url) + 1);
    c->pace = RTED_PACE_FAST;
    c->deadline_ms = 1000; /* generous: sanitizer builds are slow */
}

static inline rted_daemon *open_daemon(const rted_config *c, const char *config_path)
{
    rted_daemon *d;
    char msg[RTED_MSG];
    bool ok = rted_daemon_open(&d, c, config_path, msg, sizeof msg);
    if (!ok)
        print_error("%s\n", msg);
    assert_true(ok);
    return d;
}

/* A looping objects sequence of `frames` frames written to y4m, and the test
 * configuration on it (memq://). */
static inline void looping_objects_config(rted_config *c, const char *y4m, int frames)
{
    write_objects_y4m(y4m, frames, 0);
    base_config(c, y4m, "memq://");
    c->loop = true;
}

#endif
