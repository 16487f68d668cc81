"""A mission's optional frame (docs/flight-stack.md) in the CLI: `sva validate` and `sva
plan` check it (exit 2, one line naming the field, the rule and the limit); `sva plan`
and `sva replan` echo it into the plan with the same six keys, each value at its
stored resolution (1e-7 degree, cm, ms; t0 as UTC with milliseconds); `--residual`
keeps it."""
import json

import pytest

from test_cli import assert_one_error_line, check_plan, mission, run

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
    ({"lat": 85.5}, "frame.lat: 85.5 is outside [-85, 85] degrees"),
    ({"lon": -180.25}, "frame.lon: -180.25 is outside [-180, 180] degrees"),
    ({"alt_m": -1}, "frame.alt_m: -1 is outside [0, 10000] m"),
    ({"cell_m": 0.05}, "frame.cell_m: 0.05 is outside [0.1, 10000] m"),
    ({"cell_m": 20000}, "frame.cell_m: 20000 is outside [0.1, 10000] m"),
    ({"tick_s": 0}, "frame.tick_s: 0 is outside [0.001, 3600] s"),
    ({"t0": "2026-06-01 08:00:00"},
     "frame.t0: must be an ISO 8601 date-time with a UTC offset, e.g. 2026-06-01T08:00:00Z"),
    ({"t0": "2026-02-30T08:00:00Z"}, 'frame.t0: "2026-02-30T08:00:00Z" is not a calendar date and time'),
    ({"t0": "1969-12-31T23:59:59Z"},
     "frame.t0: must be between 1970-01-01T00:00:00Z and 9999-12-31T23:59:59.999Z"),
    ({"lat": "47.4"}, "frame.lat: must be a number, got string"),
    ({"t0": 0}, "frame.t0: must be a string, got integer"),
    ({"datum": "WGS84"}, 'frame: unknown key "datum"'),
])
@pytest.mark.parametrize("command", [["validate"], ["plan"]])
def test_bad_frame_field(tmp_path, change, message, command):
    _, path = framed(tmp_path, {**FRAME, **change})
    assert assert_one_error_line(run([*command, str(path)]), 2) == message


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
        "mission.frame.tick_s: 0 is outside [0.001, 3600] s")
