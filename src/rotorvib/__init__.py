"""rotorvib: rotor-dynamics models, numerics and dataset I/O behind the reproduction pipeline."""

__version__ = "0.1.0"
