"""RO-Crate validation with the real validator (rocrate-validator), offline.

The validator fetches the crate's JSON-LD context from w3id.org, which neither this machine
nor CI can reach. It also runs offline from its HTTP cache, so the cache is first given the
RO-Crate 1.3 context from the copy the ``rocrate`` library ships; every check then runs as
published (availability checks of web entities, such as licence URLs, are skipped).

The profile's SPARQL-based constraints are evaluated by pyshacl once per focus node, each time
through ``Graph.query`` with the query's text, which rdflib parses anew at every call: about 840
parses of 39 texts for the crate of a reduced run, two thirds of the validator's time. While the
validator runs, each text is parsed once and evaluated prepared (:func:`each_query_parsed_once`).
"""

import io
from contextlib import contextmanager
from importlib.resources import files
from pathlib import Path

from rdflib.plugins.sparql.processor import SPARQLProcessor, prepareQuery
from requests.adapters import HTTPAdapter
from requests_cache import CachedSession
from rocrate_validator import services
from rocrate_validator.models import Severity, ValidationSettings
from urllib3 import HTTPResponse

CONTEXT = "https://w3id.org/ro/crate/1.3/context"


class _ShippedContext(HTTPAdapter):
    """Answers every request with the rocrate library's copy of the RO-Crate 1.3 context."""

    def send(self, request, **kwargs):
        data = files("rocrate").joinpath("data/ro-crate.jsonld").read_bytes()
        raw = HTTPResponse(body=io.BytesIO(data), status=200, preload_content=False,
                           headers={"Content-Type": "application/ld+json"},
                           request_url=request.url)
        return self.build_response(request, raw)


@contextmanager
def each_query_parsed_once():
    """rdflib's SPARQL processor, for the duration, prepares each query text once
    (``prepareQuery``: parsed and translated to its algebra, rdflib's way to evaluate one query
    under many initial bindings) and evaluates the prepared query at every later call with the
    same text, namespaces and base. Yields the prepared queries by key."""
    evaluate = SPARQLProcessor.query
    prepared = {}

    def query(self, query, initBindings=None, initNs=None, base=None, DEBUG=False):
        if isinstance(query, str):
            key = (query, base, tuple(sorted((initNs or {}).items())))
            if key not in prepared:
                prepared[key] = prepareQuery(query, initNs, base)
            query = prepared[key]
        return evaluate(self, query, initBindings, initNs, base, DEBUG)

    SPARQLProcessor.query = query
    try:
        yield prepared
    finally:
        SPARQLProcessor.query = evaluate


def validate_crate(crate: Path, cache: Path, severity: str = "RECOMMENDED") -> list[tuple]:
    """Issues ``(severity, message, entity)`` of the crate in directory ``crate`` against the
    RO-Crate 1.3 profile, at ``severity`` and above; ``cache`` is a scratch path."""
    session = CachedSession(cache_name=str(cache), backend="sqlite", expire_after=-1,
                            allowable_methods=("GET",), allowable_codes=(200,))
    session.mount(CONTEXT, _ShippedContext())
    for accept in ("application/ld+json, application/json", "application/ld+json"):
        session.get(CONTEXT, headers={"Accept": accept}).raise_for_status()
    session.close()
    settings = ValidationSettings(rocrate_uri=str(crate), profile_identifier="ro-crate-1.3",
                                  cache_path=str(cache), offline=True,
                                  requirement_severity=Severity[severity],
                                  skip_availability_check=True)
    with each_query_parsed_once():
        result = services.validate(settings)
    return [(issue.severity.name, issue.message, issue.violatingEntity)
            for issue in result.get_issues()]
