"""One ArduCopter SITL vehicle for `sva-tools sitl`: its process and the ground
operator's MAVLink link to it.

The process: `arducopter --model + --speedup N --defaults copter.parm,EXTRA -I i
--sysid i+1 --home LAT,LON,0,0 --start-time T --serial0 tcp:0` in a working folder of
its own (fresh eeprom: a clean vehicle). SERIAL0 (TCP 5760 + 10 i) is the bridge's;
`tcp:0` without `:wait` lets the simulation (and the vehicle's GPS clock, T + its
simulated time) run from launch, whenever the bridge connects. SERIAL1 (TCP
5762 + 10 i) is the operator link below. The process gets SIGKILL when the tool dies
(PR_SET_PDEATHSIG), so no vehicle outlives a crashed run.

The operator link (pymavlink's MAVLink codec over a socket of our own) asks for the
telemetry the tool logs (SET_MESSAGE_INTERVAL), keeps the vehicle's clock (SYSTEM_TIME:
GPS time in microseconds against its boot time), arms the vehicle in AUTO, and reads
back the mission the bridge uploaded.
"""
from __future__ import annotations

import ctypes
import os
import select
import signal
import socket
import subprocess
import time
from pathlib import Path
from typing import Any

from pymavlink.dialects.v20 import ardupilotmega as mavlink

REPO = Path(__file__).resolve().parents[3]
DEFAULT_SITL = REPO.parent / "shared" / "sitl" / "arducopter"
OPERATOR_SYSTEM = 255          # a ground station (ArduPilot's default SYSID_MYGCS)
OPERATOR_COMPONENT = 190       # MAV_COMP_ID_MISSIONPLANNER
COPTER_AUTO = 3                # ArduCopter custom modes
COPTER_GUIDED = 4

# Parameters laid over copter.parm for every vehicle (a second --defaults file):
# AUTO_OPTIONS 3 allows arming in AUTO and taking off without raising the throttle (the
# operator arms a vehicle in AUTO with its mission loaded); no dataflash logs, no
# terrain (nothing to fetch it from); no default telemetry streams on SERIAL1 (the
# operator link asks for what it logs).
EXTRA_PARAMETERS = {
    "AUTO_OPTIONS": 3,
    "LOG_BACKEND_TYPE": 0,
    "TERRAIN_ENABLE": 0,
    "SR1_RAW_SENS": 0, "SR1_EXT_STAT": 0, "SR1_RC_CHAN": 0, "SR1_RAW_CTRL": 0,
    "SR1_POSITION": 0, "SR1_EXTRA1": 0, "SR1_EXTRA2": 0, "SR1_EXTRA3": 0, "SR1_PARAMS": 0,
    "SR1_ADSB": 0,
}

# Telemetry the operator link asks for: message id -> interval in vehicle microseconds.
STREAMS_US = {
    mavlink.MAVLINK_MSG_ID_GLOBAL_POSITION_INT: 200_000,
    mavlink.MAVLINK_MSG_ID_SYSTEM_TIME: 1_000_000,
    mavlink.MAVLINK_MSG_ID_MISSION_CURRENT: 200_000,
    mavlink.MAVLINK_MSG_ID_EKF_STATUS_REPORT: 1_000_000,
    mavlink.MAVLINK_MSG_ID_GPS_RAW_INT: 1_000_000,
}
EKF_POS_HORIZ_ABS = 1 << 4     # EKF_STATUS_FLAGS
EKF_PRED_POS_HORIZ_ABS = 1 << 8
MAV_MODE_FLAG_SAFETY_ARMED = 128


class SitlError(RuntimeError):
    """A vehicle could not be started or reached."""


def sitl_binary(path: str | None = None) -> Path:
    """The arducopter binary: PATH, else $SVA_SITL, else ../shared/sitl/arducopter."""
    p = Path(path or os.environ.get("SVA_SITL") or DEFAULT_SITL)
    if not (p.is_file() and os.access(p, os.X_OK)):
        raise SitlError(f"the ArduCopter SITL binary is missing: {p} is not an executable file "
                        f"(give --sitl PATH or set SVA_SITL)")
    return p


HELD_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def die_with_parent() -> None:
    """In a child before exec: SIGKILL when the tool dies. A stop signal sent to the
    tool's process group while the child was forming (start_child holds them blocked) is
    dropped here; the program starts with both at their default."""
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    for sig in HELD_SIGNALS:
        signal.signal(sig, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, HELD_SIGNALS)
    for sig in HELD_SIGNALS:
        signal.signal(sig, signal.SIG_DFL)


