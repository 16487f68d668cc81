"""Uploads over UDP on loopback to vehicle sides that are not the bridge's code:
`sva-tools mavlink upload` (pymavlink) and the C library (mavlink_tool) to MAVSDK's
MissionRawServer, whose received missions are read back and judged item by item; and
the failures (no frame, a vehicle that does not answer, a refusal, a vehicle's item
limit) each reported for its vehicle while the others' uploads go on. The host command
against hostile bytes and spoofers: stray bytes before every answer over UDP and TCP,
answers from another port, another system or another component."""
from __future__ import annotations

import json
import os
import random
import subprocess
import time

import pytest

import mavcheck
from standin import free_tcp_port
from vehicles import MavsdkVehicle, PymavlinkVehicle, RawVehicle, free_udp_port
from test_items import CASES, FRAME_MIDNIGHT, with_frame

MAV_MISSION_DENIED = 14
FAST = ["--timeout-ms", "300", "--retries", "2"]


def as_tuples(mavsdk_items):
    return [(i.command, i.frame, i.param1, i.param2, i.param3, i.param4, i.x, i.y, i.z)
            for i in mavsdk_items]


def write(tmp_path, name, doc):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return str(path)


def sva_tools(*args):
    return subprocess.run([os.environ["SVA_TOOLS"], "mavlink", "upload", *args],
                          capture_output=True, text=True, timeout=120)


@pytest.fixture
def vehicles():
    made = []

    def make(kind, *args, **kw):
        port = free_tcp_port() if kw.get("transport") == "tcp" else free_udp_port()
        cls = {"mavsdk": MavsdkVehicle, "pymavlink": PymavlinkVehicle, "raw": RawVehicle}[kind]
        v = cls(port, *args, **kw)
        made.append(v)
        return port, v
    yield make
    for v in made:
        v.close()


def routed(plan, n):
    rs = [r for r in plan["routes"] if r["targets"]]
    assert len(rs) >= n, "the case must route enough UAVs"
    return rs[:n]


def judge(mission, frame, route, got, home=False):
    assert len(got) == 1, f"uav {route['uav']}: {len(got)} missions received"
    result, items = got[0]
    assert result == 1  # MissionRawServerResult.SUCCESS
    items = as_tuples(items)
    if home:  # ArduPilot's item 0: a waypoint where the take-off is, altitude 0
        assert (items[0][0], items[0][6], items[0][7], items[0][8]) == \
            (mavcheck.NAV_WAYPOINT, items[1][6], items[1][7], 0.0)
        items = items[1:]
    problems = mavcheck.check_route(items, mission, frame, route["uav"], route["targets"])
    assert problems == [], "\n".join(problems)


@pytest.mark.parametrize("frame_in", ["mission", "plan", "ardupilot"])
def test_host_tool_uploads_to_mavsdk_vehicles(frame_in, tmp_path, vehicles):
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    if frame_in == "plan":
        # the plan's frame wins over the mission's
        plan = dict(plan, frame=mission["frame"])
        mission = dict(mission, frame=dict(mission["frame"], lat=10.0, lon=20.0))
    a, b = routed(plan, 2)
    (pa, va), (pb, vb) = vehicles("mavsdk", 1), vehicles("mavsdk", 7)
    home = frame_in == "ardupilot"
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission",
                  write(tmp_path, "mission.json", mission),
                  "--vehicle", f"{a['uav']}=udp:127.0.0.1:{pa}",
                  "--vehicle", f"{b['uav']}=udp:127.0.0.1:{pb}:7", *(["--ardupilot"] if home else []))
    assert p.returncode == 0, p.stderr + p.stdout
    n_a, n_b = 3 + home + 2 * len(a["targets"]), 3 + home + 2 * len(b["targets"])
    assert p.stdout.splitlines() == [
        f"uav {a['uav']}: udp:127.0.0.1:{pa}: uploaded {n_a} items",
        f"uav {b['uav']}: udp:127.0.0.1:{pb}:7: uploaded {n_b} items"]
    frame = plan.get("frame", mission["frame"])
    judge(mission, frame, a, va.wait_missions(1), home)
    judge(mission, frame, b, vb.wait_missions(1), home)


