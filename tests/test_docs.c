/* The documents: every relative link of README.md, CONTRIBUTING.md and each page of docs/ names a file of the
 * repository, and none of them points outside it or cites a file the repository does not hold. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "test.h"

/* Each Markdown link "](target)" of the file: a target that is not a URL or an anchor must exist,
 * relative to the file's folder, and stay inside the repository. */
static int check_links(hb_test_ctx *t, const char *dir, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s%s", dir, name);
    char *text = hb_test_read_file(path, NULL);
    CHECK(t, text != NULL, "cannot read %s", path);
    if (!text)
        return 0;
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
    free(text);
    return links;
}

static void test_links(hb_test_ctx *t)
{
    int links = check_links(t, "", "README.md") + check_links(t, "", "CONTRIBUTING.md");
    DIR *docs = opendir("docs");
    CHECK(t, docs != NULL, "no docs/ folder");
    int pages = 0;
    for (struct dirent *e; docs && (e = readdir(docs));) {
        size_t n = strlen(e->d_name);
        if (n > 3 && !strcmp(e->d_name + n - 3, ".md")) {
            links += check_links(t, "docs/", e->d_name);
            pages++;
        }
    }
    if (docs)
        closedir(docs);
    CHECK(t, pages >= 8, "docs/ holds %d pages", pages);
    hb_test_note(t, "%d relative links in README.md, CONTRIBUTING.md and %d docs pages", links, pages);
}

const hb_test hb_tests_docs[] = {
    { "docs_links_resolve", test_links, 0 },
    { NULL, NULL, 0 },
};
