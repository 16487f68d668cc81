"""plot writes a readable PNG; bench runs end to end on a reduced protocol."""
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
