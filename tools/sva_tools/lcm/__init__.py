"""LCM ground side of sva: publish a mission and fleet state, collect the plan.

`python -m sva_tools.lcm send MISSION.json` (or `sva-tools lcm send` once the
sva-tools entry point dispatches here). The wire types come from port/lcm/types/*.lcm
(see wire.py for where the Python codec comes from).
"""
