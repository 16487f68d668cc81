/// sva_config.h -- every compile-time bound and switch of the sva core.
///
/// Each bound has a default, a range check that names it, and a documented memory
/// cost. To change bounds, either define them on the compiler command line or point
/// SVA_CONFIG_HEADER at a header that defines them (CMake's SVA_PROFILE option writes
/// one and exports it PUBLIC, so every consumer sees the same struct layout).
/// SVA_BUILD_CONFIG=1 is the same hook without a quoted value: it includes
/// "sva_build_config.h", the header an installed build puts in its include directory
/// (pkg-config's sva.pc passes it: flags that need no quoting in a shell).
/// sva_limits() reports the compiled values at run time.
///
/// Memory formulas (bytes on x86-64, measured by varying each bound; DESIGN.md
/// section 4 has the default profile's totals):
///   sva_mission_t  ~ 20 * SVA_MAX_UAVS + 24 * SVA_MAX_TARGETS
///   sva_plan_t     ~ SVA_MAX_UAVS * (24 + 2 * SVA_MAX_ROUTE_TARGETS) + 2 * SVA_MAX_TARGETS
///   sva_planner_t  ~ SVA_TABLEAU_CELLS + 22 * SVA_TABLEAU_COLS           (tableau)
///                  + 16 * SVA_MAX_TP_SOURCES * SVA_MAX_TP_SINKS          (problem, hga)
///                  + bfa's stack (~3 KB by default)
///                  + 156 * SVA_MAX_UAVS + (74 + 16 * SVA_FLOW_LABELS) * SVA_MAX_TARGETS
///                  + 8 * SVA_FLOW_MAX_ARCS (10 past 65,535 arcs)         (flow's graph)
///                  + (106 + 2 * SVA_FLOW_MAX_DEPTH) * SVA_FLOW_MAX_COPIES (copies, search)
///                  + 8 * SVA_FLOW_LP_ROWS^2 + 68 * SVA_FLOW_LP_ROWS
///                  + 14 * SVA_FLOW_LP_COLS                               (route master)
///                  + the coverage search (SVA_FLOW_COVER_TARGETS below)
///                  + the route enumeration (SVA_FLOW_ENUM_ROUTES below)
///                  + large missions' granular moves (SVA_FLOW_NEAR below)
///   (default profile: 783,600 B on x86-64, of which flow's sva_flow_work_t is 637,680 B;
///   large profile: 7,388,208 B, of which 6,560,000 B are flow's 656,000 arcs.)

#ifndef SVA_CONFIG_H
#define SVA_CONFIG_H

/// 1: include "sva_build_config.h" (found through the include path) unless
/// SVA_CONFIG_HEADER names a header, which wins. 0 (default): neither, the defaults.
#ifndef SVA_BUILD_CONFIG
#    define SVA_BUILD_CONFIG 0
#endif
#if (SVA_BUILD_CONFIG != 0) && (SVA_BUILD_CONFIG != 1)
#    error "SVA_BUILD_CONFIG must be 0 or 1"
#endif
#if defined(SVA_CONFIG_HEADER)
#    include SVA_CONFIG_HEADER
#elif SVA_BUILD_CONFIG
#    include "sva_build_config.h"
#endif

// ---------------------------------------------------------------------------------
// Mission size.

/// Largest fleet. Cost: ~ 20 B in the mission, ~ 24 B + route in the plan, ~ 40 B of
/// planner state per UAV.
#ifndef SVA_MAX_UAVS
#    define SVA_MAX_UAVS 64
#endif
#if (SVA_MAX_UAVS < 1) || (SVA_MAX_UAVS > 1024)
#    error "SVA_MAX_UAVS must be in [1, 1024]"
#endif

/// Most targets in one mission. Cost: 24 B in the mission, ~ 16 B of planner state.
#ifndef SVA_MAX_TARGETS
#    define SVA_MAX_TARGETS 256
#endif
#if (SVA_MAX_TARGETS < 1) || (SVA_MAX_TARGETS > 4096)
#    error "SVA_MAX_TARGETS must be in [1, 4096]"
#endif

