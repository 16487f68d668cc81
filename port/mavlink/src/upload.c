// The mission upload protocol, sender side (MAVLink mission protocol): MISSION_COUNT,
// then one MISSION_ITEM_INT per MISSION_REQUEST_INT (or the older MISSION_REQUEST),
// until MISSION_ACK. Every message sent waits up to timeout_ms for the vehicle's next
// message and is sent again up to `retries` times.
#include <stdio.h>
#include <string.h>

#include "sva/sva_mavlink.h"

static void finish(const mavlink_message_t* msg, sva_mavlink_packet_t* out)
{
    out->len = mavlink_msg_to_send_buffer(out->bytes, msg);
}

static void send_count(sva_mavlink_upload_t* up, sva_mavlink_packet_t* out)
{
    mavlink_message_t msg;
    mavlink_msg_mission_count_pack(up->own_system, up->own_component, &msg, up->target_system,
                                   up->target_component, up->count, MAV_MISSION_TYPE_MISSION);
    finish(&msg, out);
}

static void send_item(sva_mavlink_upload_t* up, uint16_t seq, sva_mavlink_packet_t* out)
{
    const sva_mavlink_item_t* it = &up->items[seq];
    mavlink_message_t msg;
    mavlink_msg_mission_item_int_pack(up->own_system, up->own_component, &msg, up->target_system,
                                      up->target_component, seq, it->frame, it->command,
                                      seq == 0 ? 1 : 0, 1, it->param1, it->param2, it->param3,
                                      it->param4, it->x, it->y, it->z, MAV_MISSION_TYPE_MISSION);
    finish(&msg, out);
    up->last_seq = seq;
    up->sent_items++;
    if ((up->sent[seq / 8] & (1U << (seq % 8))) == 0) {
        up->sent[seq / 8] = (uint8_t)(up->sent[seq / 8] | (1U << (seq % 8)));
        up->distinct_sent++;
    }
}

static void fail(sva_mavlink_upload_t* up, const char* text)
{
    up->state = SVA_MAVLINK_UPLOAD_FAILED;
    snprintf(up->error, sizeof up->error, "%s", text);
}

static const char* result_name(uint8_t type)
{
    switch (type) {
    case MAV_MISSION_ACCEPTED:
        return "MAV_MISSION_ACCEPTED";
    case MAV_MISSION_ERROR:
        return "MAV_MISSION_ERROR";
    case MAV_MISSION_UNSUPPORTED_FRAME:
        return "MAV_MISSION_UNSUPPORTED_FRAME";
    case MAV_MISSION_UNSUPPORTED:
        return "MAV_MISSION_UNSUPPORTED";
    case MAV_MISSION_NO_SPACE:
        return "MAV_MISSION_NO_SPACE";
    case MAV_MISSION_INVALID:
        return "MAV_MISSION_INVALID";
    case MAV_MISSION_INVALID_PARAM1:
        return "MAV_MISSION_INVALID_PARAM1";
    case MAV_MISSION_INVALID_PARAM2:
        return "MAV_MISSION_INVALID_PARAM2";
    case MAV_MISSION_INVALID_PARAM3:
        return "MAV_MISSION_INVALID_PARAM3";
    case MAV_MISSION_INVALID_PARAM4:
        return "MAV_MISSION_INVALID_PARAM4";
    case MAV_MISSION_INVALID_PARAM5_X:
        return "MAV_MISSION_INVALID_PARAM5_X";
    case MAV_MISSION_INVALID_PARAM6_Y:
        return "MAV_MISSION_INVALID_PARAM6_Y";
    case MAV_MISSION_INVALID_PARAM7:
        return "MAV_MISSION_INVALID_PARAM7";
    case MAV_MISSION_INVALID_SEQUENCE:
        return "MAV_MISSION_INVALID_SEQUENCE";
    case MAV_MISSION_DENIED:
        return "MAV_MISSION_DENIED";
    case MAV_MISSION_OPERATION_CANCELLED:
        return "MAV_MISSION_OPERATION_CANCELLED";
    default:
        return "an unknown MAV_MISSION_RESULT";
    }
}

bool sva_mavlink_upload_start(sva_mavlink_upload_t* up, const sva_mavlink_item_t* items,
                              size_t count, int64_t now_ms, sva_mavlink_packet_t* out)
{
    up->error[0] = '\0';
    up->refusal = MAV_MISSION_ACCEPTED;
    up->tries = 0;
    up->sent_items = 0;
    up->distinct_sent = 0;
    memset(up->sent, 0, sizeof up->sent);
    up->last_seq = 0;
    if (up->timeout_ms <= 0) {
        up->timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    }
    if (up->retries < 0) {
        up->retries = 0;
    }
    if (count == 0 || count > SVA_MAVLINK_MAX_ITEMS) {
        up->count = 0;
        snprintf(up->error, sizeof up->error, "mission: %zu items, must be in [1, %d]", count,
                 SVA_MAVLINK_MAX_ITEMS);
        up->state = SVA_MAVLINK_UPLOAD_FAILED;
        return false;
    }
    up->items = items;
    up->count = (uint16_t)count;
    up->state = SVA_MAVLINK_UPLOAD_COUNT;
    up->deadline_ms = now_ms + up->timeout_ms;
    send_count(up, out);
    return true;
}

