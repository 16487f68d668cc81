/// sva_private.h -- the layout of the planner's working memory (sva_planner_t.priv).
///
/// PRIVATE. Included by sva.h only, so that a caller can own the planner (firmware
/// writes `static sva_planner_t planner;`) and the compiler knows its size. Every type
/// and macro here is read-only to users and may change in any release, patch releases
/// included: code outside core/ must not name them. The public API is sva.h.
#ifndef SVA_PRIVATE_H
#define SVA_PRIVATE_H

#ifndef SVA_H
#    error "sva_private.h is private: include sva/sva.h"
#endif

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sva_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/// sva_plan_t (sva.h), which flow's working memory points to.
struct sva_plan;

/// One transportation problem: sources are UAV groups, sinks are targets.
typedef struct {
    uint16_t source_count;
    uint16_t sink_count;
    uint16_t sink_target[SVA_MAX_TP_SINKS];  ///< target index of each sink
    bool sink_dropped[SVA_MAX_TP_SINKS];     ///< left out: not coverable in full
    uint16_t source_first_uav[SVA_MAX_TP_SOURCES];
    int32_t source_x[SVA_MAX_TP_SOURCES];
    int32_t source_y[SVA_MAX_TP_SOURCES];
    int32_t supply[SVA_MAX_TP_SOURCES];
    int32_t demand[SVA_MAX_TP_SINKS];
    int32_t cost[SVA_MAX_TP_SOURCES * SVA_MAX_TP_SINKS];  ///< or SVA_TP_NO_ARC
    int32_t flow[SVA_MAX_TP_SOURCES * SVA_MAX_TP_SINKS];
    int32_t unmet[SVA_MAX_TP_SINKS];  ///< demand the tableau's optimum leaves unmet
    int16_t uav_group[SVA_MAX_UAVS];  ///< source of each UAV or -1
    int16_t uav_rep[SVA_MAX_UAVS];    ///< first UAV (index) of the same position and reach
    int32_t rep_cost[SVA_MAX_UAVS];   ///< nearest reachable sink of a group representative
    bool uav_reach[SVA_MAX_UAVS * SVA_MAX_TP_SINKS];  ///< UAV can serve sink
    uint32_t pivots;
} sva_tp_t;

/// The dense integer tableau of one transportation problem (tableau.c).
typedef struct {
    int8_t cell[SVA_TABLEAU_CELLS];  ///< rows x cols, every entry in {-1, 0, +1}
    int32_t rhs[SVA_TABLEAU_ROWS];
    int16_t basis[SVA_TABLEAU_ROWS];
    int64_t reduced[SVA_TABLEAU_COLS];
    int64_t col_cost[SVA_TABLEAU_COLS];
    int16_t col_source[SVA_TABLEAU_COLS];  ///< source row of an arc column, else -1
    int16_t col_sink[SVA_TABLEAU_COLS];    ///< sink of an arc or unmet-demand column, else -1
    int16_t nonzero[SVA_TABLEAU_COLS];     ///< columns where the pivot row is not 0
    int16_t sink_row[SVA_MAX_TP_SINKS];    ///< tableau row of each sink, -1 if dropped
} sva_tableau_t;

/// hga's enumeration of one transportation problem: one frame per sink.
typedef struct {
    int32_t pick[SVA_MAX_TP_SINKS * SVA_MAX_TP_SOURCES];  ///< units from each source
    int32_t best[SVA_MAX_TP_SINKS * SVA_MAX_TP_SOURCES];
    int32_t left[SVA_MAX_TP_SOURCES];  ///< supply not yet used
    uint8_t phase[SVA_MAX_TP_SINKS];
    int64_t cost_before[SVA_MAX_TP_SINKS];
} sva_hga_work_t;

/// bfa's explicit search stack: one frame per target, in visit-time order.
typedef struct {
    uint16_t cand[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];  ///< UAVs able to serve
    int64_t cand_cost[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];
    uint8_t cand_count[SVA_BFA_MAX_TARGETS];
    uint8_t pick[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];  ///< chosen candidate positions
    uint8_t phase[SVA_BFA_MAX_TARGETS];
    int32_t saved_x[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];
    int32_t saved_y[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];
    int64_t saved_free_at[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];
    int64_t saved_fuel_left[SVA_BFA_MAX_TARGETS][SVA_BFA_MAX_UAVS];
    int64_t cost_before[SVA_BFA_MAX_TARGETS];
    uint16_t best_route[SVA_BFA_MAX_UAVS][SVA_BFA_MAX_TARGETS];
    uint8_t best_len[SVA_BFA_MAX_UAVS];
} sva_bfa_work_t;

