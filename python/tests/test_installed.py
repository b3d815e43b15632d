"""Which fuzzymotiv the suite tests: with FUZZYMOTIV_EXPECT_WHEEL=1 (.ci/run, which installs the
wheel into a fresh virtual environment), the installed package in site-packages, never the
source tree's python/fuzzymotiv."""

import os
import sysconfig
from pathlib import Path

import pytest

import fuzzymotiv

REPO = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(not os.environ.get("FUZZYMOTIV_EXPECT_WHEEL"), reason="FUZZYMOTIV_EXPECT_WHEEL unset")
def test_the_installed_wheel_is_tested():
    where = Path(fuzzymotiv.__file__).resolve()
    site = Path(sysconfig.get_paths()["platlib"]).resolve()
    assert site in where.parents, f"fuzzymotiv imported from {where}, not from {site}"
    assert REPO / "python" not in where.parents, f"fuzzymotiv imported from the source tree: {where}"
    native = Path(fuzzymotiv._fuzzymotiv.__file__).name
    assert native.endswith(".abi3.so"), f"the extension is {native}, not an abi3 module"
