/* The blocks of README.md, CONTRIBUTING.md and docs/ that `make figures` writes: what one test
 * measured (its notes, in the long tier, on one ISA) between the lines
 * "<!-- make figures: TEST ISA begin -->" and "<!-- make figures: TEST ISA end -->", ISA being an
 * ISA's name or "-" for a test that does not depend on one; TEST may end in '*' for every test whose
 * name starts with what comes before it. Pages point at these blocks instead of
 * retyping a measurement. */
#ifndef HB_TEST_FIGURES_H
#define HB_TEST_FIGURES_H

#include "hairbsdf.h"

#define HB_FIGURES_MARKER "<!-- make figures: "

/* Keeps every note from here on (the runner's --figures). */
void hb_figures_enable(void);
int hb_figures_enabled(void);

/* One note of a test on an ISA (HB_ISA_AUTO: the test does not depend on one). */
void hb_figures_record(const char *test, hb_isa isa, const char *line);

/* Rewrites every block whose test and ISA left notes; the others stay as they are. Prints what it
 * wrote and returns the number of pages it could not rewrite. */
int hb_figures_write(const char *run);

#endif
