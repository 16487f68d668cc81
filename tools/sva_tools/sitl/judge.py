"""What a `sva-tools sitl` flight achieved, judged from the vehicles' own telemetry: a
flight's record (sitl.record) completed into its flight log (the `sva-tools sim` log's
keys, docs/live.md: targets, per UAV track and visits, summary; plus the holds judged
and each loss's latencies). A stored log can be judged again (judge_log).

Presence: a vehicle is at a target while its horizontal distance to the target's WGS84
point (the cell's point of the frame) is at most the coverage radius,
max(cell_m / 2, 5 m); the instants it enters and leaves are interpolated between
telemetry samples (GLOBAL_POSITION_INT, every 200 ms of vehicle time) on the distance.
A target is covered when it was neither cancelled nor lost and at least `need`
vehicles were present from its window's start to its end ([t0 + start * tick_s,
t0 + end * tick_s) on each vehicle's GPS clock). A target is promised when the plan in
force at its window's start (the last plan or replan at or before that tick that had it
in its residual mission) routes UAVs to it. The visit of a UAV sent to a target is its
stay there that overlaps the window most; its arrival slack is the window's start minus
the arrival (negative: late); a UAV sent there that never stood in the window missed it
(counted late, unless it was out of service at the window's start). A stay of another
UAV over at least half a window is listed too. A target is lost when a vehicle present
there was lost while its window was open.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import frame
from ..lcm.simnode import percentile

MIN_RADIUS_M = 5.0
MAX_GAP_MS = 1500          # telemetry gap (vehicle ms) that breaks a stay


def radius_m(cell_m: float) -> float:
    return max(cell_m / 2.0, MIN_RADIUS_M)


def enu(geo: frame.Frame, lat: np.ndarray, lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """East and north of positions in the frame's tangent plane (Frame.geodetic_to_enu,
    on arrays)."""
    import pymap3d

    e0, n0, u0 = pymap3d.geodetic2enu(lat, lon, 0.0, geo.lat, geo.lon, 0.0)
    e1, n1, u1 = pymap3d.geodetic2enu(lat, lon, 1.0, geo.lat, geo.lon, 0.0)
    h = -np.asarray(u0) / (np.asarray(u1) - np.asarray(u0))
    return np.asarray(e0) + h * (np.asarray(e1) - np.asarray(e0)), \
        np.asarray(n0) + h * (np.asarray(n1) - np.asarray(n0))


def final_targets(scenario_targets: list[dict[str, Any]], events: list[dict[str, Any]]
                  ) -> tuple[dict[int, dict[str, Any]], dict[int, int], list[int]]:
    """Every target as it finally stood, the tick each cancelled one was cancelled at,
    and the ids in order of appearance."""
    out = {t["id"]: dict(t) for t in scenario_targets}
    order = [t["id"] for t in scenario_targets]
    cancelled: dict[int, int] = {}
    for e in events:
        if e["type"] in ("target_added", "target_changed"):
            t = e["target"]
            if t["id"] not in out:
                order.append(t["id"])
            out[t["id"]] = dict(t)
        elif e["type"] == "target_cancelled":
            tid = e["target"]["id"] if isinstance(e["target"], dict) else e["target"]
            cancelled.setdefault(tid, e["at"])
    return out, cancelled, order


class Track:
    """One UAV's telemetry in the frame: t (ms since t0), east, north (m), alt (m)."""

    def __init__(self, geo: frame.Frame, telemetry: list[list[float]]):
        a = np.array(telemetry, dtype=float).reshape(-1, 4)
        a = a[np.argsort(a[:, 0], kind="stable")] if len(a) else a
        self.t = a[:, 0]
        self.lat, self.lon, self.alt = a[:, 1], a[:, 2], a[:, 3]
        if len(a):
            self.e, self.n = enu(geo, self.lat, self.lon)
        else:
            self.e = self.n = np.zeros(0)

    def stays(self, x_m: float, y_m: float, r: float) -> list[tuple[float, float]]:
        """(enter, leave) ms of every stay within r of (x_m, y_m), interpolated."""
        if len(self.t) == 0:
            return []
        d = np.hypot(self.e - x_m, self.n - y_m)
        inside = d <= r
        out: list[tuple[float, float]] = []
        k, n = 0, len(d)
        while k < n:
            if not inside[k]:
                k += 1
                continue
            j = k
            while j + 1 < n and inside[j + 1] and self.t[j + 1] - self.t[j] <= MAX_GAP_MS:
                j += 1
            enter = self._cross(k - 1, k, d, r) if k > 0 and self.t[k] - self.t[k - 1] <= MAX_GAP_MS \
                else float(self.t[k])
            leave = self._cross(j, j + 1, d, r) if j + 1 < n and self.t[j + 1] - self.t[j] <= MAX_GAP_MS \
                else float(self.t[j])
            out.append((enter, leave))
            k = j + 1
        return out

    def _cross(self, a: int, b: int, d: np.ndarray, r: float) -> float:
        da, db = float(d[a]), float(d[b])
        if da == db:
            return float(self.t[b])
        f = min(1.0, max(0.0, (r - da) / (db - da)))
        return float(self.t[a] + f * (self.t[b] - self.t[a]))

    def cell_at(self, t_ms: float, cell_m: float) -> tuple[int, int] | None:
        if len(self.t) == 0:
            return None
        k = int(np.searchsorted(self.t, t_ms))
        best = min((i for i in (k - 1, k) if 0 <= i < len(self.t)), key=lambda i: abs(self.t[i] - t_ms))
        if abs(self.t[best] - t_ms) > MAX_GAP_MS:
            return None
        return _snap(self.e[best] / cell_m), _snap(self.n[best] / cell_m)


