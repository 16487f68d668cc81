// SocketCAN stand-in for non-Linux builds: every call reports SVA_CAN_ERR_UNSUPPORTED.

#include "sva/sva_can.h"
#include "sva/sva_can_transport.h"

sva_can_status_t sva_can_socketcan_open(sva_can_socketcan_t* self, const char* ifname)
{
    (void)ifname;
    if (self != NULL) {
        self->fd = -1;
        self->last_errno = 0;
        self->rx_short = 0U;
        self->rx_bad_dlc = 0U;
    }
    return SVA_CAN_ERR_UNSUPPORTED;
}

sva_can_status_t sva_can_socketcan_transport(sva_can_socketcan_t* self, sva_can_transport_t* out)
{
    (void)self;
    (void)out;
    return SVA_CAN_ERR_UNSUPPORTED;
}

void sva_can_socketcan_close(sva_can_socketcan_t* self)
{
    (void)self;
}
