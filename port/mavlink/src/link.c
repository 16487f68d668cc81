// One vehicle's link (sva_mavlink.h): the UDP socket or the TCP connection with its
// reconnection, the bytes in (parser) and out (a queue on TCP), and what every message
// feeds: the upload in progress and the telemetry.
#include <errno.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "mavlink_internal.h"

/// Bytes read from the socket at a time (a UDP datagram at most).
#define RX_CHUNK 2048

int64_t sva_mavlink_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static bool is_tcp(const sva_mavlink_vehicle_t* v)
{
    return v->spec.transport == SVA_MAVLINK_TCP;
}

static void flush_tx(sva_mavlink_vehicle_t* v)
{
    if (v->tx_len == 0 || v->link != SVA_MAVLINK_LINK_UP) {
        return;
    }
    ssize_t n = send(v->fd, v->tx, v->tx_len, MSG_NOSIGNAL);
    if (n > 0) {
        memmove(v->tx, v->tx + n, v->tx_len - (size_t)n);
        v->tx_len -= (size_t)n;
    }
    // n < 0: EAGAIN keeps the bytes for later; a broken connection shows up on reading.
}

static void send_packet(sva_mavlink_vehicle_t* v, const sva_mavlink_packet_t* f)
{
    if (!is_tcp(v)) {
        if (send(v->fd, f->bytes, f->len, 0) != (ssize_t)f->len) {
            v->send_errors++;  // nobody listening yet (ICMP refused): the timeout resends
        }
        return;
    }
    // A packet is queued whole or not at all: half a packet would corrupt the stream.
    if (v->link != SVA_MAVLINK_LINK_UP || v->tx_len + f->len > sizeof v->tx) {
        v->send_errors++;
        return;
    }
    memcpy(v->tx + v->tx_len, f->bytes, f->len);
    v->tx_len += f->len;
    flush_tx(v);
}

static void send_heartbeat(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    sva_mavlink_packet_t f;
    sva_mavlink_heartbeat(v->upload.own_system, v->upload.own_component, &f);
    send_packet(v, &f);
    v->next_heartbeat_ms = now_ms + SVA_MAVLINK_HEARTBEAT_MS;
}

static void on_connected(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    v->link = SVA_MAVLINK_LINK_UP;
    v->connects++;
    v->failed_connects = 0;
    v->link_error[0] = '\0';
    v->tx_len = 0;
    sva_mavlink_parser_reset(&v->parser);
    sva_mavlink_telemetry_on_link(&v->telemetry);
    send_heartbeat(v, now_ms);
    if (v->upload.state == SVA_MAVLINK_UPLOAD_COUNT) {
        // Its MISSION_COUNT went nowhere: send it now, with every retry still to come.
        sva_mavlink_packet_t f;
        if (sva_mavlink_upload_start(&v->upload, v->upload.items, v->upload.count, now_ms, &f)) {
            send_packet(v, &f);
        }
    }
}

static void close_fd(sva_mavlink_vehicle_t* v)
{
    if (v->fd >= 0) {
        close(v->fd);
    }
    v->fd = -1;
}

// A TCP attempt failed (why: errno's text or a reason): the next one in
// SVA_MAVLINK_RECONNECT_MS.
static void connect_failed(sva_mavlink_vehicle_t* v, int64_t now_ms, const char* why)
{
    close_fd(v);
    v->link = SVA_MAVLINK_LINK_DOWN;
    v->failed_connects++;
    v->next_connect_ms = now_ms + SVA_MAVLINK_RECONNECT_MS;
    snprintf(v->link_error, sizeof v->link_error, "%s", why);
}

static void link_lost(sva_mavlink_vehicle_t* v, int64_t now_ms, const char* why)
{
    close_fd(v);
    v->link = SVA_MAVLINK_LINK_DOWN;
    v->drops++;
    v->next_connect_ms = now_ms + SVA_MAVLINK_RECONNECT_MS;
    v->tx_len = 0;
    snprintf(v->link_error, sizeof v->link_error, "%s", why);
    if (sva_mavlink_vehicle_busy(v)) {
        char text[SVA_MAVLINK_ERROR_SIZE];
        snprintf(text, sizeof text, "link: tcp:%.64s:%u: connection lost during the upload: %.80s",
                 v->spec.host, (unsigned)v->spec.port, why);
        sva_mavlink_upload_abort(&v->upload, text);
    }
}

