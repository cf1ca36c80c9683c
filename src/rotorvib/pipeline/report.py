"""The words of the HTML report, written from the comparison table so that they cannot disagree
with ``results/comparison.md``.

Snakemake renders each caption and the landing page as reStructuredText through Jinja2. Figure
captions share one template (a rule's caption file cannot depend on its wildcards), which picks
the caption of ``snakemake.wildcards``; each table has its own caption file. A figure or table
is tied to the comparison rows whose ``item`` names it ("Fig 8", "Figs 8-10", "Table 2") and to
any further items its declaration lists ("Error study").
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

from rotorvib.comparison.table import margin_text
from rotorvib.comparison.verdicts import VERDICT_GROUPS, totals, verdict_definitions

# Verdicts that are findings: the paper and the reproduction disagree.
FINDINGS = ("MAJOR", "PAPER-INCONSISTENT", "UNEXPECTED", "NOT SUPPORTED")
# reST's inline markup characters, and the characters of Jinja's delimiters ({{ }}, {% %}, {# #}):
# Snakemake renders a caption and the landing page as a Jinja template before docutils reads
# it, so escaping each of them (reST shows ``\{`` as ``{``) leaves no two adjacent and no
# template tag, and a text cannot close a raw block.
_RST_SPECIAL = re.compile(r"([\\`*_|\[\]<>{}%#])")
# Control characters (other than whitespace, which is collapsed): shown as U+FFFD.
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
# URI schemes that run code where a browser follows them: docutils makes a link of a bare URI,
# so their colon is escaped (the text reads the same and links nowhere).
_SCRIPT_SCHEME = re.compile(r"(?i)\b(javascript|vbscript|data)(\s*):")
_ITEM = re.compile(r"^(Figs?|Tables?)\s+(\d+)(?:\s*[-–]\s*(\d+))?$")


def rst_text(text: str) -> str:
    """``text`` as literal reStructuredText inline content, inert when Snakemake renders it as
    a Jinja template: on one line (whitespace collapsed, so no text starts a directive such as
    ``.. include::``), markup and template characters escaped, control characters replaced."""
    one_line = " ".join(_CONTROL.sub("\ufffd", str(text)).split())
    return _SCRIPT_SCHEME.sub(r"\1\2\\:", _RST_SPECIAL.sub(r"\\\1", one_line))


def numbers_of_name(name: str) -> tuple[int, ...]:
    """The paper's figure or table numbers an output name stands for: ``fig4_5`` -> (4, 5),
    ``table2`` -> (2,), ``basin`` -> () (beyond the paper)."""
    match = re.fullmatch(r"(?:fig|table)(\d+(?:_\d+)*)", name)
    return tuple(int(n) for n in match.group(1).split("_")) if match else ()


def numbers_of_item(item: str) -> tuple[str, tuple[int, ...]]:
    """``"Figs 8-10"`` -> ("figure", (8, 9, 10)); an item naming no figure or table -> ("", ())."""
    match = _ITEM.match(item.strip())
    if not match:
        return "", ()
    first = int(match.group(2))
    last = int(match.group(3) or first)
    kind = {"fig": "figure", "table": "table"}[match.group(1).rstrip("s").lower()]
    return kind, tuple(range(first, last + 1))


def names_in(text: str) -> set[str]:
    """The output names of the figures and tables a text names: "Table 2's cases, as Figs
    8-10" -> {"table2", "fig8", "fig9", "fig10"}."""
    names = set()
    for match in re.finditer(r"\b(Figs?|Tables?)\s+(\d+)(?:\s*[-–]\s*(\d+))?", text):
        kind, numbers = numbers_of_item(match.group(0))
        names |= {f"{'fig' if kind == 'figure' else 'table'}{n}" for n in numbers}
    return names


def label(name: str, kind: str | None = None) -> str:
    """Reader's name of an output: ``fig4_5`` -> "Figs 4-5", ``table2`` -> "Table 2"; names
    beyond the paper keep their words ("error study"). ``kind`` ("figure" or "table") names
    the output's kind where its name does not."""
    numbers = numbers_of_name(name)
    kind = kind or ("table" if name.startswith("table") else "figure")
    word = {"figure": "Fig", "table": "Table"}[kind]
    if not numbers:
        return name.replace("_", " ")
    if len(numbers) == 1:
        return f"{word} {numbers[0]}"
    return f"{word}s {numbers[0]}-{numbers[-1]}"


