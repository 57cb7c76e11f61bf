"""The Python module against the program: the same numbers, names, formulas and errors.

Run by ctest ("python: ..."), which sets KINEMA_PROGRAM (the kinema program), KINEMA_SAMPLES
(samples/) and PYTHONPATH (the built module).
"""
import doctest
import html
import json
import math
import os
import pathlib
import subprocess
import tomllib

import numpy as np
import pytest

import kinema

PROGRAM = os.environ["KINEMA_PROGRAM"]
SAMPLES = pathlib.Path(os.environ["KINEMA_SAMPLES"])
ALL_SAMPLES = sorted(SAMPLES.glob("*.toml"))
# A run of each kind of input: numbers in the input's output unit, as --sweep takes them.
RUNS = {"deg": (0, 360, 15), "s": (0, 2, 0.25), "mm": (110, 190, 10), "in": (1, 9, 1), "m": (0.11, 0.19, 0.01)}
LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254, "ft": 0.3048}


def program(*arguments):
    return subprocess.run([PROGRAM, *arguments], check=True, capture_output=True).stdout


def run_of(model):
    return RUNS[model.units[model.input]]


@pytest.mark.parametrize("sample", ALL_SAMPLES, ids=lambda path: path.stem)
def test_sweep_equals_the_programs_npy_field_by_field(sample, tmp_path):
    model = kinema.load(str(sample))
    unit = model.units[model.input]
    first, last, step = run_of(model)
    table = model.sweep(f"{first} {unit}", f"{last} {unit}", f"{step} {unit}")
    program("eval", str(sample), "--sweep", f"{first}:{last}:{step}", "--format", "npy", "-o", str(tmp_path / "run.npy"))
    expected = np.load(tmp_path / "run.npy")
    assert table.dtype == expected.dtype
    assert len(table) == len(expected) > 1
    assert (table["status"] == 0).any(), "the run should assemble somewhere"
    for field in expected.dtype.names:
        assert np.array_equal(table[field], expected[field], equal_nan=True), field


def test_sweep_in_si_numbers_gives_the_same_rows_within_rounding():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    in_degrees = model.sweep("0 deg", "90 deg", "10 deg")
    in_radians = model.sweep(0.0, math.pi / 2, math.pi / 18)
    assert len(in_radians) == len(in_degrees) == 10
    assert np.allclose(in_radians["omega3"], in_degrees["omega3"], rtol=1e-12, atol=0)


def test_named_access_equals_the_programs_row():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    result = model.at("30 deg")
    assert result.ok and result.status == "ok" and result.message == ""
    row = model.sweep("30 deg", "30 deg", "1 deg")[0]
    length = LENGTH_UNITS[model.units["P_x"]]
    assert result["theta2"] == pytest.approx(math.radians(30), rel=1e-15)
    assert result["theta3"] == pytest.approx(math.radians(row["theta3"]), rel=1e-12)
    assert result["omega3"] == pytest.approx(row["omega3"], rel=1e-12)
    assert result["alpha4"] == pytest.approx(row["alpha4"], rel=1e-12)
    p = result.point("P")
    assert p.velocity == pytest.approx((row["P_vx"] * length, row["P_vy"] * length), rel=1e-12)
    assert p.acceleration == pytest.approx((row["P_ax"] * length, row["P_ay"] * length), rel=1e-12)
    assert set(result.keys()) >= {"theta2", "omega2", "alpha2", "theta3", "omega3", "alpha3"}
    assert "omega3" in result._repr_html_()
    # A list is solved as `kinema eval` solves one, each value from the one before.
    listed = model.at(["30 deg", math.radians(40)])
    assert [r.input for r in listed] == pytest.approx([math.radians(30), math.radians(40)], rel=1e-15)


def test_a_spatial_chain_reads_its_points_in_three_dimensions():
    model = kinema.load(str(SAMPLES / "robot_arm_seed000.toml"))
    result = model.at(0.0)
    point = result.point(model.points[-1])
    assert len(point.position) == len(point.velocity) == len(point.acceleration) == 3


CHAINS = [path for path in ALL_SAMPLES if "frames" in tomllib.loads(path.read_text())]


