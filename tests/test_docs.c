/* The documents: every relative link of README.md, CONTRIBUTING.md and each page of docs/ names a file of the
 * repository, and none of them points outside it or cites a file the repository does not hold; every
 * timing they print comes from a block `make bench` wrote, and every other figure (an error in
 * e-notation, a percentage) either comes from such a block or is a value the code states (a bound a
 * test asserts, a constant of the library). */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "figures.h"
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

/* Length of the timing at p, a digit, an optional space, then ns, us or ms not followed by a letter
("12 ns", "1.5ms/sample"), counted from the digit; 0 when p starts none. */
static size_t timing_at(const char *text, const char *p)
{
    (void)text;
    if (!(p[0] >= '0' && p[0] <= '9'))
        return 0;
    const char *u = p[1] == ' ' ? p + 2 : p + 1;
    return (u[0] == 'n' || u[0] == 'u' || u[0] == 'm') && u[1] == 's' && !is_letter(u[2]) ? (size_t)(u + 2 - p) : 0;
}

/* 1 inside a generated block from p on, 0 outside it, -1 when p does not start a marker line
 * ("<!-- make bench: ... begin -->" to "<!-- make bench: ... end -->", and the same of
 * `make figures`, figures.h; a marker quoted inside a line is none). */
static int generated_marker(const char *text, const char *p)
{
    if ((p > text && p[-1] != '\n') ||
        (strncmp(p, "<!-- make bench:", 16) && strncmp(p, HB_FIGURES_MARKER, strlen(HB_FIGURES_MARKER))))
        return -1;
    const char *close = strstr(p, "-->");
    return close && close - p > 8 && !strncmp(close - 6, "begin ", 6);
}

/* The length of a figure at p that no page may print by hand, 0 when p starts none. */
typedef size_t (*figure_finder)(const char *text, const char *p);

/* The number of figures find finds in text outside generated blocks, each reported with advice. */
static int count_by_hand(hb_test_ctx *t, const char *path, const char *text, figure_finder find, const char *advice)
{
    int generated = 0, line = 1, found = 0;
    for (const char *p = text; *p; p++) {
        if (*p == '\n')
            line++;
        int marker = generated_marker(text, p);
        if (marker >= 0)
            generated = marker;
        size_t n = generated ? 0 : find(text, p);
        if (n) {
            CHECK(t, 0, "%s:%d: '%.*s' %s", path, line, (int)n, p, advice);
            found++;
            p += n - 1;
        }
    }
    return found;
}

static int check_timings(hb_test_ctx *t, const char *dir, const char *path, const char *text)
{
    (void)dir;
    return count_by_hand(t, path, text, timing_at, "is a timing typed by hand: point at the bench's generated tables");
}

/* Every number the code states: the numeric literals of the sources, headers, scripts and budget
 * files under src/, include/, tests/ (without its data and fuzz corpus), bench/ and tools/, sorted. */
typedef struct code_numbers {
    double *value;
    size_t count, capacity;
} code_numbers;

static int is_word(char c) { return is_letter(c) || (c >= '0' && c <= '9') || c == '_' || c == '.'; }

static void add_numbers(code_numbers *n, const char *text)
{
    for (const char *p = text; *p; p++) {
        if (!(*p >= '0' && *p <= '9') || (p > text && is_word(p[-1])) || (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')))
            continue;
        char *end;
        double v = strtod(p, &end);
        if (n->count == n->capacity) {
            n->capacity = n->capacity ? 2 * n->capacity : 4096;
            n->value = realloc(n->value, n->capacity * sizeof *n->value);
        }
        n->value[n->count++] = v;
        p = end - 1;
    }
}

static int has_suffix(const char *name, const char *suffix)
{
    size_t a = strlen(name), b = strlen(suffix);
    return a >= b && !strcmp(name + a - b, suffix);
}

static void add_tree(code_numbers *n, const char *dir)
{
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));) {
        if (e->d_name[0] == '.' || !strcmp(e->d_name, "data") || !strcmp(e->d_name, "corpus"))
            continue;
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0)
            continue;
        if (S_ISDIR(st.st_mode))
            add_tree(n, path);
        else if (has_suffix(path, ".c") || has_suffix(path, ".h") || has_suffix(path, ".sh") || has_suffix(path, ".txt")) {
            char *text = hb_test_read_file(path, NULL);
            if (text)
                add_numbers(n, text);
            free(text);
        }
    }
    if (d)
        closedir(d);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static code_numbers stated;