# The report lists the results of a view sorted by their label as strings (JavaScript's
# localeCompare). A number below 10 is padded with a figure space (U+2007, the width of a
# digit), which collates before the digits: "Fig  2" < "Fig 10", and the numbers line up.
_PAD = "\u2007"
_WORDS = {"ga": "GA", "r": "R"}


def entry_label(name: str, kind: str, items: tuple[str, ...] = ()) -> str:
    """The label of an output in the report's lists, which sort by it: ``fig8`` -> "Fig  8",
    ``fig4_5`` -> "Fig  4-5" (padded, :data:`_PAD`); other outputs by their words, with the
    paper's section they belong to (``items``): ``ga_convergence``, ("GA", "Section 9") ->
    "GA convergence (section 9)", ``uncertainty_table2`` -> "Uncertainty Table 2"."""
    numbers = numbers_of_name(name)
    if numbers:
        word = {"figure": "Fig", "table": "Table"}[kind]
        return f"{word} {numbers[0]:{_PAD}>2}" + (f"\u2013{numbers[-1]}" if len(numbers) > 1 else "")
    words = [label(w) if numbers_of_name(w) else _WORDS.get(w.lower(), w)
             for w in name.split("_")]
    words[0] = words[0][0].upper() + words[0][1:]
    sections = [i[0].lower() + i[1:] for i in items if re.match(r"(Section|Abstract)\b", i)]
    return " ".join(words) + (f" ({', '.join(sections)})" if sections else "")


BEYOND = "Beyond the paper"


def in_order(names: list[str]) -> dict[str, str]:
    """Each name as the report's sidebar shows it, opening with its place ("1 Summary"; zeros
    before it where there are ten or more): the sidebar lists categories and subcategories
    sorted by name, and the story has an order."""
    width = len(str(len(names)))
    return {name: f"{place:0{width}d} {name}" for place, name in enumerate(names, start=1)}


def categories(papers) -> dict[str, str]:
    """The report's categories in the story's order: the summary, each paper (``papers``:
    their letters), the comparison; ``"Paper A"`` -> ``"2 Paper A"``."""
    return in_order(["Summary", *(f"Paper {p.upper()}" for p in sorted(papers)), "Comparison"])


#: A paper's subcategories in the story's order: its own figures and tables, then beyond it.
SUBCATEGORIES = in_order(["Figures", "Tables", BEYOND])


def subcategory(shows: str, kind: str) -> str:
    """The report subcategory of a paper's output: "1 Figures" or "2 Tables" for the paper's
    own items, "3 Beyond the paper" for those whose declaration says they go beyond it
    (:data:`SUBCATEGORIES`)."""
    name = BEYOND if shows.startswith(BEYOND) else {"figure": "Figures", "table": "Tables"}[kind]
    return SUBCATEGORIES[name]


def rows_for(table: list[dict], paper: str, name: str, kind: str = "figure",
             items: tuple[str, ...] = ()) -> list[dict]:
    """Comparison rows of ``paper`` whose item names output ``name`` or is one of ``items``."""
    numbers = set(numbers_of_name(name))

    def names_it(row):
        row_kind, row_numbers = numbers_of_item(row["item"])
        return row["item"] in items or (row_kind == kind and numbers & set(row_numbers))

    return [row for row in table if row["paper"].lower() == paper and names_it(row)]


def _number(value) -> str:
    return f"{float(value):.4g}"


def statement(row: dict, claim: str = "", lead: str = "") -> str:
    """One comparison row as a reST bullet: what the paper states (``claim``, else the
    quantity's name), what we find (a claim: its margin and the margin's uncertainty), the
    paper's own words where the row quotes them, the verdict and its explanation; ``lead``
    replaces the verdict and item at the start."""
    said = claim or row["quantity"]
    if row["paper_value"] not in ("", None):
        unit = f" {row['unit']}" if row["unit"] not in ("", "1", None) else ""
        found = f"paper {_number(row['paper_value'])}{unit}, reproduced " \
                f"{_number(row['reproduced'])}{unit}"
        if row["rel_error"] not in ("", None):
            found += f" ({100 * float(row['rel_error']):.1f} % off)"
        said = f"{said}: {found}"
    elif margin_text(row):
        said = f"{said}: margin {margin_text(row)}"
    lead = (f"**{rst_text(lead)}**" if lead
            else f"**{rst_text(row['verdict'])}** ({rst_text(row['item'])})")
    # a claim's explanation quotes each variant, "printed: ... | consistent: ..."
    explanation = f" {rst_text(row['explanation'].replace(' | ', '; '))}" if row["explanation"] else ""
    says = f" The paper: {rst_text(row['paper_says'])}." if row.get("paper_says") else ""
    return f"- {lead} {rst_text(said)}.{says}{explanation}"


