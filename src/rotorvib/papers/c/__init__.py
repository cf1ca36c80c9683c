"""Paper C: dual torsional dynamic vibration absorber."""
