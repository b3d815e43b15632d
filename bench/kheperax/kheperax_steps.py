"""Robot-steps per second of Kheperax's standard maze task (kheperax's own
`KheperaxTask.create_default_task`: the "standard" maze, 1000-step episodes, an MLP policy with
one hidden layer of 8 units and tanh outputs, three lasers and two bumpers as inputs), JAX on
CPU. For each batch size: the jitted scoring function (reset, 1000 steps of every policy in the
batch, fitness and descriptors) is called once to compile it (not timed), then REPEAT times;
robot-steps per second = batch x episode length / seconds, median over the repetitions.

    python kheperax_steps.py --batch 1 64 1024 --repeat 5 [--episode-length 1000]

Prints one JSON document.
"""

import argparse
import json
import os
import statistics
import time

import jax
import jax.numpy as jnp

# kheperax 0.2.0 (the newest on PyPI) still calls jax.tree_leaves and jax.tree_map, which JAX
# removed in 0.6; they are the same functions as jax.tree_util's, so they are put back here
# rather than pinning an old JAX (which today's flax, chex and optax on PyPI no longer accept).
for _name in ("tree_leaves", "tree_map"):
    if not hasattr(jax, _name):
        setattr(jax, _name, getattr(jax.tree_util, _name))
from kheperax.tasks.config import KheperaxConfig
from kheperax.tasks.main import KheperaxTask


def measure(batch: int, repeat: int, episode_length: int) -> dict:
    config = KheperaxConfig.get_default()
    config.episode_length = episode_length
    key = jax.random.PRNGKey(1)
    env, policy, scoring_fn = KheperaxTask.create_default_task(config, random_key=key)
    key, sub = jax.random.split(key)
    fake = jnp.zeros((batch, env.observation_size))
    params = jax.vmap(policy.init)(jax.random.split(sub, batch), fake)
    scoring = jax.jit(scoring_fn)
    start = time.perf_counter()
    jax.block_until_ready(scoring(params, key))  # compile + first run: not timed
    warmup = time.perf_counter() - start
    seconds = []
    for _ in range(repeat):
        key, sub = jax.random.split(key)
        start = time.perf_counter()
        jax.block_until_ready(scoring(params, sub))
        seconds.append(time.perf_counter() - start)
    steps = batch * episode_length
    rates = [steps / s for s in seconds]
    return {
        "batch": batch,
        "episode_length": episode_length,
        "robot_steps_per_call": steps,
        "median_robot_steps_per_sec": statistics.median(rates),
        "min": min(rates),
        "max": max(rates),
        "seconds": seconds,
        "warmup_seconds": warmup,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--batch", type=int, nargs="+", default=[1, 64, 1024])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--episode-length", type=int, default=1000)
    args = ap.parse_args()
    import kheperax  # noqa: F401  (version below)
    from importlib.metadata import version

    doc = {
        "kheperax": version("kheperax"),
        "jax": jax.__version__,
        "devices": [str(d) for d in jax.devices()],
        "cpus_allowed": len(os.sched_getaffinity(0)),
        "runs": [measure(b, args.repeat, args.episode_length) for b in args.batch],
    }
    print(json.dumps(doc, indent=2))


if __name__ == "__main__":
    main()
