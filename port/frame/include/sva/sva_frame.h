/// sva_frame.h -- the mission frame (docs/flight-stack.md, SPEC section 3): what a cell
/// and a tick mean to a flight stack. Host and companion-computer code only (PROJ,
/// doubles); the core keeps cells and ticks and never sees a frame. CMake target
/// sva_frame (alias sva::frame).
///
/// A frame is stored in integers (sva_frame_t) so that every port carries it exactly:
/// 1e-7 degree, centimetres, milliseconds. Cell (x, y) is the point x * cell east and
/// y * cell north of the origin in the local East-North-Up tangent plane of the WGS84
/// ellipsoid at the origin (height 0); every waypoint flies alt above home (the launch
/// point). Tick t is the UTC instant t0 + t * tick.
///
/// Errors follow the ports' convention (DESIGN.md section 10): a fallible function returns
/// the core's sva_status_t (SVA_OK, SVA_ERR_ARGUMENT for a NULL pointer, SVA_ERR_INVALID
/// for a value it refuses) and writes the detail as one line into the caller's err
/// buffer (NULL allowed), since the core has no words for a frame's fields. The one
/// exception is sva_frame_geodesy_open, a constructor: its handle or NULL.
#ifndef SVA_FRAME_H
#define SVA_FRAME_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sva/sva.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Ranges of a frame, in the units of the mission JSON (docs/flight-stack.md).
#define SVA_FRAME_MAX_LAT_DEG 85       ///< |lat| <= 85 degrees
#define SVA_FRAME_MAX_LON_DEG 180      ///< |lon| <= 180 degrees
#define SVA_FRAME_MAX_ALT_CM  1000000  ///< alt_m in [0, 10000]
#define SVA_FRAME_MIN_CELL_CM 10       ///< cell_m in [0.1, 10000]
#define SVA_FRAME_MAX_CELL_CM 1000000
#define SVA_FRAME_MIN_TICK_MS 1  ///< tick_s in [0.001, 3600]
#define SVA_FRAME_MAX_TICK_MS 3600000
/// t0 from 1970-01-01T00:00:00Z to 9999-12-31T23:59:59.999Z, in ms since the epoch.
#define SVA_FRAME_MAX_T0_MS 253402300799999LL
/// The ends of t0's range and the rule of its form, as the messages write them.
#define SVA_FRAME_T0_MIN "1970-01-01T00:00:00Z"
#define SVA_FRAME_T0_MAX "9999-12-31T23:59:59.999Z"
#define SVA_FRAME_UTC_RULE                             \
    "must be an ISO 8601 date-time with a UTC offset " \
    "(YYYY-MM-DDThh:mm:ss[.fff] then Z or +hh:mm or -hh:mm)"
/// Room for any message this library writes, and for an ISO 8601 time it formats.
#define SVA_FRAME_ERROR_SIZE 320
#define SVA_FRAME_UTC_SIZE   32

/// A mission frame in integers.
typedef struct sva_frame {
    int32_t lat_e7;   ///< origin latitude, 1e-7 degree
    int32_t lon_e7;   ///< origin longitude, 1e-7 degree
    int32_t alt_cm;   ///< flight altitude above home, centimetres
    int32_t cell_cm;  ///< cell size, centimetres
    int32_t tick_ms;  ///< tick length, milliseconds
    int64_t t0_ms;    ///< the mission's tick 0, UTC milliseconds since 1970-01-01
} sva_frame_t;

/// A frame as the mission JSON writes it (degrees, metres, seconds, ISO 8601 text).
typedef struct sva_frame_units {
    double lat;
    double lon;
    double alt_m;
    double cell_m;
    double tick_s;
    const char* t0;
    /// Bit i (lat 0, lon 1, alt_m 2, cell_m 3, tick_s 4) set: value i was written as an
    /// integer. Only the messages use it (`got 86`, not `got 86.0`); 0 when unknown.
    unsigned integers;
} sva_frame_units_t;