/// Most targets one UAV may serve in a plan. A UAV whose route is full is no longer
/// ready for further targets. Cost: 2 B per UAV per slot in the plan.
#ifndef SVA_MAX_ROUTE_TARGETS
#    define SVA_MAX_ROUTE_TARGETS SVA_MAX_TARGETS
#endif
#if (SVA_MAX_ROUTE_TARGETS < 1) || (SVA_MAX_ROUTE_TARGETS > SVA_MAX_TARGETS)
#    error "SVA_MAX_ROUTE_TARGETS must be in [1, SVA_MAX_TARGETS]"
#endif

// ---------------------------------------------------------------------------------
// Transportation problem (the tableau). A cluster with more targets than
// SVA_MAX_TP_SINKS is solved as consecutive chunks of that size; when more source
// groups are ready than SVA_MAX_TP_SOURCES, the ones nearest the chunk are kept
// (DESIGN.md section 3). Neither is an error.

/// Most source groups (UAVs grouped by position and reachable targets) per problem.
#ifndef SVA_MAX_TP_SOURCES
#    define SVA_MAX_TP_SOURCES 24
#endif
#if (SVA_MAX_TP_SOURCES < 1) || (SVA_MAX_TP_SOURCES > 255)
#    error "SVA_MAX_TP_SOURCES must be in [1, 255]"
#endif

/// Most targets (sinks) per transportation problem.
#ifndef SVA_MAX_TP_SINKS
#    define SVA_MAX_TP_SINKS 48
#endif
#if (SVA_MAX_TP_SINKS < 1) || (SVA_MAX_TP_SINKS > 255)
#    error "SVA_MAX_TP_SINKS must be in [1, 255]"
#endif

/// Pivot budget per transportation problem; exceeding it is SVA_ERR_SOLVER.
#ifndef SVA_MAX_PIVOTS
#    define SVA_MAX_PIVOTS 20000
#endif
#if (SVA_MAX_PIVOTS < 16) || (SVA_MAX_PIVOTS > 100000000)
#    error "SVA_MAX_PIVOTS must be in [16, 100000000]"
#endif

/// Derived tableau shape: one row per source and per sink; one column per arc, per
/// unmet-demand slack and per surplus slack. Cost: 1 B per cell, ~ 22 B per column.
#define SVA_TABLEAU_ROWS  (SVA_MAX_TP_SOURCES + SVA_MAX_TP_SINKS)
#define SVA_TABLEAU_COLS  ((SVA_MAX_TP_SOURCES * SVA_MAX_TP_SINKS) + SVA_TABLEAU_ROWS)
#define SVA_TABLEAU_CELLS (SVA_TABLEAU_ROWS * SVA_TABLEAU_COLS)

// ---------------------------------------------------------------------------------
// Exhaustive search (bfa, and hga's per-problem enumeration).

/// bfa refuses missions with more targets than this (SVA_ERR_LIMIT, diag names it).
/// The size bounds alone do not bound the search: a mission within both can still be
/// refused once its search passes SVA_BFA_MAX_NODES (measured with the defaults: some
/// 8 UAV x 12 target missions with chained windows and need >= 2 do; docs/cli.md).
#ifndef SVA_BFA_MAX_TARGETS
#    define SVA_BFA_MAX_TARGETS 12
#endif
#if (SVA_BFA_MAX_TARGETS < 1) || (SVA_BFA_MAX_TARGETS > 64) || \
    (SVA_BFA_MAX_TARGETS > SVA_MAX_TARGETS)
#    error "SVA_BFA_MAX_TARGETS must be in [1, min(64, SVA_MAX_TARGETS)]"
#endif

/// bfa refuses missions with more UAVs than this.
#ifndef SVA_BFA_MAX_UAVS
#    define SVA_BFA_MAX_UAVS 8
#endif
#if (SVA_BFA_MAX_UAVS < 1) || (SVA_BFA_MAX_UAVS > 32) || (SVA_BFA_MAX_UAVS > SVA_MAX_UAVS)
#    error "SVA_BFA_MAX_UAVS must be in [1, min(32, SVA_MAX_UAVS)]"
#endif

