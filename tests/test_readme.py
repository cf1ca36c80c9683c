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