/// flow's branch-and-bound frame: a node whose relaxation broke a rule, and the
/// children that partition its plans (flow.c).
typedef struct {
    uint8_t kind;       ///< half-covered target, or a route over fuel or length
    uint16_t subject;   ///< target index, or UAV index
    uint16_t path_len;  ///< copies on the infeasible route
    uint16_t child_count;
    int16_t next_child;
    int16_t active_child;                ///< applied to the graph now, or -1
    int64_t bound;                       ///< relaxation value of this node
    uint16_t path[SVA_FLOW_MAX_COPIES];  ///< the infeasible route's copies, in order
} sva_flow_frame_t;

#if SVA_FLOW_MAX_ARCS <= 65535L
typedef uint16_t sva_flow_arc_t;
#else
typedef uint32_t sva_flow_arc_t;
#endif
/// Nodes: UAVs, copy in/out pairs, the depot, the super sink.
#define SVA_FLOW_NODES (SVA_MAX_UAVS + (2L * SVA_FLOW_MAX_COPIES) + 2L)

/// flow's Lagrangian phase (flow_lagrange.c): target prices, and the labels of one
/// resource-constrained shortest path (a UAV's best route under the prices).
typedef struct {
    int64_t price[SVA_MAX_TARGETS];       ///< pi_t, in 1/SVA_FLOW_PRICE_SCALE cells
    int64_t path_price[SVA_MAX_TARGETS];  ///< the prices one shortest path sees
    int64_t grad[SVA_MAX_TARGETS];        ///< subgradient: need * y - visits
    uint16_t visits[SVA_MAX_TARGETS];     ///< UAVs whose best route serves t
    uint8_t closed[SVA_MAX_TARGETS];      ///< no route may serve t (the heuristic)
    int64_t label_cost[SVA_MAX_TARGETS * SVA_FLOW_LABELS];   ///< reduced cost so far
    int32_t label_fuel[SVA_MAX_TARGETS * SVA_FLOW_LABELS];   ///< fuel used so far
    uint32_t label_pred[SVA_MAX_TARGETS * SVA_FLOW_LABELS];  ///< previous label or none
    uint8_t label_count[SVA_MAX_TARGETS];
    /// Labels kept per target by the last shortest path: SVA_FLOW_LABELS, or more with
    /// cells free when fewer targets leave room (flow_label.c); target t's labels start
    /// at t * labels.
    uint16_t labels;
    uint16_t group[SVA_MAX_UAVS];    ///< first UAV in the same state (flow_graph.c)
    uint16_t path[SVA_MAX_TARGETS];  ///< the last shortest path's targets
    uint16_t path_len;
#if SVA_FLOW_LARGE
    bool real_paths;           ///< a full label set keeps real paths (flow_label.c)
    uint64_t evaluation_work;  ///< the last evaluation's work (flow_lagrange.c)
#endif
} sva_flow_lagrange_t;

/// Words of a route column's row set (one bit per master row).
#define SVA_FLOW_LP_WORDS (((uint32_t)SVA_FLOW_LP_ROWS + 31U) / 32U)

/// flow's route master (flow_lp.c): a fraction-free revised simplex. adj is
/// det(B) * B^-1 of the basis B, row-major; x, dual and alpha are scaled by det(B) too.
typedef struct {
    int64_t adj[SVA_FLOW_LP_ROWS * SVA_FLOW_LP_ROWS];
    int64_t x[SVA_FLOW_LP_ROWS];      ///< basic values
    int64_t dual[SVA_FLOW_LP_ROWS];   ///< row duals
    int64_t alpha[SVA_FLOW_LP_ROWS];  ///< the entering column in the basis
    int64_t rhs[SVA_FLOW_LP_ROWS];
    int64_t det;                       ///< det(B) up to sign, > 0
    uint16_t basic[SVA_FLOW_LP_ROWS];  ///< column of each basic position
    uint32_t col_rows[(uint32_t)SVA_FLOW_LP_COLS * SVA_FLOW_LP_WORDS];  ///< a route's rows
    int32_t col_cost[SVA_FLOW_LP_COLS];                                 ///< a route's cells
    uint8_t
        col_deficit[SVA_FLOW_LP_COLS];  ///< the dive's deficit of a fixed route: -A_r, cost big_m
    uint16_t fixed[SVA_MAX_UAVS];       ///< the dive's fixed routes (columns)
    uint16_t fixed_count;
    uint8_t forced[SVA_FLOW_LP_ROWS];  ///< the dive's targets partly served: w_t costs big_m
    uint8_t in_basis[SVA_FLOW_LP_ROWS + 2 + SVA_FLOW_LP_COLS];
    uint16_t group_row[SVA_MAX_UAVS];  ///< master row of a UAV's state
    int64_t lcm;                       ///< L: the lcm of the needs
    int64_t big_m;                     ///< cost of the coverage row's artificial
    int64_t cells_weight;              ///< a route's cost per cell: 1, or 0 (cover)
    uint16_t targets;                  ///< n: rows 0..n-1 are the targets
    uint16_t groups;                   ///< G: rows n..n+G-1; row n+G is the coverage
    uint16_t cols;                     ///< route columns so far
    uint16_t rows;
} sva_flow_lp_t;

