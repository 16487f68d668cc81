"""A mission's optional frame (docs/flight-stack.md) in the CLI: `sva validate` and `sva
plan` check it (exit 2, one line naming the field, the rule and the limit); `sva plan`
and `sva replan` echo it into the plan with the same six keys, each value at its
stored resolution (1e-7 degree, cm, ms; t0 as UTC with milliseconds); `--residual`
keeps it."""
import json
import sys
from pathlib import Path

import pytest

from test_cli import assert_one_error_line, check_plan, mission, run

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
from sva_tools.frame import Frame  # noqa: E402  (the frame's contract)
from sva_tools import schema  # noqa: E402

pytestmark = pytest.mark.sanitize  # cheap: also run against the ASan/UBSan build

FRAME = {"lat": 47.39774189, "lon": -122.3493, "alt_m": 30.004, "cell_m": 12.5, "tick_s": 0.25,
         "t0": "2026-06-01T10:00:00.0004+02:00"}
# What the plan echoes: rounded half away from zero to the stored integers, printed back.
ECHO = {"lat": 47.3977419, "lon": -122.3493, "alt_m": 30.0, "cell_m": 12.5, "tick_s": 0.25,
        "t0": "2026-06-01T08:00:00.000Z"}


def framed(tmp_path, frame, name="hand_3_1"):
    doc = mission(name)
    doc["frame"] = frame
    path = tmp_path / "framed.json"
    path.write_text(json.dumps(doc))
    return doc, path


def test_plan_echoes_the_frame(tmp_path):
    doc, path = framed(tmp_path, FRAME)
    result = run(["plan", "--algo", "sva", str(path)])
    assert result.returncode == 0, result.stderr
    plan = json.loads(result.stdout)
    assert list(plan)[-1] == "frame" and plan["frame"] == ECHO
    assert list(plan["frame"]) == ["lat", "lon", "alt_m", "cell_m", "tick_s", "t0"]
    # the cells and ticks are the mission's: the plan is the one without a frame
    (tmp_path / "plain.json").write_text(json.dumps(mission("hand_3_1")))
    plain = json.loads(run(["plan", "--algo", "sva", str(tmp_path / "plain.json")]).stdout)
    assert "frame" not in plain
    assert {k: v for k, v in plan.items() if k not in ("frame", "stats")} == {
        k: v for k, v in plain.items() if k != "stats"}
    check_plan(doc, {k: v for k, v in plan.items() if k != "frame"}, "sva")
    # printed exactly: the text holds the decimals, not a binary expansion
    text = result.stdout.decode()
    assert '"lat": 47.3977419,' in text and '"alt_m": 30.0,' in text and '"tick_s": 0.25,' in text
    ok = run(["validate", str(path)])
    assert ok.returncode == 0 and ok.stdout.decode().startswith("ok: hand_3_1:")


def test_echo_is_a_fixed_point(tmp_path):
    """A plan's frame, given back as a mission's frame, echoes unchanged."""
    _, path = framed(tmp_path, ECHO)
    plan = json.loads(run(["plan", str(path)]).stdout)
    assert plan["frame"] == ECHO


@pytest.mark.parametrize("change, message", [
    ({"lat": 85.5}, "frame.lat: must be <= 85, got 85.5"),
    ({"lon": -180.25}, "frame.lon: must be >= -180, got -180.25"),
    ({"alt_m": -1}, "frame.alt_m: must be >= 0, got -1"),
    ({"alt_m": -1.0}, "frame.alt_m: must be >= 0, got -1.0"),
    ({"cell_m": 0.05}, "frame.cell_m: must be >= 0.1, got 0.05"),
    ({"cell_m": 20000}, "frame.cell_m: must be <= 10000, got 20000"),
    ({"cell_m": 1e-5}, "frame.cell_m: must be >= 0.1, got 1e-05"),
    ({"cell_m": 1e20}, "frame.cell_m: must be <= 10000, got 1e+20"),
    ({"tick_s": 0}, "frame.tick_s: must be >= 0.001, got 0"),
    ({"tick_s": 0.00049999}, "frame.tick_s: must be >= 0.001, got 0.00049999"),
    ({"t0": "2026-06-01 08:00:00"},
     "frame.t0: must be an ISO 8601 date-time with a UTC offset (YYYY-MM-DDThh:mm:ss[.fff] "
     'then Z or +hh:mm or -hh:mm), got "2026-06-01 08:00:00"'),
    ({"t0": "8 \"h\"\\\u00e9\U0001f6f8\x01"},
     "frame.t0: must be an ISO 8601 date-time with a UTC offset (YYYY-MM-DDThh:mm:ss[.fff] "
     'then Z or +hh:mm or -hh:mm), got "8 \\"h\\"\\\\\\u00e9\\ud83d\\udef8\\u0001"'),
    ({"t0": "2026-02-30T08:00:00Z"}, 'frame.t0: must be a date of the calendar, got "2026-02-30T08:00:00Z"'),
    ({"t0": "2026-06-01T08:00:60Z"},
     'frame.t0: must have a time of day within 00:00:00..23:59:59, got "2026-06-01T08:00:60Z"'),
    ({"t0": "2026-06-01T08:00:00-00:60"},
     'frame.t0: must have a UTC offset within -23:59..+23:59, got "2026-06-01T08:00:00-00:60"'),
    ({"t0": "1969-12-31T23:59:59Z"},
     'frame.t0: must be >= 1970-01-01T00:00:00Z, got "1969-12-31T23:59:59Z"'),
    ({"t0": "9999-12-31T23:59:59.9991Z"},
     'frame.t0: must be <= 9999-12-31T23:59:59.999Z, got "9999-12-31T23:59:59.9991Z"'),
    ({"lat": "47.4"}, "frame.lat: must be a number, got string"),
    ({"t0": 0}, "frame.t0: must be a string, got integer"),
    ({"datum": "WGS84"}, 'frame: unknown key "datum"'),
])
@pytest.mark.parametrize("command", [["validate"], ["plan"]])
def test_bad_frame_field(tmp_path, change, message, command):
    """The C CLI's message is the Python tools' (the contract, docs/flight-stack.md)."""
    doc, path = framed(tmp_path, {**FRAME, **change})
    assert schema.first_error(doc, "mission") == message
    assert assert_one_error_line(run([*command, str(path)]), 2) == message


