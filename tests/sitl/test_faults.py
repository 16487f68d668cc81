"""`sva-tools sitl --fault`: fixtures/scenarios/sitl_faults.json (four UAVs; three targets
at ticks 8 to 16, which leave UAV 1 free, then four at ticks 40 to 46, which need every
UAV) flown by four ArduCopter SITL vehicles at speedup 10, with faults injected:

- upload: UAV 2's link to the bridge goes silent at the take-off plan's MISSION_COUNT
  (silent-upload), and UAV 3's first waypoint is rewritten so that ArduCopter itself
  refuses the upload (reject-item). The bridge reports both LOST (the silence by its
  heartbeat timeout, the refusal at once) and the node replans their work to UAVs 1 and 4
  (UAV 1 takes a first-wave target over).
- reboot: UAV 2's SITL is killed 100 s of vehicle time after t0, on its way from its
  first target to its second, and a fresh one starts where it was, on the ground. The bridge reports
  it LOST from its link's drop, the node replans, then it is back: the next plan gives it
  work, a fresh upload, and the operator starts it again.

Each flight is judged from its log (--out) and end line: the faulty vehicle's remaining
targets went to the other vehicles only, every target the final plans promise is covered
in the telemetry, no other vehicle is late, and nothing is left behind. Run by
run_flight.sh (root and the SITL binary, else skipped); `-k upload`, `-k reboot` pick one.
"""
import json
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

from test_flight import ours, tool_env

REPO = Path(__file__).resolve().parents[2]
SCENARIO = REPO / "fixtures" / "scenarios" / "sitl_faults.json"
FLIGHTS = {"upload": ["--fault", "silent-upload:2", "--fault", "reject-item:3"],
           "reboot": ["--fault", "reboot:2:100"]}
REBOOTED = 2


def fly(kind, out):
    log = out / "log.json"
    t = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "sva_tools", "sitl", str(SCENARIO), "--speedup", "10",
                        "--out", str(log), "--quiet", *FLIGHTS[kind]],
                       capture_output=True, text=True, env=tool_env(), timeout=400)
    wall = time.monotonic() - t
    netns_after = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True).stdout.split()
    left = ours()
    assert r.returncode == 0, r.stderr[-3000:]
    print(f"sitl {kind} flight: {wall:.1f} s wall")
    return {"log": json.loads(log.read_text()), "stdout": r.stdout, "wall": wall,
            "netns_after": netns_after, "left": left}


@pytest.fixture(scope="module")
def upload(tmp_path_factory):
    return fly("upload", tmp_path_factory.mktemp("upload"))


@pytest.fixture(scope="module")
def reboot(tmp_path_factory):
    return fly("reboot", tmp_path_factory.mktemp("reboot"))


# --- what every fault flight must show ------------------------------------------------

def lines_of(log, uav):
    return [(at, text) for at, text in log["sitl"]["bridge"]["lines"] if f"uav {uav} (" in text]


def loss_replan(log, uav, after_ms):
    """The node's replan that took the UAV out of service after the fault."""
    return next(r for r in log["replans"] if r["cause"] == "report:uav_lost" and r["at_ms"] >= after_ms
                and uav not in [u["id"] for u in r["mission"]["uavs"]])


def check_cleanup(flight):
    lines = flight["stdout"].strip().splitlines()
    assert re.fullmatch(r"covered \d+ of \d+ coverable \(plan promised \d+\); arrival slack p50 \S+ s, "
                        r"p1 \S+ s; late arrivals \d+", lines[-1]), lines[-1]
    assert flight["left"] == ([], [])
    ns = flight["log"]["sitl"]["netns"]
    assert ns and ns.startswith("sva-lcm-") and ns not in flight["netns_after"]


