/* Sets a V4L2 control by name on a device another process streams from
 * (vivid's error injection while rtedged runs):
 *   vm_ctl DEVICE CONTROL VALUE
 * Exits 0 when the control was set, 1 otherwise (the reason on stderr). */
#include <stdio.h>
#include <stdlib.h>

#include "rtedge/v4l2_source.h"

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: vm_ctl DEVICE CONTROL VALUE\n");
        return 2;
    }
    char msg[RTE_SOURCE_MESSAGE_SIZE] = "";
    rte_status st = rte_v4l2_set_device_control(argv[1], argv[2], (int32_t)strtol(argv[3], NULL, 0),
                                                NULL, msg, sizeof(msg));
    if (st != RTE_OK) {
        fprintf(stderr, "vm_ctl: %s: %s\n", rte_status_message(st), msg);
        return 1;
    }
    return 0;
}