static void tcp_connect(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    v->fd = socket(v->addr_family, SOCK_STREAM, 0);
    if (v->fd < 0 || !sva_mavlink_set_nonblocking(v->fd)) {
        connect_failed(v, now_ms, strerror(errno));
        return;
    }
    int one = 1;
    // Packets are small and answered one by one: no Nagle delay.
    (void)setsockopt(v->fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    if (connect(v->fd, (const struct sockaddr*)(const void*)v->addr, (socklen_t)v->addr_len) == 0) {
        on_connected(v, now_ms);
    } else if (errno == EINPROGRESS) {
        v->link = SVA_MAVLINK_LINK_CONNECTING;
        v->next_connect_ms = now_ms + SVA_MAVLINK_CONNECT_TIMEOUT_MS;
    } else {
        connect_failed(v, now_ms, strerror(errno));
    }
}

static void tcp_check_connect(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    struct pollfd p = {v->fd, POLLOUT, 0};
    if (poll(&p, 1, 0) > 0) {
        int so_error = 0;
        socklen_t len = sizeof so_error;
        if (getsockopt(v->fd, SOL_SOCKET, SO_ERROR, &so_error, &len) != 0) {
            so_error = errno;
        }
        if (so_error == 0) {
            on_connected(v, now_ms);
        } else {
            connect_failed(v, now_ms, strerror(so_error));
        }
    } else if (now_ms >= v->next_connect_ms) {
        char why[64];
        snprintf(why, sizeof why, "no connection after %d ms", SVA_MAVLINK_CONNECT_TIMEOUT_MS);
        connect_failed(v, now_ms, why);
    }
}

sva_mavlink_status_t sva_mavlink_vehicle_open(sva_mavlink_vehicle_t* v,
                                              const sva_mavlink_vehicle_spec_t* spec,
                                              uint8_t own_system, char* err, size_t err_size)
{
    if ((v == NULL) || (spec == NULL)) {
        return SVA_MAVLINK_ERR_ARGUMENT;
    }
    memset(v, 0, sizeof *v);
    v->spec = *spec;
    v->fd = -1;
    v->upload.own_system = own_system;
    v->upload.own_component = MAV_COMP_ID_MISSIONPLANNER;
    v->upload.target_system = spec->system;
    v->upload.target_component = MAV_COMP_ID_AUTOPILOT1;
    v->upload.timeout_ms = SVA_MAVLINK_TIMEOUT_MS;
    v->upload.retries = SVA_MAVLINK_RETRIES;
    sva_mavlink_telemetry_init(&v->telemetry, spec->system);
    if (!is_tcp(v)) {
        v->fd = sva_mavlink_udp_open(spec, err, err_size);
        v->link = v->fd >= 0 ? SVA_MAVLINK_LINK_UP : SVA_MAVLINK_LINK_DOWN;
        return (v->fd >= 0) ? SVA_MAVLINK_OK : SVA_MAVLINK_ERR_IO;
    }
    if (!sva_mavlink_resolve(spec, SOCK_STREAM, v->addr, &v->addr_len, &v->addr_family, err,
                             err_size)) {
        return SVA_MAVLINK_ERR_IO;
    }
    tcp_connect(v, sva_mavlink_now_ms());
    return SVA_MAVLINK_OK;
}

void sva_mavlink_vehicle_close(sva_mavlink_vehicle_t* v)
{
    close_fd(v);
    v->link = SVA_MAVLINK_LINK_DOWN;
}

bool sva_mavlink_vehicle_start(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    send_heartbeat(v, now_ms);
    sva_mavlink_packet_t f;
    if (!sva_mavlink_upload_start(&v->upload, v->items, v->item_count, now_ms, &f)) {
        return false;
    }
    send_packet(v, &f);
    return true;
}

static void on_message(sva_mavlink_vehicle_t* v, const mavlink_message_t* msg, int64_t now_ms)
{
    sva_mavlink_packet_t f;
    if (sva_mavlink_upload_on_message(&v->upload, msg, now_ms, &f)) {
        send_packet(v, &f);
    }
    (void)sva_mavlink_telemetry_on_message(&v->telemetry, msg, now_ms);
}

// Feeds bytes to the parser and every packet it completes to on_message.
static void feed(sva_mavlink_vehicle_t* v, const uint8_t* data, size_t size, bool datagram,
                 int64_t now_ms)
{
    mavlink_message_t msg;
    size_t used = 0;
    while (used < size) {
        used += sva_mavlink_parser_put(&v->parser, data + used, size - used);
        while (sva_mavlink_parser_next(&v->parser, &msg)) {
            on_message(v, &msg, now_ms);
        }
    }
    if (datagram) {
        sva_mavlink_parser_end(&v->parser);
        while (sva_mavlink_parser_next(&v->parser, &msg)) {
            on_message(v, &msg, now_ms);
        }
    }
}

static void receive(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    uint8_t buf[RX_CHUNK];
    while (v->link == SVA_MAVLINK_LINK_UP) {
        ssize_t n = recv(v->fd, buf, sizeof buf, 0);
        if (!is_tcp(v)) {
            if (n <= 0) {
                return;  // EAGAIN, or an ICMP error of an earlier send
            }
            // Each datagram holds whole packets: it starts and ends a parse of its own
            // (after sva_mavlink_parser_end the parser is empty again).
            feed(v, buf, (size_t)n, true, now_ms);
        } else if (n > 0) {
            feed(v, buf, (size_t)n, false, now_ms);
        } else if (n == 0) {
            link_lost(v, now_ms, "closed by the vehicle");
        } else if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
            return;
        } else {
            link_lost(v, now_ms, strerror(errno));
        }
    }
}

