"""The archive's RO-Crate (rotorvib.pipeline.crate), checked by rocrate-validator."""

import hashlib
import json

import numpy as np
import xarray as xr

from ro_crate import each_query_parsed_once, validate_crate
from rotorvib.pipeline.crate import crate_metadata, describe

FILES = {"Snakefile": "rule all:\n", "LICENSE": "MIT\n", "CITATION.cff": "cff-version: 1.2.0\n",
         "config/config.yaml": "a: 1\n", "results/run/commit.txt": "commit x\n",
         "results/paper_b/figures/fig8.png": "png", "results/paper_c/tables/table2.csv": "a\n",
         "results/comparison.csv": "paper\n"}


def _tree(root):
    for name, text in FILES.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    (root / "results/paper_c/datasets").mkdir(parents=True)
    xr.Dataset({"D": ("w", np.ones(2))}, attrs={"title": "Paper C: frequency response"}
               ).to_netcdf(root / "results/paper_c/datasets/frequency_response.nc")


def _crate(root):
    return crate_metadata(
        results=["results/paper_b/figures/fig8.png", "results/paper_c/tables/table2.csv",
                 "results/comparison.csv", "results/paper_c/datasets/frequency_response.nc"],
        configuration=["config/config.yaml", "results/run/commit.txt"],
        code=["Snakefile", "LICENSE", "CITATION.cff"], title="t", description="d",
        date="2026-01-01T00:00:00+00:00", snakemake_version="9.27.1")


def test_every_file_is_described_from_its_path_or_its_dataset_title(tmp_path, monkeypatch):
    _tree(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert describe("results/paper_b/figures/fig4_5.png") == "Paper B, Figs 4-5"
    assert describe("results/paper_c/tables/table2.csv") == "Paper C, Table 2 (csv)"
    assert describe("results/paper_c/datasets/frequency_response.nc") == \
        "Dataset: Paper C: frequency response"
    assert describe("results/unknown.bin") == "unknown.bin"


def test_the_crate_passes_the_ro_crate_validator(tmp_path, monkeypatch):
    """Every REQUIRED and RECOMMENDED check of RO-Crate 1.3 passes but one: no publisher (the
    project has no organisation identifier to name)."""
    _tree(tmp_path)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ro-crate-metadata.json").write_text(_crate(tmp_path))
    issues = validate_crate(tmp_path, tmp_path / "cache")
    assert [(s, m) for s, m, _ in issues] == [
        ("RECOMMENDED", "The Root Data Entity SHOULD have a `publisher` property "
                        "(Organization or Person)")]


def test_the_crate_describes_the_run_and_each_file(tmp_path, monkeypatch):
    _tree(tmp_path)
    monkeypatch.chdir(tmp_path)
    graph = {e["@id"]: e for e in json.loads(_crate(tmp_path))["@graph"]}
    assert graph["./"]["mainEntity"] == {"@id": "Snakefile"}
    assert "ComputationalWorkflow" in graph["Snakefile"]["@type"]
    run = graph["#run"]
    assert run["instrument"] == {"@id": "Snakefile"}
    assert {o["@id"] for o in run["object"]} == {"config/config.yaml", "results/run/commit.txt"}
    assert len(run["result"]) == 4
    fig = graph["results/paper_b/figures/fig8.png"]
    assert fig["sha256"] == hashlib.sha256(b"png").hexdigest()
    assert fig["contentSize"] == "3" and fig["encodingFormat"] == "image/png"
    assert "license" not in fig  # the data inherit the crate's CC-BY-4.0
    assert graph["LICENSE"]["license"] == {"@id": "https://spdx.org/licenses/MIT"}
    assert graph["./"]["license"] == {"@id": "https://spdx.org/licenses/CC-BY-4.0"}


def test_a_query_prepared_once_answers_as_its_text_at_every_binding():
    """The validator's shortcut (tests/ro_crate.py): a SPARQL constraint of pyshacl's shape,
    ``$this`` bound to each focus node in turn, gives the same rows prepared once as parsed
    at every call, and is prepared once."""
    from rdflib import Graph, Literal, Namespace

    ex = Namespace("http://example.org/")
    graph = Graph()
    for i in range(6):
        graph.add((ex[f"file{i}"], ex.size, Literal(i)))
        if i % 2:
            graph.add((ex[f"file{i}"], ex.name, Literal(f"f{i}")))
    text = ("SELECT $this ?value WHERE { $this <http://example.org/size> ?value . "
            "FILTER NOT EXISTS { $this <http://example.org/name> ?name } }")

    def rows():
        return [sorted(map(tuple, graph.query(text, initBindings={"this": ex[f"file{i}"]})))
                for i in range(6)]

    parsed_each_time = rows()
    with each_query_parsed_once() as prepared:
        assert rows() == parsed_each_time
        assert len(prepared) == 1
    assert [len(r) for r in parsed_each_time] == [1, 0, 1, 0, 1, 0]
