/* Regions of Markdown files that `make bench` rewrites: the text between two marker lines, so the
 * tables there are always the last full run's (docs/benchmarks.md the full table, README.md a
 * summary). */
#ifndef HB_BENCH_README_H
#define HB_BENCH_README_H

#define HB_REPORT_BEGIN "<!-- make bench: begin -->"
#define HB_REPORT_END "<!-- make bench: end -->"
#define HB_SUMMARY_BEGIN "<!-- make bench: summary begin -->"
#define HB_SUMMARY_END "<!-- make bench: summary end -->"
#define HB_EFFECTS_BEGIN "<!-- make bench: effects begin -->"
#define HB_EFFECTS_END "<!-- make bench: effects end -->"

/* Replaces what lies between the marker lines begin and end of the file at path (lines that are
 * exactly the markers; they stay) with text. Returns 0, or 1 with a message on stderr when the file
 * or its marker lines are missing. */
int bench_update_region(const char *path, const char *begin_marker, const char *end_marker, const char *text);

#endif
