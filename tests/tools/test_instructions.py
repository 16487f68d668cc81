"""scripts/instructions.sh at its smallest (one 3 x 3 mission, flow): callgrind counts the
instructions of both builds it makes, the host's and the static i686 one (which needs
the cross tests' jansson for i686: build/cross/i686/prefix), and estimates the
Cortex-M4's time; a build that fails, or a count that is missing ("-"), fails."""
import os
import re
import subprocess

from conftest import REPO

SCRIPT = REPO / "scripts" / "instructions.sh"


def test_both_builds_are_counted(sva_bin, tmp_path):
    env = {**os.environ, "SVA_NO_BUILD": "1", "SVA_SIZES": "3x3", "SVA_ALGOS": "flow",
           "SVA_INSTRUCTIONS_OUT": str(tmp_path / "out")}
    r = subprocess.run(["bash", str(SCRIPT), "1"], cwd=REPO, env=env, capture_output=True, text=True,
                       timeout=280)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "x86-64" in r.stdout and "i686" in r.stdout, r.stdout + r.stderr
    row = re.search(r"^3x3\s+flow\s+(\d+) \((\d+)\)\s+(\d+) \((\d+)\)\s+(\d+\.\d{3})$", r.stdout, re.M)
    assert row, r.stdout
    host, host_max, i686, i686_max, m4_ms = row.groups()
    assert int(host) == int(host_max) > 1000 and int(i686) == int(i686_max) > 1000  # one mission
    assert abs(float(m4_ms) - int(i686) * 1.5 / 168_000) < 0.001  # CPI 1.5 at 168 MHz
    assert (tmp_path / "out" / "sva-i686").is_file()
