"""A fuzzymotiv sweep on SLURM from Python, through submitit: one SLURM job per job of the plan,
then the merge (the same results.csv as `fuzzymotiv sweep` + `fuzzymotiv merge`).

    pip install ./python submitit                        # in a virtual environment
    python examples/python/submitit_sweep.py configs/sweep-small.toml out/sweeps/small
    python examples/python/submitit_sweep.py SWEEP.toml OUT --cluster local   # no SLURM

Run it again after a failure or a time-out: finished jobs are skipped, killed ones resume from
their checkpoint. Jobs are locked while they run, so a resubmitted job beside a dying one waits
for it instead of running twice. The sweep directory must be on a file system every node sees.
"""

import argparse
from pathlib import Path

import submitit

import fuzzymotiv as fm


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("sweep", type=Path, help="sweep file (a config with a [sweep] table)")
    ap.add_argument("out", type=Path, help="sweep directory (shared by the nodes)")
    ap.add_argument("--cluster", default="slurm", help="slurm (default), local or debug")
    ap.add_argument("--logs", type=Path, default=None, help="submitit's folder (default: OUT.submitit)")
    ap.add_argument("--partition", default=None, help="SLURM partition (default: the cluster's)")
    ap.add_argument("--cpus", type=int, default=2, help="CPUs per job (default 2)")
    ap.add_argument("--timeout-min", type=int, default=30, help="time limit per job (default 30)")
    args = ap.parse_args()

    logs = args.logs or args.out.with_name(args.out.name + ".submitit")
    executor = submitit.AutoExecutor(folder=logs, cluster=args.cluster)
    executor.update_parameters(timeout_min=args.timeout_min, name="fuzzymotiv")
    if args.cluster == "slurm":
        executor.update_parameters(slurm_cpus_per_task=args.cpus)
        if args.partition:
            executor.update_parameters(slurm_partition=args.partition)

    result = fm.sweep(fm.plan(args.sweep), out=args.out, executor=executor)
    print(result.markdown)
    print(f"{result.jobs - result.missing} of {result.jobs} jobs in {args.out / 'results.csv'}")


if __name__ == "__main__":
    main()
