"""The package's types are inline and exist at run time: the TypedDicts name the keys of the
dicts the API returns, and the Gymnasium env is generic in its observation and action."""

import typing

import numpy as np
import pytest

import fuzzymotiv as fm


def test_typed_dicts_name_the_keys_the_api_returns():
    trajectory = fm.simulate(np.zeros(68), "H", seed=1, overrides={"trial.steps": 5})
    assert set(typing.get_type_hints(fm.Trajectory)) == set(trajectory)
    room = fm.rooms()[0]
    assert set(typing.get_type_hints(fm.RoomInfo)) == set(room)
    assert set(typing.get_type_hints(fm.Home)) == set(room["home"])
    assert set(typing.get_type_hints(fm.HomeZone)) == set(room["home_zone"])
    explanation = fm.fuzzy_fitness([0.8, 0.1, 0, 0.1], [1, 0.25, 0, 0], explain=True)
    assert set(typing.get_type_hints(fm.Explanation)) == set(explanation)
    assert set(typing.get_type_hints(fm.FiringRule)) == set(explanation["rules"][0])
    ga = fm.GA(fm.Problem(overrides={"trial.steps": 5, "ga.population": 4}))
    assert set(typing.get_type_hints(fm.GAState)) == set(ga.state)


def test_kheperaenv_is_a_gymnasium_env_of_arrays():
    gym = pytest.importorskip("gymnasium")
    import fuzzymotiv.gym as fmgym

    (base,) = fmgym.KheperaEnv.__orig_bases__
    assert typing.get_origin(base) is gym.Env
    assert all(typing.get_origin(a) is np.ndarray for a in typing.get_args(base))
