"""The record of a `sva-tools sitl` flight: what the vehicles, the node and the bridge
said, with every instant as ms since t0 on the vehicle clock. sitl.judge completes it
into the flight log (targets, visits, tracks, summary); the record alone can be judged
again (`judge.judge_log`).
"""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, cast

from .craft import tod_instant_ms

if TYPE_CHECKING:
    from .flight import Flight


def _ms(utc_ms: float | None, t0: int) -> int | None:
    return None if utc_ms is None else round(utc_ms - t0)


def _ms_key(key: str) -> str:
    """utc_ms -> at_ms, started_utc_ms -> started_ms."""
    return "at_ms" if key == "utc_ms" else key.replace("_utc_ms", "_ms")


def _times(row: dict[str, Any], t0: int) -> dict[str, Any]:
    return {_ms_key(k): _ms(v, t0) if k.endswith("utc_ms") else v for k, v in row.items()}


def _hold(h: dict[str, Any], t0: int) -> dict[str, Any]:
    out = {"seq": h["seq"], "ended_ms": _ms(h["ended_utc_ms"], t0),
           "until_ms": _ms(tod_instant_ms(h["until_tod_s"], h["ended_utc_ms"]), t0), "cut": h["cut"]}
    if h.get("wp") is not None:
        out["wp"] = [round(h["wp"][0], 7), round(h["wp"][1], 7)]
    return out


def _fault(f: dict[str, Any], t0: int) -> dict[str, Any]:
    out = _times(f, t0)
    if "acks" in f:
        out["acks"] = [_times(a, t0) for a in f["acks"]]
    return out


def record(fl: Flight) -> dict[str, Any]:
    """The flight's record (flight.Flight after fly())."""
    # t0 is known from Flight.start() on (the mission's, or chosen once the clocks agree)
    s, t0 = fl.s, cast(int, fl.t0_ms)
    scenario: dict[str, Any] = {"mission": s.mission.to_json(), "events": s.events}
    scenario["mission"]["frame"] = fl.frame_doc
    if s.penalty is not None:
        scenario["change_penalty"] = s.penalty
    uavs = []
    for c in fl.crafts:
        tel = [[round(a - t0), round(la, 7), round(lo, 7), round(al, 2)] for a, la, lo, al in c.telemetry
               if a >= t0 - fl.allowance_s * 1000]
        uavs.append({"id": c.id, "out": c.out, "telemetry": tel,
                     "holds": [_hold(h, t0) for h in c.holds if h["ended_utc_ms"] is not None],
                     "uploads": [_times(u, t0) for u in c.uploads],
                     "starts": [_times(a, t0) for a in c.starts],
                     "pauses": [_times(x, t0) for x in c.pauses],
                     "missions": [_times(m, t0) for m in c.missions],
                     "spells": c.spells,
                     "texts": [[_ms(a, t0), x] for a, x in c.texts]})
    return {
        "scenario": scenario, "algorithm": s.algo, "via": "sitl",
        "end_ms": _ms(fl.end_utc_ms, t0), "uavs": uavs,
        "replans": [_times(r, t0) for r in fl.replans],
        "sitl": {"frame": fl.frame_doc, "speedup": s.speedup,
                 "netns": os.environ.get("SVA_LCM_NETNS"),
                 "takeoff_allowance_s": fl.allowance_s,
                 "clock_spread_ms": None if fl.clock_spread_ms is None else round(fl.clock_spread_ms, 3),
                 "ended_by": fl.ended_by, "wall_s": round(fl.wall_s, 1),
                 "reports": fl.ground.reports if fl.ground is not None else 0,
                 "events": [_times({k: v for k, v in e.items() if k not in ("host", "event")}, t0)
                            for e in fl.flown_events],
                 "faults": [_fault(f, t0) for f in fl.fault_log],
                 "bridge": {"command": fl.bridge_cmd,
                            "lines": [[_ms(a, t0), x] for a, x in fl.bridge_log]}},
    }
