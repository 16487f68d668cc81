/// sva.h -- the on-board mission planner core: its public header (live missions: sva_live.h).
///
/// ## What it does
/// A fleet of identical UAVs (capacity one, limited fuel, start where the fleet state
/// says, end at the depot) must cover target areas; target t needs t.need UAVs
/// present for its whole window [start, end]. sva_plan() assigns UAVs to targets and
/// orders their visits: first cover as many targets as possible, then minimise the
/// sum of route distances (Manhattan, integer). The rules are SPEC.md section 1.
///
/// ## Pipeline (algorithm SVA_ALGO_SVA, the paper's Simplex VRP Algorithm)
///   validate -> sort targets by (start, end, id) -> cluster by window overlap ->
///   for each cluster (in chunks of SVA_MAX_TP_SINKS targets):
///     ready UAVs -> source groups (position, reachable targets) ->
///     transportation problem -> integer tableau simplex -> commit, advance
///   -> routes with the return leg, uncovered targets, cost.
/// SVA_ALGO_HGA runs the same pipeline but solves each transportation problem by
/// enumeration; SVA_ALGO_GA fills targets one by one with the cheapest ready UAVs;
/// SVA_ALGO_BFA searches exhaustively for the optimum (small missions only).
///
/// ## Where every byte lives
/// Nothing is allocated. The caller owns three structs and may place them anywhere
/// (firmware writes `static sva_planner_t planner;`):
///   sva_mission_t  the input (mission and fleet state), read only by the planner;
///   sva_plan_t     the output;
///   sva_planner_t  all working memory (tableau, per-UAV state, search stacks); the
///                  layout of its `priv` member is in sva_private.h, private and
///                  read-only to users.
/// Their sizes follow from sva_config.h (formulas there and in DESIGN.md); sva_limits() reports
/// the default profile's. The core uses no heap, no stdio, no floating point, no recursion and
/// no variable-length arrays; its stack use is bounded, measured with -fstack-usage (DESIGN.md 6).
///
/// ## Complexity (U = UAVs, T = targets, S/K = sources/sinks of one problem)
///   validation O(U^2 + T^2); sorting and clustering O(T^2);
///   sva: per problem at most SVA_MAX_PIVOTS pivots of O((S+K) * S*K) each;
///   ga: O(T * U log U); hga: at most SVA_HGA_MAX_NODES nodes per problem;
///   bfa: at most SVA_BFA_MAX_NODES nodes.
///
/// ## Thread safety
/// Functions are reentrant: they touch only the structs passed in. One planner may be
/// used by one thread at a time; distinct planners may run concurrently.
///
/// ## Trust
/// sva_mission_t contents are untrusted: sva_plan() validates them first and reports any
/// violation through sva_diag_t, never an assert. SVA_ASSERT guards API misuse only (NULL
/// pointers, enum values out of range). See docs/security.md.

#ifndef SVA_H
#define SVA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sva_config.h"
// The planner's memory layout, for static allocation only: private, may change in any release.
#include "sva_private.h"

