"""The documentation (docs/, Sphinx with MyST): it builds with warnings as errors, every Python
example in it runs, and what it says of the code is what the code is."""

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT
from rotorvib.pipeline.config import load_yaml
from rotorvib.pipeline.fingerprint import import_closure

DOCS = ROOT / "docs"


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> tuple[Path, subprocess.CompletedProcess]:
    """The site built once for this file's tests, with warnings as errors (``--keep-going``:
    a warning fails the build test, and the site is still written for the others)."""
    out = tmp_path_factory.mktemp("docs")
    build = subprocess.run([str(Path(sys.executable).parent / "sphinx-build"), "-W",
                            "--keep-going", "-q", "-b", "html", str(DOCS), str(out)],
                           capture_output=True, text=True, timeout=600)
    return out, build


@pytest.fixture(scope="module")
def site(built) -> Path:
    return built[0]


def test_the_documentation_builds_with_warnings_as_errors(built):
    """A broken cross-reference, an unknown page in a toctree or a docstring that is not valid
    reStructuredText is an error."""
    site, build = built
    assert build.returncode == 0, build.stdout + build.stderr
    assert "paper_c.rotor.M" in (site / "configuration.html").read_text()
    simulate = site / "api/rotorvib.models.balancer.simulate.html"   # a page per module
    assert "rotorvib.models.balancer.simulate.run_batch" in simulate.read_text()
    assert 'href="api/rotorvib.models.balancer.simulate.html"' in (site / "api.html").read_text()


def _python_blocks():
    return [(page.name, block) for page in sorted(DOCS.glob("*.md"))
            for block in re.findall(r"```python\n(.*?)```", page.read_text(), re.S)]


@pytest.mark.workflow
@pytest.mark.parametrize("page, code", _python_blocks(), ids=lambda v: str(v)[:30])
def test_every_python_example_runs(page, code, run_dir, monkeypatch, capsys):
    """Each example of the docs, run in a finished reduced run (where its results exist)."""
    monkeypatch.chdir(run_dir)
    exec(compile(code, page, "exec"), {})
    if "balance time" in code:      # the API example prints what the text promises
        out = capsys.readouterr().out
        assert "balance time 6.179 s (censored: False)" in out and "can balance: True" in out


def _layout_block():
    return re.search(r"## Layout\n\n```\n(.*?)```", (DOCS / "architecture.md").read_text(),
                     re.S).group(1)


def test_the_layout_names_every_package_and_module():
    """The architecture page's layout matches the tree: every package directory of
    src/rotorvib and every module in it is named there."""
    layout = _layout_block()
    src = ROOT / "src/rotorvib"
    for package in sorted(p for p in src.rglob("*") if (p / "__init__.py").is_file()):
        rel = package.relative_to(src).as_posix()
        if rel != ".":
            assert f"{rel}/" in layout, rel
        for module in package.glob("*.py"):
            if module.stem != "__init__":
                assert re.search(rf"\b{module.stem}\b", layout), module


def test_following_fig8_names_the_files_and_modules_a_reader_crosses():
    """The user guide's walk through paper B's Fig 8: its seven files exist, and the modules it
    says the two jobs load are their scripts' import closure (what the code fingerprints
    follow)."""
    text = (DOCS / "user-guide.md").read_text()
    walk = text.split("**Following one figure**", 1)[1].split("\nA balance-time study", 1)[0]
    files = re.findall(r"^\d\. `([^`]+)`", walk, re.M)
    assert len(files) == 7 and all((ROOT / f).is_file() for f in files), files
    assert "seven files" in walk

    def listed(label):
        line = re.search(rf"^- {label}: (.*)$", walk, re.M).group(1)
        return re.findall(r"`([^`]+)`", line)

    def loaded(*entries):
        return [m for m in import_closure(*entries, root=ROOT / "src")
                if m.startswith("rotorvib.") and m.count(".") >= 2]

    assert listed("the study") == loaded(str(ROOT / "workflow/scripts/b_balance_study.py"))
    assert listed("the figure") == loaded(str(ROOT / "workflow/scripts/figures.py"),
                                          "rotorvib.papers.b.figures")
    assert '"fig8": figure("balance_against",\n   {"study": "balance_beta"}' in walk
    from rotorvib.papers.b.outputs import figures
    fig8 = figures(load_yaml(ROOT / "config/config.yaml")["paper_b"])["fig8"]
    assert (fig8["function"], fig8["datasets"]) == ("balance_against", {"study": "balance_beta"})


