"""The C library's links beyond the UDP upload (tests/mavlink/mavlink_tool): its parser
against stray, truncated and corrupted bytes; uploads over TCP to a pymavlink vehicle
stand-in (standin.py) served on a socket of its own, with stray bytes before every reply,
with the connection lost mid-upload, made late or never; the telemetry it listens to, the
SET_MESSAGE_INTERVAL requests it makes, the reports it derives (cell, tick from the
vehicle's own clock, fuel, health), and the reconnection to a restarted vehicle. Expected
values come from pymap3d, pymavlink and the stand-in's records, never from the library."""
from __future__ import annotations

import os
import random
import subprocess
import threading
import time

import pytest
from pymavlink.dialects.v20 import common as mavlink2

import mavcheck
from standin import StandIn, free_tcp_port, stray_patterns
from test_items import CASES, FRAME_MIDNIGHT
from test_upload import pymavlink_items
from vehicles import free_udp_port

TOOL = os.environ["SVA_MAVLINK_TOOL"]
FI = mavcheck.frame_ints(FRAME_MIDNIGHT)
# The streams the library asks for and their intervals (us).
STREAMS = {mavlink2.MAVLINK_MSG_ID_GLOBAL_POSITION_INT: 200_000.0,
           mavlink2.MAVLINK_MSG_ID_SYSTEM_TIME: 1_000_000.0,
           mavlink2.MAVLINK_MSG_ID_SYS_STATUS: 1_000_000.0,
           mavlink2.MAVLINK_MSG_ID_BATTERY_STATUS: 1_000_000.0,
           mavlink2.MAVLINK_MSG_ID_MISSION_CURRENT: 1_000_000.0}


def frame_line() -> str:
    return (f"frame {FI['lat_e7']} {FI['lon_e7']} {FI['alt_cm']} {FI['cell_cm']} {FI['tick_ms']} "
            f"{FI['t0_ms']}")


def run_parser(lines, timeout=60):
    p = subprocess.run([TOOL], input="parse\n" + "\n".join(lines) + "\n", capture_output=True,
                       text=True, timeout=timeout)
    assert p.returncode == 0, p.stderr
    return p.stdout.splitlines()


def good_frames(n: int, sysid: int = 7):
    """n frames of several kinds, seq 0..n-1: (bytes, (sysid, compid, msgid, seq))."""
    mav = mavlink2.MAVLink(None, srcSystem=sysid, srcComponent=1)
    makers = [lambda: mav.heartbeat_encode(2, 3, 0, 0, 4),
              lambda: mav.mission_request_int_encode(250, 190, 3, 0),
              lambda: mav.global_position_int_encode(1000, 473977419, 85455938, 1, 2, 3, 4, 5, 6),
              lambda: mav.mission_ack_encode(250, 190, 0, 0),
              lambda: mav.system_time_encode(1_795_000_000_000_000, 77)]
    out = []
    for k in range(n):
        msg = makers[k % len(makers)]()
        data = msg.pack(mav)
        mav.seq = (mav.seq + 1) % 256  # pack() does not count, send() would
        out.append((data, f"msg {sysid} 1 {msg.get_msgId()} {k % 256}"))
    return out


@pytest.mark.parametrize("mode", ["stream", "datagram"])
def test_the_parser_keeps_every_good_frame_behind_bad_bytes(mode):
    """Each stray pattern before a good frame: every good frame comes out, in order. With
    the generated parser, `FD FF 00` takes the next 267 bytes as its frame."""
    strays = stray_patterns()
    frames = good_frames(len(strays) * 2 + 3)
    if mode == "stream":
        data = b"".join(strays[k % len(strays)][1] + f[0] if k < len(strays) * 2 else f[0]
                        for k, f in enumerate(frames))
        lines = [f"stream {data.hex()}"]
    else:
        # each stray inside the datagram of a good frame, then in a datagram of its own
        lines = []
        for k, (data, _) in enumerate(frames[:len(strays) * 2]):
            stray = strays[k % len(strays)][1]
            if k < len(strays):
                lines.append(f"datagram {(stray + data).hex()}")
            else:
                lines += [f"datagram {stray.hex()}", f"datagram {data.hex()}"]
        lines += [f"datagram {f[0].hex()}" for f in frames[len(strays) * 2:]]
    out = run_parser(lines)
    assert out[:-1] == [f[1] for f in frames]
    assert out[-1].startswith(f"parser {len(frames)} ")


