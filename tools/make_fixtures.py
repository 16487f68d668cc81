#!/usr/bin/env python3
"""Writes the random missions of fixtures/missions/ (rand_*.json), reproducibly.

Standard library only. Every mission comes from its own seeded random.Random, so
running the script again rewrites byte-identical files:

    python3 tools/make_fixtures.py [OUTPUT_DIR]     (default: fixtures/missions)

Parameters (the paper's random set, section 5: 20x20 grid, 5 UAVs):
    coordinates     x, y uniform in [0, 20]; depot (0, 0)
    window width    uniform in [10, 20] ticks
    window start    uniform in [first_start, first_start + spread] ticks, where
                    first_start = 30 * ticks_per_cell: most targets can be reached
                    from the depot by their start, while the few more than 30 cells
                    away cannot when they open early (they stay uncovered)
    need            1 or 2 (uniform)
    hover_fuel      2 fuel units per served window
    fuel            "generous": 400 per UAV (never binds);
                    "tight": 70 per UAV (binds: fewer targets covered than with 400)
Variants:
    ticks_per_cell  2 in rand_10_2 (travel takes twice as long; starts scaled)
    replan          rand_7_2 is a mid-mission fleet state: UAVs at random cells with
                    ready_at in [1, 10] and fuel 60..120, plus one UAV whose fuel
                    cannot bring it home (it must be reported as stranded)
"""
import json
import os
import random
import sys

GRID = 20
UAVS = 5

# name: (seed, targets, spread of window starts, fuel, ticks_per_cell, replan)
MISSIONS = {
    "rand_7_1": (701, 7, 100, "generous", 1, False),
    "rand_7_2": (702, 7, 100, "generous", 1, True),
    "rand_10_1": (1001, 10, 160, "generous", 1, False),
    "rand_10_2": (1002, 10, 160, "tight", 2, False),
    "rand_25_1": (2501, 25, 400, "generous", 1, False),
    "rand_25_2": (2502, 25, 400, "tight", 1, False),
}
FUEL = {"generous": 400, "tight": 70}


def make(name, seed, n_targets, spread, fuel, ticks_per_cell, replan):
    rng = random.Random(seed)
    first_start = 30 * ticks_per_cell
    targets = []
    for i in range(n_targets):
        start = rng.randint(first_start, first_start + spread * ticks_per_cell)
        width = rng.randint(10, 20)
        targets.append({
            "id": i + 1,
            "x": rng.randint(0, GRID),
            "y": rng.randint(0, GRID),
            "start": start,
            "end": start + width,
            "need": rng.randint(1, 2),
        })
    uavs = []
    for i in range(UAVS):
        uav = {"id": i + 1, "x": 0, "y": 0, "fuel": FUEL[fuel], "ready_at": 0}
        if replan:
            uav["x"] = rng.randint(0, GRID)
            uav["y"] = rng.randint(0, GRID)
            uav["ready_at"] = rng.randint(1, 10)
            uav["fuel"] = rng.randint(60, 120)
        uavs.append(uav)
    if replan:
        # The last UAV is far out with too little fuel to come home: stranded (SPEC 1).
        far = uavs[-1]
        far["x"], far["y"] = GRID, GRID
        far["fuel"] = 2 * GRID - 5
    return {
        "name": name,
        "depot": {"x": 0, "y": 0},
        "ticks_per_cell": ticks_per_cell,
        "hover_fuel": 2,
        "overlap_percent": 70,
        "uavs": uavs,
        "targets": targets,
    }


def dump(mission):
    """JSON with one UAV or target per line (readable diffs)."""
    lines = ["{"]
    keys = list(mission)
    for key in keys:
        value = mission[key]
        comma = "," if key != keys[-1] else ""
        if isinstance(value, list):
            lines.append(f'  "{key}": [')
            for i, item in enumerate(value):
                sep = "," if i + 1 < len(value) else ""
                lines.append("    " + json.dumps(item) + sep)
            lines.append("  ]" + comma)
        else:
            lines.append(f'  "{key}": {json.dumps(value)}{comma}')
    lines.append("}")
    return "\n".join(lines) + "\n"


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("fixtures", "missions")
    os.makedirs(out, exist_ok=True)
    for name, params in MISSIONS.items():
        path = os.path.join(out, name + ".json")
        with open(path, "w", encoding="utf-8") as f:
            f.write(dump(make(name, *params)))
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
