"""Paper A: multiple scales and Lyapunov stability of the two-ball balancer (reconstructed model)."""
