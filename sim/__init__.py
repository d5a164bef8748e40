"""Golden models, behavioural bus models and test benches (never imported by rtl/)."""
