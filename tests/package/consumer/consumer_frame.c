// Installed-tree consumer of sva::frame: a frame from JSON units, tick 0 in UTC, and the
// origin cell through PROJ.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sva/sva_frame.h"

int main(void)
{
    const sva_frame_units_t units = {47.3977419, 8.5455939, 30.0, 10.0, 1.0, "2026-06-01T08:00:00Z",
                                     0U};
    sva_frame_t frame;
    char err[SVA_FRAME_ERROR_SIZE];
    if (sva_frame_from_units(&units, &frame, err, sizeof err) != SVA_OK) {
        fprintf(stderr, "consumer_frame: %s\n", err);
        return 1;
    }
    char utc[SVA_FRAME_UTC_SIZE];
    if (frame.lat_e7 != 473977419 || !sva_frame_format_utc(frame.t0_ms, utc, sizeof utc) ||
        strcmp(utc, "2026-06-01T08:00:00.000Z") != 0) {
        fprintf(stderr, "consumer_frame: lat_e7 %ld, t0 %s\n", (long)frame.lat_e7, utc);
        return 1;
    }
    sva_frame_geodesy_t* g = sva_frame_geodesy_open(&frame, err, sizeof err);
    if (g == NULL) {
        fprintf(stderr, "consumer_frame: %s\n", err);
        return 1;
    }
    sva_frame_geo_t at;
    const int ok = sva_frame_cell_to_geo(g, 0, 0, &at) && fabs(at.lat_deg - 47.3977419) < 1e-9 &&
                   fabs(at.lon_deg - 8.5455939) < 1e-9;
    sva_frame_geodesy_close(g);
    if (!ok) {
        fprintf(stderr, "consumer_frame: cell (0, 0) is not the origin\n");
        return 1;
    }
    printf("consumer_frame: ok\n");
    return 0;
}
