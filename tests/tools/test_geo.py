"""The geographic mission frame (docs/SPEC.md section 3, docs/flight-stack.md) and
`sva-tools geo`: positions checked against an independent geodesic (geographiclib),
rounding, snapping, windows, every bad input, and a plan drawn on the map and read back."""
import copy
import json
import math
import random
import subprocess
from datetime import datetime, timezone
from fractions import Fraction

import pytest
from conftest import REPO, sva_tools
from geographiclib.geodesic import Geodesic

from sva_tools import commands, io, schema
from sva_tools import frame

GEO = REPO / "fixtures" / "geo"
TARGETS = GEO / "zurich_targets.geojson"
MISSION = GEO / "zurich.json"
# The frame's invalid missions live with the others in fixtures/invalid (frame_*).
INVALID = sorted((REPO / "fixtures" / "invalid").glob("frame_*.json"))
# How fixtures/geo/zurich.json is made (docs/flight-stack.md shows the same command).
ZURICH_ARGS = ["--depot", "47.3655,8.5461", "--cell-m", "50", "--tick-s", "1",
               "--t0", "2026-06-01T08:00:00Z", "--alt-m", "40", "--uavs", "3", "--fuel", "2000",
               "--speed", "10", "--name", "zurich"]
# Origins around the world: mid-latitude, southern hemisphere, the antimeridian, the range's edge.
ORIGINS = [(47.3655, 8.5461), (-33.8568, 151.2153), (64.1466, -21.9426), (0.0, 179.9999),
           (-85.0, -180.0), (85.0, 180.0)]
WGS84 = Geodesic.WGS84


class Run:
    def __init__(self, returncode, stdout, stderr):
        self.returncode, self.stdout, self.stderr = returncode, stdout, stderr


@pytest.fixture
def tools(capsys):
    """`sva-tools ARGS` in this process (the entry point's own error handling): the
    many bad-input cases cost no interpreter start each."""
    def run(*args):
        capsys.readouterr()
        try:
            rc = commands.main([str(a) for a in args])
        except SystemExit as e:  # argparse: usage errors, --help
            rc = e.code
        out = capsys.readouterr()
        return Run(rc, out.out, out.err)
    return run


def _frame(lat=47.3655, lon=8.5461, cell_m=50, tick_s=1, t0="2026-06-01T08:00:00Z", alt_m=40):
    return frame.Frame.from_json({"lat": lat, "lon": lon, "alt_m": alt_m, "cell_m": cell_m,
                              "tick_s": tick_s, "t0": t0})


# --- the frame: positions -----------------------------------------------------------

@pytest.mark.parametrize("origin", ORIGINS, ids=str)
def test_the_origin_is_cell_zero(origin):
    fr = _frame(*origin)
    lat, lon = fr.cell_to_geodetic(0, 0)
    assert abs(lat - origin[0]) < 1e-9 and abs(lon - origin[1]) < 1e-9
    assert fr.geodetic_to_cell(*origin) == (0, 0)
    east, north = fr.geodetic_to_enu(*origin)
    assert abs(east) < 1e-6 and abs(north) < 1e-6


@pytest.mark.parametrize("origin", ORIGINS, ids=str)
@pytest.mark.parametrize("cell_m", [0.1, 7.5, 50, 1000])
def test_a_kilometre_east_and_north_by_an_independent_geodesic(origin, cell_m):
    """geographiclib's direct geodesic problem (not pymap3d) puts the point 1 km east
    (azimuth 90) and 1 km north; the frame maps each within half a cell of the cell
    1000 / cell_m along its axis."""
    fr = _frame(*origin, cell_m=cell_m)
    for azimuth, axis in ((90, 0), (0, 1)):
        g = WGS84.Direct(origin[0], origin[1], azimuth, 1000)
        east, north = fr.geodetic_to_enu(g["lat2"], g["lon2"])
        along, across = (east, north) if axis == 0 else (north, east)
        assert abs(along - 1000) < cell_m / 2 and abs(across) < cell_m / 2, (along, across)
        assert abs(along - 1000) < 0.01 and abs(across) < 0.01  # the plane and the geodesic agree to 1 cm at 1 km
        want = [0, 0]
        want[axis] = frame.snap(1000 / cell_m)
        assert list(fr.geodetic_to_cell(g["lat2"], g["lon2"])) == want


@pytest.mark.parametrize("origin", ORIGINS, ids=str)
def test_cells_go_round_trip(origin):
    rng = random.Random(7)
    fr = _frame(*origin, cell_m=25)
    for _ in range(200):
        x, y = rng.randint(-2000, 2000), rng.randint(-2000, 2000)  # up to 50 km out
        lat, lon = fr.cell_to_geodetic(x, y)
        east, north = fr.geodetic_to_enu(lat, lon)
        assert abs(east - 25 * x) < 1e-3 and abs(north - 25 * y) < 1e-3
        assert fr.geodetic_to_cell(lat, lon) == (x, y)


