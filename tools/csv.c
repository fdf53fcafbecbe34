/* The CSV rows of hairbsdf eval (SPEC.md section 5). */
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
int csv_parse_row(char *line, float row[4])
{
    char *field = line;
    for (int c = 0; c < 4; c++) {
        char *comma = strchr(field, ',');
        if ((c < 3) != (comma != NULL))
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
