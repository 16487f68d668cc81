"""Ground side of lcm_latency.sh: publishes the fleet once, then ROUNDS missions with a new
revision each (so each one replans) and times mission publish -> matching plan."""
import json
import statistics
import sys
import time

import lcm

from sva_tools.lcm import wire

URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"


def main(path: str, rounds: int) -> int:
    doc = json.load(open(path, encoding="utf-8"))
    t = wire.types()
    _, fleet, mission = wire.mission_messages(doc, 1, 1)
    lc = lcm.LCM(URL)
    got = []
    # Timestamps: perf_counter for the round trip; the realtime clock as well, to split
    # it at the node's plan.utime (stamped just before it encodes and publishes).
    lc.subscribe("BENCH_PLAN", lambda c, d: got.append(
        (time.perf_counter_ns(), time.time_ns(), t.plan_t.decode(d))))
    lc.publish("BENCH_FLEET", fleet.encode())
    lat, solve, up, down = [], [], [], []
    for rev in range(2, rounds + 2):
        mission.revision = rev
        data = mission.encode()  # encoding is the ground's work, outside the timing
        del got[:]
        r0 = time.time_ns()
        t0 = time.perf_counter_ns()
        lc.publish("BENCH_MISSION", data)
        deadline = time.monotonic() + 2
        while not any(p.mission_revision == rev for _, _, p in got):
            if time.monotonic() > deadline:
                print(f"no plan for revision {rev}", file=sys.stderr)
                return 1
            lc.handle_timeout(100)
        t1, r1, p = next((ts, rt, p) for ts, rt, p in got if p.mission_revision == rev)
        if rev > 11:  # 10 warm-up rounds
            lat.append((t1 - t0) / 1000)
            solve.append(p.solve_us)
            up.append(p.utime - r0 / 1000)    # publish -> node received, decoded, planned
            down.append(r1 / 1000 - p.utime)  # node encodes, sends 19 KiB -> ground handler
    lat.sort()

    def pct(xs, f):
        xs = sorted(xs)
        return xs[min(len(xs) - 1, int(f * len(xs)))]
    q = lambda f: pct(lat, f)
    print(f"mission {doc['name']} ({len(doc['targets'])} targets, {len(doc['uavs'])} UAVs), "
          f"{len(lat)} rounds, status {p.status}, covered {p.covered}")
    print(f"latency us: median {statistics.median(lat):.0f}  p90 {q(0.90):.0f}  "
          f"p99 {q(0.99):.0f}  max {lat[-1]:.0f}")
    print(f"node solve us: median {statistics.median(solve):.0f}  p99 {pct(solve, 0.99)}  max {max(solve)}")
    for name, xs in (("ground -> node planned", up), ("node -> ground handler", down)):
        print(f"{name} us: median {statistics.median(xs):.0f}  p90 {pct(xs, 0.90):.0f}  "
              f"p99 {pct(xs, 0.99):.0f}  max {max(xs):.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 500))