@pytest.mark.parametrize("sample", CHAINS, ids=lambda path: path.stem)
def test_a_spatial_chain_reads_each_frames_angular_motion_as_the_program_prints_it(sample):
    # Issue 45: a Result gave points only; a chain's frames were in sweep columns alone.
    model = kinema.load(str(sample))
    first, last, step = run_of(model)
    values = [first + k * step for k in range(4)]  # in the input's output unit, as --at takes them
    at = [argument for v in values for argument in ("--at", str(v))]
    printed = json.loads(program("eval", str(sample), *at, "--format", "json"))
    assert model.frames == printed["frames"] and len(model.frames) > 0
    unit = model.units[model.input]
    results = model.at([f"{v} {unit}" for v in values])
    for result, row in zip(results, printed["results"]):
        assert result.ok and row["status"] == "ok"
        for name in model.frames:
            frame = result.frame(name)
            assert frame.angular_velocity == pytest.approx(row["frames"][name]["angular_velocity"], rel=1e-12, abs=1e-14)
            assert frame.angular_acceleration == pytest.approx(row["frames"][name]["angular_acceleration"], rel=1e-12, abs=1e-14)
            assert repr(frame).startswith("Frame(angular_velocity=(")
    with pytest.raises(kinema.Error, match=r'no frame named "E9" \(there are: ' + ", ".join(model.frames) + r"\)"):
        results[0].frame("E9")


def test_a_planar_mechanism_has_no_frames():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    assert model.frames == []
    with pytest.raises(kinema.Error, match=r'no frame named "E1" \(there are: none\)'):
        model.at("30 deg").frame("E1")


@pytest.mark.parametrize("sample", ["four_bar.toml", "piston_driven_crank.toml", "robot_arm_seed000.toml",
                                    "problem_4_4_joints.toml"])
def test_a_results_repr_shows_the_input_as_kinema_eval_heads_its_block(sample):
    # Issue 45: repr gave the input in SI (theta2 = 0.5235987755982988) where everything else
    # shown is in the file's units; now as `kinema eval --at` prints it ("theta2 = 37.5 deg").
    model = kinema.load(str(SAMPLES / sample))
    first, last, step = run_of(model)
    value = first + 2.5 * step  # not a round number of SI units
    unit = model.units[model.input]
    printed = program("eval", str(SAMPLES / sample), "--at", str(value)).decode()
    head = next(line for line in printed.splitlines() if line.startswith(model.input + " = "))
    shown = repr(model.at(f"{value} {unit}"))
    assert shown.startswith("<kinema.Result " + head.split("   ")[0] + ": ")
    assert head.split("   ")[0].endswith(" " + unit)


def test_parameters_are_the_files_in_si():
    sample = SAMPLES / "four_bar.toml"
    model = kinema.load(str(sample))
    written = tomllib.loads(sample.read_text())["parameters"]
    assert [p["name"] for p in model.parameters] == list(written)
    for p in model.parameters:
        assert p["text"] == written[p["name"]]
        if p["text"].endswith(" mm"):
            assert p["value"] == pytest.approx(float(p["text"][:-3]) * 1e-3, rel=1e-15)
            assert p["dimension"] == "length"


@pytest.mark.parametrize("method", ["loops", "relative-velocity", "joint-coordinates"])
@pytest.mark.parametrize("form", ["text", "latex"])
def test_derive_prints_what_the_program_prints(method, form):
    sample = SAMPLES / "example_4_1_joints.toml"
    model = kinema.load(str(sample))
    printed = program("derive", str(sample), "--method", method, "--format", form).decode()
    assert model.derive(method=method, format=form) == printed


def test_errors_are_kinema_errors_with_file_and_line():
    with pytest.raises(kinema.InputError) as missing:
        kinema.load("no_such_file.toml")
    assert "no_such_file.toml" in str(missing.value)
    assert issubclass(kinema.InputError, kinema.Error) and issubclass(kinema.UnitError, kinema.InputError)
    text = '[parameters]\na = "10 mm"\nb = "20 parsecs"\n'
    with pytest.raises(kinema.Error) as bad:
        kinema.loads(text, "bad.toml")
    assert "bad.toml:3" in str(bad.value)
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    with pytest.raises(kinema.UnitError) as unit:
        model.at("30 mm")
    assert "theta2" in str(unit.value)
    with pytest.raises(KeyError):
        model.at("30 deg")["omega9"]
    with pytest.raises(kinema.Error):
        model.derive(method="no-such-method")


def test_a_singular_value_says_why_and_gives_no_rates():
    model = kinema.load(str(SAMPLES / "piston_driven_crank.toml"))
    result = model.at("200 mm")  # top dead centre: Phi_q singular
    assert result.status == "singular" and not result.ok
    assert "singular" in result.message or "dead" in result.message
    with pytest.raises(kinema.Error):
        result["omega2"]


