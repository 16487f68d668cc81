// Cells to WGS84 and back through a PROJ pipeline (sva_frame.h): geodetic -> geocentric
// (cart) -> East-North-Up at the origin (topocentric); the inverse runs it backwards.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <proj.h>

#include "sva/sva_frame.h"

struct sva_frame_geodesy {
    PJ_CONTEXT* ctx;
    PJ* enu;  // forward: (lon, lat, h) in degrees -> (east, north, up) in metres
    sva_frame_t frame;
};

sva_frame_geodesy_t* sva_frame_geodesy_open(const sva_frame_t* frame, char* err, size_t err_size)
{
    char pipeline[384];
    sva_frame_geodesy_t* g;

    if (sva_frame_check(frame, err, err_size) != SVA_OK) {
        return NULL;
    }
    g = calloc(1U, sizeof *g);
    if (g == NULL) {
        (void)snprintf(err, err_size, "frame: out of memory");
        return NULL;
    }
    g->frame = *frame;
    g->ctx = proj_context_create();
    (void)snprintf(pipeline, sizeof pipeline,
                   "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
                   "+step +proj=cart +ellps=WGS84 "
                   "+step +proj=topocentric +ellps=WGS84 +lat_0=%.7f +lon_0=%.7f +h_0=0",
                   (double)frame->lat_e7 / 1e7, (double)frame->lon_e7 / 1e7);
    g->enu = (g->ctx != NULL) ? proj_create(g->ctx, pipeline) : NULL;
    if (g->enu == NULL) {
        (void)snprintf(err, err_size, "frame: PROJ cannot build the ENU pipeline: %s",
                       (g->ctx != NULL)
                           ? proj_context_errno_string(g->ctx, proj_context_errno(g->ctx))
                           : "no context");
        sva_frame_geodesy_close(g);
        return NULL;
    }
    return g;
}

void sva_frame_geodesy_close(sva_frame_geodesy_t* g)
{
    if (g == NULL) {
        return;
    }
    if (g->enu != NULL) {
        proj_destroy(g->enu);
    }
    if (g->ctx != NULL) {
        proj_context_destroy(g->ctx);
    }
    free(g);
}

bool sva_frame_cell_to_geo(sva_frame_geodesy_t* g, int32_t x, int32_t y, sva_frame_geo_t* out)
{
    const double cell_m = (double)g->frame.cell_cm / 100.0;
    const PJ_COORD enu = proj_coord((double)x * cell_m, (double)y * cell_m, 0.0, 0.0);
    const PJ_COORD geo = proj_trans(g->enu, PJ_INV, enu);
    if ((proj_errno(g->enu) != 0) || (geo.xyz.x == HUGE_VAL)) {
        proj_errno_reset(g->enu);
        return false;
    }
    out->lon_deg = geo.lpz.lam;
    out->lat_deg = geo.lpz.phi;
    out->alt_m = (double)g->frame.alt_cm / 100.0;
    return true;
}

bool sva_frame_geo_to_enu(sva_frame_geodesy_t* g, double lat_deg, double lon_deg, double* east_m,
                          double* north_m)
{
    const PJ_COORD geo = proj_coord(lon_deg, lat_deg, 0.0, 0.0);
    const PJ_COORD enu = proj_trans(g->enu, PJ_FWD, geo);
    if ((proj_errno(g->enu) != 0) || (enu.xyz.x == HUGE_VAL)) {
        proj_errno_reset(g->enu);
        return false;
    }
    *east_m = enu.xyz.x;
    *north_m = enu.xyz.y;
    return true;
}
