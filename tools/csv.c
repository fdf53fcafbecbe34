/* The CSV rows of hairbsdf eval and pdf. */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"

char *csv_trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

/* Four comma-separated numbers (nan and inf parse, and become invalid samples). */
long csv_read_line(char **line, size_t *cap, FILE *in)
{
    size_t length = 0;
    int c;
    while ((c = getc(in)) != EOF) {
        if (length + 2 > *cap) {
            size_t grown = *cap ? 2 * *cap : 256;
            char *bigger = realloc(*line, grown);
            if (!bigger)
                return -1;
            *line = bigger, *cap = grown;
        }
        (*line)[length++] = (char)c;
        if (c == '\n')
            break;
    }
    if (length == 0)
        return -1;
    (*line)[length] = '\0';
    return (long)length;
}

int csv_parse_row(char *line, float *row, int columns)
{
    char *field = line;
    for (int c = 0; c < columns; c++) {
        char *comma = strchr(field, ',');
        if ((c < columns - 1) != (comma != NULL))
            return 0;
        if (comma)
            *comma = '\0';
        char *s = csv_trim(field), *end;
        errno = 0;
        double x = strtod(s, &end);
        if (end == s || *end != '\0')
            return 0;
        row[c] = (float)x;
        if (comma)
            field = comma + 1;
    }
    return 1;
}

int csv_is_header(const char *line, int columns)
{
    static const char *const names[5] = { "theta_i", "phi_i", "theta_o", "phi_o", "h" };
    return csv_is_named_header(line, names, columns);
}

/* The names, comma-separated, each trimmed of white space. */
int csv_is_named_header(const char *line, const char *const *names, int columns)
{
    const char *field = line;
    for (int c = 0; c < columns; c++) {
        while (isspace((unsigned char)*field))
            field++;
        size_t length = strlen(names[c]);
        if (strncmp(field, names[c], length) != 0)
            return 0;
        field += length;
        while (isspace((unsigned char)*field))
            field++;
        if (*field != (c < columns - 1 ? ',' : '\0'))
            return 0;
        field++;
    }
    return 1;
}

char *csv_skip_bom(char *line)
{
    return (unsigned char)line[0] == 0xef && (unsigned char)line[1] == 0xbb && (unsigned char)line[2] == 0xbf ? line + 3
                                                                                                             : line;
}
