#!/usr/bin/env python3
"""Writes the checked-in seed corpora of the fuzz targets (tests/fuzz/corpus/).

Run from the repository root with the venv's Python after a build (the LCM seeds use
the build's generated Python types):
    SVA_LCM_PYTHON_TYPES=build/port/lcm/python PYTHONPATH=tools \\
        .venv/bin/python tests/fuzz/make_seeds.py
mission/  a few fixtures (valid and invalid) and hand-made edge missions;
lcm/      fleet + mission messages in fuzz_lcm.c's record format (one mission with a
          frame, one of another version);
can/      frame records (fuzz_can.c's format) of whole plan transfers, built with the
          DBC (cantools) and left to the harness's counter and CRC fix-up bits.
mavlink/  records of fuzz_mavlink.c's format: an upload answered to its end, telemetry,
          good frames behind stray bytes, cut and flipped frames, datagram ends.
`make_seeds.py mavlink` writes one corpus only (any of missions, lcm, can, mavlink).
"""
import json
import shutil
import struct
import sys
from pathlib import Path

import cantools

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "tests" / "fuzz" / "corpus"


def missions():
    d = OUT / "mission"
    d.mkdir(parents=True, exist_ok=True)
    for name in ["hand_3_1", "hand_5_3", "rand_7_1", "rand_10_1", "rand_25_1"]:
        shutil.copy(ROOT / "fixtures" / "missions" / f"{name}.json", d / f"{name}.json")
    for name in ["duplicate_uav_id", "duplicate_key", "beyond_int32", "blank"]:
        src = ROOT / "fixtures" / "invalid" / f"{name}.json"
        if src.exists():
            shutil.copy(src, d / f"invalid_{name}.json")
    # Hand-made: a stranded UAV, late ready_at, hover fuel, slow cells, every default
    # left out, and a UAV that starts away from the depot.
    edge = {"name": "edge", "depot": {"x": -3, "y": 2}, "ticks_per_cell": 2, "hover_fuel": 3,
            "overlap_percent": 0,
            "uavs": [{"id": 4, "x": 40, "y": 40, "fuel": 10},
                     {"id": 2, "x": -3, "y": 2, "fuel": 200, "ready_at": 5},
                     {"id": 9, "x": 1, "y": 1, "fuel": 90}],
            "targets": [{"id": 1, "x": 0, "y": 5, "start": 30, "end": 40, "need": 2},
                        {"id": 7, "x": 2, "y": -4, "start": 35, "end": 60, "need": 1},
                        {"id": 3, "x": -9, "y": 9, "start": 100, "end": 101, "need": 3}]}
    (d / "edge.json").write_text(json.dumps(edge) + "\n")
    (d / "defaults.json").write_text(json.dumps(
        {"name": "d", "depot": {"x": 0, "y": 0}, "uavs": [], "targets": []}) + "\n")


def lcm():
    from sva_tools.lcm import wire
    d = OUT / "lcm"
    d.mkdir(parents=True, exist_ok=True)
    for src in [ROOT / "fixtures" / "missions" / "rand_7_2.json",
                ROOT / "fixtures" / "missions" / "hand_3_1.json"]:
        _, fleet, mission = wire.mission_messages(json.loads(src.read_text()), 1, 1)
        f, m = fleet.encode(), mission.encode()
        # exact-size fleet, then exact-size mission with algorithm bits 0 (sva), 3 (bfa),
        # 4 (flow: its certificate travels in the plan)
        (d / f"{src.stem}.bin").write_bytes(bytes([0x02]) + f + bytes([0x03]) + m)
        (d / f"{src.stem}_bfa.bin").write_bytes(bytes([0x0E]) + f + bytes([0x0F]) + m)
        (d / f"{src.stem}_flow.bin").write_bytes(bytes([0x12]) + f + bytes([0x13]) + m)
        # a raw (length-prefixed) mission cut short, then the fleet twice (unchanged)
        (d / f"{src.stem}_raw.bin").write_bytes(
            bytes([0x01]) + struct.pack("<H", 100) + m[:100] + bytes([0x02]) + f + bytes([0x02]) + f)
    # a mission with a frame, then the same of mission_t version 1 (refused: version)
    doc = json.loads((ROOT / "fixtures" / "missions" / "rand_7_2.json").read_text())
    doc["frame"] = {"lat": 47.3977419, "lon": 8.5455939, "alt_m": 30, "cell_m": 10,
                    "tick_s": 1, "t0": "2026-06-01T08:00:00Z"}
    _, fleet, mission = wire.mission_messages(doc, 1, 1)
    f, m = fleet.encode(), mission.encode()
    mission.version = 1
    (d / "frame.bin").write_bytes(bytes([0x02]) + f + bytes([0x03]) + m + bytes([0x03])
                                  + mission.encode())


