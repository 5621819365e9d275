#include "unit.h"
#include "rtedge/hough.h"
static void dummy(void **state) { (void)state; }
int main(void) { const struct CMUnitTest t[] = { cmocka_unit_test(dummy) }; return cmocka_run_group_tests(t, NULL, NULL); }
