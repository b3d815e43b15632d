"""`Problem.evaluate` throughput, measured as `fuzzymotiv bench`'s population measurement is: the
same experiment (one room, 200 robots, 400-step trials, no AEM), whole populations with a new
generation number each (fresh noise), executed robot-steps per second, median of the
repetitions. Usage (after `pip install ./python`):

    python bench/python_evaluate.py [--room H] [--rooms N] [--threads T] [--repeat R] [--steps S]

`--rooms 5` evaluates every robot in the five built-in rooms (the issue's 200 × 5 × 400).
"""

import argparse
import json
import statistics
import time

import fuzzymotiv as fm

ROOMS = ["H", "T", "L", "square", "rectangle"]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--room", default="H")
    ap.add_argument("--rooms", type=int, default=1, help="use the first N built-in rooms instead")
    ap.add_argument("--population", type=int, default=200)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--steps", type=int, default=2_000_000, help="robot-steps per repetition")
    ap.add_argument("--descriptors", action="store_true")
    args = ap.parse_args()
    rooms = ROOMS[: args.rooms] if args.rooms > 1 else [args.room]
    overrides = {
        "rooms": rooms,
        "ga.population": args.population,
        "ga.elite": min(args.population, 3) - 1,
        "aem.enabled": False,
    }
    problem = fm.Problem(overrides=overrides, threads=args.threads)
    genomes = fm.GA(problem).ask()  # the initial population, as the bench evaluates
    per_eval = args.population * len(rooms) * problem.steps
    evaluations = -(-args.steps // per_eval)
    seconds, steps = [], []
    for r in range(args.repeat):
        t0 = time.perf_counter()
        done = 0
        for e in range(evaluations):
            _, _, _, executed = problem._native.evaluate(
                genomes, r * evaluations + e, None, args.descriptors, None
            )
            done += executed
        seconds.append(time.perf_counter() - t0)
        steps.append(done)
    s, n = statistics.median(seconds), statistics.median(steps)
    print(
        json.dumps(
            {
                "rooms": rooms,
                "population": args.population,
                "threads": args.threads,
                "evaluations": evaluations,
                "descriptors": args.descriptors,
                "robot_steps": n,
                "seconds": s,
                "robot_steps_per_sec": n / s,
            }
        )
    )


if __name__ == "__main__":
    main()
