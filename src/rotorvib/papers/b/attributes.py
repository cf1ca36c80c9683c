"""Paper B's reference and the global attributes of its datasets (importable without the
balancer's engine: the stability maps and boundaries need no more of paper B's setup)."""

REFERENCE = ("Paper B: The effect of damping ratio and balls mass on the stability of automatic "
             "ball balancer and determining their optimum values (M. Rezaee, R. Fathi, Modares "
             "Mechanical Engineering 14(3):110-118, 2014, Persian; data/papers.yaml)")


def dataset_attrs(title: str, summary: str, where: str) -> dict:
    """Global attributes of a paper B dataset; ``where`` names the figures/tables/equations."""
    return {"title": f"Paper B: {title}", "summary": summary,
            "references": f"{REFERENCE}; {where}"}
