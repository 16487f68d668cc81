// The geodesy of a frame library built without PROJ (cross builds for other targets,
// where only the units, ranges and UTC text are used): every conversion fails with a
// message saying why.
#include <stdio.h>

#include "sva/sva_frame.h"

sva_frame_geodesy_t* sva_frame_geodesy_open(const sva_frame_t* frame, char* err, size_t err_size)
{
    if (sva_frame_check(frame, err, err_size) != SVA_OK) {
        return NULL;
    }
    if ((err != NULL) && (err_size > 0U)) {
        (void)snprintf(err, err_size, "frame: built without PROJ: no cell to WGS84 conversion");
    }
    return NULL;
}

void sva_frame_geodesy_close(sva_frame_geodesy_t* geodesy)
{
    (void)geodesy;
}

bool sva_frame_cell_to_geo(sva_frame_geodesy_t* geodesy, int32_t x, int32_t y, sva_frame_geo_t* out)
{
    (void)geodesy;
    (void)x;
    (void)y;
    (void)out;
    return false;
}

bool sva_frame_geo_to_enu(sva_frame_geodesy_t* geodesy, double lat_deg, double lon_deg,
                          double* east_m, double* north_m)
{
    (void)geodesy;
    (void)lat_deg;
    (void)lon_deg;
    (void)east_m;
    (void)north_m;
    return false;
}
