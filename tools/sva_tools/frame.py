"""The geographic mission frame (docs/SPEC.md section 3, docs/flight-stack.md): where a
mission's grid and clock are on Earth.

`"frame": {"lat", "lon", "alt_m", "cell_m", "tick_s", "t0"}`: cell (x, y) is the point
x*cell_m east and y*cell_m north of the origin (lat, lon) in the East-North-Up tangent
plane of the WGS84 ellipsoid at the origin (height 0), i.e.
pymap3d.enu2geodetic(x*cell_m, y*cell_m, 0, lat, lon, 0); every waypoint flies alt_m
above home (the launch point); tick t is the UTC instant t0 + t*tick_s.

Resolutions: lat, lon 1e-7 degree; alt_m, cell_m 0.01 m; tick_s and t0 1 ms. A value
with finer digits is rounded half away from zero, on its shortest decimal form (the
literal as written, for up to 15 significant digits). Ranges apply to the value as
written; every limit is a multiple of its resolution, so rounding keeps a value in
range. Times are kept as integer milliseconds: every tick is an exact instant.

All WGS84 arithmetic is pymap3d's (imported on first use, so that the other commands
do not pay for it).
"""
from __future__ import annotations

import datetime as _dt
import math
import re
from dataclasses import dataclass
from decimal import ROUND_HALF_UP, Decimal
from fractions import Fraction
from typing import Any

KEYS = ("lat", "lon", "alt_m", "cell_m", "tick_s", "t0")
# Resolution of each number of the frame (t0's is T0_RESOLUTION_MS).
RESOLUTION = {"lat": Decimal("1e-7"), "lon": Decimal("1e-7"), "alt_m": Decimal("0.01"),
              "cell_m": Decimal("0.01"), "tick_s": Decimal("0.001")}

# RFC 3339's date-time, upper-case T and Z, an offset required; seconds 00..59.
_ISO = re.compile(r"([0-9]{4})-([0-9]{2})-([0-9]{2})T([0-9]{2}):([0-9]{2}):([0-9]{2})"
                  r"(?:\.([0-9]+))?(Z|([+-])([0-9]{2}):([0-9]{2}))")
ISO_RULE = ("must be an ISO 8601 date-time with a UTC offset "
            "(YYYY-MM-DDThh:mm:ss[.fff] then Z or +hh:mm or -hh:mm)")
_EPOCH = _dt.date(1970, 1, 1).toordinal()
T0_MIN = "1970-01-01T00:00:00Z"
T0_MAX = "9999-12-31T23:59:59.999Z"
MS_PER_DAY = 86_400_000


class FrameError(ValueError):
    """A value the frame cannot convert; str() is the rule broken."""


def parse_utc(text: str) -> Fraction:
    """Seconds since 1970-01-01T00:00:00Z of an ISO 8601 date-time with a UTC offset,
    exactly (every fraction digit counts). FrameError names the rule broken."""
    m = _ISO.fullmatch(text) if isinstance(text, str) else None
    if m is None:
        raise FrameError(ISO_RULE)
    year, month, day, hour, minute, second = (int(g) for g in m.groups()[:6])
    try:
        date = _dt.date(year, month, day)
    except ValueError:
        raise FrameError("must be a date of the calendar") from None
    if hour > 23 or minute > 59 or second > 59:
        raise FrameError("must have a time of day within 00:00:00..23:59:59")
    offset = 0
    if m.group(8) != "Z":
        oh, om = int(m.group(10)), int(m.group(11))
        if oh > 23 or om > 59:
            raise FrameError("must have a UTC offset within -23:59..+23:59")
        offset = (oh * 3600 + om * 60) * (1 if m.group(9) == "+" else -1)
    seconds = (date.toordinal() - _EPOCH) * 86400 + hour * 3600 + minute * 60 + second - offset
    digits = m.group(7) or ""
    return seconds + (Fraction(int(digits), 10 ** len(digits)) if digits else Fraction(0))


def _ms_half_away(seconds: Fraction) -> int:
    ms = seconds * 1000
    whole = math.floor(abs(ms) + Fraction(1, 2))
    return whole if ms >= 0 else -whole


T0_MIN_MS = int(parse_utc(T0_MIN) * 1000)
T0_MAX_MS = int(parse_utc(T0_MAX) * 1000)


def t0_rule(text: Any) -> str:
    """The rule t0 breaks (its form, its calendar, its range), or '' when it is valid."""
    try:
        seconds = parse_utc(text)
    except FrameError as e:
        return str(e)
    if seconds < Fraction(T0_MIN_MS, 1000):
        return f"must be >= {T0_MIN}"
    if seconds > Fraction(T0_MAX_MS, 1000):
        return f"must be <= {T0_MAX}"
    return ""


def format_utc(ms: int) -> str:
    """`YYYY-MM-DDThh:mm:ss.sssZ` of an instant in milliseconds since 1970 (UTC)."""
    if not T0_MIN_MS <= ms <= T0_MAX_MS:
        raise FrameError(f"must be an instant from {T0_MIN} to {T0_MAX}")
    days, rest = divmod(ms, MS_PER_DAY)
    date = _dt.date.fromordinal(_EPOCH + days)
    sec, milli = divmod(rest, 1000)
    return f"{date.isoformat()}T{sec // 3600:02d}:{sec // 60 % 60:02d}:{sec % 60:02d}.{milli:03d}Z"


