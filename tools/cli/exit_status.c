// The JSON layer's statuses as the CLI's exit statuses (exit_status.h).
#include "exit_status.h"

int sva_cli_exit_of_json(sva_json_status_t status)
{
    switch (status) {
    case SVA_JSON_OK:
        return EXIT_PLANNED;
    case SVA_JSON_ERR_INPUT:
        return EXIT_BAD_INPUT;
    case SVA_JSON_ERR_IO:
        break;
    }
    return EXIT_FAILED;
}