def test_page_is_the_programs_and_shows_inline_in_a_frame(tmp_path):
    sample = SAMPLES / "problem_4_4_joints.toml"
    model = kinema.load(str(sample))
    page = model.page()
    program("page", str(sample), "-o", str(tmp_path / "page.html"))
    assert page == (tmp_path / "page.html").read_text()
    assert page.startswith("<!DOCTYPE html>") and "Content-Security-Policy" in page
    inline = model._repr_html_()
    assert inline.startswith("<iframe") and inline.endswith("</iframe>")
    framed = inline[inline.index('srcdoc="') + len('srcdoc="'):-len('"></iframe>')]
    assert "<" not in framed and '"' not in framed  # the whole page as the attribute's text
    assert html.unescape(framed) == page


def test_circuit_equals_the_programs_npy_field_by_field(tmp_path):
    sample = SAMPLES / "triple_rocker_circuit.toml"
    table = kinema.load(str(sample)).circuit("1 deg")
    program("eval", str(sample), "--circuit", "1", "--format", "npy", "-o", str(tmp_path / "circuit.npy"))
    expected = np.load(tmp_path / "circuit.npy")
    assert table.dtype == expected.dtype
    assert len(table) == len(expected) > 360  # through the toggles and back
    for field in expected.dtype.names:
        assert np.array_equal(table[field], expected[field], equal_nan=True), field


def test_circuit_errors_say_why_in_the_modules_words():
    with pytest.raises(kinema.InputError, match="four_bar.toml: circuit step follows a mechanism described by joints"):
        kinema.load(str(SAMPLES / "four_bar.toml")).circuit("1 deg")
    with pytest.raises(kinema.InputError, match=r'the step must be a positive number, e.g. circuit\("1 deg"\)'):
        kinema.load(str(SAMPLES / "triple_rocker_circuit.toml")).circuit("-1 deg")


def test_a_model_shows_its_derivation_in_a_notebook_as_the_programs_latex():
    sample = SAMPLES / "four_bar.toml"
    shown = kinema.load(str(sample))._repr_latex_()
    latex = program("derive", str(sample), "--format", "latex").decode()
    blocks = shown.split("$$")[1::2]
    assert len(blocks) == latex.count("\\begin{align*}") >= 1
    for block in blocks:
        assert block.startswith("\\begin{align*}") and block.endswith("\\end{align*}")
        assert "%" not in block  # MathJax reads no comments
        for line in block.splitlines()[1:-1]:  # every row as the program prints it, its comment gone
            assert any(line.strip() and printed.split(" % ")[0].rstrip() == line.rstrip() for printed in latex.splitlines()), line


def test_to_dataframe_has_a_column_a_field():
    table = kinema.load(str(SAMPLES / "four_bar.toml")).sweep("0 deg", "90 deg", "10 deg")
    frame = kinema.to_dataframe(table)
    assert list(frame.columns) == list(table.dtype.names)
    assert len(frame) == len(table)
    assert np.array_equal(frame["omega3"].to_numpy(), table["omega3"], equal_nan=True)


def sweep_fields_close(a, b):
    """Every numeric field of two sweeps within 1e-12 of the field's largest magnitude."""
    assert a.dtype == b.dtype and len(a) == len(b) > 1
    assert np.array_equal(a["status"], b["status"]) and (a["status"] == 0).all()
    for field in a.dtype.names:
        if a[field].dtype.kind != "f":
            continue
        scale = max(np.abs(a[field]).max(), np.abs(b[field]).max())
        assert np.abs(a[field] - b[field]).max() <= 1e-12 * scale, field


@pytest.mark.parametrize(
    "sample, edits, values",
    [
        (
            "four_bar.toml",
            {'b = "120 mm"': 'b = "123 mm"', 'delta = "30 deg"': 'delta = "25 deg"'},
            {"b": "123 mm", "delta": 25 * math.pi / 180},
        ),
        # EF = "CE" follows CE in the copy as in the edited file (within the sketch's 1 %).
        ("problem_4_4_joints.toml", {'CE = "0.230 m"': 'CE = "0.231 m"'}, {"CE": 0.231}),
    ],
    ids=["four_bar", "problem_4_4_joints"],
)
def test_with_parameters_equals_the_edited_file(sample, edits, values):
    text = (SAMPLES / sample).read_text()
    for before, after in edits.items():
        assert before in text
        text = text.replace(before, after, 1)
    model = kinema.load(str(SAMPLES / sample))
    copy = model.with_parameters(**values)
    edited = kinema.loads(text, sample)
    sweep_fields_close(copy.sweep("0 deg", "360 deg", "5 deg"), edited.sweep("0 deg", "360 deg", "5 deg"))
    assert [p["value"] for p in copy.parameters] == pytest.approx([p["value"] for p in edited.parameters], rel=1e-15)
    # The original is untouched.
    assert model.parameters[1]["value"] == kinema.load(str(SAMPLES / sample)).parameters[1]["value"]


