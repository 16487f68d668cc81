"""The ground tool's conversions and errors, without any network."""
import json
from pathlib import Path

import pytest

from sva_tools.commands import lcm as lcm_command
from sva_tools.lcm import wire

REPO = Path(__file__).resolve().parents[2]
# A bundled mission with a mid-mission fleet state (UAVs away from the depot, ready times).
SMALL = REPO / "fixtures" / "missions" / "rand_7_2.json"


def small():
    return json.loads(SMALL.read_text())


def test_mission_round_trip_through_the_codec():
    t = wire.types()
    name, fleet, mission = wire.mission_messages(small(), 5, 6)
    f2 = t.fleet_state_t.decode(fleet.encode())
    m2 = t.mission_t.decode(mission.encode())
    assert name == "rand_7_2"
    assert (f2.revision, m2.revision) == (5, 6)
    assert f2.uav_count == 5 and [u.id for u in f2.uavs[:5]] == [1, 2, 3, 4, 5]
    assert [(u.x, u.y, u.fuel, u.ready_at_ticks) for u in f2.uavs[:2]] == [(19, 1, 66, 10),
                                                                          (19, 14, 67, 8)]
    assert m2.target_count == 7 and (m2.targets[6].id, m2.targets[6].need) == (7, 2)
    assert (m2.targets[6].start_ticks, m2.targets[6].end_ticks) == (44, 61)
    assert m2.hover_fuel == 2 and m2.overlap_percent == 70
    assert (f2.version, m2.version, m2.frame.present) == (2, 2, 0)  # no frame in the file
    assert len(fleet.encode()) == 1363 and len(mission.encode()) == 6212


def test_defaults_apply():
    doc = small()
    for k in ("ticks_per_cell", "hover_fuel", "overlap_percent"):
        del doc[k]
    _, _, m = wire.mission_messages(doc, 1, 1)
    assert (m.ticks_per_cell, m.hover_fuel, m.overlap_percent) == (1, 0, 70)


@pytest.mark.parametrize("edit, message", [
    (lambda d: d.update(extra=1), "extra: unknown key"),
    (lambda d: d["uavs"][2].pop("fuel"), "uavs[2].fuel: missing key"),
    (lambda d: d["targets"][1].update(need="2"), "targets[1].need: must be an integer"),
    (lambda d: d["targets"][1].update(x=True), "targets[1].x: must be an integer"),
    (lambda d: d["depot"].update(x=2**31), "depot.x: must fit int32"),
    (lambda d: d.update(uavs=[{"id": i, "x": 0, "y": 0, "fuel": 1} for i in range(65)]),
     "uavs: 65 entries exceed SVA_MAX_UAVS (64)"),
    (lambda d: d.update(targets=d["targets"] * 37), "exceed SVA_MAX_TARGETS (256)"),
])
def test_bad_mission_files(edit, message):
    doc = small()
    edit(doc)
    with pytest.raises(wire.InputError, match=message.replace("[", r"\[").replace("]", r"\]")
                       .replace("(", r"\(").replace(")", r"\)")):
        wire.mission_messages(doc, 1, 1)


def test_plan_document_and_diag_text():
    t = wire.types()
    p = t.plan_t()
    p.version = t.plan_t.VERSION
    p.status, p.algorithm, p.covered, p.cost = p.STATUS_PARTIAL, 1, 1, 30
    p.uncovered_count, p.uncovered[0] = 1, 9
    p.route_count = 2
    p.routes[0].uav_id, p.routes[0].target_count, p.routes[0].distance_cells = 4, 2, 30
    p.routes[0].fuel_used = 32
    p.routes[1].uav_id, p.routes[1].stranded = 5, 1
    p.item_count, p.route_targets[0], p.route_targets[1] = 2, 3, 1
    p2 = t.plan_t.decode(p.encode())
    doc = wire.plan_document(p2, "m")
    assert doc["routes"] == [{"uav": 4, "targets": [3, 1], "distance": 30, "fuel_used": 32},
                             {"uav": 5, "targets": [], "distance": 0, "fuel_used": 0}]
    assert doc["stranded"] == [5] and doc["uncovered"] == [9]
    assert (doc["status"], doc["algorithm"]) == ("partial", "ga")
    assert len(p.encode()) == 18977  # SVA_LCM_PLAN_BYTES
    assert not {"lower_bound", "optimal", "flow_incomplete"} & set(doc["stats"])  # no bound
    p.algorithm, p.has_bound, p.lower_bound, p.optimal, p.flow_incomplete = 4, 1, 27, 0, 1
    doc = wire.plan_document(t.plan_t.decode(p.encode()), "m")
    assert doc["algorithm"] == "flow"
    assert (doc["stats"]["lower_bound"], doc["stats"]["optimal"],
            doc["stats"]["flow_incomplete"]) == (27, False, 1)
    p.lower_bound, p.optimal, p.flow_incomplete = 30, 1, 0
    assert wire.plan_document(t.plan_t.decode(p.encode()), "m")["stats"]["optimal"] is True
    p.status, p.diag_field, p.diag_rule, p.diag_index = p.STATUS_REJECTED, 18, 1, 3
    p.diag_value, p.diag_limit = 0, 1
    assert wire.diag_text(p) == "targets[3].need: must be >= 1, got 0"


