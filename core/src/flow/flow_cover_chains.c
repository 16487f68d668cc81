// flow_cover_chains.c -- the coverage search's chain bound (DESIGN.md section 8,
// "Coverage search"): how many of the targets from depth d on (window order) k chains
// can hold.
//
// Target a precedes target b when a UAV can serve both, a first: a comes first in
// window order, and a's end plus the flight from a to b is at most b's start. That
// order is transitive (triangle inequality), so a UAV's targets are a chain of it, and
// targets no two of which are in a chain (an antichain) take distinct UAVs. Where every
// target left needs at least q UAVs and u UAVs are left, an antichain of the targets
// covered holds at most u / q of them; so the targets covered are at most the most that
// k = u / q chains hold (Greene and Kleitman: a set whose antichains have at most k
// elements is the union of k chains). Fuel and reach are left out: the search's other
// bound has them. At need 2 and 3 this bound is what proves the coverage of
// synchronised visits, where one pooled over needs cannot.
//
// That most is a flow of k units from a source through the targets' split nodes
// (in -> out: one unit, cost -1) to a sink, at least cost: successive shortest paths,
// each found by Bellman-Ford in sweeps along the window order (forward arcs) and back
// (the arcs of the flow undone), until a sweep changes nothing. The flow is the chains
// themselves: each target on one has the target before and after it.
//
// A depth's row is computed when a search first asks for it, as far as the chains asked
// for, and kept for the rest of the plan (sva_flow_cover_chains_forget at its start):
// it depends only on the targets.
#include "flow.h"

#if SVA_FLOW_COVER_TARGETS > 0

#    define NODE_SOURCE 0U
#    define NODE_SINK   1U
#    define FAR         INT32_MAX
#    define NONE        UINT8_MAX
// Work: an arc here is a bit test and an add, about a quarter of the arc scan that a
// unit counts elsewhere (measured: 30,000 units of this bound took 70 to 90 us where the
// whole plan ran at about 10 ns a unit).
#    define ARCS_PER_UNIT 4U

// Node ids of the i-th target of the suffix (its split nodes).
static uint8_t in_node(uint16_t i)
{
    return (uint8_t)(2U + (2U * i));
}

static uint8_t out_node(uint16_t i)
{
    return (uint8_t)(3U + (2U * i));
}

// s->after: per depth a, the depths b > a that a precedes (bits).
static void fill_after(sva_flow_chains_t* s, const sva_planner_priv_t* priv, const sva_mission_t* m,
                       uint64_t* work)
{
    const uint16_t n = m->target_count;
    for (uint16_t a = 0U; a < n; a++) {
        s->after[a] = 0U;
        for (uint16_t b = (uint16_t)(a + 1U); b < n; b++) {
            if (sva_flow_targets_chain(m, priv->target_order[a], priv->target_order[b])) {
                s->after[a] |= (uint64_t)1U << b;
            }
        }
        *work += (uint64_t)n - a;
    }
    s->after_known = true;
}

// Relaxes arc (from, to) of cost `cost`; true if it shortened the path to `to`.
static bool relax(sva_flow_chains_t* s, uint8_t from, uint8_t to, int32_t cost)
{
    if ((s->dist[from] == FAR) || ((s->dist[from] + cost) >= s->dist[to])) {
        return false;
    }
    s->dist[to] = s->dist[from] + cost;
    s->parent[to] = from;
    return true;
}

// One sweep along the window order over the suffix from depth d (count targets): the
// source's arcs, in -> out, out -> the targets it precedes and the sink. Returns
// whether a path shortened; adds to *work a unit per ARCS_PER_UNIT arcs seen.
static bool sweep_forward(sva_flow_chains_t* s, uint16_t d, uint16_t count, uint64_t* work)
{
    bool changed = false;
    uint64_t arcs = 0U;
    for (uint16_t i = 0U; i < count; i++) {
        if ((s->used[i] == 0U) || (s->pred[i] != NONE)) {
            changed = relax(s, NODE_SOURCE, in_node(i), 0) || changed;
        }
        if (s->used[i] == 0U) {
            changed = relax(s, in_node(i), out_node(i), -1) || changed;
        }
        uint64_t next = s->after[d + i] >> d;
        if ((s->used[i] != 0U) && (s->succ[i] != NONE)) {
            next &= ~((uint64_t)1U << s->succ[i]);  // the flow's own arc
        }
        for (uint16_t b = (uint16_t)(i + 1U); (b < count) && ((next >> b) != 0U); b++) {
            if (((next >> b) & 1U) != 0U) {
                changed = relax(s, out_node(i), in_node(b), 0) || changed;
                arcs++;
            }
        }
        if ((s->used[i] == 0U) || (s->succ[i] != NONE)) {
            changed = relax(s, out_node(i), NODE_SINK, 0) || changed;
        }
        arcs += 3U;
    }
    *work += arcs / ARCS_PER_UNIT;
    return changed;
}

