"""Host side of the VM test: decodes the candump capture that came back over the
second serial port with cantools and checks it holds exactly the plans the core
produced (and that the node and the bridge agree with the capture)."""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import can_wire  # noqa: E402


def sections(text):
    out, cur = {}, None
    for line in text.splitlines():
        if line.startswith("=== "):
            cur = line[4:].strip()
            out[cur] = []
        elif cur is not None:
            out[cur].append(line)
    return out


def main(ser1, exp1, exp2, tick):
    text = Path(ser1).read_text(errors="replace")
    sec = sections(text)
    fails = [k for k in sec if k.startswith("fail")]
    assert not fails, f"guest failed: {fails}"
    rc = next(k for k in sec if k.startswith("rc "))
    assert rc == "rc node=0 bridge=0", f"guest programs: {rc}\nnode.err:\n" + "\n".join(sec.get("node.err", [])) \
        + "\nbridge.err:\n" + "\n".join(sec.get("bridge.err", []))
    assert "end" in sec, "report truncated"
    frames = [can_wire.parse_frame(line) for line in sec["capture"] if "#" in line]
    db = can_wire.load_db()
    plans = can_wire.decode_transfers(db, frames)
    expected = [json.loads(Path(p).read_text()) for p in (exp1, exp2)]
    assert len(plans) == 2, f"{len(plans)} complete transfers in the capture, expected 2"
    for got, want in zip(plans, expected):
        assert got["plan_id"] == want["plan_id"]
        assert got["plan_crc"] == want["plan_crc"], "CRC-32 differs from the host's plan"
        assert got["items"] == want["items"], f"plan {got['plan_id']} on the bus differs from the core's"
        assert got["route_count"] == want["route_count"]
    # The node printed and the bridge applied the same plans.
    node_plans = [json.loads(line) for line in sec["node.out"] if line.startswith("{")]
    bridge_plans = [json.loads(line) for line in sec["bridge.out"] if line.startswith("{")]
    for seen in (node_plans, bridge_plans):
        assert [p["items"] for p in seen] == [p["items"] for p in plans]
    kinds = {}
    for fid, data in frames:
        assert len(data) == 8 and can_wire.crc8(fid, data) == data[7], f"bad frame {fid:03X}#{data.hex()}"
        name = db.get_message_by_frame_id(fid).name
        kinds[name] = kinds.get(name, 0) + 1
        db.decode_message(fid, data)
    assert kinds.get("SVA_HEARTBEAT", 0) >= 1, "no heartbeat in the capture"
    assert kinds.get("SVA_PLAN_ACK", 0) >= 3, "no ACKs in the capture"
    assert kinds.get("SVA_VEHICLE_STATUS", 0) == 1
    assert kinds.get("SVA_MISSION_CLOCK", 0) == 1
    # The plans on the bus are protocol version 2; the version-1 BEGIN was refused.
    begins = [db.decode_message(fid, data) for fid, data in frames if fid == 0x101]
    assert [b["version"] for b in begins] == [1, 2, 2], begins
    acks = [db.decode_message(fid, data, decode_choices=False) for fid, data in frames if fid == 0x108]
    assert [(a["result"], a["plan_id"]) for a in acks if a["result"] != 0] == [(4, 77)], acks
    bridge_err = "\n".join(sec["bridge.err"])
    assert "rejected frame 0x101: version" in bridge_err, bridge_err
    # The clock frame put a visit under way; the loss was an event of the live mission.
    node_err = "\n".join(sec["node.err"])
    assert f"under_way at tick {tick}" in node_err, node_err
    assert f"event uav_lost uav 1 at tick {tick}" in node_err, node_err
    print(f"check_vm_capture: {len(frames)} frames captured {dict(sorted(kinds.items()))}")
    for p in plans:
        print(f"check_vm_capture: plan {p['plan_id']}: {len(p['items'])} items, CRC-32 {p['plan_crc']:08X}, "
              "equal to the host core's plan")


if __name__ == "__main__":
    main(*sys.argv[1:5])
