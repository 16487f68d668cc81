// Mission file for the CAN node (see mission_file.h): one JSON reader for the whole
// project, sva::json's, then the limits the CAN wire format adds.
#include "mission_file.h"

#include <stdio.h>

#include "sva/sva_json.h"
#include "sva/sva_can.h"

// The CAN mission frame's ranges are sva_frame.h's: a frame the JSON layer accepts always fits.
// One assertion per range, so a mismatch names the range that differs.
#define SVA_CAN_MISSION_FRAME_AGREES(name, cond) \
    typedef char sva_can_mission_frame_agrees_##name[(cond) ? 1 : -1]
SVA_CAN_MISSION_FRAME_AGREES(lat,
                             SVA_CAN_MISSION_FRAME_MAX_LAT_E7 == SVA_FRAME_MAX_LAT_DEG * 10000000L);
SVA_CAN_MISSION_FRAME_AGREES(lon,
                             SVA_CAN_MISSION_FRAME_MAX_LON_E7 == SVA_FRAME_MAX_LON_DEG * 10000000L);
SVA_CAN_MISSION_FRAME_AGREES(alt, SVA_CAN_MISSION_FRAME_MAX_ALT_CM == SVA_FRAME_MAX_ALT_CM);
SVA_CAN_MISSION_FRAME_AGREES(min_cell, SVA_CAN_MISSION_FRAME_MIN_CELL_CM == SVA_FRAME_MIN_CELL_CM);
SVA_CAN_MISSION_FRAME_AGREES(max_cell, SVA_CAN_MISSION_FRAME_MAX_CELL_CM == SVA_FRAME_MAX_CELL_CM);
SVA_CAN_MISSION_FRAME_AGREES(min_tick, SVA_CAN_MISSION_FRAME_MIN_TICK_MS == SVA_FRAME_MIN_TICK_MS);
SVA_CAN_MISSION_FRAME_AGREES(max_tick, SVA_CAN_MISSION_FRAME_MAX_TICK_MS == SVA_FRAME_MAX_TICK_MS);
SVA_CAN_MISSION_FRAME_AGREES(t0, SVA_CAN_MISSION_FRAME_MAX_T0_MS == SVA_FRAME_MAX_T0_MS);

sva_json_status_t sva_can_mission_load(const char* path, sva_mission_t* m, char* name,
                                       size_t name_size, char* err, size_t err_size)
{
    sva_can_mission_frame_t frame;
    bool has_frame;
    return sva_can_mission_load_frame(path, m, name, name_size, &frame, &has_frame, err, err_size);
}

sva_json_status_t sva_can_mission_load_frame(const char* path, sva_mission_t* m, char* name,
                                             size_t name_size, sva_can_mission_frame_t* frame,
                                             bool* has_frame, char* err, size_t err_size)
{
    char json_name[SVA_JSON_NAME_MAX + 1];
    sva_diag_t diag;
    sva_frame_t f;
    sva_mission_init(m);
    *has_frame = false;
    const sva_json_status_t loaded =
        sva_json_load_mission_frame(path, m, json_name, &f, has_frame, err, err_size);
    if (loaded != SVA_JSON_OK) {
        return loaded;
    }
    if (*has_frame) {
        frame->lat_e7 = f.lat_e7;
        frame->lon_e7 = f.lon_e7;
        frame->alt_cm = f.alt_cm;
        frame->cell_cm = f.cell_cm;
        frame->tick_ms = f.tick_ms;
        frame->t0_ms = f.t0_ms;
    }
    if (sva_can_mission_check(m, &diag) != SVA_CAN_OK) {
        (void)sva_diag_format(&diag, err, err_size);
        return SVA_JSON_ERR_INPUT;
    }
    if ((name != NULL) && (name_size > 0U)) {
        (void)snprintf(name, name_size, "%s", json_name);
    }
    return SVA_JSON_OK;
}
