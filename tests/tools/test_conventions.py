"""One command-line convention across sva's programs (docs/cli.md, "Every program"):
`--version` prints one line "PROGRAM VERSION" on stdout and exits 0, the version being
the library's (SVA_VERSION_* of sva.h, which the Python package's must equal); `--help`
prints the usage on stdout and exits 0; the same option has the same name everywhere:
`--algo` for the algorithm (the nodes keep `--algorithm` as the same option) and
`-o/--out` for an output file (`sva-tools lcm` keeps `--output`).

The C programs come from the build (SVA_BIN, SVA_NODE, SVA_CAN_NODE,
SVA_MAVLINK_BRIDGE, set by tests/tools/CMakeLists.txt for each program the build has);
a port the build does not have is reported as skipped, a named program that is missing
fails."""
import os
import re
import struct
import subprocess
from pathlib import Path

import pytest

from conftest import REPO

SVA_TOOLS = REPO / "tools" / "sva-tools"
PROGRAMS = {  # program name: the environment variable naming the built program
    "sva": "SVA_BIN",
    "sva_node": "SVA_NODE",
    "sva_can_node": "SVA_CAN_NODE",
    "sva_mavlink_bridge": "SVA_MAVLINK_BRIDGE",
}
# More than SVA_BFA_MAX_TARGETS (12) targets: bfa refuses it with a line naming the limit.
BIG = REPO / "fixtures" / "missions" / "rand_25_1.json"


def library_version():
    text = (REPO / "core" / "include" / "sva" / "sva.h").read_text()
    parts = [re.search(rf"^#define SVA_VERSION_{part} (\d+)$", text, re.M)
             for part in ("MAJOR", "MINOR", "PATCH")]
    assert all(parts), "sva.h: no SVA_VERSION_MAJOR/MINOR/PATCH"
    return ".".join(m.group(1) for m in parts)


VERSION = library_version()


def command(name):
    """The command line that runs program NAME, or a skip when the build has no such port."""
    if name == "sva-tools":
        return [str(SVA_TOOLS)]
    path = os.environ.get(PROGRAMS[name], "")
    if not path:
        if name == "sva":
            pytest.fail("SVA_BIN is not set (tests/tools/CMakeLists.txt sets it)")
        pytest.skip(f"{name} is not built ({PROGRAMS[name]} not set)")
    assert Path(path).is_file(), f"{PROGRAMS[name]}={path}: no such program"
    return [path]


def run(cmd, *args):
    return subprocess.run([*cmd, *map(str, args)], capture_output=True, text=True, timeout=120)


ALL = ["sva", "sva-tools", "sva_node", "sva_can_node", "sva_mavlink_bridge"]


def test_python_package_version_is_the_library_version():
    import sva_tools

    assert sva_tools.__version__ == VERSION
    pyproject = (REPO / "tools" / "pyproject.toml").read_text()
    assert re.search(r'^version = "([^"]+)"$', pyproject, re.M).group(1) == VERSION


@pytest.mark.parametrize("name", ALL)
def test_version_is_one_line_program_and_version(name):
    r = run(command(name), "--version")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    first = r.stdout.splitlines()[0]
    if name == "sva":
        # sva's first line, then its bounds (docs/cli.md)
        assert first.startswith(f"sva {VERSION} "), r.stdout
    else:
        assert r.stdout == f"{name} {VERSION}\n"


@pytest.mark.parametrize("name", ALL)
def test_help_is_the_usage_on_stdout(name):
    r = run(command(name), "--help")
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    assert r.stdout.startswith(f"usage: {name}"), r.stdout
    assert "--version" in r.stdout


@pytest.mark.parametrize("name", ALL)
def test_an_unknown_option_is_one_error_line_and_status_2(name):
    """Every program refuses an option it does not know the same way: one line on stderr
    `<program>: error: ...` (after argparse's usage line for sva-tools), naming the option
    in the nodes and the bridge, and exit status 2."""
    r = run(command(name), "--no-such-option", "x")
    assert r.returncode == 2, (r.returncode, r.stderr)
    first = r.stderr.splitlines()[0] if not r.stderr.startswith("usage:") else \
        [ln for ln in r.stderr.splitlines() if not ln.startswith(("usage:", " "))][0]
    assert first.startswith(f"{name}: error: "), r.stderr
    if name not in ("sva", "sva-tools"):  # these two name the command they did not find
        assert "--no-such-option" in first, r.stderr


def one_event_log(tmp_path):
    """An LCM log of one event on an unrelated channel: a file:// provider that lets
    sva_node start, print its start line and end (--exit-on-eof) with no network."""
    channel, data = b"OTHER", b"\0" * 8
    log = tmp_path / "one.lcmlog"
    log.write_bytes(struct.pack(">IqqII", 0xEDA1DA01, 0, 0, len(channel), len(data)) + channel + data)
    return log


@pytest.mark.parametrize("option", ["--algo", "-a", "--algorithm"])
def test_sva_node_takes_algo(option, tmp_path):
    node = command("sva_node")
    log = one_event_log(tmp_path)
    r = run(node, "--url", f"file://{log}?mode=r", "--exit-on-eof", option, "flow")
    assert r.returncode == 0, r.stderr
    start = [ln for ln in r.stderr.splitlines() if ln.startswith("sva_node: in ")]
    assert len(start) == 1 and "; algorithm flow;" in start[0], r.stderr
    # a bad name is refused with the option's name as given (-a is --algo)
    r = run(node, option, "simplex")
    named = "--algorithm" if option == "--algorithm" else "--algo"
    assert r.returncode == 2
    assert r.stderr == f"sva_node: error: {named}: unknown name 'simplex' (sva, ga, hga, bfa, flow)\n"


def test_sva_node_help_names_algo():
    out = run(command("sva_node"), "--help").stdout
    assert "-a, --algo NAME" in out and "--algorithm" in out


@pytest.mark.parametrize("option", ["--algo", "--algorithm"])
def test_sva_can_node_takes_algo(option):
    node = command("sva_can_node")
    # bfa plans the mission before the node opens its interface: its refusal shows that
    # the option reached the planner, with no CAN bus.
    r = run(node, "--mission", BIG, "--iface", "sva-no-such-if", option, "bfa")
    assert r.returncode == 1
    assert "SVA_BFA_MAX_TARGETS" in r.stderr, r.stderr
    r = run(node, "--mission", BIG, option, "simplex")
    assert r.returncode == 2
    assert r.stderr == f'sva_can_node: error: {option}: unknown algorithm "simplex" (sva, ga, hga, bfa, flow)\n'


def test_sva_can_node_help_names_algo():
    out = run(command("sva_can_node"), "--help").stdout
    assert "[--algo sva|ga|hga|bfa|flow]" in out and "--algorithm" in out


@pytest.mark.parametrize("subcommand,args", [
    ("send", ["mission.json"]),
    ("scenario", ["scenario.json"]),
    ("record", []),
])
@pytest.mark.parametrize("option", ["-o", "--out", "--output"])
def test_sva_tools_lcm_takes_out(subcommand, args, option):
    from sva_tools.commands import lcm

    parsed = lcm._parser().parse_args([subcommand, *args, option, "file.out"])
    assert parsed.out == "file.out"


def test_sva_tools_lcm_send_help_names_out():
    r = run([str(SVA_TOOLS)], "lcm", "send", "--help")
    assert r.returncode == 0, r.stderr
    assert "-o OUT, --out OUT, --output OUT" in r.stdout