static int is_stated(double v)
{
    size_t lo = 0, hi = stated.count;
    while (lo < hi) { /* the first value >= v (1 - 1e-9) */
        size_t mid = (lo + hi) / 2;
        if (stated.value[mid] < v * (1.0 - 1e-9))
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < stated.count && stated.value[lo] <= v * (1.0 + 1e-9);
}

/* Length of the figure at p that the code does not state (a number in e-notation, "2.4e-5", or a
 * percentage, "0.5%", compared as a fraction); 0 when p starts none or the code states it. */
static size_t unstated_figure_at(const char *text, const char *p)
{
    if (!(*p >= '0' && *p <= '9') || (p > text && (is_word(p[-1]) || p[-1] == '-' || p[-1] == '+')))
        return 0;
    char *end;
    double v = strtod(p, &end);
    size_t n = 0;
    for (const char *q = p; q < end; q++)
        if (*q == 'e' || *q == 'E')
            n = (size_t)(end - p);
    if (!n && *end == '%')
        v /= 100.0, n = (size_t)(end + 1 - p);
    return n && !is_stated(v) ? n : 0;
}

static int check_figures(hb_test_ctx *t, const char *dir, const char *path, const char *text)
{
    (void)dir;
    return count_by_hand(t, path, text, unstated_figure_at,
                         "is measured by hand: take it from a generated block or state the bound a test asserts");
}

/* The number of `make figures` blocks of the file; each must name a test of the runner and an ISA
 * ("-" exactly when the test does not depend on one) and close. */
static int check_figure_blocks(hb_test_ctx *t, const char *dir, const char *path, const char *text)
{
    (void)dir;
    int blocks = 0;
    for (const char *p = strstr(text, HB_FIGURES_MARKER); p; p = strstr(p + 1, HB_FIGURES_MARKER)) {
        char name[64], isa[16], word[16], end[160];
        if ((p > text && p[-1] != '\n') ||
            sscanf(p + strlen(HB_FIGURES_MARKER), "%63s %15s %15s", name, isa, word) != 3 || strcmp(word, "begin"))
            continue;
        blocks++;
        const hb_test *test = hb_test_find(name);
        CHECK(t, test != NULL, "%s: a figures block names '%s', which is no test", path, name);
        int isa_known = !strcmp(isa, "-") ? 0 : -1;
        for (int i = HB_ISA_SCALAR; i < HB_ISA_COUNT; i++)
            if (!strcmp(isa, hb_isa_name((hb_isa)i)))
                isa_known = 1;
        CHECK(t, test == NULL || isa_known == (test->per_isa ? 1 : 0), "%s: the figures block of %s names ISA '%s'",
              path, name, isa);
        snprintf(end, sizeof end, "%s%s %s end -->", HB_FIGURES_MARKER, name, isa);
        CHECK(t, strstr(p, end) != NULL, "%s: the figures block of %s %s has no end marker", path, name, isa);
    }
    return blocks;
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

static void test_figures(hb_test_ctx *t)
{
    int blocks_pages, blocks = for_each_page(t, check_figure_blocks, &blocks_pages);
    static const char *const trees[] = { "src", "include", "tests", "bench", "tools" };
    for (size_t k = 0; k < sizeof trees / sizeof trees[0]; k++)
        add_tree(&stated, trees[k]);
    qsort(stated.value, stated.count, sizeof *stated.value, compare_doubles);
    CHECK(t, stated.count > 1000, "the code states %zu numbers", stated.count);
    int pages, found = for_each_page(t, check_figures, &pages);
    hb_test_note(t, "%d figures by hand in README.md, CONTRIBUTING.md and %d docs pages; %zu numbers in the code; "
                 "%d blocks of make figures", found, pages, stated.count, blocks);
    free(stated.value);
    stated = (code_numbers){ 0 };
}

const hb_test hb_tests_docs[] = {
    { "docs_links_resolve", test_links, 0 },
    { "docs_timings_generated", test_timings, 0 },
    { "docs_figures_stated", test_figures, 0 },
    { NULL, NULL, 0 },
};
