"""The on-board side of `sva-tools sitl` and the ground station's LCM link to it.

`sva_node` (the planner; $SVA_NODE, else build/bin/sva_node) and `sva_mavlink_bridge`
($SVA_MAVLINK_BRIDGE, else build/bin/sva_mavlink_bridge) run as they would on a
companion computer, over LCM in the run's network namespace; the bridge reaches every
vehicle's SERIAL0 over TCP. This module starts both (each killed with the tool,
PR_SET_PDEATHSIG), publishes the fleet, the mission and the scenario's ground events
as a ground station would, and keeps what comes back: the node's plans and replans and
the bridge's lines (one per vehicle and upload).
"""
from __future__ import annotations

import fcntl
import os
import re
import subprocess
import time
from pathlib import Path
from typing import Any, Callable, TypedDict

from ..lcm import wire
from .vehicle import start_child

REPO = Path(__file__).resolve().parents[3]
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
DEFAULT_PREFIX = "SVA_"
# `plan 3: uav 2 (tcp:127.0.0.1:5770:2): uploaded 7 items`
_BRIDGE_LINE = re.compile(r"^plan (\S+): uav (\d+) \(([^)]*)\): (.*)$")
_UPLOADED = re.compile(r"^uploaded (\d+) items$")


class BridgeLine(TypedDict):
    """A per-vehicle line of the bridge (Ground.parse_bridge_line)."""

    plan: str
    uav: int
    endpoint: str
    text: str
    items: int | None