def test_cell_distances_match_the_geodesic_near_the_origin():
    fr = _frame(cell_m=10)
    for x, y in ((100, 0), (0, 100), (-70, 70), (300, -400)):
        lat, lon = fr.cell_to_geodetic(x, y)
        s = WGS84.Inverse(fr.lat, fr.lon, lat, lon)["s12"]
        plane = math.hypot(10 * x, 10 * y)
        assert abs(s - plane) < 1e-6 * plane + 0.01, (x, y, s, plane)


def test_snapping_rounds_half_away_from_zero():
    assert [frame.snap(v) for v in (0.5, -0.5, 1.5, -1.5, 0.49999, -0.49999, 2.5000001)] == \
        [1, -1, 2, -2, 0, 0, 3]
    fr = _frame(cell_m=50)
    for east, want in ((24.99, 0), (25.01, 1), (-25.01, -1), (-24.99, 0), (74.9, 1), (75.1, 2)):
        lat, lon = fr.enu_to_geodetic(east, 0.0)
        assert fr.geodetic_to_cell(lat, lon) == (want, 0), east


def test_far_side_of_the_earth_is_refused():
    fr = _frame(10, 20)
    with pytest.raises(frame.FrameError, match="far side of the Earth"):
        fr.geodetic_to_enu(-10, -160)


# --- the frame: numbers and times ---------------------------------------------------

def test_values_round_half_away_from_zero_at_their_resolution():
    fr = frame.Frame.from_json({"lat": 47.12345675, "lon": -8.12345675, "alt_m": 0.005,
                            "cell_m": 12.345, "tick_s": 0.0015, "t0": "2026-06-01T08:00:00.0005Z"})
    assert (fr.lat, fr.lon, fr.alt_m, fr.cell_m, fr.tick_ms) == (47.1234568, -8.1234568, 0.01, 12.35, 2)
    assert fr.to_json()["t0"] == "2026-06-01T08:00:00.001Z"
    below = frame.Frame.from_json({"lat": 47.12345674, "lon": -8.12345674, "alt_m": 0.0049,
                               "cell_m": 12.344, "tick_s": 0.0014, "t0": "2026-06-01T08:00:00.00049+00:00"})
    assert (below.lat, below.lon, below.alt_m, below.cell_m, below.tick_ms) == \
        (47.1234567, -8.1234567, 0.0, 12.34, 1)
    assert below.to_json()["t0"] == "2026-06-01T08:00:00.000Z"


def test_ticks_are_exact_utc_instants():
    fr = _frame(tick_s=0.25, t0="2026-06-01T10:00:00+02:00")
    assert fr.tick_to_utc(0) == "2026-06-01T08:00:00.000Z"
    assert fr.tick_to_utc(5) == "2026-06-01T08:00:01.250Z"
    assert fr.tick_to_utc(4 * 86400) == "2026-06-02T08:00:00.000Z"
    # Python's own calendar as the independent reading of the instants.
    for tick in (0, 1, 3, 1000, 345_601, 1_000_000_000):
        got = datetime.strptime(fr.tick_to_utc(tick), "%Y-%m-%dT%H:%M:%S.%fZ").replace(tzinfo=timezone.utc)
        want = datetime(2026, 6, 1, 8, tzinfo=timezone.utc).timestamp() + tick * 0.25
        assert abs(got.timestamp() - want) < 1e-6
        assert fr.utc_to_ticks(fr.tick_to_utc(tick)) == tick
    late = _frame(tick_s=3600, t0="9999-01-01T00:00:00Z")
    with pytest.raises(frame.FrameError, match="beyond 9999-12-31T23:59:59.999Z"):
        late.tick_to_utc(10_000)


@pytest.mark.parametrize("text,rule", [
    ("2026-06-01T08:00:00", "must be an ISO 8601 date-time with a UTC offset"),
    ("2026-06-01 08:00:00Z", "must be an ISO 8601"),
    ("2026-06-01T08:00Z", "must be an ISO 8601"),
    ("2026-13-01T08:00:00Z", "must be a date of the calendar"),
    ("2025-02-29T08:00:00Z", "must be a date of the calendar"),
    ("2026-06-01T23:59:60Z", "must have a time of day within"),
    ("2026-06-01T08:00:00+05:60", "must have a UTC offset within"),
])
def test_bad_date_times_name_their_rule(text, rule):
    with pytest.raises(frame.FrameError, match=rule):
        frame.parse_utc(text)


def test_offsets_and_fractions_are_exact():
    assert frame.parse_utc("1970-01-01T00:00:00Z") == 0
    assert frame.parse_utc("1970-01-01T01:00:00+01:00") == 0
    assert frame.parse_utc("1969-12-31T23:00:00-01:00") == 0
    assert frame.parse_utc("2000-01-01T00:00:00.123456789Z") == 946684800 + Fraction(123456789, 10**9)


