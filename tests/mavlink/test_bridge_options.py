"""sva_mavlink_bridge's command line: each bad value of the report options and of
--vehicle is refused before anything starts, with exit 2 and one line naming the option,
the rule and the limit; --help lists the options; --version is one line."""
from __future__ import annotations

import os
import re
import subprocess

import pytest

BRIDGE = os.environ["SVA_MAVLINK_BRIDGE"]
OK_VEHICLE = ["--vehicle", "1=tcp:127.0.0.1:5760"]


def run(*args):
    return subprocess.run([BRIDGE, *args], capture_output=True, text=True, timeout=30)


@pytest.mark.parametrize("args,line", [
    (["--report-ms", "9"], '--report-ms: must be an integer in [10, 3600000], got "9"'),
    (["--report-ms", "3600001"], '--report-ms: must be an integer in [10, 3600000], got "3600001"'),
    (["--report-ms", "1s"], '--report-ms: must be an integer in [10, 3600000], got "1s"'),
    (["--heartbeat-timeout-ms", "0"],
     '--heartbeat-timeout-ms: must be an integer in [1, 600000], got "0"'),
    (["--heartbeat-timeout-ms", "600001"],
     '--heartbeat-timeout-ms: must be an integer in [1, 600000], got "600001"'),
    (["--fuel-capacity", "-1"], '--fuel-capacity: must be an integer in [0, 1000000000], got "-1"'),
    (["--fuel-capacity", "1000000001"],
     '--fuel-capacity: must be an integer in [0, 1000000000], got "1000000001"'),
    (["--fuel-capacity", ""], '--fuel-capacity: must be an integer in [0, 1000000000], got ""'),
    (["--cruise-speed", "0"], '--cruise-speed: must be a number in (0, 100], got "0"'),
    (["--cruise-speed", "100.5"], '--cruise-speed: must be a number in (0, 100], got "100.5"'),
    (["--cruise-speed", "nan"], '--cruise-speed: must be a number in (0, 100], got "nan"'),
    (["--cruise-speed", "9m"], '--cruise-speed: must be a number in (0, 100], got "9m"'),
])
def test_a_bad_report_option_is_one_line_and_exit_2(args, line):
    p = run(*OK_VEHICLE, *args)
    assert p.returncode == 2
    assert p.stdout == ""
    assert p.stderr == f"sva_mavlink_bridge: error: {line}\n"


@pytest.mark.parametrize("value,line", [
    ("1=serial:/dev/ttyS0", '--vehicle: 1: the endpoint must start with udp: or tcp:, got '
                            '"serial:/dev/ttyS0"'),
    ("1=tcp:127.0.0.1", '--vehicle: 1: must be tcp:HOST:PORT[:SYSID], got "tcp:127.0.0.1"'),
    ("1=tcp:127.0.0.1:0", '--vehicle: 1: PORT must be an integer in [1, 65535], got "0"'),
    ("1=tcp:127.0.0.1:5760:256", '--vehicle: 1: SYSID must be an integer in [1, 255], got "256"'),
    ("tcp:127.0.0.1:5760", '--vehicle: must be UAV_ID=udp:HOST:PORT[:SYSID] or '
                           'UAV_ID=tcp:HOST:PORT[:SYSID], got "tcp:127.0.0.1:5760"'),
])
def test_a_bad_vehicle_is_one_line_and_exit_2(value, line):
    p = run("--vehicle", value)
    assert p.returncode == 2
    assert p.stderr == f"sva_mavlink_bridge: error: {line}\n"


def test_an_unresolvable_tcp_host_is_an_error_at_start():
    p = run("--vehicle", "4=tcp:no-such-host.invalid:5760")
    assert p.returncode == 2
    assert p.stderr.startswith("sva_mavlink_bridge: error: vehicle 4: tcp:no-such-host.invalid:5760: "
                               "cannot resolve: ")
    assert p.stderr.count("\n") == 1


def test_help_lists_the_new_options():
    p = run("--help")
    assert p.returncode == 0
    for opt in ("--report-ms", "--heartbeat-timeout-ms", "--fuel-capacity", "UAV_ID=tcp:HOST:PORT",
                "--version"):
        assert opt in p.stdout


def test_version_is_one_line_and_exit_0():
    p = run("--version")
    assert p.returncode == 0
    assert p.stderr == ""
    assert re.fullmatch(r"sva_mavlink_bridge \d+\.\d+\.\d+\n", p.stdout), p.stdout
