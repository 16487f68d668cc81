// Installed-tree consumer of sva::lcm: an in-process LCM (memq://, which needs the
// static liblcm and GLib), a node on it, and one status message through it.
#include <stdio.h>
#include <string.h>

#include "sva/sva_lcm.h"

static sva_lcm_node_t node;
static int received;

static void on_status(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
{
    (void)channel;
    (void)user;
    sva_lcm_node_status_t msg;
    if (sva_lcm_node_status_t_decode(rbuf->data, 0, (int)rbuf->data_size, &msg) > 0) {
        received += 1;
        sva_lcm_node_status_t_decode_cleanup(&msg);
    }
}

int main(void)
{
    char escaped[32];
    lcm_t* lcm = lcm_create("memq://");
    if (lcm == NULL) {
        fprintf(stderr, "consumer_lcm: lcm_create(memq://) failed\n");
        return 1;
    }
    if (sva_lcm_channel_escape("SVA_.X", escaped, sizeof escaped) != SVA_OK ||
        strcmp(escaped, "SVA_\\.X") != 0) {
        fprintf(stderr, "consumer_lcm: sva_lcm_channel_escape\n");
        return 1;
    }
    if (sva_lcm_node_init(&node, lcm, "SVA_", SVA_ALGO_SVA) != SVA_OK) {
        fprintf(stderr, "consumer_lcm: sva_lcm_node_init failed\n");
        return 1;
    }
    (void)lcm_subscribe(lcm, "SVA_STATUS", on_status, NULL);
    if (sva_lcm_publish_status(&node, 1) != SVA_OK || lcm_handle_timeout(lcm, 1000) <= 0 ||
        received != 1) {
        fprintf(stderr, "consumer_lcm: no status message came back over memq://\n");
        return 1;
    }
    lcm_destroy(lcm);
    printf("consumer_lcm: ok\n");
    return 0;
}