def test_cli_errors_without_network(tmp_path, capsys):
    assert lcm_command.main(["send", str(tmp_path / "missing.json")]) == 2
    assert "missing.json" in capsys.readouterr().err
    assert lcm_command.main(["bogus"]) == 2
    assert lcm_command.main(["--help"]) == 0


def test_sva_tools_wrapper_dispatches_lcm(tmp_path):
    """`tools/sva-tools lcm ...` (the repository wrapper and the installed entry point)
    reaches sva_tools.commands.lcm.main: its own usage, its own errors and exit codes."""
    import subprocess

    wrapper = REPO / "tools" / "sva-tools"
    r = subprocess.run([str(wrapper), "lcm", "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("usage: sva-tools lcm") and "{send,scenario,record,replay}" in r.stdout
    r = subprocess.run([str(wrapper), "lcm", "send", str(tmp_path / "missing.json")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2
    assert r.stderr.startswith("sva-tools lcm send: ") and "missing.json" in r.stderr
    r = subprocess.run([str(wrapper), "lcm", "send", str(SMALL), "--url", "memq://",
                        "--timeout", "0.2"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 3 and "no plan on SVA_PLAN" in r.stderr  # nobody answers on memq


def test_event_messages_and_their_shape_errors():
    """SPEC 12.5 event objects to event_t (version 1, seq, every field) and back through
    the codec; a bad event names the field and the rule."""
    t = wire.types()
    tg = {"id": 9, "x": 2, "y": -3, "start": 40, "end": 50, "need": 2}
    e = t.event_t.decode(wire.event_message({"at": 14, "type": "target_added", "target": tg},
                                            5).encode())
    assert (e.version, e.seq, e.type, e.at_ticks) == (1, 5, 4, 14)
    assert (e.target.id, e.target.x, e.target.y, e.target.start_ticks, e.target.end_ticks,
            e.target.need) == (9, 2, -3, 40, 50, 2)
    e = wire.event_message({"at": 3, "type": "uav_back", "uav": 2, "x": 4, "y": 5, "fuel": 60}, 0)
    assert (e.type, e.uav_id, e.x, e.y, e.fuel) == (2, 2, 4, 5, 60)
    assert wire.event_message({"at": 3, "type": "target_cancelled", "target": 4}, 0).target.id == 4
    assert len(e.encode()) == 62
    for doc, message in [
        ({"at": 1, "type": "explode"}, "events[0].type: must be one of clock, uav_lost"),
        ({"at": 1, "type": "uav_lost"}, "events[0].uav: missing key (a uav_lost event needs it)"),
        ({"at": 1, "type": "clock", "uav": 3}, "events[0].uav: not a field of a clock event"),
        ({"at": "1", "type": "clock"}, "events[0].at: must be an integer"),
    ]:
        with pytest.raises(wire.InputError, match=message.replace("[", r"\[").replace("]", r"\]")
                           .replace("(", r"\(").replace(")", r"\)")):
            wire.event_message(doc, 0, "events[0].")


def test_replan_document_and_version():
    """A refused replan_t gives its text; an accepted one its residual mission and plan;
    another version is refused naming both."""
    t = wire.types()
    r = t.replan_t()
    r.version, r.event_seq, r.event_type, r.accepted = t.replan_t.VERSION, 3, 1, 0
    r.now_ticks, r.revision = 14, 2
    r.diag_text = list(b"SVA_EVENT: event.at: 3 is before now (14)".ljust(160, b"\0"))
    r = t.replan_t.decode(r.encode())
    assert wire.replan_document(r, "m") == {
        "event_seq": 3, "event": "uav_lost", "accepted": False, "now": 14, "revision": 2,
        "error": "SVA_EVENT: event.at: 3 is before now (14)"}
    r.version = 1
    with pytest.raises(wire.InputError, match=r"replan_t.version is 1, this tool speaks version 2"):
        wire.replan_document(r, "m")
    p = t.plan_t()
    p.version = 1
    with pytest.raises(wire.InputError, match=r"plan_t.version is 1, this tool speaks version 2"):
        wire.plan_document(p, "m")


FRAME = {"lat": -33.8567844, "lon": 151.2152967, "alt_m": 120.005, "cell_m": 0.125,
         "tick_s": 0.001, "t0": "2026-06-01T10:00:00.0005+02:00"}


def test_frame_message_round_trip():
    """A mission's frame to frame_t: rounded half away from zero to the wire's resolution
    as sva_frame_from_units rounds, t0 in UTC ms; back to JSON at that resolution.
    Missions without a frame send present 0 and every field 0."""
    t = wire.types()
    _, fleet, mission = wire.mission_messages(dict(small(), frame=FRAME), 1, 1)
    assert (fleet.version, mission.version) == (2, 2)
    m = t.mission_t.decode(mission.encode())
    f = m.frame
    assert (f.present, f.lat_e7, f.lon_e7, f.alt_cm, f.cell_cm, f.tick_ms) == (
        1, -338567844, 1512152967, 12001, 13, 1)
    assert f.t0_ms == 1780300800001  # 08:00:00.0005Z rounds up to .001
    assert wire.frame_document(f) == {"lat": -33.8567844, "lon": 151.2152967, "alt_m": 120.01,
                                      "cell_m": 0.13, "tick_s": 0.001,
                                      "t0": "2026-06-01T08:00:00.001Z"}
    back = wire.mission_document(fleet, m, "x")
    assert back["frame"] == wire.frame_document(f)
    _, _, plain = wire.mission_messages(small(), 1, 1)
    assert plain.frame.present == 0 and plain.frame.t0_ms == 0 and plain.frame.cell_cm == 0
    assert "frame" not in wire.mission_document(fleet, plain, "x")


@pytest.mark.parametrize("frame, message", [
    (dict(FRAME, cell_m=0.05), "frame.cell_m: must be >= 0.1, got 0.05"),
    (dict(FRAME, lat=85.5), "frame.lat: must be <= 85, got 85.5"),
    (dict(FRAME, tick_s=4000), "frame.tick_s: must be <= 3600, got 4000"),
    (dict(FRAME, alt_m="30"), "frame.alt_m: must be a number, got string"),
    (dict(FRAME, t0="2026-06-01 08:00"), "frame.t0: must be an ISO 8601 date-time with a UTC"),
    (dict(FRAME, t0="2026-02-30T08:00:00Z"),
     'frame.t0: must be a date of the calendar, got "2026-02-30T08:00:00Z"'),
    (dict(FRAME, t0="1969-12-31T23:59:59Z"),
     'frame.t0: must be >= 1970-01-01T00:00:00Z, got "1969-12-31T23:59:59Z"'),
    (dict(FRAME, datum="WGS84"), 'frame: unknown key "datum"'),
    ({k: v for k, v in FRAME.items() if k != "t0"}, 'frame: missing key "t0"'),
    ([47.4, 8.5], "frame: must be an object, got array"),
])
def test_frame_errors_name_field_rule_limit(frame, message):
    with pytest.raises(wire.InputError) as e:
        wire.mission_messages(dict(small(), frame=frame), 1, 1)
    assert str(e.value).startswith(message)


def test_scenario_file_errors_without_network(tmp_path, capsys):
    bad = tmp_path / "s.json"
    bad.write_text(json.dumps({"mission": small(), "events": [{"at": 1, "type": "nope"}]}))
    assert lcm_command.main(["scenario", str(bad), "--timeout", "0.1"]) == 2
    assert "events[0].type: must be one of" in capsys.readouterr().err
    bad.write_text(json.dumps({"mission": small(), "events": [], "extra": 1}))
    assert lcm_command.main(["scenario", str(bad)]) == 2
    assert "extra: unknown key" in capsys.readouterr().err