bool sva_mavlink_upload_on_message(sva_mavlink_upload_t* up, const mavlink_message_t* msg,
                                   int64_t now_ms, sva_mavlink_packet_t* out)
{
    if (up->state != SVA_MAVLINK_UPLOAD_COUNT && up->state != SVA_MAVLINK_UPLOAD_ITEMS) {
        return false;
    }
    if (msg->sysid != up->target_system || msg->compid != up->target_component) {
        return false;
    }
    uint16_t seq = 0;
    uint8_t to_system = 0;
    uint8_t mission_type = 0;
    switch (msg->msgid) {
    case MAVLINK_MSG_ID_MISSION_REQUEST_INT: {
        mavlink_mission_request_int_t r;
        mavlink_msg_mission_request_int_decode(msg, &r);
        seq = r.seq;
        to_system = r.target_system;
        mission_type = r.mission_type;
        break;
    }
    case MAVLINK_MSG_ID_MISSION_REQUEST: {
        mavlink_mission_request_t r;
        mavlink_msg_mission_request_decode(msg, &r);
        seq = r.seq;
        to_system = r.target_system;
        mission_type = r.mission_type;
        break;
    }
    case MAVLINK_MSG_ID_MISSION_ACK: {
        mavlink_mission_ack_t a;
        mavlink_msg_mission_ack_decode(msg, &a);
        if (a.target_system != up->own_system || a.mission_type != MAV_MISSION_TYPE_MISSION) {
            return false;
        }
        if (a.type == MAV_MISSION_ACCEPTED) {
            if (up->distinct_sent == up->count) {
                up->state = SVA_MAVLINK_UPLOAD_DONE;
            } else {
                char text[SVA_MAVLINK_ERROR_SIZE];
                snprintf(text, sizeof text,
                         "MISSION_ACK: MAV_MISSION_ACCEPTED after %u of %u items were sent",
                         (unsigned)up->distinct_sent, (unsigned)up->count);
                fail(up, text);
            }
        } else {
            char text[SVA_MAVLINK_ERROR_SIZE];
            snprintf(text, sizeof text, "MISSION_ACK: the vehicle refused the mission: %s (%u)",
                     result_name(a.type), (unsigned)a.type);
            fail(up, text);
            up->refusal = a.type;
        }
        return false;
    }
    default:
        return false;
    }
    if (to_system != up->own_system || mission_type != MAV_MISSION_TYPE_MISSION) {
        return false;
    }
    if (seq >= up->count) {
        return false;  // not a request of this mission: let the timeout decide
    }
    up->state = SVA_MAVLINK_UPLOAD_ITEMS;
    up->tries = 0;
    up->deadline_ms = now_ms + up->timeout_ms;
    send_item(up, seq, out);
    return true;
}

bool sva_mavlink_upload_on_time(sva_mavlink_upload_t* up, int64_t now_ms, sva_mavlink_packet_t* out)
{
    if (up->state != SVA_MAVLINK_UPLOAD_COUNT && up->state != SVA_MAVLINK_UPLOAD_ITEMS) {
        return false;
    }
    if (now_ms < up->deadline_ms) {
        return false;
    }
    if (up->tries >= up->retries) {
        char text[SVA_MAVLINK_ERROR_SIZE];
        if (up->state == SVA_MAVLINK_UPLOAD_COUNT) {
            snprintf(text, sizeof text,
                     "timeout: no answer to MISSION_COUNT after %d tries of %d ms",
                     (int)up->tries + 1, (int)up->timeout_ms);
        } else {
            snprintf(text, sizeof text,
                     "timeout: no answer to MISSION_ITEM_INT %u after %d tries of %d ms",
                     (unsigned)up->last_seq, (int)up->tries + 1, (int)up->timeout_ms);
        }
        fail(up, text);
        return false;
    }
    up->tries++;
    up->deadline_ms = now_ms + up->timeout_ms;
    if (up->state == SVA_MAVLINK_UPLOAD_COUNT) {
        send_count(up, out);
    } else {
        send_item(up, up->last_seq, out);
    }
    return true;
}

bool sva_mavlink_upload_refused_for_good(const sva_mavlink_upload_t* up)
{
    if (up->state != SVA_MAVLINK_UPLOAD_FAILED) {
        return false;
    }
    switch (up->refusal) {
    case MAV_MISSION_UNSUPPORTED_FRAME:
    case MAV_MISSION_UNSUPPORTED:
    case MAV_MISSION_INVALID:
    case MAV_MISSION_INVALID_PARAM1:
    case MAV_MISSION_INVALID_PARAM2:
    case MAV_MISSION_INVALID_PARAM3:
    case MAV_MISSION_INVALID_PARAM4:
    case MAV_MISSION_INVALID_PARAM5_X:
    case MAV_MISSION_INVALID_PARAM6_Y:
    case MAV_MISSION_INVALID_PARAM7:
    case MAV_MISSION_INVALID_SEQUENCE:
        return true;
    default:
        return false;  // accepted (no refusal), or a refusal that can pass
    }
}

void sva_mavlink_heartbeat(uint8_t own_system, uint8_t own_component, sva_mavlink_packet_t* out)
{
    mavlink_message_t msg;
    mavlink_msg_heartbeat_pack(own_system, own_component, &msg, MAV_TYPE_ONBOARD_CONTROLLER,
                               MAV_AUTOPILOT_INVALID, 0, 0, MAV_STATE_ACTIVE);
    finish(&msg, out);
}

void sva_mavlink_upload_abort(sva_mavlink_upload_t* up, const char* reason)
{
    if (up->state == SVA_MAVLINK_UPLOAD_COUNT || up->state == SVA_MAVLINK_UPLOAD_ITEMS) {
        fail(up, reason);
    }
}
