"""docs/results.md is assembled from docs/results/*.md (tools/bench/results.py): the
committed page equals what its fragments give, every fragment names the command that
reproduces it and the machine it ran on, and a bench rewrites only its own fragment."""
import shutil
import sys

import pytest
from conftest import REPO, sva_tools

sys.path.insert(0, str(REPO / "tools" / "bench"))
import results  # noqa: E402


def copy_of_repo(tmp_path):
    root = tmp_path / "repo"
    (root / "docs").mkdir(parents=True)
    shutil.copytree(REPO / "docs" / "results", root / "docs" / "results")
    shutil.copy(REPO / "docs" / "results.md", root / "docs" / "results.md")
    return root


def test_committed_page_equals_its_fragments():
    results.check(str(REPO))  # raises ResultsError otherwise


def test_every_fragment_names_its_command_and_machine():
    frags = sorted((REPO / "docs" / "results").glob("*.md"))
    sections = {s for s, _ in results.SECTIONS}
    assert {f.name.split(".")[0] for f in frags} == sections, "a section without a fragment"
    for f in frags:
        text = f.read_text(encoding="utf-8")
        assert results.COMMAND_RE.search(text), f"{f.name}: no 'Command: `...`' line"
        assert results.MACHINE_RE.search(text), f"{f.name}: no 'Machine: ...' line"
    page = (REPO / "docs" / "results.md").read_text(encoding="utf-8")
    for f in frags:
        assert f.read_text(encoding="utf-8").strip() in page, f"{f.name} is not in docs/results.md"


def test_hand_edit_of_the_page_fails(tmp_path):
    root = copy_of_repo(tmp_path)
    page = root / "docs" / "results.md"
    page.write_text(page.read_text(encoding="utf-8").replace("| ", "|  ", 1), encoding="utf-8")
    with pytest.raises(results.ResultsError, match="differs from its fragments"):
        results.check(str(root))
    assert results.main(["check", "--root", str(root)]) == 1
    results.main(["--root", str(root)])  # reassembled: matches again
    results.check(str(root))


def test_fragment_without_command_fails(tmp_path):
    root = copy_of_repo(tmp_path)
    frag = root / "docs" / "results" / "core.md"
    frag.write_text("\n".join(l for l in frag.read_text(encoding="utf-8").splitlines()
                              if not l.startswith("Command:")), encoding="utf-8")
    with pytest.raises(results.ResultsError, match="core.md: no line 'Command"):
        results.check(str(root))


def test_fragment_of_no_section_fails(tmp_path):
    root = copy_of_repo(tmp_path)
    (root / "docs" / "results" / "stray.md").write_text("Command: `x`\n\nMachine: y.\n", encoding="utf-8")
    with pytest.raises(results.ResultsError, match="stray.md: no section 'stray'"):
        results.check(str(root))


def test_write_rewrites_only_its_fragment(tmp_path):
    root = copy_of_repo(tmp_path)
    d = root / "docs" / "results"
    before = {f.name: f.read_bytes() for f in d.glob("*.md")}
    results.write(str(root), "instructions", "scripts/instructions.sh --results 1", "| a |\n|---|\n| 1 |\n",
                  load_start="0.10 0.20 0.30", note="test note")
    after = {f.name: f.read_bytes() for f in d.glob("*.md")}
    assert set(after) == set(before)
    changed = [n for n in after if after[n] != before[n]]
    assert changed == ["instructions.md"]
    text = after["instructions.md"].decode()
    assert "Command: `scripts/instructions.sh --results 1`" in text
    assert "load average 0.10 0.20 0.30 at the start" in text and "test note" in text and " cores, " in text
    page = (root / "docs" / "results.md").read_text(encoding="utf-8")
    assert text.strip() in page and page.index("## Instructions per plan") < page.index(text.strip())
    results.check(str(root))


def test_bench_writes_its_section(sva_bin, tmp_path):
    root = copy_of_repo(tmp_path)
    env = dict(__import__("os").environ, SVA_RESULTS_ROOT=str(root))
    r = sva_tools("bench", "--missions", 1, "--algos", "sva,ga", "--out", tmp_path / "b", "--results", env=env)
    assert r.returncode == 0, r.stderr
    text = (root / "docs" / "results" / "paper.md").read_text(encoding="utf-8")
    assert "Command: `tools/sva-tools bench --missions 1 --algos sva,ga" in text and "--results" in text
    assert "| 3t/3u |" in text and "Machine: " in text
    results.check(str(root))