def rounded(value: int | float, key: str) -> Decimal:
    """A frame number at its key's resolution, half away from zero (SPEC section 3)."""
    d = Decimal(value) if isinstance(value, int) else Decimal(repr(float(value)))
    return d.quantize(RESOLUTION[key], rounding=ROUND_HALF_UP)


def snap(v: float) -> int:
    """The nearest integer, half away from zero (the cell a coordinate falls in)."""
    return int(Decimal(v).quantize(Decimal(1), rounding=ROUND_HALF_UP))


def _pymap3d() -> Any:
    import pymap3d
    return pymap3d


@dataclass(frozen=True)
class Frame:
    """A frame at its resolutions: degrees and metres as the rounded decimals' doubles,
    times in integer milliseconds."""
    lat: float
    lon: float
    alt_m: float
    cell_m: float
    tick_ms: int
    t0_ms: int

    @staticmethod
    def from_json(doc: dict[str, Any]) -> Frame:
        """The frame of a mission or plan that passed validation (schema.first_error)."""
        return Frame(float(rounded(doc["lat"], "lat")), float(rounded(doc["lon"], "lon")),
                     float(rounded(doc["alt_m"], "alt_m")), float(rounded(doc["cell_m"], "cell_m")),
                     int(rounded(doc["tick_s"], "tick_s") * 1000),
                     _ms_half_away(parse_utc(doc["t0"])))

    def to_json(self) -> dict[str, Any]:
        """The frame as written: numbers at their resolution, t0 in UTC with milliseconds."""
        return {"lat": self.lat, "lon": self.lon, "alt_m": self.alt_m, "cell_m": self.cell_m,
                "tick_s": self.tick_ms / 1000, "t0": format_utc(self.t0_ms)}

    # --- space -----------------------------------------------------------------------

    def enu_to_geodetic(self, east: float, north: float) -> tuple[float, float]:
        """(lat, lon) of the tangent-plane point `east`, `north` metres from the origin."""
        lat, lon, _h = _pymap3d().enu2geodetic(east, north, 0.0, self.lat, self.lon, 0.0)
        return float(lat), float(lon)

    def cell_to_geodetic(self, x: int, y: int) -> tuple[float, float]:
        """(lat, lon) of cell (x, y)."""
        return self.enu_to_geodetic(x * self.cell_m, y * self.cell_m)

    def geodetic_to_enu(self, lat: float, lon: float) -> tuple[float, float]:
        """(east, north) of the tangent-plane point whose latitude and longitude are
        (lat, lon): where the ellipsoid normal through (lat, lon) meets the plane. This is
        the exact inverse of enu_to_geodetic (which drops the plane point's height)."""
        pm = _pymap3d()
        e0, n0, u0 = pm.geodetic2enu(lat, lon, 0.0, self.lat, self.lon, 0.0)
        e1, n1, u1 = pm.geodetic2enu(lat, lon, 1.0, self.lat, self.lon, 0.0)
        du = float(u1 - u0)  # ENU is affine in the height along the normal
        if du <= 0.0:
            raise FrameError(f"({lat}, {lon}) is on the far side of the Earth from the frame origin")
        h = -float(u0) / du
        return float(e0 + h * (e1 - e0)), float(n0 + h * (n1 - n0))

    def geodetic_to_cell(self, lat: float, lon: float) -> tuple[int, int]:
        """The cell whose point is nearest (lat, lon): east and north in cells, each
        rounded half away from zero."""
        east, north = self.geodetic_to_enu(lat, lon)
        return snap(east / self.cell_m), snap(north / self.cell_m)

    # --- time ------------------------------------------------------------------------

    def tick_ms_utc(self, tick: int) -> int:
        return self.t0_ms + tick * self.tick_ms

    def tick_to_utc(self, tick: int) -> str:
        """The ISO 8601 UTC instant of a tick; FrameError past 9999-12-31."""
        try:
            return format_utc(self.tick_ms_utc(tick))
        except FrameError:
            raise FrameError(f"tick {tick} is {format_ms_offset(tick * self.tick_ms)} after t0, "
                             f"beyond {T0_MAX}") from None

    def seconds_to_ticks(self, seconds: Fraction) -> Fraction:
        """Ticks since t0 of an instant `seconds` after t0 (exact)."""
        return seconds / Fraction(self.tick_ms, 1000)

    def utc_to_ticks(self, text: str) -> Fraction:
        """Ticks since t0 of an ISO 8601 instant (exact); FrameError on a bad one."""
        return self.seconds_to_ticks(parse_utc(text) - Fraction(self.t0_ms, 1000))


def format_ms_offset(ms: int) -> str:
    """A duration in milliseconds as seconds, e.g. `12.5 s`."""
    return f"{Decimal(ms).scaleb(-3).normalize():f} s"
