"""`sva-tools campaign` (docs/campaigns.md): the same tiny campaign on an embedded
LocalCluster, run directly task by task, and on a `dask scheduler` with two `dask worker`
processes on loopback, gives the same results; a worker killed mid-campaign loses no
result; a resumed or extended campaign computes no task twice; a bad spec is refused
naming the field, the rule and the limit."""
import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pyarrow.parquet as pq
import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
sys.path.insert(0, str(REPO / "tools" / "bench"))

import campaign_report_bench  # noqa: E402  (the report row by row, as it was built before Arrow)
from sva_tools.campaign import run as run_campaign  # noqa: E402
from sva_tools.campaign import report  # noqa: E402
from sva_tools.campaign.tasks import run_task  # noqa: E402
from sva_tools.campaign.spec import SpecError, first_tasks, load  # noqa: E402
from sva_tools.campaign.store import Store  # noqa: E402

VENV_BIN = Path(sys.executable).parent
ENV = dict(os.environ, PYTHONPATH=str(REPO / "tools") + os.pathsep + os.environ.get("PYTHONPATH", ""))
TINY = """name: tiny
kind: plan
sets:
  - {targets: 5, uavs: 2, width: [10, 20], need: 1, fuel: 100, hover: 2}
  - {targets: 8, uavs: 3, width: [10, 20], need: [1, 2], fuel: 100, hover: 2}
seeds: {first: 7, count: 1}
count: COUNT
algorithms: [flow, sva]
ref: {det_limit: 5}
"""
SUMMARY = re.compile(r"^campaign (\S+): (\d+) tasks for (\d+) missions; (\d+) already stored, (\d+) computed, "
                     r"(\d+) failed;", re.M)


def write_spec(tmp_path, count, name="tiny.yaml", text=TINY):
    p = tmp_path / name
    p.write_text(text.replace("COUNT", str(count)))
    return p


def campaign(*args, timeout=240):
    r = subprocess.run([sys.executable, "-m", "sva_tools", "campaign", "--no-progress", *map(str, args)],
                       capture_output=True, text=True, env=ENV, timeout=timeout)
    return r


def summary(stdout):
    m = SUMMARY.search(stdout)
    assert m, stdout
    return {"tasks": int(m.group(2)), "stored": int(m.group(4)), "computed": int(m.group(5)),
            "failed": int(m.group(6))}


def stored_rows(out):
    rows = []
    for p in sorted((Path(out) / "results").glob("part-*.parquet")):
        rows += pq.read_table(p).to_pylist()
    return rows


def deterministic(result_json):
    """A plan without its timings (stats.*_us): what must not depend on where it ran."""
    doc = json.loads(result_json)
    doc["stats"] = {k: v for k, v in doc.get("stats", {}).items() if not k.endswith("_us")}
    return doc


def by_key(rows):
    return {r["key"]: (r["covered"], r["cost"], r["optimal"], r["error"], deterministic(r["result"]))
            for r in rows}


@pytest.fixture(scope="module")
def direct(tmp_path_factory):
    """Every task of the 2-mission-per-set spec, run here, one by one, without Dask."""
    d = tmp_path_factory.mktemp("direct")
    spec = load(str(write_spec(d, 2)))
    return {t["key"]: run_task(t) for t in first_tasks(spec, "direct")}