def _snap(v: float) -> int:
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def _promised(replans: list[dict[str, Any]], tid: int, start: int) -> list[int] | None:
    """UAVs the plan in force at tick `start` sends to target tid (None: no plan had it)."""
    chosen = None
    for r in replans:
        if r["at"] > start:
            break
        ids = {t["id"] for t in r["mission"].get("targets", [])}
        if tid in ids:
            chosen = r
    if chosen is None:
        return None
    return [rt["uav"] for rt in chosen["plan"].get("routes", []) if tid in rt["targets"]]


def _targets(log: dict[str, Any], tracks: dict[int, Track], geo: frame.Frame, r: float
             ) -> dict[str, Any]:
    """Every target's outcome and every visit (see the module docstring)."""
    tick_ms = geo.tick_ms
    sc = log["scenario"]
    targets, cancelled, order = final_targets(sc["mission"]["targets"], sc["events"])
    replans = sorted(log["replans"], key=lambda x: x["at"])
    losses = [(e["uav"], e["at"]) for e in sc["events"] if e["type"] == "uav_lost"]
    spells_out = {u["id"]: u["out"] for u in log["uavs"]}

    def out_at(uid: int, tick: int) -> bool:
        """Out of service at that tick (a UAV lost before a window it was sent to did not
        miss it: the loss did)."""
        return any(lost <= tick and (back is None or tick < back) for lost, back in spells_out.get(uid, []))

    visits: dict[int, list[dict[str, Any]]] = {uid: [] for uid in tracks}
    tout = []
    slack: list[float] = []
    late = 0
    missed: list[list[int]] = []   # (uav, target) sent there that never stood in its window
    for tid in order:
        t = targets[tid]
        ws, we = t["start"] * tick_ms, t["end"] * tick_ms
        x_m, y_m = t["x"] * geo.cell_m, t["y"] * geo.cell_m
        promised = _promised(replans, tid, t["start"])
        served = []
        present_at: dict[int, list[tuple[float, float]]] = {}
        for uid, tr in tracks.items():
            st = tr.stays(x_m, y_m, r)
            present_at[uid] = st
            if any(a <= ws and b >= we for a, b in st):
                served.append(uid)
            sent = promised is not None and uid in promised and tid not in cancelled
            overlaps = [(min(b, we) - max(a, ws), a, b) for a, b in st]
            if sent:
                # its visit: the stay that overlaps the window most (none: it never came)
                best = max(overlaps, default=None)
                chosen = [best[1:]] if best is not None and best[0] > 0 else []
                if not chosen and not out_at(uid, t["start"]):
                    missed.append([uid, tid])
                    late += 1
            else:
                chosen = [(a, b) for ov, a, b in overlaps if ov >= (we - ws) / 2]
            for a, b in chosen:
                visits[uid].append({"target": tid, "arrived": round(a / tick_ms, 3),
                                    "left": round(b / tick_ms, 3), "arrived_ms": round(a),
                                    "left_ms": round(b), "slack_s": round((ws - a) / 1000.0, 3),
                                    "sent": sent})
                if sent:
                    slack.append((ws - a) / 1000.0)
                    late += 1 if a > ws else 0
        # lost: a UAV present there when it was lost, inside the window (its last sample
        # may precede the kill by up to a telemetry gap)
        lost = any(t["start"] <= at < t["end"] and
                   any(a <= at * tick_ms <= b + MAX_GAP_MS for a, b in present_at.get(u, []))
                   for u, at in losses)
        if tid in cancelled:
            outcome = "cancelled"
        elif lost and len(served) < t["need"]:
            outcome = "lost"
        else:
            outcome = "covered" if len(served) >= t["need"] else "uncovered"
        tout.append({"id": tid, "covered": outcome == "covered", "served_by": served,
                     "outcome": outcome, "need": t["need"],
                     "promised": bool(promised) and tid not in cancelled,
                     "sent": promised or []})
    for vs in visits.values():
        vs.sort(key=lambda v: v["arrived_ms"])
    return {"targets": tout, "visits": visits, "slack": slack, "late": late, "missed": missed,
            "by_id": targets}