def start_child(cmd: list[str], **kwargs: Any) -> subprocess.Popen[Any]:
    """subprocess.Popen in a session of its own, so that a Ctrl-C reaches the tool, which
    stops its children; the child dies with the tool. SIGINT and SIGTERM stay blocked over
    the fork: between fork and its new session the child is in the tool's process group,
    where a stop passed on to the group would run the tool's Python handler in the child
    (its at-fork hooks then print "Exception ignored" and a traceback). A stop that comes
    meanwhile reaches the tool once the child is started."""
    old = signal.pthread_sigmask(signal.SIG_BLOCK, HELD_SIGNALS)
    try:
        return subprocess.Popen(cmd, preexec_fn=die_with_parent, start_new_session=True, **kwargs)
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def write_extra_parameters(folder: Path) -> Path:
    path = folder / "sitl_extra.parm"
    path.write_text("".join(f"{k} {v}\n" for k, v in EXTRA_PARAMETERS.items()), encoding="utf-8")
    return path


class Process:
    """One arducopter process (one spell in service of one UAV)."""

    def __init__(self, binary: Path, defaults: str, folder: Path, instance: int, sysid: int,
                 home: tuple[float, float], speedup: float, start_time_s: int):
        folder.mkdir(parents=True, exist_ok=True)
        self.folder = folder
        self.instance = instance
        self.cmd = [str(binary), "--model", "+", "--speedup", f"{speedup:g}", "--defaults", defaults,
                    "-I", str(instance), "--sysid", str(sysid),
                    "--home", f"{home[0]:.7f},{home[1]:.7f},0,0",
                    "--start-time", str(start_time_s), "--serial0", "tcp:0"]
        self.out = open(folder / "sitl.log", "wb")
        self.launched = time.monotonic()
        self.start_time_s = start_time_s
        self.proc = start_child(self.cmd, cwd=folder, stdin=subprocess.DEVNULL, stdout=self.out,
                                stderr=subprocess.STDOUT)

    @property
    def serial0_port(self) -> int:
        return 5760 + 10 * self.instance

    @property
    def serial1_port(self) -> int:
        return 5762 + 10 * self.instance

    def alive(self) -> bool:
        return self.proc.poll() is None

    def kill(self) -> None:
        """SIGKILL, as a vehicle that drops out of the sky does not say goodbye."""
        if self.proc.poll() is None:
            self.proc.kill()
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass
        self.out.close()

    def tail(self, lines: int = 5) -> str:
        try:
            text = (self.folder / "sitl.log").read_text(encoding="utf-8", errors="replace")
        except OSError:
            return ""
        return " | ".join(text.strip().splitlines()[-lines:])


class _Sender:
    def __init__(self, sock: socket.socket):
        self.sock = sock

    def write(self, data: bytes) -> None:
        self.sock.sendall(data)


