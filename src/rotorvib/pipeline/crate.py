"""The archive's RO-Crate: ``ro-crate-metadata.json`` describing the workflow, its run, the
configuration and every archived file (checksum, size, format, licence).

It is an RO-Crate 1.3 (the ``rocrate`` library's version) laid out as a Workflow Run Crate:
the Snakefile is the main entity (a ``ComputationalWorkflow`` in Snakemake), and a
``CreateAction`` records the run with the configuration as its object and the results as its
result. It claims no profile beyond RO-Crate 1.3: the Workflow Run Crate profiles (0.5) are
defined on RO-Crate 1.1. The metadata is written into the archive as text, so the archive root
is the crate root.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import netCDF4
from rocrate.rocrate import ROCrate

from rotorvib.pipeline.archive import sha256_file
from rotorvib.pipeline.report import label

FORMATS = {".nc": "application/x-netcdf", ".csv": "text/csv", ".md": "text/markdown",
           ".png": "image/png", ".html": "text/html", ".yaml": "application/yaml",
           ".cff": "application/yaml", ".txt": "text/plain", ".json": "application/json",
           ".rst": "text/x-rst", ".svg": "image/svg+xml",
           "": "text/plain"}  # "": LICENCE, Snakefile
DATA_LICENCE = "https://spdx.org/licenses/CC-BY-4.0"
CODE_LICENCE = "https://spdx.org/licenses/MIT"
LICENCES = {DATA_LICENCE: ("CC-BY-4.0", "Creative Commons Attribution 4.0: the data"),
            CODE_LICENCE: ("MIT", "MIT licence: the code")}
WORKFLOW_PROFILE = "https://bioschemas.org/profiles/ComputationalWorkflow/1.0-RELEASE"
#: Pages the rocrate library links from the Snakemake language entity, described here.
SNAKEMAKE_PAGES = {"https://doi.org/10.1093/bioinformatics/bts480": "Snakemake's paper (DOI)",
                   "https://snakemake.readthedocs.io": "Snakemake's documentation"}


#: Descriptions by path pattern, first match wins; {paper}, {name}, {ext} and {title} (a
#: dataset's own title attribute) are filled in.
DESCRIPTIONS = (
    (r"paper_(?P<paper>\w)/datasets/(?P<name>\w+)\.nc", "Dataset: {title}"),
    (r"paper_(?P<paper>\w)/figures/(?P<name>\w+)\.png", "Paper {paper}, {figure}"),
    (r"paper_(?P<paper>\w)/figures/(?P<name>\w+)\.svg",
     "Paper {paper}, {figure}: vector copy"),
    (r"paper_(?P<paper>\w)/figures/(?P<name>\w+)\.json",
     "Paper {paper}, {figure}: what it draws and the parameters it depends on (its caption)"),
    (r"paper_(?P<paper>\w)/tables/(?P<name>\w+)\.(?P<ext>\w+)",
     "Paper {paper}, {table} ({ext})"),
    (r"paper_(?P<paper>\w)/reproduced\.csv",
     "Paper {paper}: the reproduced value of every quantity the paper states"),
    (r"comparison\.\w+", "Every value the papers state beside the reproduced one, with "
     "the relative error, the verdict and the explanation"),
    (r"discrepancies\.\w+", "Each printed number the reproduction misses, tested "
     "against alternative readings of the paper"),
    (r"report/.+\.rst", "Words of the HTML report, written from the comparison"),
    (r"report/pages/.+\.html", "A page of the HTML report (its summary or a table), "
     "written from the comparison"),
    (r"report/shown/.+", "A file the HTML report shows (a copy)"),
    (r"run/config\.yaml", "The run's whole configuration (files and overrides merged)"),
    (r"run/commit\.txt", "The commit of the code that made the results"),
    (r"config/.+\.yaml", "A configuration file the run read"),
    (r"Snakefile", "The workflow: snakemake -j2 rebuilds every result"),
    (r"LICENSE", "The licences: MIT for the code, CC-BY-4.0 for the data"),
    (r"CITATION\.cff", "How to cite this reproduction and the papers it reproduces"),
)


def describe(path: str, results: str = "results") -> str:
    """A one-line description of an archived file, from :data:`DESCRIPTIONS` (whose patterns
    name outputs relative to the run's ``results`` folder)."""
    relative = path.removeprefix(f"{results}/")
    for pattern, text in DESCRIPTIONS:
        if match := re.fullmatch(pattern, relative):
            fields = match.groupdict()
            if "paper" in fields:
                fields["paper"] = fields["paper"].upper()
            if "name" in fields:
                fields["figure"] = label(fields["name"])
                fields["table"] = label(fields["name"], "table")
            if path.endswith(".nc"):
                with netCDF4.Dataset(path) as ds:
                    fields["title"] = getattr(ds, "title", fields["name"])
            return text.format(**fields)
    return Path(path).name


def file_properties(path: str | Path, description: str, licence: str | None = None) -> dict:
    """Name, description, format, size and SHA-256 of one archived file, and its licence
    where it differs from the crate's (the code's)."""
    path = Path(path)
    properties = {"name": path.name, "description": description,
                  "encodingFormat": FORMATS.get(path.suffix, "application/octet-stream"),
                  "contentSize": str(path.stat().st_size), "sha256": sha256_file(path)}
    if licence:
        properties["license"] = {"@id": licence}
    return properties


def crate_metadata(*, results: list[str], configuration: list[str], code: list[str],
                   title: str, description: str, date: str, snakemake_version: str,
                   results_dir: str = "results") -> str:
    """``ro-crate-metadata.json`` for an archive whose root is the repository root.

    ``results``: the run's outputs (data licence), under ``results_dir``; ``configuration``:
    the files the run read (its ``object``); ``code``: the Snakefile first, then the licence
    and citation files (code licence). Each file is described by :func:`describe`.
    """
    results, configuration, code = ({p: describe(p, results_dir) for p in files}
                                     for files in (results, configuration, code))
    crate = ROCrate()
    main, *others = code
    workflow = crate.add_workflow(main, main, main=True, lang="snakemake",
                                  lang_version=snakemake_version,
                                  properties={**file_properties(main, code[main], CODE_LICENCE),
                                              "conformsTo": {"@id": WORKFLOW_PROFILE}})
    for profile in crate.root_dataset.get("conformsTo", []):  # the library's Workflow RO-Crate
        crate.delete(profile)                                 # 1.1 claim: defined on 1.1 only
    crate.root_dataset.properties().pop("conformsTo", None)
    crate.add_jsonld({"@id": WORKFLOW_PROFILE, "@type": "CreativeWork",
                      "name": "Bioschemas ComputationalWorkflow profile 1.0"})
    for uri, name in SNAKEMAKE_PAGES.items():
        crate.add_jsonld({"@id": uri, "@type": "WebPage", "name": name})
    for uri, (name, text) in LICENCES.items():
        crate.add_jsonld({"@id": uri, "@type": "CreativeWork", "name": name,
                          "description": text})
    for path in others:
        crate.add_file(path, path, properties=file_properties(path, code[path], CODE_LICENCE))
    objects = [crate.add_file(p, p, properties=file_properties(p, text))
               for p, text in configuration.items()]
    outputs = [crate.add_file(p, p, properties=file_properties(p, text))
               for p, text in results.items()]
    run = crate.add_action(workflow, identifier="#run", object=objects, result=outputs,
                           properties={"name": f"Run of {title}"})
    crate.root_dataset.properties().update({
        "name": title, "description": description, "datePublished": date,
        "license": {"@id": DATA_LICENCE}, "mentions": {"@id": run.id}})
    return json.dumps(crate.metadata.generate(), indent=1, sort_keys=True) + "\n"
