"""Independent Python view of the sva CAN protocol, for the tests.

Decodes with cantools from port/can/sva.dbc; CRC-8 from crccheck (CRC-8/SAE-J1850),
CRC-32 from zlib: none of it shares code with the C codec.
"""
import re
import zlib
from pathlib import Path

import cantools
from crccheck.crc import Crc8SaeJ1850

DBC = Path(__file__).resolve().parents[2] / "port" / "can" / "sva.dbc"


def load_db():
    return cantools.database.load_file(str(DBC))


def crc8(frame_id, data):
    """CRC-8 of a frame: id as two little-endian bytes, then data bytes 0..6."""
    return Crc8SaeJ1850.calc(bytes([frame_id & 0xFF, (frame_id >> 8) & 0x07]) + bytes(data[:7]))


def with_crc(frame_id, data):
    data = bytearray(data)
    data[7] = crc8(frame_id, data)
    return bytes(data)


def parse_frame(text):
    """'102#B53A12FEFF3412C4' or a candump -L line '(t) vcan0 102#...' -> (id, bytes)."""
    m = re.search(r"([0-9A-Fa-f]{3,8})#([0-9A-Fa-f]*)", text)
    if not m:
        raise ValueError(f"not a frame: {text!r}")
    return int(m.group(1), 16), bytes.fromhex(m.group(2))


def plan_crc(frames):
    """CRC-32/ISO-HDLC over bytes 0..6 (counter nibble cleared) of BEGIN, ITEM, ITEM_TIME."""
    crc = 0
    for fid, data in frames:
        if fid in (0x101, 0x102, 0x103):
            crc = zlib.crc32(bytes([data[0] & 0xF0]) + data[1:7], crc)
    return crc


class TransferError(AssertionError):
    pass


def decode_transfers(db, frames):
    """Reassembles every complete transfer (BEGIN..COMMIT) in a capture, checking each
    frame's CRC-8, the counter sequence, the ITEM/ITEM_TIME pairing and the CRC-32.
    Returns a list of plans: dict(plan_id, algorithm, plan_status, route_count, items)."""
    plans = []
    cur = None
    for fid, data in frames:
        if fid not in (0x100, 0x101, 0x102, 0x103, 0x104):
            continue
        if len(data) != 8:
            raise TransferError(f"frame {fid:03X} has DLC {len(data)}")
        if crc8(fid, data) != data[7]:
            raise TransferError(f"frame {fid:03X}#{data.hex()} fails CRC-8")
        sig = db.decode_message(fid, data, decode_choices=False)
        if fid == 0x100:
            cur = None
            continue
        if fid == 0x101:
            cur = {"plan_id": sig["plan_id"], "algorithm": sig["algorithm"],
                   "plan_status": sig["plan_status"], "route_count": sig["route_count"],
                   "item_count": sig["item_count"], "items": [], "frames": [(fid, data)],
                   "counter": sig["counter"]}
            continue
        if cur is None:
            continue  # tail of an aborted or partial transfer
        if sig["counter"] != (cur["counter"] + 1) % 16:
            raise TransferError(f"counter jump in plan {cur['plan_id']}")
        cur["counter"] = sig["counter"]
        if fid == 0x102:
            cur["items"].append({"uav": sig["uav_id"], "target": sig["target_id"], "x": sig["x"], "y": sig["y"]})
            cur["frames"].append((fid, data))
        elif fid == 0x103:
            item = cur["items"][-1]
            if "arrive_by" in item or sig["item_seq"] != (len(cur["items"]) - 1) % 16:
                raise TransferError("ITEM_TIME out of order")
            item["arrive_by"] = sig["arrive_by"]
            item["hold_until"] = sig["hold_until"]
            cur["frames"].append((fid, data))
        elif fid == 0x104:
            if len(cur["items"]) != cur["item_count"]:
                raise TransferError("COMMIT before every item")
            if sig["plan_id"] != cur["plan_id"] or sig["plan_crc"] != plan_crc(cur["frames"]):
                raise TransferError("COMMIT CRC-32 mismatch")
            cur["plan_crc"] = sig["plan_crc"]
            del cur["frames"], cur["counter"]
            plans.append(cur)
            cur = None
    return plans
