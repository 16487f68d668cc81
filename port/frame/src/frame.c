// The mission frame: ranges, units, UTC text (sva_frame.h).
#define _DEFAULT_SOURCE  // timegm() and gmtime_r() (glibc, musl and the BSDs have them)
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sva/sva_frame.h"

// Every refusal: one line in err (when there is room), SVA_ERR_INVALID.
static sva_status_t fail(char* err, size_t err_size, const char* text)
{
    if ((err != NULL) && (err_size > 0U)) {
        (void)snprintf(err, err_size, "%s", text);
    }
    return SVA_ERR_INVALID;
}

// --- numbers as text -----------------------------------------------------------------

// The shortest decimal that reads back as v (at most 17 significant digits): its digits
// without a point (no trailing zeros) into d, and e such that v = 0.d * 10^e. v finite.
static void shortest(double v, char d[24], int* e)
{
    char text[40];
    for (int p = 1; p <= 17; p++) {
        (void)snprintf(text, sizeof text, "%.*e", p - 1, v);
        if ((strtod(text, NULL) == v) || (p == 17)) {
            break;
        }
    }
    // text is "[-]D[.DDD]e[+-]XX"
    const char* t = (text[0] == '-') ? (text + 1) : text;
    int n = 0;
    for (; (*t != 'e') && (*t != '\0'); t++) {
        if ((*t >= '0') && (*t <= '9')) {
            d[n++] = *t;
        }
    }
    d[n] = '\0';
    *e = (*t == 'e') ? ((int)strtol(t + 1, NULL, 10) + 1) : 1;
    while ((n > 1) && (d[n - 1] == '0')) {
        d[--n] = '\0';
    }
    if ((n == 1) && (d[0] == '0')) {
        *e = 1;
    }
}

// v as Python's repr() writes a float (the Python tools' messages): positional with at
// least one fraction digit from 1e-4 up to 1e16, else "d.ddde+XX".
static void float_text(double v, char* out, size_t size)
{
    char d[24] = {0};
    int e = 0;
    if (!isfinite(v)) {
        (void)snprintf(out, size, "%s", isnan(v) ? "nan" : ((v < 0) ? "-inf" : "inf"));
        return;
    }
    shortest(v, d, &e);
    const int n = (int)strlen(d);
    const int x = e - 1;  // v = d.ddd * 10^x
    char body[48];
    if ((x < -4) || (x >= 16)) {
        (void)snprintf(body, sizeof body, "%c%s%se%c%02d", d[0], (n > 1) ? "." : "", d + 1,
                       (x < 0) ? '-' : '+', (x < 0) ? -x : x);
    } else {
        // positional: the digits with the point after the first e of them (zeros pad)
        size_t k = 0;
        if (e <= 0) {
            body[k++] = '0';
            body[k++] = '.';
            for (int i = 0; i < -e; i++) {
                body[k++] = '0';
            }
            for (int i = 0; i < n; i++) {
                body[k++] = d[i];
            }
        } else {
            for (int i = 0; i < e; i++) {
                if (i < n) {
                    body[k++] = d[i];
                } else {
                    body[k++] = '0';
                }
            }
            body[k++] = '.';
            if (e >= n) {
                body[k++] = '0';
            }
            for (int i = e; i < n; i++) {
                body[k++] = d[i];
            }
        }
        body[k] = '\0';
    }
    (void)snprintf(out, size, "%s%s", signbit(v) ? "-" : "", body);
}

// v rounded half away from zero to `places` decimals, on its shortest decimal form (the
// literal as written, for up to 15 significant digits): v * 10^places as an integer.
// |v| * 10^places must fit an int64 (the ranges are checked first).
static int64_t rounded(double v, int places)
{
    char d[24] = {0};
    int e = 0;
    shortest(v, d, &e);
    const int keep = e + places;  // digits of d before the rounding point
    const int n = (int)strlen(d);
    int64_t r = 0;
    for (int i = 0; i < keep; i++) {
        r = (r * 10) + ((i < n) ? (d[i] - '0') : 0);
    }
    if ((keep >= 0) && (keep < n) && (d[keep] >= '5')) {
        r++;
    }
    return signbit(v) ? -r : r;
}

