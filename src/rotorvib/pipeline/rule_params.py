"""The parameters the workflow gives every script rule once all its rules are read: the code
fingerprint of the library code its script can run (:func:`add_code_fingerprints`), so that a
behaviour-changing edit of that code reruns exactly its jobs, and each input dataset's producer
with the hash of the configuration it must carry (:func:`add_input_checks`), checked on read."""

from __future__ import annotations

from functools import cache
from types import SimpleNamespace

from rotorvib.io.provenance import config_hash
from rotorvib.pipeline.fingerprint import code_fingerprint
from rotorvib.pipeline.job import INPUT_PRODUCERS_PARAM, job_config
from rotorvib.pipeline.snakemake_rules import add_params, producer, script_path, wildcards


def add_code_fingerprints(rules) -> None:
    """Give every script rule of ``rules`` a ``code`` parameter, the fingerprint of the library
    code its script can run (:func:`rotorvib.pipeline.fingerprint.code_fingerprint`). A module
    the script loads by name is its ``module`` parameter (a value, or a function of the
    wildcards)."""
    for each in rules:
        if (script := script_path(each)) is None:
            continue
        named = dict(each.params.items()).get("module")
        if callable(named):
            add_params(each, code=lambda wc, s=script, m=named: code_fingerprint(s, m(wc)))
        else:
            add_params(each, code=code_fingerprint(script, *([named] if named else [])))


def add_input_checks(rules) -> None:
    """Give every script rule of ``rules`` the parameter
    :data:`rotorvib.pipeline.job.INPUT_PRODUCERS_PARAM`: for each input dataset, the rule that
    makes it in this run and the SHA-256 of the configuration that rule records in it (its
    parameters for that file's wildcards, :func:`rotorvib.pipeline.job.job_config`). A dataset
    made by another rule or under another configuration (copied, restored, touched) stops
    the job that reads it."""

    @cache
    def producer_of(path: str) -> dict:
        maker = producer(rules, path)
        given = SimpleNamespace(**wildcards(maker, path))
        return {"rule": maker.name, "config_sha256": config_hash({
            name: value(given) if callable(value) else value
            for name, value in job_config(maker.params).items()})}

    def input_producers(wildcards, input) -> dict:
        return {path: producer_of(str(path)) for path in input if str(path).endswith(".nc")}

    for each in rules:
        if script_path(each) is not None:
            add_params(each, **{INPUT_PRODUCERS_PARAM: input_producers})