def check_work_went_to_the_others(log, uav, fired_ms, back_ms=None):
    """The UAV's remaining targets (in the plan in force at the fault, windows not yet
    ended) are routed to other UAVs only until it is back, and none of its routes was
    uploaded to it meanwhile."""
    before = [r for r in log["replans"] if r["at_ms"] <= fired_ms][-1]
    tick_ms = log["sitl"]["frame"]["tick_s"] * 1000
    ends = {t["id"]: t["end"] for t in log["scenario"]["mission"]["targets"]}
    mine = [t for rt in before["plan"]["routes"] if rt["uav"] == uav for t in rt["targets"]
            if ends[t] * tick_ms > fired_ms]
    assert mine, "the faulty UAV had work left"
    loss = loss_replan(log, uav, fired_ms)
    assert all(u != uav for u, _t in loss["changes"]["added"])
    meanwhile = [r for r in log["replans"] if loss["at_ms"] <= r["at_ms"] and (back_ms is None or r["at_ms"] < back_ms)]
    for r in meanwhile:
        assert uav not in [rt["uav"] for rt in r["plan"]["routes"]], r["cause"]
    u = next(x for x in log["uavs"] if x["id"] == uav)
    assert not [x for x in u["uploads"] if x.get("items") and x["at_ms"] > fired_ms
                and (back_ms is None or x["at_ms"] < back_ms)]
    return loss, mine


def check_promised_covered_and_nobody_else_late(log, faulty):
    promised = [t for t in log["targets"] if t["promised"] and t["outcome"] != "lost"]
    assert promised and all(t["covered"] for t in promised), log["targets"]
    assert log["summary"]["covered"] >= log["summary"]["promised"] == len(promised)
    assert [m for m in log["summary"]["missed_visits"] if m[0] not in faulty] == []
    for u in log["uavs"]:
        if u["id"] not in faulty:
            assert all(v["slack_s"] >= 0 for v in u["visits"] if v["sent"]), u["visits"]


def latencies(log, uav, fired_ms, loss):
    """Vehicle ms from the fault to the node's replan and to the last upload it caused
    (every other vehicle holding its new mission)."""
    nxt = next((r["at_ms"] for r in log["replans"] if r["at_ms"] > loss["at_ms"]), None)
    ups = [x["at_ms"] for v in log["uavs"] if v["id"] != uav for x in v["uploads"]
           if x.get("items") and x["at_ms"] >= loss["at_ms"] and (nxt is None or x["at_ms"] <= nxt)]
    return loss["at_ms"] - fired_ms, (max(ups) - fired_ms) if ups else None


# --- the upload faults ----------------------------------------------------------------

def test_upload_flight_exits_0_and_leaves_nothing_behind(upload):
    check_cleanup(upload)


def test_upload_the_silent_vehicle_is_lost_by_its_heartbeat_and_its_work_replanned(upload):
    log = upload["log"]
    fault = next(f for f in log["sitl"]["faults"] if f["kind"] == "silent-upload")
    assert fault["uav"] == 2 and fault["fired_ms"] is not None and fault["count"] >= 4
    assert fault["dropped"]["to_vehicle"] >= 1 and fault["dropped"]["to_bridge"] > 100
    texts = [x for _a, x in lines_of(log, 2)]
    assert any(x.endswith("LOST: no HEARTBEAT for more than 500 ms") for x in texts), texts
    assert not any(re.search(r": uploaded \d+ items$", x) for x in texts)
    loss, mine = check_work_went_to_the_others(log, 2, fault["fired_ms"])
    to_replan, to_upload = latencies(log, 2, fault["fired_ms"], loss)
    print(f"silent-upload: fault to replan {to_replan} ms, to the last upload {to_upload} ms "
          f"(vehicle time); its targets {mine}, added {loss['changes']['added']}")
    assert 3000 <= to_replan <= 15_000           # the heartbeat timeout: 500 ms host, 5 s vehicle
    u2 = next(u for u in log["uavs"] if u["id"] == 2)
    assert u2["starts"] == [] and u2["out"] and u2["out"][0][1] is None   # never flew


def test_upload_the_refusing_vehicle_is_lost_at_once_and_its_work_replanned(upload):
    log = upload["log"]
    fault = next(f for f in log["sitl"]["faults"] if f["kind"] == "reject-item")
    assert fault["uav"] == 3 and fault["item"]["seq"] == 3 and fault["item"]["command"] == 16
    # ArduCopter's own mission code answered (the relay only rewrote the item)
    acks = [a for a in fault["acks"] if a["type"] != 0]
    assert len(acks) == 1 and acks[0]["result"].startswith("MAV_MISSION_"), fault["acks"]
    texts = [x for _a, x in lines_of(log, 3)]
    refused = f"error: MISSION_ACK: the vehicle refused the mission: {acks[0]['result']} ({acks[0]['type']})"
    assert any(x.endswith(refused) for x in texts), texts
    assert not any(" retry " in x for x in texts)   # refused for good: not tried again
    assert any("LOST: an upload failed for good" in x for x in texts), texts
    loss, mine = check_work_went_to_the_others(log, 3, fault["fired_ms"])
    to_replan, _ = latencies(log, 3, fault["fired_ms"], loss)
    print(f"reject-item: ArduCopter answered {acks[0]['result']}; fault to replan {to_replan} ms "
          f"(vehicle time); its targets {mine}")
    assert 0 < to_replan <= 3000                 # at once: no heartbeat timeout involved
    u3 = next(u for u in log["uavs"] if u["id"] == 3)
    assert u3["starts"] == []                    # it never held a mission of ours to start