/// bfa gives up (SVA_ERR_LIMIT) after visiting this many search nodes: a clear error
/// instead of hours of work. Deterministic: a node count, not a clock.
#ifndef SVA_BFA_MAX_NODES
#    define SVA_BFA_MAX_NODES 20000000L
#endif
#if (SVA_BFA_MAX_NODES < 1000L) || (SVA_BFA_MAX_NODES > 2000000000L)
#    error "SVA_BFA_MAX_NODES must be in [1000, 2000000000]"
#endif

/// hga enumerates each transportation problem up to this many nodes, then keeps the
/// best assignment found (counted in sva_stats_t.truncated_searches).
#ifndef SVA_HGA_MAX_NODES
#    define SVA_HGA_MAX_NODES 200000L
#endif
#if (SVA_HGA_MAX_NODES < 100L) || (SVA_HGA_MAX_NODES > 2000000000L)
#    error "SVA_HGA_MAX_NODES must be in [100, 2000000000]"
#endif

// ---------------------------------------------------------------------------------
// flow: min-cost flow relaxation plus branch and bound (core/src/flow/, DESIGN.md
// section 8).
// A target with need n becomes n copies of need 1; every bound below is a clear
// SVA_ERR_LIMIT (or, for the budgets, a plan not proven optimal), never a crash.

/// Most target copies (the needs summed over the mission). Cost ~ 30 B per copy plus
/// 2 B per copy per search level (SVA_FLOW_MAX_DEPTH).
#ifndef SVA_FLOW_MAX_COPIES
#    define SVA_FLOW_MAX_COPIES (2L * SVA_MAX_TARGETS)
#endif
#if (SVA_FLOW_MAX_COPIES < 1L) || (SVA_FLOW_MAX_COPIES > 16384L)
#    error "SVA_FLOW_MAX_COPIES must be in [1, 16384]"
#endif

/// Arcs of the complete time-feasibility graph for the bounds above (UAV -> copy,
/// copy -> later copy, UAV or copy -> depot); the default arc bound is this, capped.
#define SVA_FLOW_DENSE_ARCS                                                     \
    ((SVA_MAX_UAVS * SVA_FLOW_MAX_COPIES) +                                     \
     ((SVA_FLOW_MAX_COPIES * (SVA_FLOW_MAX_COPIES - 1L)) / 2L) + SVA_MAX_UAVS + \
     SVA_FLOW_MAX_COPIES)

/// Most arcs of one mission's graph (time- and fuel-feasible pairs only). Cost ~ 8 B
/// per arc, 10 B past 65,535 (the reverse index then takes 32 bits). 200 targets x 40
/// UAVs with need 1 need at most ~28,500.
#ifndef SVA_FLOW_MAX_ARCS
#    if SVA_FLOW_DENSE_ARCS < 49152L
#        define SVA_FLOW_MAX_ARCS SVA_FLOW_DENSE_ARCS
#    else
#        define SVA_FLOW_MAX_ARCS 49152L
#    endif
#endif
#if (SVA_FLOW_MAX_ARCS < 1L) || (SVA_FLOW_MAX_ARCS > 4000000L)
#    error "SVA_FLOW_MAX_ARCS must be in [1, 4000000]"
#endif

/// Deepest branch-and-bound path; a deeper node is not explored (the plan is then not
/// proven optimal). Cost: 2 B * SVA_FLOW_MAX_COPIES + 24 B per level.
#ifndef SVA_FLOW_MAX_DEPTH
#    define SVA_FLOW_MAX_DEPTH 24
#endif
#if (SVA_FLOW_MAX_DEPTH < 1) || (SVA_FLOW_MAX_DEPTH > 200)
#    error "SVA_FLOW_MAX_DEPTH must be in [1, 200]"
#endif

/// Work budget of one flow run, in arc scans (deterministic, not a clock). When it
/// runs out the best plan found is returned with stats.optimal false.
#ifndef SVA_FLOW_MAX_WORK
#    define SVA_FLOW_MAX_WORK 2000000L
#endif
#if (SVA_FLOW_MAX_WORK < 1000L) || (SVA_FLOW_MAX_WORK > 2000000000L)
#    error "SVA_FLOW_MAX_WORK must be in [1000, 2000000000]"
#endif

