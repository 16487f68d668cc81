// flow_ssp.c -- flow's relaxation: a min-cost flow over the time-feasibility graph
// (flow_graph.c) by successive shortest augmenting paths (DESIGN.md section 8).
//
// Supplies: every UAV that is not stranded (one unit), and the out-node of every
// forced copy (its own arc has lower bound 1, so the unit is pre-sent). Demands: the
// depot takes one unit per UAV, a forced copy's in-node one. Costs: arc distances,
// minus the copy's reward on a copy's own arc. Potentials start as DAG shortest
// distances (copy ids are a topological order), so reduced costs are never negative;
// the first unit follows that pass's shortest path, and each further augmenting path
// is a Dijkstra run over a static binary heap. A copy's own arc carries up to its
// copy_units (1; a target's need in the pooled graph), explicit arcs are uncapacitated
// (with unit copies no arc can carry two units: its tail holds at most one), and
// every unit is whole; the relaxation value is a lower bound on cost - reward of
// every plan that satisfies the node's branching rules.
#include "flow.h"

#define FLOW_INF (INT64_MAX / 2)

// node_mark[] bits (unsigned constants: they are masked into a uint8_t).
#define MARK_LIVE    1U  // reachable from a supply: may ever carry flow
#define MARK_SUPPLY  2U  // a supply node whose unit has not left yet
#define MARK_DONE    4U  // settled in the current Dijkstra run
#define MARK_DEFICIT 8U  // a forced copy's in-node still waiting for its unit

// pred[] codes: arc e forward, arc e backward, a copy's own arc forward or backward,
// a deficit draining into the super sink, the start of a path.
#define PRED_START (-1)

typedef struct {
    uint16_t u;  // UAVs
    uint16_t c;  // copies
    uint32_t a;  // arcs
    uint16_t depot;
    uint16_t sink;
} flow_shape_t;

static flow_shape_t shape_of(const sva_flow_work_t* w)
{
    const flow_shape_t s = {w->uavs, w->copies, w->arcs, (uint16_t)(w->uavs + (2U * w->copies)),
                            (uint16_t)(w->uavs + (2U * w->copies) + 1U)};
    return s;
}

static bool copy_usable(const sva_flow_work_t* w, uint16_t c)
{
    return w->copy_banned[c] == 0U;
}

// Whether the explicit arcs out of v may be used: not when v is a banned copy's
// out-node (tested once per node).
static bool tail_usable(const sva_flow_work_t* w, const flow_shape_t* s, uint16_t v)
{
    return (v < (uint16_t)(s->u + s->c)) || (v >= s->depot) ||
           copy_usable(w, (uint16_t)(v - s->u - s->c));
}

// Whether explicit arc e out of a usable tail may be used under the current branching
// rules: not banned, and not into a banned copy.
static bool head_usable(const sva_flow_work_t* w, const flow_shape_t* s, uint32_t e)
{
    const uint16_t h = w->arc_head[e];
    return (w->arc_ban[e] == 0U) &&
           ((h < s->u) || (h >= (uint16_t)(s->u + s->c)) || copy_usable(w, (uint16_t)(h - s->u)));
}

// Length of an arc between v and h (sva_flow_arc_cost with its tail or head known).
static int32_t leg(const sva_flow_work_t* w, uint16_t v, uint16_t h)
{
    return sva_distance(w->node_x[v], w->node_y[v], w->node_x[h], w->node_y[h]);
}

// ---------------------------------------------------------------------------------
// Binary heap keyed by dist[], with positions for decrease-key.

static void heap_swap(sva_flow_work_t* w, uint16_t i, uint16_t j)
{
    const uint16_t a = w->heap[i];
    const uint16_t b = w->heap[j];
    w->heap[i] = b;
    w->heap[j] = a;
    w->heap_pos[b] = i;
    w->heap_pos[a] = j;
}

static bool heap_less(const sva_flow_work_t* w, uint16_t i, uint16_t j)
{
    const uint16_t a = w->heap[i];
    const uint16_t b = w->heap[j];
    const int64_t dist_a = w->dist[a];
    const int64_t dist_b = w->dist[b];
    return (dist_a < dist_b) || ((dist_a == dist_b) && (a < b));
}

static void heap_up(sva_flow_work_t* w, uint16_t start)
{
    uint16_t i = start;
    while (i > 0U) {
        const uint16_t parent = (uint16_t)((i - 1U) / 2U);
        if (!heap_less(w, i, parent)) {
            break;
        }
        heap_swap(w, i, parent);
        i = parent;
    }
}