// A scaled integer as its exact decimal: 850000001 at 7 places is "85.0000001".
static void scaled_text(int64_t v, int places, char* out, size_t size)
{
    int64_t unit = 1;
    for (int i = 0; i < places; i++) {
        unit *= 10;
    }
    const uint64_t a = (v < 0) ? (uint64_t)(-(v + 1)) + 1U : (uint64_t)v;
    char frac[24];
    uint64_t rest = a % (uint64_t)unit;
    for (int i = places - 1; i >= 0; i--) {
        frac[i] = (char)('0' + (int)(rest % 10U));
        rest /= 10U;
    }
    frac[places] = '\0';
    int n = places;
    while ((n > 0) && (frac[n - 1] == '0')) {
        frac[--n] = '\0';
    }
    (void)snprintf(out, size, "%s%llu%s%s", (v < 0) ? "-" : "",
                   (unsigned long long)(a / (uint64_t)unit), (n > 0) ? "." : "", frac);
}

// text as a JSON string with every byte outside printable ASCII escaped (the Python
// tools' json.dumps). text is UTF-8; a byte that does not decode is written as \u00XX.
static void quoted(const char* text, char* out, size_t size)
{
    size_t o = 0;
    const unsigned char* p = (const unsigned char*)text;
    char piece[16];
    if (size < 3U) {
        if (size > 0U) {
            out[0] = '\0';
        }
        return;
    }
    out[o++] = '"';
    while (*p != '\0') {
        uint32_t c = *p;
        int len = 1;
        if ((c >= 0xC0U) && (c < 0xE0U) && ((p[1] & 0xC0U) == 0x80U)) {
            c = ((c & 0x1FU) << 6) | (p[1] & 0x3FU);
            len = 2;
        } else if ((c >= 0xE0U) && (c < 0xF0U) && ((p[1] & 0xC0U) == 0x80U) &&
                   ((p[2] & 0xC0U) == 0x80U)) {
            c = ((c & 0x0FU) << 12) | ((uint32_t)(p[1] & 0x3FU) << 6) | (p[2] & 0x3FU);
            len = 3;
        } else if ((c >= 0xF0U) && (c < 0xF8U) && ((p[1] & 0xC0U) == 0x80U) &&
                   ((p[2] & 0xC0U) == 0x80U) && ((p[3] & 0xC0U) == 0x80U)) {
            c = ((c & 0x07U) << 18) | ((uint32_t)(p[1] & 0x3FU) << 12) |
                ((uint32_t)(p[2] & 0x3FU) << 6) | (p[3] & 0x3FU);
            len = 4;
        }
        if (c == '"') {
            (void)snprintf(piece, sizeof piece, "\\\"");
        } else if (c == '\\') {
            (void)snprintf(piece, sizeof piece, "\\\\");
        } else if (c == '\n') {
            (void)snprintf(piece, sizeof piece, "\\n");
        } else if (c == '\r') {
            (void)snprintf(piece, sizeof piece, "\\r");
        } else if (c == '\t') {
            (void)snprintf(piece, sizeof piece, "\\t");
        } else if (c == '\b') {
            (void)snprintf(piece, sizeof piece, "\\b");
        } else if (c == '\f') {
            (void)snprintf(piece, sizeof piece, "\\f");
        } else if ((c >= 0x20U) && (c < 0x7FU)) {
            (void)snprintf(piece, sizeof piece, "%c", (char)c);
        } else if (c >= 0x10000U) {
            c -= 0x10000U;
            (void)snprintf(piece, sizeof piece, "\\u%04x\\u%04x", 0xD800U + (c >> 10),
                           0xDC00U + (c & 0x3FFU));
        } else {
            (void)snprintf(piece, sizeof piece, "\\u%04x", (unsigned)c);
        }
        const size_t k = strlen(piece);
        if ((o + k + 2U) > size) {
            break;  // the message keeps what fits
        }
        memcpy(out + o, piece, k);
        o += k;
        p += len;
    }
    out[o++] = '"';
    out[o] = '\0';
}

// --- ranges ---------------------------------------------------------------------------

// The numbers of a frame: name, decimals of the resolution, range in those units.
typedef struct {
    const char* name;
    int places;
    int64_t lo;
    int64_t hi;
    const char* lo_text;
    const char* hi_text;
} field_t;