/// Default work budget of flow given a standing plan (sva_planner_t.flow_replan_work:
/// a live replan, which starts from that plan); at most SVA_FLOW_MAX_WORK.
#ifndef SVA_FLOW_REPLAN_WORK
#    if SVA_FLOW_MAX_WORK < 60000L
#        define SVA_FLOW_REPLAN_WORK SVA_FLOW_MAX_WORK
#    else
#        define SVA_FLOW_REPLAN_WORK 60000L
#    endif
#endif
#if (SVA_FLOW_REPLAN_WORK < 1000L) || (SVA_FLOW_REPLAN_WORK > SVA_FLOW_MAX_WORK)
#    error "SVA_FLOW_REPLAN_WORK must be in [1000, SVA_FLOW_MAX_WORK]"
#endif

/// Labels kept per target by the resource-constrained shortest path of flow's
/// Lagrangian bound (flow_lagrange.c): Pareto-best (reduced cost, fuel) pairs. Past it
/// two labels merge into one that dominates both, which keeps the bound valid but
/// weaker. Cost: 16 B * SVA_MAX_TARGETS per label.
#ifndef SVA_FLOW_LABELS
#    define SVA_FLOW_LABELS 8
#endif
#if (SVA_FLOW_LABELS < 1) || (SVA_FLOW_LABELS > 64)
#    error "SVA_FLOW_LABELS must be in [1, 64]"
#endif

/// A mission of more than SVA_FLOW_LARGE_FROM targets is large for flow: its work
/// budget is flow_max_work * (targets / SVA_FLOW_LARGE_FROM)^2, at most twice
/// flow_max_work (sva.h), its Lagrangian phase gets an eighth of that budget and
/// its heuristic flies real paths when the flight fits the budget, and its ruin and
/// recreate is granular (flow_ruin.c): a round takes strings of visits out of the
/// routes serving its seed's SVA_FLOW_NEAR most related targets and puts them back in
/// an order drawn for the round, costs work for the targets it ruins, not the whole
/// mission, its local search starts from the routes the round changed and moves a
/// visit only towards the routes serving those related targets (and the empty ones),
/// and a round's plan within a falling threshold of the current one is accepted; ruin
/// and recreate gets at least half the budget, and no search follows it. Smaller
/// missions plan exactly as without these rules.
/// SVA_FLOW_NEAR 0 leaves the granular moves and the accepting out. Cost, when
/// SVA_MAX_TARGETS > SVA_FLOW_LARGE_FROM: 24 B, and when SVA_FLOW_NEAR > 0 too:
/// (2 * SVA_FLOW_NEAR + 13) B * SVA_MAX_TARGETS + 5 B * SVA_MAX_UAVS
/// + 2 B * SVA_FLOW_MAX_COPIES + 144 B.
#ifndef SVA_FLOW_LARGE_FROM
#    define SVA_FLOW_LARGE_FROM 64
#endif
#if (SVA_FLOW_LARGE_FROM < 1) || (SVA_FLOW_LARGE_FROM > 4096)
#    error "SVA_FLOW_LARGE_FROM must be in [1, 4096]"
#endif
#ifndef SVA_FLOW_NEAR
#    define SVA_FLOW_NEAR 16
#endif
#if (SVA_FLOW_NEAR < 0) || (SVA_FLOW_NEAR > 64)
#    error "SVA_FLOW_NEAR must be in [0, 64]"
#endif
/// Derived: SVA_FLOW_LARGE 1 when a mission can be large (the rules above are compiled
/// in only then), SVA_FLOW_GRANULAR 1 when the granular moves are on too (their memory
/// is there only then).
#if SVA_MAX_TARGETS > SVA_FLOW_LARGE_FROM
#    define SVA_FLOW_LARGE 1
#else
#    define SVA_FLOW_LARGE 0
#endif
#if (SVA_FLOW_NEAR > 0) && SVA_FLOW_LARGE
#    define SVA_FLOW_GRANULAR 1
#else
#    define SVA_FLOW_GRANULAR 0
#endif
/// Derived: the most visits one ruin round of a large mission takes out (its strings,
/// flow_ruin.c: at most 45, with its mean of 15 visits).
#define SVA_FLOW_RUINED_MOST 64

