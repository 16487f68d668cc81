"""sva_can_node --state-dir / --state-reset through the node's own code path. The build
host has no AF_CAN, so every run ends at the CAN interface (exit 1, "cannot open"):
the journal is opened, checked and replayed before that, and its line printed. The
torn-tail cut, refusals (exit 3, one line naming both sides, journal left as it was),
--state-reset, a SIGKILL while the node holds the folder and the folder lock are
checked here; the live mission's replay itself is test_can_journal.c's."""
import os
import signal
import subprocess
import time
from pathlib import Path

NODE = os.environ["SVA_CAN_NODE"]
MISSION = str(Path(__file__).parent / "data" / "mission_25x5.json")
JOURNAL = "sva_can_node.journal"


def run(*args):
    r = subprocess.run([NODE, "--mission", MISSION, "--iface", "sva_no_such0", *args],
                       capture_output=True, text=True, timeout=60)
    return r.returncode, r.stdout.splitlines(), r.stderr.splitlines()


def test_state_reset_needs_state_dir():
    r = subprocess.run([NODE, "--mission", MISSION, "--state-reset"], capture_output=True,
                       text=True, timeout=30)
    assert r.returncode == 2
    assert r.stderr.splitlines() == ["sva_can_node: error: --state-reset needs --state-dir"]


def test_new_resume_cut_refuse_reset(tmp_path):
    state = tmp_path / "state"
    rc, out, err = run("--state-dir", str(state))
    path = state / JOURNAL
    assert out == [f"sva_can_node: state: a new journal {path}"], (out, err)
    assert rc == 1 and "cannot open" in err[-1]
    head = path.read_bytes()
    assert head[5:9] == b"SVAC" and len(head) > 32

    rc, out, err = run("--state-dir", str(state))
    assert rc == 1
    assert len(out) == 1 and out[0].startswith(f"sva_can_node: resumed from {path}: 0 frames and 0 replans replayed, revision "), out
    assert out[0].endswith(", now 0, plan id 1")

    # A torn record on disk: cut at its offset, the file truncated there.
    with open(path, "ab") as f:
        f.write(b"\x0e\x00\x00\x00\x03garbage")
    rc, out, err = run("--state-dir", str(state))
    assert out[0].endswith(f", now 0, plan id 1, a torn tail cut at byte {len(head)}"), out
    assert err[0] == (f"sva_can_node: journal {path}: torn or corrupt record at byte {len(head)} "
                      "(short record: 12 of its 23 bytes): cut there, 12 bytes dropped")
    assert path.read_bytes() == head

    # Other options: refused with exit 3, naming both, the journal left as it was.
    rc, out, err = run("--state-dir", str(state), "--algo", "ga")
    assert rc == 3 and out == []
    assert err == [f"sva_can_node: error: --state-dir: journal {path} refused: the journal was written by a "
                   "node run with --algo sva --track-tolerance 2; this node runs with --algo ga "
                   "--track-tolerance 2; start with --state-reset to discard it"]
    assert path.read_bytes() == head

    # Another version (the header's patch number), its CRC made right: refused.
    import zlib
    other = bytearray(head)
    other[5 + 10] ^= 1
    other[5 + 23:5 + 27] = zlib.crc32(bytes(other[:5 + 23])).to_bytes(4, "little")
    path.write_bytes(bytes(other))
    rc, out, err = run("--state-dir", str(state))
    assert rc == 3 and len(err) == 1
    assert "refused: the journal was written by sva " in err[0] and "; this node is sva " in err[0]
    assert path.read_bytes() == bytes(other)

    # --state-reset: a new journal.
    rc, out, err = run("--state-dir", str(state), "--state-reset")
    assert out == [f"sva_can_node: state: --state-reset, a new journal {path}"]
    assert path.read_bytes() == head


def test_killed_while_holding_the_folder(tmp_path):
    """SIGKILL at once after start, repeatedly: the journal is always the new one whole
    (never half a head) or absent, and the next start resumes or starts it."""
    state = tmp_path / "state"
    for delay in (0.0, 0.005, 0.01, 0.02, 0.05):
        p = subprocess.Popen([NODE, "--mission", MISSION, "--iface", "sva_no_such0",
                              "--state-dir", str(state)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE)
        time.sleep(delay)
        p.send_signal(signal.SIGKILL)
        p.communicate(timeout=30)
        rc, out, err = run("--state-dir", str(state))
        assert rc == 1 and len(out) == 1, (out, err)
        assert (out[0].startswith("sva_can_node: resumed from ") or
                out[0].startswith("sva_can_node: state: a new journal")), out
        assert not (state / "sva_can_node.journal.tmp").exists()