@pytest.fixture(scope="module")
def local_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("local")
    r = campaign(write_spec(d, 2), "--workers", "2", "--out", d / "out")
    assert r.returncode == 0, r.stderr
    return d / "out", r.stdout


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A `dask scheduler` and two `dask worker` processes (no nanny: the worker's pid is
    the process that runs tasks) on loopback; yields (address, [worker Popen])."""
    d = tmp_path_factory.mktemp("cluster")
    sfile = d / "scheduler.json"
    procs = []
    logs = []

    def start(*cmd, name):
        log = open(d / f"{name}.log", "w")
        logs.append(log)
        p = subprocess.Popen([str(VENV_BIN / "dask"), *cmd], stdout=log, stderr=subprocess.STDOUT, env=ENV)
        procs.append(p)
        return p

    try:
        start("scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard", "--scheduler-file", str(sfile),
              name="scheduler")
        deadline = time.monotonic() + 60
        while not sfile.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        assert sfile.exists(), (d / "scheduler.log").read_text()
        address = json.loads(sfile.read_text())["address"]
        assert address.startswith("tcp://127.0.0.1:")
        workers = [start("worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard", "--host", "127.0.0.1",
                         "--name", f"w{i}", name=f"worker{i}") for i in (1, 2)]
        from distributed import Client
        with Client(address, timeout="30s") as c:
            c.wait_for_workers(2, timeout=60)
        yield address, workers
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        for log in logs:
            log.close()


def test_local_cluster_equals_the_tasks_run_directly(local_run, direct):
    out, stdout = local_run
    rows = stored_rows(out)
    assert len(rows) == len({r["key"] for r in rows}) == len(direct)
    assert by_key(rows) == by_key(direct.values())
    assert all(r["worker"].startswith("tcp://127.0.0.1:") for r in rows)
    assert all(r["error"] is None and r["result"] for r in rows)
    s = summary(stdout)
    assert s == {"tasks": len(direct), "stored": 0, "computed": len(direct), "failed": 0}
    # The table's figures, recomputed from the direct results: per set and algorithm,
    # covered targets and the mean cost gap to ref at equal coverage.
    refs = {r["mission_hash"]: r for r in direct.values() if r["tool"] == "ref"}
    for label in ("5x2", "8x3"):
        for tool in ("flow", "sva"):
            mine = [r for r in direct.values() if r["set"] == label and r["tool"] == tool]
            covered = sum(r["covered"] for r in mine)
            gaps = [100.0 * (r["cost"] - refs[r["mission_hash"]]["cost"]) / refs[r["mission_hash"]]["cost"]
                    for r in mine if r["covered"] == refs[r["mission_hash"]]["covered"]]
            line = next(l for l in stdout.splitlines() if l.startswith(f"| {label} | {tool} |"))
            cells = [c.strip() for c in line.strip("|").split("|")]
            assert cells[3].startswith(f"{covered}/{sum(r['coverable'] for r in mine)} ")
            assert cells[5] == (f"mean {sum(gaps) / len(gaps):.3f} %, largest {max(gaps):.2f} %" if gaps else "–")
    # metrics.parquet joins each plan to ref; the report embeds its plots.
    metrics = pq.read_table(out / "metrics.parquet").to_pylist()
    assert len(metrics) == len(direct)
    for m in metrics:
        q = refs[m["mission_hash"]] if m["tool"] != "ref" else {"covered": None, "cost": None}
        assert (m["ref_covered"], m["ref_cost"]) == (q["covered"], q["cost"])
    html = (out / "report.html").read_text(encoding="utf-8")
    assert html.count("src='data:image/png;base64,") == 3
    assert "http://" not in html and "https://" not in html


def row_by_row(spec, out, tasks):
    """The records and summary groups computed the way the report did before Arrow:
    every stored row as a dict, grouped in Python by its stored set label."""
    rows = campaign_report_bench.row_wise_rows(Store(str(out), "check"), tasks, spec)
    records = campaign_report_bench.row_wise_metrics(spec, rows)
    return len(rows), records, campaign_report_bench.row_wise_groups(spec, records)


def assert_same_report(spec, out, tasks):
    """The report built with pyarrow has the row-by-row report's records, in the same
    order, and the same groups (counts, sums, the gap and time lists the plots draw)."""
    old_stored, old_records, old_groups = row_by_row(spec, out, tasks)
    records, gs, stored = report.build(spec, Store(str(out), "check"), tasks)
    assert stored == old_stored
    assert records.column_names == list(old_records[0])
    assert records.to_pylist() == old_records
    assert gs == old_groups
    return gs


def test_report_with_arrow_equals_the_report_row_by_row(local_run):
    out, stdout = local_run
    spec = load(str(write_spec(out.parent, 2)))
    gs = assert_same_report(spec, out, first_tasks(spec, "check"))
    assert [(g["set"], g["tool"]) for g in gs] == [(s, t) for s in ("5x2", "8x3") for t in ("flow", "sva", "ref")]
    assert all(g["gaps"] or g["tool"] == "ref" for g in gs) and all(g["times"] for g in gs)
    stats = {"tasks": 12, "stored": 0, "computed": 12, "failed": [], "wall_s": 0.0}
    assert report.summary(spec, stats, gs).splitlines()[1:] == [ln for ln in stdout.splitlines() if ln.startswith("|")]
    figures = report.figures(spec, gs)  # the report's plots, drawn from the groups row by row: the same PNGs
    assert len(figures) == 3 and figures == report.figures(spec, row_by_row(spec, out, first_tasks(spec, "check"))[2])


def test_report_with_arrow_equals_the_report_row_by_row_on_a_large_store(tmp_path):
    """A synthetic store (tools/bench/campaign_report_bench.py): 4 sets, three planners,
    ref on two sets, errors, coverage below ref's."""
    spec = campaign_report_bench.synthetic_spec(4, ["flow", "sva", "hga"], 150)
    tasks = campaign_report_bench.synthetic_store(str(tmp_path), spec, flush_rows=200, seed=3)
    gs = assert_same_report(spec, tmp_path, tasks)
    assert len(gs) == 2 * 4 + 2 * 3
    assert sum(g["errors"] for g in gs) > 0 and sum(g["below"] for g in gs) > 0
    assert sum(g["equal"] for g in gs) > 0 and sum(g["judged"] for g in gs) < sum(g["n"] for g in gs)


