"""The workflow reused as others would: as a Snakemake ``module`` of another workflow (through
``workflow/Snakefile``, the catalog's layout, and as ``snakedeploy`` deploys it), with the
caller's own ``config:`` (merged over the shipped defaults and checked as strictly) and results
folder, and run from another working directory (``--directory``). Every file the workflow
reads of its own (the schema, the papers' data, the Snakefile) is found beside its rules, not
in the caller's folder."""

import subprocess

import yaml

from workflow_runs import BIN, ROOT, copy_repository, environment

TARGET = "paper_c/datasets/ga.nc"


def _reduced(results: str) -> dict:
    """The reduced configuration's overrides, writing to ``results``."""
    overrides = yaml.safe_load((ROOT / "config/test/config.yaml").read_text())
    return {**overrides, "results": results}


def _consumer(tmp_path, module_config: dict):
    repo = copy_repository(tmp_path / "rotorvib")
    consumer = tmp_path / "analysis"
    consumer.mkdir()
    (consumer / "config.yaml").write_text(yaml.safe_dump({"rotorvib": module_config}))
    (consumer / "Snakefile").write_text(
        'configfile: "config.yaml"\n\n\n'
        "module rotorvib:\n"
        f'    snakefile: "{repo / "workflow/Snakefile"}"\n'
        '    config: config["rotorvib"]\n\n\n'
        "use rule * from rotorvib as rotorvib_*\n")
    return repo, consumer


def _snakemake(cwd, *args, check=True):
    run = subprocess.run([str(BIN / "snakemake"), *args], cwd=cwd, capture_output=True,
                         text=True, env=environment(cwd), timeout=600)
    if check:
        assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return run


def test_a_module_with_its_own_config_writes_where_the_caller_says(tmp_path):
    repo, consumer = _consumer(tmp_path, _reduced("out/rv"))
    dry = _snakemake(consumer, "-n", "-j1")
    assert "rotorvib_c_ga" in dry.stdout and "out/rv/paper_c/figures/fig5.png" in dry.stdout
    _snakemake(consumer, "-j1", f"out/rv/{TARGET}")
    made = consumer / "out/rv" / TARGET
    assert made.is_file() and not (consumer / "results").exists()
    assert not (repo / "results").exists()


def test_a_module_config_gets_the_same_checks(tmp_path):
    _, consumer = _consumer(tmp_path, {"results": "out/rv", "paper_c": {"rotor": {"M": -5.0}}})
    run = _snakemake(consumer, "-n", check=False)
    assert run.returncode != 0
    assert "config key 'paper_c.rotor.M': -5.0 is not allowed" in run.stdout + run.stderr
    assert "Job " not in run.stdout


def test_a_run_from_another_directory_finds_its_own_files(tmp_path):
    repo = copy_repository(tmp_path / "rotorvib")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "reduced.yaml").write_text(yaml.safe_dump(_reduced("results")))
    args = ["--directory", str(elsewhere), "--configfile", str(repo / "config/config.yaml"),
            str(elsewhere / "reduced.yaml")]
    _snakemake(repo, "-j1", f"results/{TARGET}", *args)
    assert (elsewhere / "results" / TARGET).is_file() and not (repo / "results").exists()


def test_snakedeploys_layout_runs_the_workflow_as_a_module(tmp_path):
    """What a user of the workflow catalog does: ``snakedeploy deploy-workflow`` writes a
    workflow of their own (its Snakefile naming ``workflow/Snakefile`` as a module, with their
    copy of ``config/``); Snakemake, reading that copy with its own YAML loader, plans every job
    of the paper configuration into their folder. For a local repository snakedeploy writes the
    module's path relative to the new workflow; it is made the repository's, as ``github(...)``
    would fetch it."""
    repo = copy_repository(tmp_path / "rotorvib")
    # what a deployment fetches: the repository's last commit (snakedeploy copies a local
    # repository's whole folder, environments and results included, so it is given a clone)
    published = tmp_path / "published"
    subprocess.run(["git", "clone", "--quiet", "--depth", "1", ROOT.as_uri(), str(published)],
                   check=True, timeout=300)
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=published, capture_output=True,
                            text=True, check=True).stdout.strip()
    deployed = tmp_path / "analysis"
    run = subprocess.run([str(BIN / "snakedeploy"), "deploy-workflow", str(published),
                          str(deployed), "--commit", commit, "--name", "rotorvib"],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    snakefile = deployed / "workflow/Snakefile"
    text = snakefile.read_text()
    assert 'snakefile: \n        "workflow/Snakefile"' in text and "use rule * from rotorvib" in text
    snakefile.write_text(text.replace('"workflow/Snakefile"', f'"{repo / "workflow/Snakefile"}"'))
    (deployed / "config/config.yaml").write_text((repo / "config/config.yaml").read_text())
    plan = _snakemake(deployed, "--summary", "all")   # every output, its rule and status
    assert "results/paper_c/figures/fig5.png\t" in plan.stdout and "\tc_ga\t" in plan.stdout
    assert not (repo / "results").exists()
