"""The picture of a SITL flight (`sva-tools sitl --plot PNG`).

Left: the map in cells of the frame: every target (coloured by outcome, as
`sva-tools sim --plot`: green covered, red uncovered, grey cancelled, purple lost) with
its coverage radius, the take-off plan's routes (dashed), later replans' routes
(dotted) and the tracks flown (solid, from telemetry; a cross where a vehicle was lost,
a triangle where it came back). Right: windows and visits on the vehicle clock (ticks).
"""
from __future__ import annotations

from typing import Any

import numpy as np

from .. import frame, plot
from ..simplot import OUTCOME_COLOUR
from . import judge


def _route_points(mission: dict[str, Any], plan: dict[str, Any], uav: int
                  ) -> list[tuple[int, int]]:
    u = next((x for x in mission["uavs"] if x["id"] == uav), None)
    if u is None:
        return []
    by_id = {t["id"]: t for t in mission["targets"]}
    pts = [(u["x"], u["y"])]
    route: list[int] = next((r["targets"] for r in plan.get("routes", []) if r["uav"] == uav), [])
    pts += [(by_id[t]["x"], by_id[t]["y"]) for t in route if t in by_id]
    pts.append((mission["depot"]["x"], mission["depot"]["y"]))
    return pts


def render(log: dict[str, Any], path: str) -> None:
    plt = plot.pyplot()
    sc = log["scenario"]
    mission = sc["mission"]
    geo = frame.Frame.from_json(log["sitl"]["frame"])
    r_cells = log["sitl"]["radius_m"] / geo.cell_m
    targets, _cancelled, order = judge.final_targets(mission["targets"], sc["events"])
    outcome = {t["id"]: t["outcome"] for t in log["targets"]}
    uavs = log["uavs"]
    cmap = plt.get_cmap("tab10" if len(uavs) <= 10 else "tab20")
    colour = {u["id"]: cmap(i % cmap.N) for i, u in enumerate(uavs)}
    fig, (ax, gx) = plt.subplots(1, 2, figsize=(17, max(7.5, 0.3 * (len(order) + len(uavs)))),
                                 gridspec_kw={"width_ratios": [1, 1.4]})
    depot = (mission["depot"]["x"], mission["depot"]["y"])
    plot.draw_depot(ax, depot)
    for tid in order:
        t = targets[tid]
        col = OUTCOME_COLOUR.get(outcome.get(tid, "uncovered"), "tab:red")
        ax.add_patch(plt.Circle((t["x"], t["y"]), r_cells, color=col, alpha=0.15))
        ax.plot(t["x"], t["y"], "s", color=col, markersize=8)
        ax.annotate(f"T{tid} [{t['start']},{t['end']}) n{t['need']}", (t["x"], t["y"]),
                    textcoords="offset points", xytext=(5, 5), fontsize=7)
    for k, rp in enumerate(log["replans"]):
        for u in uavs:
            pts = _route_points(rp["mission"], rp["plan"], u["id"])
            if len(pts) > 1 and any(p != pts[0] for p in pts):
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "--" if k == 0 else ":",
                        color=colour[u["id"]], linewidth=1.0, alpha=0.6 if k == 0 else 0.35)
    for u in uavs:
        tel = u["telemetry"]
        if not tel:
            continue
        a = np.array(tel, dtype=float)
        e, n = judge.enu(geo, a[:, 1], a[:, 2])
        x, y = e / geo.cell_m, n / geo.cell_m
        # one line per spell (a gap of more than a few seconds breaks it)
        cuts = [int(c) for c in np.nonzero(np.diff(a[:, 0]) > 5000)[0] + 1]
        for k, (s0, s1) in enumerate(zip([0] + cuts, cuts + [len(a)])):
            ax.plot(x[s0:s1], y[s0:s1], "-", color=colour[u["id"]], linewidth=1.6,
                    label=f"UAV {u['id']}" if k == 0 else None)
            if k > 0:
                ax.plot(x[s0], y[s0], "^", color=colour[u["id"]], markersize=9, zorder=6)
            if k < len(cuts) or (u["out"] and u["out"][-1][1] is None):
                ax.plot(x[s1 - 1], y[s1 - 1], "x", color=colour[u["id"]], markersize=10, mew=2.5,
                        zorder=6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel(f"east (cells of {geo.cell_m:g} m)")
    ax.set_ylabel(f"north (cells of {geo.cell_m:g} m)")
    ax.legend(fontsize=7, loc="best")
    s = log["summary"]
    ax.set_title(f"{mission['name']} in SITL: {log['algorithm']}, covered {s['covered']}/"
                 f"{s['coverable']} coverable (promised {s['promised']}), late {s['late_arrivals']}")

    ts = sorted((targets[t] for t in order), key=lambda t: (t["start"], t["end"], t["id"]))
    rows = [f"T{t['id']} (n{t['need']})" for t in ts] + [f"UAV {u['id']}" for u in uavs]
    for k, t in enumerate(ts):
        gx.broken_barh([(t["start"], t["end"] - t["start"])], (k - 0.35, 0.7),
                       color=OUTCOME_COLOUR.get(outcome.get(t["id"], "uncovered"), "tab:red"), alpha=0.4)
    base = len(ts)
    for i, u in enumerate(uavs):
        row = base + i
        for v in u["visits"]:
            gx.broken_barh([(v["arrived"], max(v["left"] - v["arrived"], 0.2))], (row - 0.35, 0.7),
                           color=colour[u["id"]])
            gx.text((v["arrived"] + v["left"]) / 2, row, f"T{v['target']}", ha="center", va="center",
                    fontsize=7, color="white")
        for lost, back in u["out"]:
            stop = back if back is not None else log["end_tick"]
            gx.broken_barh([(lost, max(stop - lost, 0.5))], (row - 0.25, 0.5), facecolor="none",
                           edgecolor="gray", hatch="xx", linewidth=0.5)
    for rp in log["replans"]:
        gx.axvline(rp["at"], color="gray", linestyle="--", linewidth=0.6, alpha=0.5)
    gx.set_yticks(list(range(len(rows))))
    gx.set_yticklabels(rows, fontsize=8)
    gx.invert_yaxis()
    gx.axhline(base - 0.5, color="gray", linewidth=0.8)
    gx.set_xlabel(f"vehicle clock (ticks of {geo.tick_ms / 1000:g} s since t0)")
    gx.grid(True, axis="x", alpha=0.3)
    gx.set_title("windows by outcome; stays within the coverage radius (solid); out of service "
                 "hatched; replans dashed", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
