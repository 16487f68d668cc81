// The mission frame library (port/frame): ranges with their messages, units rounded
// half away from zero, ISO 8601 UTC text both ways, and cells to WGS84 checked against
// PROJ's geodesic (Karney's algorithm, a different computation than the ENU pipeline).
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "unity.h"
#include <geodesic.h>

#include "sva/sva_frame.h"

static sva_frame_units_t units(void)
{
    sva_frame_units_t u = {48.1372, 11.5755, 60.0, 100.0, 1.0, "2026-06-01T08:00:00Z", 0U};
    return u;
}

static void check_fails(const sva_frame_units_t* u, const char* expected)
{
    char err[SVA_FRAME_ERROR_SIZE] = "";
    sva_frame_t f;
    memset(&f, 0x5a, sizeof f);
    const sva_frame_t before = f;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_frame_from_units(u, &f, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING(expected, err);
    TEST_ASSERT_EQUAL_MEMORY(&before, &f, sizeof f);
}

void test_units_round_half_away_from_zero(void)
{
    sva_frame_units_t u = units();
    char err[SVA_FRAME_ERROR_SIZE] = "";
    sva_frame_t f;
    u.lat = -33.00000005;  // half a unit of 1e-7 degree: away from zero
    u.cell_m = 12.345;     // 1234.5 cm -> 1235
    u.tick_s = 0.0005;     // below the millisecond: out of range
    check_fails(&u, "frame.tick_s: must be >= 0.001, got 0.0005");
    u.tick_s = 2.0005;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_frame_from_units(&u, &f, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(-330000001, f.lat_e7);
    TEST_ASSERT_EQUAL_INT(1235, f.cell_cm);
    TEST_ASSERT_EQUAL_INT(2001, f.tick_ms);
    TEST_ASSERT_EQUAL_INT(6000, f.alt_cm);
}

// Ties on the literal as written, where the double is just below the tie (value * scale
// in floating point rounds the other way), and just above it.
void test_ties_round_on_the_decimal_text(void)
{
    static const struct {
        double lat, lon, alt_m, cell_m, tick_s;
        int32_t lat_e7, lon_e7, alt_cm, cell_cm, tick_ms;
    } cases[] = {
        {47.12345675, 8.00000005, 0.125, 1.005, 1.0005, 471234568, 80000001, 13, 101, 1001},
        {-47.12345675, -8.00000005, 2.675, 0.145, 0.0015, -471234568, -80000001, 268, 15, 2},
        {47.123456749999995, 179.99999995, 9999.995, 9999.994, 3599.9995, 471234567, 1800000000,
         1000000, 999999, 3600000},
        {-0.00000005, 0.00000004, 0.004, 0.105, 1.0004, -1, 0, 0, 11, 1000},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sva_frame_units_t u = units();
        char err[SVA_FRAME_ERROR_SIZE] = "";
        sva_frame_t f;
        u.lat = cases[i].lat;
        u.lon = cases[i].lon;
        u.alt_m = cases[i].alt_m;
        u.cell_m = cases[i].cell_m;
        u.tick_s = cases[i].tick_s;
        TEST_ASSERT_EQUAL_INT(SVA_OK, sva_frame_from_units(&u, &f, err, sizeof err));
        TEST_ASSERT_EQUAL_INT(cases[i].lat_e7, f.lat_e7);
        TEST_ASSERT_EQUAL_INT(cases[i].lon_e7, f.lon_e7);
        TEST_ASSERT_EQUAL_INT(cases[i].alt_cm, f.alt_cm);
        TEST_ASSERT_EQUAL_INT(cases[i].cell_cm, f.cell_cm);
        TEST_ASSERT_EQUAL_INT(cases[i].tick_ms, f.tick_ms);
    }
    // t0: the fraction past the millisecond on the text, half away from zero
    int64_t ms = -1;
    char err[SVA_FRAME_ERROR_SIZE] = "";
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("1970-01-01T00:00:00.0005Z", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(1, ms);
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("1970-01-01T00:00:00.00049999Z", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, ms);
}

void test_every_range_is_named(void)
{
    sva_frame_units_t u = units();
    u.lat = 85.5;
    check_fails(&u, "frame.lat: must be <= 85, got 85.5");
    u.lat = 85.0000001;
    check_fails(&u, "frame.lat: must be <= 85, got 85.0000001");
    u.lat = -86.0;
    check_fails(&u, "frame.lat: must be >= -85, got -86.0");
    u.integers = 1U;  // written as an integer
    check_fails(&u, "frame.lat: must be >= -85, got -86");
    u = units();
    u.lon = -180.01;
    check_fails(&u, "frame.lon: must be >= -180, got -180.01");
    u = units();
    u.lon = 1e300;
    check_fails(&u, "frame.lon: must be <= 180, got 1e+300");
    u = units();
    u.alt_m = -0.01;
    check_fails(&u, "frame.alt_m: must be >= 0, got -0.01");
    u = units();
    u.alt_m = 10000.01;
    check_fails(&u, "frame.alt_m: must be <= 10000, got 10000.01");
    u = units();
    u.cell_m = 0.00001;
    check_fails(&u, "frame.cell_m: must be >= 0.1, got 1e-05");
    u = units();
    u.cell_m = 10001.0;
    check_fails(&u, "frame.cell_m: must be <= 10000, got 10001.0");
    u = units();
    u.tick_s = 0.0;
    u.integers = 1U << 4;
    check_fails(&u, "frame.tick_s: must be >= 0.001, got 0");
    u = units();
    u.tick_s = 3600.001;
    check_fails(&u, "frame.tick_s: must be <= 3600, got 3600.001");
    u = units();
    u.cell_m = NAN;
    check_fails(&u, "frame.cell_m: must be a finite number, got nan");
    u = units();
    u.t0 = "1969-12-31T23:59:59Z";
    check_fails(&u, "frame.t0: must be >= 1970-01-01T00:00:00Z, got \"1969-12-31T23:59:59Z\"");
    u = units();
    u.t0 = NULL;
    check_fails(&u, "frame: missing key \"t0\"");

    // the integer form has the same ranges
    char err[SVA_FRAME_ERROR_SIZE] = "";
    sva_frame_t f = {0, 0, 0, SVA_FRAME_MAX_CELL_CM + 1, 1000, 0};
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_frame_check(&f, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("frame.cell_m: must be <= 10000, got 10000.01", err);
    f.cell_cm = 100;
    f.tick_ms = 0;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_frame_check(&f, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("frame.tick_s: must be >= 0.001, got 0", err);
    f.tick_ms = 1;
    f.lat_e7 = -850000001;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_frame_check(&f, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("frame.lat: must be >= -85, got -85.0000001", err);
    f.lat_e7 = 0;
    f.t0_ms = SVA_FRAME_MAX_T0_MS + 1;
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID, sva_frame_check(&f, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("frame.t0: must be <= 9999-12-31T23:59:59.999Z, got 253402300800000 "
                             "ms after 1970-01-01T00:00:00Z",
                             err);
    f.t0_ms = 0;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_frame_check(&f, err, sizeof err));
    // A NULL frame is misuse, not a refused value: no message.
    err[0] = '\0';
    TEST_ASSERT_EQUAL_INT(SVA_ERR_ARGUMENT, sva_frame_check(NULL, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("", err);
}

// One message per rule of t0, in the Python tools' words, the first rule broken.
void test_t0_rules(void)
{
    static const struct {
        const char* text;
        const char* rule;
    } cases[] = {
        {"2026-06-01", SVA_FRAME_UTC_RULE},
        {"2026-06-01T08:00:00", SVA_FRAME_UTC_RULE},
        {"2026-06-01T08:00:00.Z", SVA_FRAME_UTC_RULE},
        {"2026-06-01T08:00:00+ab:00", SVA_FRAME_UTC_RULE},
        {"2026-02-29T08:00:00Z", "must be a date of the calendar"},
        {"0000-01-01T00:00:00Z", "must be a date of the calendar"},
        {"2026-02-29T24:00:00+24:00", "must be a date of the calendar"},
        {"2026-06-01T24:00:00+24:00", "must have a time of day within 00:00:00..23:59:59"},
        {"2026-06-01T08:00:60Z", "must have a time of day within 00:00:00..23:59:59"},
        {"2026-06-01T08:00:00+24:00", "must have a UTC offset within -23:59..+23:59"},
        {"2026-06-01T08:00:00-00:60", "must have a UTC offset within -23:59..+23:59"},
        {"1970-01-01T00:30:00+01:00", "must be >= 1970-01-01T00:00:00Z"},
        {"9999-12-31T23:59:59.9991Z", "must be <= 9999-12-31T23:59:59.999Z"},
        {"9999-12-31T22:00:00-02:00", "must be <= 9999-12-31T23:59:59.999Z"},
    };
    char err[SVA_FRAME_ERROR_SIZE];
    char want[SVA_FRAME_ERROR_SIZE];
    int64_t ms = 7;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        (void)snprintf(want, sizeof want, "frame.t0: %s, got \"%s\"", cases[i].rule, cases[i].text);
        TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID,
                              sva_frame_parse_utc(cases[i].text, "frame.t0", &ms, err, sizeof err));
        TEST_ASSERT_EQUAL_STRING(want, err);
        TEST_ASSERT_EQUAL_INT(7, ms);
    }
    // the ends of the range are in it
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("9999-12-31T23:59:59.9990Z", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(SVA_FRAME_MAX_T0_MS, ms);
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("1970-01-01T01:00:00+01:00", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, ms);
    // a text that is no date is quoted as JSON writes it (json.dumps)
    TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID,
                          sva_frame_parse_utc("8 \"h\"\\\n\x01\xc3\xa9\xf0\x9f\x9b\xb8", "frame.t0",
                                              &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_STRING("frame.t0: " SVA_FRAME_UTC_RULE
                             ", got \"8 \\\"h\\\"\\\\\\n\\u0001\\u00e9\\ud83d\\udef8\"",
                             err);
}

void test_utc_text(void)
{
    char err[SVA_FRAME_ERROR_SIZE] = "";
    char text[SVA_FRAME_UTC_SIZE];
    int64_t ms = -1;

    TEST_ASSERT_EQUAL_INT(SVA_OK,
                          sva_frame_parse_utc("1970-01-01T00:00:00Z", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(0, ms);
    // 2024-02-29 is day 19782 after the epoch
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("2024-02-29T12:30:15.25Z", "t0", &ms, err, sizeof err));
    TEST_ASSERT_EQUAL_INT((19782LL * 86400 + 12 * 3600 + 30 * 60 + 15) * 1000 + 250, ms);
    TEST_ASSERT_TRUE(sva_frame_format_utc(ms, text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("2024-02-29T12:30:15.250Z", text);
    // an offset is folded into UTC; a sub-millisecond fraction rounds
    int64_t ms2 = -1;
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("2024-02-29T14:30:15.2494+02:00", "t0", &ms2, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(ms - 1, ms2);
    TEST_ASSERT_EQUAL_INT(
        SVA_OK, sva_frame_parse_utc("2024-02-29T07:00:15.2495-05:30", "t0", &ms2, err, sizeof err));
    TEST_ASSERT_EQUAL_INT(ms, ms2);

    static const char* const bad[] = {"2026-06-01 08:00:00Z",     "2026-06-01T08:00:00",
                                      "2026-06-01T08:00Z",        "2026-13-01T08:00:00Z",
                                      "2023-02-29T08:00:00Z",     "2026-06-01T24:00:00Z",
                                      "2026-06-01T08:00:00.Z",    "2026-06-01T08:00:00+2:00",
                                      "2026-06-01T08:00:00Zjunk", ""};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ms = 7;
        TEST_ASSERT_EQUAL_INT(SVA_ERR_INVALID,
                              sva_frame_parse_utc(bad[i], "frame.t0", &ms, err, sizeof err));
        TEST_ASSERT_EQUAL_INT(7, ms);
        TEST_ASSERT_TRUE(strncmp(err, "frame.t0: ", 10) == 0);
    }
    TEST_ASSERT_FALSE(sva_frame_format_utc(-1, text, sizeof text));
    TEST_ASSERT_TRUE(sva_frame_format_utc(SVA_FRAME_MAX_T0_MS, text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("9999-12-31T23:59:59.999Z", text);
}

void test_ticks_to_utc(void)
{
    const sva_frame_t f = {0, 0, 0, 100, 1500, 1000000};
    TEST_ASSERT_EQUAL_INT(1000000, sva_frame_tick_utc_ms(&f, 0));
    TEST_ASSERT_EQUAL_INT(1060000, sva_frame_tick_utc_ms(&f, 40));
}

// Distance and azimuth from the origin on the ellipsoid (PROJ's geodesic).
static void geodesic(const sva_frame_t* f, const sva_frame_geo_t* p, double* dist, double* azi)
{
    struct geod_geodesic g;
    double azi2;
    geod_init(&g, 6378137.0, 1.0 / 298.257223563);
    geod_inverse(&g, (double)f->lat_e7 / 1e7, (double)f->lon_e7 / 1e7, p->lat_deg, p->lon_deg, dist,
                 azi, &azi2);
}

void test_cells_on_the_ellipsoid(void)
{
    char err[SVA_FRAME_ERROR_SIZE] = "";
    const sva_frame_units_t u = units();
    sva_frame_t f;
    sva_frame_geo_t p;
    double dist, azi, east, north;
    TEST_ASSERT_EQUAL_INT(SVA_OK, sva_frame_from_units(&u, &f, err, sizeof err));
    sva_frame_geodesy_t* g = sva_frame_geodesy_open(&f, err, sizeof err);
    TEST_ASSERT_NOT_NULL(g);

    TEST_ASSERT_TRUE(sva_frame_cell_to_geo(g, 0, 0, &p));
    TEST_ASSERT_TRUE(fabs(p.lat_deg - 48.1372) < 1e-9);
    TEST_ASSERT_TRUE(fabs(p.lon_deg - 11.5755) < 1e-9);
    TEST_ASSERT_TRUE(fabs(p.alt_m - 60.0) < 1e-9);

    // 10 cells of 100 m east: 1 km at azimuth 90 (within a millimetre; the tangent
    // plane and the ellipsoid part by ~1e-4 m at this range)
    TEST_ASSERT_TRUE(sva_frame_cell_to_geo(g, 10, 0, &p));
    geodesic(&f, &p, &dist, &azi);
    TEST_ASSERT_TRUE(fabs(dist - 1000.0) < 1e-3);
    TEST_ASSERT_TRUE(fabs(azi - 90.0) < 1e-3);
    // 20 cells south: 2 km at azimuth 180
    TEST_ASSERT_TRUE(sva_frame_cell_to_geo(g, 0, -20, &p));
    geodesic(&f, &p, &dist, &azi);
    TEST_ASSERT_TRUE(fabs(dist - 2000.0) < 1e-3);
    TEST_ASSERT_TRUE(fabs(fabs(azi) - 180.0) < 1e-3);
    // and back to the plane (at height 0: the cell's point lies ~0.2 m above the
    // ellipsoid, which moves it ~2e-5 m)
    TEST_ASSERT_TRUE(sva_frame_cell_to_geo(g, -7, 13, &p));
    TEST_ASSERT_TRUE(sva_frame_geo_to_enu(g, p.lat_deg, p.lon_deg, &east, &north));
    TEST_ASSERT_TRUE(fabs(east + 700.0) < 1e-3);
    TEST_ASSERT_TRUE(fabs(north - 1300.0) < 1e-3);
    sva_frame_geodesy_close(g);

    const sva_frame_t bad = {0, 0, 0, 0, 1000, 0};
    TEST_ASSERT_NULL(sva_frame_geodesy_open(&bad, err, sizeof err));
    TEST_ASSERT_NOT_NULL(strstr(err, "frame.cell_m"));
}