# --- the schemas --------------------------------------------------------------------

def test_the_bundled_mission_and_a_plan_carry_a_valid_frame():
    doc = json.loads(MISSION.read_text())
    assert schema.errors(doc, "mission") == []
    plan = {"mission": "zurich", "frame": doc["frame"], "algorithm": "sva", "status": "partial",
            "covered": 0, "uncovered": [1, 2, 3, 4, 5], "cost": 0,
            "routes": [{"uav": u, "targets": [], "distance": 0, "fuel_used": 0} for u in (1, 2, 3)]}
    assert schema.errors(plan, "plan") == []
    plan["frame"] = dict(doc["frame"], tick_s="1")
    assert schema.first_error(plan, "plan") == "frame.tick_s: must be a number, got string"
    plan["frame"] = dict(doc["frame"], t0="2026-02-30T00:00:00Z")
    assert schema.first_error(plan, "plan") == 'frame.t0: must be a date of the calendar, got "2026-02-30T00:00:00Z"'


# The message of each and the schema's share: tests/tools/test_schema.py (BEYOND_SCHEMA);
# the C CLI's: tests/cli/test_cli.py. Here: the command line of sva-tools.
@pytest.mark.parametrize("path", INVALID, ids=lambda p: p.stem)
def test_invalid_frame_rejected_with_its_error(path, tools):
    expected = path.with_suffix(".err").read_text(encoding="utf-8").strip()
    with pytest.raises(io.InputError) as e:
        io.load_mission(str(path))
    assert str(e.value) == expected
    r = tools("validate", path)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == f"sva-tools: error: {path}: {expected}\n"


def test_every_invalid_frame_has_its_message():
    errs = sorted((REPO / "fixtures" / "invalid").glob("frame_*.err"))
    assert [p.stem for p in errs] == [p.stem for p in INVALID]
    assert len(INVALID) >= 20


def test_nan_and_infinity_are_not_json(tmp_path):
    for text, word in (("NaN", "invalid token NaN"), ("1e400", "real number overflow")):
        p = tmp_path / "m.json"
        p.write_text(MISSION.read_text().replace('"lat": 47.3655', f'"lat": {text}'))
        with pytest.raises(io.InputError, match=word):
            io.load_mission(str(p))


# --- geo mission --------------------------------------------------------------------

def _geo_mission(tools, tmp_path, features, crs=None, args=None):
    doc = {"type": "FeatureCollection", "features": features}
    if crs is not None:
        doc["crs"] = crs
    p = tmp_path / "targets.geojson"
    p.write_text(json.dumps(doc))
    return tools("geo", "mission", p, *(args if args is not None else ZURICH_ARGS)), p


def _point(lon, lat, **props):
    return {"type": "Feature", "geometry": {"type": "Point", "coordinates": [lon, lat]},
            "properties": props}


def test_the_bundled_mission_is_what_geo_mission_makes():
    r = sva_tools("geo", "mission", TARGETS, *ZURICH_ARGS)
    assert r.returncode == 0, r.stderr
    assert r.stdout == MISSION.read_text()
    doc = json.loads(r.stdout)
    fr = frame.Frame.from_json(doc["frame"])
    targets = json.loads(TARGETS.read_text())["features"]
    assert doc["depot"] == {"x": 0, "y": 0} and (fr.lat, fr.lon) == (47.3655, 8.5461)
    assert [t["id"] for t in doc["targets"]] == [1, 2, 3, 4, 5]  # the fourth is numbered
    assert doc["ticks_per_cell"] == 5  # 50 m at 10 m/s and 1 s ticks
    for feat, t in zip(targets, doc["targets"]):
        if feat["geometry"]["type"] == "Point":
            lon, lat = feat["geometry"]["coordinates"]
            east, north = fr.geodetic_to_enu(lat, lon)
            assert abs(east - 50 * t["x"]) <= 25 and abs(north - 50 * t["y"]) <= 25
    # Windows: seconds after t0 and ISO 8601 instants; start rounded up, end down.
    assert [(t["start"], t["end"]) for t in doc["targets"]] == \
        [(300, 900), (600, 1200), (1200, 2100), (1501, 2100), (0, 2400)]


def test_windows_round_inwards(tools, tmp_path):
    args = ["--depot", "47,8", "--cell-m", "10", "--tick-s", "2", "--t0", "2026-06-01T00:00:00Z"]
    feats = [_point(8, 47, id=1, start=3, end=9, need=1),                         # ticks 1.5 .. 4.5
             _point(8, 47, id=2, start="2026-06-01T00:00:03Z", end="2026-06-01T02:00:09+02:00", need=1),
             _point(8, 47, id=3, start=4, end=10, need=1),                        # whole ticks
             _point(8, 47, id=4, start=0.001, end=8.999, need=1)]
    r, _ = _geo_mission(tools, tmp_path, feats, args=args)
    assert r.returncode == 0, r.stderr
    got = [(t["start"], t["end"]) for t in json.loads(r.stdout)["targets"]]
    assert got == [(2, 4), (2, 4), (2, 5), (1, 4)]