def test_the_parser_finds_every_good_frame_in_random_garbage():
    seed = 20261126
    rng = random.Random(seed)
    frames = good_frames(400)
    chunks = []
    for data, _ in frames:
        garbage = bytes(rng.choice([0xFD, 0xFE, rng.randrange(256)]) for _ in range(rng.randrange(0, 30)))
        if rng.random() < 0.3:  # a good frame cut short
            cut = frames[rng.randrange(len(frames))][0]
            garbage += cut[:rng.randrange(1, len(cut))]
        chunks.append(garbage + data)
    stream = b"".join(chunks) + b"".join(f[0] for f in good_frames(3, sysid=8))
    out = run_parser([f"stream {stream.hex()}"])
    got = [x for x in out if x.startswith("msg 7 ")]
    assert got == [f[1] for f in frames], f"seed {seed}"
    assert not [x for x in out if x.startswith("msg") and not x.startswith(("msg 7 ", "msg 8 "))]


def test_cells_round_half_away_from_zero():
    cases = [(12.5, 100, "13"), (-12.5, 100, "-13"), (12.49, 100, "12"), (-12.49, 100, "-12"),
             (0.5, 100, "1"), (-0.5, 100, "-1"), (0.0, 100, "0"), (62.5, 2500, "3"),
             (-62.5, 2500, "-3"), (32767.49, 100, "32767"), (32767.5, 100, "none"),
             (-32768.49, 100, "-32768"), (-32768.5, 100, "none"), (float("nan"), 100, "none")]
    out = run_parser([f"cell {m} {c}" for m, c, _ in cases])
    assert out[:-1] == [f"cell {want}" for _, _, want in cases]


