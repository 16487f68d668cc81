// Vehicle endpoints (sva_mavlink.h): --vehicle values, address resolution, UDP sockets.
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <unistd.h>

#include "mavlink_internal.h"

#define MAX_UAV_ID 2147483647L
#define MAX_PORT   65535L
#define MAX_SYSID  255L
/// Widest decimal an option carries here ("-2147483648").
#define MAX_INT_TEXT 11U
/// How much of a bad value a message quotes.
#define QUOTE_LEN 60

static bool parse_int(const char* s, size_t len, long lo, long hi, long* out)
{
    if (len == 0 || len > MAX_INT_TEXT) {
        return false;
    }
    char buf[MAX_INT_TEXT + 1];
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

const char* sva_mavlink_transport_name(sva_mavlink_transport_t transport)
{
    return transport == SVA_MAVLINK_TCP ? "tcp" : "udp";
}

sva_mavlink_status_t sva_mavlink_parse_vehicle(const char* text, sva_mavlink_vehicle_spec_t* spec,
                                               char* err, size_t err_size)
{
    if ((text == NULL) || (spec == NULL)) {
        return SVA_MAVLINK_ERR_ARGUMENT;
    }
    memset(spec, 0, sizeof *spec);
    const char* eq = strchr(text, '=');
    long v = 0;
    if (eq == NULL) {
        snprintf(err, err_size,
                 "--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID] or UAV_ID=tcp:HOST:PORT[:SYSID], "
                 "got \"%.*s\"",
                 QUOTE_LEN, text);
        return SVA_MAVLINK_ERR_INVALID;
    }
    if (!parse_int(text, (size_t)(eq - text), 1, MAX_UAV_ID, &v)) {
        snprintf(err, err_size, "--vehicle: UAV_ID must be an integer in [1, %ld], got \"%.*s\"",
                 MAX_UAV_ID, (int)((eq - text) > 40 ? 40 : (eq - text)), text);
        return SVA_MAVLINK_ERR_INVALID;
    }
    spec->uav_id = (int32_t)v;
    const char* rest = eq + 1;
    if (strncmp(rest, "udp:", 4) == 0) {
        spec->transport = SVA_MAVLINK_UDP;
    } else if (strncmp(rest, "tcp:", 4) == 0) {
        spec->transport = SVA_MAVLINK_TCP;
    } else {
        snprintf(err, err_size,
                 "--vehicle: %d: the endpoint must start with udp: or tcp:, got \"%.*s\"",
                 (int)spec->uav_id, QUOTE_LEN, rest);
        return SVA_MAVLINK_ERR_INVALID;
    }
    const char* kind = sva_mavlink_transport_name(spec->transport);
    rest += 4;
    const char* c1 = strchr(rest, ':');
    if (c1 == NULL || c1 == rest || (size_t)(c1 - rest) >= sizeof spec->host) {
        snprintf(err, err_size, "--vehicle: %d: must be %s:HOST:PORT[:SYSID], got \"%.*s\"",
                 (int)spec->uav_id, kind, QUOTE_LEN, eq + 1);
        return SVA_MAVLINK_ERR_INVALID;
    }
    memcpy(spec->host, rest, (size_t)(c1 - rest));
    const char* port = c1 + 1;
    const char* c2 = strchr(port, ':');
    size_t port_len = c2 ? (size_t)(c2 - port) : strlen(port);
    if (!parse_int(port, port_len, 1, MAX_PORT, &v)) {
        snprintf(err, err_size, "--vehicle: %d: PORT must be an integer in [1, %ld], got \"%.*s\"",
                 (int)spec->uav_id, MAX_PORT, (int)(port_len > 20 ? 20 : port_len), port);
        return SVA_MAVLINK_ERR_INVALID;
    }
    spec->port = (uint16_t)v;
    spec->system = 1;
    if (c2 != NULL) {
        if (!parse_int(c2 + 1, strlen(c2 + 1), 1, MAX_SYSID, &v)) {
            snprintf(err, err_size,
                     "--vehicle: %d: SYSID must be an integer in [1, %ld], got \"%.20s\"",
                     (int)spec->uav_id, MAX_SYSID, c2 + 1);
            return SVA_MAVLINK_ERR_INVALID;
        }
        spec->system = (uint8_t)v;
    }
    return SVA_MAVLINK_OK;
}

bool sva_mavlink_resolve(const sva_mavlink_vehicle_spec_t* spec, int socktype, uint8_t* addr,
                         uint32_t* addr_len, int* family, char* err, size_t err_size)
{
    struct addrinfo hints;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = socktype;
    char port[8];
    snprintf(port, sizeof port, "%u", (unsigned)spec->port);
    struct addrinfo* res = NULL;
    int rc = getaddrinfo(spec->host, port, &hints, &res);
    if (rc != 0 || res == NULL) {
        snprintf(err, err_size, "vehicle %d: %s:%s:%u: cannot resolve: %s", (int)spec->uav_id,
                 sva_mavlink_transport_name(spec->transport), spec->host, (unsigned)spec->port,
                 gai_strerror(rc));
        return false;
    }
    if (res->ai_addrlen > SVA_MAVLINK_ADDR_SIZE) {
        snprintf(err, err_size, "vehicle %d: %s: address of %u bytes, at most %d",
                 (int)spec->uav_id, spec->host, (unsigned)res->ai_addrlen, SVA_MAVLINK_ADDR_SIZE);
        freeaddrinfo(res);
        return false;
    }
    memcpy(addr, res->ai_addr, res->ai_addrlen);
    *addr_len = (uint32_t)res->ai_addrlen;
    *family = res->ai_family;
    freeaddrinfo(res);
    return true;
}

bool sva_mavlink_set_nonblocking(int fd)
{
    int flags = fcntl(fd, F_GETFL, 0);
    return flags >= 0 && fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

int sva_mavlink_udp_open(const sva_mavlink_vehicle_spec_t* spec, char* err, size_t err_size)
{
    uint8_t addr[SVA_MAVLINK_ADDR_SIZE];
    uint32_t addr_len = 0;
    int family = 0;
    if (!sva_mavlink_resolve(spec, SOCK_DGRAM, addr, &addr_len, &family, err, err_size)) {
        return -1;
    }
    int fd = socket(family, SOCK_DGRAM, 0);
    if (fd < 0 ||
        connect(fd, (const struct sockaddr*)(const void*)addr, (socklen_t)addr_len) != 0) {
        snprintf(err, err_size, "vehicle %d: udp:%s:%u: %s", (int)spec->uav_id, spec->host,
                 (unsigned)spec->port, strerror(errno));
        if (fd >= 0) {
            close(fd);
        }
        return -1;
    }
    if (!sva_mavlink_set_nonblocking(fd)) {
        snprintf(err, err_size, "vehicle %d: fcntl: %s", (int)spec->uav_id, strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}