@pytest.mark.parametrize("mission", CASES, ids=lambda m: m["name"])
def test_c_library_uploads_to_mavsdk_vehicles(mission, tmp_path, vehicles):
    plan = mavcheck.plan_mission(mission, tmp_path)
    rs = [r for r in plan["routes"] if r["targets"]][:3]
    ports = {r["uav"]: vehicles("mavsdk", 1 + k) for k, r in enumerate(rs)}
    specs = {u: f"udp:127.0.0.1:{port}:{1 + k}" for k, (u, (port, _)) in enumerate(ports.items())}
    items, results, rc, err = mavcheck.run_tool(mavcheck.tool_input(mission, mission["frame"], plan, specs))
    assert rc == 0, err
    for r in rs:
        assert results[r["uav"]] == f"ok {3 + 2 * len(r['targets'])}"
        got = ports[r["uav"]][1].wait_missions(1)
        judge(mission, mission["frame"], r, got)
        # what the vehicle holds is what the library built
        assert [(i[0], i[1], i[6], i[7]) for i in as_tuples(got[0][1])] == \
            [(i[0], i[1], i[6], i[7]) for i in items[r["uav"]]]


def test_host_tool_refuses_a_plan_without_a_frame(tmp_path):
    mission = with_frame("rand_7_2", FRAME_MIDNIGHT)
    plan = mavcheck.plan_mission(mission, tmp_path)
    bare = {k: v for k, v in mission.items() if k != "frame"}
    plan_path = write(tmp_path, "plan.json", plan)
    p = sva_tools(plan_path, "--mission", write(tmp_path, "m.json", bare),
                  "--vehicle", "1=udp:127.0.0.1:9")
    assert p.returncode == 2
    assert p.stdout == ""
    assert p.stderr == (f"sva-tools: error: {plan_path}: frame: missing: neither the plan nor the "
                        f"mission has a \"frame\" (lat, lon, alt_m, cell_m, tick_s, t0): cells and "
                        f"ticks cannot be placed on the Earth\n")


def test_host_tool_names_a_bad_frame_field(tmp_path):
    mission = with_frame("rand_7_2", dict(FRAME_MIDNIGHT, cell_m=0.05))
    plan = mavcheck.plan_mission(mission, tmp_path)
    mpath = write(tmp_path, "m.json", mission)
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission", mpath,
                  "--vehicle", "1=udp:127.0.0.1:9")
    assert p.returncode == 2
    assert p.stderr == f"sva-tools: error: {mpath}: frame.cell_m: must be >= 0.1, got 0.05\n"


# Four UAVs, four targets that each needs one of them.
FOUR = {"name": "four", "depot": {"x": 0, "y": 0}, "frame": FRAME_MIDNIGHT,
        "uavs": [{"id": u, "x": 0, "y": 0, "fuel": 1000} for u in (1, 2, 3, 4)],
        "targets": [{"id": k + 1, "x": x, "y": y, "start": 20, "end": 30, "need": 1}
                    for k, (x, y) in enumerate([(10, 0), (0, 10), (-10, 0), (0, -10)])]}


def failing_fleet(tmp_path, vehicles):
    """Four routed UAVs: a MAVSDK vehicle that accepts, one port nobody answers on, a
    pymavlink vehicle that refuses (MAV_MISSION_DENIED), one whose limit is 3 items."""
    mission = FOUR
    plan = mavcheck.plan_mission(mission, tmp_path)
    rs = routed(plan, 4)
    good_port, good = vehicles("mavsdk", 1)
    deny_port, deny = vehicles("pymavlink", 3, final=MAV_MISSION_DENIED)
    small_port, small = vehicles("pymavlink", 4, max_items=3)
    silent_port = free_udp_port()
    specs = {rs[0]["uav"]: f"udp:127.0.0.1:{good_port}:1",
             rs[1]["uav"]: f"udp:127.0.0.1:{silent_port}:2",
             rs[2]["uav"]: f"udp:127.0.0.1:{deny_port}:3",
             rs[3]["uav"]: f"udp:127.0.0.1:{small_port}:4"}
    return mission, plan, rs, specs, good, deny, small