def _holds(holds: list[dict[str, Any]], geo: frame.Frame, targets: dict[int, dict[str, Any]]
           ) -> list[dict[str, Any]]:
    """A UAV's holds (NAV_DELAY items it ended), each with its target, the window's end
    and the error of the hold's end against it (ms, vehicle clock); `cut` holds are those
    the operator ended early by starting a new mission (the replan sent the UAV elsewhere
    before that window began)."""
    out = []
    for h in holds:
        row = {k: v for k, v in h.items() if k not in ("target", "window_end_ms", "error_ms")}
        wp = h.get("wp")
        if wp is not None and h.get("until_ms") is not None:
            cell = geo.geodetic_to_cell(*wp)
            cands = [t for t in targets.values() if (t["x"], t["y"]) == cell]
            if cands:
                tg = min(cands, key=lambda t: abs(t["end"] * geo.tick_ms - h["until_ms"]))
                row["target"] = tg["id"]
                row["window_end_ms"] = tg["end"] * geo.tick_ms
                row["error_ms"] = h["ended_ms"] - tg["end"] * geo.tick_ms
        out.append(row)
    return out


def _losses(log: dict[str, Any]) -> list[dict[str, Any]]:
    """Per uav_lost event: vehicle ms from the kill to the node's replan of the loss and
    to the last of the bridge's uploads that followed it (and the UAVs uploaded to)."""
    out = []
    replans = [x for x in log["replans"] if x.get("at_ms") is not None]
    for ev in log["sitl"]["events"]:
        if ev["type"] != "uav_lost" or "skipped" in ev or ev.get("at_ms") is None:
            continue
        uav, kill = ev.get("uav"), ev["at_ms"]
        rp = next((x for x in replans if x["cause"] == "report:uav_lost" and x["at_ms"] >= kill
                   and uav not in {u["id"] for u in x["mission"]["uavs"]}), None)
        row = {"uav": uav, "at": ev["at"], "replan_ms": None, "upload_ms": None, "uploaded_to": [],
               "dropped": None}
        if rp is not None:
            row["replan_ms"] = rp["at_ms"] - kill
            row["replan_at"] = rp["at"]
            row["dropped"] = rp["changes"]["dropped"]
            # the uploads of the replan's own plan (the bridge's lines name it, at whatever
            # instant they were read); without plan ids, those between it and the next replan
            pid = ((rp.get("plan") or {}).get("stats") or {}).get("plan_id")
            nxt = next((x["at_ms"] for x in replans if x["at_ms"] > rp["at_ms"]), None)
            ups = [(u["at_ms"], v["id"]) for v in log["uavs"] for u in v["uploads"]
                   if u.get("items") is not None and u["at_ms"] is not None
                   and (str(u.get("plan")) == str(pid) if pid is not None
                        else (rp["at_ms"] <= u["at_ms"] and (nxt is None or u["at_ms"] <= nxt)))]
            if ups:
                row["upload_ms"] = max(a for a, _ in ups) - kill
                row["uploaded_to"] = sorted({u for _a, u in ups})
        out.append(row)
    return out


