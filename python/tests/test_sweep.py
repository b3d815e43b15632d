"""Sweeps from Python (fm.plan, fm.run_job, fm.sweep) against `fuzzymotiv plan`, `sweep` and
`merge`, byte for byte: in threads, on a real Dask cluster (two worker processes on the
loopback interface), and through the submitit example; finished jobs skipped; job locks held
by another process (the test holds them: no sleeps); pickling of jobs, results and problems."""

import fcntl
import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import fuzzymotiv as fm
from conftest import run_cli

SWEEP = """\
name = "py-sweep"
seed = 5
rooms = ["H", "square"]
[ga]
population = 6
generations = 2
[trial]
steps = 60
[aem]
epochs = 5
test_runs = 1
[sweep]
replicates = 2
motivations = [[0.8, 0.1, 0.0, 0.1], [0.5, 0.3, 0.0, 0.2]]
"""

# The same sweep as a dict (what fm.plan also takes).
SWEEP_DICT = {
    "name": "py-sweep",
    "seed": 5,
    "rooms": ["H", "square"],
    "ga": {"population": 6, "generations": 2},
    "trial": {"steps": 60},
    "aem": {"epochs": 5, "test_runs": 1},
    "sweep": {"replicates": 2, "motivations": [[0.8, 0.1, 0.0, 0.1], [0.5, 0.3, 0.0, 0.2]]},
}

# The files of a sweep directory that must equal the CLI's byte for byte.
SWEEP_FILES = ["plan.jsonl", "sweep.toml", "results.csv", "aggregate.csv", "aggregate.md"]
# ... and of every job folder (summary.json and report.html hold wall times).
JOB_FILES = ["generations.csv", "config.resolved.toml", "best_genome.json", "job.json", "DONE"]


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory) -> Path:
    f = tmp_path_factory.mktemp("sweepfile") / "sweep.toml"
    f.write_text(SWEEP)
    return f


@pytest.fixture(scope="module")
def cli_sweep(cli, sweep_file, tmp_path_factory) -> Path:
    """`fuzzymotiv sweep` + `merge`: the reference."""
    out = tmp_path_factory.mktemp("cli") / "sweep"
    run_cli(cli, "sweep", sweep_file, "--out", out, "--threads", "1", "--quiet")
    run_cli(cli, "merge", out)
    return out


def assert_same_sweep(ours: Path, ref: Path, sweep_file: Path) -> None:
    for name in SWEEP_FILES:
        assert (ours / name).read_bytes() == (ref / name).read_bytes(), name
    for job in fm.plan(sweep_file):
        for name in JOB_FILES:
            a, b = ours / "jobs" / job.id / name, ref / "jobs" / job.id / name
            assert a.read_bytes() == b.read_bytes(), f"jobs/{job.id}/{name}"


def test_plan_equals_the_cli_plan(cli, sweep_file):
    plan = fm.plan(sweep_file)
    printed = run_cli(cli, "plan", sweep_file).stdout
    assert plan.jsonl == printed
    assert [j.record() for j in plan] == [__import__("json").loads(l) for l in printed.splitlines()]
    assert len(plan) == 4 and plan[0].index == 0 and len({j.id for j in plan}) == 4
    # The same document as a dict or as text: the same ids and seeds.
    for other in (fm.plan(SWEEP_DICT), fm.plan(sweep_text=SWEEP)):
        assert [(j.id, j.seed, j.key) for j in other] == [(j.id, j.seed, j.key) for j in plan]
    # Jobs and plans are plain values: they pickle and compare equal.
    assert pickle.loads(pickle.dumps(plan)) == plan
    assert pickle.loads(pickle.dumps(plan[1])) == plan[1]


def test_sweep_in_threads_equals_cli_sweep_and_merge(sweep_file, cli_sweep, tmp_path):
    out = tmp_path / "py"
    res = fm.sweep(fm.plan(sweep_file), out=out)
    assert_same_sweep(out, cli_sweep, sweep_file)
    assert set(res.statuses.values()) == {"ran"} and len(res.statuses) == 4
    assert (res.jobs, res.missing) == (4, 0)
    assert res.markdown == (cli_sweep / "aggregate.md").read_text()
    assert res.results.rows == 8  # one row per job and room
    assert list(res.results["job_id"]) == [j.id for j in fm.plan(sweep_file) for _ in range(2)]

    # Again: every job is finished, nothing runs, the same results.
    again = fm.sweep(fm.plan(sweep_file), out=out)
    assert set(again.statuses.values()) == {"skipped"}
    assert_same_sweep(out, cli_sweep, sweep_file)