/// Subgradient iterations of one Lagrangian phase (each one resource-constrained
/// shortest path per distinct UAV state; their label work counts against
/// SVA_FLOW_MAX_WORK).
#ifndef SVA_FLOW_LAGRANGE_ITERS
#    define SVA_FLOW_LAGRANGE_ITERS 300
#endif
#if (SVA_FLOW_LAGRANGE_ITERS < 1) || (SVA_FLOW_LAGRANGE_ITERS > 100000)
#    error "SVA_FLOW_LAGRANGE_ITERS must be in [1, 100000]"
#endif

/// Rows of the route master that gives flow's Lagrangian phase its prices (flow_lp.c):
/// one per target, one per distinct UAV state and one for the coverage. Missions with
/// more rows go without it (the prices then come from subgradient steps alone); 1
/// turns it off. Cost: 8 B * rows^2 + 32 B * rows.
#ifndef SVA_FLOW_LP_ROWS
#    define SVA_FLOW_LP_ROWS 64
#endif
#if (SVA_FLOW_LP_ROWS < 1) || (SVA_FLOW_LP_ROWS > 128)
#    error "SVA_FLOW_LP_ROWS must be in [1, 128]"
#endif

/// Route columns the master keeps (generated by the labels of the Lagrangian phase).
/// Cost: (6 + 4 * ceil(SVA_FLOW_LP_ROWS / 32)) B per column (rows, cells, flags).
#ifndef SVA_FLOW_LP_COLS
#    define SVA_FLOW_LP_COLS 256
#endif
#if (SVA_FLOW_LP_COLS < 1) || (SVA_FLOW_LP_COLS > 4096)
#    error "SVA_FLOW_LP_COLS must be in [1, 4096]"
#endif

/// Routes flow keeps to prove a plan optimal from the route master's prices
/// (flow_enum.c), on missions of at most 64 targets, need 1: every route that a plan
/// cheaper than the incumbent could fly (at most 512 of them), or one covering more
/// targets (all of them). 0 turns it off; so does SVA_FLOW_LP_ROWS 1 (no prices),
/// where it defaults to 0. Cost: 18 B per route + 20 B per UAV + 3,416 B (41,560 B
/// by default).
#ifndef SVA_FLOW_ENUM_ROUTES
#    define SVA_FLOW_ENUM_ROUTES ((SVA_FLOW_LP_ROWS >= 2) ? 2048 : 0)
#endif
#if (SVA_FLOW_ENUM_ROUTES < 0) || (SVA_FLOW_ENUM_ROUTES > 65535)
#    error "SVA_FLOW_ENUM_ROUTES must be in [0, 65535]"
#endif

/// flow's coverage search (flow_cover.c): missions of at most this many targets and
/// UAVs that are not stranded get it, while their coverage is not proven the most; 0
/// turns it off. Cost: about 4 B * T * (T + 1) + 20 B * (T + 1) * U + 3 B * T * U + 32 B * T
/// + 13 B * U (17,608 B at the default 32 x 16, 1,264 B of it the chain bound).
#ifndef SVA_FLOW_COVER_TARGETS
#    define SVA_FLOW_COVER_TARGETS ((SVA_MAX_TARGETS < 32) ? SVA_MAX_TARGETS : 32)
#endif
#if (SVA_FLOW_COVER_TARGETS < 0) || (SVA_FLOW_COVER_TARGETS > 64) || \
    (SVA_FLOW_COVER_TARGETS > SVA_MAX_TARGETS)
