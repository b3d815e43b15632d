"""fm.export_controller writes what `fuzzymotiv export` writes, through the same output guard."""

import json
import math

import pytest

import fuzzymotiv as fm
from conftest import run_cli

SMALL = {"ga.generations": 2, "ga.population": 8, "trial.steps": 80, "aem.epochs": 20, "aem.test_runs": 2}


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("export") / "run"
    fm.run(None, SMALL, out=out, threads=2)
    return out


def test_export_controller_writes_the_clis_files(run_dir, tmp_path, cli):
    written = fm.export_controller(run_dir, to="c", out=tmp_path / "py")
    assert [p.rsplit("/", 1)[1] for p in written] == ["fm_controller.h", "fm_controller.c"]
    run_cli(cli, "export", run_dir, "--to", "c", "--out", tmp_path / "cli")
    for name in ["fm_controller.h", "fm_controller.c"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    fm.export_controller(run_dir, to="json", out=tmp_path / "c.json")
    doc = json.loads((tmp_path / "c.json").read_text())
    genome = json.loads((run_dir / "best_genome.json").read_text())
    assert doc["format"] == "fuzzymotiv-controller"
    assert doc["network"]["weights"] == genome["weights"]
    fm.export_controller(run_dir, to="onnx", out=tmp_path / "c.onnx")
    run_cli(cli, "export", run_dir, "--to", "onnx", "--out", tmp_path / "cli.onnx")
    assert (tmp_path / "c.onnx").read_bytes() == (tmp_path / "cli.onnx").read_bytes()


def test_export_controller_keeps_another_file_and_names_bad_input(run_dir, tmp_path):
    target = tmp_path / "c.json"
    target.write_text("mine")
    with pytest.raises(fm.OutputExistsError):
        fm.export_controller(run_dir, to="json", out=target)
    assert target.read_text() == "mine"
    fm.export_controller(run_dir, to="json", out=target, force=True)
    assert target.read_text() != "mine"
    with pytest.raises(fm.FuzzymotivError, match="to: `tflite` is not an export format"):
        fm.export_controller(run_dir, to="tflite", out=tmp_path / "x")  # type: ignore[arg-type]
    bad = tmp_path / "best_genome.json"
    bad.write_text('{"shape": {"hidden": 6}, "weights": [1.0]}')
    with pytest.raises(fm.FuzzymotivError, match=r"best_genome.json: field `weights`"):
        fm.export_controller(bad, to="c", out=tmp_path / "c")
    assert not (tmp_path / "c").exists()


def test_robustness_gives_the_rows_the_cli_writes(run_dir, tmp_path, cli):
    table = fm.robustness(run_dir, trials=3)
    assert isinstance(table, fm.Table)
    run_cli(cli, "robustness", run_dir, "--out", tmp_path / "rob", "--trials", "3")
    text = (tmp_path / "rob" / "robustness.csv").read_text().splitlines()
    assert list(table) == text[0].split(",")
    assert table.rows == len(text) - 1
    for k, line in enumerate(text[1:]):
        cells = line.split(",")
        assert table["perturbation"][k] == cells[0]
        for name, cell in zip(list(table)[1:], cells[1:]):
            assert f"{table[name][k]:.6f}" == f"{float(cell):.6f}", (name, k)
    assert table["perturbation"][0] == "none"
    assert all(table["f_lo"] <= table["f"]) and all(table["f"] <= table["f_hi"])
    # The run models its rooms: each perturbation's trials are also recognised by that model.
    assert list(table)[-3:] == ["recognition", "recognition_lo", "recognition_hi"]
    assert all((0 <= table["recognition"]) & (table["recognition"] <= 1))


def test_robustness_names_bad_input(run_dir, tmp_path):
    with pytest.raises(fm.FuzzymotivError, match="trials must be a whole number in 2..=10000"):
        fm.robustness(run_dir, trials=1)
    with pytest.raises(fm.FuzzymotivError, match="not a run directory"):
        fm.robustness(tmp_path, trials=3)


def test_recognise_gives_the_rows_the_cli_writes(run_dir, tmp_path, cli):
    run_cli(cli, "replay", run_dir, "--out", tmp_path / "rep")
    logs = [tmp_path / f"rep-{room}.csv" for room in ("H", "square")]
    table = fm.recognise(run_dir, logs)
    run_cli(cli, "recognise", run_dir, *logs, "--out", tmp_path / "rec")
    text = (tmp_path / "rec" / "recognised.csv").read_text().splitlines()
    header = text[0].split(",")
    assert list(table) == header
    assert table.rows == 2
    for k, line in enumerate(text[1:]):
        cells = line.split(",")
        assert str(table["room"][k]) == cells[header.index("room")]
        assert int(table["winner"][k]) == int(cells[header.index("winner")])
        assert int(table["gate"][k]) == int(cells[header.index("gate")])
        if cells[header.index("room")]:
            assert int(table["r_node"][k]) == int(cells[header.index("r_node")])
            assert int(table["node_distance"][k]) <= int(table["gate"][k])
            distance = float(cells[header.index("vector_distance")])
            assert float(table["vector_distance"][k]) == distance
        else:
            assert math.isnan(table["r_node"][k]) and cells[header.index("r_node")] == ""


def test_recognise_names_a_bad_log(run_dir, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("step,action\n0,sideways\n")
    with pytest.raises(fm.FuzzymotivError, match="line 2: field `action`"):
        fm.recognise(run_dir, [bad])


def test_export_controller_to_dash_writes_one_file_formats_to_stdout_and_no_file(
    run_dir, tmp_path, monkeypatch, capsysbinary, cli
):
    monkeypatch.chdir(tmp_path)
    run_cli(cli, "export", run_dir, "--to", "json", "--out", tmp_path / "cli.json")
    run_cli(cli, "export", run_dir, "--to", "onnx", "--out", tmp_path / "cli.onnx")
    assert fm.export_controller(run_dir, to="json", out="-") == []
    assert capsysbinary.readouterr().out == (tmp_path / "cli.json").read_bytes()
    assert fm.export_controller(run_dir, to="onnx", out="-") == []
    assert capsysbinary.readouterr().out == (tmp_path / "cli.onnx").read_bytes()
    with pytest.raises(ValueError, match="to=\"c\" writes two"):
        fm.export_controller(run_dir, to="c", out="-")
    assert not (tmp_path / "-").exists()


@pytest.fixture(scope="module")
def thymio_run(tmp_path_factory, repo):
    out = tmp_path_factory.mktemp("export-thymio") / "run"
    small = {"ga.generations": 2, "ga.population": 10, "trial.steps": 100, "aem.enabled": False}
    fm.run(repo / "configs" / "thymio2.toml", small, out=out, threads=2)
    return out


def test_export_controller_target_thymio2_writes_the_clis_aseba_kit(thymio_run, tmp_path, cli):
    written = fm.export_controller(thymio_run, to="c", target="thymio2", out=tmp_path / "py")
    names = [p.rsplit("/", 1)[1] for p in written]
    assert names == ["fm_controller.aesl", "README.txt", "golden.csv"]
    run_cli(cli, "export", thymio_run, "--to", "c", "--target", "thymio2", "--out", tmp_path / "cli")
    for name in names:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
    # The Thymio II's 7 sensors are the network's inputs: golden.csv has readings r0..r6.
    header = (tmp_path / "py" / "golden.csv").read_text().splitlines()[0].split(",")
    assert [c for c in header if c[:1] == "r" and c[1:].isdigit()] == [f"r{k}" for k in range(7)]
    # "generic" (the default) is the plain C.
    plain = fm.export_controller(thymio_run, to="c", target="generic", out=tmp_path / "plain")
    assert [p.rsplit("/", 1)[1] for p in plain] == ["fm_controller.h", "fm_controller.c"]


def test_export_controller_names_a_wrong_target(thymio_run, tmp_path):
    with pytest.raises(fm.FuzzymotivError, match="target: `thymio` is not a deployment kit"):
        fm.export_controller(thymio_run, to="c", target="thymio", out=tmp_path / "a")  # type: ignore[arg-type]
    with pytest.raises(fm.FuzzymotivError, match="target epuck2: .*robot `thymio2`, not `epuck2`"):
        fm.export_controller(thymio_run, to="c", target="epuck2", out=tmp_path / "b")
    with pytest.raises(fm.FuzzymotivError, match="target thymio2: a deployment kit is C code"):
        fm.export_controller(thymio_run, to="json", target="thymio2", out="-")
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