def test_finished_jobs_of_the_cli_are_skipped(sweep_file, cli_sweep, tmp_path):
    # A directory the CLI finished half of: Python runs only the other half.
    out = tmp_path / "half"
    plan = fm.plan(sweep_file)
    assert fm.run_job(plan[0], out) == "ran"
    assert fm.run_job(plan[0], out) == "skipped"
    res = fm.sweep(plan, out=out, executor=None)
    assert [res.statuses[j.id] for j in plan] == ["skipped", "ran", "ran", "ran"]
    assert_same_sweep(out, cli_sweep, sweep_file)


def test_dask_local_cluster_equals_cli(sweep_file, cli_sweep, tmp_path):
    import distributed  # a test dependency (.ci/run, the `test` extra): never skipped
    out = tmp_path / "dask"
    cluster = distributed.LocalCluster(
        processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None
    )
    with cluster, distributed.Client(cluster) as client:
        res = fm.sweep(fm.plan(sweep_file), out=out, executor=client.get_executor())
        # The jobs ran in the worker processes, not here.
        pids = set(client.run(os.getpid).values())
        assert os.getpid() not in pids and len(pids) == 2
    assert set(res.statuses.values()) == {"ran"}
    assert_same_sweep(out, cli_sweep, sweep_file)


# ---------------------------------------------------------------------------------------------
# Job locks: the test holds a job's lock (an exclusive flock on OUT/jobs/ID.lock, as another
# worker would), and another process — Python's run_job or the CLI's sweep — meets it.


class HeldLock:
    """The lock of `job` in the sweep directory `out`, held by this process."""

    def __init__(self, out: Path, job):
        (out / "jobs").mkdir(parents=True, exist_ok=True)
        self.fd = os.open(out / "jobs" / f"{job.id}.lock", os.O_RDWR | os.O_CREAT, 0o644)
        fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)

    def release(self) -> None:
        os.close(self.fd)  # as a dying worker's lock goes when the OS closes its files


RUN_JOB = """
import pickle, sys
import fuzzymotiv as fm
job, out, wait = pickle.loads(bytes.fromhex(sys.argv[1]))
print(fm.run_job(job, out, wait=wait), flush=True)
"""


def run_job_process(job, out: Path, wait: bool) -> subprocess.Popen:
    arg = pickle.dumps((job, str(out), wait)).hex()
    return subprocess.Popen(
        [sys.executable, "-c", RUN_JOB, arg], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )


def wait_for_waiting(p: subprocess.Popen) -> str:
    """Reads the process's stderr until it says it waits for the lock (blocking reads)."""
    seen = ""
    for line in p.stderr:
        seen += line
        if "waiting for it" in line:
            return seen
    raise AssertionError(f"the process never waited for the lock; stderr: {seen!r}")


def test_a_locked_job_returns_running_without_waiting(sweep_file, tmp_path):
    out = tmp_path / "locked"
    job = fm.plan(sweep_file)[2]
    lock = HeldLock(out, job)
    p = run_job_process(job, out, wait=False)
    stdout, stderr = p.communicate()
    assert p.returncode == 0, stderr
    assert stdout.strip() == "running"
    assert not (out / "jobs" / job.id).exists() and not (out / "jobs" / f"{job.id}.partial").exists()
    lock.release()
    assert fm.run_job(job, out, wait=False) == "ran"


def test_a_waiting_worker_runs_the_job_of_a_worker_that_died(sweep_file, cli_sweep, tmp_path):
    out = tmp_path / "died"
    job = fm.plan(sweep_file)[1]
    lock = HeldLock(out, job)
    p = run_job_process(job, out, wait=True)
    wait_for_waiting(p)
    # It waits: nothing of the job is written while the lock is held.
    assert not (out / "jobs" / job.id).exists() and not (out / "jobs" / f"{job.id}.partial").exists()
    lock.release()  # the holder dies without finishing
    stdout, stderr = p.communicate()
    assert p.returncode == 0, stderr
    assert stdout.strip() == "ran"
    for name in JOB_FILES:
        assert (out / "jobs" / job.id / name).read_bytes() == (cli_sweep / "jobs" / job.id / name).read_bytes()


