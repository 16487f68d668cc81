// A vehicle's telemetry (sva_mavlink.h): what its autopilot's messages say, and the
// SET_MESSAGE_INTERVAL requests that make it say them.
#include <string.h>

#include "sva/sva_mavlink.h"

#define PERCENT_MAX 100
#define US_PER_MS   1000
#define SEQ_MAX     32767  // report_t carries sequence numbers as int16
/// The battery BATTERY_STATUS reports on: the first (ArduPilot's and PX4's main one).
#define MAIN_BATTERY 0

// The streams asked for, in request order, and their intervals.
static const uint32_t stream_ids[SVA_MAVLINK_STREAM_COUNT] = {
    MAVLINK_MSG_ID_GLOBAL_POSITION_INT, MAVLINK_MSG_ID_SYSTEM_TIME, MAVLINK_MSG_ID_SYS_STATUS,
    MAVLINK_MSG_ID_BATTERY_STATUS, MAVLINK_MSG_ID_MISSION_CURRENT};
static const int32_t stream_interval_ms[SVA_MAVLINK_STREAM_COUNT] = {
    SVA_MAVLINK_POSITION_INTERVAL_MS, SVA_MAVLINK_STATUS_INTERVAL_MS,
    SVA_MAVLINK_STATUS_INTERVAL_MS, SVA_MAVLINK_STATUS_INTERVAL_MS, SVA_MAVLINK_STATUS_INTERVAL_MS};

static void forget_boot(sva_mavlink_telemetry_t* self)
{
    self->has_position = false;
    self->has_time_boot = false;
    self->has_gps_time = false;
    self->battery_percent = SVA_MAVLINK_UNKNOWN;
    self->mission_seq = SVA_MAVLINK_UNKNOWN;
    self->reached_seq = SVA_MAVLINK_UNKNOWN;
}

void sva_mavlink_telemetry_init(sva_mavlink_telemetry_t* self, uint8_t system)
{
    memset(self, 0, sizeof *self);
    self->system = system;
    forget_boot(self);
}

static void want_streams(sva_mavlink_telemetry_t* self, int64_t now_host_ms)
{
    self->streams_pending = true;
    self->streams_due_host_ms = now_host_ms;
    memset(self->stream_tries, 0, sizeof self->stream_tries);
    self->streams_heard = 0;
}

void sva_mavlink_telemetry_on_link(sva_mavlink_telemetry_t* self)
{
    // Asked at the next heartbeat: the vehicle is known to listen then.
    self->streams_pending = false;
    memset(self->stream_tries, 0, sizeof self->stream_tries);
    self->streams_heard = 0;
    self->heard_on_link = false;
}

static void heard_stream(sva_mavlink_telemetry_t* self, uint32_t msgid)
{
    for (uint32_t k = 0; k < SVA_MAVLINK_STREAM_COUNT; k++) {
        if (stream_ids[k] == msgid) {
            self->streams_heard |= 1U << k;
        }
    }
}

static void reboot(sva_mavlink_telemetry_t* self, int64_t now_host_ms)
{
    forget_boot(self);
    self->reboots++;
    want_streams(self, now_host_ms);
}

// A vehicle with both messages may leave one unknown (-1): it does not hide the other.
static void on_battery(sva_mavlink_telemetry_t* self, int32_t percent)
{
    if (percent >= 0 && percent <= PERCENT_MAX) {
        self->battery_percent = percent;
    }
}

static int32_t seq_or_unknown(uint16_t v)
{
    return v <= SEQ_MAX ? (int32_t)v : SVA_MAVLINK_UNKNOWN;
}

static void on_heartbeat(sva_mavlink_telemetry_t* self, const mavlink_message_t* msg,
                         int64_t now_host_ms)
{
    mavlink_heartbeat_t hb;
    mavlink_msg_heartbeat_decode(msg, &hb);
    // First heartbeat on this link, or after a silence long enough for a reboot.
    if (!self->heard_on_link ||
        now_host_ms - self->heartbeat_host_ms > SVA_MAVLINK_STREAM_SILENCE_MS) {
        want_streams(self, now_host_ms);
    }
    self->heard = true;
    self->heard_on_link = true;
    self->heartbeat_host_ms = now_host_ms;
    self->armed = (hb.base_mode & MAV_MODE_FLAG_SAFETY_ARMED) != 0;
    self->system_status = hb.system_status;
}

static void on_position(sva_mavlink_telemetry_t* self, const mavlink_message_t* msg,
                        int64_t now_host_ms)
{
    mavlink_global_position_int_t p;
    mavlink_msg_global_position_int_decode(msg, &p);
    if (self->has_position && p.time_boot_ms < self->position_boot_ms) {
        reboot(self, now_host_ms);
    }
    self->has_position = true;
    self->lat_e7 = p.lat;
    self->lon_e7 = p.lon;
    self->relative_alt_mm = p.relative_alt;
    self->position_boot_ms = p.time_boot_ms;
}

