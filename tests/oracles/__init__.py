"""Independent oracles used only by the tests."""
