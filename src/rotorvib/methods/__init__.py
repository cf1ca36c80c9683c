"""Numerical and symbolic methods: integration, multiple scales, genetic algorithm, symbolic equation checks."""
