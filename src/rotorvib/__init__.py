"""rotorvib: rotor-dynamics models, numerics and dataset I/O behind the reproduction pipeline.

The packages, in the order of the layers: ``models``, ``methods``, ``papers`` (with the
contract each paper keeps), ``comparison``, ``io`` and ``pipeline``. One module stands beside
them, :mod:`rotorvib.checks`: the argument checks every layer's public entry points share
(``models``, ``methods``, ``io``, ``papers`` and ``pipeline`` all import it, and it imports
none of them), so it belongs to no one package."""

__version__ = "0.1.0"
