/* The CSV rows of hairbsdf eval and pdf. */
#ifndef HB_CSV_H
#define HB_CSV_H

#include <stdio.h>

/* The next line of in, its newline kept, into *line (grown as needed, *cap bytes; free it after
 * the last): POSIX getline in C11. Returns its length (a NUL inside counts), -1 at the end. */
long csv_read_line(char **line, size_t *cap, FILE *in);

/* Strips leading and trailing white space in place. */
char *csv_trim(char *s);

/* theta_i,phi_i,theta_o,phi_o (columns 4) or theta_i,phi_i,theta_o,phi_o,h (columns 5, a near-field
 * model): comma-separated numbers (nan and inf parse, and become invalid samples). Modifies line.
 * Returns 0 for a malformed row. */
int csv_parse_row(char *line, float *row, int columns);

/* Whether a (trimmed) line is the header theta_i,phi_i,theta_o,phi_o (and h for columns 5). */
int csv_is_header(const char *line, int columns);

/* Whether a (trimmed) line is the header of these column names, comma-separated. */
int csv_is_named_header(const char *line, const char *const *names, int columns);

/* Past a UTF-8 byte-order mark at the start of a line (what some editors write first). */
char *csv_skip_bom(char *line);

#endif