def made_by_text(made: dict) -> str:
    """How an output was made, from the workflow's rules: ``{"rule", "script"}``, with a
    figure's ``"function"`` and ``"datasets"`` (dataset -> the rule that computed it)."""
    text = f"rule {made['rule']} ({made['script']}"
    text += f", {made['function']})" if "function" in made else ")"
    if made.get("datasets"):
        text += " from " + ", ".join(f"{d}.nc (rule {r})" for d, r in made["datasets"].items())
    return text + "."


def caption(title: str, shows: str, rows: list[dict] | None = None,
            claims: dict[tuple[str, str], str] | None = None, key: list[str] = (),
            parameters: str = "", made: dict | None = None) -> str:
    """A figure's or table's caption: its title, what it shows and what it draws beyond its
    legend's words (``key``, read off the figure: rotorvib.io.plotting.drawn_key), every
    comparison row that refers to it (``claims``: the paper's words for each quantity, from
    the paper-values file; ``rows=None`` for a caption without statements), the parameters it
    depends on and how it was made (``made``, :func:`made_by_text`)."""
    lines = [f"**{rst_text(title)}.** " + " ".join(rst_text(t) for t in (shows, *key)), ""]
    if rows:
        lines += ["What the paper states, against the reproduction:", ""]
        lines += [statement(row, (claims or {}).get((row["paper"], row["quantity"]), ""))
                  for row in rows]
    elif rows is not None:
        lines += ["The paper states no value or claim here: the output is shown for what it "
                  "adds to the reproduction."]
    if parameters:
        lines += ["", f"*Parameters.* {rst_text(parameters)}"]
    if made:
        lines += ["", f"*Made by* {rst_text(made_by_text(made))}"]
    return "\n".join(lines) + "\n"


def comparison_summary(table: list[dict]) -> str:
    """The verdict definitions and totals of the comparison table."""
    return f"{verdict_definitions()} Totals: {'; '.join(totals(table))}."


def check_counts(rows: list[dict]) -> str:
    """`` Checks: 28 PASS, 2 FAIL.`` for a table with a ``status`` column, else ``""``."""
    counts = Counter(row["status"] for row in rows if "status" in row)
    if not counts:
        return ""
    return " Checks: " + ", ".join(f"{n} {status}" for status, n in sorted(counts.items())) + "."


def verdict_counts(table: list[dict]) -> dict[str, Counter]:
    """Verdict counts per paper."""
    counts: dict[str, Counter] = {}
    for row in table:
        counts.setdefault(row["paper"], Counter())[row["verdict"]] += 1
    return counts


def _list_table(header: list[str], rows: list[list[str]]) -> list[str]:
    lines = [".. list-table::", "   :header-rows: 1", ""]
    for row in [header] + rows:
        lines.append("   * - " + row[0])
        lines += [f"     - {cell}" for cell in row[1:]]
    return lines + [""]


def totals_table(table: list[dict]) -> list[str]:
    """reST list-table of the verdict totals: one row per paper and a total."""
    counts = verdict_counts(table)
    papers = sorted(counts)
    everything = sum(counts.values(), Counter())
    verdicts = list(dict.fromkeys(v for _, group in VERDICT_GROUPS for v in group))
    rows = [[f"Paper {rst_text(p)}"] + [str(counts[p][v]) for v in verdicts] for p in papers]
    rows.append(["all"] + [str(everything[v]) for v in verdicts])
    return _list_table(["paper"] + [rst_text(v) for v in verdicts], rows)


