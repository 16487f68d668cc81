"""The on-board planner of `sva-tools sim --via lcm`: a real sva_node over LCM.

The simulator stays the ground truth; this module is its planner callable
(sim.Flight's `planner`): the first call publishes the fleet and the mission and waits
for the node's plan (the live mission starts at tick 0 with it); every call then
publishes the events of the history not yet sent, one event_t each (seq counts the
messages of this run), or a clock event_t at the tick when there is none, and waits for
each replan_t. The last replan_t of the tick is the plan the UAVs fly. Every message's
round trip (publish to answer, monotonic clock) and the node's solve time are kept.

Where the node runs: `run_via_lcm` enters a network namespace made for the run
(tools/netns/netns_run.sh, root only) unless it is already inside one (SVA_LCM_NETNS),
and there starts sva_node (SVA_NODE, else build/bin/sva_node) with the algorithm and
the scenario's change_penalty, or, with `attach`, uses the node already running there.

Kills (`kills`, from `kill_plan`): the node runs with `--state-dir` in a temporary
folder of the planner's own, and after the answer to each listed message it is killed
with SIGKILL and started again with the same options. The planner then waits for the
new node's first status, checks that it resumed (the plan id, revisions, clock and
revision of the last answer), and goes on; it publishes nothing again: the node must
resume by itself. Each kill is recorded (`kills`: tick, after_message, and what the
node said it replayed).
"""
from __future__ import annotations

import os
import random
import re
import shutil
import signal
import subprocess
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

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
    return Path(env) if env else REPO / "tools" / "netns" / "netns_run.sh"


