/* Writes the sample messages (tests/lcm/messages.h, seed 21) through the
 * publisher into an LCM log, for the Python and Java readers' tests:
 *   write_sample_log PATH */
#include <stdio.h>

#include "messages.h"
#include "rtedge/publish.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: write_sample_log PATH\n");
        return 2;
    }
    static samples s;
    samples_fill(&s, 21);
    rte_publish_limits limits = {64, 8, 16, 4, 4, SAMPLE_IMAGE_W * SAMPLE_IMAGE_H, 2};
    char url[4200], msg[RTE_PUBLISH_MESSAGE_SIZE];
    snprintf(url, sizeof url, "file://%s", argv[1]);
    rte_publisher *pub;
    rte_status st = rte_publisher_create(&pub, url, &limits, msg, sizeof msg);
    if (st == RTE_OK)
        st = rte_publish_lane(pub, "LANES", &s.lane, msg, sizeof msg);
    if (st == RTE_OK)
        st = rte_publish_grasp(pub, "GRASP", &s.grasp, msg, sizeof msg);
    if (st == RTE_OK)
        st = rte_publish_status(pub, "STATUS", &s.status, msg, sizeof msg);
    if (st == RTE_OK)
        st = rte_publish_params(pub, "PARAMS", &s.paramset, msg, sizeof msg);
    if (st == RTE_OK)
        st = rte_publish_image(pub, "IMAGE", &s.image, msg, sizeof msg);
    if (st != RTE_OK) {
        fprintf(stderr, "write_sample_log: %s\n", msg);
        return 1;
    }
    rte_publisher_destroy(pub);
    return 0;
}
