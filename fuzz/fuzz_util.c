/* Helpers shared by the libFuzzer targets (fuzz_util.h). */
#include "fuzz_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FUZZ_FILES 4

static char dir[256];
static char paths[FUZZ_FILES][320];

static void remove_files(void)
{
    int i;
    for (i = 0; i < FUZZ_FILES; i++)
        if (paths[i][0])
            unlink(paths[i]);
    rmdir(dir);
}

const char *fuzz_path(const char *name)
{
    const char *tmp = getenv("TMPDIR");
    char want[320];
    int i;
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "%s/td-fuzz.XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            perror("fuzz: mkdtemp");
            abort();
        }
        atexit(remove_files);
    }
    snprintf(want, sizeof want, "%s/%s", dir, name);
    for (i = 0; i < FUZZ_FILES; i++) {
        if (!paths[i][0])
            memcpy(paths[i], want, sizeof want);
        if (!strcmp(paths[i], want))
            return paths[i];
    }
    fprintf(stderr, "fuzz: more than %d file names\n", FUZZ_FILES);
    abort();
}

void fuzz_write(const char *path, const uint8_t *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || (n && fwrite(data, 1, n, f) != n) || fclose(f) != 0) {
        perror("fuzz: writing the input");
        abort();
    }
}

void fuzz_contract_failed(const char *what, const char *message)
{
    /* to fd 2 itself: the stderr stream may be silenced (fuzz_quiet_stderr) */
    dprintf(2, "fuzz: contract broken: %s (message: \"%s\")\n", what, message ? message : "(null)");
    abort();
}

const char *fuzz_message_fault(const char *m)
{
    const unsigned char *p;
    if (!m[0])
        return "an empty message";
    for (p = (const unsigned char *)m; *p; p++)
        if (*p == '\n' || *p == '\r')
            return "a message of more than one line";
        else if (*p < 0x20 && *p != '\t')
            return "a control character in the message";
    return NULL;
}

int fuzz_verbose(void)
{
    const char *v = getenv("TD_FUZZ_VERBOSE");
    return v && v[0] == '1';
}

void fuzz_quiet_stderr(void)
{
    static int done;
    FILE *null;
    if (done || fuzz_verbose())
        return;
    done = 1;
    if ((null = fopen("/dev/null", "w")))
        stderr = null; /* glibc's stderr is an assignable FILE *; fd 2 stays as it is */
}
