"""Shared helpers of the host-tools tests (tests/tools)."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))

from sva_tools import io, model  # noqa: E402


def mission(uavs, targets, name="t", depot=(0, 0), tpc=1, hover=0, overlap=70):
    """Mission from compact tuples: uavs (id, x, y, fuel[, ready_at]), targets
    (id, x, y, start, end, need)."""
    return model.Mission(name, depot, [model.Uav(*u) for u in uavs], [model.Target(*t) for t in targets],
                     tpc, hover, overlap)


def write(tmp_path, name, doc):
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return str(p)


def sva_tools(*args, **kw):
    """Runs `python -m sva_tools ARGS` (env=... replaces os.environ); returns CompletedProcess (text)."""
    env = dict(kw.pop("env", os.environ))
    env["PYTHONPATH"] = str(REPO / "tools") + os.pathsep + env.get("PYTHONPATH", "")
    return subprocess.run([sys.executable, "-m", "sva_tools", *map(str, args)],
                          capture_output=True, text=True, env=env, **kw)


@pytest.fixture
def sva_bin():
    """The C CLI. Missing is a failure, not a skip: these tests are part of the suite."""
    from sva_tools import cbin
    try:
        return cbin.sva_bin()
    except cbin.CliMissing as e:
        pytest.fail(f"{e}. The tools tests need the C CLI: run scripts/build.sh first.")
