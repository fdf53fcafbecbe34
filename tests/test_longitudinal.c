#include "test.h"
const hb_test hb_tests_longitudinal[] = { { NULL, NULL, 0 } };