// flow's proof from the master's prices (flow_enum.c), when SVA_FLOW_ENUM_ROUTES is not 0.
#if SVA_FLOW_ENUM_ROUTES > 0
#    define SVA_FLOW_ENUM_TARGETS 64  ///< a route's targets are one uint64_t

/// The routes a plan cheaper than the incumbent could fly, and the two depth-first
/// searches: the routes' (over the DAG of targets) and the exact cover's (over them).
typedef struct {
    uint64_t mask[SVA_FLOW_ENUM_ROUTES];   ///< a route's targets, bit c = copy c
    int64_t slack[SVA_FLOW_ENUM_ROUTES];   ///< its value over its state's best (prices')
    uint16_t state[SVA_FLOW_ENUM_ROUTES];  ///< its UAV state (first UAV, lagrange.group)
    uint16_t count;                        ///< routes kept
    int64_t price[SVA_FLOW_ENUM_TARGETS];  ///< the master's prices (prices' units)
    bool has_prices;                       ///< price[] holds them for this mission
    // The question asked: the prices in use (price, or the coverage master's), a cell's
    // weight (S for cost, 0 for coverage), the routes it may list, a covered target's
    // reward mu, the targets a plan covers at least (least) and so the targets a cover
    // may leave (skips).
    const int64_t* pi;
    int64_t alpha;
    uint16_t cap;
    int64_t share[SVA_FLOW_ENUM_TARGETS];  ///< the cover's bound on what a copy adds
    int64_t mu;
    int64_t least;
    uint16_t skips;
    uint64_t skipped;  ///< the cover's search: the copies it leaves
    /// Routes first[c] .. first[c + 1] - 1 start with copy c.
    uint16_t first[SVA_FLOW_ENUM_TARGETS + 1];
    int64_t tail[SVA_FLOW_ENUM_TARGETS];  ///< least value from copy c home, fuel ignored
    int64_t best[SVA_MAX_UAVS];           ///< a state's best route value (a lower bound)
    int64_t empty[SVA_MAX_UAVS];          ///< the slack of a state's empty route
    uint16_t members[SVA_MAX_UAVS];       ///< a state's UAVs
    uint16_t used[SVA_MAX_UAVS];          ///< the cover's routes of a state
    // The routes' search: the copy, its next arc, value and fuel at each depth.
    uint16_t at[SVA_FLOW_ENUM_TARGETS];
    uint32_t arc[SVA_FLOW_ENUM_TARGETS];
    int64_t value[SVA_FLOW_ENUM_TARGETS];
    int64_t fuel[SVA_FLOW_ENUM_TARGETS];
    // The cover's search: the route taken at each depth, and the best cover found.
    uint16_t pick[SVA_FLOW_ENUM_TARGETS + 1];
    uint16_t chosen[SVA_FLOW_ENUM_TARGETS];
    uint16_t chosen_count;
} sva_flow_enum_t;
#endif

// flow's coverage search (flow_cover.c), when SVA_FLOW_COVER_TARGETS is not 0.
#if SVA_FLOW_COVER_TARGETS > 0
#    define SVA_FLOW_COVER_T SVA_FLOW_COVER_TARGETS
#    define SVA_FLOW_COVER_U ((SVA_FLOW_COVER_UAVS > 0) ? SVA_FLOW_COVER_UAVS : 1)

/// A UAV's state on the coverage search's path.
typedef struct {
    int32_t x;
    int32_t y;
    int32_t free_at;  ///< ticks
    int32_t fuel;     ///< fuel left
    uint16_t served;  ///< targets on its route so far
} sva_flow_cover_uav_t;

