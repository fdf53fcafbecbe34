/* The documents: every relative link of README.md, CONTRIBUTING.md and each page of docs/ names a file of the
 * repository, and none of them points outside it or cites a file the repository does not hold; every
 * timing they print comes from a block `make bench` wrote. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "test.h"

/* Each Markdown link "](target)" of the file: a target that is not a URL or an anchor must exist,
 * relative to the file's folder, and stay inside the repository. */
static int check_links(hb_test_ctx *t, const char *dir, const char *path, const char *text)
{
    int links = 0;
    for (const char *p = strstr(text, "]("); p; p = strstr(p + 2, "](")) {
        const char *start = p + 2, *end = strpbrk(start, ")# \n");
        if (!end || end == start || !strncmp(start, "http://", 7) || !strncmp(start, "https://", 8) ||
            !strncmp(start, "mailto:", 7))
            continue;
        char target[512], full[1024];
        snprintf(target, sizeof target, "%.*s", (int)(end - start), start);
        snprintf(full, sizeof full, "%s%s", dir, target);
        struct stat st;
        links++;
        CHECK(t, stat(full, &st) == 0, "%s: link '%s' names no file", path, target);
        CHECK(t, strstr(target, "../") == NULL || (*dir && strncmp(target, "../", 3) == 0 && strstr(target + 3, "../") == NULL),
              "%s: link '%s' leaves the repository", path, target);
    }
    /* the project's conventions live in docs/conventions.md, not in the workplace's files beside the
     * repository (named here in two pieces, so that a search for them finds their users, not this check) */
    CHECK(t, strstr(text, "SPEC" ".md") == NULL && strstr(text, "shared" "/") == NULL,
          "%s cites a file outside the repository", path);
    return links;
}

static int is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/* A digit, an optional space, then ns, us or ms not followed by a letter ("12 ns", "1.5ms/sample"). */
static int is_timing(const char *p)
{
    if (!(p[0] >= '0' && p[0] <= '9'))
        return 0;
    const char *u = p[1] == ' ' ? p + 2 : p + 1;
    return (u[0] == 'n' || u[0] == 'u' || u[0] == 'm') && u[1] == 's' && !is_letter(u[2]);
}

/* The number of timings of the file outside the blocks `make bench` writes (between
 * "<!-- make bench: ... begin -->" and "<!-- make bench: ... end -->"), each reported. */
static int check_timings(hb_test_ctx *t, const char *dir, const char *path, const char *text)
{
    (void)dir;
    int generated = 0, line = 1, found = 0;
    for (const char *p = text; *p; p++) {
        if (*p == '\n')
            line++;
        if (!strncmp(p, "<!-- make bench:", 16)) {
            const char *close = strstr(p, "-->");
            int begins = close && close - p > 8 && !strncmp(close - 6, "begin ", 6);
            generated = begins;
        }
        if (!generated && is_timing(p)) {
            CHECK(t, 0, "%s:%d: a timing typed by hand ('%.8s'): point at the bench's generated tables", path, line, p);
            found++;
        }
    }
    return found;
}

typedef int (*page_check)(hb_test_ctx *t, const char *dir, const char *path, const char *text);

/* check(t, dir, path, text) of the page dir/name; 0 when it cannot be read (the test fails). */
static int check_page(hb_test_ctx *t, page_check check, const char *dir, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s%s", dir, name);
    char *text = hb_test_read_file(path, NULL);
    CHECK(t, text != NULL, "cannot read %s", path);
    int result = text ? check(t, dir, path, text) : 0;
    free(text);
    return result;
}

/* check for README.md, CONTRIBUTING.md and every page of docs/; the sum of its results. */
static int for_each_page(hb_test_ctx *t, page_check check, int *pages)
{
    int sum = check_page(t, check, "", "README.md") + check_page(t, check, "", "CONTRIBUTING.md");
    DIR *docs = opendir("docs");
    CHECK(t, docs != NULL, "no docs/ folder");
    *pages = 0;
    for (struct dirent *e; docs && (e = readdir(docs));) {
        size_t n = strlen(e->d_name);
        if (n > 3 && !strcmp(e->d_name + n - 3, ".md")) {
            sum += check_page(t, check, "docs/", e->d_name);
            (*pages)++;
        }
    }
    if (docs)
        closedir(docs);
    return sum;
}

static void test_links(hb_test_ctx *t)
{
    int pages, links = for_each_page(t, check_links, &pages);
    CHECK(t, pages >= 8, "docs/ holds %d pages", pages);
    hb_test_note(t, "%d relative links in README.md, CONTRIBUTING.md and %d docs pages", links, pages);
}

static void test_timings(hb_test_ctx *t)
{
    int pages, found = for_each_page(t, check_timings, &pages);
    hb_test_note(t, "%d hand-typed timings in README.md, CONTRIBUTING.md and %d docs pages", found, pages);
}

const hb_test hb_tests_docs[] = {
    { "docs_links_resolve", test_links, 0 },
    { "docs_timings_generated", test_timings, 0 },
    { NULL, NULL, 0 },
};
