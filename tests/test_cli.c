#include "test.h"
const hb_test hb_tests_cli[] = { { NULL, NULL, 0 } };