def test_a_polygon_goes_to_its_area_centroid(tools, tmp_path):
    """An L of two rectangles in the plane, drawn through the frame: its area centroid is
    known by hand; extra vertices along one edge pull the vertices' mean, not the area's."""
    fr = _frame(cell_m=10)
    # cells: (0,0)-(40,0)-(40,10)-(10,10)-(10,30)-(0,30), many vertices on the bottom edge
    ring = [(0, 0)] + [(k, 0) for k in range(2, 40, 2)] + [(40, 0), (40, 10), (10, 10), (10, 30), (0, 30), (0, 0)]
    # Rectangles 40x10 (centroid (20, 5), area 400) and 10x20 (centroid (5, 20), area 200).
    cx, cy = (400 * 20 + 200 * 5) / 600, (400 * 5 + 200 * 20) / 600   # (15, 10)
    coords = [[list(reversed(fr.cell_to_geodetic(x, y)))] for x, y in ring]
    coords = [c[0] for c in coords]
    poly = {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [coords]},
            "properties": {"id": 9, "start": 10, "end": 20, "need": 1}}
    args = ["--depot", f"{fr.lat},{fr.lon}", "--cell-m", "10", "--tick-s", "1", "--t0", "2026-06-01T00:00:00Z"]
    r, _ = _geo_mission(tools, tmp_path, [poly], args=args)
    assert r.returncode == 0, r.stderr
    t = json.loads(r.stdout)["targets"][0]
    assert (t["x"], t["y"]) == (round(cx), round(cy)) == (15, 10)
    mean = [sum(v[i] for v in ring[:-1]) / len(ring[:-1]) for i in (0, 1)]
    assert (round(mean[0]), round(mean[1])) != (15, 10)  # the vertices' mean is elsewhere


def test_a_polygon_with_a_hole_goes_to_the_centroid_of_what_is_left(tools, tmp_path):
    fr = _frame(cell_m=10)

    def ring(cells):
        return [list(reversed(fr.cell_to_geodetic(x, y))) for x, y in cells]

    outer = ring([(0, 0), (40, 0), (40, 40), (0, 40), (0, 0)])      # area 1600, centroid (20, 20)
    hole = ring([(1, 1), (1, 11), (11, 11), (11, 1), (1, 1)])        # area 100, centroid (6, 6)
    # (1600 * 20 - 100 * 6) / 1500 = 20.93: cell 21 on both axes.
    feat = {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [outer, hole]},
            "properties": {"start": 10, "end": 20, "need": 1}}
    args = ["--depot", f"{fr.lat},{fr.lon}", "--cell-m", "10", "--tick-s", "1", "--t0", "2026-06-01T00:00:00Z"]
    r, _ = _geo_mission(tools, tmp_path, [feat], args=args)
    assert r.returncode == 0, r.stderr
    t = json.loads(r.stdout)["targets"][0]
    assert (t["x"], t["y"]) == (21, 21)
    r, _ = _geo_mission(tools, tmp_path, [dict(feat, geometry={"type": "Polygon", "coordinates": [outer]})],
                        args=args)
    assert [(t["x"], t["y"]) for t in json.loads(r.stdout)["targets"]] == [(20, 20)]


def test_a_point_half_a_cell_out_snaps_away_from_zero(tools, tmp_path):
    fr = _frame(cell_m=10)
    feats = []
    for k, (e, n) in enumerate(((15.01, -15.01), (14.99, -14.99))):
        lat, lon = fr.enu_to_geodetic(e, n)
        feats.append(_point(lon, lat, id=k + 1, start=0, end=5, need=1))
    args = ["--depot", f"{fr.lat},{fr.lon}", "--cell-m", "10", "--tick-s", "1", "--t0", "2026-06-01T00:00:00Z"]
    r, _ = _geo_mission(tools, tmp_path, feats, args=args)
    assert r.returncode == 0, r.stderr
    assert [(t["x"], t["y"]) for t in json.loads(r.stdout)["targets"]] == [(2, -2), (1, -1)]


