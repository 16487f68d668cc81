// Installed-tree consumer of sva::mavlink: a --vehicle value parsed and a bad one refused,
// the commanded ground speed of a frame, and a heartbeat encoded by the library and
// decoded again with the installed mavgen headers.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sva/sva_mavlink.h"

static int fail(const char* what)
{
    fprintf(stderr, "consumer_mavlink: %s\n", what);
    return 1;
}

int main(void)
{
    sva_mavlink_vehicle_spec_t spec;
    char err[SVA_MAVLINK_ERROR_SIZE];
    if (sva_mavlink_parse_vehicle("3=udp:127.0.0.1:14550:2", &spec, err, sizeof err) !=
        SVA_MAVLINK_OK) {
        return fail(err);
    }
    if (spec.uav_id != 3 || strcmp(spec.host, "127.0.0.1") != 0 || spec.port != 14550U ||
        spec.system != 2U) {
        return fail("3=udp:127.0.0.1:14550:2 parsed wrong");
    }
    if (sva_mavlink_parse_vehicle("3=serial:127.0.0.1:14550", &spec, err, sizeof err) !=
            SVA_MAVLINK_ERR_INVALID ||
        strstr(err, "must start with udp:") == NULL) {
        return fail("3=serial:... not refused with the rule");
    }

    // 10 m cells, 1 s ticks, 2 ticks per cell, 30 m up: 5 m/s times (1 + 30 / R), rounded
    // up to the next float.
    const sva_frame_t frame = {473977419, 85455939, 3000, 1000, 1000, 0};
    const double want = 5.0 * (1.0 + 30.0 / SVA_MAVLINK_MIN_RADIUS_M);
    const float speed = sva_mavlink_speed(&frame, 2);
    if (!((double)speed >= want && (double)nextafterf(speed, 0.0f) < want)) {
        fprintf(stderr, "consumer_mavlink: speed %.9g, want the float just above %.12g\n",
                (double)speed, want);
        return 1;
    }

    sva_mavlink_packet_t out;
    sva_mavlink_heartbeat(250, MAV_COMP_ID_MISSIONPLANNER, &out);
    static sva_mavlink_parser_t parser;
    mavlink_message_t msg;
    int complete = 0;
    for (uint16_t i = 0; i < out.len; i++) {
        complete += sva_mavlink_parse(&parser, out.bytes[i], &msg) ? 1 : 0;
    }
    if (complete != 1 || msg.msgid != MAVLINK_MSG_ID_HEARTBEAT || msg.sysid != 250U ||
        msg.compid != MAV_COMP_ID_MISSIONPLANNER ||
        mavlink_msg_heartbeat_get_type(&msg) != MAV_TYPE_ONBOARD_CONTROLLER) {
        return fail("the heartbeat did not decode as sent");
    }
    printf("consumer_mavlink: ok\n");
    return 0;
}