def test_rows_stored_under_another_label_are_grouped_by_this_runs_sets(tmp_path):
    """Rows first stored by another set (or an older name of a set) are counted under the
    set of this run's task: the report equals that of a store with this run's labels."""
    spec = campaign_report_bench.synthetic_spec(3, ["flow", "sva"], 40)
    tasks = campaign_report_bench.synthetic_store(str(tmp_path / "own"), spec, seed=5)
    shared = campaign_report_bench.synthetic_store(str(tmp_path / "shared"), spec, seed=5,
                                shared={"set1_40x8": "set0_25x5", "set2_100x20": "old_name"})
    assert [t["key"] for t in shared] == [t["key"] for t in tasks]
    mine = report.build(spec, Store(str(tmp_path / "own"), "check"), tasks)[1]
    assert report.build(spec, Store(str(tmp_path / "shared"), "check"), shared)[1] == mine
    assert [g["n"] for g in mine] == [40] * 8


def test_a_key_stored_twice_is_read_once_from_the_first_file(tmp_path):
    """Two clients on one folder may store one key twice: reading keeps the row of the
    first part file in name order."""
    spec = campaign_report_bench.synthetic_spec(2, ["flow"], 3)
    campaign_report_bench.synthetic_store(str(tmp_path), spec, flush_rows=2, seed=1)  # part-bench-*
    rows = stored_rows(tmp_path)
    later = Store(str(tmp_path), "zz")  # part-zz-*: after part-bench-*
    for r in (rows[3], rows[0]):
        later.add(dict(r, covered=-1, run="zz"))
    later.flush()
    cols = ["key", "covered", "run"]
    assert len(stored_rows(tmp_path)) == len(rows) + 2
    assert Store(str(tmp_path), "read").table(cols).to_pylist() == [{c: r[c] for c in cols} for r in rows]


LIVE = """name: tiny_live
kind: live
sets:
  - {targets: 6, uavs: 2, width: [10, 20], need: 1, fuel: 100, hover: 2, events: 4}
  - {targets: 8, uavs: 3, width: [10, 20], need: 1, fuel: 100, hover: 2, events: 4, ref_count: 1}
seeds: {first: 7, count: 1}
count: 2
algorithms: [flow, sva]
penalties: [0, 1000]
ref: {det_limit: 2}
"""


