/* hb_figures_*: a test's notes kept in memory, then written into the pages' blocks (figures.h). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figures.h"
#include "readme.h"
#include "test.h"

typedef struct note {
    char test[64], isa[16];
    char *line;
} note;

static int enabled;
static note *notes;
static size_t count, capacity;

void hb_figures_enable(void) { enabled = 1; }
int hb_figures_enabled(void) { return enabled; }

static const char *isa_label(hb_isa isa) { return isa == HB_ISA_AUTO ? "-" : hb_isa_name(isa); }

void hb_figures_record(const char *test, hb_isa isa, const char *line)
{
    if (count == capacity) {
        size_t grown = capacity ? 2 * capacity : 256;
        note *more = realloc(notes, grown * sizeof *notes);
        if (!more)
            return;
        notes = more, capacity = grown;
    }
    note *n = &notes[count];
    snprintf(n->test, sizeof n->test, "%s", test);
    snprintf(n->isa, sizeof n->isa, "%s", isa_label(isa));
    n->line = malloc(strlen(line) + 1);
    if (n->line)
        strcpy(n->line, line), count++;
}

/* Whether the block's name (a test's, or a prefix ending in '*': every test it starts) covers test. */
static int names(const char *block, const char *test)
{
    size_t n = strlen(block);
    return n && block[n - 1] == '*' ? !strncmp(block, test, n - 1) : !strcmp(block, test);
}

/* The block's text: the notes of test on isa in a text fence, then the run; NULL when it left none. */
static char *block_text(const char *test, const char *isa, const char *run)
{
    size_t size = strlen(run) + 64;
    for (size_t k = 0; k < count; k++)
        if (names(test, notes[k].test) && !strcmp(notes[k].isa, isa))
            size += strlen(notes[k].line) + 1;
    if (size == strlen(run) + 64)
        return NULL;
    char *text = malloc(size);
    if (!text)
        return NULL;
    size_t used = (size_t)snprintf(text, size, "```text\n");
    for (size_t k = 0; k < count; k++)
        if (names(test, notes[k].test) && !strcmp(notes[k].isa, isa))
            used += (size_t)snprintf(text + used, size - used, "%s\n", notes[k].line);
    snprintf(text + used, size - used, "```\n%s (%s, %s)\n", run, test, isa);
    return text;
}

/* Rewrites each block of the page; the number of blocks that could not be written. */
static int write_page(const char *path, const char *run)
{
    char *page = hb_test_read_file(path, NULL);
    int failed = 0;
    for (const char *p = page ? strstr(page, HB_FIGURES_MARKER) : NULL; p; p = strstr(p + 1, HB_FIGURES_MARKER)) {
        char test[64], isa[16], word[16];
        if ((p > page && p[-1] != '\n') ||
            sscanf(p + strlen(HB_FIGURES_MARKER), "%63s %15s %15s", test, isa, word) != 3 || strcmp(word, "begin"))
            continue;
        char *text = block_text(test, isa, run);
        if (!text)
            continue;
        char begin[160], end[160];
        snprintf(begin, sizeof begin, "%s%s %s begin -->", HB_FIGURES_MARKER, test, isa);
        snprintf(end, sizeof end, "%s%s %s end -->", HB_FIGURES_MARKER, test, isa);
        if (bench_update_region(path, begin, end, text))
            failed++;
        else
            printf("wrote %s %s of %s\n", test, isa, path);
        free(text);
    }
    free(page);
    return failed;
}

int hb_figures_write(const char *run)
{
    int failed = write_page("README.md", run) + write_page("CONTRIBUTING.md", run);
    DIR *docs = opendir("docs");
    for (struct dirent *e; docs && (e = readdir(docs));) {
        size_t n = strlen(e->d_name);
        if (n > 3 && !strcmp(e->d_name + n - 3, ".md")) {
            char path[512];
            snprintf(path, sizeof path, "docs/%s", e->d_name);
            failed += write_page(path, run);
        }
    }
    if (docs)
        closedir(docs);
    return failed;
}
