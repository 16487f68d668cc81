// Plans on the wire: the transfer frame sequence, the plan CRC-32, the wire limits of
// a mission and the conversion of a core plan into items.

#include "sva/sva_can.h"

#include "can_internal.h"

uint32_t sva_can_crc32_frame(uint32_t crc, const sva_can_frame_t* frame)
{
    uint8_t bytes[7];
    unsigned i;
    for (i = 0; i < 7U; ++i) {
        bytes[i] = frame->data[i];
    }
    bytes[0] = (uint8_t)(bytes[0] & 0xF0U);  // counter nibble cleared: retries give one CRC
    return sva_can_crc32(crc, bytes, sizeof bytes);
}

sva_can_status_t sva_can_transfer_frame(const sva_can_plan_t* plan, uint32_t index, uint8_t counter,
                                        uint32_t plan_crc, sva_can_frame_t* out)
{
    sva_can_msg_t m;
    const uint32_t n = plan->item_count;
    m.counter = (uint8_t)(counter & 0x0FU);
    if (index == 0U) {
        m.kind = SVA_CAN_MSG_PLAN_BEGIN;
        m.u.begin.version = SVA_CAN_PROTOCOL_VERSION;
        m.u.begin.plan_id = plan->plan_id;
        m.u.begin.item_count = plan->item_count;
        m.u.begin.algorithm = plan->algorithm;
        m.u.begin.plan_status = plan->plan_status;
        m.u.begin.route_count = plan->route_count;
    } else if (index <= 2U * n) {
        const uint32_t item_index = (index - 1U) / 2U;
        const sva_can_item_t* it = &plan->items[item_index];
        if ((index % 2U) == 1U) {
            m.kind = SVA_CAN_MSG_PLAN_ITEM;
            m.u.item.uav_id = it->uav_id;
            m.u.item.target_id = it->target_id;
            m.u.item.x = it->x;
            m.u.item.y = it->y;
        } else {
            m.kind = SVA_CAN_MSG_PLAN_ITEM_TIME;
            m.u.item_time.item_seq = (uint8_t)(item_index & 0x0FU);
            m.u.item_time.arrive_by_ticks = it->arrive_by_ticks;
            m.u.item_time.hold_until_ticks = it->hold_until_ticks;
        }
    } else if (index == (2U * n) + 1U) {
        m.kind = SVA_CAN_MSG_PLAN_COMMIT;
        m.u.commit.plan_id = plan->plan_id;
        m.u.commit.plan_crc = plan_crc;
    } else {
        return SVA_CAN_ERR_ARGUMENT;
    }
    return sva_can_encode(&m, out);
}

uint32_t sva_can_plan_crc(const sva_can_plan_t* plan)
{
    uint32_t crc = 0U;
    uint32_t index;
    if ((plan == NULL) || (plan->item_count > SVA_CAN_MAX_ITEMS)) {
        return 0U;
    }
    for (index = 0U; index <= 2U * (uint32_t)plan->item_count; ++index) {
        sva_can_frame_t f;
        if (sva_can_transfer_frame(plan, index, 0U, 0U, &f) != SVA_CAN_OK) {
            return 0U;  // a field wider than its signal: such a plan cannot be sent
        }
        crc = sva_can_crc32_frame(crc, &f);
    }
    return crc;
}

static sva_can_status_t fail(sva_diag_t* diag, sva_field_t field, int32_t index, int64_t value,
                             sva_rule_t rule, int64_t limit, const char* limit_name)
{
    sva_diag_set(diag, field, rule, index, value, limit, limit_name);
    return SVA_CAN_ERR_LIMIT;
}

