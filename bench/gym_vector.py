"""Robot-steps per second of fuzzymotiv's native vector env (64 envs, info included) on one
core, beside a typical pure-Python Gymnasium env (CartPole-v1, stepped one env at a time).

    taskset -c 0 python bench/gym_vector.py [--envs 64] [--seconds 5] [--room H] [--json]

Needs `pip install ./python gymnasium` (a release build of the extension). The vector env runs
the paper's trials (T = 400, `motion = "actions"`, end at home) with uniformly random motor
outputs, reward "end", float32 spaces, next-step autoreset; every step returns the full `info`
(a, g, l, b, pose, t, room, action and their masks). The actions are drawn before timing.
Reported: robot-steps per CPU second = num_envs x vector steps / process CPU time (best of 3
rounds; the process runs one thread, so this is the rate on one core, whatever the load).
"""

import argparse
import json
import os
import time

import gymnasium as gym
import numpy as np

from fuzzymotiv.gym import KheperaVectorEnv


def best_rate(step, n_per_call, seconds, rounds=3):
    """Best of `rounds` rounds of calling `step` for about `seconds` of this process's CPU
    time: items per CPU second (on a shared machine wall time counts the other processes too;
    the process is single-threaded, so its CPU time is its time on one core)."""
    best = 0.0
    for _ in range(rounds):
        calls, start = 0, time.process_time()
        while True:
            for _ in range(200):
                step()
            calls += 200
            elapsed = time.process_time() - start
            if elapsed >= seconds:
                break
        best = max(best, calls * n_per_call / elapsed)
    return best


def vector_rate(envs, room, seconds, discrete=False):
    vec = KheperaVectorEnv(envs, room, discrete=discrete)
    vec.reset(seed=0)
    rng = np.random.default_rng(0)
    if discrete:
        pool = rng.integers(0, 4, (256, envs))
    else:
        pool = rng.random((256, envs, 2))
    k = [0]

    def step():
        vec.step(pool[k[0] & 255])
        k[0] += 1

    return best_rate(step, envs, seconds)


def native_only_rate(envs, room, seconds):
    """The native call alone (no Python wrapper): where the time goes."""
    vec = KheperaVectorEnv(envs, room)
    vec.reset(seed=0)
    core = vec._core
    pool = np.random.default_rng(0).random((256, envs, 2))
    k = [0]

    def step():
        core.step(pool[k[0] & 255])
        k[0] += 1

    return best_rate(step, envs, seconds)


def cartpole_rate(seconds):
    env = gym.make("CartPole-v1")
    env.reset(seed=0)
    actions = np.random.default_rng(0).integers(0, 2, 4096)
    k = [0]

    def step():
        _, _, term, trunc, _ = env.step(int(actions[k[0] & 4095]))
        k[0] += 1
        if term or trunc:
            env.reset()

    return best_rate(step, 1, seconds)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--envs", type=int, default=64)
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--room", default="H")
    ap.add_argument("--json", action="store_true")
    a = ap.parse_args()
    result = {
        "envs": a.envs,
        "room": a.room,
        "cpus": len(os.sched_getaffinity(0)),
        "vector_env_steps_per_s": vector_rate(a.envs, a.room, a.seconds),
        "vector_env_discrete_steps_per_s": vector_rate(a.envs, a.room, a.seconds, discrete=True),
        "native_step_only_steps_per_s": native_only_rate(a.envs, a.room, a.seconds),
        "cartpole_v1_steps_per_s": cartpole_rate(a.seconds),
    }
    if a.json:
        print(json.dumps(result, indent=2))
        return
    print(f"fuzzymotiv vector env, {a.envs} envs, room {a.room}, {result['cpus']} CPU(s):")
    print(f"  Box actions:      {result['vector_env_steps_per_s']:>12,.0f} robot-steps/s")
    print(f"  Discrete actions: {result['vector_env_discrete_steps_per_s']:>12,.0f} robot-steps/s")
    print(f"  native call only: {result['native_step_only_steps_per_s']:>12,.0f} robot-steps/s")
    print(f"CartPole-v1 (gym.make, one env): {result['cartpole_v1_steps_per_s']:>9,.0f} steps/s")


if __name__ == "__main__":
    main()
