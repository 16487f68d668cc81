// The mission frame: ranges, units, UTC text (sva_frame.h).
#define _DEFAULT_SOURCE  // timegm() and gmtime_r() (glibc, musl and the BSDs have them)
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "sva/sva_frame.h"

static bool fail(char* err, size_t err_size, const char* text)
{
    if ((err != NULL) && (err_size > 0U)) {
        (void)snprintf(err, err_size, "%s", text);
    }
    return false;
}

bool sva_frame_check(const sva_frame_t* f, char* err, size_t err_size)
{
    char line[SVA_FRAME_ERROR_SIZE];
    const int64_t lat_max = (int64_t)SVA_FRAME_MAX_LAT_DEG * 10000000LL;
    const int64_t lon_max = (int64_t)SVA_FRAME_MAX_LON_DEG * 10000000LL;

    if (((int64_t)f->lat_e7 < -lat_max) || ((int64_t)f->lat_e7 > lat_max)) {
        (void)snprintf(line, sizeof line, "frame.lat: %.7f is outside [-%d, %d] degrees",
                       (double)f->lat_e7 / 1e7, SVA_FRAME_MAX_LAT_DEG, SVA_FRAME_MAX_LAT_DEG);
        return fail(err, err_size, line);
    }
    if (((int64_t)f->lon_e7 < -lon_max) || ((int64_t)f->lon_e7 > lon_max)) {
        (void)snprintf(line, sizeof line, "frame.lon: %.7f is outside [-%d, %d] degrees",
                       (double)f->lon_e7 / 1e7, SVA_FRAME_MAX_LON_DEG, SVA_FRAME_MAX_LON_DEG);
        return fail(err, err_size, line);
    }
    if ((f->alt_cm < 0) || (f->alt_cm > SVA_FRAME_MAX_ALT_CM)) {
        (void)snprintf(line, sizeof line, "frame.alt_m: %.2f is outside [0, %d] m",
                       (double)f->alt_cm / 100.0, SVA_FRAME_MAX_ALT_CM / 100);
        return fail(err, err_size, line);
    }
    if ((f->cell_cm < SVA_FRAME_MIN_CELL_CM) || (f->cell_cm > SVA_FRAME_MAX_CELL_CM)) {
        (void)snprintf(line, sizeof line, "frame.cell_m: %.2f is outside [0.1, %d] m",
                       (double)f->cell_cm / 100.0, SVA_FRAME_MAX_CELL_CM / 100);
        return fail(err, err_size, line);
    }
    if ((f->tick_ms < SVA_FRAME_MIN_TICK_MS) || (f->tick_ms > SVA_FRAME_MAX_TICK_MS)) {
        (void)snprintf(line, sizeof line, "frame.tick_s: %.3f is outside [0.001, %d] s",
                       (double)f->tick_ms / 1000.0, SVA_FRAME_MAX_TICK_MS / 1000);
        return fail(err, err_size, line);
    }
    if ((f->t0_ms < 0) || (f->t0_ms > SVA_FRAME_MAX_T0_MS)) {
        return fail(err, err_size,
                    "frame.t0: must be between 1970-01-01T00:00:00Z and 9999-12-31T23:59:59.999Z");
    }
    return true;
}

// value * scale rounded half away from zero into [lo, hi]; false when it is not finite
// or falls outside (the caller names the field).
static bool scaled(double value, double scale, double lo, double hi, int64_t* out)
{
    if (!isfinite(value) || (value < lo) || (value > hi)) {
        return false;
    }
    *out = (int64_t)llround(value * scale);
    return true;
}

bool sva_frame_from_units(const sva_frame_units_t* u, sva_frame_t* frame, char* err,
                          size_t err_size)
{
    char line[SVA_FRAME_ERROR_SIZE];
    sva_frame_t f;
    int64_t v[5];
    static const char* const names[5] = {"lat", "lon", "alt_m", "cell_m", "tick_s"};
    static const char* const units[5] = {"degrees", "degrees", "m", "m", "s"};
    const double values[5] = {u->lat, u->lon, u->alt_m, u->cell_m, u->tick_s};
    const double scale[5] = {1e7, 1e7, 100.0, 100.0, 1000.0};
    const double lo[5] = {-SVA_FRAME_MAX_LAT_DEG, -SVA_FRAME_MAX_LON_DEG, 0.0, 0.1, 0.001};
    const double hi[5] = {SVA_FRAME_MAX_LAT_DEG, SVA_FRAME_MAX_LON_DEG,
                          SVA_FRAME_MAX_ALT_CM / 100.0, SVA_FRAME_MAX_CELL_CM / 100.0,
                          SVA_FRAME_MAX_TICK_MS / 1000.0};

    for (int i = 0; i < 5; i++) {
        if (!scaled(values[i], scale[i], lo[i], hi[i], &v[i])) {
            (void)snprintf(line, sizeof line, "frame.%s: %g is outside [%g, %g] %s", names[i],
                           values[i], lo[i], hi[i], units[i]);
            return fail(err, err_size, line);
        }
    }
    f.lat_e7 = (int32_t)v[0];
    f.lon_e7 = (int32_t)v[1];
    f.alt_cm = (int32_t)v[2];
    f.cell_cm = (int32_t)v[3];
    f.tick_ms = (int32_t)v[4];
    if (u->t0 == NULL) {
        return fail(err, err_size, "frame.t0: missing (an ISO 8601 UTC date-time)");
    }
    if (!sva_frame_parse_utc(u->t0, "frame.t0", &f.t0_ms, err, err_size)) {
        return false;
    }
    if (!sva_frame_check(&f, err, err_size)) {
        return false;
    }
    *frame = f;
    return true;
}

