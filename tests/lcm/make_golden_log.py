"""Writes tests/lcm/data/golden.lcmlog, the input of test_lcm_golden (run by hand when
the wire types change; the log is committed as the golden input):

    PYTHONPATH=tools .venv/bin/python tests/lcm/make_golden_log.py

The mission is the bundled fixtures/missions/rand_7_2.json (a mid-mission fleet
state: UAVs away from the depot, ready times, one stranded UAV). Events on channel
prefix GOLD_, in order: fleet (rev 1), truncated fleet, mission
(rev 1) -> plan 1; mission with a wrong fingerprint; mission with target_count 257;
fleet with a UAV at x = 40000; the same mission again (unchanged); a mission of
mission_t version 1; a fleet of rev 2 with UAV 3 unavailable -> plan 2.
"""
import json
import sys
from pathlib import Path

import lcm

from sva_tools.lcm import wire

here = Path(__file__).resolve().parent
doc = json.loads((here.parents[1] / "fixtures" / "missions" / "rand_7_2.json").read_text())
_, fleet, mission = wire.mission_messages(doc, 1, 1)
fb, mb = fleet.encode(), mission.encode()
bad_fp = bytes([mb[0] ^ 0x80]) + mb[1:]
_, over, _ = wire.mission_messages(doc, 1, 1)
m2 = wire.mission_messages(doc, 1, 1)[2]
m2.target_count = 257
_, f_val, _ = wire.mission_messages(doc, 1, 1)
f_val.uavs[1].x = 40000
m_v1 = wire.mission_messages(doc, 3, 3)[2]
m_v1.version = 1
_, f2, _ = wire.mission_messages(doc, 2, 2)
f2.uavs[2].health = f2.uavs[2].HEALTH_UNAVAILABLE

events = [("GOLD_FLEET", fb), ("GOLD_FLEET", fb[:100]), ("GOLD_MISSION", mb),
          ("GOLD_MISSION", bad_fp), ("GOLD_MISSION", m2.encode()),
          ("GOLD_FLEET", f_val.encode()), ("GOLD_MISSION", mb), ("GOLD_MISSION", m_v1.encode()),
          ("GOLD_FLEET", f2.encode())]
out = Path(sys.argv[1]) if len(sys.argv) > 1 else here / "data" / "golden.lcmlog"
log = lcm.EventLog(str(out), "w", overwrite=True)
for i, (ch, data) in enumerate(events):
    log.write_event(1_000_000 + 1000 * i, ch, data)
log.close()
print(f"wrote {len(events)} events to {out}")
