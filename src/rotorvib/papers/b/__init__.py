"""Paper B: damping ratio and ball mass of a two-ball balancer with a run-up."""