def test_a_crs_naming_wgs84_lon_lat_is_accepted(tools, tmp_path):
    crs = {"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}}
    r, _ = _geo_mission(tools, tmp_path, [_point(8.5461, 47.3655, start=0, end=5, need=1)], crs=crs)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["targets"][0]["x"] == 0


BAD_FEATURES = [
    ([_point(8.55, 47.37, start=0, end=5)], 'features[0].properties: missing key "need"'),
    ([_point(8.55, 47.37, start=0, end=5, need=0)], "features[0].properties.need: must be >= 1, got 0"),
    ([_point(8.55, 47.37, start=0, end=5, need="2")], "features[0].properties.need: must be an integer, got string"),
    ([_point(8.55, 47.37, start=0, end=5, need=65)], "features[0].properties.need: must be <= SVA_MAX_UAVS (64), got 65"),
    ([_point(8.55, 47.37, end=5, need=1)], 'features[0].properties: missing key "start"'),
    ([_point(8.55, 47.37, start=0, end="soon", need=1)],
     'features[0].properties.end: must be an ISO 8601 date-time with a UTC offset (YYYY-MM-DDThh:mm:ss[.fff] '
     'then Z or +hh:mm or -hh:mm), got "soon"'),
    ([_point(8.55, 47.37, start=0, end="2026-06-01T08:10:00", need=1)],
     "features[0].properties.end: must be an ISO 8601 date-time with a UTC offset"),
    ([_point(8.55, 47.37, start=True, end=5, need=1)],
     "features[0].properties.start: must be seconds after t0 (a number) or an ISO 8601 date-time, got boolean"),
    ([_point(8.55, 47.37, start=-1, end=5, need=1)], "features[0].properties.start: must not be before t0, got -1"),
    ([_point(8.55, 47.37, start="2026-06-01T07:59:59Z", end=5, need=1)],
     'features[0].properties.start: must not be before t0, got "2026-06-01T07:59:59Z"'),
    ([_point(8.55, 47.37, id=7, start=10.2, end=10.8, need=1)],
     "features[0].properties: the window of target 7 holds no tick interval: start rounds up to tick 11, "
     "end down to tick 10 (tick_s 1); a window needs end > start"),
    ([_point(8.55, 47.37, start=5, end=5, need=1)],
     "features[0].properties: the window of target 1 holds no tick interval"),
    ([_point(8.55, 47.37, start=0, end=2e9, need=1)],
     "features[0].properties.end: must be at most SVA_MAX_TICK (1000000000) ticks after t0, got tick 2000000000"),
    ([_point(8.55, 47.37, id=3, start=0, end=5, need=1), _point(8.55, 47.37, id=3, start=0, end=5, need=1)],
     "features[1].properties.id: duplicate id 3 (first at index 0)"),
    ([_point(8.55, 47.37, id=0, start=0, end=5, need=1)], "features[0].properties.id: must be >= 1, got 0"),
    ([_point(188, 47.37, start=0, end=5, need=1)],
     "features[0].geometry.coordinates[0]: longitude must be in [-180, 180], got 188"),
    ([_point(47.37, 95, start=0, end=5, need=1)],
     "features[0].geometry.coordinates[1]: latitude must be in [-90, 90], got 95"),
    ([{"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[8.5, 47.3], [8.6, 47.4]]},
       "properties": {"start": 0, "end": 5, "need": 1}}],
     'features[0].geometry.type: must be "Point" or "Polygon", got "LineString"'),
    ([{"type": "Feature", "geometry": None, "properties": {"start": 0, "end": 5, "need": 1}}],
     'features[0].geometry.type: must be "Point" or "Polygon", got null'),
    ([{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[8.54, 47.36], [8.55, 47.37],
                                                                          [8.55, 47.36], [8.54, 47.37], [8.54, 47.36]]]},
       "properties": {"start": 0, "end": 5, "need": 1}}],
     "features[0].geometry.coordinates: must be a valid polygon, got Self-intersection"),
    ([{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[8.54, 47.36], [8.55, 47.37], [8.54, 47.36]]]},
       "properties": {"start": 0, "end": 5, "need": 1}}],
     "features[0].geometry.coordinates[0]: a linear ring must have at least 4 positions (RFC 7946)"),
    ([{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[8.54, 47.36], [8.55, 47.37],
                                                                          [8.55, 47.36], [8.54, 47.365]]]},
       "properties": {"start": 0, "end": 5, "need": 1}}],
     "features[0].geometry.coordinates[0]: a linear ring must end where it starts (RFC 7946)"),
    ([{"type": "Feature", "geometry": {"type": "Point", "coordinates": [8.55]},
       "properties": {"start": 0, "end": 5, "need": 1}}],
     "features[0].geometry.coordinates: must be a position [longitude, latitude] (RFC 7946), got [8.55]"),
    ([{"type": "Feature", "geometry": {"type": "Point", "coordinates": [8.55, 47.37]}}],
     "features[0].properties: must be an object, got null"),
]


@pytest.mark.parametrize("features,message", BAD_FEATURES, ids=lambda v: str(v)[:40])
def test_a_bad_feature_is_refused_with_its_rule(tools, tmp_path, features, message):
    r, p = _geo_mission(tools, tmp_path, features)
    assert r.returncode == 2 and r.stdout == "", r.stdout
    assert r.stderr.startswith(f"sva-tools: error: {p}: {message}"), r.stderr
    assert r.stderr.count("\n") == 1