# Literals near a tie of their resolution (half away from zero on the decimal as
# written), where the double is just below or just above the tie; 17 significant
# digits where the shortest form and 15 digits part (47.123456749999995 reads
# 47.12345675 at 15 digits, which would round up).
TIES = [
    {"lat": 47.12345675, "lon": 8.00000005, "alt_m": 0.125, "cell_m": 1.005, "tick_s": 1.0005},
    {"lat": -47.12345675, "lon": -8.00000005, "alt_m": 2.675, "cell_m": 0.145, "tick_s": 0.0015},
    {"lat": 47.123456749999995, "lon": 179.99999995, "alt_m": 9999.995, "cell_m": 9999.994,
     "tick_s": 3599.9995},
    {"lat": -5e-08, "lon": 4e-08, "alt_m": 0.004, "cell_m": 0.105, "tick_s": 1.0004},
    {"lat": 0.30000000000000004, "lon": -0.1, "alt_m": 1e-2, "cell_m": 0.1, "tick_s": 1},
    {"lat": 84.99999995, "lon": -179.99999995, "alt_m": 5, "cell_m": 10000, "tick_s": 3600},
]
T0S = ["2026-06-01T08:00:00.0005Z", "2026-06-01T08:00:00.00049999Z",
       "2026-06-01T10:00:00.9995+02:00", "1970-01-01T00:00:00.0004Z", "9999-12-31T23:59:59.999Z",
       "2026-06-01T08:00:00.123456789-05:30"]


@pytest.mark.parametrize("case", range(len(TIES)))
def test_the_echo_is_what_the_python_tools_make(tmp_path, case):
    """`sva plan`'s echoed frame equals sva_tools.frame's rounding of the same mission."""
    frame = {**TIES[case], "t0": T0S[case]}
    doc, path = framed(tmp_path, frame)
    plan = json.loads(run(["plan", str(path)]).stdout)
    assert plan["frame"] == Frame.from_json(frame).to_json()


@pytest.mark.parametrize("frame, message", [
    ({k: v for k, v in FRAME.items() if k != "t0"}, 'frame: missing key "t0"'),
    ({k: v for k, v in FRAME.items() if k != "cell_m"}, 'frame: missing key "cell_m"'),
    ([1, 2], "frame: must be an object, got array"),
])
def test_frame_shape(tmp_path, frame, message):
    _, path = framed(tmp_path, frame)
    assert assert_one_error_line(run(["plan", str(path)]), 2) == message


def test_replan_echoes_the_frame_and_the_residual_keeps_it(tmp_path):
    doc = mission("hand_3_1")
    doc["frame"] = FRAME
    live = tmp_path / "live.json"
    residual = tmp_path / "residual.json"
    live.write_text(json.dumps({"mission": doc, "events": [{"at": 2, "type": "clock"}]}))
    result = run(["replan", "--residual", str(residual), str(live)])
    assert result.returncode == 0, result.stderr
    plan = json.loads(result.stdout)
    assert list(plan)[-1] == "frame" and plan["frame"] == ECHO
    rest = json.loads(residual.read_text())
    assert rest["frame"] == ECHO
    # the residual mission, frame and all, is a mission `sva plan` accepts
    again = run(["plan", str(residual)])
    assert again.returncode == 0, again.stderr
    assert json.loads(again.stdout)["frame"] == ECHO
    live.write_text(json.dumps({"mission": {**doc, "frame": {**FRAME, "tick_s": 0}}}))
    assert assert_one_error_line(run(["replan", str(live)]), 2) == (
        "mission.frame.tick_s: must be >= 0.001, got 0")