def judge_log(log: dict[str, Any]) -> dict[str, Any]:
    """The flight log of a record (or of a flight log: judged again): targets, each UAV's
    track, visits and holds, the losses' latencies and the summary."""
    geo = frame.Frame.from_json(log["sitl"]["frame"])
    tick_ms = geo.tick_ms
    r = radius_m(geo.cell_m)
    tracks = {u["id"]: Track(geo, u["telemetry"]) for u in log["uavs"]}
    j = _targets(log, tracks, geo, r)
    last = [u["telemetry"][-1][0] for u in log["uavs"] if u["telemetry"]]
    end_ms = log["end_ms"] if log.get("end_ms") is not None else max(last + [0])
    end_tick = int(math.ceil(end_ms / tick_ms))
    uavs, distance, hold_err = [], 0, []
    for u in log["uavs"]:
        tr = tracks[u["id"]]
        track, prev = [], None
        for k in range(0, end_tick + 1):
            cell = tr.cell_at(k * tick_ms, geo.cell_m)
            if cell is None:
                prev = None
                continue
            if prev is not None:
                distance += abs(cell[0] - prev[0]) + abs(cell[1] - prev[1])
            track.append([k, cell[0], cell[1], None])
            prev = cell
        holds = _holds(u["holds"], geo, j["by_id"])
        hold_err += [abs(h["error_ms"]) for h in holds if "error_ms" in h and not h.get("cut")]
        uavs.append(dict(u, track=track, visits=j["visits"][u["id"]], holds=holds))
    slack = j["slack"]
    targets = j["targets"]
    summary = {"covered": sum(1 for x in targets if x["covered"]),
               "coverable": sum(1 for x in targets if x["outcome"] not in ("cancelled", "lost")),
               "targets": len(targets), "distance": distance, "replans": len(log["replans"]),
               "changes": sum(int(x["changes"].get("count", 0)) for x in log["replans"]),
               "promised": sum(1 for x in targets if x["promised"] and x["outcome"] != "lost"),
               "visits": len(slack), "late_arrivals": j["late"], "missed_visits": j["missed"],
               "slack_p50_s": _r(percentile(slack, 50)), "slack_p1_s": _r(percentile(slack, 1)),
               "hold_error_max_ms": max(hold_err) if hold_err else None}
    out = dict(log, end_tick=end_tick, uavs=uavs, targets=targets, summary=summary)
    out["sitl"] = dict(log["sitl"], radius_m=r, losses=_losses(log))
    return out


def _r(v: float | None) -> float | None:
    return None if v is None else round(float(v), 3)


def end_line(log: dict[str, Any]) -> str:
    s = log["summary"]
    p50 = "-" if s["slack_p50_s"] is None else f"{s['slack_p50_s']:.1f}"
    p1 = "-" if s["slack_p1_s"] is None else f"{s['slack_p1_s']:.1f}"
    return (f"covered {s['covered']} of {s['coverable']} coverable (plan promised {s['promised']}); "
            f"arrival slack p50 {p50} s, p1 {p1} s; late arrivals {s['late_arrivals']}")