static const field_t FIELDS[5] = {
    {"lat", 7, -(int64_t)SVA_FRAME_MAX_LAT_DEG * 10000000LL,
     (int64_t)SVA_FRAME_MAX_LAT_DEG * 10000000LL, "-85", "85"},
    {"lon", 7, -(int64_t)SVA_FRAME_MAX_LON_DEG * 10000000LL,
     (int64_t)SVA_FRAME_MAX_LON_DEG * 10000000LL, "-180", "180"},
    {"alt_m", 2, 0, SVA_FRAME_MAX_ALT_CM, "0", "10000"},
    {"cell_m", 2, SVA_FRAME_MIN_CELL_CM, SVA_FRAME_MAX_CELL_CM, "0.1", "10000"},
    {"tick_s", 3, SVA_FRAME_MIN_TICK_MS, SVA_FRAME_MAX_TICK_MS, "0.001", "3600"},
};

static sva_status_t out_of_range(const field_t* f, bool below, const char* got, char* err,
                                 size_t err_size)
{
    char line[SVA_FRAME_ERROR_SIZE];
    (void)snprintf(line, sizeof line, "frame.%s: must be %s %s, got %s", f->name,
                   below ? ">=" : "<=", below ? f->lo_text : f->hi_text, got);
    return fail(err, err_size, line);
}

static sva_status_t t0_failure(const char* field, const char* rule, const char* text, char* err,
                               size_t err_size)
{
    char line[SVA_FRAME_ERROR_SIZE];
    char got[SVA_FRAME_ERROR_SIZE / 2];
    quoted(text, got, sizeof got);
    (void)snprintf(line, sizeof line, "%s: %s, got %s", field, rule, got);
    return fail(err, err_size, line);
}

sva_status_t sva_frame_check(const sva_frame_t* f, char* err, size_t err_size)
{
    if (f == NULL) {
        return SVA_ERR_ARGUMENT;
    }
    const int64_t v[5] = {f->lat_e7, f->lon_e7, f->alt_cm, f->cell_cm, f->tick_ms};
    char got[48];

    for (int i = 0; i < 5; i++) {
        if ((v[i] < FIELDS[i].lo) || (v[i] > FIELDS[i].hi)) {
            scaled_text(v[i], FIELDS[i].places, got, sizeof got);
            return out_of_range(&FIELDS[i], v[i] < FIELDS[i].lo, got, err, err_size);
        }
    }
    if ((f->t0_ms < 0) || (f->t0_ms > SVA_FRAME_MAX_T0_MS)) {
        char line[SVA_FRAME_ERROR_SIZE];
        (void)snprintf(line, sizeof line, "frame.t0: must be %s, got %lld ms after %s",
                       (f->t0_ms < 0) ? ">= " SVA_FRAME_T0_MIN : "<= " SVA_FRAME_T0_MAX,
                       (long long)f->t0_ms, SVA_FRAME_T0_MIN);
        return fail(err, err_size, line);
    }
    return SVA_OK;
}

sva_status_t sva_frame_from_units(const sva_frame_units_t* u, sva_frame_t* frame, char* err,
                                  size_t err_size)
{
    sva_frame_t f;
    int64_t v[5];
    sva_status_t status;
    if ((u == NULL) || (frame == NULL)) {
        return SVA_ERR_ARGUMENT;
    }
    const double values[5] = {u->lat, u->lon, u->alt_m, u->cell_m, u->tick_s};
    char got[48];

    for (int i = 0; i < 5; i++) {
        const field_t* fd = &FIELDS[i];
        // The range applies to the value as written; every limit is a multiple of the
        // resolution, so the rounded value stays in range.
        const double lo = strtod(fd->lo_text, NULL);
        const double hi = strtod(fd->hi_text, NULL);
        if ((u->integers & (1U << i)) != 0U) {
            (void)snprintf(got, sizeof got, "%.0f", values[i]);
        } else {
            float_text(values[i], got, sizeof got);
        }
        if (!isfinite(values[i])) {
            char line[SVA_FRAME_ERROR_SIZE];
            (void)snprintf(line, sizeof line, "frame.%s: must be a finite number, got %s", fd->name,
                           got);
            return fail(err, err_size, line);
        }
        if ((values[i] < lo) || (values[i] > hi)) {
            return out_of_range(fd, values[i] < lo, got, err, err_size);
        }
        v[i] = rounded(values[i], fd->places);
    }
    f.lat_e7 = (int32_t)v[0];
    f.lon_e7 = (int32_t)v[1];
    f.alt_cm = (int32_t)v[2];
    f.cell_cm = (int32_t)v[3];
    f.tick_ms = (int32_t)v[4];
    if (u->t0 == NULL) {
        return fail(err, err_size, "frame: missing key \"t0\"");
    }
    status = sva_frame_parse_utc(u->t0, "frame.t0", &f.t0_ms, err, err_size);
    if (status == SVA_OK) {
        status = sva_frame_check(&f, err, err_size);
    }
    if (status == SVA_OK) {
        *frame = f;
    }
    return status;
}

