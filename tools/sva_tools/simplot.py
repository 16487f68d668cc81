"""The picture of a flight log (`sva-tools sim --plot FILE.png`).

Left: the map, with the depot, every target coloured by its outcome (green covered, red
uncovered, grey cancelled, purple lost; the label shows its final window) and every
UAV's track as flown (one colour per UAV; a cross where it was lost, a triangle where it
came back). Right: a Gantt chart: one row per target window (coloured by outcome), one
row per UAV (solid: visits, grey hatched: out of service), dashed lines at each tick
with events and a replan marker row on top (labelled with its cause).
"""
from __future__ import annotations

from typing import Any

from . import model, plot

OUTCOME_COLOUR = {"covered": "tab:green", "uncovered": "tab:red", "cancelled": "tab:gray",
                  "lost": "tab:purple"}


def final_targets(log: dict[str, Any]) -> dict[int, model.Target]:
    """Every target of the scenario as it finally stood (added and changed ones too)."""
    sc = log["scenario"]
    out = {}
    for t in sc["mission"]["targets"]:
        out[t["id"]] = model.Target(t["id"], t["x"], t["y"], t["start"], t["end"], t["need"])
    for e in sc["events"]:
        if e["type"] in ("target_added", "target_changed"):
            t = e["target"]
            out[t["id"]] = model.Target(t["id"], t["x"], t["y"], t["start"], t["end"], t["need"])
    return out


def render_flight(log: dict[str, Any], path: str) -> None:
    plt = plot.pyplot()
    sc = log["scenario"]
    mission = sc["mission"]
    depot = (mission["depot"]["x"], mission["depot"]["y"])
    tmap = final_targets(log)
    outcome = {t["id"]: t.get("outcome", "covered" if t["covered"] else "uncovered")
               for t in log["targets"]}
    uavs = log["uavs"]
    cmap = plt.get_cmap("tab10" if len(uavs) <= 10 else "tab20")
    rows_n = len(tmap) + len(uavs) + 1
    fig, (ax, gx) = plt.subplots(1, 2, figsize=(17, max(7.5, 0.28 * rows_n)),
                                 gridspec_kw={"width_ratios": [1, 1.5]})

    # --- map
    plot.draw_depot(ax, depot)
    for tid, t in tmap.items():
        plot.draw_target(ax, t, OUTCOME_COLOUR[outcome.get(tid, "uncovered")])
    for i, u in enumerate(uavs):
        col = cmap(i % cmap.N)
        off = (i - len(uavs) / 2) * 0.06
        # One line per stretch in service (a loss breaks the track).
        seg: list[tuple[float, float]] = []
        segs = [seg]
        last = None
        for t, x, y, _f in u["track"]:
            if last is not None and t != last + 1:
                seg = []
                segs.append(seg)
            seg.append((x + off, y + off))
            last = t
        for k, s in enumerate(segs):
            if s:
                ax.plot([p[0] for p in s], [p[1] for p in s], "-", color=col, linewidth=1.5,
                        alpha=0.85, label=f"UAV {u['id']}" if k == 0 else None)
                if k > 0:
                    ax.plot(*s[0], "^", color=col, markersize=9, zorder=6)
                if k < len(segs) - 1 or any(b is None for _l, b in u["out"][-1:]):
                    ax.plot(*s[-1], "x", color=col, markersize=10, mew=2.5, zorder=6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("x (cells)")
    ax.set_ylabel("y (cells)")
    ax.legend(fontsize=7, loc="best")
    s = log["summary"]
    ax.set_title(f"{mission['name']}: {log['algorithm']}, covered {s['covered']}/"
                 f"{s['coverable']} coverable, {s['distance']} cells, {s['replans']} replans")

    # --- Gantt
    ts = sorted(tmap.values(), key=lambda t: (t.start, t.end, t.id))
    rows = [f"T{t.id} (n{t.need})" for t in ts] + [f"UAV {u['id']}" for u in uavs]
    for k, t in enumerate(ts):
        gx.broken_barh([(t.start, t.end - t.start)], (k - 0.35, 0.7),
                       color=OUTCOME_COLOUR[outcome.get(t.id, "uncovered")], alpha=0.4)
    base = len(ts)
    end = log["end_tick"]
    for i, u in enumerate(uavs):
        y = base + i
        col = cmap(i % cmap.N)
        for v in u["visits"]:
            left = v["left"] if v["left"] is not None else end
            a = tmap[v["target"]].start if v["target"] in tmap else v["arrived"]
            gx.broken_barh([(a, max(left - a, 0.5))], (y - 0.35, 0.7), color=col)
            gx.text((a + left) / 2, y, f"T{v['target']}", ha="center", va="center",
                    fontsize=7, color="white")
        for lost, back in u["out"]:
            stop = back if back is not None else end
            gx.broken_barh([(lost, max(stop - lost, 0.5))], (y - 0.25, 0.5), facecolor="none",
                           edgecolor="gray", hatch="xx", linewidth=0.5)
    for r in log["replans"]:
        gx.axvline(r["at"], color="gray", linestyle="--", linewidth=0.7, alpha=0.6)
        gx.plot(r["at"], -1, "v", color="black", markersize=6)
        gx.annotate(r["cause"], (r["at"], -1), textcoords="offset points", xytext=(2, 4),
                    fontsize=6, rotation=30)
    gx.set_yticks([-1] + list(range(len(rows))))
    gx.set_yticklabels(["replans"] + rows, fontsize=8)
    gx.invert_yaxis()
    gx.axhline(base - 0.5, color="gray", linewidth=0.8)
    gx.set_xlabel("time (ticks)")
    gx.grid(True, axis="x", alpha=0.3)
    gx.set_title("windows by outcome (green covered, red not, grey cancelled, purple lost); "
                 "visits solid, out of service hatched", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
