/* The camera listing as `rtedged --list-cameras` prints it. Exits 0 when
 * at least one camera was found, 1 otherwise. */
#include <stdio.h>

#include "rtedge/v4l2_source.h"

int main(void)
{
    int n = rte_list_cameras(stdout);
    printf("%d camera(s)\n", n);
    return n > 0 ? 0 : 1;
}
