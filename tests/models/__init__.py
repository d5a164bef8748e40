"""Tests of ``models/``: the tables and the golden models against facts that do not come from them."""