def test_a_target_beyond_the_grid_is_refused(tools, tmp_path):
    # San Francisco seen from Zurich on a 10 m grid: far beyond 32767 cells.
    args = list(ZURICH_ARGS)
    args[args.index("--cell-m") + 1] = "10"
    r, p = _geo_mission(tools, tmp_path, [_point(8.5461, 47.0, start=0, end=5, need=1),
                                   _point(-122.4, 37.8, start=0, end=5, need=1)], args=args)
    assert r.returncode == 2
    assert "features[1].geometry: " in r.stderr and "beyond the grid [-32768, 32767]" in r.stderr
    assert "cell_m 10" in r.stderr


@pytest.mark.parametrize("crs", [{"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::3857"}},
                                 {"type": "name", "properties": {"name": "EPSG:2056"}}, "WGS84"])
def test_a_crs_other_than_wgs84_is_refused(tools, tmp_path, crs):
    r, p = _geo_mission(tools, tmp_path, [_point(8.55, 47.37, start=0, end=5, need=1)], crs=crs)
    assert r.returncode == 2
    assert r.stderr.startswith(f"sva-tools: error: {p}: crs: must be WGS84 longitude, latitude (RFC 7946; "
                               f"urn:ogc:def:crs:OGC:1.3:CRS84), got ")


BAD_OPTIONS = [
    (("--t0", "2026-06-01 08:00"), "--t0: must be an ISO 8601 date-time with a UTC offset"),
    (("--t0", "1969-06-01T08:00:00Z"), "--t0: must be >= 1970-01-01T00:00:00Z"),
    (("--cell-m", "0.05"), "--cell-m: must be >= 0.1, got 0.05"),
    (("--tick-s", "0"), "--tick-s: must be >= 0.001, got 0"),
    (("--tick-s", "7200"), "--tick-s: must be <= 3600, got 7200"),
    (("--alt-m", "-5"), "--alt-m: must be >= 0, got -5"),
    (("--depot", "86,8"), "--depot (latitude): must be <= 85, got 86.0"),
    (("--uavs", "65"), "--uavs: must be in [0, 64] (SVA_MAX_UAVS), got 65"),
    (("--speed", "0.001"), "--speed: gives 50000 ticks per cell, more than SVA_MAX_TICKS_PER_CELL (1000)"),
]


@pytest.mark.parametrize("option,message", BAD_OPTIONS, ids=lambda v: str(v)[:30])
def test_a_bad_option_is_refused_with_its_rule(tools, option, message):
    args = list(ZURICH_ARGS)
    if option[0] in args:
        args[args.index(option[0]) + 1] = option[1]
    else:
        args += list(option)
    r = tools("geo", "mission", TARGETS, *args)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.startswith(f"sva-tools: error: geo: {message}"), r.stderr


# Options and arguments argparse refuses: one line too, naming the option.
BAD_USAGE = [
    (("--depot", "95,8"), "--depot: must be LAT in [-90, 90] and LON in [-180, 180], got '95,8'"),
    (("--depot", "47"), "--depot: must be LAT,LON in degrees, got '47'"),
    (("--cell-m", "abc"), "--cell-m: must be a number, got 'abc'"),
    (("--tick-s", "inf"), "--tick-s: must be a number, got 'inf'"),
    (("--uavs", "x"), "--uavs: must be an integer, got 'x'"),
    (("--fuel", "1.5"), "--fuel: must be an integer, got '1.5'"),
    (("--speed", "nan"), "--speed: must be a number, got 'nan'"),
    (("--ticks-per-cell", "2"), "--ticks-per-cell: not allowed with argument --speed"),
    (("--colour", "red"), "unrecognized arguments: --colour red"),
    (("--depot", "\x1b[31m\n"), "--depot: must be LAT,LON in degrees, got '\\x1b[31m\\n'"),
]


@pytest.mark.parametrize("option,message", BAD_USAGE, ids=lambda v: str(v)[:30])
def test_a_bad_option_value_is_one_line(tools, option, message):
    args = list(ZURICH_ARGS)
    if option[0] in args:
        args[args.index(option[0]) + 1] = option[1]
    else:
        args += list(option)
    r = tools("geo", "mission", TARGETS, *args)
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr == f"sva-tools: error: geo: {message}\n"


@pytest.mark.parametrize("args,message", [
    (("geo",), "the following arguments are required: GEO_COMMAND"),
    (("geo", "nope"), "GEO_COMMAND: invalid choice: 'nope' (choose from 'mission', 'plan', 'cell', 'point')"),
    (("geo", "mission", TARGETS, "--cell-m", "50"), "the following arguments are required: --depot, "
     "--tick-s, --t0"),
    (("geo", "cell", "47.3655,8.5461,3", "--mission", MISSION),
     "LAT,LON: must be LAT,LON in degrees, got '47.3655,8.5461,3'"),
    (("geo", "point", "1", "--mission", MISSION), "X,Y: must be X,Y (integers), got '1'"),
    (("geo", "point", "1,2"), "the following arguments are required: --mission"),
    (("geo", "plan", MISSION), "the following arguments are required: PLAN.json"),
    (("geo", "plan", MISSION, MISSION, MISSION), f"unrecognized arguments: {MISSION}"),
], ids=lambda v: str(v)[:40])
def test_a_bad_command_line_is_one_line(tools, args, message):
    r = tools(*args)
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr == f"sva-tools: error: geo: {message}\n"