def test_the_cli_waits_for_a_job_python_holds_and_skips_it_once_finished(cli, sweep_file, cli_sweep, tmp_path):
    import shutil

    out = tmp_path / "finished-by-holder"
    job = fm.plan(sweep_file)[0]
    lock = HeldLock(out, job)
    p = subprocess.Popen(
        [str(cli), "sweep", str(sweep_file), "--out", str(out), "--index", "0", "--threads", "1"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    said = wait_for_waiting(p)
    assert f"job {job.id}: another worker is running it" in said
    # The holder finishes the job (its files, as the reference sweep wrote them), then lets go.
    shutil.copytree(cli_sweep / "jobs" / job.id, out / "jobs" / job.id)
    lock.release()
    _, stderr = p.communicate()
    assert p.returncode == 0, stderr
    assert "0 jobs run, 1 already done" in stderr


# ---------------------------------------------------------------------------------------------
# Bad input, and what pickles.


def test_bad_sweeps_and_jobs_raise_fuzzymotiv_error(sweep_file, tmp_path):
    bad = dict(SWEEP_DICT, sweep={"replicates": 0})
    with pytest.raises(fm.FuzzymotivError, match="sweep.replicates"):
        fm.plan(bad)
    with pytest.raises(fm.FuzzymotivError, match="expected a fuzzymotiv.Job"):
        fm.run_job({"id": "x"}, tmp_path / "o")
    import dataclasses

    job = fm.plan(sweep_file)[0]
    with pytest.raises(fm.FuzzymotivError, match="not a job of"):
        fm.run_job(dataclasses.replace(job, id="0000000000000000"), tmp_path / "o")
    with pytest.raises(fm.FuzzymotivError, match="out: an empty path"):
        fm.run_job(job, "")
    # Another plan's directory is refused, as `fuzzymotiv sweep` refuses it.
    other = fm.plan(sweep_text=SWEEP.replace("seed = 5", "seed = 6"))
    fm.run_job(other[0], tmp_path / "other", wait=False)
    with pytest.raises(fm.FuzzymotivError, match="holds a sweep of another plan"):
        fm.run_job(job, tmp_path / "other")


def test_errors_pickle_so_executors_can_return_them():
    for e in (fm.FuzzymotivError("bad field"), fm.FuzzymotivOSError("disk full")):
        back = pickle.loads(pickle.dumps(e))
        assert type(back) is type(e) and back.args == e.args


def test_run_result_survives_pickle():
    res = fm.run(overrides={"ga.population": 6, "ga.generations": 2, "trial.steps": 50, "rooms": ["H"], "aem.enabled": False})
    back = pickle.loads(pickle.dumps(res))
    assert back.summary == res.summary
    assert np.array_equal(back.best_genome, res.best_genome)
    assert list(back.generations["best"]) == list(res.generations["best"])
    assert repr(back) == repr(res)


@pytest.mark.parametrize("config", ["file", "text", "defaults"])
def test_problem_survives_pickle(repo, config):
    overrides = {"rooms": ["H", "T"], "trial.steps": 40}
    made = {
        "file": lambda: fm.Problem(repo / "configs/tiny.toml", overrides, seed=3),
        "text": lambda: fm.Problem(config_text="seed = 11\n", overrides=overrides, threads=1),
        "defaults": lambda: fm.Problem(None, overrides, room=None),
    }[config]
    p = made()
    back = pickle.loads(pickle.dumps(p))
    assert repr(back) == repr(p)
    genomes = np.random.default_rng(0).normal(size=(3, p.genome_size))
    a, b = p.evaluate(genomes, generation=1), back.evaluate(genomes, generation=1)
    assert a.fitness.tobytes() == b.fitness.tobytes() and a.terms.tobytes() == b.terms.tobytes()


def test_submitit_example_runs_the_sweep(repo, sweep_file, cli_sweep, tmp_path):
    import submitit  # noqa: F401  (a test dependency: the example needs it)
    out = tmp_path / "submitit"
    p = subprocess.run(
        [sys.executable, str(repo / "examples/python/submitit_sweep.py"), str(sweep_file), str(out),
         "--cluster", "local", "--logs", str(tmp_path / "logs")],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stderr + p.stdout
    assert_same_sweep(out, cli_sweep, sweep_file)


def test_ga_survives_pickle_and_goes_on_alike():
    p = fm.Problem(overrides={"rooms": ["H"], "aem.enabled": False, "ga.population": 6, "trial.steps": 40})
    ga = fm.GA(p, seed=2)
    ev = p.evaluate(ga.ask(), generation=ga.generation, seed=ga.seed)
    ga.tell(ev.fitness, ev.terms)
    back = pickle.loads(pickle.dumps(ga))
    assert back.state == ga.state
    assert back.ask().tobytes() == ga.ask().tobytes()


def test_sweep_into_another_plans_sweep_needs_force(sweep_file, cli_sweep, tmp_path):
    """fm.sweep checks `out` before any job, as `fuzzymotiv sweep` does, in Python's words; with
    force=True the other sweep's own files go and a file of the user's stays."""
    out = tmp_path / "sw"
    other = dict(SWEEP_DICT, sweep={"replicates": 1, "motivations": [[0.2, 0.6, 0.0, 0.2]]})
    fm.sweep(fm.plan(other), out=out)
    mine = out / "notes.txt"
    mine.write_text("mine")
    before = (out / "results.csv").read_bytes()
    with pytest.raises(fm.FuzzymotivError, match=r"another plan.*force=True") as e:
        fm.sweep(fm.plan(sweep_file), out=out)
    assert "--force" not in str(e.value) and "--out" not in str(e.value)
    assert (out / "results.csv").read_bytes() == before
    fm.sweep(fm.plan(sweep_file), out=out, force=True)
    assert_same_sweep(out, cli_sweep, sweep_file)
    assert mine.read_text() == "mine"