sva_can_status_t sva_can_mission_check(const sva_mission_t* mission, sva_diag_t* diag)
{
    uint32_t i;
    if (mission == NULL) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if (mission->uav_count > SVA_CAN_MAX_UAV_ID) {
        return fail(diag, SVA_FIELD_UAVS, -1, mission->uav_count, SVA_RULE_COUNT,
                    SVA_CAN_MAX_UAV_ID, "SVA_CAN_MAX_UAV_ID");
    }
    for (i = 0; i < mission->uav_count; ++i) {
        const sva_uav_t* u = &mission->uavs[i];
        if ((u->id < 1) || (u->id > SVA_CAN_MAX_UAV_ID)) {
            return fail(diag, SVA_FIELD_UAV_ID, (int32_t)i, u->id,
                        (u->id < 1) ? SVA_RULE_MIN : SVA_RULE_MAX,
                        (u->id < 1) ? 1 : SVA_CAN_MAX_UAV_ID,
                        (u->id < 1) ? NULL : "SVA_CAN_MAX_UAV_ID");
        }
    }
    for (i = 0; i < mission->target_count; ++i) {
        const sva_target_t* t = &mission->targets[i];
        if ((t->id < 1) || (t->id > SVA_CAN_MAX_TARGET_ID)) {
            return fail(diag, SVA_FIELD_TARGET_ID, (int32_t)i, t->id,
                        (t->id < 1) ? SVA_RULE_MIN : SVA_RULE_MAX,
                        (t->id < 1) ? 1 : SVA_CAN_MAX_TARGET_ID,
                        (t->id < 1) ? NULL : "SVA_CAN_MAX_TARGET_ID");
        }
        if ((t->start_ticks < 0) || (t->start_ticks > SVA_CAN_MAX_TICK)) {
            return fail(diag, SVA_FIELD_TARGET_START, (int32_t)i, t->start_ticks,
                        (t->start_ticks < 0) ? SVA_RULE_MIN : SVA_RULE_MAX,
                        (t->start_ticks < 0) ? 0 : SVA_CAN_MAX_TICK,
                        (t->start_ticks < 0) ? NULL : "SVA_CAN_MAX_TICK");
        }
        if ((t->end_ticks < 0) || (t->end_ticks > SVA_CAN_MAX_TICK)) {
            return fail(diag, SVA_FIELD_TARGET_END, (int32_t)i, t->end_ticks,
                        (t->end_ticks < 0) ? SVA_RULE_MIN : SVA_RULE_MAX,
                        (t->end_ticks < 0) ? 0 : SVA_CAN_MAX_TICK,
                        (t->end_ticks < 0) ? NULL : "SVA_CAN_MAX_TICK");
        }
        if ((t->x < SVA_CAN_MIN_COORD) || (t->x > SVA_CAN_MAX_COORD)) {
            return fail(diag, SVA_FIELD_TARGET_X, (int32_t)i, t->x, SVA_RULE_MAX, SVA_CAN_MAX_COORD,
                        "SVA_CAN_MAX_COORD");
        }
        if ((t->y < SVA_CAN_MIN_COORD) || (t->y > SVA_CAN_MAX_COORD)) {
            return fail(diag, SVA_FIELD_TARGET_Y, (int32_t)i, t->y, SVA_RULE_MAX, SVA_CAN_MAX_COORD,
                        "SVA_CAN_MAX_COORD");
        }
    }
    return SVA_CAN_OK;
}

sva_can_status_t sva_can_plan_from_core(sva_can_plan_t* out, const sva_mission_t* mission,
                                        const sva_plan_t* plan, uint16_t plan_id)
{
    uint32_t r;
    uint32_t n = 0U;
    if ((out == NULL) || (mission == NULL) || (plan == NULL) || (plan_id == 0U) ||
        (plan->status == SVA_PLAN_NONE) || (plan->route_count > SVA_MAX_UAVS)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    if ((plan->route_count > SVA_CAN_MAX_UAV_ID) || ((unsigned)plan->algorithm > 15U)) {
        return SVA_CAN_ERR_LIMIT;
    }
    // First pass: check everything, so *out stays untouched on error.
    for (r = 0; r < plan->route_count; ++r) {
        const sva_route_t* route = &plan->routes[r];
        uint32_t k;
        if ((route->uav_id < 1) || (route->uav_id > SVA_CAN_MAX_UAV_ID) ||
            (route->target_count > SVA_MAX_ROUTE_TARGETS)) {
            return SVA_CAN_ERR_LIMIT;
        }
        for (k = 0; k < route->target_count; ++k) {
            const uint16_t ti = route->targets[k];
            const sva_target_t* t;
            if (ti >= mission->target_count) {
                return SVA_CAN_ERR_ARGUMENT;
            }
            t = &mission->targets[ti];
            if ((t->id < 1) || (t->id > SVA_CAN_MAX_TARGET_ID) || (t->start_ticks < 0) ||
                (t->end_ticks > SVA_CAN_MAX_TICK) || (t->start_ticks >= t->end_ticks) ||
                (t->x < SVA_CAN_MIN_COORD) || (t->x > SVA_CAN_MAX_COORD) ||
                (t->y < SVA_CAN_MIN_COORD) || (t->y > SVA_CAN_MAX_COORD)) {
                return SVA_CAN_ERR_LIMIT;
            }
            ++n;
            if (n > SVA_CAN_MAX_ITEMS) {
                return SVA_CAN_ERR_LIMIT;
            }
        }
    }
    out->plan_id = plan_id;
    out->algorithm = (uint8_t)plan->algorithm;
    out->plan_status =
        (plan->status == SVA_PLAN_COMPLETE) ? SVA_CAN_PLAN_COMPLETE : SVA_CAN_PLAN_PARTIAL;
    out->route_count = (uint8_t)plan->route_count;
    out->item_count = (uint16_t)n;
    n = 0U;
    for (r = 0; r < plan->route_count; ++r) {
        const sva_route_t* route = &plan->routes[r];
        uint32_t k;
        for (k = 0; k < route->target_count; ++k) {
            const sva_target_t* t = &mission->targets[route->targets[k]];
            sva_can_item_t* it = &out->items[n];
            it->uav_id = (uint8_t)route->uav_id;
            it->target_id = (uint16_t)t->id;
            it->x = (int16_t)t->x;
            it->y = (int16_t)t->y;
            it->arrive_by_ticks = (uint32_t)t->start_ticks;
            it->hold_until_ticks = (uint32_t)t->end_ticks;
            ++n;
        }
    }
    return SVA_CAN_OK;
}
