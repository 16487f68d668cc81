"""The SITL flight's bookkeeping that needs no autopilot: the loss latencies the judge
reads from a record (tools/sva_tools/sitl/judge.py) and the fleet clock the record's
instants come from (tools/sva_tools/sitl/flight.py)."""
import time
import types

from sva_tools.sitl import judge
from sva_tools.sitl.flight import Flight


def record(uploads, pid=7):
    """UAV 1 lost at 1,000 ms; the node's replan without it read at 1,200 ms."""
    replans = [
        {"at_ms": 0, "at": 0, "cause": "start", "mission": {"uavs": [{"id": 1}, {"id": 2}]},
         "plan": {"stats": {"plan_id": 6}}, "changes": {"dropped": []}},
        {"at_ms": 1200, "at": 3, "cause": "report:uav_lost", "mission": {"uavs": [{"id": 2}]},
         "plan": {"stats": {"plan_id": pid}}, "changes": {"dropped": [[1, 5]]}},
    ]
    events = [{"type": "uav_lost", "uav": 1, "at": 2, "at_ms": 1000}]
    uavs = [{"id": 1, "uploads": []},
            {"id": 2, "uploads": [dict(u, items=[]) for u in uploads]}]
    return {"replans": replans, "sitl": {"events": events}, "uavs": uavs}


def test_an_upload_of_the_replans_plan_counts_whenever_its_line_was_read():
    # the bridge's line about plan 7 read 5 ms before the node's reply that carries it
    [row] = judge._losses(record([{"at_ms": 1195, "plan": 7}, {"at_ms": 1300, "plan": 6}]))
    assert row["uav"] == 1 and row["replan_ms"] == 200
    assert row["uploaded_to"] == [2] and row["upload_ms"] == 195
    assert row["dropped"] == [[1, 5]]


def test_uploads_of_other_plans_do_not_count():
    [row] = judge._losses(record([{"at_ms": 1300, "plan": 6}, {"at_ms": 1400, "plan": 8}]))
    assert row["replan_ms"] == 200
    assert row["uploaded_to"] == [] and row["upload_ms"] is None


def test_without_plan_ids_only_the_uploads_after_the_replan_count():
    [row] = judge._losses(record([{"at_ms": 1195, "plan": None}, {"at_ms": 1250, "plan": None}],
                                 pid=None))
    assert row["uploaded_to"] == [2] and row["upload_ms"] == 250


class Clock:
    def __init__(self, ms):
        self.ms = ms
        self.in_service = True
        self.ready = True

    def utc_ms(self):
        return self.ms


def test_the_fleet_clock_never_runs_back_when_a_vehicle_leaves():
    fl = Flight.__new__(Flight)
    a, b, c = Clock(1000.0), Clock(1040.0), Clock(1080.0)
    fl.crafts, fl._last_fleet, fl.s = [a, b, c], None, types.SimpleNamespace(speedup=1.0)
    assert fl.fleet_utc_ms() == 1040.0
    c.in_service = False
    b.in_service = False
    assert fl.fleet_utc_ms() == 1040.0  # a alone says 1000: held at 1040
    a.ms = 1100.0
    assert fl.fleet_utc_ms() == 1100.0
    a.in_service = False  # nobody: the last clock runs on
    t = fl.fleet_utc_ms()
    assert t is not None and t >= 1100.0
    time.sleep(0.01)
    assert fl.fleet_utc_ms() > t