void sva_mavlink_vehicle_service(sva_mavlink_vehicle_t* v, int64_t now_ms)
{
    if (is_tcp(v)) {
        if (v->link == SVA_MAVLINK_LINK_DOWN && now_ms >= v->next_connect_ms) {
            tcp_connect(v, now_ms);
        }
        if (v->link == SVA_MAVLINK_LINK_CONNECTING) {
            tcp_check_connect(v, now_ms);
        }
        flush_tx(v);
    }
    receive(v, now_ms);
    sva_mavlink_packet_t f;
    const bool was_busy = sva_mavlink_vehicle_busy(v);
    if (sva_mavlink_upload_on_time(&v->upload, now_ms, &f)) {
        send_packet(v, &f);
    }
    if (was_busy && v->upload.state == SVA_MAVLINK_UPLOAD_FAILED && is_tcp(v) &&
        v->link != SVA_MAVLINK_LINK_UP) {
        // Timed out on a link that is not up: say why it is not.
        size_t n = strlen(v->upload.error);
        snprintf(v->upload.error + n, sizeof v->upload.error - n,
                 "; tcp:%.64s:%u not connected: %.80s", v->spec.host, (unsigned)v->spec.port,
                 v->link_error[0] != '\0' ? v->link_error : "connecting");
    }
    if (v->link != SVA_MAVLINK_LINK_UP) {
        return;
    }
    if (now_ms >= v->next_heartbeat_ms) {
        send_heartbeat(v, now_ms);
    }
    sva_mavlink_packet_t requests[SVA_MAVLINK_STREAM_COUNT];
    size_t n =
        sva_mavlink_telemetry_requests(&v->telemetry, now_ms, v->upload.own_system,
                                       v->upload.own_component, requests, SVA_MAVLINK_STREAM_COUNT);
    for (size_t k = 0; k < n; k++) {
        send_packet(v, &requests[k]);
    }
}

bool sva_mavlink_vehicle_busy(const sva_mavlink_vehicle_t* v)
{
    return v->upload.state == SVA_MAVLINK_UPLOAD_COUNT ||
           v->upload.state == SVA_MAVLINK_UPLOAD_ITEMS;
}
