"""`sva-tools sitl SCENARIO.json [--algo A] [--speedup N] [--frame LAT,LON,ALT_M,CELL_M,TICK_S]
[--sitl PATH] [--out LOG.json] [--plot PNG]`: a scenario flown by real autopilots.

One ArduCopter SITL process per UAV of the mission (home at its start cell), sva_node
and sva_mavlink_bridge over LCM, all in a network namespace made for the run (root).
The node plans, the bridge uploads each route as a MAVLink mission and reports every
vehicle's telemetry back to the node; the tool is the ground operator (it arms each
vehicle in AUTO once it holds a mission) and makes the scenario's events real at their
ticks on the vehicles' GPS clock: uav_lost kills a vehicle's process, uav_back starts a
fresh one on its cell, the other events are published as a ground station would.

The frame is the mission's, else --frame (default 47.3977,8.5456,30,25,6: 25 m cells,
6 s ticks, 30 m above home; t0 chosen on the vehicles' clock). A frame whose plan speed
cell_m / (ticks_per_cell * tick_s) exceeds 6 m/s, or whose cell is shorter in time than
the copter needs for a one-cell leg from a hold, is refused; the vehicles are commanded
10 m/s. Coverage is judged from
each vehicle's telemetry: present within max(cell_m / 2, 5 m) of the target for its
whole window. The last line: `covered C of K coverable (plan promised P); arrival slack
p50 X s, p1 Y s; late arrivals N`. --fault KIND:UAV_ID[:T_S] (repeatable) makes a vehicle
fail: silent-upload (its link to the bridge goes silent at an upload), reject-item (the
vehicle refuses an upload), reboot (a fresh SITL where it is). docs/sitl.md has the
details and measurements.
"""
from .cli import add_parser  # noqa: F401