class Link:
    """The operator's MAVLink link to one vehicle (its SERIAL1): non-blocking receive
    (poll() returns the messages that arrived), blocking sends."""

    def __init__(self, port: int, sysid: int):
        self.port, self.sysid = port, sysid
        self.sock: socket.socket | None = None
        self.mav: mavlink.MAVLink | None = None
        self.closed = False

    def connect(self) -> bool:
        """One attempt; True once connected (SITL listens within a second of launch)."""
        if self.sock is not None:
            return True
        s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        s.settimeout(1.0)
        try:
            s.connect(("127.0.0.1", self.port))
        except OSError:
            s.close()
            return False
        s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        s.settimeout(2.0)
        self.sock = s
        self.mav = mavlink.MAVLink(_Sender(s), srcSystem=OPERATOR_SYSTEM,
                                   srcComponent=OPERATOR_COMPONENT)
        self.mav.robust_parsing = True
        return True

    def fileno(self) -> int:
        return self.sock.fileno() if self.sock is not None else -1

    def poll(self) -> list[Any]:
        """Messages from the vehicle that are ready (none when nothing arrived)."""
        if self.sock is None:
            return []
        out: list[Any] = []
        while True:
            r, _w, _x = select.select([self.sock], [], [], 0)
            if not r:
                return out
            try:
                data = self.sock.recv(65536)
            except OSError:
                data = b""
            if not data:
                self.close()
                return out
            msgs = (self.mav.parse_buffer(data) or []) if self.mav is not None else []
            out += [m for m in msgs if m.get_type() != "BAD_DATA"
                    and m.get_srcSystem() == self.sysid]

    def close(self) -> None:
        if self.sock is not None:
            try:
                self.sock.close()
            except OSError:
                pass
        self.sock = None
        self.closed = True

    def send(self, what: str, *args: float) -> bool:
        if self.sock is None:
            return False
        try:
            getattr(self.mav, what + "_send")(*args)
        except OSError:
            self.close()
            return False
        return True

    def command(self, cmd: int, *params: float) -> bool:
        p = list(params) + [0.0] * (7 - len(params))
        return self.send("command_long", self.sysid, 1, cmd, 0, *p)

    def ask_streams(self, which: list[int]) -> None:
        for msgid in which:
            self.command(mavlink.MAV_CMD_SET_MESSAGE_INTERVAL, msgid, STREAMS_US[msgid])

    def set_mode(self, custom_mode: int) -> bool:
        return self.command(mavlink.MAV_CMD_DO_SET_MODE,
                            mavlink.MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, custom_mode)

    def arm(self) -> bool:
        return self.command(mavlink.MAV_CMD_COMPONENT_ARM_DISARM, 1)

    def request_mission(self) -> bool:
        return self.send("mission_request_list", self.sysid, 1, 0)

    def request_item(self, seq: int) -> bool:
        return self.send("mission_request_int", self.sysid, 1, seq, 0)

    def mission_ack(self) -> bool:
        return self.send("mission_ack", self.sysid, 1, 0, 0, 0)


class Clock:
    """A vehicle's GPS clock: the last SYSTEM_TIME's offset of UTC against boot time, and
    the freshest boot time heard (any message with time_boot_ms)."""

    def __init__(self, speedup: float):
        self.speedup = speedup
        self.offset_ms: float | None = None   # UTC ms - boot ms
        self.boot_ms: int | None = None
        self.heard_at = 0.0                      # host monotonic of boot_ms

    def on_system_time(self, unix_us: int, boot_ms: int) -> None:
        if unix_us > 0:
            self.offset_ms = unix_us / 1000.0 - boot_ms
        self.on_boot(boot_ms)

    def on_boot(self, boot_ms: int) -> None:
        if self.boot_ms is None or boot_ms >= self.boot_ms:
            self.boot_ms = boot_ms
            self.heard_at = time.monotonic()

    def utc_ms(self, boot_ms: int | None = None) -> float | None:
        """UTC ms of a boot time (of now, extrapolated at the speedup, for None)."""
        if self.offset_ms is None or self.boot_ms is None:
            return None
        if boot_ms is not None:
            return boot_ms + self.offset_ms
        late = min(time.monotonic() - self.heard_at, 0.5) * 1000.0 * self.speedup
        return self.boot_ms + self.offset_ms + late


class MissionReader:
    """Reads back the mission a vehicle holds (MISSION_REQUEST_LIST, then each item)."""

    def __init__(self) -> None:
        self.count: int | None = None
        self.items: dict[int, object] = {}
        self.asked_at = 0.0
        self.active = False

    def start(self, link: Link) -> None:
        self.count, self.items, self.active = None, {}, True
        self.asked_at = time.monotonic()
        link.request_mission()

    def on_message(self, link: Link, m: Any) -> list[Any] | None:
        """The items once complete, else None."""
        # m, like the items, is a pymavlink message: pymavlink has no type hints
        if not self.active:
            return None
        kind = m.get_type()
        if kind == "MISSION_COUNT" and getattr(m, "mission_type", 0) == 0:
            self.count = m.count
            if self.count == 0:
                self.active = False
                return []
            link.request_item(0)
            self.asked_at = time.monotonic()
        elif kind in ("MISSION_ITEM_INT", "MISSION_ITEM") and self.count is not None:
            self.items[m.seq] = m
            nxt = next((s for s in range(self.count) if s not in self.items), None)
            if nxt is None:
                link.mission_ack()
                self.active = False
                return [self.items[s] for s in range(self.count)]
            link.request_item(nxt)
            self.asked_at = time.monotonic()
        return None

    def retry(self, link: Link) -> None:
        if self.active and time.monotonic() - self.asked_at > 1.0:
            if self.count is None:
                self.start(link)
            else:
                nxt = next((s for s in range(self.count) if s not in self.items), 0)
                link.request_item(nxt)
                self.asked_at = time.monotonic()