def test_upload_every_promised_target_is_covered_and_nobody_else_is_late(upload):
    log = upload["log"]
    check_promised_covered_and_nobody_else_late(log, {2, 3})
    served = {u for t in log["targets"] if t["covered"] for u in t["served_by"]}
    assert served <= {1, 4}, served               # the faulty two never flew
    assert log["summary"]["covered"] >= 4
    # UAV 1, free in the first wave, took over a target of UAV 2's or 3's there
    added = [t for r in log["replans"] if r["cause"] == "report:uav_lost" for u, t in r["changes"]["added"]]
    assert set(added) & {1, 2}, log["replans"]


# --- the reboot -----------------------------------------------------------------------

def test_reboot_flight_exits_0_and_leaves_nothing_behind(reboot):
    check_cleanup(reboot)


def test_reboot_the_vehicle_is_lost_then_back_with_a_fresh_mission_and_started_again(reboot):
    log = reboot["log"]
    fault = next(f for f in log["sitl"]["faults"] if f["kind"] == "reboot")
    assert fault["uav"] == REBOOTED and 99_000 <= fault["fired_ms"] <= 102_000 and "skipped" not in fault
    ur = next(u for u in log["uavs"] if u["id"] == REBOOTED)
    assert len(ur["spells"]) == 2 and ur["spells"][1]["ready_utc_ms"] is not None
    texts = [x for _a, x in lines_of(log, REBOOTED)]
    assert any("connection lost" in x for x in texts)
    assert any("LOST: its link dropped, it rebooted" in x for x in texts), texts
    assert any(x.endswith("OK: heard again") for x in texts), texts
    loss = loss_replan(log, REBOOTED, fault["fired_ms"])
    back = next(r for r in log["replans"] if r["cause"] == "report:uav_back" and r["at_ms"] > loss["at_ms"])
    assert REBOOTED in [u["id"] for u in back["mission"]["uavs"]]
    loss, mine = check_work_went_to_the_others(log, REBOOTED, fault["fired_ms"], back["at_ms"])
    assert ur["out"] == [[loss["at"], back["at"]]]
    # back: the plan gives it work, the bridge uploads it afresh, the operator starts it
    new_route = next(rt["targets"] for rt in back["plan"]["routes"] if rt["uav"] == REBOOTED)
    assert new_route, "the second wave needs every UAV"
    fresh = [x for x in ur["uploads"] if x.get("items") and x["at_ms"] >= back["at_ms"]]
    assert fresh, ur["uploads"]
    started = [s for s in ur["starts"] if s["at_ms"] > fault["fired_ms"] and s.get("started_ms")]
    assert started and started[0]["started_ms"] > fresh[0]["at_ms"]
    by_id = {t["id"]: t for t in log["targets"]}
    assert all(by_id[t]["covered"] and REBOOTED in by_id[t]["served_by"] for t in new_route)
    to_replan, to_upload = latencies(log, REBOOTED, fault["fired_ms"], loss)
    print(f"reboot: fault to replan {to_replan} ms, to the last upload {to_upload} ms, to back "
          f"{back['at_ms'] - fault['fired_ms']} ms, to its fresh upload {fresh[0]['at_ms'] - fault['fired_ms']} "
          f"ms, to its start {started[0]['started_ms'] - fault['fired_ms']} ms (vehicle time); "
          f"its targets {mine}, then {new_route}")
    assert 0 < to_replan <= 3000                 # from the link's drop, not the heartbeat timeout


def test_reboot_every_promised_target_is_covered_and_nobody_else_is_late(reboot):
    check_promised_covered_and_nobody_else_late(reboot["log"], {REBOOTED})
