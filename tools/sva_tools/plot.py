"""Drawings of a mission and its plan (`sva-tools plot`)."""
from __future__ import annotations

from types import ModuleType
from typing import Any

from . import model


def pyplot() -> ModuleType:
    """matplotlib.pyplot on the file-only Agg backend."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def draw_depot(ax: Any, depot: tuple[int, int]) -> None:
    ax.plot(*depot, marker="s", color="black", markersize=12, zorder=5)
    ax.annotate("depot", depot, textcoords="offset points", xytext=(6, -12), fontsize=9)


def draw_target(ax: Any, t: model.Target, colour: str) -> None:
    """A target on the map: a circle in `colour`, labelled "T<id> n<need> [start,end]"."""
    ax.plot(t.x, t.y, "o", color=colour, markersize=10, zorder=4, alpha=0.8)
    ax.annotate(f"T{t.id} n{t.need} [{t.start},{t.end}]", (t.x, t.y),
                textcoords="offset points", xytext=(6, 6), fontsize=8)


def render(m: model.Mission, p: model.Plan, path: str) -> None:
    plt = pyplot()

    tmap = m.target_by_id()
    served = {t.id: 0 for t in m.targets}
    for r in p.routes:
        for tid in r.targets:
            if tid in served:
                served[tid] += 1
    cmap = plt.get_cmap("tab10" if len(m.uavs) <= 10 else "tab20")
    fig, (ax, gx) = plt.subplots(1, 2, figsize=(16, 7), gridspec_kw={"width_ratios": [1, 1.4]})

    # --- map
    draw_depot(ax, m.depot)
    for t in m.targets:
        draw_target(ax, t, "tab:green" if served[t.id] == t.need else "tab:red")
    for i, r in enumerate(p.routes):
        u = next((x for x in m.uavs if x.id == r.uav), None)
        if u is None:
            continue
        ax.plot(u.x, u.y, "^", color=cmap(i % cmap.N), markersize=9, zorder=6)
        if not r.targets:
            continue
        pts = [(u.x, u.y)] + [(tmap[t].x, tmap[t].y) for t in r.targets if t in tmap] + [m.depot]
        # Manhattan legs drawn as an L (x first, then y), offset per UAV so they stay apart.
        off = (i - len(p.routes) / 2) * 0.08
        xs, ys = [], []
        for (ax0, ay0), (bx, by) in zip(pts, pts[1:]):
            xs += [ax0 + off, bx + off, bx + off]
            ys += [ay0 + off, ay0 + off, by + off]
        ax.plot(xs, ys, "-", color=cmap(i % cmap.N), linewidth=1.6, alpha=0.85,
                label=f"UAV {r.uav}: {len(r.targets)} targets, {r.distance} cells")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("x (cells)")
    ax.set_ylabel("y (cells)")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"{m.name}: {p.algorithm}, {p.status}, covered {p.covered}/{len(m.targets)}, "
                 f"cost {p.cost}")

    # --- Gantt
    ts = model.sorted_targets(m)
    rows = []
    for t in ts:
        rows.append(f"T{t.id} (n{t.need})")
    for r in p.routes:
        rows.append(f"UAV {r.uav}" + (" stranded" if r.uav in p.stranded else ""))
    for k, t in enumerate(ts):
        ok = served[t.id] == t.need
        gx.broken_barh([(t.start, t.end - t.start)], (k - 0.35, 0.7),
                       color="tab:green" if ok else "tab:red", alpha=0.35)
    base = len(ts)
    for i, r in enumerate(p.routes):
        u = next((x for x in m.uavs if x.id == r.uav), None)
        if u is None:
            continue
        y = base + i
        col = cmap(i % cmap.N)
        clock, pos = u.ready_at, (u.x, u.y)
        for tid in r.targets:
            tt = tmap.get(tid)
            if tt is None:
                continue
            t = tt
            fly = model.dist_pt(pos, t) * m.ticks_per_cell
            gx.broken_barh([(clock, fly)], (y - 0.15, 0.3), color=col, alpha=0.5)
            if clock + fly < t.start:
                gx.broken_barh([(clock + fly, t.start - clock - fly)], (y - 0.25, 0.5),
                               facecolor="none", edgecolor=col, hatch="///", linewidth=0.5)
            gx.broken_barh([(t.start, t.end - t.start)], (y - 0.35, 0.7), color=col)
            gx.text((t.start + t.end) / 2, y, f"T{t.id}", ha="center", va="center", fontsize=7,
                    color="white")
            clock, pos = t.end, (t.x, t.y)
        if r.targets or pos != m.depot:
            home = model.dist_pt(pos, m.depot) * m.ticks_per_cell
            gx.broken_barh([(clock, home)], (y - 0.15, 0.3), color=col, alpha=0.5)
    gx.set_yticks(range(len(rows)))
    gx.set_yticklabels(rows, fontsize=8)
    gx.invert_yaxis()
    gx.axhline(base - 0.5, color="gray", linewidth=0.8)
    gx.set_xlabel("time (ticks)")
    gx.grid(True, axis="x", alpha=0.3)
    gx.set_title("windows (green covered, red not) and UAV time lines (thin: flying, "
                 "hatched: waiting, solid: serving)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
