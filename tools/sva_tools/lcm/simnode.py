"""The on-board planner of `sva-tools sim --via lcm`: a real sva_node over LCM.

The simulator stays the ground truth; this module is its planner callable
(sim.Flight's `planner`): the first call publishes the fleet and the mission and waits
for the node's plan (the live mission starts at tick 0 with it); every call then
publishes the events of the history not yet sent, one event_t each (seq counts the
messages of this run), or a clock event_t at the tick when there is none, and waits for
each replan_t. The last replan_t of the tick is the plan the UAVs fly. Every message's
round trip (publish to answer, monotonic clock) and the node's solve time are kept.

Where the node runs: `run_via_lcm` enters a network namespace made for the run
(tests/lcm/netns_run.sh, root only) unless it is already inside one (SVA_LCM_NETNS),
and there starts sva_node (SVA_NODE, else build/bin/sva_node) with the algorithm and
the scenario's change_penalty, or, with `attach`, uses the node already running there.
"""
from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path
from typing import List, Optional, Tuple

from . import wire

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
DEFAULT_PREFIX = "SVA_"
REPO = Path(__file__).resolve().parents[3]


class NodeError(Exception):
    """The node refused or failed, or did not answer; `status` is the exit status."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


def node_bin() -> Path:
    env = os.environ.get("SVA_NODE")
    p = Path(env) if env else REPO / "build" / "bin" / "sva_node"
    if not (p.is_file() and os.access(p, os.X_OK)):
        raise NodeError(f"the LCM node is missing: {p} is not an executable file (build it "
                        "with scripts/build.sh, or point SVA_NODE at it)", 2)
    return p


def netns_helper() -> Path:
    env = os.environ.get("SVA_NETNS_RUN")
    return Path(env) if env else REPO / "tests" / "lcm" / "netns_run.sh"


def percentile(values: List[float], q: float) -> Optional[float]:
    """Nearest-rank percentile (q in [0, 100]) of values; None for none."""
    if not values:
        return None
    s = sorted(values)
    k = max(1, -(-len(s) * q // 100))  # ceil(n q / 100), at least 1
    return s[int(k) - 1]


class NodePlanner:
    """sim.Flight's planner, answered by sva_node over LCM (see the module docstring)."""

    def __init__(self, algo: str, penalty: Optional[int], url: str = DEFAULT_URL,
                 prefix: str = DEFAULT_PREFIX, attach: bool = False, timeout: float = 10.0):
        import lcm  # the venv's lcm==1.5.3

        self.algo, self.penalty = algo, penalty or 0
        self.url, self.prefix, self.attach, self.timeout = url, prefix, attach, timeout
        self.proc: Optional[subprocess.Popen] = None
        self.t = wire.types()
        self.lc = lcm.LCM(url)
        self.statuses: list = []
        self.plans: list = []
        self.replans: dict = {}
        self.rev = time.time_ns() // 1000
        self.seq0 = (self.rev % 10**12) * 10**6  # this run's event seqs: seq0, seq0 + 1, ...
        self.sent = 0        # history events published
        self.messages = 0    # event_t published
        self.name = "mission"
        self.round_trips: List[int] = []
        esc = prefix.replace("\\", "\\\\")
        t = self.t

        def keep(store, decode):
            def on(channel, data):
                try:
                    store(decode(data))
                except (ValueError, IndexError):
                    pass  # not this type: nothing to answer
            return on

        self.lc.subscribe(esc + "STATUS", keep(self.statuses.append, t.node_status_t.decode)
                          ).set_queue_capacity(1000)
        self.lc.subscribe(esc + "PLAN", keep(self._on_plan, t.plan_t.decode)
                          ).set_queue_capacity(1000)
        self.lc.subscribe(esc + "REPLAN", keep(self._on_replan, t.replan_t.decode)
                          ).set_queue_capacity(1000)
        if not attach:
            self.proc = subprocess.Popen(
                [str(node_bin()), "--url", url, "--prefix", prefix, "--algorithm", algo,
                 "--change-penalty", str(self.penalty), "--status-ms", "200"],
                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if not self._wait(lambda: self.statuses, timeout):
            self.close()
            raise NodeError(f"no node status on {prefix}STATUS within {timeout} s "
                            f"(is sva_node running on {url}?)", 3)
        have = self.statuses[-1].algorithm
        want = wire.ALGORITHMS.index(algo)
        if have != want:
            self.close()
            shown = wire.ALGORITHMS[have] if 0 <= have < len(wire.ALGORITHMS) else have
            raise NodeError(f"--algo {algo}: the node plans with {shown} (start sva_node "
                            f"--algorithm {algo})", 2)

    def _on_plan(self, p) -> None:
        if p.fleet_revision == self.rev and p.mission_revision == self.rev:
            self.plans.append((time.perf_counter_ns(), p))

    def _on_replan(self, r) -> None:
        if self.seq0 <= r.event_seq < self.seq0 + 10**6:
            self.replans[r.event_seq] = (time.perf_counter_ns(), r)

    def _wait(self, cond, timeout: float) -> bool:
        end = time.monotonic() + timeout
        while not cond():
            left = end - time.monotonic()
            if left <= 0:
                return False
            self.lc.handle_timeout(max(1, int(left * 1000)))
        return True

    def close(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.communicate(timeout=5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.communicate()
        self.proc = None

    def _start(self, mission_doc: dict) -> dict:
        doc = {k: v for k, v in mission_doc.items() if k != "change_penalty"}
        try:
            self.name, fleet, mission = wire.mission_messages(doc, self.rev, self.rev)
        except wire.InputError as e:
            raise NodeError(f"mission: {e}", 2) from None
        t0 = time.perf_counter_ns()
        self.lc.publish(self.prefix + "FLEET", fleet.encode())
        self.lc.publish(self.prefix + "MISSION", mission.encode())
        if not self._wait(lambda: self.plans, self.timeout):
            raise NodeError(f"no plan on {self.prefix}PLAN for revision {self.rev} within "
                            f"{self.timeout} s", 3)
        at, p = self.plans[0]
        if p.status not in (p.STATUS_COMPLETE, p.STATUS_PARTIAL):
            raise NodeError(f"the node did not plan the mission (status {p.status}): "
                            f"{wire.diag_text(p)}", 2 if p.status == p.STATUS_REJECTED else 1)
        rt = (at - t0) // 1000
        self.round_trips.append(rt)
        return {"channel": "PLAN", "plan_id": p.plan_id, "solve_us": p.solve_us,
                "round_trip_us": rt}

    def _send(self, event: dict, now: int, is_event: bool) -> Tuple[dict, object]:
        seq = self.seq0 + self.messages
        self.messages += 1
        where = f"events[{self.sent}]." if is_event else "clock."
        try:
            msg = wire.event_message(event, seq, where)
        except wire.InputError as e:
            raise NodeError(f"tick {now}: {e}", 2) from None
        t0 = time.perf_counter_ns()
        self.lc.publish(self.prefix + "EVENT", msg.encode())
        if not self._wait(lambda: seq in self.replans, self.timeout):
            raise NodeError(f"tick {now}: no replan of event seq {seq} on {self.prefix}REPLAN "
                            f"within {self.timeout} s", 3)
        at, r = self.replans.pop(seq)
        try:
            doc = wire.replan_document(r, self.name)
        except wire.InputError as e:
            raise NodeError(f"tick {now}: {self.prefix}REPLAN: {e}", 1) from None
        rt = (at - t0) // 1000
        self.round_trips.append(rt)
        info = {"channel": "REPLAN", "event_seq": seq, "event": doc["event"],
                "accepted": doc["accepted"], "now": doc["now"], "revision": doc["revision"],
                "solve_us": r.plan.solve_us if doc["accepted"] else None,
                "plan_id": r.plan.plan_id if doc["accepted"] else None, "round_trip_us": rt}
        return info, (doc, r)

    def __call__(self, mission_doc: dict, history: List[dict], now: int, algo: str):
        messages = []
        if not self.plans:
            messages.append(self._start(mission_doc))
        new = history[self.sent:]
        todo = new if new else [{"at": now, "type": "clock"}]
        last = None
        for e in todo:
            info, (doc, r) = self._send(e, now, bool(new))
            messages.append(info)
            if not doc["accepted"]:
                which = f"events[{self.sent}]" if new else "clock"
                raise NodeError(f"tick {now}: sva_node refused {which}: {doc['error']}", 2)
            if "plan" not in doc:
                raise NodeError(f"tick {now}: sva_node: {doc.get('error')}", 1)
            if r.change_penalty != self.penalty:
                raise NodeError(f"change_penalty: the scenario asks {self.penalty}, the node "
                                f"replans with {r.change_penalty} (start sva_node "
                                f"--change-penalty {self.penalty})", 2)
            if new:
                self.sent += 1
            last = (doc, r)
        doc, r = last
        out = doc["plan"]
        ch = doc["changes"]
        out["changes"] = {"dropped": ch["dropped_visits"], "added": ch["added_visits"],
                          "count": ch["dropped"] + ch["added"], "penalty": doc["change_penalty"]}
        out["live"] = {"now": doc["now"], "revision": doc["revision"], "kept": doc["kept"],
                       "covered": doc["covered"], "under_way_count": doc["under_way"],
                       "objective": doc["objective"]}
        out["node"] = {"plan_id": r.plan.plan_id, "messages": messages}
        return out, doc["residual"]

    def summary(self) -> dict:
        rts = self.round_trips
        return {"url": self.url, "prefix": self.prefix, "algorithm": self.algo,
                "change_penalty": self.penalty, "attached": self.attach,
                "messages": len(rts),
                "round_trip_us": {"p50": percentile(rts, 50), "p99": percentile(rts, 99),
                                  "max": max(rts) if rts else None}}


def reexec_in_netns(argv: List[str]) -> int:
    """Runs `python -m sva_tools ARGV` in a fresh network namespace (netns_run.sh) and
    returns its exit status; 2 with a clear message when that cannot be done."""
    if os.geteuid() != 0:
        print("sva-tools: error: sim --via lcm: needs root to create the network namespace "
              "the node and the simulator talk in (ip netns); run it as root, or inside a "
              "namespace made for it (SVA_LCM_NETNS set, as tests/lcm/netns_run.sh does)",
              file=sys.stderr)
        return 2
    helper = netns_helper()
    if not os.access(helper, os.X_OK):
        print(f"sva-tools: error: sim --via lcm: the network namespace helper {helper} is "
              "missing (point SVA_NETNS_RUN at tests/lcm/netns_run.sh)", file=sys.stderr)
        return 2
    env = dict(os.environ)
    tools = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = tools + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    rc = subprocess.run([str(helper), sys.executable, "-m", "sva_tools", *argv], env=env).returncode
    if rc == 77:
        print("sva-tools: error: sim --via lcm: could not create a network namespace "
              "(ip netns: needs root and iproute2)", file=sys.stderr)
        return 2
    return rc
