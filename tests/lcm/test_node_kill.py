"""Crash safety of sva_node end to end (docs/lcm.md, "Crash safety"), in a network
namespace made for this run (tools/netns/netns_run.sh): real processes, real multicast,
the journal on disk.

- `sva-tools sim --via lcm --kill-node 3 --seed S` on bundled scenarios: the node is
  killed with SIGKILL at seeded moments and restarted on its journal, nothing is sent
  again, and every flight equals the uninterrupted one (its plans, replans, tracks and
  outcomes) and passes the independent flight checker;
- a torn record on disk (a write cut short) is cut at its byte offset on restart, and
  the node resumes where the last whole record left it;
- a journal of another sva version, one that is no journal and one written with other
  options are refused (exit 3, the message naming both versions or both option sets) and
  left untouched; `--state-reset` discards them; a second node on the same folder is
  refused.
"""
import json
import os
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

import pytest

if not os.environ.get("SVA_LCM_NETNS"):
    pytest.skip("run through tools/netns/netns_run.sh (multicast only in a private netns)",
                allow_module_level=True)

import lcm  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
sys.path.insert(0, str(REPO / "tests" / "tools"))

from flight_checker import check_flight  # noqa: E402
from sva_tools.lcm import simnode, wire  # noqa: E402

SCENARIOS = REPO / "fixtures" / "scenarios"
NODE = os.environ["SVA_NODE"]
URL = "udpm://239.255.76.67:7667?ttl=0"
JOURNAL = "sva_node.journal"
SEEDS = range(1, 7)
KILLS = 3


def sim(*args, timeout=300):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO / "tools")
    return subprocess.run([sys.executable, "-m", "sva_tools", "sim", *args], capture_output=True,
                          text=True, env=env, timeout=timeout)


def fly(tmp_path, scenario, algo, *extra):
    out = tmp_path / f"{scenario.stem}-{algo}-{'-'.join(extra) or 'whole'}.json"
    r = sim(str(scenario), "--algo", algo, "--via", "lcm", "--out", str(out), *extra)
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text())


@pytest.mark.parametrize("scenario, algo", [("hand_events", "sva"), ("gen_25t5u_events", "flow"),
                                            ("hand_loss", "hga")])
def test_killed_node_flies_as_the_uninterrupted_one(tmp_path, scenario, algo):
    path = SCENARIOS / f"{scenario}.json"
    events = json.loads(path.read_text())["events"]
    messages = 1 + len(events) + (0 if any(e["at"] == 0 for e in events) else 1)
    whole = fly(tmp_path, path, algo)
    assert "node_kills" not in whole and whole["node"]["restarts"] == 0
    want = simnode.comparable_flight(whole)
    kills = 0
    moments = {}
    for seed in SEEDS:
        log = fly(tmp_path, path, algo, "--kill-node", str(KILLS), "--seed", str(seed))
        moments[seed] = [k["after_message"] for k in log["node_kills"]]
        # the seed's moments, drawn again the same
        assert moments[seed] == [k for k, _ in simnode.kill_plan(events, KILLS, seed)]
        assert check_flight(log) == []
        assert simnode.comparable_flight(log) == want, f"seed {seed}: the flight differs after its kills"
        done = log["node_kills"]
        assert len(done) == KILLS == log["node"]["restarts"]
        assert [k["after_message"] for k in done] == sorted(k["after_message"] for k in done)
        msgs = [m for r in log["replans"] for m in r["node"]["messages"]]
        assert len(msgs) == messages  # nothing was sent twice
        for k in done:
            assert 1 <= k["after_message"] < messages
            answered = msgs[k["after_message"] - 1]  # the answer before the kill
            assert k["plan_id"] == answered["plan_id"]
            assert k["now"] == (answered.get("now") or 0) == k["tick"]
            # header aside, every input record since the last new mission: the fleet, the
            # mission, one event per accepted event message
            assert k["replayed"] == 2 + (k["after_message"] - 1)
        kills += len(done)
    assert kills == KILLS * len(SEEDS)
    assert len({tuple(m) for m in moments.values()}) > 1  # the seeds draw other moments


def test_kill_node_needs_a_node_of_its_own(tmp_path):
    path = str(SCENARIOS / "hand_events.json")
    r = sim(path, "--kill-node", "2")
    assert r.returncode == 2 and "--kill-node: needs --via lcm" in r.stderr
    r = sim(path, "--via", "lcm", "--attach", "--kill-node", "2")
    assert r.returncode == 2 and "(not --attach)" in r.stderr


# --- the node and its journal on disk ---------------------------------------------------

class Node:
    """sva_node with --state-dir, its status read over LCM."""

    def __init__(self, state_dir, *extra, url=URL):
        self.proc = subprocess.Popen([NODE, "--url", url, "--status-ms", "100", "--state-dir",
                                      str(state_dir), *extra], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)

    def stop(self, sig=15):
        self.proc.send_signal(sig)
        return self.proc.communicate(timeout=10)


