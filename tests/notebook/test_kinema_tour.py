"""examples/kinema_tour.ipynb executed headless, its outputs against the program and the module.

Run by ctest ("notebook: ..."), which sets KINEMA_PROGRAM (the kinema program), KINEMA_SOURCE
(the repository) and PYTHONPATH (the built module; the kernel inherits it). The notebook runs
once, in its own directory as Jupyter runs it, in a kernel of the Python running this test.
"""
import base64
import html
import json
import os
import pathlib
import re
import subprocess
import sys

import nbclient
import nbformat
import pytest
from ipykernel.kernelspec import install as install_kernelspec

import kinema

PROGRAM = os.environ["KINEMA_PROGRAM"]
SOURCE = pathlib.Path(os.environ["KINEMA_SOURCE"])
NOTEBOOK = SOURCE / "examples" / "kinema_tour.ipynb"
SAMPLE = SOURCE / "samples" / "problem_4_4_six_bar.toml"
KERNEL = "kinema-tour"


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    # A kernelspec of our own, for this very interpreter, whatever kernels the machine has
    # (none, or a python3 of another Python without numpy); and the module's directory
    # first on the kernel's path, absolute (the kernel runs in examples/, and a module
    # installed in site-packages must not stand in for the build's).
    prefix = tmp_path_factory.mktemp("jupyter")
    install_kernelspec(kernel_name=KERNEL, prefix=str(prefix))
    os.environ["JUPYTER_PATH"] = str(prefix / "share" / "jupyter")
    os.environ["PYTHONPATH"] = os.pathsep.join([str(pathlib.Path(kinema.__file__).parent), os.environ.get("PYTHONPATH", "")])
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(notebook, kernel_name=KERNEL, timeout=60,
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    client.execute()
    return notebook


def outputs_of(notebook, tag):
    cells = [cell for cell in notebook.cells if tag in cell.metadata.get("tags", [])]
    assert len(cells) == 1, f"one cell tagged {tag}"
    return cells[0].outputs


def shown(notebook, tag, mime):
    """The one displayed value of the tagged cell in that MIME type."""
    values = [output.data[mime] for output in outputs_of(notebook, tag) if mime in output.get("data", {})]
    assert len(values) == 1, f"{tag} shows one {mime}"
    return values[0]


def printed(notebook, tag):
    return "".join(output.text for output in outputs_of(notebook, tag) if output.output_type == "stream")


def table_rows(table_html):
    """A DataFrame's HTML table: its column names, then each row's cells as text."""
    rows = [re.findall(r"<t[hd][^>]*>(.*?)</t[hd]>", row, re.S) for row in re.findall(r"<tr[^>]*>(.*?)</tr>", table_html, re.S)]
    header, body = rows[0], rows[1:]
    return header[1:], [row[1:] for row in body]  # without the index column


def program_json(*arguments):
    return json.loads(subprocess.run([PROGRAM, *arguments, "--format", "json"], check=True, capture_output=True).stdout)


def test_the_committed_notebook_has_no_outputs():
    # Committed stripped: a run's outputs hold the page (about a megabyte) and a PNG whose
    # bytes follow matplotlib's version and fonts, so they could not be checked against a
    # fresh run; GitHub shows the code and the text, Jupyter the rest.
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(notebook)
    for cell in notebook.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, (
                "strip the outputs before committing: python3 -c \"import nbformat as n; p='examples/kinema_tour.ipynb'; "
                "b=n.read(p, 4); [c.update(outputs=[], execution_count=None) for c in b.cells if c.cell_type == 'code']; "
                "n.write(b, p)\"")


def test_no_cell_fails_or_warns(executed):
    for cell in executed.cells:
        for output in cell.get("outputs", []):
            assert output.output_type != "error"
            assert not (output.output_type == "stream" and output.name == "stderr"), output.text


def test_omega3_at_30_deg_is_the_programs(executed):
    value = re.search(r"omega3 at 30 deg: (\S+) rad/s", printed(executed, "one-position"))
    assert value, printed(executed, "one-position")
    row = program_json("eval", str(SAMPLE), "--at", "30")["results"][0]
    assert float(value.group(1)) == pytest.approx(row["coordinates"]["phi3"]["rate"], rel=1e-12)


def test_the_derivation_shows_in_latex(executed):
    latex = shown(executed, "derivation", "text/latex")
    assert latex == kinema.load(str(SAMPLE))._repr_latex_()
    assert latex.startswith("$$\\begin{align*}") and "\\phi_{3}" in latex


def test_the_result_and_the_sweep_show_as_tables(executed):
    result = shown(executed, "result-table", "text/html")
    assert "<table" in result and "omega3" in result and "yF" in result
    columns, rows = table_rows(shown(executed, "sweep", "text/html"))
    assert "omega3" in columns and len(rows) == 5  # head()'s five rows


def test_the_plot_is_a_png(executed):
    png = base64.b64decode(shown(executed, "plot", "image/png"))
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 10_000  # drawn, not an empty canvas


def test_the_design_study_row_of_the_files_ce_is_the_programs_sweep(executed):
    columns, rows = table_rows(shown(executed, "design-study", "text/html"))
    designs = [dict(zip(columns, row)) for row in rows]
    assert [float(d["CE"]) for d in designs] == pytest.approx([0.20, 0.21, 0.22, 0.23, 0.24, 0.25, 0.26])
    assert all(d["assembles"] == "True" for d in designs)
    speeds = [float(d["max_F_speed"]) for d in designs]
    assert len(set(speeds)) == len(speeds)  # each design its own CE
    # The file's own CE: the time ratio the program finds at the slider's limits, and the
    # largest |omega3| and slider speed of the program's own sweep at the study's step
    # (to the digits the table shows).
    files = designs[3]
    assert float(files["time_ratio"]) == pytest.approx(program_json("eval", str(SAMPLE), "--at", "30")["strokes"][0]["time_ratio"], rel=1e-5)
    rows = program_json("eval", str(SAMPLE), "--sweep", "0:360:0.1")["results"]
    omega3 = max(abs(r["coordinates"]["phi3"]["rate"]) for r in rows)
    speed_F = max(r["points"]["F"]["speed"] for r in rows)
    assert float(files["max_abs_omega3"]) == pytest.approx(omega3, rel=1e-5)
    assert float(files["max_F_speed"]) == pytest.approx(speed_F, rel=1e-5)


def test_the_page_shows_inline_with_the_mechanism(executed, monkeypatch):
    framed = re.fullmatch(r'<iframe [^>]*srcdoc="([^"]*)"></iframe>', shown(executed, "page", "text/html"))
    assert framed
    page = html.unescape(framed.group(1))
    # The page names its file as the notebook wrote it, from the notebook's directory.
    monkeypatch.chdir(NOTEBOOK.parent)
    same = page == kinema.load("../samples/problem_4_4_six_bar.toml").page()
    assert same, "the inline page is not the sample's page"  # (not a diff of a megabyte)
    assert "Problem 4.4: R-RRR-RRT six-bar" in page