static void heap_push_or_lower(sva_flow_work_t* w, uint16_t v)
{
    if (w->heap_pos[v] == UINT16_MAX) {
        w->heap[w->heap_size] = v;
        w->heap_pos[v] = w->heap_size;
        w->heap_size++;
    }
    heap_up(w, w->heap_pos[v]);
}

static uint16_t heap_pop(sva_flow_work_t* w)
{
    const uint16_t top = w->heap[0];
    w->heap_size--;
    if (w->heap_size > 0U) {
        heap_swap(w, 0U, w->heap_size);
    }
    w->heap_pos[top] = UINT16_MAX;
    uint16_t i = 0U;
    for (;;) {
        const uint32_t l = (2U * (uint32_t)i) + 1U;
        const uint32_t r = l + 1U;
        uint16_t m = i;
        if (l < w->heap_size) {
            const uint16_t left = (uint16_t)l;
            m = heap_less(w, left, m) ? left : m;
        }
        if (r < w->heap_size) {
            const uint16_t right = (uint16_t)r;
            m = heap_less(w, right, m) ? right : m;
        }
        if (m == i) {
            break;
        }
        heap_swap(w, i, m);
        i = m;
    }
    return top;
}

// ---------------------------------------------------------------------------------

static int64_t own_cost(const sva_flow_work_t* w, uint16_t c)
{
    return -w->copy_reward[c];
}

static bool is_deficit(const sva_flow_work_t* w, const flow_shape_t* s, uint16_t v)
{
    return ((v == s->depot) && (w->sink_left > 0)) || ((w->node_mark[v] & MARK_DEFICIT) != 0U);
}

// Offers h the distance d through pred code p from node v.
static inline void offer(sva_flow_work_t* w, uint16_t v, uint16_t h, int64_t cost, int32_t p)
{
    if (((w->node_mark[h] & MARK_LIVE) == 0U) || ((w->node_mark[h] & MARK_DONE) != 0U)) {
        return;
    }
    const int64_t reduced = cost + w->pot[v] - w->pot[h];
    SVA_ASSERT(reduced >= 0);
    const int64_t d = w->dist[v] + reduced;
    if (d < w->dist[h]) {
        w->dist[h] = d;
        w->pred[h] = p;
        w->pred_node[h] = v;
        heap_push_or_lower(w, h);
    }
}

// Every residual arc leaving v (DESIGN.md section 8 lists them).
static void scan(sva_flow_work_t* w, const flow_shape_t* s, uint16_t v)
{
    const int32_t a = (int32_t)s->a;
    const uint32_t out_end = w->out_start[v + 1U];
    if (tail_usable(w, s, v)) {
        for (uint32_t e = w->out_start[v]; e < out_end; e++) {
            if (head_usable(w, s, e)) {
                offer(w, v, w->arc_head[e], leg(w, v, w->arc_head[e]), (int32_t)e);
            }
        }
    }
    w->work += (uint64_t)out_end - (uint64_t)w->out_start[v];
    const uint32_t in_end = w->in_start[v + 1U];
    for (uint32_t k = w->in_start[v]; k < in_end; k++) {
        const uint32_t e = w->in_arc[k];
        if (w->arc_flow[e] != 0U) {
            offer(w, v, w->arc_tail[e], -(int64_t)leg(w, w->arc_tail[e], v), a + (int32_t)e);
        }
    }
    w->work += (uint64_t)in_end - (uint64_t)w->in_start[v];
    if ((v >= s->u) && (v < (uint16_t)(s->u + s->c))) {
        const uint16_t c = (uint16_t)(v - s->u);
        if ((w->copy_forced[c] == 0U) && (w->copy_cover[c] < w->copy_units[c]) &&
            copy_usable(w, c)) {
            offer(w, v, (uint16_t)(v + s->c), own_cost(w, c), (2 * a) + (int32_t)c);
        }
    } else if ((v >= (uint16_t)(s->u + s->c)) && (v < s->depot)) {
        const uint16_t c = (uint16_t)(v - s->u - s->c);
        if ((w->copy_forced[c] == 0U) && (w->copy_cover[c] != 0U)) {
            offer(w, v, (uint16_t)(v - s->c), -own_cost(w, c),
                  (2 * a) + (int32_t)s->c + (int32_t)c);
        }
    } else {
        // the depot and the sink: only the explicit arcs above
    }
    if (is_deficit(w, s, v)) {
        offer(w, v, s->sink, 0, PRED_START - 1);
    }
}

