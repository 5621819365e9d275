/* The params_t handler on raw bytes, as they would arrive from the network:
 * rted_daemon_handle_params on a running daemon, then a frame. */
#include "fuzz_daemon.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    rted_daemon *d = fuzz_daemon_reset();
    rted_counters before;
    rted_daemon_get_counters(d, &before);
    rted_daemon_handle_params(d, data, size);
    fuzz_daemon_check(d, &before);
    return 0;
}
