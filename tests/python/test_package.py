"""The `sva` Python package (pyproject.toml at the repository root, docs/python.md).

Builds the wheel once (pip wheel . --no-deps), installs it with its base dependencies
into a clean venv, and checks there: `sva-tools --version`, `import sva`, the wheel's
contents, and that the API answers as the C CLI ($SVA_BIN, default build/bin/sva) does:
every mission of fixtures/missions by every algorithm (the plan text byte for byte but
stats.solve_us, a time; or the same error), every fixtures/invalid file (the message of
its .err, as MissionError), and `sva replan` on the scenarios and fixtures/invalid/live.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
FIXTURES = REPO / "fixtures"
ALGORITHMS = ("sva", "ga", "hga", "bfa", "flow")
# every bundled mission, and one with a frame (echoed into its plan)
MISSIONS = sorted(f"missions/{p.name}" for p in (FIXTURES / "missions").glob("*.json")) + ["geo/zurich.json"]
INVALID = sorted(p.stem for p in (FIXTURES / "invalid").glob("*.json"))
LIVE_INVALID = sorted(p.stem for p in (FIXTURES / "invalid" / "live").glob("*.json"))
SCENARIOS = sorted(p.name for p in (FIXTURES / "scenarios").glob("*.json"))
REPLAN_ALGORITHMS = ("sva", "flow")
SOLVE_US = re.compile(rb'"solve_us": [0-9]+')


def sva_bin() -> Path:
    path = Path(os.environ.get("SVA_BIN", REPO / "build" / "bin" / "sva"))
    assert path.is_file(), f"the C CLI is missing: {path} (build it, or set SVA_BIN)"
    return path


def cli(args: list[str], cwd: Path) -> tuple[int, bytes, str]:
    result = subprocess.run([str(sva_bin()), *args], cwd=cwd, capture_output=True, check=False, timeout=300)
    return result.returncode, result.stdout, result.stderr.decode("utf-8", "replace")


def cli_message(stderr: str) -> str:
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("sva: error: "), stderr
    return lines[0][len("sva: error: "):]


def timeless(text: bytes) -> bytes:
    return SOLVE_US.sub(b'"solve_us": 0', text)


@pytest.fixture(scope="session")
def venv() -> Path:
    """A clean venv with the wheel installed (built once per test run)."""
    work = Path(os.environ.get("SVA_PYTHON_WORKDIR", REPO / "build-py" / "python-test"))
    shutil.rmtree(work, ignore_errors=True)
    (work / "wheel").mkdir(parents=True)
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(REPO), "--no-deps", "-q",
                    "--disable-pip-version-check", "-w", str(work / "wheel")],
                   check=True, timeout=600)
    subprocess.run([sys.executable, "-m", "venv", str(work / "venv")], check=True, timeout=120)
    wheel = next((work / "wheel").glob("sva-*.whl"))
    subprocess.run([str(work / "venv" / "bin" / "pip"), "install", "-q",
                    "--disable-pip-version-check", str(wheel)], check=True, timeout=600)
    return work / "venv"


@pytest.fixture(scope="session")
def api(venv: Path):
    """Runs a batch of API calls in the venv's Python, outside the repository."""
    def run(requests: list[dict]) -> list[dict]:
        result = subprocess.run([str(venv / "bin" / "python"), str(Path(__file__).parent / "api_runner.py")],
                                input=json.dumps(requests).encode(), capture_output=True, check=False,
                                cwd=venv, timeout=600, env={**os.environ, "PYTHONPATH": ""})
        assert result.returncode == 0, result.stderr.decode()
        answers: list[dict] = json.loads(result.stdout)
        return answers
    return run


@pytest.fixture(scope="session")
def mission_plans(api) -> dict[tuple[str, str], dict]:
    requests = [{"kind": kind, "path": str(FIXTURES / m), "algo": a, "source": m}
                for kind in ("plan", "plan_dict") for m in MISSIONS for a in ALGORITHMS]
    answers = api(requests)
    return {(r["kind"], r["source"], r["algo"]): a for r, a in zip(requests, answers)}


def test_fixture_sets_are_there():
    assert len(MISSIONS) >= 17 and len(INVALID) >= 40 and len(LIVE_INVALID) >= 10


def test_sva_tools_version(venv: Path):
    result = subprocess.run([str(venv / "bin" / "sva-tools"), "--version"], capture_output=True, check=False,
                            text=True, cwd=venv, timeout=60)
    assert result.returncode == 0, result.stderr
    assert re.fullmatch(r"sva-tools \d+\.\d+\.\d+\n", result.stdout)


def test_sva_tools_validate_from_the_venv(venv: Path):
    """The host tools find their JSON Schemas in the installed package, outside the
    repository: a good mission validates, a bad one names its field."""
    tool = str(venv / "bin" / "sva-tools")
    good = subprocess.run([tool, "validate", str(REPO / "fixtures" / "missions" / "hand_5_3.json")],
                          capture_output=True, check=False, text=True, cwd=venv, timeout=60)
    assert good.returncode == 0, good.stderr
    bad = subprocess.run([tool, "validate", str(REPO / "fixtures" / "invalid" / "fuel_over_max.json")],
                         capture_output=True, check=False, text=True, cwd=venv, timeout=60)
    assert bad.returncode == 2 and "fuel" in bad.stderr, bad.stderr