/// A geographic position: WGS84 degrees, altitude above home in metres.
typedef struct sva_frame_geo {
    double lat_deg;
    double lon_deg;
    double alt_m;
} sva_frame_geo_t;

/// Checks every field against its range. Returns SVA_OK, SVA_ERR_ARGUMENT when frame is
/// NULL, or SVA_ERR_INVALID with one line in err naming the field, the rule and the
/// limit, as the Python tools word it ("frame.cell_m: must be >= 0.1, got 0.05"; the
/// value is the exact decimal of the stored integer).
SVA_NODISCARD sva_status_t sva_frame_check(const sva_frame_t* frame, char* err, size_t err_size);

/// Converts units into *frame, rounding half away from zero to the stored resolution on
/// the value's shortest decimal form (the literal as written, for up to 15 significant
/// digits: 47.12345675 -> 47.1234568), then checks it. Ranges apply to the value as
/// written. Returns SVA_OK; SVA_ERR_ARGUMENT when units or frame is NULL; SVA_ERR_INVALID
/// with one line in err (frame unchanged) when a value is not finite, out of range, t0
/// is missing, or t0 breaks a rule of sva_frame_parse_utc; the messages are the Python
/// tools' (docs/flight-stack.md), e.g. "frame.lat: must be <= 85, got 85.5".
SVA_NODISCARD sva_status_t sva_frame_from_units(const sva_frame_units_t* units, sva_frame_t* frame,
                                                char* err, size_t err_size);

/// Parses "YYYY-MM-DDTHH:MM:SS[.fff...](Z|+hh:mm|-hh:mm)" into ms since the epoch
/// (fractions past the millisecond rounded half away from zero; the range applies to the
/// instant as written). `field` names the value in the message. Returns SVA_OK;
/// SVA_ERR_ARGUMENT when text, field or ms is NULL; SVA_ERR_INVALID (*ms unchanged) with
/// one line in err naming the first rule broken, in this order: the form
/// (SVA_FRAME_UTC_RULE), a date of the calendar, the time of day, the UTC offset, the
/// range (SVA_FRAME_T0_MIN to SVA_FRAME_T0_MAX), e.g. `frame.t0: must be a date of the
/// calendar, got "2026-02-29T08:00:00Z"`.
SVA_NODISCARD sva_status_t sva_frame_parse_utc(const char* text, const char* field, int64_t* ms,
                                               char* err, size_t err_size);

/// Writes ms since the epoch as "YYYY-MM-DDTHH:MM:SS.fffZ" into out (at least
/// SVA_FRAME_UTC_SIZE bytes). False when ms is outside [0, SVA_FRAME_MAX_T0_MS].
bool sva_frame_format_utc(int64_t ms, char* out, size_t size);

/// The UTC instant of tick t, ms since the epoch.
int64_t sva_frame_tick_utc_ms(const sva_frame_t* frame, int64_t tick);

/// The conversions between cells and WGS84 positions (a PROJ pipeline, opened once).
typedef struct sva_frame_geodesy sva_frame_geodesy_t;

/// Opens the conversions of a checked frame. NULL with one line in err when the frame
/// is out of range or PROJ cannot build the pipeline. Close with sva_frame_geodesy_close.
sva_frame_geodesy_t* sva_frame_geodesy_open(const sva_frame_t* frame, char* err, size_t err_size);
void sva_frame_geodesy_close(sva_frame_geodesy_t* geodesy);

/// The centre of cell (x, y) at the frame's altitude. False when PROJ fails.
bool sva_frame_cell_to_geo(sva_frame_geodesy_t* geodesy, int32_t x, int32_t y,
                           sva_frame_geo_t* out);

/// The East and North offsets in metres of a WGS84 position from the origin.
bool sva_frame_geo_to_enu(sva_frame_geodesy_t* geodesy, double lat_deg, double lon_deg,
                          double* east_m, double* north_m);

#ifdef __cplusplus
}
#endif

#endif  // SVA_FRAME_H
