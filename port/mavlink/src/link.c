// UDP endpoints of vehicles and the MAVLink byte parser (sva_mavlink.h).
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "sva/sva_mavlink.h"

static bool parse_int(const char* s, size_t len, long lo, long hi, long* out)
{
    if (len == 0 || len > 11) {
        return false;
    }
    char buf[16];
    memcpy(buf, s, len);
    buf[len] = '\0';
    char* end = NULL;
    errno = 0;
    long v = strtol(buf, &end, 10);
    if (errno != 0 || *end != '\0' || buf[0] == '+' || buf[0] == ' ' || v < lo || v > hi) {
        return false;
    }
    *out = v;
    return true;
}

bool sva_mavlink_parse_vehicle(const char* text, sva_mavlink_vehicle_spec_t* spec, char* err,
                               size_t err_size)
{
    memset(spec, 0, sizeof *spec);
    const char* eq = strchr(text, '=');
    long v = 0;
    if (eq == NULL) {
        snprintf(err, err_size, "--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID], got \"%.60s\"",
                 text);
        return false;
    }
    if (!parse_int(text, (size_t)(eq - text), 1, 2147483647L, &v)) {
        snprintf(err, err_size,
                 "--vehicle: UAV_ID must be an integer in [1, 2147483647], got \"%.*s\"",
                 (int)((eq - text) > 40 ? 40 : (eq - text)), text);
        return false;
    }
    spec->uav_id = (int32_t)v;
    const char* rest = eq + 1;
    if (strncmp(rest, "udp:", 4) != 0) {
        snprintf(err, err_size, "--vehicle: %d: the endpoint must start with udp:, got \"%.60s\"",
                 (int)spec->uav_id, rest);
        return false;
    }
    rest += 4;
    const char* c1 = strchr(rest, ':');
    if (c1 == NULL || c1 == rest || (size_t)(c1 - rest) >= sizeof spec->host) {
        snprintf(err, err_size, "--vehicle: %d: must be udp:HOST:PORT[:SYSID], got \"%.60s\"",
                 (int)spec->uav_id, eq + 1);
        return false;
    }
    memcpy(spec->host, rest, (size_t)(c1 - rest));
    const char* port = c1 + 1;
    const char* c2 = strchr(port, ':');
    size_t port_len = c2 ? (size_t)(c2 - port) : strlen(port);
    if (!parse_int(port, port_len, 1, 65535, &v)) {
        snprintf(err, err_size,
                 "--vehicle: %d: PORT must be an integer in [1, 65535], got \"%.*s\"",
                 (int)spec->uav_id, (int)(port_len > 20 ? 20 : port_len), port);
        return false;
    }
    spec->port = (uint16_t)v;
    spec->system = 1;
    if (c2 != NULL) {
        if (!parse_int(c2 + 1, strlen(c2 + 1), 1, 255, &v)) {
            snprintf(err, err_size,
                     "--vehicle: %d: SYSID must be an integer in [1, 255], got \"%.20s\"",
                     (int)spec->uav_id, c2 + 1);
            return false;
        }
        spec->system = (uint8_t)v;
    }
    return true;
}