#ifdef __cplusplus
extern "C" {
#endif

/// Library version (CMakeLists.txt reads it from here).
#define SVA_VERSION_MAJOR 0
#define SVA_VERSION_MINOR 4
#define SVA_VERSION_PATCH 0
/// Version of the mission and plan JSON schema (SPEC.md section 3).
#define SVA_SCHEMA_VERSION 4

#if defined(__GNUC__) || defined(__clang__)
#    define SVA_NODISCARD __attribute__((warn_unused_result))
#else
#    define SVA_NODISCARD
#endif

// =================================================================================
// Status and diagnostics

/// Result of every status-returning function. 0 is success; errors are negative.
typedef enum {
    SVA_OK = 0,
    /// API misuse caught at run time when SVA_ENABLE_ASSERT is 0 (NULL pointer, enum
    /// out of range). No diagnostic.
    SVA_ERR_ARGUMENT = -1,
    /// The mission breaks a rule of SPEC.md section 1 or a bound of sva_config.h; the
    /// diagnostic names the field, the rule and the limit.
    SVA_ERR_INVALID = -2,
    /// The mission is valid but exceeds a limit of the chosen algorithm (bfa's size
    /// limits or node budget); the diagnostic names the limit.
    SVA_ERR_LIMIT = -3,
    /// The simplex hit SVA_MAX_PIVOTS or met a pivot element other than +1 (the
    /// transportation matrix is totally unimodular, so this means a defect, reported
    /// loudly instead of returning a wrong plan).
    SVA_ERR_SOLVER = -4,
} sva_status_t;

/// Which input field a diagnostic is about.
typedef enum {
    SVA_FIELD_NONE = 0,
    SVA_FIELD_DEPOT_X,
    SVA_FIELD_DEPOT_Y,
    SVA_FIELD_TICKS_PER_CELL,
    SVA_FIELD_HOVER_FUEL,
    SVA_FIELD_OVERLAP_PERCENT,
    SVA_FIELD_UAVS,  ///< the list as a whole (its length)
    SVA_FIELD_UAV_ID,
    SVA_FIELD_UAV_X,
    SVA_FIELD_UAV_Y,
    SVA_FIELD_UAV_FUEL,
    SVA_FIELD_UAV_READY_AT,
    SVA_FIELD_TARGETS,  ///< the list as a whole (its length)
    SVA_FIELD_TARGET_ID,
    SVA_FIELD_TARGET_X,
    SVA_FIELD_TARGET_Y,
    SVA_FIELD_TARGET_START,
    SVA_FIELD_TARGET_END,
    SVA_FIELD_TARGET_NEED,
    SVA_FIELD_CHANGE_PENALTY,  ///< a live mission's change_penalty
    SVA_FIELD_ROUTES,          ///< a plan in force's route list (its length)
    SVA_FIELD_ROUTE_UAV,       ///< a route's UAV id
    SVA_FIELD_ROUTE_TARGETS,   ///< a route's target list (value: the target index)
    SVA_FIELD_EVENT_TYPE,
    SVA_FIELD_EVENT_AT,
    SVA_FIELD_EVENT_UAV,
    SVA_FIELD_EVENT_TARGET,  ///< the id an event names
    SVA_FIELD_EVENT_X,
    SVA_FIELD_EVENT_Y,
    SVA_FIELD_EVENT_FUEL,
    SVA_FIELD_TAKEOFF_TICKS,  ///< a live mission's takeoff_ticks
    SVA_FIELD_COUNT_          ///< number of fields (not a field)
} sva_field_t;

/// Which rule was broken.
typedef enum {
    SVA_RULE_NONE = 0,
    SVA_RULE_MIN,         ///< value < limit
    SVA_RULE_MAX,         ///< value > limit (limit_name names the bound, if any)
    SVA_RULE_COUNT,       ///< list longer than limit (limit_name names the bound)
    SVA_RULE_DUPLICATE,   ///< id equal to the one at index `limit` of the same list
    SVA_RULE_AFTER,       ///< end <= start: value is end, limit is start
    SVA_RULE_ALGO_LIMIT,  ///< an algorithm limit (limit_name names it)
    SVA_RULE_UNKNOWN,     ///< no UAV or target has the id `value`
    SVA_RULE_PAST,        ///< the tick `value` is before the live mission's now (`limit`)
    SVA_RULE_STARTED,     ///< the target's window started at `value`; now is `limit`
    SVA_RULE_STATE,       ///< the UAV or target is in a state (`value`) the event needs otherwise
    SVA_RULE_ROUTE,  ///< a plan in force's route names the target `value` twice or a UAV out of
                     ///< order
    SVA_RULE_COUNT_  ///< number of rules (not a rule)
} sva_rule_t;

/// A diagnostic: the first error found wins. index is the list position (-1 when the
/// field is not in a list); value is what was found; limit is what the rule allows.
typedef struct {
    sva_field_t field;
    sva_rule_t rule;
    int32_t index;
    int64_t value;
    int64_t limit;
    const char* limit_name;  ///< e.g. "SVA_MAX_UAVS"; NULL when the limit is a SPEC rule
} sva_diag_t;

/// Fills *self with "no error". Allocates nothing; O(1).
void sva_diag_clear(sva_diag_t* self);

/// Fills *self (when not NULL) with one diagnostic. For ports and tools that check
/// limits of their own (wire formats, JSON lists) and report them in the core's terms,
/// so sva_diag_format() words every message the same way. Allocates nothing; O(1).
void sva_diag_set(sva_diag_t* self, sva_field_t field, sva_rule_t rule, int32_t index,
                  int64_t value, int64_t limit, const char* limit_name);

/// True iff lo <= value <= hi; otherwise false with *diag (when not NULL) set: SVA_RULE_MIN
/// with limit lo, or SVA_RULE_MAX with limit hi and hi_name (may be NULL). O(1).
bool sva_in_range(sva_diag_t* diag, sva_field_t field, int32_t index, int64_t value, int64_t lo,
                  int64_t hi, const char* hi_name);

/// Writes a one-line message, e.g. "targets[3].need: must be >= 1, got 0" or
/// "uavs: 65 entries exceed SVA_MAX_UAVS (64)", into buf (always NUL-terminated when
/// size > 0, truncated to fit). Returns the length the whole message needs, without
/// the NUL (as snprintf does). Uses no stdio; allocates nothing; O(size).
size_t sva_diag_format(const sva_diag_t* self, char* buf, size_t size);

/// The JSON path of a field without the list index ("targets.need"), or "" for
/// SVA_FIELD_NONE. Never NULL.
const char* sva_field_name(sva_field_t field);

// =================================================================================
// Mission (input)

/// One UAV of the fleet state. Units: cells, fuel units, ticks.
typedef struct {
    int32_t id;              ///< positive, unique in the mission
    int32_t x;               ///< [SVA_COORD_MIN, SVA_COORD_MAX]
    int32_t y;               ///< [SVA_COORD_MIN, SVA_COORD_MAX]
    int32_t fuel;            ///< remaining fuel, [0, SVA_MAX_FUEL]
    int32_t ready_at_ticks;  ///< free to fly from this tick, [0, SVA_MAX_TICK]
} sva_uav_t;

/// One target area.
typedef struct {
    int32_t id;  ///< positive, unique in the mission
    int32_t x;
    int32_t y;
    int32_t start_ticks;  ///< window start, [0, SVA_MAX_TICK)
    int32_t end_ticks;    ///< window end, (start, SVA_MAX_TICK]
    int32_t need;         ///< UAVs required for the whole window, [1, SVA_MAX_UAVS]
} sva_target_t;

/// A whole planning problem: the instance constants, the fleet and the targets.
typedef struct {
    int32_t depot_x;
    int32_t depot_y;
    int32_t ticks_per_cell;   ///< travel ticks per cell, [1, SVA_MAX_TICKS_PER_CELL]
    int32_t hover_fuel;       ///< fuel per served window, [0, SVA_MAX_HOVER_FUEL]
    int32_t overlap_percent;  ///< clustering threshold, [0, 100]
    /// Live missions only, ignored by sva_plan() (SPEC section 12): cells a replan pays per
    /// changed visit, [0, SVA_MAX_CHANGE_PENALTY]; ticks a UAV on the ground takes to leave.
    int32_t change_penalty;
    int32_t takeoff_ticks;  ///< [0, SVA_MAX_TICK]
    uint16_t uav_count;     ///< [0, SVA_MAX_UAVS]
    uint16_t target_count;  ///< [0, SVA_MAX_TARGETS]
    sva_uav_t uavs[SVA_MAX_UAVS];
    sva_target_t targets[SVA_MAX_TARGETS];
} sva_mission_t;

/// Sets the SPEC defaults: depot (0,0), ticks_per_cell 1, hover_fuel 0,
/// overlap_percent 70, no UAVs, no targets. Allocates nothing; O(1).
void sva_mission_init(sva_mission_t* self);

/// Checks every rule of SPEC.md section 4 and every bound of sva_config.h.
/// Returns SVA_OK, or SVA_ERR_INVALID with *diag describing the first violation in
/// field order (instance fields, then UAVs, then targets). diag may be NULL.
/// Allocates nothing; O(U^2 + T^2); stack O(1).
SVA_NODISCARD sva_status_t sva_mission_validate(const sva_mission_t* self, sva_diag_t* diag);

// =================================================================================
// Plan (output)

typedef enum {
    SVA_ALGO_SVA = 0,  ///< the paper's Simplex VRP Algorithm
    SVA_ALGO_GA,       ///< greedy
    SVA_ALGO_HGA,      ///< SVA pipeline, transportation problems by enumeration
    SVA_ALGO_BFA,      ///< exhaustive search: the optimum (small missions)
    SVA_ALGO_FLOW,     ///< min-cost flow relaxation + branch and bound, certified bound
    SVA_ALGO_COUNT_    ///< number of algorithms (not an algorithm)
} sva_algorithm_t;

/// The SPEC name ("sva", "ga", "hga", "bfa", "flow"), or "" when out of range. Never NULL.
const char* sva_algorithm_name(sva_algorithm_t algorithm);

/// Looks up an algorithm by its SPEC name. Returns SVA_OK, or SVA_ERR_ARGUMENT when
/// the name is unknown or NULL (then *out is untouched).
SVA_NODISCARD sva_status_t sva_algorithm_from_name(const char* name, sva_algorithm_t* out);

typedef enum {
    SVA_PLAN_NONE = 0,  ///< no plan (the planner failed or was not run)
    SVA_PLAN_COMPLETE,  ///< every target covered
    SVA_PLAN_PARTIAL,   ///< some target left uncovered
} sva_plan_status_t;

/// One UAV's route: its position, then targets in visit order, then the depot.
typedef struct {
    int32_t uav_id;
    uint16_t target_count;
    /// Indices into sva_mission_t.targets, in visit order.
    uint16_t targets[SVA_MAX_ROUTE_TARGETS];
    int64_t distance_cells;  ///< legs summed, return leg included
    int64_t fuel_used;       ///< distance + hover_fuel * target_count
    /// The UAV's fuel cannot bring it home: not planned for (no targets, distance 0).
    bool stranded;
} sva_route_t;

/// Why flow did not prove its plan optimal: sva_stats_t.flow_incomplete holds one of
/// these (SVA_FLOW_COMPLETE for the other algorithms).
typedef enum {
    /// flow proved the plan optimal, or its search finished.
    SVA_FLOW_COMPLETE = 0,
    /// The search stopped at the work budget (sva_planner_t.flow_max_work).
    SVA_FLOW_INCOMPLETE_WORK = 1,
    /// A branch-and-bound node lay deeper than SVA_FLOW_MAX_DEPTH.
    SVA_FLOW_INCOMPLETE_DEPTH = 2,
    /// The needs' lcm is too large for exact cost ties: flow never claims optimality.
    SVA_FLOW_INCOMPLETE_REWARD = 3,
    /// The needs summed exceed SVA_FLOW_MAX_COPIES: no relaxation, lower_bound 0, and
    /// the plan is the better of ga's and sva's.
    SVA_FLOW_OVER_COPIES = 4,
    /// The graph of copies exceeds SVA_FLOW_MAX_ARCS: no search. With a need above 1
    /// the bound is the pooled graph's relaxation (one node per target) when that
    /// fits, else 0; the plan is the pooled flow's routes, and unless they are proven
    /// optimal (then SVA_FLOW_COMPLETE), the better of them and ga's and sva's plans
    /// after the repair, the local search and ruin and recreate.
    SVA_FLOW_OVER_ARCS = 5,
} sva_flow_incomplete_t;

/// What flow's dive for one target more than its plan covers did (run when that
/// coverage was not proven the most): sva_stats_t.flow_cover_dive holds one of these.
typedef enum {
    SVA_FLOW_COVER_DIVE_NOT_RUN = 0,  ///< it did not run (or not flow)
    SVA_FLOW_COVER_DIVE_NONE = 1,     ///< it ran and found no such plan
    SVA_FLOW_COVER_DIVE_FOUND = 2,    ///< it found one: the plan covers it
} sva_flow_cover_dive_t;

/// Counters of one planning run (peaks let integrators shrink bounds to measurements).
typedef struct {
    uint32_t clusters;               ///< clusters formed (sva, hga)
    uint32_t largest_cluster;        ///< most targets in one cluster
    uint32_t transport_problems;     ///< problems solved (chunks included)
    uint32_t largest_sources;        ///< most source groups in one problem
    uint32_t largest_sinks;          ///< most sinks in one problem
    uint32_t largest_tableau_cells;  ///< most tableau cells used (sva)
    uint32_t pivots;                 ///< simplex pivots, all problems (sva)
    uint32_t max_pivots;             ///< most pivots in one problem (sva)
    uint32_t dropped_sources;        ///< source groups left out by SVA_MAX_TP_SOURCES
    uint32_t chunked_clusters;       ///< clusters split by SVA_MAX_TP_SINKS
    uint64_t search_nodes;           ///< nodes visited (hga, bfa, flow)
    uint32_t truncated_searches;     ///< hga problems cut at SVA_HGA_MAX_NODES
    // flow only (has_bound false for the other algorithms):
    bool has_bound;  ///< lower_bound and optimal are set
    /// No plan covering as many targets as this one costs less than lower_bound.
    int64_t lower_bound;
    /// The plan is proven optimal under SPEC section 1 (lower_bound == cost).
    bool optimal;
    /// No plan of the mission covers more targets than this one (flow only; true when
    /// optimal).
    bool coverage_proven;
    uint16_t flow_cover_nodes;     ///< coverage search nodes (0: did not run; at most 65,535)
    uint32_t flow_solves;          ///< min-cost flow relaxations solved
    uint32_t flow_augmentations;   ///< shortest augmenting paths, all solves
    uint64_t flow_work;            ///< arc scans, against SVA_FLOW_MAX_WORK
    uint32_t flow_graph_arcs;      ///< arcs of the time-feasibility graph
    uint32_t flow_max_depth;       ///< deepest branch-and-bound node
    uint32_t flow_lagrange_iters;  ///< subgradient iterations (0: the search sufficed)
    /// Routes in the route master when it gave the Lagrangian its prices (0: it did not
    /// run, or stopped on a bound or the work budget).
    uint16_t flow_lp_columns;
    /// Routes the dive on the route master fixed before the repair completed its plan
    /// (0: it did not run).
    uint16_t flow_dive_routes;
    /// The dive for one target more than the plan covers: an sva_flow_cover_dive_t.
    uint8_t flow_cover_dive;
    /// Why flow did not prove optimality: an sva_flow_incomplete_t.
    uint8_t flow_incomplete;
    /// Ruin-and-recreate rounds (0: the search or the Lagrangian phase proved the plan,
    /// or left it within 1/64 of the bound, or no budget was left).
    uint16_t flow_ruin_rounds;
} sva_stats_t;

typedef struct sva_plan {
    sva_algorithm_t algorithm;
    sva_plan_status_t status;
    uint16_t covered;  ///< targets covered
    uint16_t uncovered_count;
    uint16_t uncovered[SVA_MAX_TARGETS];  ///< indices into mission targets, mission order
    int64_t cost;                         ///< sum of route distances
    uint16_t route_count;                 ///< == mission uav_count
    uint16_t stranded_count;
    sva_route_t routes[SVA_MAX_UAVS];  ///< one per UAV, in mission order
    sva_stats_t stats;
} sva_plan_t;

// =================================================================================
// Planner

/// What a transportation problem looked like once solved (sva and hga): handed to
/// sva_planner_t.on_transport, valid only during the call. Row-major costs with
/// SVA_TP_NO_ARC where a UAV group cannot serve a target.
#define SVA_TP_NO_ARC (-1L)
typedef struct {
    sva_algorithm_t algorithm;
    uint16_t source_count;
    uint16_t sink_count;
    const int32_t* supply;  ///< [source_count] UAVs per group
    const int32_t* demand;  ///< [sink_count] need per target
    /// [sink_count] true for a sink left out because the problem could not cover every
    /// target (SPEC section 2); the flow into dropped sinks is 0, and the other sinks'
    /// demand is met in full: the flow is an optimum of the problem without them.
    const bool* sink_dropped;
    const int32_t* cost;               ///< [source_count * sink_count] cells or SVA_TP_NO_ARC
    const int32_t* flow;               ///< [source_count * sink_count] UAVs sent
    const uint16_t* sink_targets;      ///< [sink_count] target index of each sink
    const uint16_t* source_first_uav;  ///< [source_count] lowest UAV index of each group
    int64_t cost_total;                ///< sum of cost * flow
    uint16_t covered;                  ///< sinks whose demand is met in full
    uint32_t pivots;                   ///< simplex pivots for this problem (0 for hga)
} sva_tp_view_t;

typedef void (*sva_tp_observer_t)(void* user, const sva_tp_view_t* problem);

/// The planner: caller-owned working memory plus an optional observer. Firmware
/// writes `static sva_planner_t planner;`.
typedef struct sva_planner {
    /// Called after each transportation problem is solved (sva, hga); NULL for none.
    /// Must not call back into this planner.
    sva_tp_observer_t on_transport;
    void* on_transport_user;
    /// flow's work budget in arc scans (deterministic; about 10 ns each on a desktop
    /// core): the search stops there and returns its best plan, not proven optimal.
    /// sva_planner_init sets SVA_FLOW_MAX_WORK; any value in [1000, SVA_FLOW_MAX_WORK]
    /// may be set between runs (others are clamped into that range). A mission of more
    /// than SVA_FLOW_LARGE_FROM targets gets this budget times (targets /
    /// SVA_FLOW_LARGE_FROM)^2, at most twice this budget (sva_config.h).
    uint32_t flow_max_work;
    /// flow's work budget in sva_replan() with a standing plan, if smaller:
    /// sva_planner_init sets SVA_FLOW_REPLAN_WORK (clamped and scaled as flow_max_work).
    uint32_t flow_replan_work;
    /// All working memory (sva_private.h): read-only to users, its layout may change
    /// in any release.
    sva_planner_priv_t priv;
} sva_planner_t;

/// Prepares a planner (no observer). Allocates nothing; O(1).
/// Returns SVA_OK, or SVA_ERR_ARGUMENT when self is NULL.
SVA_NODISCARD sva_status_t sva_planner_init(sva_planner_t* self);

/// Validates *mission, then plans it with `algorithm` into *plan.
/// Returns
///   SVA_OK            plan->status is SVA_PLAN_COMPLETE or SVA_PLAN_PARTIAL;
///   SVA_ERR_ARGUMENT  a NULL pointer or an algorithm out of range;
///   SVA_ERR_INVALID   the mission breaks a rule (diag filled, see sva_mission_validate);
///   SVA_ERR_LIMIT     bfa only: the mission exceeds SVA_BFA_MAX_TARGETS,
///                     SVA_BFA_MAX_UAVS or SVA_BFA_MAX_NODES (diag names it);
///   SVA_ERR_SOLVER    the simplex exceeded SVA_MAX_PIVOTS or met a non-unit pivot.
/// All-or-nothing: it fails iff it returns non-zero, and then plan->status is
/// SVA_PLAN_NONE with no routes. Deterministic: the same mission gives the same plan
/// on every platform (ties broken by ids). diag may be NULL.
/// Allocates nothing; stack bounded (DESIGN.md section 6); complexity above.
SVA_NODISCARD sva_status_t sva_plan(sva_planner_t* self, const sva_mission_t* mission,
                                    sva_algorithm_t algorithm, sva_plan_t* plan, sva_diag_t* diag);

/// sva_plan() with `standing`, the plan in force over *mission (a live mission's plan
/// carried over), or NULL (then it is sva_plan()). flow alone reads it (SPEC 12.4): its first
/// seed, the budget flow_replan_work, changes weighed with change_penalty. It must be a plan
/// of this mission (route r for UAV r, visits in time, no target over its need); flow ignores
/// one that is not, past SVA_FLOW_MAX_COPIES and with SVA_FLOW_STANDING 0. Returns and fails
/// as sva_plan(); reads *standing during the call only. Allocates nothing.
SVA_NODISCARD sva_status_t sva_replan(sva_planner_t* self, const sva_mission_t* mission,
                                      sva_algorithm_t algorithm, const sva_plan_t* standing,
                                      sva_plan_t* plan, sva_diag_t* diag);

/// One visit of a plan: a route index and a target index of its mission.
typedef struct {
    uint16_t route;
    uint16_t target;
} sva_visit_t;

/// The changed visits one way: the visits of `from` that `to` lacks, route r of one held
/// against route r of the other (a route `to` does not have is empty), in route, then visit
/// order. Lists the first `cap` into out[] (NULL when cap is 0); returns how many there are.
/// Allocates nothing; O(routes * SVA_MAX_ROUTE_TARGETS^2).
uint32_t sva_plan_changes(const sva_plan_t* from, const sva_plan_t* to, sva_visit_t* out,
                          uint32_t cap);

// =================================================================================
// Compiled limits

/// The compiled bounds, for tools and ports to report and check against (sva_limits()).
typedef struct {
    uint32_t max_uavs;
    uint32_t max_targets;
    uint32_t max_route_targets;
    uint32_t max_tp_sources;
    uint32_t max_tp_sinks;
    uint32_t max_pivots;
    uint32_t bfa_max_targets;
    uint32_t bfa_max_uavs;
    uint32_t bfa_max_nodes;
    uint32_t hga_max_nodes;
    uint32_t flow_max_copies;
    uint32_t flow_max_arcs;
    uint32_t flow_max_depth;
    uint32_t flow_max_work;
    uint32_t mission_bytes;  ///< sizeof(sva_mission_t)
    uint32_t plan_bytes;     ///< sizeof(sva_plan_t)
    uint32_t planner_bytes;  ///< sizeof(sva_planner_t)
    uint32_t live_bytes;     ///< sizeof(sva_live_t)
} sva_limits_t;

sva_limits_t sva_limits(void);  ///< Allocates nothing; O(1).

#ifdef __cplusplus
}
#endif

#endif  // SVA_H