static bool digits(const char* s, int n, int64_t* out)
{
    int64_t v = 0;
    for (int i = 0; i < n; i++) {
        if ((s[i] < '0') || (s[i] > '9')) {
            return false;
        }
        v = (v * 10) + (s[i] - '0');
    }
    *out = v;
    return true;
}

static bool leap(int64_t y)
{
    return ((y % 4) == 0) && (((y % 100) != 0) || ((y % 400) == 0));
}

bool sva_frame_parse_utc(const char* text, const char* field, int64_t* ms, char* err,
                         size_t err_size)
{
    static const int month_days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    char line[SVA_FRAME_ERROR_SIZE];
    int64_t y, mo, d, h, mi, s, frac = 0, off = 0;
    const char* p = text;

    (void)snprintf(line, sizeof line,
                   "%s: must be an ISO 8601 date-time with a UTC offset, e.g. "
                   "2026-06-01T08:00:00Z",
                   field);
    if ((strlen(text) < 20U) || !digits(p, 4, &y) || (p[4] != '-') || !digits(p + 5, 2, &mo) ||
        (p[7] != '-') || !digits(p + 8, 2, &d) || (p[10] != 'T') || !digits(p + 11, 2, &h) ||
        (p[13] != ':') || !digits(p + 14, 2, &mi) || (p[16] != ':') || !digits(p + 17, 2, &s)) {
        return fail(err, err_size, line);
    }
    p += 19;
    if (*p == '.') {
        // milliseconds from the first three digits, the rest rounds half away from zero
        int n = 0;
        p++;
        while ((*p >= '0') && (*p <= '9')) {
            if (n < 3) {
                frac = (frac * 10) + (*p - '0');
            } else if ((n == 3) && (*p >= '5')) {
                frac++;
            }
            n++;
            p++;
        }
        if (n == 0) {
            return fail(err, err_size, line);
        }
        for (; n < 3; n++) {
            frac *= 10;
        }
    }
    if ((p[0] == 'Z') && (p[1] == '\0')) {
        off = 0;
    } else if (((p[0] == '+') || (p[0] == '-')) && (strlen(p) == 6U) && (p[3] == ':')) {
        int64_t oh, om;
        if (!digits(p + 1, 2, &oh) || !digits(p + 4, 2, &om) || (oh > 23) || (om > 59)) {
            return fail(err, err_size, line);
        }
        off = ((oh * 60) + om) * 60000LL * ((p[0] == '-') ? -1 : 1);
    } else {
        return fail(err, err_size, line);
    }
    if ((mo < 1) || (mo > 12) || (d < 1) ||
        (d > (month_days[mo - 1] + (((mo == 2) && leap(y)) ? 1 : 0))) || (h > 23) || (mi > 59) ||
        (s > 59)) {
        (void)snprintf(line, sizeof line, "%s: \"%.40s\" is not a calendar date and time", field,
                       text);
        return fail(err, err_size, line);
    }
    struct tm tm;
    memset(&tm, 0, sizeof tm);
    tm.tm_year = (int)y - 1900;
    tm.tm_mon = (int)mo - 1;
    tm.tm_mday = (int)d;
    tm.tm_hour = (int)h;
    tm.tm_min = (int)mi;
    tm.tm_sec = (int)s;
    const int64_t t = ((int64_t)timegm(&tm) * 1000) + frac - off;
    if ((t < 0) || (t > SVA_FRAME_MAX_T0_MS)) {
        (void)snprintf(line, sizeof line,
                       "%s: must be between 1970-01-01T00:00:00Z and 9999-12-31T23:59:59.999Z",
                       field);
        return fail(err, err_size, line);
    }
    *ms = t;
    return true;
}

bool sva_frame_format_utc(int64_t ms, char* out, size_t size)
{
    struct tm tm;
    if ((ms < 0) || (ms > SVA_FRAME_MAX_T0_MS) || (size < (size_t)SVA_FRAME_UTC_SIZE)) {
        return false;
    }
    const time_t seconds = (time_t)(ms / 1000);
    if (gmtime_r(&seconds, &tm) == NULL) {
        return false;
    }
    (void)snprintf(out, size, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900,
                   tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, (int)(ms % 1000));
    return true;
}

int64_t sva_frame_tick_utc_ms(const sva_frame_t* frame, int64_t tick)
{
    return frame->t0_ms + (tick * (int64_t)frame->tick_ms);
}
