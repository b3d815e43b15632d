"""Checks the Kubernetes and HTCondor sweep examples and runs them as their engines would.

    python .ci/engines.py FUZZYMOTIV_BIN SWEEP.toml WORKDIR

Kubernetes (examples/kubernetes/sweep-job.yaml): schema check with kubernetes-validate
(--strict), an indexed Job whose completions equal the plan's count; HTCondor
(examples/htcondor/sweep.sub): parsed by the htcondor bindings' Submit parser, a queue count
equal to the plan's count, IDX=$(Process). Then each file's own command line runs once per
index of SWEEP.toml (the small CI sweep, put in place of the example's sweep file), with the
index variable set as that engine sets it, and the merged results.csv must equal the local
`fuzzymotiv sweep` + `merge` byte for byte.
"""

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import htcondor2
import yaml

REPO = Path(__file__).resolve().parents[1]
K8S = REPO / "examples/kubernetes/sweep-job.yaml"
CONDOR = REPO / "examples/htcondor/sweep.sub"


def fail(msg):
    sys.exit(f"engines: {msg}")


def fm(bin_, *args):
    p = subprocess.run([bin_, *map(str, args)], cwd=REPO, capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"fuzzymotiv {' '.join(map(str, args))} failed ({p.returncode}): {p.stderr}")
    return p.stdout


def plan_count(bin_, sweep):
    return int(fm(bin_, "plan", sweep, "--count").strip())


def run_tasks(tasks):
    """Runs (argv, env) pairs at the same time, as an engine's pods or processes would."""
    procs = [subprocess.Popen(a, cwd=REPO, env=e, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True) for a, e in tasks]
    for (argv, env), p in zip(tasks, procs):
        _, err = p.communicate()
        if p.returncode != 0:
            fail(f"task {argv} failed ({p.returncode}): {err}")


def kubernetes(bin_, sweep, out):
    v = subprocess.run([sys.executable, "-m", "kubernetes_validate", "--strict", str(K8S)],
                       capture_output=True, text=True)
    if v.returncode != 0:
        fail(f"{K8S.name}: kubernetes-validate: {v.stdout}{v.stderr}")
    job = yaml.safe_load(K8S.read_text())
    spec = job["spec"]
    if job["kind"] != "Job" or spec.get("completionMode") != "Indexed":
        fail(f"{K8S.name}: want kind Job with completionMode Indexed")
    (c,) = spec["template"]["spec"]["containers"]
    env = {e["name"]: e["value"] for e in c.get("env", [])}
    argv = c["command"] + c["args"]
    if "JOB_COMPLETION_INDEX" not in argv or "--index-from-env" not in argv:
        fail(f"{K8S.name}: the command must read --index-from-env JOB_COMPLETION_INDEX")
    n = plan_count(bin_, env["SWEEP"])
    if spec["completions"] != n:
        fail(f"{K8S.name}: completions {spec['completions']}, but {env['SWEEP']} plans {n} jobs")
    env.update(SWEEP=str(sweep), OUT=str(out))
    # Kubernetes expands $(VAR) in command and args from the container's env.
    expand = lambda s: re.sub(r"\$\((\w+)\)", lambda m: env.get(m[1], m[0]), s)  # noqa: E731
    argv = [bin_ if a == "fuzzymotiv" else expand(a) for a in argv]
    tasks = [(argv, {**os.environ, **env, "JOB_COMPLETION_INDEX": str(i)})
             for i in range(plan_count(bin_, sweep))]
    run_tasks(tasks)
    return f"kubernetes: {K8S.name} valid (strict), completions {n}; {len(tasks)} pods run"


def htcondor(bin_, sweep, out):
    sub = htcondor2.Submit(CONDOR.read_text())  # raises on a malformed description
    n = plan_count(bin_, sub["SWEEP"])
    if int(sub.getQArgs()) != n:
        fail(f"{CONDOR.name}: queue {sub.getQArgs()}, but {sub['SWEEP']} plans {n} jobs")
    if "$(Process)" not in sub["environment"] or "--index-from-env IDX" not in sub["arguments"]:
        fail(f"{CONDOR.name}: want environment IDX=$(Process) and --index-from-env IDX")
    sub["FUZZYMOTIV"], sub["SWEEP"], sub["OUT"] = bin_, str(sweep), str(out)
    tasks = []
    for i in range(plan_count(bin_, sweep)):
        sub["Process"] = str(i)
        # HTCondor's "new syntax": one double-quoted string, words split as by a shell.
        argv = [sub.expand("executable"), *shlex.split(sub.expand("arguments").strip('"'))]
        env = dict(w.split("=", 1) for w in shlex.split(sub.expand("environment").strip('"')))
        tasks.append((argv, {**os.environ, **env}))
    run_tasks(tasks)
    return f"htcondor: {CONDOR.name} parsed, queue {n}; {len(tasks)} processes run"


def main():
    bin_, sweep, work = sys.argv[1], Path(sys.argv[2]).resolve(), Path(sys.argv[3]).resolve()
    local = work / "local"
    fm(bin_, "sweep", sweep, "--out", local, "--quiet")
    fm(bin_, "merge", local)
    want = (local / "results.csv").read_bytes()
    for engine in (kubernetes, htcondor):
        out = work / engine.__name__
        print(engine(bin_, sweep, out))
        fm(bin_, "merge", out)
        if (out / "results.csv").read_bytes() != want:
            fail(f"{engine.__name__}: results.csv differs from the local sweep ({local})")
        print(f"{engine.__name__}: results.csv equals the local sweep's byte for byte")


if __name__ == "__main__":
    main()
