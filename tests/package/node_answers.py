"""Starts an installed sva_node and waits for its status messages over udpm multicast:
    node_answers.py /path/to/sva_node
Runs only inside the network namespace netns_run.sh makes (SVA_LCM_NETNS set), with
PYTHONPATH holding the lcm-gen Python types (sva_lcm). Exit 0 iff the node published
two status messages that decode, with increasing seq, and then exited 0 on SIGTERM."""
import os
import select
import signal
import subprocess
import sys
import time

import lcm
from sva_lcm import node_status_t

URL = "udpm://239.255.76.67:7667?ttl=0"
PREFIX = "PKG_"


def main() -> int:
    if not os.environ.get("SVA_LCM_NETNS"):
        print("node_answers: run me through tools/netns/netns_run.sh", file=sys.stderr)
        return 1
    node = sys.argv[1]
    seen = []
    lc = lcm.LCM(URL)
    lc.subscribe(PREFIX + "STATUS", lambda _ch, data: seen.append(node_status_t.decode(data)))
    proc = subprocess.Popen([node, "--url", URL, "--prefix", PREFIX, "--status-ms", "100"])
    deadline = time.monotonic() + 10.0
    try:
        while len(seen) < 2 and time.monotonic() < deadline and proc.poll() is None:
            ready, _, _ = select.select([lc.fileno()], [], [], 0.2)
            if ready:
                lc.handle()
    finally:
        if proc.poll() is None:
            proc.send_signal(signal.SIGTERM)
        rc = proc.wait(timeout=10)
    if len(seen) < 2:
        print(f"node_answers: {len(seen)} status messages from {node} in 10 s (exit {rc})", file=sys.stderr)
        return 1
    if not seen[1].seq > seen[0].seq:
        print(f"node_answers: status seq {seen[0].seq} then {seen[1].seq}", file=sys.stderr)
        return 1
    if rc != 0:
        print(f"node_answers: {node} exited {rc} on SIGTERM", file=sys.stderr)
        return 1
    print(f"node_answers: {node} published status (seq {seen[0].seq}, {seen[1].seq}) and stopped cleanly")
    return 0


if __name__ == "__main__":
    sys.exit(main())
