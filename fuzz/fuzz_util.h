/* Helpers shared by the libFuzzer targets (fuzz/fuzz_*.c): a private directory for the files an
 * input becomes, writing them, a broken contract turned into abort(), and the one-line rule for
 * messages. */
#ifndef TD_FUZZ_UTIL_H
#define TD_FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

/* The path of file `name` in the process's private temporary directory (made on first use,
 * removed with the files named here at exit), in a static buffer per name slot (at most 4). */
const char *fuzz_path(const char *name);

/* Write data[0 .. n) to path; abort() when that fails (not a finding of the code under test). */
void fuzz_write(const char *path, const uint8_t *data, size_t n);

/* Print "fuzz: contract broken: WHAT (message: ...)" on fd 2 and abort(), so that libFuzzer keeps the input. */
void fuzz_contract_failed(const char *what, const char *message);

/* NULL if m is one non-empty line without control characters (what the tool prints on stderr),
 * else what is wrong with it. */
const char *fuzz_message_fault(const char *m);

/* 1 if the environment asks for each status and message on stderr (TD_FUZZ_VERBOSE=1). */
int fuzz_verbose(void);

/* The messages the code under test prints on stderr go nowhere unless fuzz_verbose(): only the
 * FILE stream is redirected, the sanitizers' reports and libFuzzer's output still reach fd 2. */
void fuzz_quiet_stderr(void);

#endif
