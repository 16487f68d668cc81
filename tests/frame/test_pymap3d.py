"""The C frame library (PROJ) against pymap3d: every cell that frame_tool prints must
be where pymap3d.enu2geodetic puts the same East-North offset from the same origin,
within 1e-9 degree."""
import math
import os
import subprocess

import pymap3d
import pytest

TOOL = os.environ.get("SVA_FRAME_TOOL", "")
TOL_DEG = 1e-9


def lines():
    assert TOOL, "SVA_FRAME_TOOL is not set (ctest sets it)"
    out = subprocess.run([TOOL], capture_output=True, text=True, timeout=60, check=True).stdout
    rows = [line.split() for line in out.splitlines()]
    assert len(rows) == 28 and all(len(r) == 7 for r in rows), out
    return rows


def test_cells_agree_with_pymap3d():
    worst = 0.0
    for lat0, lon0, cell, x, y, lat, lon in lines():
        lat0, lon0, cell, lat, lon = map(float, (lat0, lon0, cell, lat, lon))
        e, n = int(x) * cell, int(y) * cell
        plat, plon, _ = pymap3d.enu2geodetic(e, n, 0.0, lat0, lon0, 0.0)
        dlon = (lon - plon + 180.0) % 360.0 - 180.0  # the antimeridian frame wraps
        worst = max(worst, abs(lat - plat), abs(dlon))
        assert abs(lat - plat) <= TOL_DEG and abs(dlon) <= TOL_DEG, (lat0, lon0, cell, x, y, lat, lon,
                                                                      plat, plon)
    print(f"largest difference: {worst:.3g} degree")


def test_the_comparison_can_fail():
    """A cell off by one (10 m at the first frame) is far outside the tolerance."""
    lat0, lon0, cell, x, y, lat, lon = lines()[1]
    plat, plon, _ = pymap3d.enu2geodetic((int(x) + 1) * float(cell), int(y) * float(cell), 0.0,
                                         float(lat0), float(lon0), 0.0)
    assert math.hypot(float(lat) - plat, float(lon) - plon) > 1e-5


def test_origin_is_the_frame_origin():
    for lat0, lon0, _, x, y, lat, lon in lines():
        if (x, y) == ("0", "0"):
            assert float(lat) == pytest.approx(float(lat0), abs=1e-12)
            assert float(lon) == pytest.approx(float(lon0), abs=1e-12)
