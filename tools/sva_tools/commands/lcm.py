"""`lcm send | scenario | record | replay`: the ground side of the LCM link (docs/lcm.md).

Exit status: 0 success; 1 the node rejected the mission, an event, or planning failed;
2 bad command line, mission or scenario file; 3 no plan (or replan) before the timeout;
4 an LCM program failed.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Any

from ..lcm import wire
from ..text import shown
from .common import Parser

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
DEFAULT_PREFIX = "SVA_"


def _parser() -> argparse.ArgumentParser:
    p = Parser(prog="sva-tools lcm", description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest="command", required=True)

    s = sub.add_parser("send", help="publish a mission and its fleet, print the plan")
    s.add_argument("mission", help="SPEC section 3 mission JSON")
    s.add_argument("-o", "--out", "--output", dest="out",
                   help="write the plan here instead of stdout")
    s.add_argument("--url", default=DEFAULT_URL, help=f"LCM provider (default {DEFAULT_URL})")
    s.add_argument("--prefix", default=DEFAULT_PREFIX, help="channel prefix (default SVA_)")
    s.add_argument("--timeout", type=float, default=5.0, help="seconds to wait for the plan")
    s.add_argument("--revision", type=int, default=None,
                   help="fleet and mission revision (default: a fresh one from the clock)")

    c = sub.add_parser("scenario", help="publish a mission, then each event of a scenario; "
                       "record the node's replans")
    c.add_argument("scenario", help='{"mission": MISSION, "events": [EVENT, ...], '
                   '"change_penalty": N} (SPEC section 12.5)')
    c.add_argument("-o", "--out", "--output", dest="out",
                   help="write the record here instead of stdout")
    c.add_argument("--url", default=DEFAULT_URL, help=f"LCM provider (default {DEFAULT_URL})")
    c.add_argument("--prefix", default=DEFAULT_PREFIX, help="channel prefix (default SVA_)")
    c.add_argument("--timeout", type=float, default=5.0,
                   help="seconds to wait for each plan or replan")
    c.add_argument("--revision", type=int, default=None,
                   help="fleet and mission revision (default: a fresh one from the clock)")

    r = sub.add_parser("record", help="log LCM traffic with lcm-logger")
    r.add_argument("-o", "--out", "--output", dest="out", required=True,
                   help="log file to write")
    r.add_argument("--url", default=DEFAULT_URL)
    r.add_argument("--channels", default=".*", help="channel regex (default .*)")

    y = sub.add_parser("replay", help="play an LCM log with lcm-logplayer")
    y.add_argument("log", help="log file")
    y.add_argument("--url", default=DEFAULT_URL)
    y.add_argument("--speed", type=float, default=1.0, help="speed multiplier (default 1)")
    y.add_argument("--channels", default=None, help="channel regex to play")
    return p


def _send(args) -> int:
    import lcm  # the venv's lcm==1.5.3

    try:
        with open(args.mission, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        print(f"sva-tools lcm send: {shown(args.mission)}: {shown(e)}", file=sys.stderr)
        return 2
    rev = args.revision if args.revision is not None else time.time_ns() // 1000
    try:
        name, fleet, mission = wire.mission_messages(doc, rev, rev)
    except wire.InputError as e:
        print(f"sva-tools lcm send: {shown(args.mission)}: {shown(e)}", file=sys.stderr)
        return 2
    t = wire.types()
    lc = lcm.LCM(args.url)
    answer = []

    def on_plan(channel, data):
        try:
            p = t.plan_t.decode(data)
        except ValueError:
            return
        if p.fleet_revision == rev and p.mission_revision == rev:
            answer.append(p)

    sub = lc.subscribe(args.prefix.replace("\\", "\\\\") + "PLAN", on_plan)
    sub.set_queue_capacity(1000)
    lc.publish(args.prefix + "FLEET", fleet.encode())
    lc.publish(args.prefix + "MISSION", mission.encode())
    deadline = time.monotonic() + args.timeout
    while not answer:
        left = deadline - time.monotonic()
        if left <= 0:
            print(shown(f"sva-tools lcm send: no plan on {args.prefix}PLAN for revision {rev} "
                        f"within {args.timeout} s (is sva_node running on {args.url}?)"), file=sys.stderr)
            return 3
        lc.handle_timeout(max(1, int(left * 1000)))
    plan = answer[0]
    try:
        wire.check_version(plan, "plan_t")
    except wire.InputError as e:
        print(shown(f"sva-tools lcm send: {args.prefix}PLAN: {e}"), file=sys.stderr)
        return 1
    if plan.status not in (plan.STATUS_COMPLETE, plan.STATUS_PARTIAL):
        what = {plan.STATUS_REJECTED: "rejected the mission",
                plan.STATUS_FAILED: f"failed to plan (status {plan.error_code})",
                plan.STATUS_TOO_LARGE: "made a plan larger than MAX_ROUTE_ITEMS"}.get(
                    plan.status, f"answered status {plan.status}")
        detail = "" if plan.status == plan.STATUS_TOO_LARGE else ": " + wire.diag_text(plan)
        print(shown(f"sva-tools lcm send: the node {what}{detail}"), file=sys.stderr)
        return 1
    text = json.dumps(wire.plan_document(plan, name), indent=2) + "\n"
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


def _fail(msg: str, status: int) -> int:
    print(shown(f"sva-tools lcm scenario: {msg}"), file=sys.stderr)
    return status


def _scenario(args) -> int:
    """The mission (fleet and mission_t), then each event in order (seq = its index),
    each after the answer to the one before; the record holds the first plan and every
    replan as wire.replan_document gives it."""
    import lcm  # the venv's lcm==1.5.3

    try:
        with open(args.scenario, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        return _fail(f"{shown(args.scenario)}: {shown(e)}", 2)
    rev = args.revision if args.revision is not None else time.time_ns() // 1000
    try:
        if not isinstance(doc, dict):
            raise wire.InputError("scenario: must be an object")
        extra = sorted(set(doc) - {"mission", "events", "change_penalty"})
        if extra:
            raise wire.InputError(f"{extra[0]}: unknown key")
        if "mission" not in doc or not isinstance(doc.get("events"), list):
            raise wire.InputError("mission, events: a scenario needs a mission and a list of events")
        mission_doc = dict(doc["mission"]) if isinstance(doc["mission"], dict) else doc["mission"]
        penalty = doc.get("change_penalty")
        if isinstance(mission_doc, dict) and "change_penalty" in mission_doc:
            penalty = mission_doc.pop("change_penalty") if penalty is None else penalty
        if penalty is not None and (isinstance(penalty, bool) or not isinstance(penalty, int)):
            raise wire.InputError(f"change_penalty: must be an integer, got {penalty!r}")
        name, fleet, mission = wire.mission_messages(mission_doc, rev, rev)
        events = [wire.event_message(e, i, f"events[{i}].") for i, e in enumerate(doc["events"])]
    except wire.InputError as e:
        return _fail(f"{shown(args.scenario)}: {shown(e)}", 2)
    t = wire.types()
    lc = lcm.LCM(args.url)
    plans, replans = [], []

    def on_plan(channel, data):
        try:
            p = t.plan_t.decode(data)
        except ValueError:
            return
        if p.fleet_revision == rev and p.mission_revision == rev:
            plans.append(p)

    def on_replan(channel, data):
        try:
            r = t.replan_t.decode(data)
        except ValueError:
            return
        if r.plan.fleet_revision == rev and r.plan.mission_revision == rev:
            replans.append(r)

    prefix = args.prefix.replace("\\", "\\\\")
    lc.subscribe(prefix + "PLAN", on_plan).set_queue_capacity(1000)
    lc.subscribe(prefix + "REPLAN", on_replan).set_queue_capacity(1000)

    def wait(cond, what):
        deadline = time.monotonic() + args.timeout
        while not cond():
            left = deadline - time.monotonic()
            if left <= 0:
                print(shown(f"sva-tools lcm scenario: no {what} on {args.prefix} for revision "
                            f"{rev} within {args.timeout} s (is sva_node running on "
                            f"{args.url}?)"), file=sys.stderr)
                return False
            lc.handle_timeout(max(1, int(left * 1000)))
        return True

    lc.publish(args.prefix + "FLEET", fleet.encode())
    lc.publish(args.prefix + "MISSION", mission.encode())
    if not wait(lambda: plans, "plan"):
        return 3
    plan = plans[0]
    try:
        wire.check_version(plan, "plan_t")
    except wire.InputError as e:
        return _fail(f"{args.prefix}PLAN: {e}", 1)
    if plan.status not in (plan.STATUS_COMPLETE, plan.STATUS_PARTIAL):
        return _fail(f"the node did not plan the mission (status {plan.status}): "
                     f"{wire.diag_text(plan)}", 1)
    record: dict[str, Any] = {"mission": name, "plan": wire.plan_document(plan, name),
                              "replans": []}
    refused = 0
    for ev in events:
        lc.publish(args.prefix + "EVENT", ev.encode())
        if not wait(lambda seq=ev.seq: any(r.event_seq == seq for r in replans), f"replan of event {ev.seq}"):
            return 3
        r = next(r for r in replans if r.event_seq == ev.seq)
        try:
            answer = wire.replan_document(r, name)
        except wire.InputError as err:
            return _fail(f"{args.prefix}REPLAN: {err}", 1)
        if penalty is not None and r.change_penalty != penalty:
            return _fail(f"change_penalty: the scenario asks {penalty}, the node replans with "
                         f"{r.change_penalty} (start sva_node --change-penalty {penalty}; "
                         "mission_t does not carry it)", 2)
        if not answer["accepted"]:
            refused += 1
            print(shown(f"sva-tools lcm scenario: events[{ev.seq}] refused: {answer['error']}"),
                  file=sys.stderr)
        record["replans"].append(answer)
    text = json.dumps(record, indent=2) + "\n"
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 1 if refused else 0


def _run(argv: list[str]) -> int:
    """Runs an LCM program in the foreground. SIGINT and SIGTERM sent to this process
    are passed on to it (a signal sent to this process alone, not to its process group,
    must not leave lcm-logger running); it then ends as after a Ctrl-C: status 0."""
    import signal
    import subprocess

    try:
        proc = subprocess.Popen(argv)
    except OSError as e:
        print(f"sva-tools lcm: {shown(argv[0])}: {shown(e)}", file=sys.stderr)
        return 4
    stopped = []

    def forward(signum, frame):
        stopped.append(signum)
        proc.send_signal(signum)

    old = {s: signal.signal(s, forward) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        rc = proc.wait()
    finally:
        for s, h in old.items():
            signal.signal(s, h)
    if stopped:
        return 0
    return 4 if rc != 0 else 0


def main(argv: list[str]) -> int:
    try:
        args = _parser().parse_args(argv)
    except SystemExit as e:  # --help (0) or a usage error (2)
        return int(e.code or 0)
    if args.command == "send":
        return _send(args)
    if args.command == "scenario":
        return _scenario(args)
    if args.command == "record":
        return _run([wire.lcm_tool("lcm-logger"), "-f", "-q", "-c", args.channels,
                     "-l", args.url, args.out])
    cmd = [wire.lcm_tool("lcm-logplayer"), "-s", str(args.speed), "-l", args.url]
    if args.channels:
        cmd += ["-e", args.channels]
    return _run(cmd + [args.log])