class GroundError(RuntimeError):
    """The node or the bridge failed, refused the mission, or did not answer; `status`
    is the exit status."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


def program(env: str, name: str) -> Path:
    p = Path(os.environ.get(env) or REPO / "build" / "bin" / name)
    if not (p.is_file() and os.access(p, os.X_OK)):
        raise GroundError(f"{name} is missing: {p} is not an executable file (build it with "
                          f"scripts/build.sh, or point {env} at it)", 2)
    return p


class Ground:
    def __init__(self, folder: Path, algo: str, penalty: int, url: str = DEFAULT_URL,
                 prefix: str = DEFAULT_PREFIX, takeoff: int = 0):
        import lcm

        self.folder, self.algo, self.penalty, self.takeoff = folder, algo, penalty, takeoff
        self.url, self.prefix = url, prefix
        self.node: subprocess.Popen[bytes] | None = None
        self.bridge: subprocess.Popen[bytes] | None = None
        self._bridge_buf = b""
        self.t = wire.types()
        self.lc = lcm.LCM(url)
        self.statuses = 0
        self.plans: list[tuple[float, Any]] = []
        self.replans: list[tuple[float, object]] = []   # (host monotonic, replan_t)
        self.reports = 0                                 # report_t heard
        self.report_now = -1                             # the latest at_ticks reported
        self.health: dict[int, list[list[Any]]] = {}     # uav -> [[host, health], ...] on change
        self.rev = time.time_ns() // 1000
        self.seq0 = (self.rev % 10**12) * 10**6
        self.sent = 0
        esc = prefix.replace("\\", "\\\\")
        t = self.t

        def keep(store: Callable[[tuple[float, Any]], object],
                 decode: Callable[[bytes], Any]) -> Callable[[str, bytes], None]:
            def on(_channel: str, data: bytes) -> None:
                try:
                    store((time.monotonic(), decode(data)))
                except (ValueError, IndexError):
                    pass  # not this type
            return on

        self.lc.subscribe(esc + "STATUS", keep(self._on_status, t.node_status_t.decode)
                          ).set_queue_capacity(10000)
        self.lc.subscribe(esc + "PLAN", keep(self.plans.append, t.plan_t.decode)
                          ).set_queue_capacity(10000)
        self.lc.subscribe(esc + "REPLAN", keep(self.replans.append, t.replan_t.decode)
                          ).set_queue_capacity(10000)
        self.lc.subscribe(esc + "REPORT", keep(self._on_report, t.report_t.decode)
                          ).set_queue_capacity(10000)

    def _on_status(self, _item: tuple[float, Any]) -> None:
        self.statuses += 1

    def _on_report(self, item: tuple[float, Any]) -> None:
        at, r = item
        self.reports += 1
        self.report_now = max(self.report_now, r.at_ticks)
        seen = self.health.setdefault(r.uav_id, [])
        if not seen or seen[-1][1] != r.health:
            seen.append([at, r.health])

    # --- processes -------------------------------------------------------------------

    def start_node(self) -> None:
        exe = program("SVA_NODE", "sva_node")
        log = open(self.folder / "sva_node.log", "wb")
        self.node = start_child(
            [str(exe), "--url", self.url, "--prefix", self.prefix, "--algo", self.algo,
             "--change-penalty", str(self.penalty), "--takeoff-ticks", str(self.takeoff),
             "--status-ms", "200"],
            stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)

    def start_bridge(self, vehicles: list[tuple[int, int, int]], report_ms: int,
                     heartbeat_timeout_ms: int, cruise_m_s: float) -> list[str]:
        """vehicles: (uav id, TCP port, system id); cruise_m_s: the speed the vehicles are
        commanded (the plan's is lower: the difference is the margin). Returns the
        command line."""
        exe = program("SVA_MAVLINK_BRIDGE", "sva_mavlink_bridge")
        cmd = [str(exe), "--url", self.url, "--prefix", self.prefix, "--ardupilot",
               "--report-ms", str(report_ms), "--heartbeat-timeout-ms", str(heartbeat_timeout_ms),
               "--cruise-speed", f"{cruise_m_s:g}"]
        for uid, port, sysid in vehicles:
            cmd += ["--vehicle", f"{uid}=tcp:127.0.0.1:{port}:{sysid}"]
        self.bridge = start_child(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                  stderr=open(self.folder / "bridge.err", "wb"))
        stdout = self.bridge.stdout
        if stdout is None:  # cannot happen: stdout=PIPE
            raise GroundError("the bridge has no stdout pipe")
        fd = stdout.fileno()
        fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) | os.O_NONBLOCK)
        return cmd

    def check_alive(self) -> None:
        for name, p, log in (("sva_node", self.node, "sva_node.log"),
                             ("sva_mavlink_bridge", self.bridge, "bridge.err")):
            if p is not None and p.poll() is not None:
                raise GroundError(f"{name} exited with status {p.returncode}: "
                                  f"{self.tail(log)}")

    def tail(self, name: str) -> str:
        try:
            text = (self.folder / name).read_text(encoding="utf-8", errors="replace")
        except OSError:
            return ""
        return " | ".join(text.strip().splitlines()[-3:])

    def close(self) -> None:
        for p in (self.bridge, self.node):
            if p is not None and p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        self.bridge = self.node = None

    # --- traffic ---------------------------------------------------------------------

    def fds(self) -> list[int]:
        out = [self.lc.fileno()]
        if self.bridge is not None and self.bridge.stdout is not None:
            out.append(self.bridge.stdout.fileno())
        return out

    def handle(self) -> None:
        """Dispatches every LCM message waiting (handlers fill the lists above)."""
        while self.lc.handle_timeout(0) > 0:
            pass

    def bridge_lines(self) -> list[str]:
        """The bridge's complete stdout lines since the last call."""
        if self.bridge is None or self.bridge.stdout is None:
            return []
        try:
            data = os.read(self.bridge.stdout.fileno(), 65536)
        except BlockingIOError:
            data = b""
        self._bridge_buf += data
        *lines, self._bridge_buf = self._bridge_buf.split(b"\n")
        return [ln.decode("utf-8", "replace") for ln in lines]

    @staticmethod
    def parse_bridge_line(line: str) -> BridgeLine | None:
        """{plan, uav, endpoint, text, items (for an accepted upload)} of a per-vehicle
        line, None for another line."""
        m = _BRIDGE_LINE.match(line)
        if not m:
            return None
        up = _UPLOADED.match(m.group(4))
        return {"plan": m.group(1), "uav": int(m.group(2)), "endpoint": m.group(3),
                "text": m.group(4), "items": int(up.group(1)) if up else None}

    def wait(self, cond: Callable[[], bool], timeout: float) -> bool:
        end = time.monotonic() + timeout
        while not cond():
            left = end - time.monotonic()
            if left <= 0:
                return False
            self.lc.handle_timeout(max(1, int(min(left, 0.2) * 1000)))
            self.check_alive()
        return True

    def publish_mission(self, mission_doc: dict[str, Any]) -> str:
        """Publishes the fleet and the mission (one revision); returns its name. The
        mission's takeoff_ticks is the node's --takeoff-ticks (mission_t has none)."""
        name: str
        try:
            name, fleet, mission = wire.mission_messages(mission_doc, self.rev, self.rev)
        except wire.InputError as e:
            raise GroundError(f"mission: {e}", 2) from None
        self.lc.publish(self.prefix + "FLEET", fleet.encode())
        self.lc.publish(self.prefix + "MISSION", mission.encode())
        return name

    def first_plan(self) -> tuple[float, Any] | None:
        for at, p in self.plans:
            if p.fleet_revision == self.rev and p.mission_revision == self.rev:
                return at, p
        return None

    def publish_event(self, event: dict[str, Any]) -> int:
        """Publishes one event_t; returns its seq."""
        seq = self.seq0 + self.sent
        self.sent += 1
        try:
            msg = wire.event_message(event, seq)
        except wire.InputError as e:
            raise GroundError(f"event: {e}", 2) from None
        self.lc.publish(self.prefix + "EVENT", msg.encode())
        return seq