def status(timeout=5.0):
    """The first node_status_t on SVA_STATUS."""
    t = wire.types()
    lc = lcm.LCM(URL)
    got = []
    lc.subscribe("SVA_STATUS", lambda ch, data: got.append(t.node_status_t.decode(data)))
    end = time.monotonic() + timeout
    while not got and time.monotonic() < end:
        lc.handle_timeout(100)
    assert got, "no status"
    return got[0]


def version():
    return subprocess.run([NODE, "--version"], capture_output=True, text=True,
                          check=True).stdout.split()[1]


def record(kind, payload):
    head = struct.pack("<IB", len(payload), kind) + payload
    return head + struct.pack("<I", zlib.crc32(head))


def test_torn_record_on_disk_is_cut_and_the_node_resumes(tmp_path):
    state = tmp_path / "state"
    node = Node(state, "--change-penalty", "2")
    status()
    env = dict(os.environ, PYTHONPATH=str(REPO / "tools"))
    r = subprocess.run([sys.executable, "-m", "sva_tools", "lcm", "scenario",
                        str(SCENARIOS / "hand_events.json"), "-o", str(tmp_path / "rec.json")],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode in (0, 1), r.stderr  # 1: the scenario has events the node refuses
    rec = json.loads((tmp_path / "rec.json").read_text())
    last = [x for x in rec["replans"] if x["accepted"]][-1]
    node.stop(9)  # SIGKILL
    journal = state / JOURNAL
    whole = journal.read_bytes()
    # a write the kill cut short: the first 30 bytes of one more event record
    with open(journal, "ab") as f:
        f.write(whole[-71:-41])
    node = Node(state, "--change-penalty", "2")
    s = status()
    out, err = node.stop()
    assert node.proc.returncode == 0, err
    assert journal.read_bytes() == whole  # cut back to the last whole record
    assert f"a torn tail cut at byte {len(whole)}" in out
    assert (f"torn or corrupt record at byte {len(whole)} (short record: 30 of its 71 bytes): "
            f"cut there, 30 bytes dropped") in err
    assert f"records replayed, revision {last['revision']}, now {last['now']}, " \
           f"plan id {last['plan']['stats']['plan_id']}" in out
    assert s.last_plan_id == last["plan"]["stats"]["plan_id"]
    assert s.fleet_revision == rec["plan"]["stats"]["fleet_revision"]
    assert s.state == s.STATE_READY


def test_other_version_garbage_and_other_options_refused(tmp_path):
    state = tmp_path / "state"
    state.mkdir()
    journal = state / JOURNAL
    node = Node(state, url="memq://")
    status_line = node.proc.stdout.readline()
    node.stop()
    assert "a new journal" in status_line
    own = journal.read_bytes()
    assert own[5:9] == b"SVAJ" and len(own) == 67
    header = bytearray(own[5:63])
    major, minor, patch = (int(v) for v in version().split("."))

    def refused(data, *extra):
        journal.write_bytes(data)
        r = subprocess.run([NODE, "--url", "memq://", "--state-dir", str(state), *extra],
                           capture_output=True, text=True, timeout=10)
        assert r.returncode == 3, r.stderr
        assert journal.read_bytes() == data  # left as it was
        assert r.stderr.strip().endswith("; start with --state-reset to discard it")
        return r.stderr

    header[8:10] = struct.pack("<H", minor + 1)
    err = refused(record(1, bytes(header)))
    assert (f"refused: the journal was written by sva {major}.{minor + 1}.{patch} (journal format "
            f"2); this node is sva {major}.{minor}.{patch} (journal format 2)") in err
    header[8:10] = struct.pack("<H", minor)
    err = refused(b"\x00" * 100)
    assert "the header does not parse" in err
    err = refused(record(1, bytes(header)), "--algo", "flow")
    assert ("written by a node run with --algo sva --change-penalty 0 --track-tolerance 2; "
            "this node runs with --algo flow") in err
    # --state-reset discards it and starts afresh
    journal.write_bytes(record(1, bytes(header[:20])))
    node = Node(state, "--state-reset", url="memq://")
    line = node.proc.stdout.readline()
    node.stop()
    assert "--state-reset, a new journal" in line
    assert journal.read_bytes() == own
    # one node per folder
    first = Node(state, url="memq://")
    first.proc.stdout.readline()
    r = subprocess.run([NODE, "--url", "memq://", "--state-dir", str(state)],
                       capture_output=True, text=True, timeout=10)
    first.stop()
    assert r.returncode == 1 and "is in use: another process holds its lock" in r.stderr
    r = subprocess.run([NODE, "--state-reset"], capture_output=True, text=True, timeout=10)
    assert r.returncode == 2 and "--state-reset needs --state-dir" in r.stderr
