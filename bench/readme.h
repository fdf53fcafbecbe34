/* The README's bench region: `make bench` rewrites the text between two marker lines of README.md
 * with its table, so the table there is always the last run's. */
#ifndef HB_BENCH_README_H
#define HB_BENCH_README_H

#define HB_README_BEGIN "<!-- make bench: begin -->"
#define HB_README_END "<!-- make bench: end -->"

/* Replaces what lies between the marker lines of the file at path (lines that are exactly the
 * markers; they stay) with text. Returns 0, or 1 with a message on stderr when the file or its
 * marker lines are missing. */
int bench_update_readme(const char *path, const char *text);

#endif