def percentile(values: Sequence[float], q: float) -> float | None:
    """Nearest-rank percentile (q in [0, 100]) of values; None for none."""
    if not values:
        return None
    s = sorted(values)
    k = max(1, -(-len(s) * q // 100))  # ceil(n q / 100), at least 1
    return s[int(k) - 1]


def flight_messages(events: list[dict[str, Any]]) -> int:
    """The messages a flight sends the node: the fleet and mission (one answer, the
    plan), then one event_t per event, and a clock event_t at tick 0 when no event is
    at tick 0 (sim.Flight replans at tick 0 and at every tick with events)."""
    return 1 + len(events) + (0 if any(e.get("at") == 0 for e in events) else 1)


def kill_plan(events: list[dict[str, Any]], kills: int, seed: int) -> list[tuple[int, float]]:
    """`kills` seeded moments to kill the node: (after_message, delay in seconds), the
    message drawn from 1 .. messages - 1 (after the plan, before the last event; the same
    message may come twice: a node killed again right after it resumed), sorted."""
    rng = random.Random(seed)
    last = max(1, flight_messages(events) - 1)
    plan = [(rng.randint(1, last), round(rng.uniform(0.0, 0.02), 4)) for _ in range(kills)]
    return sorted(plan, key=lambda k: k[0])


RESUMED = re.compile(r"resumed from .*: (\d+) records replayed, (?:revision (\d+), now (-?\d+)|"
                     r"no live mission), plan id (\d+)")


class NodePlanner:
    """sim.Flight's planner, answered by sva_node over LCM (see the module docstring)."""

    def __init__(self, algo: str, penalty: int | None, url: str = DEFAULT_URL,
                 prefix: str = DEFAULT_PREFIX, attach: bool = False, timeout: float = 10.0,
                 kills: list[tuple[int, float]] | None = None, takeoff: int = 0) -> None:
        import lcm  # the venv's lcm==1.5.3

        self.algo, self.penalty = algo, penalty or 0
        self.takeoff = takeoff  # the mission's takeoff_ticks: a node option (not on the wire)
        self.url, self.prefix, self.attach, self.timeout = url, prefix, attach, timeout
        self.proc: subprocess.Popen[str] | None = None
        self.kill_at = list(kills or [])
        if self.kill_at and attach:
            raise NodeError("--kill-node: the node must be the run's own (not --attach)", 2)
        self.state_dir = tempfile.mkdtemp(prefix="sva-sim-state-") if self.kill_at else None
        self.kills: list[dict[str, Any]] = []
        self.answered = 0    # messages answered (the plan, then each replan)
        self.last: tuple[int, int, int] = (-1, 0, 0)  # plan id, revision, now of the last answer
        self.t = wire.types()
        self.lc = lcm.LCM(url)
        self.subs: list[Any] = []      # lcm.LCMSubscription (the lcm package has no hints)
        self.statuses: list[wire.Message] = []
        self.plans: list[tuple[int, wire.Message]] = []    # (arrival, plan_t)
        self.replans: dict[int, tuple[int, wire.Message]] = {}  # event seq: (arrival, replan_t)
        self.rev = time.time_ns() // 1000
        self.seq0 = (self.rev % 10**12) * 10**6  # this run's event seqs: seq0, seq0 + 1, ...
        self.sent = 0        # history events published
        self.messages = 0    # event_t published
        self.name = "mission"
        self.round_trips: list[int] = []
        esc = prefix.replace("\\", "\\\\")
        t = self.t

        def keep(store: Callable[[wire.Message], object],
                 decode: Callable[[bytes], wire.Message]) -> Callable[[str, bytes], None]:
            def on(channel: str, data: bytes) -> None:
                try:
                    store(decode(data))
                except (ValueError, IndexError):
                    pass  # not this type: nothing to answer
            return on

        # The subscriptions' handlers hold this planner, and the LCM object holds them: a
        # cycle the garbage collector cannot see into. close() unsubscribes, so that the
        # LCM object (its socket and receive thread) goes when the planner does.
        self.subs = [
            self.lc.subscribe(esc + "STATUS", keep(self.statuses.append, t.node_status_t.decode)),
            self.lc.subscribe(esc + "PLAN", keep(self._on_plan, t.plan_t.decode)),
            self.lc.subscribe(esc + "REPLAN", keep(self._on_replan, t.replan_t.decode))]
        for sub in self.subs:
            sub.set_queue_capacity(1000)
        if not attach:
            self._spawn()
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

    def _on_plan(self, p: wire.Message) -> None:
        if p.fleet_revision == self.rev and p.mission_revision == self.rev:
            self.plans.append((time.perf_counter_ns(), p))

    def _on_replan(self, r: wire.Message) -> None:
        if self.seq0 <= r.event_seq < self.seq0 + 10**6:
            self.replans[r.event_seq] = (time.perf_counter_ns(), r)

    def _wait(self, cond: Callable[[], object], timeout: float) -> bool:
        end = time.monotonic() + timeout
        while not cond():
            left = end - time.monotonic()
            if left <= 0:
                return False
            self.lc.handle_timeout(max(1, int(left * 1000)))
        return True

    def _spawn(self) -> None:
        argv = [str(node_bin()), "--url", self.url, "--prefix", self.prefix, "--algorithm",
                self.algo, "--change-penalty", str(self.penalty),
                "--takeoff-ticks", str(self.takeoff), "--status-ms", "200"]
        if self.state_dir is not None:
            argv += ["--state-dir", self.state_dir]
        self.proc = subprocess.Popen(
            argv, stdout=subprocess.PIPE if self.state_dir else subprocess.DEVNULL,
            stderr=subprocess.PIPE, text=True)

    def _kill_and_resume(self, now: int) -> None:
        """SIGKILL the node after the answer to message self.answered, start it again on
        the same journal, wait for its first status and check that it resumed."""
        after, delay = self.kill_at.pop(0)
        if delay > 0:
            time.sleep(delay)
        assert self.proc is not None
        self.proc.send_signal(signal.SIGKILL)
        self.proc.communicate()
        self.statuses.clear()
        t0 = time.perf_counter()
        self._spawn()
        proc = self.proc

        def first() -> bool:  # the new process's first status, or its end
            return any(s.seq == 1 for s in self.statuses) or proc.poll() is not None

        if not self._wait(first, self.timeout) or proc.poll() is not None:
            why = (proc.communicate()[1] or "").strip().splitlines() if proc.poll() is not None \
                else []
            self.close()
            raise NodeError(f"tick {now}: the node did not come back within {self.timeout} s "
                            f"after kill {len(self.kills) + 1} (after message {after})"
                            + (f": {why[-1]}" if why else ""), 3)
        resume_ms = round((time.perf_counter() - t0) * 1000, 1)
        status = next(s for s in self.statuses if s.seq == 1)
        assert self.proc is not None and self.proc.stdout is not None
        line = self.proc.stdout.readline().strip()
        said = RESUMED.search(line)
        plan_id, revision, now_ticks = self.last
        want = (plan_id, self.rev, self.rev)
        got = (status.last_plan_id, status.fleet_revision, status.mission_revision)
        if said is None or got != want or int(said.group(2) or 0) != revision or \
                int(said.group(3) or 0) != now_ticks:
            self.close()
            raise NodeError(f"tick {now}: the node did not resume after kill {len(self.kills) + 1} "
                            f"(after message {after}): it says {line!r} and its status plan id "
                            f"{got[0]}, revisions {got[1]}/{got[2]}; expected plan id {plan_id}, "
                            f"revision {revision}, now {now_ticks}", 1)
        self.kills.append({"tick": now, "after_message": after,
                           "replayed": int(said.group(1)), "revision": revision,
                           "now": now_ticks, "plan_id": plan_id, "resume_ms": resume_ms})

    def _answered(self, now: int, plan_id: int, revision: int, now_ticks: int) -> None:
        self.answered += 1
        self.last = (plan_id, revision, now_ticks)
        while self.kill_at and self.kill_at[0][0] <= self.answered:
            self._kill_and_resume(now)

    def close(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.communicate(timeout=5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.communicate()
        self.proc = None
        if self.state_dir is not None:
            shutil.rmtree(self.state_dir, ignore_errors=True)
            self.state_dir = None
        for sub in self.subs:
            self.lc.unsubscribe(sub)
        self.subs = []

    def _start(self, mission_doc: dict[str, Any]) -> dict[str, Any]:
        try:
            self.name, fleet, mission = wire.mission_messages(mission_doc, self.rev, self.rev)
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
        self._answered(0, p.plan_id, 0, 0)
        return {"channel": "PLAN", "plan_id": p.plan_id, "solve_us": p.solve_us,
                "round_trip_us": rt}

    def _send(self, event: dict[str, Any], now: int,
              is_event: bool) -> tuple[dict[str, Any], tuple[dict[str, Any], wire.Message]]:
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
        if doc["accepted"]:
            self._answered(now, r.plan.plan_id, r.revision, r.now_ticks)
        info = {"channel": "REPLAN", "event_seq": seq, "event": doc["event"],
                "accepted": doc["accepted"], "now": doc["now"], "revision": doc["revision"],
                "solve_us": r.plan.solve_us if doc["accepted"] else None,
                "plan_id": r.plan.plan_id if doc["accepted"] else None, "round_trip_us": rt}
        return info, (doc, r)

    def __call__(self, mission_doc: dict[str, Any], history: list[dict[str, Any]], now: int,
                 algo: str) -> tuple[dict[str, Any], dict[str, Any]]:
        messages = []
        if not self.plans:
            messages.append(self._start(mission_doc))
        new = history[self.sent:]
        todo = new if new else [{"at": now, "type": "clock"}]
        last: tuple[dict[str, Any], wire.Message] | None = None
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
        if last is None:  # cannot happen: there is always a message to send
            raise NodeError("no message was sent to the node", 2)
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

    def summary(self) -> dict[str, Any]:
        rts = self.round_trips
        return {"url": self.url, "prefix": self.prefix, "algorithm": self.algo,
                "change_penalty": self.penalty, "attached": self.attach,
                "restarts": len(self.kills), "messages": len(rts),
                "round_trip_us": {"p50": percentile(rts, 50), "p99": percentile(rts, 99),
                                  "max": max(rts) if rts else None}}


def comparable_flight(log: dict[str, Any]) -> dict[str, Any]:
    """What a flight through the node must share with another flight of the same
    scenario to count as the same flight (e.g. one whose node was killed and resumed):
    the ground truth (tracks, visits, outcomes, summary) and every replan (residual
    mission, plan with its plan id, changes, live figures, each node message's answer);
    times and revisions aside, as the revisions name the run."""
    replans = []
    for r in log["replans"]:
        plan = dict(r["plan"])
        stats = {k: v for k, v in plan.pop("stats", {}).items()
                 if k not in ("solve_us", "fleet_revision", "mission_revision")}
        msgs = [{k: m.get(k) for k in ("channel", "event", "accepted", "now", "revision",
                                       "plan_id")} for m in r["node"]["messages"]]
        replans.append({"at": r["at"], "cause": r["cause"], "mission": r["mission"],
                        "plan": plan, "stats": stats, "changes": r["changes"],
                        "live": r["live"], "plan_id": r["node"]["plan_id"], "messages": msgs})
    return {"end_tick": log["end_tick"], "targets": log["targets"], "uavs": log["uavs"],
            "summary": log["summary"], "replans": replans}