def test_usage_errors_are_one_line_from_the_entry_point_too():
    r = sva_tools("geo", "mission", TARGETS, *ZURICH_ARGS, "--uavs", "many")
    assert (r.returncode, r.stdout) == (2, "")
    assert r.stderr == "sva-tools: error: geo: --uavs: must be an integer, got 'many'\n"
    assert sva_tools("geo", "mission", "--help").returncode == 0


def test_bad_documents_are_refused(tools, tmp_path):
    for text, message in (('{"type": "Feature"}', 'feature.properties: must be an object, got null'),
                          ('[1]', "geojson: must be an object, got array"),
                          ('{"type": "GeometryCollection"}', 'type: must be "FeatureCollection" or "Feature"'),
                          ('{"type": "FeatureCollection", "features": [1, }', "invalid JSON")):
        p = tmp_path / "t.geojson"
        p.write_text(text)
        r = tools("geo", "mission", p, *ZURICH_ARGS)
        assert r.returncode == 2 and r.stdout == "", r.stdout
        assert r.stderr.startswith(f"sva-tools: error: {p}") and message in r.stderr, r.stderr


# --- geo plan -----------------------------------------------------------------------

def _c_plan(sva_bin, mission_path, algo="flow"):
    """`sva plan` of a framed mission file: the plan echoes the mission's frame."""
    r = subprocess.run([str(sva_bin), "plan", "--algo", algo, str(mission_path)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


@pytest.fixture
def zurich_plan(sva_bin, tmp_path):
    mission = json.loads(MISSION.read_text())
    plan = _c_plan(sva_bin, MISSION)
    plan_path = tmp_path / "plan.json"
    plan_path.write_text(json.dumps(plan))
    r = sva_tools("geo", "plan", MISSION, plan_path)
    assert r.returncode == 0, r.stderr
    return mission, plan, json.loads(r.stdout), plan_path


def test_sva_plan_echoes_the_missions_frame(zurich_plan, sva_bin, tmp_path):
    """The C CLI reads the framed mission: its plan carries the frame as the mission
    writes it (the mission is at the frame's resolutions) and is the plan of the same
    mission without a frame."""
    mission, plan, _, _ = zurich_plan
    assert plan["frame"] == mission["frame"]
    bare = tmp_path / "bare.json"
    bare.write_text(json.dumps({k: v for k, v in mission.items() if k != "frame"}))
    plain = _c_plan(sva_bin, bare)
    assert "frame" not in plain
    assert {k: v for k, v in plan.items() if k not in ("frame", "stats")} == \
        {k: v for k, v in plain.items() if k != "stats"}


def test_the_plan_on_the_map_reads_back_as_the_plan(zurich_plan):
    mission, plan, gj, _ = zurich_plan
    fr = frame.Frame.from_json(mission["frame"])
    targets = {t["id"]: t for t in mission["targets"]}
    uavs = {u["id"]: u for u in mission["uavs"]}
    assert gj["type"] == "FeatureCollection"
    routes = [f for f in gj["features"] if f["properties"]["kind"] == "route"]
    points = [f for f in gj["features"] if f["properties"]["kind"] == "target"]
    assert [f["properties"]["uav"] for f in routes] == [r["uav"] for r in plan["routes"]]
    assert [f["properties"]["id"] for f in points] == [t["id"] for t in mission["targets"]]
    assert plan["covered"] >= 3 and any(r["targets"] for r in plan["routes"])
    for f, r in zip(routes, plan["routes"]):
        u = uavs[r["uav"]]
        want = [(u["x"], u["y"])] + [(targets[t]["x"], targets[t]["y"]) for t in r["targets"]] + [(0, 0)]
        coords = f["geometry"]["coordinates"]
        assert f["geometry"]["type"] == "LineString" and len(coords) == len(want)
        # RFC 7946 order [lon, lat]: near Zurich, lon ~ 8.5 and lat ~ 47.4.
        assert all(8.4 < lon < 8.7 and 47.3 < lat < 47.5 for lon, lat in coords)
        assert [fr.geodetic_to_cell(lat, lon) for lon, lat in coords] == want
        props = f["properties"]
        assert props["distance"] == r["distance"] and props["targets"] == r["targets"]
        assert props["distance_m"] == r["distance"] * 50
        arrive, leave = props["arrival_ticks"], props["departure_ticks"]
        assert len(props["arrivals"]) == len(coords) == len(props["departures"])
        assert [fr.utc_to_ticks(a) for a in props["arrivals"]] == arrive
        for k, tid in enumerate(r["targets"], 1):
            assert arrive[k] <= targets[tid]["start"] and leave[k] == targets[tid]["end"]  # SPEC 1
        assert leave[-1] is None and props["departures"][-1] is None
    for f in points:
        t = targets[f["properties"]["id"]]
        lon, lat = f["geometry"]["coordinates"]
        assert fr.geodetic_to_cell(lat, lon) == (t["x"], t["y"])
        assert f["properties"]["start"] == fr.tick_to_utc(t["start"])
        assert f["properties"]["covered"] == (t["id"] not in plan["uncovered"])
        served = [r["uav"] for r in plan["routes"] if t["id"] in r["targets"]]
        assert f["properties"]["served_by"] == served
        assert len(served) == (t["need"] if f["properties"]["covered"] else 0)
    depot = next(f for f in gj["features"] if f["properties"]["kind"] == "depot")
    assert depot["geometry"]["coordinates"] == [8.5461, 47.3655]


def test_arrivals_are_those_the_simulator_flies(zurich_plan, sva_bin, tmp_path):
    """The GeoJSON's arrival ticks against `sva-tools sim` (the C CLI's `sva replan`
    steering a tick-by-tick flight, SPEC section 12.2) with no events."""
    from sva_tools import sim

    mission, plan, gj, _ = zurich_plan
    log = sim.simulate(io.mission_from_json({k: v for k, v in mission.items() if k != "frame"}), [],
                       algo="flow")
    flown = {u["id"]: u for u in log["uavs"]}
    checked = 0
    for f in gj["features"]:
        props = f["properties"]
        if props["kind"] != "route":
            continue
        visits = flown[props["uav"]]["visits"]
        assert [v["target"] for v in visits] == props["targets"]
        for k, v in enumerate(visits, 1):
            assert v["arrived"] == props["arrival_ticks"][k]
            assert v["left"] == props["departure_ticks"][k]
            checked += 1
    assert checked == sum(len(r["targets"]) for r in plan["routes"]) > 0


def test_a_plan_carrying_the_frame_must_carry_the_missions(zurich_plan, tmp_path, tools):
    mission, plan, gj, plan_path = zurich_plan
    echoed = dict(plan, frame=mission["frame"])
    plan_path.write_text(json.dumps(echoed))
    r = tools("geo", "plan", MISSION, plan_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout) == gj
    plan_path.write_text(json.dumps(dict(plan, frame=dict(mission["frame"], cell_m=25))))
    r = tools("geo", "plan", MISSION, plan_path)
    assert r.returncode == 2 and r.stderr == f"sva-tools: error: {plan_path}: frame: must be the mission's frame\n"


def test_geo_plan_refuses_what_it_cannot_draw(zurich_plan, tmp_path, tools):
    mission, plan, _, plan_path = zurich_plan
    bare = tmp_path / "bare.json"
    bare.write_text(json.dumps({k: v for k, v in mission.items() if k != "frame"}))
    r = tools("geo", "plan", bare, plan_path)
    assert r.returncode == 2
    assert r.stderr == (f'sva-tools: error: {bare}: mission: missing key "frame" '
                        f'(the geo commands need the mission\'s frame)\n')
    wrong = copy.deepcopy(plan)
    wrong["routes"][0]["distance"] += 1
    plan_path.write_text(json.dumps(wrong))
    r = tools("geo", "plan", MISSION, plan_path)
    assert r.returncode == 2 and "not a plan of this mission (SPEC section 1): " in r.stderr
    bad_frame = tmp_path / "m.json"
    bad_frame.write_text(json.dumps(dict(mission, frame=dict(mission["frame"], lat=90))))
    r = tools("geo", "plan", bad_frame, plan_path)
    assert r.returncode == 2 and r.stderr == f"sva-tools: error: {bad_frame}: frame.lat: must be <= 85, got 90\n"


def test_geo_cell_and_point_go_both_ways(tools):
    r = tools("geo", "point", "2,24", "--mission", MISSION)
    assert r.returncode == 0, r.stderr
    pt = json.loads(r.stdout)
    assert pt["alt_m"] == 40.0
    g = WGS84.Inverse(47.3655, 8.5461, pt["lat"], pt["lon"])
    assert abs(g["s12"] - math.hypot(100, 1200)) < 0.05
    r = tools("geo", "cell", f"{pt['lat']},{pt['lon']}", "--mission", MISSION)
    assert r.returncode == 0, r.stderr
    cell = json.loads(r.stdout)
    assert (cell["x"], cell["y"]) == (2, 24)
    assert abs(cell["east_m"] - 100) < 0.02 and abs(cell["north_m"] - 1200) < 0.02
    r = sva_tools("geo", "cell", "47.3655,8.5461,3", "--mission", MISSION)
    assert r.returncode == 2 and r.stderr == ("sva-tools: error: geo: LAT,LON: must be LAT,LON in "
                                              "degrees, got '47.3655,8.5461,3'\n")
