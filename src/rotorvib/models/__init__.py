"""Physical models: the ball balancer and the torsional vibration absorber (no paper lives here)."""