def findings(table: list[dict], claims: dict[tuple[str, str], str]) -> list[str]:
    """The disagreements, one bullet per finding (rotorvib.comparison.table.with_findings: one cause,
    however many rows show it), naming the items and rows it covers and stating its largest
    miss (the first row where no number is printed) as in a caption, with the whole
    explanation (a clause cut short loses its numbers)."""
    groups: dict[str, list[dict]] = {}
    for row in table:
        if row["verdict"] in FINDINGS:
            groups.setdefault(row["finding"], []).append(row)
    lines = []
    for finding, rows in sorted(groups.items(), key=lambda group: group[1][0]["paper"]):
        items = ", ".join(dict.fromkeys(r["item"] for r in rows))
        count = f"{len(rows)} rows" if len(rows) > 1 else "1 row"
        worst = max(rows, key=lambda r: float(r["rel_error"] or -1))
        lines.append(statement(worst, claims.get((worst["paper"], worst["quantity"]), ""),
                               lead=f"Paper {rows[0]['paper']}, finding {finding}: {items} "
                                    f"({count}, {rows[0]['verdict']})"))
    return lines


TITLE = "rotorvib: three rotor-dynamics papers reproduced from first principles"


def paper_entries(papers: dict) -> dict[str, dict[str, str]]:
    """The papers of ``data/papers.yaml`` as the report links them: each key one capital letter
    (the report's category "2 Paper A" is a link target) and each entry a mapping of texts;
    ``ValueError`` naming the entry otherwise."""
    for letter, entry in papers.items():
        if not (isinstance(letter, str) and re.fullmatch("[A-Z]", letter)):
            raise ValueError(f"data/papers.yaml: paper {letter!r} is not one capital letter")
        if not (isinstance(entry, dict) and all(isinstance(v, str) for v in entry.values())):
            raise ValueError(f"data/papers.yaml: paper {letter}: every field must be a text")
    return papers


def _papers(papers: dict) -> str:
    """The count of ``papers`` in words: "three papers", "one paper"."""
    count = len(papers)
    word = {1: "one", 2: "two", 3: "three"}.get(count, str(count))
    return f"{word} paper{'s' if count != 1 else ''}"


def landing_page(table: list[dict], papers: dict[str, dict]) -> str:
    """The report's first page, short enough to read beside the rule graph: what was
    reproduced, the verdict totals in one line per group, and links to the summary (the
    verdict table, the findings, the discrepancy analysis) and to each paper
    (``papers``: letter -> {"title", ...})."""
    lines = [TITLE, "=" * len(TITLE), "",
             f"Every figure and table of {_papers(papers)} is regenerated from the equations "
             "with the "
             "parameters of ``config/config.yaml`` and set beside the paper's own numbers: "
             f"{len(table)} stated values and claims. Each figure's caption states the rows "
             "about it.", "",
             "**Verdict totals**", ""]
    lines += [f"- {rst_text(group)}" for group in totals(table)]
    named = categories(paper_entries(papers))
    lines += ["", f"`{named['Summary']}`_: the totals of each paper, the findings and the "
              f"discrepancy analysis. `{named['Comparison']}`_: every row.", ""]
    lines += [f"- `{named[f'Paper {letter}']}`_: {rst_text(paper['title'])}"
              for letter, paper in sorted(papers.items())]
    return "\n".join(lines) + "\n"


def summary_text(table: list[dict], claims: dict[tuple[str, str], str], papers: dict[str, dict],
                 discrepancy_totals: str) -> str:
    """The report's summary page (reStructuredText): the verdict definitions and totals of
    each paper, the discrepancy totals, the findings and the papers
    (``papers``: letter -> {"citation", "summary"})."""
    lines = ["Summary", "=======", "",
             f"{len(table)} values and claims of {_papers(papers)} compared with their "
             "reproduction.", "",
             "Verdict totals", "--------------", "", rst_text(verdict_definitions()), ""]
    lines += totals_table(table)
    lines += [f"Discrepancy analysis: {rst_text(discrepancy_totals)}.", "",
              "Findings", "--------", "",
              "Where the paper and the reproduction disagree (verdicts "
              + ", ".join(FINDINGS) + "), one entry per paper and item, stating its largest "
              "miss:", ""]
    lines += findings(table, claims) + ["", "Papers", "------", ""]
    lines += [f"- **Paper {letter}.** {rst_text(paper['citation'])} {rst_text(paper['summary'])}"
              for letter, paper in sorted(paper_entries(papers).items())]
    return "\n".join(lines) + "\n"


def write(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` (UTF-8), making its folder."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(text, encoding="utf-8")


def write_caption(path: str | Path, text: str) -> None:
    """Write a caption file: Snakemake renders captions as Jinja templates, so the text is one
    raw block, shown as written whatever braces it holds."""
    write(path, "{% raw %}" + text.rstrip() + "\n{% endraw %}\n")
