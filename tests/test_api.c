#include "test.h"
const hb_test hb_tests_api[] = { { NULL, NULL, 0 } };