def test_host_tool_reports_each_failing_vehicle_and_uploads_the_others(tmp_path, vehicles):
    mission, plan, rs, specs, good, deny, small = failing_fleet(tmp_path, vehicles)
    args = [write(tmp_path, "plan.json", plan), "--mission", write(tmp_path, "m.json", mission)]
    for u, s in specs.items():
        args += ["--vehicle", f"{u}={s}"]
    p = sva_tools(*args, *FAST)
    assert p.returncode == 1, p.stderr
    lines = p.stdout.splitlines()
    n0 = 3 + 2 * len(rs[0]["targets"])
    assert lines == [
        f"uav {rs[0]['uav']}: {specs[rs[0]['uav']]}: uploaded {n0} items",
        f"uav {rs[1]['uav']}: {specs[rs[1]['uav']]}: error: timeout: no answer to MISSION_COUNT "
        f"after 3 tries of 300 ms",
        f"uav {rs[2]['uav']}: {specs[rs[2]['uav']]}: error: MISSION_ACK: the vehicle refused the "
        f"mission: MAV_MISSION_DENIED (14)",
        f"uav {rs[3]['uav']}: {specs[rs[3]['uav']]}: error: MISSION_ACK: the vehicle refused the "
        f"mission: MAV_MISSION_NO_SPACE (4)"]
    judge(mission, mission["frame"], rs[0], good.wait_missions(1))
    assert len(deny.items) == 1 and len(deny.items[0]) == 3 + 2 * len(rs[2]["targets"])
    assert small.counts == [3 + 2 * len(rs[3]["targets"])] and small.items == []


def test_c_library_reports_each_failing_vehicle_and_uploads_the_others(tmp_path, vehicles):
    mission, plan, rs, specs, good, deny, small = failing_fleet(tmp_path, vehicles)
    _, results, rc, err = mavcheck.run_tool(mavcheck.tool_input(mission, mission["frame"], plan, specs,
                                                  timeout="300 2"))
    assert rc == 1, err
    assert results[rs[0]["uav"]] == f"ok {3 + 2 * len(rs[0]['targets'])}"
    assert results[rs[1]["uav"]] == ("error timeout: no answer to MISSION_COUNT after 3 tries of "
                                     "300 ms")
    assert results[rs[2]["uav"]] == ("error MISSION_ACK: the vehicle refused the mission: "
                                     "MAV_MISSION_DENIED (14)")
    assert results[rs[3]["uav"]] == ("error MISSION_ACK: the vehicle refused the mission: "
                                     "MAV_MISSION_NO_SPACE (4)")
    judge(mission, mission["frame"], rs[0], good.wait_missions(1))
    assert len(deny.items) == 1
    assert small.items == []


def pymavlink_items(msgs):
    assert all(m.get_type() == "MISSION_ITEM_INT" for m in msgs)
    return [(m.command, m.frame, m.param1, m.param2, m.param3, m.param4, m.x, m.y, m.z)
            for m in msgs]


def test_c_library_answers_a_fussy_vehicle(tmp_path, vehicles):
    """A lost MISSION_COUNT (resent after the timeout), MISSION_REQUEST instead of
    MISSION_REQUEST_INT, items asked for backwards and twice each."""
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    r = routed(plan, 1)[0]
    port, v = vehicles("pymavlink", 5, fussy=True)
    _, results, rc, err = mavcheck.run_tool(mavcheck.tool_input(mission, mission["frame"], plan,
                                                  {r["uav"]: f"udp:127.0.0.1:{port}:5"},
                                                  timeout="300 2"))
    assert rc == 0, err
    assert results[r["uav"]] == f"ok {3 + 2 * len(r['targets'])}"
    assert len(v.counts) == 2 and len(v.items) == 1
    problems = mavcheck.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


def test_host_tool_answers_a_fussy_vehicle(tmp_path, vehicles):
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    r = routed(plan, 1)[0]
    port, v = vehicles("pymavlink", 5, fussy=True)
    p = sva_tools(write(tmp_path, "plan.json", plan), "--mission",
                  write(tmp_path, "m.json", mission), "--vehicle",
                  f"{r['uav']}=udp:127.0.0.1:{port}:5", *FAST)
    assert p.returncode == 0, p.stderr + p.stdout
    assert len(v.counts) == 2 and len(v.items) == 1
    problems = mavcheck.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