static void on_system_time(sva_mavlink_telemetry_t* self, const mavlink_message_t* msg,
                           int64_t now_host_ms)
{
    mavlink_system_time_t t;
    mavlink_msg_system_time_decode(msg, &t);
    if (self->has_time_boot && t.time_boot_ms < self->time_boot_ms) {
        reboot(self, now_host_ms);
    }
    self->has_time_boot = true;
    self->has_gps_time = t.time_unix_usec != 0;  // 0 until the GPS has the time
    self->time_unix_usec = t.time_unix_usec;
    self->time_boot_ms = t.time_boot_ms;
    self->time_host_ms = now_host_ms;
}

static bool on_command_ack(sva_mavlink_telemetry_t* self, const mavlink_message_t* msg)
{
    mavlink_command_ack_t a;
    mavlink_msg_command_ack_decode(msg, &a);
    if (a.command != MAV_CMD_SET_MESSAGE_INTERVAL) {
        return false;
    }
    if (a.result == MAV_RESULT_ACCEPTED) {
        self->requests_accepted++;
    } else {
        self->requests_refused++;
    }
    return true;
}

bool sva_mavlink_telemetry_on_message(sva_mavlink_telemetry_t* self, const mavlink_message_t* msg,
                                      int64_t now_host_ms)
{
    if (msg->sysid != self->system || msg->compid != MAV_COMP_ID_AUTOPILOT1) {
        return false;
    }
    heard_stream(self, msg->msgid);
    switch (msg->msgid) {
    case MAVLINK_MSG_ID_HEARTBEAT:
        on_heartbeat(self, msg, now_host_ms);
        return true;
    case MAVLINK_MSG_ID_GLOBAL_POSITION_INT:
        on_position(self, msg, now_host_ms);
        return true;
    case MAVLINK_MSG_ID_SYSTEM_TIME:
        on_system_time(self, msg, now_host_ms);
        return true;
    case MAVLINK_MSG_ID_SYS_STATUS:
        on_battery(self, mavlink_msg_sys_status_get_battery_remaining(msg));
        return true;
    case MAVLINK_MSG_ID_BATTERY_STATUS:
        if (mavlink_msg_battery_status_get_id(msg) != MAIN_BATTERY) {
            return false;
        }
        on_battery(self, mavlink_msg_battery_status_get_battery_remaining(msg));
        return true;
    case MAVLINK_MSG_ID_MISSION_CURRENT:
        self->mission_seq = seq_or_unknown(mavlink_msg_mission_current_get_seq(msg));
        return true;
    case MAVLINK_MSG_ID_MISSION_ITEM_REACHED:
        self->reached_seq = seq_or_unknown(mavlink_msg_mission_item_reached_get_seq(msg));
        return true;
    case MAVLINK_MSG_ID_COMMAND_ACK:
        return on_command_ack(self, msg);
    default:
        return false;
    }
}

size_t sva_mavlink_telemetry_requests(sva_mavlink_telemetry_t* self, int64_t now_host_ms,
                                      uint8_t own_system, uint8_t own_component,
                                      sva_mavlink_packet_t* out, size_t capacity)
{
    if (!self->streams_pending || now_host_ms < self->streams_due_host_ms) {
        return 0;
    }
    size_t n = 0;
    bool more = false;
    for (uint32_t k = 0; k < SVA_MAVLINK_STREAM_COUNT && n < capacity; k++) {
        const bool first_round = self->stream_tries[k] == 0;
        if (self->stream_tries[k] >= SVA_MAVLINK_STREAM_TRIES ||
            (!first_round && (self->streams_heard & (1U << k)) != 0)) {
            continue;
        }
        mavlink_message_t msg;
        // param1 the message id, param2 the interval in us; param7 0: send to the asker.
        mavlink_msg_command_long_pack(
            own_system, own_component, &msg, self->system, MAV_COMP_ID_AUTOPILOT1,
            MAV_CMD_SET_MESSAGE_INTERVAL, self->stream_tries[k], (float)stream_ids[k],
            (float)(stream_interval_ms[k] * US_PER_MS), 0.0F, 0.0F, 0.0F, 0.0F, 0.0F);
        out[n].len = mavlink_msg_to_send_buffer(out[n].bytes, &msg);
        n++;
        self->stream_tries[k]++;
        self->streams_heard &= ~(1U << k);
        self->requests_sent++;
        more = more || self->stream_tries[k] < SVA_MAVLINK_STREAM_TRIES;
    }
    self->streams_pending = more || n == capacity;  // out is full: the others are asked for later
    self->streams_due_host_ms = now_host_ms + SVA_MAVLINK_STREAM_RETRY_MS;
    return n;
}

bool sva_mavlink_telemetry_gps_ms(const sva_mavlink_telemetry_t* self, int64_t* gps_ms)
{
    if (!self->has_position || !self->has_gps_time) {
        return false;
    }
    *gps_ms = (int64_t)(self->time_unix_usec / US_PER_MS) +
              ((int64_t)self->position_boot_ms - (int64_t)self->time_boot_ms);
    return true;
}
