"""The formal proofs (``formal/``) in the test suite."""
