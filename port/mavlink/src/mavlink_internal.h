// Private to sva::mavlink: what the endpoint and link files share.
#ifndef SVA_MAVLINK_INTERNAL_H
#define SVA_MAVLINK_INTERNAL_H

#include "sva/sva_mavlink.h"

/// Resolves the vehicle's host for sockets of `socktype` (SOCK_DGRAM, SOCK_STREAM) into
/// addr[0..SVA_MAVLINK_ADDR_SIZE) (a struct sockaddr), *addr_len and *family. False with
/// one line in err ("vehicle 3: tcp:nohost:5760: cannot resolve: ...").
bool sva_mavlink_resolve(const sva_mavlink_vehicle_spec_t* spec, int socktype, uint8_t* addr,
                         uint32_t* addr_len, int* family, char* err, size_t err_size);

/// Makes `fd` non-blocking. False with errno set.
bool sva_mavlink_set_nonblocking(int fd);

#endif  // SVA_MAVLINK_INTERNAL_H
