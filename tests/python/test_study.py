"""Model.study and kinema.grid against per-design models (with_parameters, sweep), and the
Dask example (examples/dask_study.py) against Model.study on the whole.

Run by ctest with the module's other tests (KINEMA_SAMPLES, PYTHONPATH as there).
"""
import importlib.util
import math
import os
import pathlib

import numpy as np
import pytest

import kinema

SAMPLES = pathlib.Path(os.environ["KINEMA_SAMPLES"])
EXAMPLES = SAMPLES.parent / "examples"
SWEEP = ("40 deg", "400 deg", "1 deg")  # the file's 40 deg and a turn on


def grashof(a, b, c, d):
    """The textbook's class of a four-bar of crank a, coupler b, rocker c, ground d."""
    s, l = min(a, b, c, d), max(a, b, c, d)
    p_q = a + b + c + d - s - l
    if math.isclose(s + l, p_q, rel_tol=1e-9):
        return "change point"
    if s + l > p_q:
        return "non-Grashof triple rocker"
    return {d: "double-crank", a: "crank-rocker", c: "rocker-crank"}.get(s, "double-rocker")


def test_study_equals_per_design_with_parameters_sweeps():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    designs = kinema.grid(b=[0.110, 0.120, 0.130], c=[0.045, 0.080])  # c = 45 mm: not assembled over part of the turn
    table = model.study(designs, sweep=SWEEP)
    assert table.dtype.names[:2] == ("b", "c")
    assert len(table) == 6
    for i, row in enumerate(table):
        b, c = designs["b"][i], designs["c"][i]
        assert (row["b"], row["c"]) == (b, c)
        sweep = model.with_parameters(b=b, c=c).sweep(*SWEEP)
        ok, assembled = sweep["status"] == 0, sweep["status"] != 2
        assert kinema.GRASHOF_CLASSES[row["grashof"]] == grashof(0.040, b, c, 0.100)
        assert row["failed_values"] == np.sum(~assembled)
        assert row["assembles"] == bool(np.all(assembled))
        for field in ("omega3", "alpha3", "omega4", "alpha4"):
            assert row["max_abs_" + field] == pytest.approx(np.max(np.abs(sweep[field][ok])), rel=1e-12)
        for point in ("A", "B", "P"):  # the sweep in mm, the study in SI
            assert row[f"max_{point}_speed"] == pytest.approx(np.max(sweep[f"{point}_speed"][ok]) / 1000, rel=1e-12)
            assert row[f"max_{point}_acceleration"] == pytest.approx(
                np.max(sweep[f"{point}_acceleration"][ok]) / 1000, rel=1e-12)
        # The transmission angle of this loop (coupler +b, rocker -c) is |theta4 - theta3|, folded into [0, 180].
        mu = np.abs((sweep["theta4"][assembled] - sweep["theta3"][assembled] + 180) % 360 - 180)
        if row["grashof"] != 0:
            assert math.degrees(row["min_transmission_angle"]) == pytest.approx(np.min(mu), abs=1e-9)
    # The crank-rocker's time ratio from the rocker's limits: crank and coupler in line.
    a, b, c, d = 0.040, 0.120, 0.080, 0.100
    extended = math.acos(((a + b) ** 2 + d * d - c * c) / (2 * (a + b) * d))
    folded = math.acos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d)) + math.pi
    stroke = folded - extended
    ratio = max(stroke, 2 * math.pi - stroke) / min(stroke, 2 * math.pi - stroke)
    assert table[3]["time_ratio"] == pytest.approx(ratio, rel=1e-9)
    assert not table[0]["assembles"]  # (110 mm, 45 mm): the design meant to fail somewhere


def test_study_gives_the_figures_asked_for_and_names_what_it_refuses():
    model = kinema.load(str(SAMPLES / "slider_crank.toml"))
    table = model.study({"e": np.array([0.0, 0.01])}, sweep=("0 deg", "360 deg", "1 deg"),
                        figures=["time_ratio", "max_abs_x_dot"])
    assert table.dtype.names == ("e", "time_ratio", "max_abs_x_dot")
    assert table["time_ratio"][0] == pytest.approx(1.0, rel=1e-9)  # no offset: equal strokes
    assert table["time_ratio"][1] > 1
    with pytest.raises(kinema.InputError, match=r'no figure "omega9" \(there are: grashof, '):
        model.study({"e": [0.0]}, sweep=("0 deg", "360 deg", "1 deg"), figures=["omega9"])
    with pytest.raises(kinema.InputError, match=r'1 values of "e" but 2 of "a"'):
        model.study({"a": [0.05, 0.06], "e": [0.0]}, sweep=("0 deg", "360 deg", "1 deg"))
    with pytest.raises(kinema.InputError, match=r'no parameter named "f" \(there are: a, b, e\)'):
        model.study({"f": [0.0]}, sweep=("0 deg", "360 deg", "1 deg"))


def test_grid_is_every_combination_the_first_name_slowest():
    grid = kinema.grid(b=[1, 2], c=[10, 20, 30])
    assert list(grid) == ["b", "c"]
    assert grid["b"].tolist() == [1, 1, 1, 2, 2, 2]
    assert grid["c"].tolist() == [10, 20, 30, 10, 20, 30]


def test_dask_example_equals_one_study_on_the_whole():
    spec = importlib.util.spec_from_file_location("dask_study", EXAMPLES / "dask_study.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    from dask.distributed import Client, LocalCluster

    text = (SAMPLES / "four_bar.toml").read_text()
    designs = example.random_designs(2000)
    sweep = ("0 deg", "360 deg", "1 deg")
    # Workers in threads of this process: the same scheduler and chunks as processes, started in
    # a fraction of the time (kinema releases the GIL).
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        rows = example.distributed_study(client, text, "four_bar.toml", designs, sweep, chunks=5)
    whole = kinema.loads(text, "four_bar.toml").study(designs, sweep=sweep)
    assert rows.dtype == whole.dtype
    assert len(rows) == 2000
    for field in whole.dtype.names:
        np.testing.assert_array_equal(rows[field], whole[field])


def test_python_threads_may_call_kinema_at_once():
    """GiNaC (the symbolic layer) is not thread-safe: calls from several Python threads at
    once (reading, deriving, studying, sensitivities; kinema lets go of the GIL while it
    solves) must take turns in the symbolic parts and give each thread its own numbers."""
    import threading

    text = (SAMPLES / "four_bar.toml").read_text()
    designs = {"b": np.linspace(0.11, 0.13, 40), "c": np.linspace(0.07, 0.09, 40)}
    sweep = ("0 deg", "360 deg", "5 deg")
    whole = kinema.loads(text, "four_bar.toml").study(designs, sweep=sweep, threads=1)
    failures = []

    def work():
        try:
            for _ in range(6):
                model = kinema.loads(text, "four_bar.toml")
                rows = model.study(designs, sweep=sweep, threads=1)
                for field in whole.dtype.names:
                    np.testing.assert_array_equal(rows[field], whole[field])
                model.derive()
                model.sensitivity("omega3", "b", "0 deg", "360 deg", "30 deg")
                del model
        except Exception as error:  # noqa: BLE001 - reported below with the thread's failure
            failures.append(repr(error))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert failures == []