def test_live_report_with_arrow_equals_the_report_row_by_row(tmp_path, cluster):
    address, _ = cluster
    spec = load(str(write_spec(tmp_path, 2, "live.yaml", LIVE)))
    stats = run_campaign(spec, str(tmp_path / "out"), scheduler=address, progress=False, columns=[])
    assert not stats["failed"] and "rows" not in stats
    gs = assert_same_report(spec, tmp_path / "out", stats["task_list"])
    assert [(g["set"], g["tool"], g["penalty"]) for g in gs] == [
        (s, t, p) for s in ("6x2", "8x3") for t in ("flow", "sva") for p in (0, 1000)]
    assert all(g["n"] == 2 and g["times"] for g in gs) and sum(g["judged"] for g in gs) > 0


TWINS = """name: twins
kind: plan
sets:
  - {targets: 5, uavs: 2, width: [10, 20], need: 1, fuel: 100, hover: 2, label: LABEL}
  - {targets: 5, uavs: 2, width: [10, 20], need: 1, fuel: 100, hover: 2, label: twin}
seeds: {first: 7, count: 1}
count: 2
algorithms: [flow, sva]
ref: {det_limit: 5}
"""


def table_rows(stdout):
    return {tuple(c.strip() for c in ln.strip("|").split("|")[:2]): [c.strip() for c in ln.strip("|").split("|")[2:]]
            for ln in stdout.splitlines() if ln.startswith("| ") and not ln.startswith("| set ")}


def test_two_sets_of_the_same_missions_and_a_renamed_set_each_get_their_rows(tmp_path, cluster):
    """Two sets that generate the same missions share their stored rows (one task each),
    yet each set's table rows count its own missions; a re-run with a set renamed lists
    the stored rows under the new name."""
    address, _ = cluster
    out = tmp_path / "out"
    r = campaign(write_spec(tmp_path, 2, "twins.yaml", TWINS.replace("LABEL", "first")),
                 "--scheduler", address, "--out", out, "--no-report")
    assert r.returncode == 0, r.stderr
    rows = table_rows(r.stdout)
    assert sorted(rows) == sorted((s, t) for s in ("first", "twin") for t in ("flow", "sva", "ref"))
    for tool in ("flow", "sva", "ref"):
        assert rows["first", tool] == rows["twin", tool]
        assert rows["first", tool][0] == "2"  # missions
    assert summary(r.stdout) == {"tasks": 12, "stored": 0, "computed": 6, "failed": 0}  # each mission once
    metrics = pq.read_table(out / "metrics.parquet").to_pylist()
    assert sorted((m["set"], m["tool"]) for m in metrics) == sorted(
        (s, t) for s in ("first", "twin") for t in ("flow", "sva", "ref") for _ in range(2))
    r2 = campaign(write_spec(tmp_path, 2, "renamed.yaml", TWINS.replace("LABEL", "renamed")),
                  "--scheduler", "tcp://127.0.0.1:9", "--out", out)
    assert r2.returncode == 0, r2.stderr
    assert summary(r2.stdout) == {"tasks": 12, "stored": 12, "computed": 0, "failed": 0}
    renamed = table_rows(r2.stdout)
    assert sorted(renamed) == sorted((s, t) for s in ("renamed", "twin") for t in ("flow", "sva", "ref"))
    for tool in ("flow", "sva", "ref"):
        assert renamed["renamed", tool] == renamed["twin", tool] == rows["first", tool]


def test_separate_scheduler_and_workers_give_the_same_results(tmp_path, cluster, local_run, direct):
    address, workers = cluster
    stats = run_campaign(load(str(write_spec(tmp_path, 2))), str(tmp_path / "out"), scheduler=address, progress=False)
    assert (stats["computed"], stats["failed"], stats["workers"]) == (len(direct), [], 2)
    rows = stored_rows(tmp_path / "out")
    assert by_key(rows) == by_key(stored_rows(local_run[0])) == by_key(direct.values())
    assert len({r["worker"] for r in rows}) == 2  # both workers ran tasks
    assert all(r["worker"].startswith("tcp://127.0.0.1:") for r in rows)