// Potentials: shortest distances from the supplies over the residual graph of the
// empty flow, which is acyclic in node-id order. Marks the live nodes.
static bool init_potentials(sva_flow_work_t* w, const flow_shape_t* s)
{
    const uint32_t nodes = (uint32_t)s->sink + 1U;
    for (uint32_t v = 0U; v < nodes; v++) {
        w->dist[v] = FLOW_INF;
        w->node_mark[v] = 0U;
        w->heap_pos[v] = UINT16_MAX;
    }
    for (uint16_t u = 0U; u < s->u; u++) {
        if (w->out_start[u + 1U] > w->out_start[u]) {  // not stranded
            w->dist[u] = 0;
            w->pred[u] = PRED_START;
            w->node_mark[u] = MARK_SUPPLY;
        }
    }
    w->sink_left = 0;
    for (uint16_t u = 0U; u < s->u; u++) {
        w->sink_left += ((w->node_mark[u] & MARK_SUPPLY) != 0U) ? 1 : 0;
    }
    for (uint16_t c = 0U; c < s->c; c++) {
        w->copy_cover[c] = 0U;
        if ((w->copy_forced[c] != 0U) && copy_usable(w, c)) {
            w->dist[s->u + s->c + c] = 0;
            w->pred[s->u + s->c + c] = PRED_START;
            w->node_mark[s->u + s->c + c] = MARK_SUPPLY;
            w->node_mark[s->u + c] = MARK_DEFICIT;
        }
    }
    for (uint32_t e = 0U; e < s->a; e++) {
        w->arc_flow[e] = 0U;
    }
    // Relax in topological order: UAVs, then each copy's in- then out-node, depot.
    for (uint32_t k = 0U; k < nodes; k++) {
        uint16_t v = (uint16_t)k;
        if ((k >= s->u) && (k < s->depot)) {
            const uint32_t j = k - s->u;  // 2c: in-node of copy c, 2c + 1: its out-node
            v = (uint16_t)(s->u + (j / 2U) + (((j % 2U) != 0U) ? s->c : 0U));
        }
        if (w->dist[v] >= FLOW_INF) {
            continue;
        }
        w->node_mark[v] |= MARK_LIVE;
        const uint32_t out_end = w->out_start[v + 1U];
        if (tail_usable(w, s, v)) {
            for (uint32_t e = w->out_start[v]; e < out_end; e++) {
                const uint16_t h = w->arc_head[e];
                const int64_t d = w->dist[v] + leg(w, v, h);
                if ((d < w->dist[h]) && head_usable(w, s, e)) {
                    w->dist[h] = d;
                    w->pred[h] = (int32_t)e;
                    w->pred_node[h] = v;
                }
            }
        }
        w->work += (uint64_t)out_end - (uint64_t)w->out_start[v];
        if ((v >= s->u) && (v < (uint16_t)(s->u + s->c))) {
            const uint16_t c = (uint16_t)(v - s->u);
            const int64_t d = w->dist[v] + own_cost(w, c);
            if ((w->copy_forced[c] == 0U) && copy_usable(w, c) && (d < w->dist[v + s->c])) {
                w->dist[v + s->c] = d;
                w->pred[v + s->c] = (2 * (int32_t)s->a) + (int32_t)c;
                w->pred_node[v + s->c] = v;
            }
        }
        if (is_deficit(w, s, v) && (w->dist[v] < w->dist[s->sink])) {
            w->dist[s->sink] = w->dist[v];
            w->pred[s->sink] = PRED_START - 1;
            w->pred_node[s->sink] = v;
        }
    }
    for (uint16_t c = 0U; c < s->c; c++) {
        if (((w->node_mark[s->u + c] & MARK_DEFICIT) != 0U) &&
            ((w->node_mark[s->u + c] & MARK_LIVE) == 0U)) {
            return false;  // a forced copy no unit can reach
        }
    }
    for (uint32_t v = 0U; v < nodes; v++) {
        w->pot[v] = ((w->node_mark[v] & MARK_LIVE) != 0U) ? w->dist[v] : 0;
    }
    w->pot_source = 0;
    return true;
}

// Flips the path that pred[] and pred_node[] trace from the sink back to its supply.
static void flip_path(sva_flow_work_t* w, const flow_shape_t* s)
{
    const int32_t a = (int32_t)s->a;
    uint16_t v = w->pred_node[s->sink];
    if (v == s->depot) {
        w->sink_left--;
    } else {
        w->node_mark[v] &= (uint8_t)~MARK_DEFICIT;
    }
    while (w->pred[v] != PRED_START) {
        const int32_t p = w->pred[v];
        if (p < a) {
            w->arc_flow[p]++;
        } else if (p < (2 * a)) {
            w->arc_flow[p - a]--;
        } else if (p < ((2 * a) + (int32_t)s->c)) {
            w->copy_cover[p - (2 * a)]++;
        } else {
            w->copy_cover[p - (2 * a) - (int32_t)s->c]--;
        }
        v = w->pred_node[v];
    }
    w->node_mark[v] &= (uint8_t)~MARK_SUPPLY;
}