def test_import_sva_from_the_venv(venv: Path):
    code = "import sva, sys; print(sva.__file__); print(sva.core_version())"
    result = subprocess.run([str(venv / "bin" / "python"), "-c", code], capture_output=True, check=False,
                            text=True, cwd=venv, timeout=60, env={**os.environ, "PYTHONPATH": ""})
    assert result.returncode == 0, result.stderr
    path, version = result.stdout.split()
    assert Path(path).resolve().is_relative_to(venv.resolve())
    assert f"sva {version} " in cli(["--version"], REPO)[1].decode()


def test_wheel_holds_the_packages_only(venv: Path):
    wheel = next((venv.parent / "wheel").glob("sva-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    tops = {name.split("/")[0] for name in names}
    assert tops == {"sva", "sva_tools", wheel.name.split("-py3")[0] + ".dist-info"}
    assert {"sva/py.typed", "sva/libsva_py.so", "sva/__init__.py",
            "sva_tools/ground/static/index.html", "sva_tools/schema_files/mission.schema.json"} <= set(names)


@pytest.mark.parametrize("algo", ALGORITHMS)
@pytest.mark.parametrize("mission", MISSIONS)
def test_plan_equals_the_cli(mission: str, algo: str, mission_plans):
    code, stdout, stderr = cli(["plan", "--algo", algo, mission], FIXTURES)
    answer = mission_plans[("plan", mission, algo)]
    from_dict = mission_plans[("plan_dict", mission, algo)]
    if code == 0:
        assert "text" in answer, answer
        assert timeless(answer["text"].encode()) == timeless(stdout)
        # the dict API: the same plan, parsed
        plan = json.loads(from_dict["text"])
        expected = json.loads(stdout)
        plan["stats"]["solve_us"] = expected["stats"]["solve_us"] = 0
        assert plan == expected
    else:
        assert code == 1, stderr  # an algorithm's limit (bfa)
        assert answer == {"error": "PlanError", "message": cli_message(stderr)}
        assert from_dict == answer


def test_invalid_fixtures(api):
    directory = FIXTURES / "invalid"
    requests = [{"kind": "plan", "path": str(directory / f"{n}.json"), "algo": "sva",
                 "source": f"{n}.json"} for n in INVALID]
    # as a dict too, where Python reads the file as the C reader does (no syntax error,
    # no duplicate key, no value JSON cannot carry back)
    as_dict = []
    for name in INVALID:
        message = (directory / f"{name}.err").read_text().rstrip("\n")
        if not message.startswith(f"{name}.json"):
            as_dict.append(name)
    requests += [{"kind": "plan_dict", "path": str(directory / f"{n}.json"), "algo": "sva",
                  "source": f"{n}.json"} for n in as_dict]
    answers = api(requests)
    for request, answer in zip(requests, answers):
        name = Path(request["path"]).stem
        expected = (directory / f"{name}.err").read_text().rstrip("\n")
        assert answer == {"error": "MissionError", "message": expected}, (request["kind"], name)
        code, _, stderr = cli(["plan", f"{name}.json"], directory)
        assert code == 2 and cli_message(stderr) == expected


def test_replan_equals_the_cli(api):
    requests = [{"kind": "replan", "path": str(FIXTURES / "scenarios" / s), "algo": a, "source": s}
                for s in SCENARIOS for a in REPLAN_ALGORITHMS]
    answers = api(requests)
    compared = 0
    for request, answer in zip(requests, answers):
        code, stdout, stderr = cli(["replan", "--algo", request["algo"], request["source"]],
                                   FIXTURES / "scenarios")
        if code == 0:
            assert "text" in answer, (request, answer)
            assert timeless(answer["text"].encode()) == timeless(stdout), request
            compared += 1
        else:
            kind = "MissionError" if code == 2 else "PlanError"
            assert answer == {"error": kind, "message": cli_message(stderr)}, request
    assert compared > 0


def test_invalid_live_fixtures(api):
    directory = FIXTURES / "invalid" / "live"
    names = [n for n in LIVE_INVALID
             if not (directory / f"{n}.err").read_text().startswith(f"{n}.json")]
    requests = [{"kind": "replan", "path": str(directory / f"{n}.json"), "algo": "sva",
                 "source": f"{n}.json"} for n in names]
    for request, answer in zip(requests, api(requests)):
        expected = (directory / f"{request['source'][:-5]}.err").read_text().rstrip("\n")
        assert answer == {"error": "MissionError", "message": expected}, request["source"]


def test_errors_of_the_call(venv: Path):
    code = ("import sva\n"
            "m = {'name': 'x', 'depot': {'x': 0, 'y': 0}, 'uavs': [], 'targets': []}\n"
            "for call in (lambda: sva.plan(m, 'simplex'), lambda: sva.plan(m, 'flow', flow_work=10)):\n"
            "    try:\n"
            "        call()\n"
            "    except ValueError as error:\n"
            "        print(error)\n"
            "print(sva.plan(m)['status'])\n")
    result = subprocess.run([str(venv / "bin" / "python"), "-c", code], capture_output=True, check=False,
                            text=True, cwd=venv, timeout=60, env={**os.environ, "PYTHONPATH": ""})
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == 'algo: unknown algorithm "simplex" (known: sva, ga, hga, bfa, flow)'
    assert lines[1].startswith("flow_work: must be an integer in [1000, ")
    assert lines[2] == "complete"
