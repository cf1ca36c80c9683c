"""Jeffcott rotor with an n-ball automatic balancer: compiled engine, parameters, simulation API, stability of the balanced state, series expansion."""