def tool_lines(text: str, timeout: float = 60):
    """Runs mavlink_tool on `text`; yields (host time the line arrived, line)."""
    p = subprocess.Popen([TOOL], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    p.stdin.write(text)
    p.stdin.close()
    lines = []
    end = time.monotonic() + timeout
    for line in p.stdout:
        lines.append((time.monotonic(), line.rstrip("\n")))
        assert time.monotonic() < end, "mavlink_tool ran too long"
    rc = p.wait(10)
    return lines, rc, p.stderr.read()


def results_of(lines):
    return {int(x.split()[1]): " ".join(x.split()[2:]) for _, x in lines if x.startswith("result ")}


def a_route(tmp_path):
    mission = CASES[0]
    plan = mavcheck.plan_mission(mission, tmp_path)
    r = [r for r in plan["routes"] if r["targets"]][0]
    return mission, plan, r


def standin(transport, port, **kw):
    lat, lon = mavcheck.position_e7(FRAME_MIDNIGHT, 3.3, -2.2)
    kw.setdefault("gps_at_boot_ms", FI["t0_ms"] + 1_000_000)
    return StandIn(transport, port, kw.pop("sysid", 1), lat_e7=lat, lon_e7=lon, **kw)


@pytest.mark.parametrize("transport,strays", [("tcp", False), ("tcp", True), ("udp", True)])
def test_an_upload_works_with_stray_bytes_before_every_reply(transport, strays, tmp_path):
    """Over TCP, and with a stray pattern before every MISSION_REQUEST_INT, MISSION_ACK
    and COMMAND_ACK (UDP: in the reply's datagram or one of its own): the upload succeeds
    with one MISSION_COUNT and each item sent once (no frame was lost, so nothing was
    resent), and the items are the plan's."""
    mission, plan, r = a_route(tmp_path)
    port = free_tcp_port() if transport == "tcp" else free_udp_port()
    v = standin(transport, port, sysid=5, strays=strays)
    try:
        text = mavcheck.tool_input(mission, mission["frame"], plan, {r["uav"]: f"{transport}:127.0.0.1:{port}:5"})
        lines, rc, err = tool_lines(text)
        n = 3 + 2 * len(r["targets"])
        assert rc == 0, err
        assert results_of(lines)[r["uav"]] == f"ok {n}"
        assert v.counts == [n] and v.item_seqs == list(range(n))
        assert len(v.missions) == 1
        problems = mavcheck.check_route(pymavlink_items(v.missions[0]), mission, mission["frame"],
                                 r["uav"], r["targets"])
        assert problems == [], "\n".join(problems)
    finally:
        v.close()


def test_an_upload_fails_with_a_clear_error_when_the_tcp_link_drops(tmp_path):
    mission, plan, r = a_route(tmp_path)
    port = free_tcp_port()
    v = standin("tcp", port, drop_after_items=2)
    try:
        text = mavcheck.tool_input(mission, mission["frame"], plan, {r["uav"]: f"tcp:127.0.0.1:{port}"})
        lines, rc, err = tool_lines(text)
        assert rc == 1, err
        assert results_of(lines)[r["uav"]] == (
            f"error link: tcp:127.0.0.1:{port}: connection lost during the upload: closed by the "
            f"vehicle")
        assert v.missions == []
    finally:
        v.close()


def test_an_upload_waits_for_a_late_tcp_vehicle_and_names_a_missing_one(tmp_path):
    mission, plan, r = a_route(tmp_path)
    late, missing = free_tcp_port(), free_tcp_port()
    uavs = [x["uav"] for x in plan["routes"] if x["targets"]][:2]
    text = mavcheck.tool_input(mission, mission["frame"], plan,
                        {uavs[0]: f"tcp:127.0.0.1:{late}", uavs[1]: f"tcp:127.0.0.1:{missing}"},
                        timeout="1000 2")
    box = {}
    t = threading.Thread(target=lambda: box.update(out=tool_lines(text)))
    t.start()
    time.sleep(0.8)  # the tool has tried and been refused
    v = standin("tcp", late)
    try:
        t.join(60)
        lines, rc, err = box["out"]
        assert rc == 1, err
        res = results_of(lines)
        assert res[uavs[0]].startswith("ok "), res
        assert v.counts == [int(res[uavs[0]].split()[1])]
        assert res[uavs[1]] == (f"error timeout: no answer to MISSION_COUNT after 3 tries of 1000 ms; "
                                f"tcp:127.0.0.1:{missing} not connected: Connection refused")
    finally:
        v.close()


def reports_of(lines, uav=1):
    out = []
    for t, x in lines:
        w = x.split()
        if w[0] == "report" and int(w[1]) == uav:
            kv = dict(p.split("=") for p in w[3:] if "=" in p)
            out.append((t, int(w[2]), {k: int(v) for k, v in kv.items()}, x))
    return out


def test_telemetry_streams_are_requested_and_reports_use_the_vehicle_clock():
    """A vehicle whose clock runs ten times as fast as the host's, starting 1000 s after
    t0, with SYSTEM_TIME only every 2 s: each report's tick is that of a position sent
    just before it (GPS time from SYSTEM_TIME plus time since boot), not of the last
    SYSTEM_TIME nor of host time. Cell, fuel and sequence numbers are the stand-in's;
    LOST once its heartbeats stop, OK when they resume. A second vehicle over UDP, with
    no battery figure, is reported with fuel and sequence numbers unknown."""
    port, port2 = free_tcp_port(), free_udp_port()
    v = standin("tcp", port, rate=10.0, system_time_every_s=2.0, mission_current=4, reached=3)
    lat2, lon2 = mavcheck.position_e7(FRAME_MIDNIGHT, -7.45, 0.6)
    v2 = StandIn("udp", port2, 2, lat_e7=lat2, lon_e7=lon2, gps_at_boot_ms=FI["t0_ms"] + 3_600_000,
                 battery=-1)
    text = "\n".join([frame_line(), "reportcfg 1500 500", f"vehicle 1=tcp:127.0.0.1:{port}",
                      f"vehicle 2=udp:127.0.0.1:{port2}:2", "listen 7000 250"]) + "\n"

    def toggle():
        time.sleep(2.5)
        v.heartbeats = False
        time.sleep(2.5)
        v.heartbeats = True
    threading.Thread(target=toggle, daemon=True).start()
    try:
        lines, rc, err = tool_lines(text)
        assert rc == 0, err
        assert v.requested() == STREAMS and v2.requested() == STREAMS
        want_cell = mavcheck.cell_of(FRAME_MIDNIGHT, v.lat_e7, v.lon_e7)
        assert want_cell == (3, -2)
        reps = [x for x in reports_of(lines) if x[1] == 0]
        assert len(reps) >= 15, [x for _, x in lines]
        for t, _, r, line in reps:
            assert (r["x"], r["y"]) == want_cell, line
            assert (r["fuel"], r["mission_seq"], r["reached_seq"]) == (365, 4, 3), line
            with v.lock:
                sent = [mavcheck.tick_of(FRAME_MIDNIGHT, g) for ts, g in v.positions if t - 0.7 <= ts <= t]
            assert r["at_ticks"] in sent, (line, sent)
        health = [r["health"] for _, _, r, _ in reps]
        first_lost = health.index(1)
        assert 0 not in health[first_lost:first_lost + 3] and health[-1] == 0, health
        reps2 = [x for x in reports_of(lines, 2) if x[1] == 0]
        assert reps2 and all((r["x"], r["y"], r["fuel"], r["mission_seq"], r["reached_seq"]) ==
                             (-7, 1, -1, -1, -1) for _, _, r, _ in reps2), reps2
    finally:
        v.close()
        v2.close()


def test_no_fuel_without_a_capacity_and_no_report_without_gps_time():
    port = free_tcp_port()
    v = standin("tcp", port)
    port2 = free_tcp_port()
    v2 = standin("tcp", port2)
    v2.gps_ms = lambda boot: 0  # noqa: E731 -- no GPS fix yet: SYSTEM_TIME.time_unix_usec 0
    text = "\n".join([frame_line(), "reportcfg 1000 0", f"vehicle 1=tcp:127.0.0.1:{port}",
                      f"vehicle 2=tcp:127.0.0.1:{port2}", "listen 1500 500"]) + "\n"
    try:
        lines, rc, err = tool_lines(text)
        assert rc == 0, err
        reps = [x for x in reports_of(lines) if x[1] == 0]
        assert reps and all(r["fuel"] == -1 for _, _, r, _ in reps)
        assert [x for _, x in lines if x.startswith("report 2 ")][-1] == \
            "report 2 -3 no SYSTEM_TIME with a GPS time (time_unix_usec) heard yet"
    finally:
        v.close()
        v2.close()


def test_a_tcp_link_reconnects_to_a_restarted_vehicle():
    """The vehicle's process ends (its socket closes) and a new one (a reboot: time since
    boot starts again, another position) listens on the same port: the link is made again
    within the reconnection period, the streams are requested again, and the telemetry is
    the new boot's."""
    port = free_tcp_port()
    a = standin("tcp", port)
    text = "\n".join([frame_line(), f"vehicle 1=tcp:127.0.0.1:{port}", "listen 5000 250"]) + "\n"
    box = {}
    t = threading.Thread(target=lambda: box.update(out=tool_lines(text)))
    t.start()
    time.sleep(1.5)
    a.close()
    time.sleep(1.0)
    lat, lon = mavcheck.position_e7(FRAME_MIDNIGHT, -1.0, 4.0)
    # Taken before the new vehicle listens: the link cannot come back earlier, and the
    # tool's reader may see it come back before this thread runs again.
    b_started = time.monotonic()
    b = StandIn("tcp", port, 1, lat_e7=lat, lon_e7=lon, gps_at_boot_ms=FI["t0_ms"] + 2_000_000)
    try:
        t.join(60)
        lines, rc, err = box["out"]
        assert rc == 0, err
        events = [x for _, x in lines if x.startswith("link ")]
        assert events == ["link 1 connected", "link 1 lost closed by the vehicle",
                          "link 1 failed Connection refused", "link 1 connected"], events
        again = next(ts for ts, x in lines if x == "link 1 connected" and ts > b_started)
        assert again - b_started < 0.5 + 0.3
        assert a.requested() == STREAMS and b.requested() == STREAMS
        last = [x for _, x in lines if x.startswith("telemetry 1 ")][-1]
        assert f"lat_e7={lat} lon_e7={lon}" in last and "reboots=1" in last and "connects=2" in last
        rep = [x for x in reports_of(lines) if x[1] == 0][-1][2]
        assert (rep["x"], rep["y"]) == (-1, 4)
        assert rep["at_ticks"] >= (2_000_000) // FI["tick_ms"]
    finally:
        b.close()
