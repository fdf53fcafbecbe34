/* bench_update_region: a marked region of a Markdown file, rewritten in place (readme.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "readme.h"

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t size = 0, cap = 1 << 16;
    char *text = malloc(cap);
    for (size_t got; text && (got = fread(text + size, 1, cap - size - 1, f)) > 0;) {
        size += got;
        if (cap - size < 4096) {
            char *grown = realloc(text, 2 * cap);
            if (!grown)
                free(text);
            text = grown;
            cap *= 2;
        }
    }
    fclose(f);
    if (text)
        text[size] = '\0';
    return text;
}

/* The first line of text that is exactly marker. */
static char *marker_line(char *text, const char *marker)
{
    size_t n = strlen(marker);
    for (char *line = text; line && *line; line = strchr(line, '\n'), line = line ? line + 1 : NULL)
        if (strncmp(line, marker, n) == 0 && (line[n] == '\n' || line[n] == '\0'))
            return line;
    return NULL;
}

int bench_update_region(const char *path, const char *begin_marker, const char *end_marker, const char *text)
{
    char *old = read_all(path);
    char *begin = old ? marker_line(old, begin_marker) : NULL;
    char *after_begin = begin ? strchr(begin, '\n') : NULL;
    char *end = after_begin ? marker_line(after_begin + 1, end_marker) : NULL;
    if (!end) {
        fprintf(stderr, "%s has no %s ... %s region; its text is not written\n", path, begin_marker,
                end_marker);
        free(old);
        return 1;
    }
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    int failed = !f;
    if (f) {
        fwrite(old, 1, (size_t)(after_begin + 1 - old), f);
        fputs(text, f);
        fputs(end, f);
        failed = fclose(f) != 0 || rename(tmp, path) != 0;
    }
    if (failed)
        fprintf(stderr, "cannot rewrite %s\n", path);
    free(old);
    return failed;
}
