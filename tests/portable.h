/* The POSIX calls the tests make, on Windows (MinGW builds, run natively or under wine): temporary
 * files and directories, the environment, a command's exit status. Elsewhere the system's own. */
#ifndef HB_TESTS_PORTABLE_H
#define HB_TESTS_PORTABLE_H

#include <stdlib.h>

#ifdef _WIN32
#include <direct.h>
#include <fcntl.h>
#include <io.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static inline int setenv(const char *name, const char *value, int overwrite)
{
    (void)overwrite;
    return _putenv_s(name, value);
}

static inline int unsetenv(const char *name) { return _putenv_s(name, ""); }

/* The template's six X before its last `suffix` characters replaced until a new file is created. */
static inline int mkstemps(char *path, int suffix)
{
    char *x = path + strlen(path) - suffix - 6;
    for (unsigned attempt = 0; attempt < 1000; attempt++) {
        unsigned v = (unsigned)rand() * 2654435761u + attempt;
        for (int i = 0; i < 6; i++, v /= 36)
            x[i] = "abcdefghijklmnopqrstuvwxyz0123456789"[v % 36];
        int fd = _open(path, _O_CREAT | _O_EXCL | _O_RDWR | _O_BINARY, _S_IREAD | _S_IWRITE);
        if (fd >= 0)
            return fd;
    }
    return -1;
}

static inline char *mkdtemp(char *path)
{
    return _mktemp_s(path, strlen(path) + 1) == 0 && _mkdir(path) == 0 ? path : NULL;
}

#define WIFEXITED(status) 1 /* system() returns the command's exit code itself */
#define WEXITSTATUS(status) (status)
#else
#include <sys/wait.h>
#include <unistd.h>
#endif

#endif