/// The coverage search's chain bound (flow_cover_chains.c): per depth d, the most
/// targets from d on that k chains hold, and the flow that finds them.
typedef struct {
    uint8_t most[SVA_FLOW_COVER_T][SVA_FLOW_COVER_U + 1];  ///< [d][k]
    uint8_t known[SVA_FLOW_COVER_T];                       ///< row d's chains computed
    uint64_t after[SVA_FLOW_COVER_T];  ///< the later depths a depth precedes (bits)
    bool after_known;
    int32_t dist[(2 * SVA_FLOW_COVER_T) + 2];  ///< Bellman-Ford: cost from the source
    uint8_t parent[(2 * SVA_FLOW_COVER_T) + 2];
    uint8_t used[SVA_FLOW_COVER_T];  ///< on a chain
    uint8_t pred[SVA_FLOW_COVER_T];  ///< the target before it on its chain (UINT8_MAX: none)
    uint8_t succ[SVA_FLOW_COVER_T];  ///< the target after it on its chain (UINT8_MAX: none)
} sva_flow_chains_t;

/// The coverage search: a depth-first path over the targets in window order (depth d
/// decides the d-th), every UAV's state at each depth.
typedef struct {
    /// Least fuel that leaving the i-th target gets k more targets served and the UAV
    /// home (INT32_MAX: no route does).
    int32_t fuel_after[SVA_FLOW_COVER_T][SVA_FLOW_COVER_T + 1];
    sva_flow_cover_uav_t at[SVA_FLOW_COVER_T + 1][SVA_FLOW_COVER_U];
    uint16_t uav[SVA_FLOW_COVER_U];                    ///< the search's UAV k: mission UAV
    uint8_t cand[SVA_FLOW_COVER_T][SVA_FLOW_COVER_U];  ///< able to serve, cheapest first
    uint8_t pick[SVA_FLOW_COVER_T][SVA_FLOW_COVER_U];  ///< combination to try next
    uint8_t cand_count[SVA_FLOW_COVER_T];
    uint8_t step[SVA_FLOW_COVER_T];          ///< combinations, the target left, done
    uint32_t chosen[SVA_FLOW_COVER_T];       ///< UAVs serving it on the path (bits)
    uint16_t covered[SVA_FLOW_COVER_T + 1];  ///< targets covered above depth d
    uint16_t most[SVA_FLOW_COVER_U];         ///< bound: targets a UAV can still serve
    uint8_t reach[SVA_FLOW_COVER_T];         ///< bound: UAVs that can reach a target
    uint8_t need_left[SVA_FLOW_COVER_T];     ///< UAVs still to send (0: the kept routes cover it)
    uint16_t all[SVA_FLOW_COVER_U];          ///< every UAV not stranded (mission UAVs)
    uint8_t freed[SVA_FLOW_COVER_U];         ///< the search's UAVs, indices into all
    uint16_t by_need[SVA_FLOW_COVER_U + 1];  ///< bound: those targets by need
    int32_t leg[SVA_FLOW_COVER_U];           ///< candidates: cells to the target
    bool incumbent_first;                    ///< a target the incumbent leaves is left first
    sva_flow_chains_t chains;                ///< bound: the chains of the targets ahead
} sva_flow_cover_t;
#endif

