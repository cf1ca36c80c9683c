"""Every number of the reduced configuration moved, one at a time, to the values of the fuzzer
(tests/schema_fuzz.py: the schema's bounds, just inside an open bound, zero, a sign change,
three orders of magnitude), and its shape changed (texts, other kinds, containers, keys
removed, renamed or added): the checks run before any job either accept the configuration or
refuse it with messages that each name a config key, and never crash."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import schema_fuzz

BASE = schema_fuzz.reduced_config()
MUTATIONS = schema_fuzz.mutations(BASE)


def test_the_fuzzer_moves_every_number_of_the_configuration():
    paths = {path for path, _ in MUTATIONS}
    assert paths == set(schema_fuzz.numbers(BASE)) and len(paths) > 250
    # an open bound is approached from inside: the next float above paper_b.machine.M's 0
    assert 5e-324 in {v for p, v in MUTATIONS if p == ("paper_b", "machine", "M")}


def test_every_mutation_is_accepted_or_refused_naming_its_keys():
    verdicts = [schema_fuzz.verdict(schema_fuzz.mutate(BASE, path, value))
                for path, value in MUTATIONS]
    refused = [v for v in verdicts if v is not None]
    unnamed = [line for message in refused for line in message.splitlines()[1:]
               if not line.strip().startswith("config key '")]
    assert unnamed == []
    # both outcomes occur, and the checks beyond the schema refuse some: the existence bound
    # (34), a GA-law study with nothing to fit, a boundary plane that cannot start, subnormals
    assert 0.3 < len(refused) / len(verdicts) < 0.7
    for words in ("existence bound", "three bins", "must contain the base value",
                  "subnormal"):
        assert any(words in message for message in refused), words


@pytest.mark.parametrize("sample_dt", [5e-324, 1e-300])
def test_a_vanishing_sample_step_is_refused_not_a_crash(sample_dt):
    """Found by the fuzzer: the sample count of a subnormal step overflowed an integer."""
    mutated = schema_fuzz.mutate(BASE, ("paper_b", "balance", "sample_dt"), sample_dt)
    assert "'paper_b.balance.sample_dt'" in schema_fuzz.verdict(mutated)


STRUCTURE = schema_fuzz.structure_mutations(BASE)


def _refusal_names_its_keys(message: str | None) -> bool:
    return message is None or all(line.strip().startswith("config key '")
                                  for line in message.splitlines()[1:])


@settings(max_examples=400, deadline=None, derandomize=True)
@given(st.sampled_from(STRUCTURE))
def test_every_change_of_shape_is_accepted_or_refused_naming_its_keys(mutation):
    message = schema_fuzz.verdict(schema_fuzz.apply(BASE, *mutation))
    assert _refusal_names_its_keys(message), (mutation, message)


@pytest.mark.parametrize("kind", ["remove", "rename", "add"])
def test_every_key_change_of_paper_b_machine_is_refused(kind):
    """Each key of a section the schema closes: removed, renamed or added, it is refused."""
    for mutation in STRUCTURE:
        if mutation[0] == kind and mutation[1][:2] == ("paper_b", "machine"):
            message = schema_fuzz.verdict(schema_fuzz.apply(BASE, *mutation))
            assert message and "'paper_b.machine" in message, mutation
