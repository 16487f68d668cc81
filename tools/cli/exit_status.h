/// exit_status.h -- the sva CLI's exit statuses (docs/cli.md) and the one place where
/// the JSON layer's statuses become them.
#ifndef SVA_EXIT_STATUS_H
#define SVA_EXIT_STATUS_H

#include <sva/sva_json.h>

/// 0 planned (or validated, or written), 1 failed (I/O, limits, the solver), 2 bad input.
enum { EXIT_PLANNED = 0, EXIT_FAILED = 1, EXIT_BAD_INPUT = 2 };

/// SVA_JSON_OK: EXIT_PLANNED; SVA_JSON_ERR_INPUT: EXIT_BAD_INPUT; any other status
/// (SVA_JSON_ERR_IO): EXIT_FAILED.
int sva_cli_exit_of_json(sva_json_status_t status);

#endif  // SVA_EXIT_STATUS_H
