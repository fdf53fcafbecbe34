/* Temporary files and runs of the hairbsdf tool, the same on POSIX systems and Windows: the tool's
 * command line (HB_TOOL, then the test's arguments) runs with stdin, stdout and stderr redirected
 * to files in the system's temporary directory. POSIX runs it through the shell, so HB_TOOL may
 * hold an emulator's prefix (qemu); Windows starts the process itself, without cmd.exe. Arguments
 * use double quotes only, which both parse alike. */
#include <stdlib.h>
#include <string.h>

#include "portable.h"
#include "test.h"

#ifdef _WIN32
#include <windows.h>
#endif

const char *hb_test_temp_dir(void)
{
    static char dir[512];
    if (dir[0])
        return dir;
    const char *env = getenv("TMPDIR");
#ifdef _WIN32
    char system_dir[MAX_PATH + 1];
    if (!env || !*env) {
        DWORD n = GetTempPathA(sizeof system_dir, system_dir);
        if (n > 0 && n < sizeof system_dir) {
            system_dir[n - 1] = system_dir[n - 1] == '\\' ? '\0' : system_dir[n - 1];
            env = system_dir;
        }
    }
#endif
    snprintf(dir, sizeof dir, "%s", env && *env ? env : "/tmp");
    return dir;
}

int hb_test_temp_file(char *path, size_t capacity, const char *suffix)
{
    int n = snprintf(path, capacity, "%s/hb_XXXXXX%s", hb_test_temp_dir(), suffix);
    if (n < 0 || (size_t)n >= capacity)
        return -1;
    int fd = mkstemps(path, (int)strlen(suffix));
    if (fd < 0)
        return -1;
    close(fd);
    return 0;
}

void hb_test_read_text(const char *path, char *text, size_t capacity)
{
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(text, 1, capacity - 1, f) : 0;
    text[n] = '\0';
    if (f)
        fclose(f);
}

#ifdef _WIN32
/* CreateProcess on "tool args" with the three files as its standard streams; the exit code, or -1. */
static int run_command(const char *tool, const char *args, const char *paths[3])
{
    SECURITY_ATTRIBUTES inherit = { sizeof inherit, NULL, TRUE };
    HANDLE files[3];
    for (int k = 0; k < 3; k++)
        files[k] = CreateFileA(paths[k], k ? GENERIC_WRITE : GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_WRITE, &inherit,
                               k ? CREATE_ALWAYS : OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, NULL);
    char command[4096];
    int n = snprintf(command, sizeof command, "%s %s", tool, args);
    for (char *c = command; *c && *c != ' '; c++) /* the program's own path, in Windows' separators */
        *c = *c == '/' ? '\\' : *c;
    STARTUPINFOA start;
    memset(&start, 0, sizeof start);
    start.cb = sizeof start;
    start.dwFlags = STARTF_USESTDHANDLES;
    start.hStdInput = files[0], start.hStdOutput = files[1], start.hStdError = files[2];
    PROCESS_INFORMATION process;
    DWORD code = (DWORD)-1;
    if (n > 0 && (size_t)n < sizeof command && files[0] != INVALID_HANDLE_VALUE && files[1] != INVALID_HANDLE_VALUE &&
        files[2] != INVALID_HANDLE_VALUE &&
        CreateProcessA(NULL, command, NULL, NULL, TRUE, 0, NULL, NULL, &start, &process)) {
        WaitForSingleObject(process.hProcess, INFINITE);
        GetExitCodeProcess(process.hProcess, &code);
        CloseHandle(process.hProcess);
        CloseHandle(process.hThread);
    }
    for (int k = 0; k < 3; k++)
        if (files[k] != INVALID_HANDLE_VALUE)
            CloseHandle(files[k]);
    return (int)code;
}
#else
static int run_command(const char *tool, const char *args, const char *paths[3])
{
    char command[4096];
    int n = snprintf(command, sizeof command, "%s %s < \"%s\" > \"%s\" 2> \"%s\"", tool, args, paths[0], paths[1],
                     paths[2]);
    if (n < 0 || (size_t)n >= sizeof command)
        return -1;
    int status = system(command);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
#endif

int hb_test_run_tool(hb_test_ctx *t, const char *args, const void *input, size_t input_size, hb_tool_run *r)
{
    r->status = -1, r->out[0] = r->err[0] = '\0';
    const char *tool = hb_test_tool(t);
    if (!tool)
        return 0;
    char paths[3][600];
    const char *names[3] = { paths[0], paths[1], paths[2] };
    for (int k = 0; k < 3; k++)
        if (hb_test_temp_file(paths[k], sizeof paths[k], "") != 0) {
            CHECK(t, 0, "no temporary file in %s", hb_test_temp_dir());
            while (k--)
                unlink(paths[k]);
            return 0;
        }
    FILE *in = fopen(paths[0], "wb");
    if (in) {
        fwrite(input, 1, input_size, in);
        fclose(in);
    }
    r->status = run_command(tool, args, names);
    hb_test_read_text(paths[1], r->out, sizeof r->out);
    hb_test_read_text(paths[2], r->err, sizeof r->err);
    for (int k = 0; k < 3; k++)
        unlink(paths[k]);
    return 1;
}
