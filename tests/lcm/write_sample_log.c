/* Writes the sample messages (tests/lcm/messages.h, seed 21) through the
 * publisher into an LCM log, for the Python and Java readers' tests:
 *   write_sample_log PATH */
#include <stdio.h>

#include "messages.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: write_sample_log PATH\n");
        return 2;
    }
    static samples s;
    samples_fill(&s, 21);
    rte_publish_limits limits = {64, 8, 16, 4, 4, SAMPLE_IMAGE_W * SAMPLE_IMAGE_H, 2, 0};
    char url[4200], msg[RTE_PUBLISH_MESSAGE_SIZE];
    snprintf(url, sizeof url, "file://%s", argv[1]);
    rte_publisher *pub;
    rte_status st = rte_publisher_create(&pub, url, &limits, msg, sizeof msg);
    for (int i = 0; i < 5 && st == RTE_OK; i++)
        st = sample_publish(pub, i, &s, msg, sizeof msg);
    if (st != RTE_OK) {
        fprintf(stderr, "write_sample_log: %s\n", msg);
        return 1;
    }
    rte_publisher_destroy(pub);
    return 0;
}