def test_every_page_fits_the_window_and_every_link_leads_somewhere(site, browser):
    """Each page of the built site, opened at 1280 px: nothing wider than the window (the
    configuration reference is a wide table), and every link inside the site reaches a page
    that exists (links are checked offline)."""
    pages = sorted(p for p in site.glob("*.html") if p.name not in ("genindex.html",
                                                                    "search.html"))
    assert len(pages) >= 8
    view = browser.new_page(viewport={"width": 1280, "height": 900})
    for page in pages:
        view.goto(page.as_uri())
        assert view.evaluate("document.documentElement.scrollWidth") <= 1280, page.name
        links = view.eval_on_selector_all("a[href]", "links => links.map(a => a.href)")
        local = [href.split("#")[0] for href in links if href.startswith("file://")]
        missing = [href for href in local if not Path(href.removeprefix("file://")).exists()]
        assert not missing, (page.name, missing)
    view.close()


def test_every_public_module_function_and_class_has_a_docstring():
    """The API reference is generated from every module of the package: each module, and
    each public function and class it defines, says what it is (the page would otherwise list
    a bare signature)."""
    import importlib
    import inspect
    import pkgutil

    import rotorvib

    bare = []
    for info in pkgutil.walk_packages(rotorvib.__path__, "rotorvib."):
        module = importlib.import_module(info.name)
        if not (module.__doc__ or "").strip():
            bare.append(info.name)
        bare += [f"{info.name}.{name}" for name, obj in vars(module).items()
                 if not name.startswith("_") and getattr(obj, "__module__", None) == info.name
                 and (inspect.isfunction(obj) or inspect.isclass(obj))
                 and not (obj.__doc__ or "").strip()]
    assert not bare, bare


def test_the_outputs_table_names_every_result_and_the_rules_that_make_it(run_dir):
    """The user guide's table of where each paper item lands, written as the docs build writes
    it (docs/conf.py) but for a reduced run (same outputs as the paper configuration): every
    dataset and figure the run made is in it, every file it names exists, each row names the
    rules that made its files (by the run's own job records) and every declared figure and
    table has a row."""
    from importlib import import_module

    from rotorvib.papers.outputs import PROJECT_TABLES
    from rotorvib.pipeline.config import merge
    from rotorvib.pipeline.outputs_table import outputs_rows, outputs_table, producers
    from workflow_runs import REDUCED, job_records, snakemake

    plan = producers(snakemake(run_dir, "--summary", *REDUCED).stdout)
    config = merge(load_yaml(ROOT / "config/config.yaml"),
                   load_yaml(ROOT / "config/test/config.yaml"))
    papers = {k.removeprefix("paper_"): v for k, v in config.items() if k.startswith("paper_")}
    outputs = {p: import_module(f"rotorvib.papers.{p}.outputs") for p in papers}
    figures = {p: m.figures(papers[p]) for p, m in outputs.items()}
    tables = {**{p: m.tables(papers[p]) for p, m in outputs.items()}, "all": PROJECT_TABLES}
    rows = outputs_rows(plan, figures, tables)
    made_by = {f: r["rule"] for r in job_records(run_dir) for f in r["output"]}
    named = set()
    for _, _, rules, paths in rows:
        assert set(rules) == {made_by[f] for f in paths}, rules
        named |= set(paths)
    written = outputs_table(rows)
    assert written.count("\n* - ") == len(rows) + 1 and "`paper_c/figures/fig5.png`" in written
    made = {p.relative_to(run_dir).as_posix()
            for kind in ("datasets", "figures") for ext in ("nc", "png")
            for p in (run_dir / "results").glob(f"paper_*/{kind}/*.{ext}")}
    assert made - named == set(), "results the table does not name"
    assert {p for p in named if not (run_dir / p).exists()} == set()
    declared = sum(map(len, figures.values())) + sum(map(len, tables.values()))
    assert len(rows) >= declared


def test_the_tutorials_commands_are_accepted():
    """Every ``snakemake`` command of the tutorial, as a dry run: the reduced run and the one
    with a parameter changed are accepted, the refused value stops before any job naming its key
    (the report's command needs a finished run and is left to the delivery tests)."""
    text = (DOCS / "tutorial.md").read_text()
    commands = [line.strip() for block in re.findall(r"```bash\n(.*?)```", text, re.S)
                for line in block.splitlines() if line.strip().startswith("snakemake")]
    commands.append("snakemake -j1 --configfile config/config.yaml config/test/config.yaml "
                    + re.search(r"`(--config paper_c='\{rotor: \{M: -5\}\}')`", text).group(1))
    assert len(commands) == 4
    for command in commands:
        if "--report" in command:
            continue
        args = shlex.split(command)[1:]
        run = subprocess.run([str(Path(sys.executable).parent / "snakemake"), "-n", *args],
                             cwd=ROOT, capture_output=True, text=True)
        if "M: -5" in command:
            assert run.returncode != 0 and "config key 'paper_c.rotor.M'" in run.stdout, command
        else:
            planned = "Job stats" in run.stdout or "Nothing to be done" in run.stdout
            assert run.returncode == 0 and planned, run.stdout + run.stderr
