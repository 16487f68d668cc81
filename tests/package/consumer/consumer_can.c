// Installed-tree consumer of sva::can: the CRC check values of the protocol.
#include <stdio.h>

#include "sva/sva_can.h"

int main(void)
{
    static const uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
    const uint8_t crc8 = sva_can_crc8(check, sizeof check);
    const uint32_t crc32 = sva_can_crc32(0, check, sizeof check);
    if (crc8 != 0x4Bu || crc32 != 0xCBF43926u) {
        fprintf(stderr, "consumer_can: crc8 0x%02X crc32 0x%08lX, want 0x4B 0xCBF43926\n",
                (unsigned)crc8, (unsigned long)crc32);
        return 1;
    }
    printf("consumer_can: ok\n");
    return 0;
}