int sva_mavlink_udp_open(const sva_mavlink_vehicle_spec_t* spec, char* err, size_t err_size)
{
    struct addrinfo hints;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    char port[8];
    snprintf(port, sizeof port, "%u", (unsigned)spec->port);
    struct addrinfo* res = NULL;
    int rc = getaddrinfo(spec->host, port, &hints, &res);
    if (rc != 0 || res == NULL) {
        snprintf(err, err_size, "vehicle %d: udp:%s:%u: cannot resolve: %s", (int)spec->uav_id,
                 spec->host, (unsigned)spec->port, gai_strerror(rc));
        return -1;
    }
    int fd = socket(res->ai_family, res->ai_socktype, res->ai_protocol);
    if (fd < 0 || connect(fd, res->ai_addr, res->ai_addrlen) != 0) {
        snprintf(err, err_size, "vehicle %d: udp:%s:%u: %s", (int)spec->uav_id, spec->host,
                 (unsigned)spec->port, strerror(errno));
        if (fd >= 0) {
            close(fd);
        }
        freeaddrinfo(res);
        return -1;
    }
    freeaddrinfo(res);
    int flags = fcntl(fd, F_GETFL, 0);
    if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0) {
        snprintf(err, err_size, "vehicle %d: fcntl: %s", (int)spec->uav_id, strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}

bool sva_mavlink_parse(sva_mavlink_parser_t* parser, uint8_t byte, mavlink_message_t* msg)
{
    uint8_t r =
        mavlink_frame_char_buffer(&parser->buffer, &parser->status, byte, msg, &parser->out_status);
    return r == MAVLINK_FRAMING_OK;
}

int64_t sva_mavlink_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

bool sva_mavlink_vehicle_open(sva_mavlink_vehicle_t* v, const sva_mavlink_vehicle_spec_t* spec,
                              uint8_t own_system, char* err, size_t err_size)
{
    memset(&v->parser, 0, sizeof v->parser);
    memset(&v->upload, 0, sizeof v->upload);
    v->spec = *spec;
    v->item_count = 0;
    v->next_heartbeat_ms = 0;
    v->send_errors = 0;
    v->upload.own_system = own_system;
    v->upload.own_component = MAV_COMP_ID_MISSIONPLANNER;
    v->upload.target_system = spec->system;
    v->upload.target_component = MAV_COMP_ID_AUTOPILOT1;
    v->upload.timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    v->upload.retries = SVA_MAVLINK_RETRIES;
    v->fd = sva_mavlink_udp_open(spec, err, err_size);
    return v->fd >= 0;
}

void sva_mavlink_vehicle_close(sva_mavlink_vehicle_t* v)
{
    if (v->fd >= 0) {
        close(v->fd);
    }
    v->fd = -1;
}

static void send_frame(sva_mavlink_vehicle_t* v, const sva_mavlink_frame_t* f)
{
    if (send(v->fd, f->bytes, f->len, 0) != (ssize_t)f->len) {
        v->send_errors++;  // nobody listening yet (ICMP refused): the timeout resends
    }
}

bool sva_mavlink_vehicle_start(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    sva_mavlink_frame_t f;
    sva_mavlink_heartbeat(v->upload.own_system, v->upload.own_component, &f);
    send_frame(v, &f);
    v->next_heartbeat_ms = now_ms + 1000;
    if (!sva_mavlink_upload_start(&v->upload, v->items, v->item_count, now_ms, &f)) {
        return false;
    }
    send_frame(v, &f);
    return true;
}

void sva_mavlink_vehicle_service(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    uint8_t buf[2048];
    sva_mavlink_frame_t f;
    for (;;) {
        ssize_t n = recv(v->fd, buf, sizeof buf, 0);
        if (n <= 0) {
            break;  // EAGAIN, or an ICMP error of an earlier send
        }
        for (ssize_t i = 0; i < n; i++) {
            mavlink_message_t msg;
            if (sva_mavlink_parse(&v->parser, buf[i], &msg) &&
                sva_mavlink_upload_on_message(&v->upload, &msg, now_ms, &f)) {
                send_frame(v, &f);
            }
        }
    }
    if (sva_mavlink_upload_on_time(&v->upload, now_ms, &f)) {
        send_frame(v, &f);
    }
    if (sva_mavlink_vehicle_busy(v) && now_ms >= v->next_heartbeat_ms) {
        sva_mavlink_heartbeat(v->upload.own_system, v->upload.own_component, &f);
        send_frame(v, &f);
        v->next_heartbeat_ms = now_ms + 1000;
    }
}

bool sva_mavlink_vehicle_busy(const sva_mavlink_vehicle_t* v)
{
    return v->upload.state == SVA_MAVLINK_UPLOAD_COUNT ||
           v->upload.state == SVA_MAVLINK_UPLOAD_ITEMS;
}
