"""Torsional rotor with dynamic vibration absorbers: parameters, frequency and time responses, classical tuning."""
