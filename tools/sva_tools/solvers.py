"""Transportation problems solved by an integer LP: HiGHS's MIP solver as bundled in
OR-tools (pywraplp). The separate highspy wheel is not used: its libhighs.so.1 and the
one inside the ortools wheel have the same soname but different ABIs, so the two
cannot be loaded into one process (docs/tools.md).

A problem is given as supply[i] (UAVs in source group i), demand[j] (need of sink j)
and cost[i][j] (cells, or None where the group cannot serve the sink: no arc).
Supplies are upper bounds (surplus UAVs stay put, SPEC 2); costs are integers, and
every solve runs with zero MIP gap so the optimum is exact.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Optional

Cost = Sequence[Sequence[Optional[int]]]
# A constraint lo <= sum(val * x[col]) <= hi (None: no bound on that side).
Row = tuple[Optional[float], Optional[float], list[tuple[int, float]]]


@dataclass
class TpSolution:
    covered: int              # sinks whose demand is met in full
    cost: int                 # sum of cost * flow
    flow: list[list[int]]     # [source][sink]
    kept: list[bool]          # sink met in full (True) or left out (False)


def _arcs(cost: Cost) -> list[tuple[int, int]]:
    return [(i, j) for i, row in enumerate(cost) for j, c in enumerate(row) if c is not None]


def _arc_costs(cost: Cost, arcs: list[tuple[int, int]]) -> list[int]:
    """The cost of each arc (every arc has one: _arcs keeps only those)."""
    return [c for c in (cost[i][j] for i, j in arcs) if c is not None]


def _milp(ncols: int, col_cost: Sequence[float], lb: Sequence[int], ub: Sequence[int], integer: bool,
          rows: list[Row], sense_max: bool = False) -> list[int] | None:
    """rows: list of (lo, hi, [(col, val), ...]), None for no bound. Returns the column
    values of an optimum, or None when infeasible."""
    from ortools.linear_solver import pywraplp

    if ncols == 0:
        return [] if all((lo is None or lo <= 0) and (hi is None or hi >= 0)
                         for lo, hi, _ in rows) else None
    s = pywraplp.Solver.CreateSolver("HIGHS_MIXED_INTEGER_PROGRAMMING")
    s.SuppressOutput()
    s.SetSolverSpecificParametersAsString("output_flag=false\nlog_to_console=false\n")
    inf = s.infinity()
    x = [s.IntVar(lb[k], ub[k], f"x{k}") if integer else s.NumVar(lb[k], ub[k], f"x{k}")
         for k in range(ncols)]
    for lo, hi, entries in rows:
        c = s.Constraint(-inf if lo is None else float(lo), inf if hi is None else float(hi))
        for col, val in entries:
            c.SetCoefficient(x[col], float(val))
    obj = s.Objective()
    for k in range(ncols):
        obj.SetCoefficient(x[k], float(col_cost[k]))
    if sense_max:
        obj.SetMaximization()
    else:
        obj.SetMinimization()
    params = pywraplp.MPSolverParameters()
    params.SetDoubleParam(params.RELATIVE_MIP_GAP, 0.0)
    if s.Solve(params) != pywraplp.Solver.OPTIMAL:
        return None
    return [int(round(v.solution_value())) for v in x]


def solve_exact(supply: Sequence[int], demand: Sequence[int], cost: Cost) -> TpSolution | None:
    """Least cost with every sink's demand met exactly (flow <= supply per source), only
    the given arcs. None when infeasible."""
    arcs = _arcs(cost)
    rows: list[Row] = []
    for i, s in enumerate(supply):
        rows.append((None, s, [(k, 1.0) for k, (a, _) in enumerate(arcs) if a == i]))
    for j, d in enumerate(demand):
        rows.append((d, d, [(k, 1.0) for k, (_, b) in enumerate(arcs) if b == j]))
    ub = [min(supply[i], demand[j]) for i, j in arcs]
    costs = _arc_costs(cost, arcs)
    x = _milp(len(arcs), costs, [0] * len(arcs), ub, True, rows)
    if x is None:
        return None
    flow = [[0] * len(demand) for _ in supply]
    for k, (i, j) in enumerate(arcs):
        flow[i][j] = x[k]
    total = sum(c * x[k] for k, c in enumerate(costs))
    return TpSolution(len(demand), total, flow, [True] * len(demand))


def solve_max_cover(supply: Sequence[int], demand: Sequence[int], cost: Cost) -> TpSolution:
    """SPEC 2's rule for a cluster that cannot be covered in full, solved exactly: first
    as many sinks met in full as possible (all or nothing each), then least cost. Two
    integer LPs: max sum(y), then min cost with sum(y) fixed."""
    arcs = _arcs(cost)
    na, nk = len(arcs), len(demand)
    ncols = na + nk  # arcs, then y_j in {0, 1}

    def rows(extra: list[Row]) -> list[Row]:
        r: list[Row] = []
        for i, s in enumerate(supply):
            r.append((None, s, [(k, 1.0) for k, (a, _) in enumerate(arcs) if a == i]))
        for j, d in enumerate(demand):
            ent = [(k, 1.0) for k, (_, b) in enumerate(arcs) if b == j] + [(na + j, -float(d))]
            r.append((0, 0, ent))
        return r + extra

    ub = [min(supply[i], demand[j]) for i, j in arcs] + [1] * nk
    lb = [0] * ncols
    x = _milp(ncols, [0] * na + [1] * nk, lb, ub, True, rows([]), sense_max=True)
    if x is None:  # cannot happen: all zero is feasible
        raise RuntimeError("max-cover integer LP failed")
    best = sum(x[na:])
    costs = _arc_costs(cost, arcs)
    x = _milp(ncols, costs + [0] * nk, lb, ub, True,
              rows([(best, best, [(na + j, 1.0) for j in range(nk)])]))
    if x is None:
        raise RuntimeError("min-cost integer LP failed at fixed coverage")
    flow = [[0] * nk for _ in supply]
    for k, (i, j) in enumerate(arcs):
        flow[i][j] = x[k]
    total = sum(c * x[k] for k, c in enumerate(costs))
    return TpSolution(best, total, flow, [bool(v) for v in x[na:]])
