/// sva_can_transport.h -- the transports of the CAN port (sva_can_transport_t, in
/// sva_can.h): an in-memory loopback bus with two endpoints, for tests, and a Linux
/// SocketCAN socket. Each is a struct the caller owns; nothing is allocated, nothing
/// blocks.
#ifndef SVA_CAN_TRANSPORT_H
#define SVA_CAN_TRANSPORT_H

#include <stdint.h>

#include "sva/sva_can.h"

#ifdef __cplusplus
extern "C" {
#endif

/// In-memory bus with two endpoints (0 and 1): what one sends, the other receives, in
/// order. Used by tests; a test may also push raw (corrupt) frames with
/// sva_can_loopback_inject().
typedef struct {
    sva_can_frame_t frames[SVA_CAN_LOOPBACK_CAPACITY];
    uint16_t head;
    uint16_t count;
} sva_can_queue_t;

typedef struct sva_can_loopback_s sva_can_loopback_t;

/// One end of the bus (the transport context); read-only to users.
typedef struct {
    sva_can_loopback_t* bus;
    unsigned endpoint;
} sva_can_loopback_end_t;

struct sva_can_loopback_s {
    sva_can_queue_t to[2];  ///< to[e]: frames waiting for endpoint e
    uint32_t sent[2];       ///< frames sent by endpoint e
    uint32_t dropped[2];    ///< sends refused because to[1-e] was full
    sva_can_loopback_end_t priv_ends[2];
};

/// Empties the bus. O(1); allocates nothing.
void sva_can_loopback_init(sva_can_loopback_t* self);

/// A transport for `endpoint` (0 or 1) of the bus. self must outlive the transport.
/// Returns SVA_CAN_OK or SVA_CAN_ERR_ARGUMENT (NULL, endpoint > 1).
SVA_CAN_NODISCARD sva_can_status_t sva_can_loopback_transport(sva_can_loopback_t* self,
                                                              unsigned endpoint,
                                                              sva_can_transport_t* out);

/// Queues *frame for `endpoint` as if the other side had sent it. Returns SVA_CAN_OK,
/// SVA_CAN_AGAIN when full, or SVA_CAN_ERR_ARGUMENT.
SVA_CAN_NODISCARD sva_can_status_t sva_can_loopback_inject(sva_can_loopback_t* self,
                                                           unsigned endpoint,
                                                           const sva_can_frame_t* frame);

/// Removes the oldest frame waiting for `endpoint` into *out (SVA_CAN_AGAIN if none).
SVA_CAN_NODISCARD sva_can_status_t sva_can_loopback_take(sva_can_loopback_t* self,
                                                         unsigned endpoint, sva_can_frame_t* out);

/// SocketCAN (Linux only). One raw CAN socket bound to one interface, non-blocking,
/// CAN FD frames enabled on read when the interface allows it (an FD frame is
/// delivered with SVA_CAN_FLAG_FD and rejected by the decoder).
typedef struct {
    int fd;               ///< -1 when closed
    int last_errno;       ///< errno of the last failed system call, 0 if none
    uint32_t rx_short;    ///< reads shorter than a classic frame (dropped)
    uint32_t rx_bad_dlc;  ///< frames whose length exceeds their size (dropped)
} sva_can_socketcan_t;

/// Opens and binds a raw CAN socket on `ifname` (e.g. "vcan0").
/// Returns SVA_CAN_OK; SVA_CAN_ERR_NAME when ifname is empty or does not fit IFNAMSIZ
/// (including its NUL); SVA_CAN_ERR_IO when socket, fcntl, ioctl(SIOCGIFINDEX) or bind
/// fails (last_errno says why; the socket is closed again); SVA_CAN_ERR_UNSUPPORTED on
/// non-Linux builds. All-or-nothing: on error self->fd is -1.
SVA_CAN_NODISCARD sva_can_status_t sva_can_socketcan_open(sva_can_socketcan_t* self,
                                                          const char* ifname);

/// The transport over an open socket (self must outlive it).
SVA_CAN_NODISCARD sva_can_status_t sva_can_socketcan_transport(sva_can_socketcan_t* self,
                                                               sva_can_transport_t* out);

/// Closes the socket (no-op if closed).
void sva_can_socketcan_close(sva_can_socketcan_t* self);

#ifdef __cplusplus
}
#endif

#endif  // SVA_CAN_TRANSPORT_H