# --- the host command against hostile bytes and spoofers ----------------------------

SEED = 20260611
# Long enough that a loaded machine resends nothing; an answer lost shows as a resend.
SLOW = ["--timeout-ms", "1000", "--retries", "1"]


def bad_bytes():
    """(name, k -> bytes): what a hostile link puts before the k-th answer."""
    from pymavlink.dialects.v20 import common
    mav = common.MAVLink(None, srcSystem=1, srcComponent=1)
    heartbeat = mav.heartbeat_encode(2, 3, 0, 0, 4).pack(mav)
    position = mav.global_position_int_encode(1, 2, 3, 4, 5, 6, 7, 8, 9).pack(mav)
    signer = common.MAVLink(None, srcSystem=1, srcComponent=1)
    signer.signing.secret_key = bytes(range(32))
    signer.signing.timestamp = 1
    signer.signing.sign_outgoing = True
    signed = signer.heartbeat_encode(2, 3, 0, 0, 4).pack(signer)
    assert signed[2] & 1 and len(signed) == len(heartbeat) + 13

    def garbage(k):
        rng = random.Random(SEED + k)
        return bytes(rng.choice([0xFD, 0xFE, rng.randrange(256)]) for _ in range(rng.randrange(1, 40)))

    return [("FD FF 00", lambda k: b"\xfd\xff\x00"),
            ("garbage", garbage),
            ("truncated frame", lambda k: (heartbeat[:12], position[:10])[k % 2]),
            ("signed flag, no signature", lambda k: signed[:-13])]


def one_route(tmp_path):
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    r = routed(plan, 1)[0]
    return mission, r, [write(tmp_path, "plan.json", plan), "--mission",
                        write(tmp_path, "m.json", mission)]


@pytest.mark.parametrize("placement", ["udp, in the answer's datagram", "udp, a datagram of its own",
                                       "tcp, in the stream"])
@pytest.mark.parametrize("name, stray", bad_bytes(), ids=[b[0] for b in bad_bytes()])
def test_host_tool_finds_every_answer_behind_stray_bytes(name, stray, placement, tmp_path, vehicles):
    """Stray bytes before every answer of the vehicle: the upload completes with one
    MISSION_COUNT and each item sent once (no answer lost), and the items are right.
    pymavlink's parser, kept from one datagram to the next, loses the answers."""
    mission, r, files = one_route(tmp_path)
    transport = placement[:3]
    port, v = vehicles("raw", 5, transport=transport, strays=stray, alone="own" in placement)
    spec = f"{transport}:127.0.0.1:{port}:5"
    p = sva_tools(*files, "--vehicle", f"{r['uav']}={spec}", *SLOW)
    n = 3 + 2 * len(r["targets"])
    assert p.returncode == 0, f"seed {SEED}: " + p.stderr + p.stdout
    assert p.stdout == f"uav {r['uav']}: {spec}: uploaded {n} items\n"
    assert v.answers == n + 1  # every request and the ACK came behind stray bytes
    assert v.counts == [n] and v.item_seqs == list(range(n)), f"seed {SEED}"
    problems = mavcheck.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


def test_host_tool_takes_no_answer_from_another_port(tmp_path, vehicles):
    """The vehicle's port is silent; a spoofer that sees the traffic answers every
    message as the vehicle (its system id, component 1) from another port. The tool
    reads datagrams from the vehicle's address and port only: it times out."""
    _, r, files = one_route(tmp_path)
    port, v = vehicles("raw", 3, answer_from_port=free_udp_port())
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=udp:127.0.0.1:{port}:3", *FAST)
    assert p.returncode == 1, p.stderr
    assert p.stdout == (f"uav {r['uav']}: udp:127.0.0.1:{port}:3: error: timeout: no answer to "
                        f"MISSION_COUNT after 3 tries of 300 ms\n")
    assert v.counts == [3 + 2 * len(r["targets"])] * 3 and v.answers == 3  # it did answer


