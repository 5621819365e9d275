/* rtedged's configuration: the INI reader (first byte odd: the rest is the
 * file) or `--set` overrides (first byte even: one per line), then the
 * cross-key checks, the checks against a frame size taken from the input,
 * and a round trip: a configuration that validates, printed as INI and read
 * back, is the same configuration (same hash). */
#include "fuzz.h"

#include "config.h"

/* The configuration printed into a memory file and read back. */
static void round_trip(const rted_config *c)
{
    char path[64], msg[RTED_MSG];
    int fd = fuzz_file(NULL, 0, path, sizeof path);
    FILE *f = fdopen(dup(fd), "w");
    FUZZ_ASSERT(f);
    rted_config_print(c, f);
    fclose(f);
    rted_config back;
    rted_config_defaults(&back);
    bool ok = rted_config_load(&back, path, msg, sizeof msg);
    if (!ok)
        fprintf(stderr, "fuzz: the printed configuration does not load: %s\n", msg);
    FUZZ_ASSERT(ok);
    FUZZ_ASSERT(rted_config_hash(&back) == rted_config_hash(c));
    FUZZ_ASSERT(!rted_config_fixed_change(c, &back, msg, sizeof msg));
    close(fd);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    rted_config c;
    rted_config_defaults(&c);
    char msg[RTED_MSG];
    bool ok = true;
    if (data[0] & 1) {
        char path[64];
        int fd = fuzz_file(data + 1, size - 1, path, sizeof path);
        ok = rted_config_load(&c, path, msg, sizeof msg);
        close(fd);
    } else {
        char text[4096];
        size_t n = size - 1 < sizeof text - 1 ? size - 1 : sizeof text - 1;
        memcpy(text, data + 1, n);
        text[n] = 0;
        for (char *line = text, *next; ok && line; line = next) {
            next = strchr(line, '\n');
            if (next)
                *next++ = 0;
            ok = rted_config_set(&c, line, "--set", msg, sizeof msg);
        }
    }
    fuzz_check_message(msg, sizeof msg);
    if (!ok || !rted_config_validate(&c, msg, sizeof msg))
        return 0;
    int32_t w = 1 + (int32_t)(data[0] >> 1) * 67, h = 1 + (int32_t)(data[size - 1]) * 31;
    rted_config_check_frame(&c, w, h, msg, sizeof msg);
    fuzz_check_message(msg, sizeof msg);
    round_trip(&c);
    return 0;
}
