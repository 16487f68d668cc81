// SocketCAN transport (Linux only; CMake builds src/socketcan_other.c elsewhere).
// One raw CAN socket, non-blocking, every system call checked, lengths checked before
// any byte is copied.

// DEVIATION(C99 strict): the POSIX and Linux socket declarations need _DEFAULT_SOURCE.
#define _DEFAULT_SOURCE 1

#ifndef __linux__
#    error "socketcan.c is Linux only"
#endif

#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

sva_can_status_t sva_can_socketcan_open(sva_can_socketcan_t* self, const char* ifname)
{
    struct ifreq ifr;
    struct sockaddr_can addr;
    const void* nul;
    size_t len;
    int fd;
    int on = 1;
    if (self == NULL) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    self->fd = -1;
    self->last_errno = 0;
    self->rx_short = 0U;
    self->rx_bad_dlc = 0U;
    if (ifname == NULL) {
        return SVA_CAN_ERR_NAME;
    }
    nul = memchr(ifname, '\0', IFNAMSIZ);  // never reads past IFNAMSIZ bytes
    if (nul == NULL) {
        return SVA_CAN_ERR_NAME;  // no room for the NUL in ifr_name
    }
    len = (size_t)((const char*)nul - ifname);
    if (len == 0U) {
        return SVA_CAN_ERR_NAME;
    }
    fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        self->last_errno = errno;
        return SVA_CAN_ERR_IO;
    }
    // FD frames on read: an FD sender on the bus must not make reads fail; the decoder
    // rejects them. Kernels without CAN FD answer ENOPROTOOPT, which is fine.
    if ((setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, (socklen_t)sizeof on) != 0) &&
        (errno != ENOPROTOOPT)) {
        self->last_errno = errno;
        (void)close(fd);
        return SVA_CAN_ERR_IO;
    }
    memset(&ifr, 0, sizeof ifr);
    memcpy(ifr.ifr_name, ifname, len + 1U);
    if (ioctl(fd, SIOCGIFINDEX, &ifr) != 0) {
        self->last_errno = errno;
        (void)close(fd);
        return SVA_CAN_ERR_IO;
    }
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (bind(fd, (struct sockaddr*)&addr, (socklen_t)sizeof addr) != 0) {
        self->last_errno = errno;
        (void)close(fd);
        return SVA_CAN_ERR_IO;
    }
    self->fd = fd;
    return SVA_CAN_OK;
}

void sva_can_socketcan_close(sva_can_socketcan_t* self)
{
    if ((self != NULL) && (self->fd >= 0)) {
        if (close(self->fd) != 0) {
            self->last_errno = errno;
        }
        self->fd = -1;
    }
}

static sva_can_status_t sc_send(void* ctx, const sva_can_frame_t* frame)
{
    sva_can_socketcan_t* self = (sva_can_socketcan_t*)ctx;
    struct can_frame f;
    ssize_t n;
    unsigned i;
    if ((self == NULL) || (frame == NULL) || (self->fd < 0) || (frame->dlc > 8U)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    memset(&f, 0, sizeof f);
    if ((frame->flags & SVA_CAN_FLAG_EXTENDED) != 0U) {
        f.can_id = (canid_t)((frame->id & CAN_EFF_MASK) | CAN_EFF_FLAG);
    } else {
        f.can_id = (canid_t)(frame->id & CAN_SFF_MASK);
    }
    f.can_dlc = frame->dlc;
    for (i = 0; i < frame->dlc; ++i) {
        f.data[i] = frame->data[i];
    }
    n = write(self->fd, &f, sizeof f);
    if (n < 0) {
        self->last_errno = errno;
        if ((errno == EAGAIN) || (errno == EWOULDBLOCK) || (errno == ENOBUFS) || (errno == EINTR)) {
            return SVA_CAN_AGAIN;  // transmit queue full: the caller polls again
        }
        return SVA_CAN_ERR_IO;
    }
    if ((size_t)n != sizeof f) {
        self->last_errno = EIO;
        return SVA_CAN_ERR_IO;
    }
    return SVA_CAN_OK;
}

static sva_can_status_t sc_recv(void* ctx, sva_can_frame_t* frame)
{
    sva_can_socketcan_t* self = (sva_can_socketcan_t*)ctx;
    unsigned guard;
    if ((self == NULL) || (frame == NULL) || (self->fd < 0)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    // Bounded: malformed reads are dropped and counted, at most 64 per call.
    for (guard = 0; guard < 64U; ++guard) {
        struct canfd_frame f;
        ssize_t n;
        size_t max_len;
        size_t len;
        size_t i;
        uint8_t flags = 0U;
        memset(&f, 0, sizeof f);
        n = read(self->fd, &f, sizeof f);
        if (n < 0) {
            self->last_errno = errno;
            if ((errno == EAGAIN) || (errno == EWOULDBLOCK) || (errno == EINTR)) {
                return SVA_CAN_AGAIN;
            }
            return SVA_CAN_ERR_IO;
        }
        if ((size_t)n == CAN_MTU) {
            max_len = CAN_MAX_DLEN;  // classic struct can_frame, 16 bytes
        } else if ((size_t)n == CANFD_MTU) {
            max_len = CANFD_MAX_DLEN;  // struct canfd_frame, 72 bytes
            flags |= SVA_CAN_FLAG_FD;
        } else {
            ++self->rx_short;
            continue;
        }
        len = f.len;  // can_dlc and len share the byte
        if (len > max_len) {
            ++self->rx_bad_dlc;
            continue;
        }
        if ((f.can_id & CAN_ERR_FLAG) != 0U) {
            continue;  // error frames are not requested; ignore if they come
        }
        if ((f.can_id & CAN_EFF_FLAG) != 0U) {
            flags |= SVA_CAN_FLAG_EXTENDED;
            frame->id = f.can_id & CAN_EFF_MASK;
        } else {
            frame->id = f.can_id & CAN_SFF_MASK;
        }
        if ((f.can_id & CAN_RTR_FLAG) != 0U) {
            flags |= SVA_CAN_FLAG_RTR;
        }
        frame->flags = flags;
        frame->dlc = (uint8_t)len;
        for (i = 0; i < sizeof frame->data; ++i) {
            frame->data[i] = (i < len) ? f.data[i] : 0U;
        }
        return SVA_CAN_OK;
    }
    return SVA_CAN_AGAIN;
}

sva_can_status_t sva_can_socketcan_transport(sva_can_socketcan_t* self, sva_can_transport_t* out)
{
    if ((self == NULL) || (out == NULL) || (self->fd < 0)) {
        return SVA_CAN_ERR_ARGUMENT;
    }
    out->send = sc_send;
    out->recv = sc_recv;
    out->ctx = self;
    return SVA_CAN_OK;
}