@pytest.mark.parametrize("sysid, compid", [(9, 1), (3, 2)],
                         ids=["another system", "another component"])
def test_host_tool_takes_no_answer_from_another_system_or_component(sysid, compid, tmp_path,
                                                                    vehicles):
    """On the vehicle's own port, answers from system 9 (the vehicle is 3) or from
    component 2 (not the autopilot): the tool times out."""
    _, r, files = one_route(tmp_path)
    port, v = vehicles("raw", sysid, compid=compid)
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=udp:127.0.0.1:{port}:3", *FAST)
    assert p.returncode == 1, p.stderr
    assert p.stdout == (f"uav {r['uav']}: udp:127.0.0.1:{port}:3: error: timeout: no answer to "
                        f"MISSION_COUNT after 3 tries of 300 ms\n")
    assert v.answers == 3


@pytest.mark.parametrize("sysid, compid", [(9, 1), (3, 2)],
                         ids=["another system", "another component"])
def test_host_tool_ignores_a_refusal_from_another_system_or_component(sysid, compid, tmp_path,
                                                                      vehicles):
    """The vehicle (system 3, component 1) answers; before each of its answers another
    system or component on the same port sends MISSION_ACK MAV_MISSION_DENIED."""
    mission, r, files = one_route(tmp_path)
    port, v = vehicles("raw", 3, decoys=[(sysid, compid)])
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=udp:127.0.0.1:{port}:3", *SLOW)
    n = 3 + 2 * len(r["targets"])
    assert p.returncode == 0, p.stderr + p.stdout
    assert p.stdout == f"uav {r['uav']}: udp:127.0.0.1:{port}:3: uploaded {n} items\n"
    problems = mavcheck.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


def test_host_tool_names_the_signed_frames_it_did_not_take(tmp_path, vehicles):
    """A vehicle that signs its frames: this side checks no signature and takes none of
    them; the timeout says so."""
    _, r, files = one_route(tmp_path)
    port, v = vehicles("raw", 1, signed=True)
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=udp:127.0.0.1:{port}", *FAST)
    assert p.returncode == 1, p.stderr
    assert p.stdout == (f"uav {r['uav']}: udp:127.0.0.1:{port}: error: timeout: no answer to "
                        f"MISSION_COUNT after 3 tries of 300 ms; 3 signed frames not taken (this "
                        f"side checks no MAVLink signature)\n")
    assert v.answers == 3


