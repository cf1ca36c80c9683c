"""Automatic ball balancer (papers A and B): one engine for both reproductions."""