def test_resumed_and_extended_campaign_computes_nothing_twice(tmp_path, cluster):
    """Run in this process (campaign.run, as the CLI calls it): one mission per set, then
    two (only the new ones run), then two again (nothing runs, no cluster is reached)."""
    address, _ = cluster
    out = tmp_path / "out"
    first = run_campaign(load(str(write_spec(tmp_path, 1))), str(out), scheduler=address, progress=False)
    assert (first["tasks"], first["stored"], first["computed"], first["failed"]) == (6, 0, 6, [])
    second = run_campaign(load(str(write_spec(tmp_path, 2))), str(out), scheduler=address, progress=False)
    assert (second["tasks"], second["stored"], second["computed"], second["failed"]) == (12, 6, 6, [])
    rows = stored_rows(out)
    runs = {}
    for r in rows:
        runs.setdefault(r["run"], []).append(r)
    assert {k: len(v) for k, v in runs.items()} == {first["run"]: 6, second["run"]: 6}  # each task ran once
    assert {r["index"] for r in runs[second["run"]]} == {1}
    assert len({r["key"] for r in rows}) == len(rows) == 12
    assert set(second["rows"]) == {r["key"] for r in rows}
    files = sorted((out / "results").iterdir())
    third = run_campaign(load(str(write_spec(tmp_path, 2))), str(out), scheduler="tcp://127.0.0.1:9", progress=False)
    assert (third["tasks"], third["stored"], third["computed"], third["workers"]) == (12, 12, 0, 0)
    assert sorted((out / "results").iterdir()) == files


