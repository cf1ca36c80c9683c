"""The README's public-API example runs and prints what it promises."""

import re

from conftest import ROOT


def test_readme_api_example_runs(capsys):
    text = (ROOT / "README.md").read_text()
    section = text.split("### Public API", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "balance time 6.179 s (censored: False)" in out
    assert "can balance: True" in out


def _layout_block(text):
    return re.search(r"## Layout\n\n```\n(.*?)```", text, re.S).group(1)


def test_readme_layout_names_every_package_and_module():
    """The layout section matches the tree: every package directory of src/rotorvib and every
    module in it is named there."""
    layout = _layout_block((ROOT / "README.md").read_text())
    src = ROOT / "src/rotorvib"
    for package in sorted(p for p in src.rglob("*") if (p / "__init__.py").is_file()):
        rel = package.relative_to(src).as_posix()
        if rel != ".":
            assert f"{rel}/" in layout, rel
        for module in package.glob("*.py"):
            if module.stem != "__init__":
                assert re.search(rf"\b{module.stem}\b", layout), module


def test_readme_follows_fig8_through_files_that_exist():
    text = (ROOT / "README.md").read_text()
    walk = text.split("**Following one figure**", 1)[1].split("\n\n", 2)[1]
    files = re.findall(r"^\d\. `([^`]+)`", walk, re.M)
    assert len(files) <= 6 and all((ROOT / f).is_file() for f in files), files


def test_readme_cites_the_papers_as_data_papers_yaml_does():
    """The README's papers section quotes data/papers.yaml, the report's source."""
    from rotorvib.pipeline.config import load_yaml

    text = " ".join((ROOT / "README.md").read_text().split())
    for paper in load_yaml(ROOT / "data/papers.yaml").values():
        assert " ".join(paper["citation"].split()) in text
        assert " ".join(paper["summary"].split()) in text


def test_readme_types_no_measured_time():
    """Timings are measured on the machine at hand by the benchmark scripts (benchmarks/), never
    typed into the README, where they would go stale with the next speed-up."""
    typed = re.findall(r"\d[\d.,]*\s?(?:CPU-s|CPU seconds|s of wall|(?:ms|s) (?:a|per) run"
                       r"|[x×] (?:faster|slower))", (ROOT / "README.md").read_text())
    assert typed == []
