"""sva_can_node prints user-supplied text (option values, the mission file name)
escaped: exactly the expected lines, no raw control bytes. These paths end before
the node opens its CAN interface, so no bus is needed."""
import os
import subprocess

import pytest

NODE = os.environ["SVA_CAN_NODE"]
HOSTILE = "x\n\x1b[31mforged"
HOSTILE_SHOWN = "x\\n\\x1b[31mforged"


def run(*args):
    r = subprocess.run([NODE, *args], capture_output=True, text=True, timeout=30)
    assert "\x1b" not in r.stderr and "\r" not in r.stderr, r.stderr
    return r.returncode, r.stderr.splitlines()


@pytest.mark.parametrize("option", ["--algo", "--algorithm"])
def test_algorithm_value_is_escaped(option):
    rc, lines = run("--mission", "m.json", option, HOSTILE)
    assert rc == 2
    assert lines == [f'sva_can_node: error: {option}: unknown algorithm "{HOSTILE_SHOWN}" (sva, ga, hga, bfa, flow)']


def test_integer_value_and_unknown_option_are_escaped():
    rc, lines = run("--settle-ms", HOSTILE)
    assert rc == 2
    assert lines == [f'sva_can_node: error: --settle-ms: must be an integer in [0, 2147483647], got "{HOSTILE_SHOWN}"']
    rc, lines = run("--" + HOSTILE, "1")
    assert rc == 2 and lines[0] == f"sva_can_node: error: unknown option --{HOSTILE_SHOWN}"


def test_mission_file_name_is_escaped(tmp_path):
    rc, lines = run("--mission", str(tmp_path / HOSTILE))
    shown = f"{tmp_path}/{HOSTILE_SHOWN}"
    assert rc == 1
    assert lines == [f"sva_can_node: error: {shown}: {shown}: cannot open: No such file or directory"]