#    error "SVA_FLOW_COVER_TARGETS must be in [0, min(64, SVA_MAX_TARGETS)]"
#endif
#ifndef SVA_FLOW_COVER_UAVS
#    define SVA_FLOW_COVER_UAVS ((SVA_MAX_UAVS < 16) ? SVA_MAX_UAVS : 16)
#endif
#if (SVA_FLOW_COVER_UAVS < 0) || (SVA_FLOW_COVER_UAVS > 32) || (SVA_FLOW_COVER_UAVS > SVA_MAX_UAVS)
#    error "SVA_FLOW_COVER_UAVS must be in [0, min(32, SVA_MAX_UAVS)]"
#endif

// ---------------------------------------------------------------------------------
// Value bounds (SPEC section 1). Coordinates are fixed by the SPEC; the others keep
// every sum inside int64 with a wide margin and every leg inside int32 (DESIGN.md
// section 5).

#define SVA_COORD_MIN (-32768L)
#define SVA_COORD_MAX 32767L

/// Latest tick a window or ready time may name.
#ifndef SVA_MAX_TICK
#    define SVA_MAX_TICK 1000000000L
#endif
#if (SVA_MAX_TICK < 1L) || (SVA_MAX_TICK > 1000000000L)
#    error "SVA_MAX_TICK must be in [1, 1000000000]"
#endif

/// Largest ticks_per_cell (travel time of one grid cell).
#ifndef SVA_MAX_TICKS_PER_CELL
#    define SVA_MAX_TICKS_PER_CELL 1000L
#endif
#if (SVA_MAX_TICKS_PER_CELL < 1L) || (SVA_MAX_TICKS_PER_CELL > 10000L)
#    error "SVA_MAX_TICKS_PER_CELL must be in [1, 10000]"
#endif

/// Largest fuel a UAV may carry.
#ifndef SVA_MAX_FUEL
#    define SVA_MAX_FUEL 1000000000L
#endif
#if (SVA_MAX_FUEL < 1L) || (SVA_MAX_FUEL > 2000000000L)
#    error "SVA_MAX_FUEL must be in [1, 2000000000]"
#endif

/// Largest hover_fuel (fuel per served window).
#ifndef SVA_MAX_HOVER_FUEL
#    define SVA_MAX_HOVER_FUEL 1000000L
#endif
#if (SVA_MAX_HOVER_FUEL < 0L) || (SVA_MAX_HOVER_FUEL > 100000000L)
#    error "SVA_MAX_HOVER_FUEL must be in [0, 100000000]"
#endif

/// Largest change_penalty of a live mission (cells per changed visit). The objective
/// cost + change_penalty * changes stays far inside int64_t: changes are at most
/// 2 * SVA_MAX_UAVS * SVA_MAX_ROUTE_TARGETS.
#ifndef SVA_MAX_CHANGE_PENALTY
#    define SVA_MAX_CHANGE_PENALTY 1000000L
#endif
#if (SVA_MAX_CHANGE_PENALTY < 0L) || (SVA_MAX_CHANGE_PENALTY > 1000000000L)
#    error "SVA_MAX_CHANGE_PENALTY must be in [0, 1000000000]"
#endif

/// Largest UAV or target id (ids are positive).
#define SVA_MAX_ID 2147483647L

// ---------------------------------------------------------------------------------
// Switches (0/1, tested with #if).

/// 1: SVA_ASSERT checks API misuse (NULL pointers, bad enum values). Never used on
/// untrusted input, which is validated and reported through sva_diag_t.
#ifndef SVA_ENABLE_ASSERT
#    define SVA_ENABLE_ASSERT 1
#endif
#if (SVA_ENABLE_ASSERT != 0) && (SVA_ENABLE_ASSERT != 1)
#    error "SVA_ENABLE_ASSERT must be 0 or 1"
#endif

/// 1: flow honours sva_planner_t.standing (a live mission's change_penalty, SPEC
/// section 12.4); 0: it ignores it, saving about 1.2 KB of code (Cortex-M4, -Os).
#ifndef SVA_FLOW_STANDING
#    define SVA_FLOW_STANDING 1
#endif
#if (SVA_FLOW_STANDING != 0) && (SVA_FLOW_STANDING != 1)
#    error "SVA_FLOW_STANDING must be 0 or 1"
#endif

#endif  // SVA_CONFIG_H