// One sweep back over the suffix: the flow's arcs undone (out -> in of a target on a
// chain, in -> out of the target before it).
static bool sweep_back(sva_flow_chains_t* s, uint16_t count, uint64_t* work)
{
    *work += ((uint64_t)count * 2U) / ARCS_PER_UNIT;
    bool changed = false;
    for (uint16_t i = count; i > 0U; i--) {
        const uint16_t t = (uint16_t)(i - 1U);
        if (s->used[t] != 0U) {
            changed = relax(s, out_node(t), in_node(t), 1) || changed;
            if (s->pred[t] != NONE) {
                changed = relax(s, in_node(t), out_node(s->pred[t]), 0) || changed;
            }
        }
    }
    return changed;
}

// The shortest path from the source to the sink; returns its cost (the targets it
// adds, negated; 0 when it adds none).
static int32_t shortest_path(sva_flow_chains_t* s, uint16_t d, uint16_t count, uint64_t* work)
{
    const uint16_t nodes = (uint16_t)(2U + (2U * count));
    for (uint16_t v = 0U; v < nodes; v++) {
        s->dist[v] = FAR;
        s->parent[v] = NONE;
    }
    s->dist[NODE_SOURCE] = 0;
    // The flow's residual graph has no negative cycle (it is a least-cost flow): at most
    // `nodes` rounds settle every path.
    bool changed = true;
    for (uint16_t round = 0U; changed && (round < nodes); round++) {
        const bool ahead = sweep_forward(s, d, count, work);
        const bool back = sweep_back(s, count, work);
        changed = ahead || back;
    }
    return (s->dist[NODE_SINK] == FAR) ? 0 : s->dist[NODE_SINK];
}

// The path found into the chains: arcs forward set pred and succ, an arc out -> in
// drops the target (the other arcs undone are set again by the path's next arcs).
static void take_path(sva_flow_chains_t* s)
{
    uint8_t v = NODE_SINK;
    while (v != NODE_SOURCE) {
        const uint8_t u = s->parent[v];
        if (v == NODE_SINK) {
            s->succ[(u - 3U) / 2U] = NONE;
        } else if (u == NODE_SOURCE) {
            s->pred[(v - 2U) / 2U] = NONE;
        } else if (((u & 1U) != 0U) && ((v & 1U) == 0U)) {
            const uint8_t a = (uint8_t)((u - 3U) / 2U);
            const uint8_t b = (uint8_t)((v - 2U) / 2U);
            if (a == b) {
                s->used[a] = 0U;
            } else {
                s->succ[a] = b;
                s->pred[b] = a;
            }
        } else if (((u - 2U) / 2U) == ((v - 3U) / 2U)) {
            s->used[(u - 2U) / 2U] = 1U;
        } else {
            // in -> out of another target: an arc into that target undone
        }
        v = u;
    }
}

uint16_t sva_flow_cover_chains(sva_flow_chains_t* s, const sva_planner_priv_t* priv,
                               const sva_mission_t* m, uint16_t d, uint16_t k, uint64_t* work)
{
    const uint16_t count = (uint16_t)(m->target_count - d);
    if (k >= count) {
        return count;  // at most every target
    }
    if (k > (uint16_t)s->known[d]) {
        // Row d up to k chains, from no flow.
        if (!s->after_known) {
            fill_after(s, priv, m, work);
        }
        for (uint16_t i = 0U; i < count; i++) {
            s->used[i] = 0U;
        }
        uint16_t held = 0U;
        bool grows = true;  // a chain more may hold more targets (the gains only shrink)
        s->most[d][0] = 0U;
        for (uint16_t j = 1U; j <= k; j++) {
            if (grows && (held < count)) {
                const int32_t gain = -shortest_path(s, d, count, work);
                grows = gain > 0;
                if (grows) {
                    take_path(s);
                    held = (uint16_t)(held + (uint16_t)gain);
                }
            }
            s->most[d][j] = (uint8_t)held;
        }
        s->known[d] = (uint8_t)k;
    }
    return s->most[d][k];
}

void sva_flow_cover_chains_forget(sva_planner_priv_t* priv)
{
    sva_flow_chains_t* s = &priv->flow.cover.chains;
    s->after_known = false;
    for (uint16_t d = 0U; d < (uint16_t)SVA_FLOW_COVER_T; d++) {
        s->known[d] = 0U;
    }
}

#endif
