"""plot writes a readable PNG; bench runs end to end on a reduced protocol."""
import os

from conftest import sva_tools, write

from sva_tools import gen, ref


def test_plot_png(tmp_path):
    m = gen.generate(7, 5, seed=5)
    p = ref.solve_ref(m)
    mp = write(tmp_path, "m.json", m.to_json())
    pp = write(tmp_path, "p.json", p.to_json())
    r = sva_tools("plot", mp, pp, "-o", tmp_path / "x.png")
    assert r.returncode == 0, r.stderr
    data = (tmp_path / "x.png").read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20000


def test_bench_python_planners(tmp_path):
    r = sva_tools("bench", "--missions", 1, "--algos", "ih,ref", "--out", tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    md = (tmp_path / "README.md").read_text()
    assert "| 25t/5u | ih | 1/1 |" in md and "Plans failing `sva-tools check`: 0." in md
    assert (tmp_path / "bench_size.png").exists() and (tmp_path / "bench_ratio.png").exists()


def test_bench_c_planners(sva_bin, tmp_path):
    r = sva_tools("bench", "--missions", 1, "--algos", "sva,ga,bfa", "--out", tmp_path,
                  "--scaling", "--scaling-missions", 1, "--scaling-algos", "sva,ga")
    assert r.returncode == 0, r.stderr[-2000:]
    md = (tmp_path / "README.md").read_text()
    assert "| 10t/5u high | sva | 1/1 |" in md and "| 200t/40u | ga | 1/1 |" in md


def test_bench_flow_certificate_column(sva_bin, tmp_path):
    """flow carries stats.lower_bound / optimal: the report shows its certified gap and
    how many plans were proven optimal; a planner without a bound shows '–'."""
    r = sva_tools("bench", "--missions", 1, "--algos", "sva,flow", "--out", tmp_path)
    assert r.returncode == 0, r.stderr[-2000:]
    md = (tmp_path / "README.md").read_text()
    lines = md.splitlines()
    head = next(line for line in lines if "| certified gap % (n); proven optimal |" in line)
    col = [c.strip() for c in head.split("|")[1:-1]].index("certified gap % (n); proven optimal")
    rows = [[c.strip() for c in line.split("|")[1:-1]] for line in lines
            if line.startswith("| ") and not line.startswith("| set |")]
    flow = [r for r in rows if r[1] == "flow"]
    assert len(flow) == 8 and all(r[2] == "1/1" for r in flow)  # 5 sizes, 3 categories
    assert all(r[col] == "–" for r in rows if r[1] == "sva")
    proven = 0
    for r in flow:
        gap, opt = r[col].split("; optimal ")
        assert opt in ("0/1", "1/1") and (gap.endswith("(0)") or gap.endswith("(1)")), r
        if gap.endswith("(1)"):
            assert float(gap.split()[0]) >= 0.0, r
            if opt == "1/1":  # proven optimal: the bound equals the cost
                assert gap == "0.0 (1)", r
                proven += 1
    assert proven >= 3, flow  # flow proves most of these small missions optimal
    assert "skipped" not in md


def test_bench_skips_an_algorithm_the_cli_lacks(sva_bin, tmp_path):
    """A C CLI without `flow` (before it was merged): bench notes the skip and runs the rest."""
    fake = tmp_path / "sva_without_flow"
    fake.write_text(f"""#!/bin/sh
for a in "$@"; do
  if [ "$a" = flow ]; then
    echo 'sva: error: plan: --algo: unknown algorithm "flow" (known: sva, ga, hga, bfa)' >&2
    exit 2
  fi
done
exec {sva_bin} "$@"
""")
    fake.chmod(0o755)
    env = dict(os.environ, SVA_BIN=str(fake))
    r = sva_tools("bench", "--missions", 1, "--algos", "sva,flow", "--no-paper", "--scaling",
                  "--scaling-missions", 1, "--scaling-algos", "ga,flow", "--out", tmp_path, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "flow skipped" in r.stderr
    md = (tmp_path / "README.md").read_text()
    assert '- flow: skipped: `sva plan --algo flow` exit 2: sva: error: plan: --algo: unknown algorithm "flow"' in md
    assert "| 50t/10u | ga | 1/1 |" in md and "| flow |" not in md
