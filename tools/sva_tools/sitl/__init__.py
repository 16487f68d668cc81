"""Scenarios flown by real autopilots (ArduCopter SITL): the settings, the vehicles, the
flight, its record and its judgement (`sva-tools sitl`, docs/sitl.md)."""