// --- UTC text -------------------------------------------------------------------------

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

sva_status_t sva_frame_parse_utc(const char* text, const char* field, int64_t* ms, char* err,
                                 size_t err_size)
{
    static const int month_days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int64_t y = 0;
    int64_t mo = 0;
    int64_t d = 0;
    int64_t h = 0;
    int64_t mi = 0;
    int64_t s = 0;
    int64_t frac = 0;
    int64_t oh = 0;
    int64_t om = 0;
    bool finer = false;  // nonzero digits past the millisecond
    bool round_up = false;
    const char* p = text;

    if ((text == NULL) || (field == NULL) || (ms == NULL)) {
        return SVA_ERR_ARGUMENT;
    }

    // The form: YYYY-MM-DDThh:mm:ss[.f...] then Z or +hh:mm or -hh:mm.
    bool form = (strlen(text) >= 20U) && digits(p, 4, &y) && (p[4] == '-') &&
                digits(p + 5, 2, &mo) && (p[7] == '-') && digits(p + 8, 2, &d) && (p[10] == 'T') &&
                digits(p + 11, 2, &h) && (p[13] == ':') && digits(p + 14, 2, &mi) &&
                (p[16] == ':') && digits(p + 17, 2, &s);
    if (form) {
        p += 19;
        if (*p == '.') {
            int n = 0;
            p++;
            while ((*p >= '0') && (*p <= '9')) {
                if (n < 3) {
                    frac = (frac * 10) + (*p - '0');
                } else {
                    round_up = round_up || ((n == 3) && (*p >= '5'));
                    finer = finer || (*p != '0');
                }
                n++;
                p++;
            }
            form = n > 0;
            for (; n < 3; n++) {
                frac *= 10;
            }
        }
    }
    const bool zulu = form && (p[0] == 'Z') && (p[1] == '\0');
    if (form && !zulu) {
        form = ((p[0] == '+') || (p[0] == '-')) && (strlen(p) == 6U) && digits(p + 1, 2, &oh) &&
               (p[3] == ':') && digits(p + 4, 2, &om);
    }
    if (!form) {
        return t0_failure(field, SVA_FRAME_UTC_RULE, text, err, err_size);
    }
    if ((y < 1) || (mo < 1) || (mo > 12) || (d < 1) ||
        (d > (month_days[mo - 1] + (((mo == 2) && leap(y)) ? 1 : 0)))) {
        return t0_failure(field, "must be a date of the calendar", text, err, err_size);
    }
    if ((h > 23) || (mi > 59) || (s > 59)) {
        return t0_failure(field, "must have a time of day within 00:00:00..23:59:59", text, err,
                          err_size);
    }
    if ((oh > 23) || (om > 59)) {
        return t0_failure(field, "must have a UTC offset within -23:59..+23:59", text, err,
                          err_size);
    }
    const int64_t off = ((oh * 60) + om) * 60000LL * ((p[0] == '-') ? -1 : 1);
    struct tm tm;
    memset(&tm, 0, sizeof tm);
    tm.tm_year = (int)y - 1900;
    tm.tm_mon = (int)mo - 1;
    tm.tm_mday = (int)d;
    tm.tm_hour = (int)h;
    tm.tm_min = (int)mi;
    tm.tm_sec = (int)s;
    // whole milliseconds; the exact instant is t plus `finer` digits below 1 ms
    const int64_t t = ((int64_t)timegm(&tm) * 1000) + frac - off;
    if (t < 0) {
        return t0_failure(field, "must be >= " SVA_FRAME_T0_MIN, text, err, err_size);
    }
    if ((t > SVA_FRAME_MAX_T0_MS) || ((t == SVA_FRAME_MAX_T0_MS) && finer)) {
        return t0_failure(field, "must be <= " SVA_FRAME_T0_MAX, text, err, err_size);
    }
    *ms = t + (round_up ? 1 : 0);  // half away from zero (t >= 0)
    return SVA_OK;
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
