// Mission file for the CAN node (see mission_file.h): one JSON reader for the whole
// project, sva::json's, then the limits the CAN wire format adds.
#include "mission_file.h"

#include <stdio.h>

#include "sva/sva_json.h"
#include "sva/sva_can.h"

int sva_can_mission_load(const char* path, sva_mission_t* m, char* name, size_t name_size,
                         char* err, size_t err_size)
{
    char json_name[SVA_JSON_NAME_MAX + 1];
    sva_diag_t diag;
    sva_mission_init(m);
    if (sva_json_load_mission(path, m, json_name, err, err_size) != SVA_JSON_OK) {
        return -1;
    }
    if (sva_can_mission_check(m, &diag) != SVA_CAN_OK) {
        (void)sva_diag_format(&diag, err, err_size);
        return -1;
    }
    if ((name != NULL) && (name_size > 0U)) {
        (void)snprintf(name, name_size, "%s", json_name);
    }
    return 0;
}