def test_host_tool_waits_for_a_tcp_vehicle_that_listens_late(tmp_path, vehicles):
    """The connection is tried again every 500 ms; once made, the upload starts with
    every retry still to come."""
    mission, r, files = one_route(tmp_path)
    port = free_tcp_port()
    p = subprocess.Popen([os.environ["SVA_TOOLS"], "mavlink", "upload", *files, "--vehicle",
                          f"{r['uav']}=tcp:127.0.0.1:{port}", "--timeout-ms", "1000",
                          "--retries", "4"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    time.sleep(2.5)  # the command is up and trying by then (it starts within a second here)
    v = RawVehicle(port, 1, transport="tcp")
    try:
        out, err = p.communicate(timeout=60)
    finally:
        v.close()
    n = 3 + 2 * len(r["targets"])
    assert p.returncode == 0, err + out
    assert out == f"uav {r['uav']}: tcp:127.0.0.1:{port}: uploaded {n} items\n"
    assert v.counts == [n]
    problems = mavcheck.check_route(pymavlink_items(v.items[0]), mission, mission["frame"], r["uav"],
                             r["targets"])
    assert problems == [], "\n".join(problems)


def test_host_tool_names_a_tcp_vehicle_that_is_not_there(tmp_path):
    _, r, files = one_route(tmp_path)
    port = free_tcp_port()
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=tcp:127.0.0.1:{port}", *FAST)
    assert p.returncode == 1, p.stderr
    assert p.stdout == (f"uav {r['uav']}: tcp:127.0.0.1:{port}: error: timeout: no answer to "
                        f"MISSION_COUNT after 3 tries of 300 ms; tcp:127.0.0.1:{port} not "
                        f"connected: Connection refused\n")


def test_host_tool_fails_at_once_when_the_tcp_vehicle_drops_the_connection(tmp_path, vehicles):
    _, r, files = one_route(tmp_path)
    port, v = vehicles("raw", 1, transport="tcp", drop_after_items=2)
    p = sva_tools(*files, "--vehicle", f"{r['uav']}=tcp:127.0.0.1:{port}")
    assert p.returncode == 1, p.stderr
    assert p.stdout == (f"uav {r['uav']}: tcp:127.0.0.1:{port}: error: link: tcp:127.0.0.1:{port}: "
                        f"connection lost during the upload: closed by the vehicle\n")
    assert v.item_seqs == [0, 1]


@pytest.mark.parametrize("value, message", [
    ("1=serial:/dev/ttyS0", '--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID] or '
                            'UAV_ID=tcp:HOST:PORT[:SYSID] (UAV_ID in [1, 2147483647], PORT in '
                            '[1, 65535], SYSID in [1, 255]), got "1=serial:/dev/ttyS0"'),
    ("1=tcp:127.0.0.1:5760:256", '--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID] or '
                                 'UAV_ID=tcp:HOST:PORT[:SYSID] (UAV_ID in [1, 2147483647], PORT '
                                 'in [1, 65535], SYSID in [1, 255]), got "1=tcp:127.0.0.1:5760:256"'),
    ("4=tcp:no-such-host.invalid:5760", "--vehicle: 4: tcp:no-such-host.invalid:5760: cannot "
                                        "resolve: "),
])
def test_host_tool_refuses_a_bad_vehicle(value, message, tmp_path):
    _, _, files = one_route(tmp_path)
    p = sva_tools(*files, "--vehicle", value)
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr.startswith(f"sva-tools: error: mavlink upload: {message}"), p.stderr
    assert p.stderr.count("\n") == 1


def good_frames(n: int):
    """n good frames of several kinds, system 7, seq 0..n-1, and what each decodes to."""
    from pymavlink.dialects.v20 import common
    mav = common.MAVLink(None, srcSystem=7, srcComponent=1)
    makers = [lambda: mav.heartbeat_encode(2, 3, 0, 0, 4),
              lambda: mav.mission_request_int_encode(250, 190, 3, 0),
              lambda: mav.global_position_int_encode(1000, 473977419, 85455938, 1, 2, 3, 4, 5, 6),
              lambda: mav.mission_ack_encode(250, 190, 0, 0)]
    out = []
    for k in range(n):
        msg = makers[k % len(makers)]()
        out.append((msg.pack(mav), (msg.get_type(), k % 256)))
        mav.seq = (mav.seq + 1) % 256
    return out


def decoded(msgs):
    return [(m.get_type(), m.get_seq()) for m in msgs]


@pytest.mark.parametrize("mode", ["datagrams", "stream"])
def test_the_host_frames_keep_every_good_frame_behind_bad_bytes(mode):
    """sva_tools.mavlink.Frames on seeded random garbage, truncated frames and each bad
    pattern above before every good frame: every good frame comes out, in order, and
    nothing else; in a stream, fed in random pieces."""
    from sva_tools.mavlink import Frames
    rng = random.Random(SEED)
    frames = good_frames(400)
    patterns = [f for _, f in bad_bytes()]
    chunks = []
    for k, (data, _) in enumerate(frames):
        junk = patterns[k % len(patterns)](k)
        if rng.random() < 0.3:  # a good frame cut short
            cut = frames[rng.randrange(len(frames))][0]
            junk += cut[:rng.randrange(1, len(cut))]
        chunks.append(junk + data)
    parser, got = Frames(), []
    if mode == "datagrams":
        for chunk in chunks:
            got += parser.datagram(chunk)
    else:
        stream = b"".join(chunks)
        at = 0
        while at < len(stream):
            step = rng.randrange(1, 64)
            got += parser.stream(stream[at:at + step])
            at += step
    assert decoded(got) == [f[1] for f in frames], f"seed {SEED}"
    if mode == "datagrams":  # the signed one, each time, with the next frame as "signature"
        assert parser.signed == len(frames) // len(patterns)