/// flow's graph, relaxation and search state (flow_graph.c, flow_ssp.c, flow.c).
typedef struct {
    uint16_t uavs;    ///< U: node ids 0..U-1 are the UAVs
    uint16_t copies;  ///< C: copy c is in-node U+c, out-node U+C+c
    uint32_t arcs;
    uint16_t copy_target[SVA_FLOW_MAX_COPIES];
    uint16_t target_first_copy[SVA_MAX_TARGETS];  ///< copies of t are contiguous
    int64_t copy_reward[SVA_FLOW_MAX_COPIES];     ///< per covered copy: W / need
    int64_t reward_whole;                         ///< W: reward of a covered target
    int32_t need_max;                             ///< the mission's largest need
    bool reward_exact;                            ///< need * (W / need) == W for all
    uint8_t cost_parity;             ///< every plan's cost modulo 2 (flow.h, sva_flow_cost_floor)
    int32_t node_x[SVA_FLOW_NODES];  ///< arc cost = Manhattan distance
    int32_t node_y[SVA_FLOW_NODES];
    uint32_t out_start[SVA_FLOW_NODES + 1];  ///< arcs by tail (CSR)
    uint32_t in_start[SVA_FLOW_NODES + 1];   ///< arc ids by head
    uint16_t arc_tail[SVA_FLOW_MAX_ARCS];
    uint16_t arc_head[SVA_FLOW_MAX_ARCS];
    sva_flow_arc_t in_arc[SVA_FLOW_MAX_ARCS];
    uint8_t arc_flow[SVA_FLOW_MAX_ARCS];
    uint8_t arc_ban[SVA_FLOW_MAX_ARCS];        ///< banning levels (0: allowed)
    uint8_t copy_cover[SVA_FLOW_MAX_COPIES];   ///< flow on the copy's own arc
    uint8_t copy_units[SVA_FLOW_MAX_COPIES];   ///< its capacity: 1, need when pooled
    uint8_t copy_forced[SVA_FLOW_MAX_COPIES];  ///< forcing levels
    uint8_t copy_banned[SVA_FLOW_MAX_COPIES];  ///< banning levels
    // Shortest augmenting paths (Dijkstra with potentials, static binary heap).
    int64_t pot[SVA_FLOW_NODES];
    int64_t dist[SVA_FLOW_NODES];
    int32_t pred[SVA_FLOW_NODES];
    uint16_t heap[SVA_FLOW_NODES];
    uint16_t heap_pos[SVA_FLOW_NODES];
    uint8_t node_mark[SVA_FLOW_NODES];  ///< live / sent / settled bits
    uint16_t heap_size;
    int32_t sink_left;  ///< units the depot still takes
    int64_t value;      ///< relaxation: cost - rewards
    uint64_t work;
    uint64_t local_work;  ///< work one local search may start
    uint64_t proof_end;   ///< the Lagrangian phase's coverage proof may work until (flow.c)
#if SVA_FLOW_LARGE
    uint64_t budget;  ///< this plan's work budget (flow.c)
#endif
    // Scratch of the graph builder and of the rounding heuristic (flow_repair.c).
    int64_t target_lead[SVA_MAX_TARGETS];  ///< fuel labels (flow_graph.c)
    int64_t target_tail[SVA_MAX_TARGETS];
    uint16_t target_taken[SVA_MAX_TARGETS];
    int64_t route_cells[SVA_MAX_UAVS];
    int64_t insert_delta[SVA_MAX_UAVS];
    uint16_t insert_pos[SVA_MAX_UAVS];
    uint8_t uav_pick[SVA_MAX_UAVS];
    bool insert_backwards;  ///< the repair inserts in reverse window order (ruin and recreate)
#if SVA_FLOW_GRANULAR
    /// Past SVA_FLOW_LARGE_FROM targets: ruin and recreate's local search starts
    /// only from routes changed since it last looked at them, with granular moves, and
    /// there only from the visits next to a change (don't-look bits).
    bool local_changed_only;               ///< the local search is in that mode now
    uint8_t route_changed[SVA_MAX_UAVS];   ///< route u changed (set by every edit)
    uint8_t visit_awake[SVA_MAX_TARGETS];  ///< an edit came next to the visit since
                                           ///< the search last looked at it
    /// Each target's most related targets, nearest first (flow_ruin.c); near_count each.
    uint16_t near[SVA_MAX_TARGETS][SVA_FLOW_NEAR];
    uint16_t near_count;
    uint16_t route_of[SVA_MAX_TARGETS];  ///< a route serving the target (checked on use)
    uint16_t pos_of[SVA_MAX_TARGETS];    ///< its place there
    int32_t lead_of[SVA_MAX_TARGETS];    ///< cells from that route's UAV to it
    int32_t post_of[SVA_MAX_TARGETS];    ///< and from it to the depot
    uint16_t uav_tried[SVA_MAX_UAVS];    ///< try_epoch: already tried for this visit
    uint16_t try_epoch;
    /// Ruin and recreate's current plan, as the incumbent's successor lists (flow_ruin.c:
    /// a large mission's rounds accept a plan within a threshold of it).
    uint16_t cur_first[SVA_MAX_UAVS];
    uint16_t cur_next[SVA_FLOW_MAX_COPIES];
    int64_t cur_value;
    /// A large mission's round: the visits its strings took out, in the order the repair
    /// puts them back first (flow_ruin.c), and the rounds' pseudo-random state.
    uint16_t ruined[SVA_FLOW_RUINED_MOST];
    uint16_t ruined_count;
    /// The string rounds at their rate could not afford one round per target, and are
    /// shallow now (flow_ruin.c): the local search's passes and reach are cut (flow.h).
    bool local_shallow;
    uint32_t ruin_random;
#endif
    uint16_t spare_route[SVA_MAX_ROUTE_TARGETS];       ///< a route's tail in an exchange
    uint16_t trade_pos[SVA_MAX_UAVS];                  ///< where a traded target was
    int32_t piece_pre[2][SVA_MAX_ROUTE_TARGETS + 1];   ///< two routes' cells up to a stop
    int32_t piece_post[2][SVA_MAX_ROUTE_TARGETS + 1];  ///< and from a stop on
    uint16_t pred_node[SVA_FLOW_NODES];
    int64_t pot_source;
    // Best plan found: successor lists over copies (0xFFFF ends a route).
    uint16_t inc_first[SVA_MAX_UAVS];
    uint16_t inc_next[SVA_FLOW_MAX_COPIES];
    int64_t inc_value;
    bool has_inc;
    // The plan offered that is best against the standing plan (sva_planner_t.standing):
    // coverage first, then cost + change_penalty * changed visits (flow_incumbent.c).
    const struct sva_plan* standing;  ///< while it counts (penalty > 0), else NULL
    bool has_pen;
#if SVA_FLOW_STANDING
    uint16_t pen_first[SVA_MAX_UAVS];
    uint16_t pen_next[SVA_FLOW_MAX_COPIES];
    int64_t pen_value;  ///< cost + change_penalty * changed visits
    uint16_t pen_covered;
#endif
    uint16_t depth;
    int64_t max_cost;  ///< no flow or plan costs more (rewards)
    sva_flow_frame_t stack[SVA_FLOW_MAX_DEPTH];
    sva_flow_lagrange_t lagrange;
    sva_flow_lp_t lp;
#if SVA_FLOW_ENUM_ROUTES > 0
    sva_flow_enum_t enumeration;
#endif
#if SVA_FLOW_COVER_TARGETS > 0
    sva_flow_cover_t cover;
#endif
} sva_flow_work_t;

