"""Cross-check of the C codec against cantools and the DBC, both directions, field by
field and byte for byte, plus a whole plan transfer produced by the core."""
import json
import os
import random
import subprocess
from pathlib import Path

import cantools
import pytest

import can_wire

TOOL = os.environ.get("SVA_CAN_FRAMES_TOOL", "")
HERE = Path(__file__).resolve().parent
SEED = int(os.environ.get("SVA_CAN_SEED", "20260521"))


FRAME_MESSAGES = ["SVA_MISSION_FRAME_A", "SVA_MISSION_FRAME_B", "SVA_MISSION_FRAME_C",
                  "SVA_MISSION_FRAME_D"]


class PlanMessages:
    """The DBC as the generic codec (sva_can_encode/decode) sees it: every message but the
    mission frame's, which has a codec of its own (sva_can_mission_frame.h; tested below)."""

    def __init__(self, db):
        self._db = db
        self.messages = [m for m in db.messages if m.name not in FRAME_MESSAGES]

    def __getattr__(self, name):
        return getattr(self._db, name)


@pytest.fixture(scope="module")
def full_db():
    return can_wire.load_db()


@pytest.fixture(scope="module")
def db(full_db):
    return PlanMessages(full_db)


@pytest.fixture(scope="module")
def codec():
    assert TOOL and Path(TOOL).is_file(), f"SVA_CAN_FRAMES_TOOL not set or missing: {TOOL!r}"
    proc = subprocess.Popen([TOOL, "codec"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)

    def ask(line):
        proc.stdin.write(line + "\n")
        proc.stdin.flush()
        return proc.stdout.readline().strip()

    yield ask
    proc.stdin.close()
    proc.wait(timeout=10)


def value_sets(msg, rng):
    """Signal values (crc excluded): each signal's minimum, its maximum, then random ones,
    within the DBC ranges, with arrive_by < hold_until."""
    sigs = [s for s in msg.signals if s.name != "crc"]
    sets = [{s.name: int(s.minimum) for s in sigs}, {s.name: int(s.maximum) for s in sigs}]
    for _ in range(40):
        sets.append({s.name: rng.randint(int(s.minimum), int(s.maximum)) for s in sigs})
    for v in sets:
        if "arrive_by" in v and v["arrive_by"] >= v["hold_until"]:
            v["arrive_by"], v["hold_until"] = sorted((v["arrive_by"], v["hold_until"]))
            if v["arrive_by"] == v["hold_until"]:
                v["arrive_by"] = v["hold_until"] - 1 if v["hold_until"] > 0 else 0
                v["hold_until"] = max(v["hold_until"], 1)
    return sets


def parse_decoded(line):
    name, *pairs = line.split()
    return name, {k: int(v) for k, v in (p.split("=") for p in pairs)}


def test_dbc_describes_ten_messages_with_counter_and_crc(db):
    assert len(db.messages) == 10
    for msg in db.messages:
        assert not msg.is_extended_frame and msg.frame_id <= 0x7FF and msg.length == 8
        counter = msg.get_signal_by_name("counter")
        crc = msg.get_signal_by_name("crc")
        assert (counter.start, counter.length, counter.byte_order) == (0, 4, "little_endian")
        assert (crc.start, crc.length) == (56, 8)
        assert all(s.byte_order == "little_endian" for s in msg.signals)


def test_c_encode_is_decoded_by_cantools(db, codec):
    rng = random.Random(SEED)
    print(f"seed {SEED} (replay with SVA_CAN_SEED={SEED})")
    checked = 0
    for msg in db.messages:
        for values in value_sets(msg, rng):
            line = codec("encode " + msg.name + " " + " ".join(f"{k}={v}" for k, v in values.items()))
            assert not line.startswith("error"), (msg.name, values, line)
            fid, data = can_wire.parse_frame(line)
            assert fid == msg.frame_id
            assert data[7] == can_wire.crc8(fid, data), "C CRC-8 differs from crccheck's"
            decoded = db.decode_message(fid, data, decode_choices=False)
            for k, v in values.items():
                assert decoded[k] == v, (msg.name, k, values, line)
            # Byte for byte what cantools itself encodes from the DBC.
            ref = db.encode_message(fid, dict(values, crc=0), strict=True)
            assert can_wire.with_crc(fid, ref) == data
            checked += 1
    assert checked == 10 * 42


def test_cantools_encode_is_decoded_by_c(db, codec):
    rng = random.Random(SEED + 1)
    for msg in db.messages:
        for values in value_sets(msg, rng):
            data = can_wire.with_crc(msg.frame_id, db.encode_message(msg.frame_id, dict(values, crc=0), strict=True))
            line = codec(f"decode {msg.frame_id:03X}#{data.hex().upper()}")
            assert not line.startswith("error"), (msg.name, values, line)
            name, got = parse_decoded(line)
            assert name == msg.name
            for k, v in values.items():
                assert got[k] == v, (msg.name, k)
            assert got["crc"] == data[7]


def test_c_rejects_what_cantools_sends_with_a_bad_crc_or_dlc(db, codec):
    msg = db.get_message_by_name("SVA_PLAN_ITEM")
    data = bytearray(can_wire.with_crc(0x102, db.encode_message(0x102, {"counter": 1, "uav_id": 3, "target_id": 9,
                                                                      "x": -5, "y": 7, "crc": 0})))
    data[7] ^= 0x01
    assert codec(f"decode 102#{data.hex()}") == "error crc"
    assert codec(f"decode 102#{bytes(data[:6]).hex()}") == "error dlc"
    assert msg.frame_id == 0x102


def test_core_plan_transfer_decodes_with_cantools(db):
    assert TOOL, "SVA_CAN_FRAMES_TOOL not set"
    out = subprocess.run([TOOL, "plan", str(HERE / "data" / "mission_25x5.json"), "sva", "7"],
                         check=True, capture_output=True, text=True, timeout=60).stdout
    plan = json.loads(out)
    frames = [can_wire.parse_frame(f) for f in plan["frames"]]
    assert len(frames) == 2 * len(plan["items"]) + 2
    decoded = can_wire.decode_transfers(db, frames)
    assert len(decoded) == 1
    got = decoded[0]
    assert got["plan_id"] == 7
    assert got["plan_crc"] == plan["plan_crc"]
    assert got["items"] == plan["items"]
    assert got["route_count"] == 5
    print(f"25-target 5-UAV plan: {len(plan['items'])} items, {len(frames)} frames, covered {plan['covered']}")


def test_every_named_value_is_inside_its_signal_range(db):
    """A VAL_ entry outside the signal's [min|max] is a DBC that contradicts itself (the
    BEGIN.algorithm range once stopped at 3 while VAL_ named 4 "flow"). cantools 45's
    strict encoding lets a named value through whatever the range, so it would not
    notice; range-checking tools that read the DBC would refuse the value."""
    for msg in db.messages:
        for sig in msg.signals:
            for value, name in (sig.choices or {}).items():
                assert sig.minimum <= value <= sig.maximum, (msg.name, sig.name, value, str(name))


def test_begin_algorithm_range_is_what_the_c_codec_accepts(db, codec):
    """SVA_PLAN_BEGIN.algorithm: the DBC range is exactly the values the C decoder
    accepts (the core's algorithms, flow included), each named by its VAL_ entry; every
    algorithm goes through cantools (strict) and the C codec byte for byte, both ways."""
    sig = db.get_message_by_name("SVA_PLAN_BEGIN").get_signal_by_name("algorithm")
    names = ["sva", "ga", "hga", "bfa", "flow"]  # sva_algorithm_t order
    assert {k: str(v) for k, v in sig.choices.items()} == dict(enumerate(names))
    base = {"counter": 3, "version": 2, "plan_id": 42, "item_count": 7, "plan_status": 1,
            "route_count": 5, "crc": 0}
    accepted = []
    for number in range(16):  # every value of the 4-bit field
        data = can_wire.with_crc(0x101, db.encode_message(0x101, dict(base, algorithm=number),
                                                          strict=False))
        line = codec(f"decode 101#{data.hex().upper()}")
        if not line.startswith("error "):
            accepted.append(number)
    assert accepted == list(range(int(sig.minimum), int(sig.maximum) + 1)) == list(range(len(names)))
    for number, name in enumerate(names):
        # cantools (strict, by name) -> C decoder
        data = can_wire.with_crc(0x101, db.encode_message(0x101, dict(base, algorithm=name)))
        got_name, got = parse_decoded(codec(f"decode 101#{data.hex().upper()}"))
        assert (got_name, got["algorithm"]) == ("SVA_PLAN_BEGIN", number), name
        # C encoder -> the same bytes; cantools decodes the name and (strict, by number)
        # encodes the same bytes
        line = codec("encode SVA_PLAN_BEGIN " + " ".join(
            f"{k}={v}" for k, v in dict(base, algorithm=number).items() if k != "crc"))
        assert can_wire.parse_frame(line) == (0x101, data), name
        assert str(db.decode_message(0x101, data)["algorithm"]) == name
        assert can_wire.with_crc(0x101, db.encode_message(0x101, dict(base, algorithm=number))) == data
    with pytest.raises(cantools.database.EncodeError):
        db.encode_message(0x101, dict(base, algorithm=len(names)))


def test_core_flow_plan_transfer_decodes_with_cantools(db):
    """A flow plan made by the core goes out with BEGIN.algorithm 4, which cantools
    decodes as "flow" and re-encodes unchanged with strict range checking."""
    assert TOOL, "SVA_CAN_FRAMES_TOOL not set"
    out = subprocess.run([TOOL, "plan", str(HERE / "data" / "mission_25x5.json"), "flow", "9"],
                         check=True, capture_output=True, text=True, timeout=60).stdout
    plan = json.loads(out)
    frames = [can_wire.parse_frame(f) for f in plan["frames"]]
    decoded = can_wire.decode_transfers(db, frames)
    assert len(decoded) == 1 and decoded[0]["algorithm"] == 4
    assert decoded[0]["plan_crc"] == plan["plan_crc"] and decoded[0]["items"] == plan["items"]
    fid, begin = frames[0]
    assert fid == 0x101
    sig = db.decode_message(fid, begin)
    assert str(sig["algorithm"]) == "flow"
    assert can_wire.with_crc(fid, db.encode_message(fid, dict(sig, crc=0))) == begin


def test_dbc_and_c_speak_protocol_version_2(db):
    """The DBC's VERSION string names the protocol version the C port puts in BEGIN."""
    assert db.version == "sva-can 2"
    begin = db.get_message_by_name("SVA_PLAN_BEGIN")
    data = can_wire.with_crc(0x101, begin.encode({"counter": 0, "version": 2, "plan_id": 1,
                                                  "item_count": 0, "algorithm": 0,
                                                  "plan_status": 1, "route_count": 0, "crc": 0}))
    assert db.decode_message(0x101, data)["version"] == 2


def test_frame_check_against_cantools_frames(db, codec):
    """sva_can_frame_check() on frames cantools encodes (CRC-8 from crccheck): a
    counter sequence passes; a corrupted CRC, a flipped data bit, a skipped or repeated
    counter and a short frame each fail with the check that catches them."""
    clock = db.get_message_by_name("SVA_MISSION_CLOCK")
    status = db.get_message_by_name("SVA_VEHICLE_STATUS")

    def frame(msg, counter, **sig):
        return can_wire.with_crc(msg.frame_id, msg.encode(dict(sig, counter=counter, crc=0)))

    def check(fid, data, expected):
        return codec(f"check {fid:03X}#{data.hex().upper()} {expected}")

    checked = 0
    for k in range(40):  # counters wrap at 16
        data = frame(clock, k % 16, tick=1000 + k)
        assert check(clock.frame_id, data, k % 16) == "ok"
        assert check(clock.frame_id, data, -1) == "ok"  # any counter
        checked += 1
    good = frame(status, 7, state=1, uav_id=3, x=-5, y=12)
    assert check(status.frame_id, good, 7) == "ok"
    bad_crc = good[:7] + bytes([good[7] ^ 0x01])
    assert check(status.frame_id, bad_crc, 7) == "crc"
    flipped = bytes([good[0], good[1] ^ 0x10]) + good[2:]
    assert check(status.frame_id, flipped, 7) == "crc"
    assert check(status.frame_id, good, 6) == "counter"   # a frame was skipped
    assert check(status.frame_id, good, 8) == "counter"   # repeated (or old)
    assert check(status.frame_id, good[:7], 7) == "dlc"
    # The CRC covers the id: the same bytes under another id fail it.
    assert check(clock.frame_id, good, 7) == "crc"
    # A corrupted CRC is reported before a wrong counter.
    assert check(status.frame_id, bad_crc, 6) == "crc"
    print(f"frame check: {checked} cantools frames in sequence, 7 faults caught")


# --- the mission frame (SVA_MISSION_FRAME_A..D, sva_can_mission_frame.h) ----------------

FRAMES = [(473977419, 85455939, 3000, 1000, 1000, 1780300800125, 3),
          (-850000000, -1800000000, 0, 10, 1, 0, 14),
          (850000000, 1800000000, 1000000, 1000000, 3600000, 253402300799999, 15)]


def test_dbc_describes_the_mission_frame(full_db):
    ids = [full_db.get_message_by_name(n).frame_id for n in FRAME_MESSAGES]
    assert ids == [0x130, 0x131, 0x132, 0x133]
    for n in FRAME_MESSAGES:
        msg = full_db.get_message_by_name(n)
        assert msg.length == 8 and msg.senders == ["PLANNER"]
        assert (msg.get_signal_by_name("counter").start, msg.get_signal_by_name("crc").start) == (0, 56)


@pytest.mark.parametrize("values", FRAMES)
def test_c_mission_frame_decodes_with_cantools(full_db, values):
    line = subprocess.run([TOOL, "frame", *map(str, values)], check=True, capture_output=True,
                          text=True, timeout=30).stdout.split()
    assert len(line) == 4
    got = {}
    for k, text in enumerate(line):
        fid, data = can_wire.parse_frame(text)
        assert fid == 0x130 + k and data[7] == can_wire.crc8(fid, data)
        d = full_db.decode_message(fid, data)
        assert d["counter"] == (values[6] + k) % 16
        got.update({n: v for n, v in d.items() if n not in ("counter", "crc")})
    names = ["lat_e7", "lon_e7", "alt_cm", "cell_cm", "tick_ms", "t0_ms"]
    assert got == dict(zip(names, values[:6]))


@pytest.mark.parametrize("values", FRAMES)
def test_cantools_mission_frame_decodes_in_c(full_db, values):
    lat, lon, alt, cell, tick, t0, c = values
    sig = [{"lat_e7": lat, "alt_cm": alt}, {"lon_e7": lon, "cell_cm": cell}, {"t0_ms": t0},
           {"tick_ms": tick}]
    frames = []
    for k, (name, fields) in enumerate(zip(FRAME_MESSAGES, sig)):
        msg = full_db.get_message_by_name(name)
        data = can_wire.with_crc(msg.frame_id, msg.encode(dict(fields, counter=(c + k) % 16, crc=0),
                                                          strict=True))
        frames.append(f"{msg.frame_id:03X}#{data.hex().upper()}")
    out = subprocess.run([TOOL, "frame-rx", *frames], check=True, capture_output=True, text=True,
                         timeout=30).stdout.strip()
    assert out == (f"ok ok ok applied lat_e7={lat} lon_e7={lon} alt_cm={alt} cell_cm={cell} "
                   f"tick_ms={tick} t0_ms={t0}")
    # out of order (B before A) and a value outside the DBC's range are refused
    out = subprocess.run([TOOL, "frame-rx", frames[1], *frames], check=True, capture_output=True,
                         text=True, timeout=30).stdout.split()
    assert out[:5] == ["sequence", "ok", "ok", "ok", "applied"]
    bad = full_db.get_message_by_name("SVA_MISSION_FRAME_B")
    data = can_wire.with_crc(bad.frame_id, bad.encode({"counter": (c + 1) % 16, "lon_e7": lon,
                                                       "cell_cm": 9, "crc": 0}, strict=False))
    out = subprocess.run([TOOL, "frame-rx", frames[0], f"131#{data.hex()}", *frames[2:]], check=True,
                         capture_output=True, text=True, timeout=30).stdout.split()
    assert out == ["ok", "ok", "ok", "value"]


def test_framed_mission_sends_its_frame_before_the_plan(full_db, tmp_path):
    """A mission with a frame: the four frame messages (as sva_can_node sends them before
    each plan) decode with cantools to the frame's integers; a mission without one sends
    none."""
    doc = json.loads((HERE / "data" / "mission_25x5.json").read_text())
    doc["frame"] = {"lat": 47.3977419, "lon": 8.5455939, "alt_m": 30.25, "cell_m": 12.5,
                    "tick_s": 0.5, "t0": "2026-06-01T08:00:00.125Z"}
    path = tmp_path / "framed.json"
    path.write_text(json.dumps(doc))
    plan = json.loads(subprocess.run([TOOL, "plan", str(path), "sva", "3"], check=True,
                                     capture_output=True, text=True, timeout=60).stdout)
    got = {}
    for k, text in enumerate(plan["frame_frames"]):
        fid, data = can_wire.parse_frame(text)
        assert fid == 0x130 + k
        got.update({n: v for n, v in full_db.decode_message(fid, data).items()
                    if n not in ("counter", "crc")})
    assert got == {"lat_e7": 473977419, "lon_e7": 85455939, "alt_cm": 3025, "cell_cm": 1250,
                   "tick_ms": 500, "t0_ms": 1780300800125}
    plain = json.loads(subprocess.run([TOOL, "plan", str(HERE / "data" / "mission_25x5.json"), "sva",
                                       "3"], check=True, capture_output=True, text=True,
                                      timeout=60).stdout)
    assert plain["frame_frames"] == [] and plain["items"] == plan["items"]