// One shortest augmenting path from any waiting supply to the sink; false if none.
static bool augment(sva_flow_work_t* w, const flow_shape_t* s)
{
    const uint32_t nodes = (uint32_t)s->sink + 1U;
    w->heap_size = 0U;
    for (uint32_t v = 0U; v < nodes; v++) {
        w->dist[v] = FLOW_INF;
        w->node_mark[v] &= (uint8_t)~MARK_DONE;
        if (((w->node_mark[v] & MARK_SUPPLY) != 0U) && ((w->node_mark[v] & MARK_LIVE) != 0U)) {
            w->dist[v] = w->pot_source - w->pot[v];
            SVA_ASSERT(w->dist[v] >= 0);
            w->pred[v] = PRED_START;
            heap_push_or_lower(w, (uint16_t)v);
        }
    }
    while ((w->heap_size > 0U) && ((w->node_mark[s->sink] & MARK_DONE) == 0U)) {
        const uint16_t v = heap_pop(w);
        w->node_mark[v] |= MARK_DONE;
        if (v != s->sink) {
            scan(w, s, v);
        }
    }
    while (w->heap_size > 0U) {
        (void)heap_pop(w);
    }
    if ((w->node_mark[s->sink] & MARK_DONE) == 0U) {
        return false;
    }
    flip_path(w, s);
    // Keep reduced costs non-negative: nodes beyond the sink's distance move by it.
    const int64_t reach = w->dist[s->sink];
    for (uint32_t k = 0U; k < nodes; k++) {
        if ((w->node_mark[k] & MARK_LIVE) != 0U) {
            w->pot[k] += (w->dist[k] < reach) ? w->dist[k] : reach;
        }
    }
    return true;
}

static int64_t relaxation_value(const sva_flow_work_t* w, const flow_shape_t* s)
{
    int64_t value = 0;
    for (uint32_t e = 0U; e < s->a; e++) {
        if (w->arc_flow[e] != 0U) {
            value += (int64_t)w->arc_flow[e] * sva_flow_arc_cost(w, e);
        }
    }
    for (uint16_t c = 0U; c < s->c; c++) {
        if ((w->copy_forced[c] != 0U) && copy_usable(w, c)) {
            value -= w->copy_reward[c];  // forced copies exist in the unit graph alone
        } else {
            value -= (int64_t)w->copy_cover[c] * w->copy_reward[c];
        }
    }
    return value;
}

bool sva_flow_solve(sva_flow_work_t* w, sva_stats_t* stats)
{
    const flow_shape_t s = shape_of(w);
    stats->flow_solves++;
    if (!init_potentials(w, &s)) {
        return false;
    }
    uint32_t units = 0U;
    for (uint32_t v = 0U; v <= s.sink; v++) {
        units += ((w->node_mark[v] & MARK_SUPPLY) != 0U) ? 1U : 0U;
    }
    // The first unit takes the shortest path the potentials' pass found: under
    // potentials equal to the shortest distances every reduced distance is 0, so a
    // Dijkstra run would change no potential.
    for (uint32_t k = 0U; k < units; k++) {
        stats->flow_augmentations++;
        if ((k == 0U) && (w->dist[s.sink] < FLOW_INF)) {
            flip_path(w, &s);
        } else {
            if (!augment(w, &s)) {
                return false;
            }
        }
    }
    w->value = relaxation_value(w, &s);
    return true;
}

bool sva_flow_covered(const sva_flow_work_t* w, uint16_t c)
{
    return (w->copy_cover[c] != 0U) || ((w->copy_forced[c] != 0U) && (w->copy_banned[c] == 0U));
}

uint16_t sva_flow_route(const sva_flow_work_t* w, uint16_t u, uint16_t* out, uint16_t cap)
{
    const flow_shape_t s = shape_of(w);
    uint16_t n = 0U;
    uint16_t v = u;
    for (;;) {
        uint16_t next = s.depot;
        for (uint32_t e = w->out_start[v]; e < w->out_start[v + 1U]; e++) {
            if (w->arc_flow[e] != 0U) {
                next = w->arc_head[e];
                break;
            }
        }
        if (next == s.depot) {
            return n;
        }
        const uint16_t c = (uint16_t)(next - s.u);
        if (n >= cap) {
            // Not an error: a relaxation's route may be longer than the rounding's cap
            // SVA_MAX_ROUTE_TARGETS (flow_round.c cuts it; branching splits it).
            return n;
        }
        out[n] = c;
        n++;
        v = (uint16_t)(s.u + s.c + c);
    }
}
