#!/bin/busybox sh
# /init of the SocketCAN VM test. Console on ttyS0; results on ttyS1 for the host.
/bin/busybox --install -s /bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
report() { echo "$*" > /dev/ttyS1; }
fail() { report "=== fail $*"; poweroff -f; }

for m in $(cat /modules.order); do insmod "/lib/modules/$m.ko" || fail "insmod $m"; done
ip link add dev vcan0 type vcan || fail "ip link add vcan0"
ip link set up vcan0 || fail "ip link set up vcan0"

candump -L vcan0 > /tmp/capture.log 2>/tmp/candump.err &
cpid=$!
sleep 0.5
can_vm_bridge vcan0 "$(cat /clock_tick)" > /tmp/bridge.out 2> /tmp/bridge.err &
bpid=$!
sleep 0.2
# A PLAN_BEGIN of protocol version 1: the bridge must refuse it (NACK BAD_VERSION).
cansend vcan0 "$(cat /bad_begin.frame)" || fail "cansend"
sleep 0.2
sva_can_node --mission /mission.json --iface vcan0 --algorithm sva --print-plans \
    --exit-after-acks 2 --max-runtime-ms 20000 > /tmp/node.out 2> /tmp/node.err
nrc=$?
wait $bpid
brc=$?
sleep 0.3
kill $cpid
wait $cpid 2>/dev/null
{
    echo "=== rc node=$nrc bridge=$brc"
    echo "=== capture"; cat /tmp/capture.log
    echo "=== node.out"; cat /tmp/node.out
    echo "=== node.err"; cat /tmp/node.err
    echo "=== bridge.out"; cat /tmp/bridge.out
    echo "=== bridge.err"; cat /tmp/bridge.err /tmp/candump.err
    echo "=== end"
} > /dev/ttyS1
poweroff -f