def test_interrupted_campaign_resumes_without_redoing(tmp_path, cluster, direct):
    """The client is killed once some results are stored; the re-run computes only the
    tasks not stored, and the store ends with every task once."""
    address, _ = cluster
    out = tmp_path / "out"
    spec = write_spec(tmp_path, 2)
    p = subprocess.Popen([sys.executable, "-m", "sva_tools", "campaign", "--no-progress", "--no-report",
                          "--flush-rows", "1",
                          str(spec), "--scheduler", address, "--out", str(out)], env=ENV,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while p.poll() is None and time.monotonic() < deadline and not list((out / "results").glob("part-*")):
        time.sleep(0.05)
    if p.poll() is None:
        p.send_signal(signal.SIGKILL)
    p.communicate()
    assert p.returncode == -signal.SIGKILL, "the campaign ended before it was interrupted"
    before = stored_rows(out)
    assert 0 < len(before) < len(direct)
    r = campaign(spec, "--scheduler", address, "--out", out, "--no-report")
    assert r.returncode == 0, r.stderr
    s = summary(r.stdout)
    assert s["stored"] == len({x["key"] for x in before}) and s["computed"] == len(direct) - s["stored"]
    rows = stored_rows(out)
    assert len(rows) == len({x["key"] for x in rows}) == len(direct)
    assert by_key(rows) == by_key(direct.values())


def test_worker_killed_mid_campaign_loses_no_result(tmp_path, cluster, direct):
    """SIGKILL a worker while it runs a task: the scheduler reruns its tasks on the
    other worker and every result is stored once. Runs last: it uses up a worker."""
    from distributed import Client
    address, workers = cluster
    spec = write_spec(tmp_path, 2)
    p = subprocess.Popen([sys.executable, "-m", "sva_tools", "campaign", "--no-progress", "--no-report", str(spec),
                          "--scheduler", address, "--out", str(tmp_path / "out")], env=ENV,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    victim = None
    with Client(address, timeout="30s") as c:
        deadline = time.monotonic() + 120
        while victim is None and p.poll() is None and time.monotonic() < deadline:
            info = c.run(os.getpid)  # worker address -> pid
            for addr, keys in c.processing().items():
                ref_keys = [k for k in keys if str(k).startswith("sva-ref-")]
                if ref_keys and addr in info:
                    victim = (addr, info[addr], {str(k) for k in keys})
                    break
            time.sleep(0.02)
        assert victim, "no task seen running on a worker"
        proc = next(w for w in workers if w.pid == victim[1])
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
    stdout, stderr = p.communicate(timeout=240)
    assert p.returncode == 0, stderr
    rows = stored_rows(tmp_path / "out")
    assert len(rows) == len({r["key"] for r in rows}) == len(direct)
    assert by_key(rows) == by_key(direct.values())
    # The tasks the victim held when it was killed: one may have finished just before the
    # signal (stored by the victim), the others ran again on the surviving worker.
    held = [r for r in rows if any(k.endswith(r["key"]) for k in victim[2])]
    assert held, victim[2]
    assert any(r["worker"] != victim[0] for r in held), [(r["key"], r["worker"]) for r in held]
    assert summary(stdout)["failed"] == 0


@pytest.mark.parametrize("text, message", [
    (TINY.replace("targets: 5,", "targets: 5000,"),
     "sets[0].targets: must be <= 256 (SVA_MAX_TARGETS), got 5000"),
    (TINY.replace("uavs: 2,", "uavs: 65,"), "sets[0].uavs: must be <= 64 (SVA_MAX_UAVS), got 65"),
    (TINY.replace("[flow, sva]", "[flow, magic]"),
     'algorithms[1]: must be one of "sva", "ga", "hga", "bfa", "flow", got "magic"'),
    (TINY.replace("width: [10, 20]", "width: [20, 10]", 1),
     "sets[0].width: must be [LO, HI] with LO <= HI, got [20, 10]"),
    (TINY.replace("width: [10, 20]", "width: 0", 1), "sets[0].width: must be >= 1, got 0"),
    (TINY.replace("count: COUNT", "count: 2\ncolour: red"), 'spec: unknown key "colour"'),
    (TINY.replace("algorithms: [flow, sva]\n", ""), 'spec: missing key "algorithms"'),
    (TINY.replace("count: COUNT", "count: 2000000"),
     "count: must be <= 100000 (missions or scenarios per set and seed), got 2000000"),
    (TINY.replace("det_limit: 5", "det_limit: 0"), "ref.det_limit: must be > 0, got 0"),
    (TINY.replace("count: COUNT", "count: [2"), "spec: must be YAML, got expected ',' or ']', but got ':' at line 8, column 11"),
])
def test_bad_spec_is_refused_naming_the_field(tmp_path, text, message):
    p = write_spec(tmp_path, 2, text=text)
    with pytest.raises(SpecError) as e:
        load(str(p))
    assert message in str(e.value)


def test_cli_refuses_a_bad_spec_before_running_anything(tmp_path):
    p = write_spec(tmp_path, 2, text=TINY.replace("uavs: 2,", "uavs: 65,"))
    r = campaign(p, "--out", tmp_path / "out", timeout=60)
    assert r.returncode == 2
    assert r.stderr == f"sva-tools: error: campaign: {p}: sets[0].uavs: must be <= 64 (SVA_MAX_UAVS), got 65\n"
    assert r.stdout == ""
    assert not (tmp_path / "out").exists()  # refused before anything ran or was written


def test_worker_of_another_build_refuses_the_task(tmp_path):
    """A task keyed with another version (here: another C CLI binary) is refused, not
    stored under a key its result does not belong to."""
    spec = load(str(write_spec(tmp_path, 1)))
    task = next(t for t in first_tasks(spec, "direct") if t["tool"] == "flow")
    assert run_task(task)["covered"] is not None
    other = dict(task, version=dict(task["version"], sva="0" * 64))
    with pytest.raises(RuntimeError, match="differs from the client's"):
        run_task(other)
