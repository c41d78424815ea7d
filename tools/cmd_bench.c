/* touchdown bench: time the paper's cases with the constrained and penalty models. */
#include "cli.h"

int td_cmd_bench(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    td_cli_error("bench", "not available in this build yet");
    return TD_EXIT_FAILED;
}
