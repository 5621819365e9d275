/* Overlay drawing on BGR images (see draw.h). */
#include "rtedge/draw.h"

#include "core/int_math.h"

#include <stddef.h>

#define MAX_THICKNESS 64
#define MAX_SCALE 16

/* 5x7 glyphs for ' ' .. '_' (lower case maps onto upper case): one byte
 * per row, bit 4 the leftmost pixel. */
static const uint8_t font[64][RTE_DRAW_GLYPH_H] = {
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* space */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ! (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* " (blank) */
    {0x0a, 0x0a, 0x1f, 0x0a, 0x1f, 0x0a, 0x0a}, /* # */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* $ (blank) */
    {0x19, 0x1a, 0x02, 0x04, 0x08, 0x0b, 0x13}, /* % */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* & (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ' (blank) */
    {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}, /* ( */
    {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}, /* ) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* * (blank) */
    {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}, /* + */
    {0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08}, /* , */
    {0x00, 0x00, 0x00, 0x0e, 0x00, 0x00, 0x00}, /* - */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}, /* . */
    {0x01, 0x02, 0x02, 0x04, 0x08, 0x08, 0x10}, /* / */
    {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}, /* 0 */
    {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}, /* 1 */
    {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}, /* 2 */
    {0x1e, 0x01, 0x01, 0x0e, 0x01, 0x01, 0x1e}, /* 3 */
    {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}, /* 4 */
    {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}, /* 5 */
    {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}, /* 6 */
    {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}, /* 7 */
    {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}, /* 8 */
    {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}, /* 9 */
    {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}, /* : */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ; (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* < (blank) */
    {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}, /* = */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* > (blank) */
    {0x0e, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}, /* ? */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* @ (blank) */
    {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}, /* A */
    {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}, /* B */
    {0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e}, /* C */
    {0x1c, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1c}, /* D */
    {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}, /* E */
    {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}, /* F */
    {0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f}, /* G */
    {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}, /* H */
    {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}, /* I */
    {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}, /* J */
    {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}, /* K */
    {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}, /* L */
    {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}, /* M */
    {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}, /* N */
    {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}, /* O */
    {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}, /* P */
    {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}, /* Q */
    {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}, /* R */
    {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}, /* S */
    {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}, /* T */
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}, /* U */
    {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}, /* V */
    {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a}, /* W */
    {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}, /* X */
    {0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04}, /* Y */
    {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}, /* Z */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* [ (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* backslash (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ] (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}, /* ^ (blank) */
    {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f}, /* _ */
};

static int image_ok(const rte_image_u8c3 *img)
{
    return img && img->buf && img->width >= 1 && img->height >= 1 && img->width <= RTE_MAX_SIDE &&
           img->height <= RTE_MAX_SIDE && img->stride >= 3 * img->width;
}

/* Fills the clipped rectangle [x0, x1] x [y0, y1]. */
static void fill_rect(rte_image_u8c3 *img, int64_t x0, int64_t y0, int64_t x1, int64_t y1,
                      rte_draw_color c)
{
    if (x0 < 0)
        x0 = 0;
    if (y0 < 0)
        y0 = 0;
    if (x1 > img->width - 1)
        x1 = img->width - 1;
    if (y1 > img->height - 1)
        y1 = img->height - 1;
    for (int64_t y = y0; y <= y1; y++) {
        uint8_t *p = img->buf + (ptrdiff_t)y * img->stride + 3 * x0;
        for (int64_t x = x0; x <= x1; x++, p += 3) {
            p[0] = c.b;
            p[1] = c.g;
            p[2] = c.r;
        }
    }
}

/* A square brush of side t centred on (x, y). */
static void brush(rte_image_u8c3 *img, int64_t x, int64_t y, int32_t t, rte_draw_color c)
{
    const int32_t lo = (t - 1) / 2;
    fill_rect(img, x - lo, y - lo, x - lo + t - 1, y - lo + t - 1, c);
}

enum { LEFT = 1, RIGHT = 2, TOP = 4, BOTTOM = 8 };

static int outcode(int64_t x, int64_t y, int64_t xmin, int64_t ymin, int64_t xmax, int64_t ymax)
{
    return (x < xmin ? LEFT : x > xmax ? RIGHT : 0) | (y < ymin ? TOP : y > ymax ? BOTTOM : 0);
}

/* Cohen-Sutherland clipping to the image grown by the brush; 0 when the
 * segment misses it. Keeps Bresenham's loop short for far-away endpoints. */
static int clip(int64_t *x0, int64_t *y0, int64_t *x1, int64_t *y1, int64_t xmin, int64_t ymin,
                int64_t xmax, int64_t ymax)
{
    int c0 = outcode(*x0, *y0, xmin, ymin, xmax, ymax),
        c1 = outcode(*x1, *y1, xmin, ymin, xmax, ymax);
    for (int iter = 0; iter < 8; iter++) {
        if (!(c0 | c1))
            return 1;
        if (c0 & c1)
            return 0;
        const int c = c0 ? c0 : c1;
        const int64_t dx = *x1 - *x0, dy = *y1 - *y0;
        int64_t x, y;
        if (c & (TOP | BOTTOM)) {
            y = (c & TOP) ? ymin : ymax;
            x = *x0 + rte_div_round64(dx * (y - *y0), dy);
        } else {
            x = (c & LEFT) ? xmin : xmax;
            y = *y0 + rte_div_round64(dy * (x - *x0), dx);
        }
        if (c == c0) {
            *x0 = x;
            *y0 = y;
            c0 = outcode(x, y, xmin, ymin, xmax, ymax);
        } else {
            *x1 = x;
            *y1 = y;
            c1 = outcode(x, y, xmin, ymin, xmax, ymax);
        }
    }
    return !(c0 | c1);
}

rte_status rte_draw_line(rte_image_u8c3 *img, int32_t x0, int32_t y0, int32_t x1, int32_t y1,
                         rte_draw_color color, int32_t thickness)
{
    if (!image_ok(img) || thickness < 1 || thickness > MAX_THICKNESS)
        return RTE_ERR_ARGUMENT;
    int64_t ax = x0, ay = y0, bx = x1, by = y1;
    if (!clip(&ax, &ay, &bx, &by, -thickness, -thickness, (int64_t)img->width - 1 + thickness,
              (int64_t)img->height - 1 + thickness))
        return RTE_OK;
    /* Bresenham over all octants */
    const int64_t dx = bx > ax ? bx - ax : ax - bx, sx = ax < bx ? 1 : -1;
    const int64_t dy = by > ay ? ay - by : by - ay, sy = ay < by ? 1 : -1;
    int64_t err = dx + dy;
    for (;;) {
        brush(img, ax, ay, thickness, color);
        if (ax == bx && ay == by)
            break;
        const int64_t e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            ax += sx;
        }
        if (e2 <= dx) {
            err += dx;
            ay += sy;
        }
    }
    return RTE_OK;
}

rte_status rte_draw_polyline(rte_image_u8c3 *img, const rte_point *pts, int32_t n, int closed,
                             rte_draw_color color, int32_t thickness)
{
    if (!image_ok(img) || n < 0 || (n > 0 && !pts) || thickness < 1 || thickness > MAX_THICKNESS)
        return RTE_ERR_ARGUMENT;
    if (n == 1)
        return rte_draw_line(img, pts[0].x, pts[0].y, pts[0].x, pts[0].y, color, thickness);
    for (int32_t i = 0; i + 1 < n; i++)
        rte_draw_line(img, pts[i].x, pts[i].y, pts[i + 1].x, pts[i + 1].y, color, thickness);
    if (closed && n > 2)
        rte_draw_line(img, pts[n - 1].x, pts[n - 1].y, pts[0].x, pts[0].y, color, thickness);
    return RTE_OK;
}

rte_status rte_draw_circle(rte_image_u8c3 *img, int32_t cx, int32_t cy, int32_t r,
                           rte_draw_color color, int32_t thickness)
{
    if (!image_ok(img) || r < 0 || thickness < 1 || thickness > MAX_THICKNESS)
        return RTE_ERR_ARGUMENT;
    /* entirely outside: nothing to draw (also bounds the loop below) */
    if ((int64_t)cx + r + thickness < 0 || (int64_t)cy + r + thickness < 0 ||
        (int64_t)cx - r - thickness >= img->width || (int64_t)cy - r - thickness >= img->height)
        return RTE_OK;
    /* midpoint circle, eight octants per step */
    int64_t x = r, y = 0, err = 1 - (int64_t)r;
    while (x >= y) {
        const int64_t px[8] = {cx + x, cx - x, cx + x, cx - x, cx + y, cx - y, cx + y, cx - y};
        const int64_t py[8] = {cy + y, cy + y, cy - y, cy - y, cy + x, cy + x, cy - x, cy - x};
        for (int k = 0; k < 8; k++)
            brush(img, px[k], py[k], thickness, color);
        y++;
        if (err < 0) {
            err += 2 * y + 1;
        } else {
            x--;
            err += 2 * (y - x) + 1;
        }
    }
    return RTE_OK;
}

rte_status rte_draw_dot(rte_image_u8c3 *img, int32_t cx, int32_t cy, int32_t r,
                        rte_draw_color color)
{
    if (!image_ok(img) || r < 0 || r > RTE_MAX_SIDE)
        return RTE_ERR_ARGUMENT;
    const int64_t rr = (int64_t)r * r + r;
    int64_t half = r;
    for (int64_t dy = 0; dy <= r; dy++) {
        while (half > 0 && half * half + dy * dy > rr)
            half--;
        fill_rect(img, (int64_t)cx - half, (int64_t)cy + dy, (int64_t)cx + half, (int64_t)cy + dy,
                  color);
        if (dy)
            fill_rect(img, (int64_t)cx - half, (int64_t)cy - dy, (int64_t)cx + half,
                      (int64_t)cy - dy, color);
    }
    return RTE_OK;
}

static const uint8_t *glyph(char ch)
{
    unsigned c = (unsigned char)ch;
    if (c >= 'a' && c <= 'z')
        c -= 'a' - 'A';
    return (c >= 32 && c < 96) ? font[c - 32] : font[0];
}

rte_status rte_draw_text(rte_image_u8c3 *img, int32_t x, int32_t y, const char *text,
                         rte_draw_color color, int32_t scale)
{
    if (!image_ok(img) || !text || scale < 1 || scale > MAX_SCALE)
        return RTE_ERR_ARGUMENT;
    int64_t ox = x;
    for (const char *p = text; *p && ox < img->width; p++, ox += (int64_t)RTE_DRAW_CELL_W * scale) {
        const uint8_t *g = glyph(*p);
        for (int32_t row = 0; row < RTE_DRAW_GLYPH_H; row++)
            for (int32_t col = 0; col < RTE_DRAW_GLYPH_W; col++)
                if (g[row] & (0x10 >> col)) {
                    const int64_t px = ox + (int64_t)col * scale,
                                  py = (int64_t)y + (int64_t)row * scale;
                    fill_rect(img, px, py, px + scale - 1, py + scale - 1, color);
                }
    }
    return RTE_OK;
}

void rte_draw_text_size(const char *text, int32_t scale, int32_t *width, int32_t *height)
{
    int32_t n = 0;
    while (text && text[n])
        n++;
    if (width)
        *width = n > 0 ? (n * RTE_DRAW_CELL_W - 1) * scale : 0;
    if (height)
        *height = RTE_DRAW_GLYPH_H * scale;
}