def can():
    db = cantools.database.load_file(str(ROOT / "port" / "can" / "sva.dbc"))
    d = OUT / "can"
    d.mkdir(parents=True, exist_ok=True)
    sel = {"SVA_PLAN_ABORT": 0, "SVA_PLAN_BEGIN": 1, "SVA_PLAN_ITEM": 2, "SVA_PLAN_ITEM_TIME": 3,
           "SVA_PLAN_COMMIT": 4, "SVA_PLAN_ACK": 5, "SVA_HEARTBEAT": 6}

    def rec(msg, fields, fix=0x70, dt=1):
        fields = dict(fields)
        for sig in db.get_message_by_name(msg).signals:
            fields.setdefault(sig.name, 0)
        data = db.get_message_by_name(msg).encode(fields, strict=False)
        return bytes([sel[msg] | fix, 0x08, dt]) + bytes(data)

    def transfer(plan_id, items):
        out = rec("SVA_PLAN_BEGIN", {"version": 1, "plan_id": plan_id, "item_count": len(items),
                                     "algorithm": 0, "plan_status": 1, "route_count": 2})
        for i, (uav, target, x, y, a, h) in enumerate(items):
            out += rec("SVA_PLAN_ITEM", {"uav_id": uav, "target_id": target, "x": x, "y": y})
            out += rec("SVA_PLAN_ITEM_TIME", {"item_seq": i % 16, "arrive_by": a, "hold_until": h})
        out += rec("SVA_PLAN_COMMIT", {"plan_id": plan_id, "plan_crc": 0})
        return out

    items = [(1, 3, 5, 7, 12, 20), (2, 3, 5, 7, 12, 20), (1, 9, -4, 0, 30, 45)]
    (d / "transfer.bin").write_bytes(transfer(5, items))
    (d / "two_transfers.bin").write_bytes(transfer(5, items) + transfer(6, items[:1]))
    # a transfer interrupted by an ABORT, a heartbeat and an ACK for the harness's sender
    (d / "abort_ack.bin").write_bytes(
        transfer(5, items)[:33] + rec("SVA_PLAN_ABORT", {"reason": 3, "plan_id": 5})
        + rec("SVA_HEARTBEAT", {"state": 4, "active_plan_id": 5, "uav_count": 2,
                                "target_count": 2, "covered_count": 2})
        + rec("SVA_PLAN_ACK", {"result": 0, "plan_id": 7, "items_received": 1}, fix=0x20))
    # a transfer that times out (255 * 16 ms between frames)
    (d / "timeout.bin").write_bytes(transfer(8, items[:1]).replace(b"\x72\x08\x01", b"\x72\x08\xff", 1))


def mavlink():
    """fuzz_mavlink.c's records: 0 raw, 1 good frame, 2 datagram end, 3 clock."""
    d = OUT / "mavlink"
    d.mkdir(parents=True, exist_ok=True)
    # the harness's message list (fuzz_mavlink.c `ids`), by name
    pick = {"HEARTBEAT": 0, "MISSION_REQUEST_INT": 1, "MISSION_REQUEST": 2, "MISSION_ACK": 3,
            "GLOBAL_POSITION_INT": 4, "SYS_STATUS": 5, "BATTERY_STATUS": 6,
            "MISSION_CURRENT": 7, "MISSION_ITEM_REACHED": 8, "SYSTEM_TIME": 9,
            "COMMAND_ACK": 10, "STATUSTEXT": 11}

    def frame(name, payload, how=0, sender=3):
        return bytes([1 | (how << 2), pick[name], sender, len(payload)]) + payload

    def raw(b):
        return bytes([0, len(b)]) + b

    own = (255, 190)  # the harness's system and component (MAV_COMP_ID_MISSIONPLANNER)
    upload = b"".join(frame("MISSION_REQUEST_INT", struct.pack("<HBBB", seq, *own, 0))
                      for seq in range(4))
    upload += frame("MISSION_ACK", struct.pack("<BBBB", *own, 0, 0))
    (d / "upload.bin").write_bytes(upload)
    # the legacy MISSION_REQUEST, a resend after a timeout, then a refusal
    (d / "legacy_refused.bin").write_bytes(
        frame("MISSION_REQUEST", struct.pack("<HBBB", 0, *own, 0)) + bytes([3, 40])
        + frame("MISSION_REQUEST", struct.pack("<HBBB", 1, *own, 0))
        + frame("MISSION_ACK", struct.pack("<BBBB", *own, 9, 0)))
    heartbeat = struct.pack("<IBBBBB", 3, 2, 3, 0x81, 4, 3)
    position = struct.pack("<IiiiihhhH", 5000, 473977000, 85456000, 520000, 30000, 100, 0, 0, 9000)
    system_time = struct.pack("<QI", 1_700_000_000_000_000, 5000)
    telemetry = (frame("HEARTBEAT", heartbeat) + frame("GLOBAL_POSITION_INT", position)
                 + frame("SYSTEM_TIME", system_time)
                 + frame("MISSION_CURRENT", struct.pack("<H", 2))
                 + frame("MISSION_ITEM_REACHED", struct.pack("<H", 1)))
    (d / "telemetry.bin").write_bytes(telemetry)
    # stray bytes (a MAVLink 2 start, a length, a flag) before good frames, per datagram
    (d / "stray_prefix.bin").write_bytes(
        raw(b"\xfd\xff\x00") + frame("HEARTBEAT", heartbeat) + bytes([2])
        + raw(b"\xfd\x09\x01\x00") + telemetry + bytes([2]))
    # cut, flipped and MAVLink 1 frames, other senders
    (d / "damaged.bin").write_bytes(
        frame("HEARTBEAT", heartbeat, how=1) + frame("SYSTEM_TIME", system_time, how=2)
        + bytes([2]) + frame("HEARTBEAT", heartbeat, how=3)
        + frame("GLOBAL_POSITION_INT", position, sender=0) + bytes([2]))


CORPORA = {"missions": missions, "lcm": lcm, "can": can, "mavlink": mavlink}

if __name__ == "__main__":
    for name in (sys.argv[1:] or list(CORPORA)):
        CORPORA[name]()
    for p in sorted(OUT.rglob("*")):
        if p.is_file():
            print(p.relative_to(ROOT), p.stat().st_size)
