"""Tests of the host software (``host/``)."""
