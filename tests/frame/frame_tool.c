// Prints cells of a few frames as WGS84 through sva_frame (PROJ), one line per cell:
//   lat0 lon0 cell_m x y lat lon
// (degrees and metres; %.12f). test_pymap3d.py recomputes each with pymap3d.
#include <stdio.h>

#include "sva/sva_frame.h"

int main(void)
{
    // Frames: mid-latitude, southern hemisphere across the antimeridian, near the
    // latitude limit, the equator at the prime meridian; cells out to the int16 corner
    // (up to 1,159 km from the origin with 25 m cells). Far beyond any mission the two
    // libraries part: 1.6e-8 degree at 4,634 km (the equator frame with 100 m cells).
    static const sva_frame_t frames[] = {
        {473977419, 85455939, 3000, 1000, 1000, 1780300800000LL},
        {-338567844, 1799990000, 12000, 2500, 500, 1780300800000LL},
        {849000000, -1234567890, 5000, 10, 1, 0},
        {0, 0, 0, 2000, 1000, 0},
    };
    static const int cells[][2] = {{0, 0},     {1, 0},        {0, 1},         {-7, 13},
                                   {250, -40}, {-3000, 2999}, {32767, -32768}};
    for (size_t f = 0; f < sizeof frames / sizeof frames[0]; ++f) {
        char err[SVA_FRAME_ERROR_SIZE];
        sva_frame_geodesy_t* g = sva_frame_geodesy_open(&frames[f], err, sizeof err);
        if (g == NULL) {
            fprintf(stderr, "frame_tool: %s\n", err);
            return 1;
        }
        for (size_t c = 0; c < sizeof cells / sizeof cells[0]; ++c) {
            sva_frame_geo_t at;
            if (!sva_frame_cell_to_geo(g, cells[c][0], cells[c][1], &at)) {
                fprintf(stderr, "frame_tool: cell (%d, %d) failed\n", cells[c][0], cells[c][1]);
                sva_frame_geodesy_close(g);
                return 1;
            }
            printf("%.7f %.7f %.2f %d %d %.12f %.12f\n", (double)frames[f].lat_e7 / 1e7,
                   (double)frames[f].lon_e7 / 1e7, (double)frames[f].cell_cm / 100.0, cells[c][0],
                   cells[c][1], at.lat_deg, at.lon_deg);
        }
        sva_frame_geodesy_close(g);
    }
    return 0;
}