def test_with_parameters_errors_name_the_parameter():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    with pytest.raises(kinema.InputError, match='no parameter named "bb"'):
        model.with_parameters(bb="1 m")
    with pytest.raises(kinema.UnitError, match='parameter "b" is a length'):
        model.with_parameters(b="30 deg")


@pytest.mark.parametrize("value", [None, True, [0.1], {"value": 0.1}], ids=["None", "bool", "list", "dict"])
def test_with_parameters_refuses_a_value_that_is_neither_text_nor_a_number_naming_the_parameter(value):
    # Issue 45: with_parameters(delta=None) raised RuntimeError "Unable to cast ..." naming
    # neither the parameter nor what it takes. Since issue 49 kinema.InputTypeError, still a
    # TypeError (test_bounds.py).
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    with pytest.raises(TypeError) as refused:
        model.with_parameters(delta=value)
    message = str(refused.value)
    assert "delta" in message and type(value).__name__ in message
    assert "quantity with units" in message and "number in SI" in message
    # Numbers of NumPy's and Python's own kinds are numbers in SI.
    for number in (np.float64(0.5), np.int64(1), 1):
        assert model.with_parameters(delta=number).parameters[5]["value"] == pytest.approx(float(number), rel=1e-15)


@pytest.mark.parametrize(
    "sample, column, parameter, unit",
    [
        ("four_bar.toml", "omega3", "b", 1.0),  # rad/s in the sweep as in SI
        ("four_bar.toml", "P_ay", "delta", 1e-3),  # mm/s^2 in the sweep: m/s^2 is 1e-3 of the number
        ("problem_4_4_joints.toml", "vF", "CE", 1.0),  # EF = "CE" follows CE
        ("robot_arm_seed000.toml", "B_vz", "alpha", 1.0),
    ],
    ids=["four_bar_omega3_b", "four_bar_P_ay_delta", "problem_4_4_joints_vF_CE", "robot_arm_B_vz_alpha"],
)
def test_sensitivity_equals_finite_differences_of_with_parameters(sample, column, parameter, unit):
    model = kinema.load(str(SAMPLES / sample))
    first, last, step = (0.0, 1.0, 0.25) if model.units[model.input] == "s" else (0.0, 330 * math.pi / 180, math.pi / 6)
    exact = model.sensitivity(column, parameter, first, last, step)
    value = next(p["value"] for p in model.parameters if p["name"] == parameter)
    h = 1e-5 * max(abs(value), 0.1)  # central differences: truncation ~1e-10, the solves' rounding ~1e-9
    above = model.with_parameters(**{parameter: value + h}).sweep(first, last, step)
    below = model.with_parameters(**{parameter: value - h}).sweep(first, last, step)
    assert (above["status"] == 0).all() and (below["status"] == 0).all()
    differences = (above[column] - below[column]) * unit / (2 * h)
    assert exact.shape == differences.shape and len(exact) > 3
    assert np.abs(exact - differences).max() <= 1e-6 * np.abs(exact).max()
    # The same with the sweep written with units.
    unit_name = model.units[model.input]
    written = (f"{first} s", f"{last} s", f"{step} s") if unit_name == "s" else ("0 deg", "330 deg", "30 deg")
    assert np.allclose(model.sensitivity(column, parameter, *written), exact, rtol=1e-12, atol=0)


def test_sensitivity_errors_name_the_parameter_and_the_column():
    model = kinema.load(str(SAMPLES / "four_bar.toml"))
    with pytest.raises(kinema.InputError, match=r'no parameter named "bb" \(there are: a, b, c, d, p, delta\)'):
        model.sensitivity("omega3", "bb", "0 deg", "10 deg", "5 deg")
    with pytest.raises(kinema.InputError, match=r'no output column named "omega9" that has a derivative \(there are: theta3'):
        model.sensitivity("omega9", "b", "0 deg", "10 deg", "5 deg")


def test_the_readmes_python_prints_what_it_shows():
    # The README's snippet run as a doctest from the repository root, as a reader runs it.
    root = SAMPLES.parent
    block = (root / "README.md").read_text().split("```python\n")[1].split("```")[0]
    test = doctest.DocTestParser().get_doctest(block, {}, "README", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    here = os.getcwd()
    os.chdir(root)
    try:
        runner.run(test)
    finally:
        os.chdir(here)
    assert runner.tries >= 4 and runner.failures == 0