/// All of the planner's working memory.
typedef struct {
    // Planning state of each UAV (index = mission order) and target.
    int32_t uav_x[SVA_MAX_UAVS];
    int32_t uav_y[SVA_MAX_UAVS];
    int64_t uav_free_at[SVA_MAX_UAVS];  ///< ticks
    int64_t uav_fuel_left[SVA_MAX_UAVS];
    uint16_t uav_order[SVA_MAX_UAVS];        ///< UAV indices by id
    uint16_t target_order[SVA_MAX_TARGETS];  ///< target indices by (start, end, id)
    uint16_t target_served[SVA_MAX_TARGETS];
    uint16_t cluster_end[SVA_MAX_TARGETS];  ///< exclusive end (in target_order)
    uint16_t cluster_count;
    sva_tp_t tp;
    sva_tableau_t tableau;
    sva_hga_work_t hga;
    sva_bfa_work_t bfa;
    sva_flow_work_t flow;
    /// sva_replan()'s standing plan for the sva_plan() call it makes; NULL otherwise.
    const struct sva_plan* standing;
} sva_planner_priv_t;

/// One UAV of a live mission (core/src/live/): where its route in force starts, and
/// the route.
typedef struct {
    int32_t x;  ///< the route starts here,
    int32_t y;
    int64_t fuel;        ///< with this much fuel,
    int64_t from_ticks;  ///< at this tick (it may leave then)
    int32_t busy_with;   ///< until from_ticks: the target under way there, or -1
    bool lost;           ///< out of service
    uint16_t route_count;
    uint16_t route[SVA_MAX_ROUTE_TARGETS];  ///< indices into mission.targets, in visit order
} sva_live_uav_t;

/// A live mission's own state and the replan's scratch (sva_live_t.priv).
typedef struct {
    sva_live_uav_t uavs[SVA_MAX_UAVS];
    int32_t target_ended[SVA_MAX_TARGETS];  ///< tick it was lost or cancelled
    uint16_t uav_of[SVA_MAX_UAVS];          ///< residual UAV -> mission UAV
    uint16_t target_of[SVA_MAX_TARGETS];    ///< residual target -> mission target
    int32_t busy_with[SVA_MAX_UAVS];        ///< residual UAV's target under way, or -1
    int32_t residual_of[SVA_MAX_TARGETS];   ///< mission target -> residual target, or -1
    uint16_t served[SVA_MAX_TARGETS];       ///< UAVs per residual target (scratch)
} sva_live_priv_t;

#ifdef __cplusplus
}
#endif

#endif  // SVA_PRIVATE_H
