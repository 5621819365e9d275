/* The params_t handler on well-formed messages with chosen values: the
 * input picks keys from the configuration table (or a bad name), a kind
 * (mostly the key's own) and values (boundaries, specials, any bits; for
 * text and choice keys a choice's name, a ROI or printable bytes); the
 * message is encoded with lcm-gen's encoder, decoded by the daemon's own
 * decoder (which must give back exactly what was encoded) and handled on a
 * running daemon, then a frame. */
#include "fuzz_daemon.h" /* first: fuzz.h sets _GNU_SOURCE */

#include <math.h>

#include "params.h"
#include "rtedge_params_t.h"

typedef struct input {
    const uint8_t *p;
    size_t left;
} input;

static uint8_t u8(input *in)
{
    if (!in->left)
        return 0;
    in->left--;
    return *in->p++;
}

static uint64_t u64(input *in)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = v << 8 | u8(in);
    return v;
}

static int64_t int_value(input *in)
{
    static const int64_t special[] = {0,
                                      1,
                                      -1,
                                      2,
                                      3,
                                      5,
                                      15,
                                      16,
                                      255,
                                      256,
                                      1000,
                                      2040,
                                      2041,
                                      16384,
                                      16385,
                                      65536,
                                      6912,
                                      6913,
                                      100000,
                                      67108864,
                                      67108865,
                                      INT32_MAX,
                                      (int64_t)INT32_MAX + 1,
                                      INT32_MIN,
                                      INT64_MAX,
                                      INT64_MIN};
    uint8_t how = u8(in);
    if (how < 128)
        return special[how % (sizeof special / sizeof special[0])];
    if (how < 192) {
        int64_t hi = u8(in);
        return (hi << 8 | u8(in)) - 1000;
    }
    return (int64_t)u64(in);
}

static double real_value(input *in)
{
    static const double special[] = {0,       0.1,   0.09999, 1,    2,      30,      1000,  10000,
                                     10000.5, 60000, -1,      -0.5, 1e-300, -1e-300, 1e300, 5e-324};
    uint8_t how = u8(in);
    if (how < 100)
        return special[how % (sizeof special / sizeof special[0])];
    if (how < 110)
        return how & 1 ? NAN : (how & 2 ? INFINITY : -INFINITY);
    if (how < 200) {
        int hi = u8(in), lo = u8(in);
        return (double)((hi << 8 | lo) - 1000) / (1 + u8(in) % 100);
    }
    uint64_t bits = u64(in);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

static size_t key_count(void)
{
    size_t n = 0;
    while (rted_config_key_at(n))
        n++;
    return n;
}

/* A text value: one of a few meaningful ones or up to 40 printable bytes
 * (blanks, '#' and ';' among them). */
static void text_value(input *in, char *text, size_t size)
{
    static const char *const special[] = {"fixed",
                                          "median",
                                          "otsu",
                                          "canny-close",
                                          "dark",
                                          "auto",
                                          "0,1;0.45,0.6;0.55,0.6;1,1",
                                          "0,0;1,0;1,1",
                                          "",
                                          " fixed",
                                          "0,1;0.5,0.5;1,1 # x",
                                          "9,9;9,9;9,9"};
    uint8_t pick = u8(in);
    if (pick < 128) {
        snprintf(text, size, "%s", special[pick % (sizeof special / sizeof special[0])]);
        return;
    }
    size_t n = pick % 41;
    if (n >= size)
        n = size - 1;
    for (size_t i = 0; i < n; i++)
        text[i] = (char)(0x20 + u8(in) % 95);
    text[n] = 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const bad_names[] = {
        "lane", "lane.", ".x", "nosuch.key", "lane.canny", "grasp.min_area2", "params.enabled"};
    static size_t n_keys;
    if (!n_keys)
        n_keys = key_count();
    input in = {data, size};
    static char names[RTED_PARAMS_MAX + 2][RTED_PARAM_NAME_MAX];
    static rtedge_param_t params[RTED_PARAMS_MAX + 2];
    static char texts[RTED_PARAMS_MAX + 2][48];
    uint8_t first = u8(&in);
    int32_t count = first < 240 ? 1 + first % 6 : 1 + first % (RTED_PARAMS_MAX + 2);
    for (int32_t i = 0; i < count; i++) {
        uint8_t pick = u8(&in);
        const rted_key *k = rted_config_key_at(pick % n_keys);
        if (pick >= 250)
            snprintf(names[i], sizeof names[i], "%s", bad_names[pick % 7]);
        else
            rted_key_get_name(k, names[i], sizeof names[i]);
        rted_key_type t = rted_key_get_type(k);
        int8_t right = t == RTED_KEY_REAL   ? RTEDGE_PARAM_T_KIND_REAL
                       : t == RTED_KEY_BOOL ? RTEDGE_PARAM_T_KIND_BOOL
                       : t == RTED_KEY_INT  ? RTEDGE_PARAM_T_KIND_INT
                                            : RTEDGE_PARAM_T_KIND_TEXT;
        uint8_t kind = u8(&in);
        params[i] =
            (rtedge_param_t){.name = names[i], .kind = kind < 200 ? right : (int8_t)(kind % 9 - 1)};
        params[i].int_value = int_value(&in);
        params[i].real_value = real_value(&in);
        text_value(&in, texts[i], sizeof texts[i]);
        params[i].text_value = texts[i];
    }
    rtedge_params_t m = {.utime = (int64_t)u64(&in),
                         .request_id = (int64_t)u64(&in),
                         .nparams = count,
                         .params = params};
    static uint8_t buf[2 * RTED_PARAMS_MAX_BYTES];
    int len = rtedge_params_t_encode(buf, 0, sizeof buf, &m);
    FUZZ_ASSERT(len > 0);

    /* The decoder gives back what lcm-gen encoded (or refuses a count over the bound). */
    static rted_params_request req;
    char why[RTED_MSG];
    bool decoded = rted_params_decode(buf, (size_t)len, &req, why, sizeof why);
    FUZZ_ASSERT(decoded == (count <= RTED_PARAMS_MAX));
    if (decoded) {
        FUZZ_ASSERT(req.count == count && req.request_id == m.request_id && req.utime == m.utime);
        for (int32_t i = 0; i < count; i++) {
            FUZZ_ASSERT(!strcmp(req.params[i].name, names[i]));
            FUZZ_ASSERT(req.params[i].kind == params[i].kind);
            FUZZ_ASSERT(req.params[i].int_value == params[i].int_value);
            FUZZ_ASSERT(!memcmp(&req.params[i].real_value, &params[i].real_value, sizeof(double)));
            FUZZ_ASSERT(!strcmp(req.params[i].text_value, texts[i]));
        }
    }

    rted_daemon *d = fuzz_daemon_reset();
    rted_counters before;
    rted_daemon_get_counters(d, &before);
    rted_daemon_handle_params(d, buf, (size_t)len);
    fuzz_daemon_check(d, &before);
    return 0;
}
